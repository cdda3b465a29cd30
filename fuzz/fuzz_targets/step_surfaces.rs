//! Any bytes as a STEP file, for its surfaces (`knotshape_fuzzing::files::check_step_surfaces`):
//! a list or an error, never a panic, and the surfaces read write and read back unchanged.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|input: &[u8]| {
    if let Err(finding) = knotshape_fuzzing::files::check_step_surfaces(input) {
        panic!("{finding}");
    }
});

//! Any bytes as a DXF file (`knotshape_fuzzing::files`): a curve list or an error, never a
//! panic, and the curves read write and read back unchanged.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|input: &[u8]| {
    if let Err(finding) = knotshape_fuzzing::files::check_dxf(input) {
        panic!("{finding}");
    }
});

//! Random valid curves drawn from the bytes (`arbitrary`) through evaluation, closest point,
//! insertion, Bézier pieces, tessellation and, for cubics, solve (both methods, `nearest`) and
//! regions, each answer checked (`knotshape_fuzzing::structured`).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|input: &[u8]| {
    if let Err(finding) = knotshape_fuzzing::structured::check(input) {
        panic!("{finding}");
    }
});

//! Raw bytes as the body of every POST endpoint, through the real router in-process
//! (`knotshape_fuzzing`): no server error, every client error a problem document that says
//! why. The first byte picks the endpoint.
#![no_main]

use std::sync::OnceLock;

use knotshape_fuzzing::Target;
use libfuzzer_sys::fuzz_target;
use tokio::runtime::Runtime;

fn runtime_and_target() -> &'static (Runtime, Target) {
    static SHARED: OnceLock<(Runtime, Target)> = OnceLock::new();
    SHARED.get_or_init(|| {
        let runtime = tokio::runtime::Builder::new_current_thread()
            .enable_all()
            .build()
            .expect("a runtime");
        (runtime, Target::new())
    })
}

fuzz_target!(|input: &[u8]| {
    let (runtime, target) = runtime_and_target();
    if let Err(finding) = runtime.block_on(target.check(input)) {
        panic!("{finding}");
    }
});

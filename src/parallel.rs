//! Whether the geometry core may spread one request's independent pieces — a knot family's
//! pairs and triples, the certified deviations of many solutions — over rayon's thread pool.
//!
//! On by default: an edit on an otherwise idle machine then uses every core (the worked
//! quintic's full knots solve takes about half the time on two cores). Off, each request is
//! solved on its own thread only, as it was before: right where the cores are busy with
//! something else — a browser on the same two-core machine drawing the editor's frames
//! (docs/performance.md, "The knot method on every degree") — or with many requests at once.
//! The answer is the same either way (the pieces are put back in order and share the
//! request's budgets without depending on it).
//!
//! The setting is process-wide: the service applies its `--solve-threads` once at start.

use std::sync::atomic::{AtomicBool, Ordering};

/// Set when the core must stay on the calling thread.
static SEQUENTIAL: AtomicBool = AtomicBool::new(false);

/// Applies a `--solve-threads` value: `0` leaves rayon's pool as it is (every core unless
/// `RAYON_NUM_THREADS` says otherwise), `1` keeps each request on its own thread, `n ≥ 2`
/// sizes the pool to `n` threads when it is not built yet (it is built once per process).
pub fn set_solve_threads(threads: usize) {
    SEQUENTIAL.store(threads == 1, Ordering::Relaxed);
    if threads >= 2 {
        // Only the first build of the global pool takes effect; a later one is refused and
        // the pool keeps its size, which is all a second server in one process can expect.
        let _ = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build_global();
    }
}

/// Whether the core may use the pool.
pub fn allowed() -> bool {
    !SEQUENTIAL.load(Ordering::Relaxed)
}

//! Driver for `benches/instructions.sh`: sends `COUNT` requests of one kind (`healthz` or
//! `solve`, the load test's body) through the real router, in-process, one after the other.
//! Run under callgrind it gives instructions per request, a measure that, unlike time, does
//! not change with the machine's load.
//!
//! Usage: `request_cost healthz|solve COUNT`.

#[path = "support/requests.rs"]
mod requests;
use requests::{Bench, Kind};

fn main() {
    let mut args = std::env::args().skip(1);
    let kind = match args.next().as_deref() {
        Some("healthz") => Kind::Healthz,
        Some("solve") => Kind::Solve,
        _ => {
            eprintln!("usage: request_cost healthz|solve COUNT");
            std::process::exit(2);
        }
    };
    let Some(count) = args.next().map_or(Some(1000), |n| n.parse::<usize>().ok()) else {
        eprintln!("request_cost: COUNT must be a whole number");
        std::process::exit(2);
    };
    let bench = Bench::new();
    for _ in 0..count {
        bench.send(kind);
    }
}

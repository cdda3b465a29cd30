//! Criterion benchmark of whole requests through the real router, in-process (no sockets):
//! `GET /healthz` against `POST /v1/shape/solve` with the load test's body. Their ratio is the
//! service's own share of the load test's solve/healthz ratio (the kernel's TCP work is not in
//! it).

use criterion::{Criterion, criterion_group, criterion_main};

#[path = "support/requests.rs"]
mod requests;
use requests::{Bench, Kind};

fn bench_requests(c: &mut Criterion) {
    let bench = Bench::new();
    let mut group = c.benchmark_group("request");
    group.bench_function("healthz", |b| b.iter(|| bench.send(Kind::Healthz)));
    group.bench_function("solve", |b| b.iter(|| bench.send(Kind::Solve)));
    group.finish();
}

criterion_group!(benches, bench_requests);
criterion_main!(benches);

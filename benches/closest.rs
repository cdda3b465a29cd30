//! Closest point per query (`ClosestPointSearch`): 2,000 random queries on a 2D cubic with 60
//! control points (the size of docs/performance.md's comparison), and how the cost grows from
//! 10 to 10,000 control points. Before timing, every answer on the 60-pole curve is checked
//! against brute force (200,001 samples plus golden-section refinement), and the number of
//! answers worse than brute force is printed: it must be 0. Then the 60-pole curve, the same
//! curve refined to 10,000 control points and a random 10,000-pole curve are timed in
//! interleaved rounds of the same run and the ratios are printed.
#![allow(clippy::unwrap_used)]

use std::hint::black_box;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use knotshape::spline::{ClosestPointSearch, Curve, CurveLimits, Point};

/// Queries per timed iteration.
const QUERIES: usize = 2_000;
/// Seed of the curves and queries.
const SEED: u64 = 0x5EED_0FC0_FFEE;

/// SplitMix64: a tiny, well-known seeded generator.
struct SplitMix64(u64);

impl SplitMix64 {
    fn next_f64(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A clamped 2D cubic on `[0, 1]` with `count` control points random in `[-10, 10]²` and
/// sorted random interior knots.
fn curve(count: usize, rng: &mut SplitMix64) -> Curve {
    let points: Vec<Vec<f64>> = (0..count)
        .map(|_| vec![20.0 * rng.next_f64() - 10.0, 20.0 * rng.next_f64() - 10.0])
        .collect();
    let mut interior: Vec<f64> = (0..count - 4).map(|_| rng.next_f64()).collect();
    interior.sort_by(f64::total_cmp);
    let mut knots = vec![0.0; 4];
    knots.extend(interior);
    knots.extend([1.0; 4]);
    Curve::new(3, &points, &knots, None, &CurveLimits::default()).unwrap()
}

/// Query points uniform in `[-12, 12]²`.
fn queries(rng: &mut SplitMix64) -> Vec<Point> {
    (0..QUERIES)
        .map(|_| {
            [
                24.0 * rng.next_f64() - 12.0,
                24.0 * rng.next_f64() - 12.0,
                0.0,
            ]
        })
        .collect()
}

/// The least distance by dense sampling and golden-section refinement of the best samples.
fn brute_force(curve: &Curve, q: Point) -> f64 {
    const SAMPLES: usize = 200_000;
    let gap = |u: f64| {
        let p = curve.point(u.clamp(0.0, 1.0)).unwrap();
        ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)).sqrt()
    };
    let values: Vec<f64> = (0..=SAMPLES)
        .map(|i| gap(i as f64 / SAMPLES as f64))
        .collect();
    let mut best = values.iter().copied().fold(f64::INFINITY, f64::min);
    for i in 1..SAMPLES {
        if values[i] <= values[i - 1] && values[i] <= values[i + 1] && values[i] < best + 1e-3 {
            let (mut a, mut b) = (
                (i - 1) as f64 / SAMPLES as f64,
                (i + 1) as f64 / SAMPLES as f64,
            );
            for _ in 0..60 {
                let x = b - 0.618_033_988_749_895 * (b - a);
                let y = a + 0.618_033_988_749_895 * (b - a);
                if gap(x) < gap(y) { b = y } else { a = x }
            }
            best = best.min(gap(0.5 * (a + b)));
        }
    }
    best
}

fn bench_closest(c: &mut Criterion) {
    let mut rng = SplitMix64(SEED);
    let sixty = curve(60, &mut rng);
    let points = queries(&mut rng);
    let search = ClosestPointSearch::new(&sixty, None).unwrap();
    // `KNOTSHAPE_CLOSEST_ONLY=<poles>`: answer the queries once on a curve with that many
    // control points and stop, for an instruction count (`valgrind --tool=callgrind`), which
    // the machine's load does not disturb.
    if let Some(poles) = std::env::var("KNOTSHAPE_CLOSEST_ONLY")
        .ok()
        .and_then(|v| v.parse::<usize>().ok())
    {
        let scaled = if poles == 60 {
            sixty.clone()
        } else {
            curve(poles, &mut rng)
        };
        let search = ClosestPointSearch::new(&scaled, None).unwrap();
        let total: f64 = points.iter().map(|&q| search.closest(q).distance).sum();
        eprintln!("{poles} poles: sum of distances {total}");
        std::process::exit(0);
    }
    let wrong = points
        .iter()
        .filter(|&&q| search.closest(q).distance > brute_force(&sixty, q) + 1e-9)
        .count();
    eprintln!("closest point, 60 poles: {wrong} of {QUERIES} answers worse than brute force");
    assert_eq!(wrong, 0);

    // Growth with the size, in one run: the best of interleaved rounds of the 2,000 queries on
    // the 60-pole curve, on the same curve with knots inserted up to 10,000 control points
    // (the same shape in 9,997 pieces: a large curve as CAD files hold them), and on a random
    // 10,000-pole curve (a scribble 167 times as long in the same square: the curve near a
    // query, which any exact search must look at, grows with it). The refined curve's answers
    // must be the 60-pole curve's.
    let inserted: Vec<f64> = (1..=10_000 - 60).map(|i| i as f64 / 9_941.0).collect();
    let refined = sixty.insert_knots(&inserted, usize::MAX).unwrap();
    assert_eq!(refined.control_points().len(), 10_000);
    let refined_search = ClosestPointSearch::new(&refined, None).unwrap();
    let differing = points
        .iter()
        .filter(|&&q| {
            let (a, b) = (search.closest(q), refined_search.closest(q));
            (a.distance - b.distance).abs() > 1e-12 * (1.0 + a.distance)
        })
        .count();
    eprintln!(
        "closest point, 60 poles refined to 10,000: {differing} of {QUERIES} distances differ"
    );
    assert_eq!(differing, 0);
    let scribble = curve(10_000, &mut rng);
    let scribble_search = ClosestPointSearch::new(&scribble, None).unwrap();
    let mut best = [f64::INFINITY; 3];
    for _ in 0..15 {
        for (slot, search) in best
            .iter_mut()
            .zip([&search, &refined_search, &scribble_search])
        {
            let start = std::time::Instant::now();
            for &q in &points {
                black_box(search.closest(black_box(q)));
            }
            *slot = slot.min(start.elapsed().as_secs_f64());
        }
    }
    let per_query = |seconds: f64| seconds / QUERIES as f64 * 1e6;
    eprintln!(
        "closest point per query, best of 15 interleaved rounds: 60 poles {:.2} µs; refined to 10,000 poles {:.2} µs ({:.2} times); random 10,000 poles {:.2} µs ({:.1} times)",
        per_query(best[0]),
        per_query(best[1]),
        best[1] / best[0],
        per_query(best[2]),
        best[2] / best[0],
    );

    let mut group = c.benchmark_group("closest_point");
    group.measurement_time(Duration::from_secs(4));
    group.throughput(Throughput::Elements(QUERIES as u64));
    group.bench_function("query_60_poles", |b| {
        b.iter(|| {
            for &q in &points {
                black_box(search.closest(black_box(q)));
            }
        })
    });
    group.bench_function("pieces_60_poles", |b| {
        b.iter(|| ClosestPointSearch::new(black_box(&sixty), None).unwrap())
    });
    group.bench_function("query_60_poles_refined_to_10000", |b| {
        b.iter(|| {
            for &q in &points {
                black_box(refined_search.closest(black_box(q)));
            }
        })
    });
    for count in [10, 100, 1_000, 10_000] {
        let scaled = curve(count, &mut rng);
        let search = ClosestPointSearch::new(&scaled, None).unwrap();
        group.bench_with_input(BenchmarkId::new("query_by_poles", count), &count, |b, _| {
            b.iter(|| {
                for &q in &points {
                    black_box(search.closest(black_box(q)));
                }
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench_closest);
criterion_main!(benches);

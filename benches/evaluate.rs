//! Batch evaluation throughput: 1,000,000 uniformly spaced points of a 2D B-spline with 60
//! control points and seeded random interior knots (`BatchEvaluator`, Bézier form), for a cubic
//! and for degree 9.
//!
//! Each curve is also written as JSON (to `$KNOTSHAPE_BENCH_CURVE_DIR/evaluate_curve_<name>.json`,
//! default directory `$CARGO_TARGET_TMPDIR`) with a few reference points, so that
//! `benches/scipy_compare.py` times SciPy on the very same curve and checks it.
#![allow(clippy::unwrap_used)]

use std::hint::black_box;
use std::path::PathBuf;
use std::time::Duration;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use knotshape::spline::{BatchEvaluator, Curve, CurveLimits};

/// Points evaluated per iteration.
const POINTS: usize = 1_000_000;
/// The benchmark curves: a name (of the criterion group `evaluate_1M_<name>` and of the JSON
/// file) and the degree.
const CURVES: [(&str, usize); 2] = [("cubic_2d", 3), ("degree9_2d", 9)];
/// Number of control points of each benchmark curve.
const CONTROL_POINTS: usize = 60;
/// Seed of the curve's control points and interior knots.
const SEED: u64 = 0x5EED_0FC0_FFEE;
/// Uniform points written to the JSON for the SciPy side to check against.
const CHECK_POINTS: usize = 101;

/// SplitMix64: a tiny, well-known seeded generator (no extra dependency).
struct SplitMix64(u64);

impl SplitMix64 {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `[0, 1)`.
    fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A benchmark curve of degree `degree`: clamped knots on `[0, 1]` with sorted random interior
/// knots, control points random in `[-10, 10]²`.
fn bench_curve(degree: usize) -> (Vec<Vec<f64>>, Vec<f64>) {
    let mut rng = SplitMix64(SEED);
    let points: Vec<Vec<f64>> = (0..CONTROL_POINTS)
        .map(|_| vec![20.0 * rng.next_f64() - 10.0, 20.0 * rng.next_f64() - 10.0])
        .collect();
    let mut interior: Vec<f64> = (0..CONTROL_POINTS - degree - 1)
        .map(|_| rng.next_f64())
        .collect();
    interior.sort_by(f64::total_cmp);
    let mut knots = vec![0.0; degree + 1];
    knots.extend(interior);
    knots.extend(std::iter::repeat_n(1.0, degree + 1));
    (points, knots)
}

/// Writes the curve and [`CHECK_POINTS`] uniform points as JSON for the SciPy comparison.
fn write_curve_json(name: &str, curve: &Curve, points: &[Vec<f64>], knots: &[f64]) {
    let directory = std::env::var_os("KNOTSHAPE_BENCH_CURVE_DIR")
        .map_or_else(|| PathBuf::from(env!("CARGO_TARGET_TMPDIR")), PathBuf::from);
    let path = directory.join(format!("evaluate_curve_{name}.json"));
    let mut check = vec![[0.0; 3]; CHECK_POINTS];
    BatchEvaluator::new(curve).uniform_points_into(&mut check);
    let json = serde_json::json!({
        "degree": curve.degree(),
        "control_points": points,
        "knots": knots,
        "points_evaluated": POINTS,
        "check_parameters": curve.uniform_parameters(CHECK_POINTS).collect::<Vec<f64>>(),
        "check_points": check.iter().map(|p| [p[0], p[1]]).collect::<Vec<_>>(),
    });
    std::fs::write(&path, serde_json::to_string_pretty(&json).unwrap()).unwrap();
    eprintln!("benchmark curve written to {}", path.display());
}

fn evaluate(c: &mut Criterion) {
    for (name, degree) in CURVES {
        let (points, knots) = bench_curve(degree);
        let curve = Curve::new(degree, &points, &knots, None, &CurveLimits::default()).unwrap();
        write_curve_json(name, &curve, &points, &knots);
        let batch = BatchEvaluator::new(&curve);
        let parameters: Vec<f64> = curve.uniform_parameters(POINTS).collect();
        let mut out = vec![[0.0; 3]; POINTS];

        let mut group = c.benchmark_group(format!("evaluate_1M_{name}"));
        group.throughput(Throughput::Elements(POINTS as u64));
        group.bench_function("uniform_points_into", |b| {
            b.iter(|| batch.uniform_points_into(black_box(&mut out)));
        });
        group.bench_function("points_into", |b| {
            b.iter(|| {
                batch
                    .points_into(black_box(&parameters), black_box(&mut out))
                    .unwrap()
            });
        });
        group.finish();
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .sample_size(30)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(4));
    targets = evaluate
}
criterion_main!(benches);

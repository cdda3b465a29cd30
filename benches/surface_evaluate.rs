//! Surface evaluation per point: `Surface::point` and `Surface::partials` (order 1) at 100,000
//! seeded random parameter pairs of three surfaces: a bicubic and a biquintic with 20 × 20
//! random poles and random interior knots, and a rational biquadratic (10 × 10, weights in
//! [0.5, 2]).
//!
//! Each surface and its parameters are also written as JSON (to
//! `$KNOTSHAPE_BENCH_CURVE_DIR/surface_<name>.json`, default directory `$CARGO_TARGET_TMPDIR`)
//! with the first points and partials, so that `benches/ndbspline_compare.py` times SciPy's
//! `NdBSpline` on the very same surfaces and parameters and checks its values
//! (`bash benches/surface_compare.sh` runs both).
#![allow(clippy::unwrap_used)]

use std::hint::black_box;
use std::path::PathBuf;
use std::time::Duration;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use knotshape::spline::KnotForm;
use knotshape::surface::{Surface, SurfaceLimits};

/// Parameter pairs per iteration.
const PAIRS: usize = 100_000;
/// Pairs whose values are written for SciPy to check.
const CHECK_PAIRS: usize = 200;
/// The benchmark surfaces: name, degrees, poles per direction, rational.
const SURFACES: [(&str, usize, usize, bool); 3] = [
    ("bicubic", 3, 20, false),
    ("biquintic", 5, 20, false),
    ("rational_biquadratic", 2, 10, true),
];
/// Seed of the surfaces and the parameters.
const SEED: u64 = 0x5EED_5A2F_ACE5;

/// SplitMix64: a tiny seeded generator (no extra dependency).
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
    fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Clamped knots on `[0, 1]` for `count` poles of degree `p`, sorted random interior knots.
fn knots(rng: &mut SplitMix64, p: usize, count: usize) -> Vec<f64> {
    let mut interior: Vec<f64> = (0..count - p - 1).map(|_| rng.unit()).collect();
    interior.sort_by(f64::total_cmp);
    let mut knots = vec![0.0; p + 1];
    knots.extend(interior);
    knots.extend(std::iter::repeat_n(1.0, p + 1));
    knots
}

/// One benchmark surface's data: poles `[i][j]`, weights, knots.
struct Data {
    degree: usize,
    poles: Vec<Vec<[f64; 3]>>,
    weights: Option<Vec<Vec<f64>>>,
    knots_u: Vec<f64>,
    knots_v: Vec<f64>,
}

fn data(degree: usize, count: usize, rational: bool, rng: &mut SplitMix64) -> Data {
    let poles = (0..count)
        .map(|i| {
            (0..count)
                .map(|j| [i as f64, j as f64, 4.0 * rng.unit() - 2.0])
                .collect()
        })
        .collect();
    let weights = rational.then(|| {
        (0..count)
            .map(|_| (0..count).map(|_| 0.5 + 1.5 * rng.unit()).collect())
            .collect()
    });
    Data {
        degree,
        poles,
        weights,
        knots_u: knots(rng, degree, count),
        knots_v: knots(rng, degree, count),
    }
}

/// Writes the surface, the parameters and the first values as JSON for the SciPy side.
fn write_json(name: &str, data: &Data, surface: &Surface, pairs: &[[f64; 2]]) {
    let directory = std::env::var_os("KNOTSHAPE_BENCH_CURVE_DIR")
        .map_or_else(|| PathBuf::from(env!("CARGO_TARGET_TMPDIR")), PathBuf::from);
    let path = directory.join(format!("surface_{name}.json"));
    let check: Vec<_> = pairs[..CHECK_PAIRS]
        .iter()
        .map(|&[u, v]| {
            let partials = surface.partials(u, v, 1);
            [partials.point(), partials.du(), partials.dv()]
        })
        .collect();
    let json = serde_json::json!({
        "degree": data.degree,
        "poles": data.poles,
        "weights": data.weights,
        "knots_u": data.knots_u,
        "knots_v": data.knots_v,
        "pairs": pairs,
        "check": check,
    });
    std::fs::write(&path, serde_json::to_string(&json).unwrap()).unwrap();
    eprintln!("benchmark surface written to {}", path.display());
}

fn surface_evaluate(c: &mut Criterion) {
    let mut rng = SplitMix64(SEED);
    for (name, degree, count, rational) in SURFACES {
        let data = data(degree, count, rational, &mut rng);
        let surface = Surface::from_knot_forms(
            (degree, degree),
            &data.poles,
            (KnotForm::Flat(&data.knots_u), KnotForm::Flat(&data.knots_v)),
            data.weights.as_deref(),
            &SurfaceLimits::default(),
        )
        .unwrap();
        let pairs: Vec<[f64; 2]> = (0..PAIRS).map(|_| [rng.unit(), rng.unit()]).collect();
        write_json(name, &data, &surface, &pairs);
        let mut group = c.benchmark_group(format!("surface_100k_{name}"));
        group.throughput(Throughput::Elements(PAIRS as u64));
        let mut out = vec![[0.0; 3]; PAIRS];
        group.bench_function("points", |b| {
            b.iter(|| {
                for (o, &[u, v]) in out.iter_mut().zip(black_box(&pairs)) {
                    *o = surface.point(u, v);
                }
            });
        });
        let mut first = vec![[[0.0; 3]; 3]; PAIRS];
        group.bench_function("first_partials", |b| {
            b.iter(|| {
                for (o, &[u, v]) in first.iter_mut().zip(black_box(&pairs)) {
                    let partials = surface.partials(u, v, 1);
                    *o = [partials.point(), partials.du(), partials.dv()];
                }
            });
        });
        group.finish();
        black_box((&out, &first));
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .sample_size(20)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));
    targets = surface_evaluate
}
criterion_main!(benches);

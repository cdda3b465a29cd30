//! Reach of the surface knot families (docs/method.md §48; MATH.md §8.5, knot-family.md §6):
//! the fraction of a ball of radius `f·L` around `S(ũ, ṽ)` that the solve reaches, by family,
//! on random bicubics (or of degree 4 or 5). Prints a Markdown table; no timing.
//!
//! `cargo bench --bench surface_knot_reach` (options after `--`: `--surfaces N`, default 12;
//! `--grid M`, targets on an `M³` grid of the ball's cube, default 11 as in the study;
//! `--mixed-direct`: the mixed moves' single knot from the direct problem too; `--degree P`:
//! biquartics or biquintics instead, on `4P × 4P` nets).
//!
//! The samples follow the study's `check14_surface_reach3d.py`: 12 × 12 poles over a unit grid
//! jittered by `0.15·N(0, 1)` in x and y, height a doubly cumulated `0.3·N(0, 1)` times 0.3,
//! clamped knots on `[0, 1]` with uniform random interior knots, a span `j ∈ [2p, n − p]` in
//! each direction and `(ũ, ṽ)` uniform in the middle 80 % of it; `L` is the mean leg length of
//! the 4 × 4 local net in both directions. Each target is solved once with everything
//! (domain kept); a family reaches it when it returns a solution.
#![allow(clippy::unwrap_used)]

use knotshape::shape::family::Family;
use knotshape::spline::KnotForm;
use knotshape::surface::edit::knots::{
    SurfaceKnotFamily, SurfaceKnotOptions, solve_surface_knots_with,
};
use knotshape::surface::{Direction, Surface, SurfaceLimits};

/// SplitMix64.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
    fn normal(&mut self) -> f64 {
        let (a, b) = (self.unit().max(1e-300), self.unit());
        (-2.0 * a.ln()).sqrt() * (std::f64::consts::TAU * b).cos()
    }
}

const COLUMNS: [&str; 8] = [
    "iso u: envelope",
    "iso u: direct",
    "iso u: triples",
    "iso v (all)",
    "all iso (one direction)",
    "mixed, pair u",
    "mixed, pair v",
    "**everything**",
];

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let option = |name: &str, default: usize| {
        args.iter()
            .position(|a| a == name)
            .and_then(|i| args.get(i + 1))
            .and_then(|v| v.parse().ok())
            .unwrap_or(default)
    };
    let count = option("--surfaces", 12);
    let grid = option("--grid", 11);
    let options = SurfaceKnotOptions {
        mixed_direct: args.iter().any(|a| a == "--mixed-direct"),
        ..SurfaceKnotOptions::all(true)
    };
    let mut rng = Rng(18);
    // Degree 3 as in the study; `--degree 4` or `5` (the mixed moves' curved pair) on nets
    // large enough for the picked span's local net and its neighbours.
    let p = option("--degree", 3);
    let n = 12usize.max(4 * p);
    let radii = [0.05, 0.15];
    let mut sums = vec![[0.0f64; 8]; radii.len()];
    for _ in 0..count {
        let knots = |rng: &mut Rng| {
            let mut interior: Vec<f64> = (0..n - p - 1).map(|_| 0.05 + 0.9 * rng.unit()).collect();
            interior.sort_by(f64::total_cmp);
            let mut k = vec![0.0; p + 1];
            k.extend(interior);
            k.extend(vec![1.0; p + 1]);
            k
        };
        let (ku, kv) = (knots(&mut rng), knots(&mut rng));
        let mut z = vec![vec![0.0; n]; n];
        for i in 0..n {
            for j in 0..n {
                let s = 0.3 * rng.normal();
                let l = if j > 0 { z[i][j - 1] } else { 0.0 };
                let u = if i > 0 { z[i - 1][j] } else { 0.0 };
                let d = if i > 0 && j > 0 { z[i - 1][j - 1] } else { 0.0 };
                z[i][j] = l + u - d + s;
            }
        }
        let poles: Vec<Vec<[f64; 3]>> = (0..n)
            .map(|i| {
                (0..n)
                    .map(|j| {
                        [
                            i as f64 + 0.15 * rng.normal(),
                            j as f64 + 0.15 * rng.normal(),
                            0.3 * z[i][j],
                        ]
                    })
                    .collect()
            })
            .collect();
        let surface = Surface::from_knot_forms(
            (p, p),
            &poles,
            (KnotForm::Flat(&ku), KnotForm::Flat(&kv)),
            None::<&[Vec<f64>]>,
            &SurfaceLimits::default(),
        )
        .unwrap();
        let pick = |rng: &mut Rng, k: &[f64]| loop {
            let j = 2 * p + (rng.next() % (n - 3 * p + 1) as u64) as usize;
            if k[j] < k[j + 1] {
                return (j, k[j] + (0.1 + 0.8 * rng.unit()) * (k[j + 1] - k[j]));
            }
        };
        let ((ju, u), (jv, v)) = (pick(&mut rng, &ku), pick(&mut rng, &kv));
        let local = |a: usize, b: usize| poles[ju - p + a][jv - p + b];
        let dist = |x: [f64; 3], y: [f64; 3]| {
            ((x[0] - y[0]).powi(2) + (x[1] - y[1]).powi(2) + (x[2] - y[2]).powi(2)).sqrt()
        };
        let (mut legs, mut total) = (0, 0.0);
        for a in 0..=p {
            for b in 0..=p {
                if a < p {
                    total += dist(local(a, b), local(a + 1, b));
                    legs += 1;
                }
                if b < p {
                    total += dist(local(a, b), local(a, b + 1));
                    legs += 1;
                }
            }
        }
        let length = total / legs as f64;
        let centre = surface.point(u, v);
        for (r, &f) in radii.iter().enumerate() {
            let mut hits = [0usize; 8];
            let mut targets = 0usize;
            for a in 0..grid {
                for b in 0..grid {
                    for c in 0..grid {
                        let g = [a, b, c].map(|i| -1.0 + 2.0 * i as f64 / (grid - 1) as f64);
                        if g[0] * g[0] + g[1] * g[1] + g[2] * g[2] > 1.0 {
                            continue;
                        }
                        targets += 1;
                        let target: [f64; 3] =
                            std::array::from_fn(|k| centre[k] + f * length * g[k]);
                        let found = solve_surface_knots_with(&surface, u, v, target, &options);
                        let has = |test: &dyn Fn(SurfaceKnotFamily) -> bool| {
                            found.iter().any(|s| test(s.family))
                        };
                        let iso = |d: Direction, fam: Option<Family>| {
                            move |x: SurfaceKnotFamily| matches!(x, SurfaceKnotFamily::Iso { direction, family } if direction == d && fam.is_none_or(|f| f == family))
                        };
                        let marks = [
                            has(&iso(Direction::U, Some(Family::Envelope))),
                            has(&iso(Direction::U, Some(Family::Direct))),
                            has(&iso(Direction::U, Some(Family::Triples))),
                            has(&iso(Direction::V, None)),
                            has(&|x| x.is_iso()),
                            has(&|x| x == SurfaceKnotFamily::Mixed { pair: Direction::U }),
                            has(&|x| x == SurfaceKnotFamily::Mixed { pair: Direction::V }),
                            !found.is_empty(),
                        ];
                        for (h, m) in hits.iter_mut().zip(marks) {
                            *h += usize::from(m);
                        }
                    }
                }
            }
            for (s, h) in sums[r].iter_mut().zip(hits) {
                *s += h as f64 / targets as f64;
            }
        }
    }
    println!(
        "random surfaces of degree {p} in both directions ({n} x {n} poles): {count} surfaces, {grid}³ grid of targets in the ball, domain kept, mixed_direct {}\n",
        options.mixed_direct
    );
    print!("| family |");
    for f in radii {
        print!(" {f}L |");
    }
    println!("\n|---|{}", "---|".repeat(radii.len()));
    for (k, name) in COLUMNS.iter().enumerate() {
        print!("| {name} |");
        for sum in &sums {
            print!(" {:.3} |", sum[k] / count as f64);
        }
        println!();
    }
}

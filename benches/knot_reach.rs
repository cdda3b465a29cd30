//! Reach of the knot families (issue 26's closing note; MATH.md §8.4, knot-family.md §7): the
//! fraction of a disc of radius `f·L` around `s(t)` that the solve reaches, by family, on
//! random 2D cubics and quintics. Prints a Markdown table; no timing.
//!
//! `cargo bench --bench knot_reach` (options after `--`: `--cubic N` and `--quintic N` curves
//! of each degree, two points each, default 20 and 12; `--grid M`, targets on an `M × M`
//! grid of the disc's square, default 41 as in the study; `--mesh` adds the reference reach
//! of the same samples by this bench's own meshing of every pair's box).
//!
//! The samples follow the study's `check10_reach.py`: `3p + 4` control points, a wavy or a
//! uniform random polygon (alternating), clamped knots on `[0, 1]` with interior gaps uniform
//! in `[0.5, 1.5]`, a span `j` whose `2p` relevant knots are all interior, `t` uniform in the
//! middle 80 % of it; `L` is the mean leg length of `d_{j−p} … d_j`; the targets are the grid
//! points inside the disc. Each target is solved once with every family that applies
//! (envelope both sides, direct; domain kept), and a family reaches it when it returns a
//! solution. Columns: envelope left side only (the study's E1: `u_j := t`), right side only,
//! both sides (E2), direct pairs (D), both families (ED), and the local control points' hull
//! (the study's W, the most any knot move can reach).
//!
//! With `--mesh`, the reference reach is the study's method in this bench's own code: every
//! pair's admissible box is meshed (a graded 33 × 33 grid, triangles), its vertices mapped by
//! an independent de Boor, and a target counts as reached when a mapped triangle holds it.
#![allow(clippy::unwrap_used)]

#[path = "../tests/common/mod.rs"]
mod common;

use common::SplitMix64;
use common::families::{Net, SetBox, setup};
use knotshape::shape::family::{Family, FamilyChoice, solve_families};
use knotshape::shape::{ShapeQuery, Side};
use knotshape::spline::{Curve, CurveLimits};

/// Disc radii in units of `L`.
const RADII: [f64; 3] = [0.05, 0.15, 0.4];

/// Column names.
const COLUMNS: [&str; 6] = [
    "envelope, left side (E1)",
    "envelope, right side",
    "envelope, both sides (E2)",
    "direct (D)",
    "both families (ED)",
    "local hull (W)",
];

/// Mesh-reference columns.
const MESH_COLUMNS: [&str; 3] = [
    "mesh: envelope both sides",
    "mesh: direct",
    "mesh: both families",
];

struct Options {
    cubic: usize,
    quintic: usize,
    grid: usize,
    mesh: bool,
}

fn options() -> Options {
    let args: Vec<String> = std::env::args().collect();
    let value = |name: &str, default: usize| {
        args.iter()
            .position(|a| a == name)
            .and_then(|i| args.get(i + 1))
            .and_then(|v| v.parse().ok())
            .unwrap_or(default)
    };
    Options {
        cubic: value("--cubic", 20),
        quintic: value("--quintic", 12),
        grid: value("--grid", 41),
        mesh: args.iter().any(|a| a == "--mesh"),
    }
}

/// A standard normal variate (Box–Muller).
fn normal(rng: &mut SplitMix64) -> f64 {
    let u = rng.unit().max(1e-300);
    let v = rng.unit();
    (-2.0 * u.ln()).sqrt() * (2.0 * std::f64::consts::PI * v).cos()
}

/// The study's random curve: `n + 1 = 3p + 4` control points, clamped on `[0, 1]`.
fn study_curve(rng: &mut SplitMix64, p: usize, wavy: bool) -> Curve {
    let n = 3 * p + 3;
    let points: Vec<[f64; 2]> = if wavy {
        let mut y = 0.0;
        (0..=n)
            .map(|i| {
                y += 0.8 * normal(rng);
                [i as f64 + 0.25 * normal(rng), y]
            })
            .collect()
    } else {
        (0..=n)
            .map(|_| {
                [
                    rng.range(0.0, n as f64 / 2.0),
                    rng.range(0.0, n as f64 / 2.0),
                ]
            })
            .collect()
    };
    let gaps: Vec<f64> = (0..n - p + 1).map(|_| rng.range(0.5, 1.5)).collect();
    let total: f64 = gaps.iter().sum();
    let mut knots = vec![0.0; p + 1];
    let mut acc = 0.0;
    for g in &gaps[..gaps.len() - 1] {
        acc += g;
        knots.push(acc / total);
    }
    knots.extend(std::iter::repeat_n(1.0, p + 1));
    Curve::new(p, &points, &knots, None, &CurveLimits::default()).unwrap()
}

/// Convex hull (counter-clockwise) of 2D points.
fn hull(points: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let mut pts = points.to_vec();
    pts.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    let cross = |o: [f64; 2], a: [f64; 2], b: [f64; 2]| {
        (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    };
    let mut lower: Vec<[f64; 2]> = Vec::new();
    for &p in &pts {
        while lower.len() >= 2 && cross(lower[lower.len() - 2], lower[lower.len() - 1], p) <= 0.0 {
            lower.pop();
        }
        lower.push(p);
    }
    let mut upper: Vec<[f64; 2]> = Vec::new();
    for &p in pts.iter().rev() {
        while upper.len() >= 2 && cross(upper[upper.len() - 2], upper[upper.len() - 1], p) <= 0.0 {
            upper.pop();
        }
        upper.push(p);
    }
    lower.pop();
    upper.pop();
    lower.extend(upper);
    lower
}

/// Whether `p` lies strictly inside the convex polygon `h` (counter-clockwise).
fn in_convex(h: &[[f64; 2]], p: [f64; 2]) -> bool {
    (0..h.len()).all(|i| {
        let (a, b) = (h[i], h[(i + 1) % h.len()]);
        (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]) > 0.0
    })
}

/// Whether `p` lies in the triangle `a b c` (either orientation, edges included).
fn in_triangle(a: [f64; 2], b: [f64; 2], c: [f64; 2], p: [f64; 2]) -> bool {
    let d = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    if d == 0.0 {
        return false;
    }
    let l1 = ((p[0] - a[0]) * (c[1] - a[1]) - (p[1] - a[1]) * (c[0] - a[0])) / d;
    let l2 = ((b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])) / d;
    let e = -1e-12;
    l1 >= e && l2 >= e && l1 + l2 <= 1.0 - e
}

/// The reference reach of one family problem: every pair's box meshed (graded grid),
/// targets inside a mapped triangle.
fn mesh_reach(
    curve: &Curve,
    t: f64,
    family: Family,
    side: Option<Side>,
    targets: &[[f64; 2]],
    reached: &mut [bool],
) {
    let Ok(problem) = setup(curve, t, family, side, true) else {
        return;
    };
    let net = Net::of(curve);
    let g = 32;
    let nodes: Vec<f64> = (0..=g)
        .map(|i| 0.5 - 0.5 * (std::f64::consts::PI * i as f64 / g as f64).cos())
        .collect();
    for unknowns in problem.unknown_sets() {
        let Some(sbox) = SetBox::new(&problem, &unknowns) else {
            continue;
        };
        let mut vertices = Vec::with_capacity((g + 1) * (g + 1));
        let mut singular = Vec::with_capacity((g + 1) * (g + 1));
        for &s0 in &nodes {
            for &s1 in &nodes {
                let x = sbox.at(&[s0, s1]);
                let knots = problem.knots_with(&unknowns, &x);
                // The span's collapse (both its ends at t) has no point.
                singular.push(sbox.span_ends.is_some() && x[0] == problem.t && x[1] == problem.t);
                let m = problem.evaluation_span(&knots);
                let p = net.point_in_span(&knots, m, t);
                vertices.push([p[0], p[1]]);
            }
        }
        let at = |i: usize, k: usize| i * (g + 1) + k;
        for i in 0..g {
            for k in 0..g {
                let quad = [at(i, k), at(i + 1, k), at(i + 1, k + 1), at(i, k + 1)];
                for tri in [[quad[0], quad[1], quad[2]], [quad[0], quad[2], quad[3]]] {
                    if tri.iter().any(|&v| singular[v]) {
                        continue;
                    }
                    let [a, b, c] = tri.map(|v| vertices[v]);
                    let lo = [a[0].min(b[0]).min(c[0]), a[1].min(b[1]).min(c[1])];
                    let hi = [a[0].max(b[0]).max(c[0]), a[1].max(b[1]).max(c[1])];
                    for (r, p) in reached.iter_mut().zip(targets) {
                        if !*r
                            && p[0] >= lo[0]
                            && p[0] <= hi[0]
                            && p[1] >= lo[1]
                            && p[1] <= hi[1]
                            && in_triangle(a, b, c, *p)
                        {
                            *r = true;
                        }
                    }
                }
            }
        }
    }
}

/// Per-sample fractions, per column.
type Row = Vec<f64>;

fn main() {
    let options = options();
    let mut rng = SplitMix64::new(0x7265_6163_6801);
    println!("## Reach of the knot families (fraction of a disc of radius f·L around s(t))\n");
    println!(
        "`cargo bench --bench knot_reach -- --cubic {} --quintic {} --grid {}{}`: {} cubic and {} quintic random curves, two points each; mean ± its standard error [min, max] over the samples.\n",
        options.cubic,
        options.quintic,
        options.grid,
        if options.mesh { " --mesh" } else { "" },
        options.cubic,
        options.quintic
    );
    let mut columns: Vec<&str> = COLUMNS.to_vec();
    if options.mesh {
        columns.extend(MESH_COLUMNS);
    }
    // rows[degree index][radius index] = per-sample rows.
    let mut table: Vec<Vec<Vec<Row>>> = vec![vec![Vec::new(); RADII.len()]; 2];
    let mut solves = 0usize;
    let started = std::time::Instant::now();
    for (d, (p, curves)) in [(3usize, options.cubic), (5, options.quintic)]
        .into_iter()
        .enumerate()
    {
        let n = 3 * p + 3;
        for c in 0..curves {
            let curve = study_curve(&mut rng, p, c % 2 == 0);
            for _ in 0..2 {
                let j = 2 * p + rng.below(n - p + 1 - 2 * p);
                let knots = curve.knots();
                let h = knots[j + 1] - knots[j];
                let t = rng.range(knots[j] + 0.1 * h, knots[j + 1] - 0.1 * h);
                let s = common::de_boor(&curve, knots, t).unwrap();
                let d_local: Vec<[f64; 2]> = curve.control_points()[j - p..=j]
                    .iter()
                    .map(|q| [q[0], q[1]])
                    .collect();
                let l = d_local
                    .windows(2)
                    .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]))
                    .sum::<f64>()
                    / p as f64;
                let local_hull = hull(&d_local);
                let query = ShapeQuery::new(&curve, t);
                for (r, &f) in RADII.iter().enumerate() {
                    let targets: Vec<[f64; 2]> = (0..options.grid)
                        .flat_map(|a| (0..options.grid).map(move |b| (a, b)))
                        .map(|(a, b)| {
                            let step = 2.0 / (options.grid - 1) as f64;
                            [-1.0 + step * a as f64, -1.0 + step * b as f64]
                        })
                        .filter(|g| g[0] * g[0] + g[1] * g[1] <= 1.0)
                        .map(|g| [s[0] + f * l * g[0], s[1] + f * l * g[1]])
                        .collect();
                    let mut hits = vec![0usize; columns.len()];
                    for target in &targets {
                        let outcome = solve_families(
                            &query,
                            FamilyChoice::Default,
                            [target[0], target[1], 0.0],
                        );
                        solves += 1;
                        let by = |family: Family, side: Option<Side>| {
                            outcome
                                .solutions
                                .iter()
                                .any(|s| s.family == family && (side.is_none() || s.side == side))
                        };
                        let left = by(Family::Envelope, Some(Side::Left));
                        let right = by(Family::Envelope, Some(Side::Right));
                        let direct = by(Family::Direct, None);
                        let flags = [
                            left,
                            right,
                            left || right,
                            direct,
                            left || right || direct,
                            in_convex(&local_hull, *target),
                        ];
                        for (h, flag) in hits.iter_mut().zip(flags) {
                            *h += usize::from(flag);
                        }
                    }
                    if options.mesh {
                        let mut envelope = vec![false; targets.len()];
                        for side in [Side::Left, Side::Right] {
                            mesh_reach(
                                &curve,
                                t,
                                Family::Envelope,
                                Some(side),
                                &targets,
                                &mut envelope,
                            );
                        }
                        let mut direct = vec![false; targets.len()];
                        mesh_reach(&curve, t, Family::Direct, None, &targets, &mut direct);
                        let both = envelope
                            .iter()
                            .zip(&direct)
                            .filter(|(a, b)| **a || **b)
                            .count();
                        hits[6] = envelope.iter().filter(|a| **a).count();
                        hits[7] = direct.iter().filter(|a| **a).count();
                        hits[8] = both;
                    }
                    table[d][r].push(
                        hits.iter()
                            .map(|&h| h as f64 / targets.len() as f64)
                            .collect(),
                    );
                }
            }
        }
    }
    print!("| method |");
    for p in ["cubic", "quintic"] {
        for f in RADII {
            print!(" {p} {f}L |");
        }
    }
    println!();
    println!("|---|{}", "---|".repeat(2 * RADII.len()));
    for (k, name) in columns.iter().enumerate() {
        print!("| {name} |");
        for per_degree in &table {
            for rows in per_degree {
                if rows.is_empty() {
                    print!(" – |");
                    continue;
                }
                let values: Vec<f64> = rows.iter().map(|row| row[k]).collect();
                let mean = values.iter().sum::<f64>() / values.len() as f64;
                let lo = values.iter().copied().fold(f64::INFINITY, f64::min);
                let hi = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                let spread = (values.iter().map(|v| (v - mean).powi(2)).sum::<f64>()
                    / (values.len().max(2) - 1) as f64)
                    .sqrt();
                let se = spread / (values.len() as f64).sqrt();
                print!(" {mean:.2} ±{se:.2} [{lo:.2}, {hi:.2}] |");
            }
        }
        println!();
    }
    println!(
        "\n{} cubic and {} quintic samples per radius, {} solves in {:.0} s.",
        2 * options.cubic,
        2 * options.quintic,
        solves,
        started.elapsed().as_secs_f64()
    );
}

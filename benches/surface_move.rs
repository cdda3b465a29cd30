//! knotshape's side of `bash benches/occt_surface_move.sh`: moving one point of every real
//! surface (tests/data/real_surfaces.json.gz) onto a target off the surface, Open CASCADE's
//! `Geom_BSplineSurface::MovePoint` against knotshape's surface edit by control points, by
//! weights and by knots, on the same input.
//!
//! benches/occt_surface_move.py picks the parameter pair and the target (`S(u, v)` moved by
//! `size (1e-2 n + 5e-3 t)`, `n` the unit normal, `t` the unit `S_u`, `size` the diagonal of
//! the poles' box) and writes Open CASCADE's moved poles and its time per call. Here, for every
//! surface, each of knotshape's methods runs alone through [`surface_edit`] with the domain
//! kept (as `MovePoint` keeps it; its best solution is the first ranked: the least certified
//! deviation), and every result — Open CASCADE's
//! too — is measured the same way:
//!
//! * reached: `|S_new(u, v) − target| <= 1e-9 size` (knotshape's evaluation for both);
//! * the pole-displacement norm `sqrt(Σ_ij |d_ij,new − d_ij,old|²)` over the distinct poles
//!   (zero for weights and knots, which keep the net);
//! * the sampled max deviation `max |S_new − S_old|` over a 101 × 101 grid on the domain and a
//!   41 × 41 grid on the support of the poles active at `(u, v)` (the same points for every
//!   method), and knotshape's certified bound ([`surface_max_deviation`] on the whole domain;
//!   never below the true maximum, so sampled ≤ true ≤ certified);
//! * times: Open CASCADE's `MovePoint` call (median of five, through the Python binding),
//!   knotshape's method `solve` alone and the whole edit with each solution's certified
//!   deviation and the ranking (medians of three).
//!
//! Prints the table of docs/performance.md (sizes relative to each surface's `size`).
//!
//! Usage: `cargo bench --bench surface_move -- OCCT_MOVES_JSON`.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::collections::HashMap;
use std::io::Read;
use std::time::Instant;

use knotshape::spline::KnotForm;
use knotshape::surface::edit::{
    FixedNet, SurfaceConstraints, SurfaceEditContext, SurfaceEditOptions, SurfaceEditRequest,
    SurfaceMethodKind, surface_edit, surface_max_deviation,
};
use knotshape::surface::{Surface, SurfaceLimits};
use serde::Deserialize;

/// Grid points per side of the sample on the whole domain.
const DOMAIN_GRID: usize = 101;

/// Grid points per side of the sample on the active poles' support.
const LOCAL_GRID: usize = 41;

/// A move reaches its target within this fraction of the surface's size.
const REACHED: f64 = 1e-9;

#[derive(Deserialize)]
struct Data {
    id: String,
    degree_u: usize,
    degree_v: usize,
    poles: Vec<Vec<[f64; 3]>>,
    #[serde(default)]
    weights: Option<Vec<Vec<f64>>>,
    knots_u: Vec<f64>,
    knots_v: Vec<f64>,
}

#[derive(Deserialize)]
struct File {
    surfaces: Vec<Data>,
}

#[derive(Deserialize)]
struct OcctMove {
    id: String,
    u: f64,
    v: f64,
    target: [f64; 3],
    size: f64,
    #[serde(default)]
    poles: Option<Vec<Vec<[f64; 3]>>>,
    #[serde(default)]
    seconds: f64,
    #[serde(default)]
    error: Option<String>,
}

#[derive(Deserialize)]
struct OcctFile {
    surfaces: Vec<OcctMove>,
}

/// One method's results over the surfaces.
#[derive(Default)]
struct Column {
    tried: usize,
    reached: usize,
    displacement: Vec<f64>,
    sampled: Vec<f64>,
    certified: Vec<f64>,
    solve_seconds: Vec<f64>,
    edit_seconds: Vec<f64>,
    /// Per surface reached by both: (ours / Open CASCADE's) displacement and sampled deviation.
    displacement_ratio: Vec<f64>,
    sampled_ratio: Vec<f64>,
}

/// The sample points (module docs): the domain grid and the local grid.
fn samples(surface: &Surface, u: f64, v: f64) -> Vec<(f64, f64)> {
    let [(u0, u1), (v0, v1)] = surface.domain();
    let mut points = Vec::with_capacity(DOMAIN_GRID * DOMAIN_GRID + LOCAL_GRID * LOCAL_GRID);
    let grid = |lo: f64, hi: f64, n: usize, k: usize| lo + (hi - lo) * k as f64 / (n - 1) as f64;
    for a in 0..DOMAIN_GRID {
        for b in 0..DOMAIN_GRID {
            points.push((grid(u0, u1, DOMAIN_GRID, a), grid(v0, v1, DOMAIN_GRID, b)));
        }
    }
    let support = |axis: &knotshape::surface::Axis, t: f64| {
        let (p, span) = (axis.degree(), axis.span(t));
        let knots = axis.knots();
        let (lo, hi) = axis.domain();
        (knots[span - p].max(lo), knots[span + p + 1].min(hi))
    };
    let ((su0, su1), (sv0, sv1)) = (support(surface.u(), u), support(surface.v(), v));
    for a in 0..LOCAL_GRID {
        for b in 0..LOCAL_GRID {
            points.push((grid(su0, su1, LOCAL_GRID, a), grid(sv0, sv1, LOCAL_GRID, b)));
        }
    }
    points
}

fn gap(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// `sqrt(Σ |Δd|²)` over the stored poles `(i, j)` with `i < rows`, `j < columns` (the
/// distinct ones).
fn displacement(old: &Surface, new: &Surface, rows: usize, columns: usize) -> f64 {
    let mut total = 0.0;
    for i in 0..rows {
        for j in 0..columns {
            total += gap(old.control_point(i, j), new.control_point(i, j)).powi(2);
        }
    }
    total.sqrt()
}

fn median(values: &mut [f64]) -> f64 {
    if values.is_empty() {
        return f64::NAN;
    }
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

fn max(values: &[f64]) -> f64 {
    values.iter().fold(f64::NAN, |m, &x| m.max(x))
}

fn min(values: &[f64]) -> f64 {
    values.iter().fold(f64::NAN, |m, &x| m.min(x))
}

/// Median of three timed runs of `run`, and its last result.
fn timed<T>(mut run: impl FnMut() -> T) -> (f64, T) {
    let mut times = Vec::with_capacity(3);
    let mut last = None;
    for _ in 0..3 {
        let started = Instant::now();
        let result = run();
        times.push(started.elapsed().as_secs_f64());
        last = Some(result);
    }
    (median(&mut times), last.unwrap())
}

fn main() {
    let mut args = std::env::args().skip(1).filter(|a| !a.starts_with("--"));
    let occt_path = args.next().expect("usage: surface_move OCCT_MOVES_JSON");
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/real_surfaces.json.gz");
    let mut text = String::new();
    flate2::read::GzDecoder::new(std::fs::File::open(path).unwrap())
        .read_to_string(&mut text)
        .unwrap();
    let file: File = serde_json::from_str(&text).unwrap();
    let occt: OcctFile =
        serde_json::from_str(&std::fs::read_to_string(&occt_path).unwrap()).unwrap();
    let occt: HashMap<&str, &OcctMove> = occt.surfaces.iter().map(|r| (r.id.as_str(), r)).collect();
    const KINDS: [SurfaceMethodKind; 3] = [
        SurfaceMethodKind::ControlPoints,
        SurfaceMethodKind::Weights,
        SurfaceMethodKind::Knots,
    ];
    let mut theirs = Column::default();
    let mut ours: Vec<Column> = KINDS.iter().map(|_| Column::default()).collect();
    let mut occt_errors = Vec::new();
    for data in &file.surfaces {
        let Some(row) = occt.get(data.id.as_str()) else {
            continue;
        };
        let build = |poles: &[Vec<[f64; 3]>]| {
            Surface::from_knot_forms(
                (data.degree_u, data.degree_v),
                poles,
                (KnotForm::Flat(&data.knots_u), KnotForm::Flat(&data.knots_v)),
                data.weights.as_deref(),
                &SurfaceLimits::default(),
            )
            .unwrap()
        };
        let surface = build(&data.poles);
        let (u, v, target, size) = (row.u, row.v, row.target, row.size);
        let points = samples(&surface, u, v);
        let before: Vec<[f64; 3]> = points.iter().map(|&(a, b)| surface.point(a, b)).collect();
        let sampled = |new: &Surface| {
            points
                .iter()
                .zip(&before)
                .fold(0.0f64, |m, (&(a, b), old)| {
                    m.max(gap(new.point(a, b), *old))
                })
        };
        let domain = surface.domain();
        let (rows, columns) = (data.poles.len(), data.poles[0].len());
        // Open CASCADE's move, its poles mapped onto the stored net (row i of the stored net is
        // Open CASCADE's row i modulo its count, for a periodic direction's repeated poles).
        let occt_result = match (&row.poles, &row.error) {
            (Some(poles), None) => {
                let (n_u, n_v) = (poles.len(), poles[0].len());
                let mapped: Vec<Vec<[f64; 3]>> = (0..rows)
                    .map(|i| (0..columns).map(|j| poles[i % n_u][j % n_v]).collect())
                    .collect();
                let new = build(&mapped);
                theirs.tried += 1;
                let residual = gap(new.point(u, v), target);
                if residual <= REACHED * size {
                    theirs.reached += 1;
                }
                let d = displacement(&surface, &new, n_u, n_v) / size;
                let s = sampled(&new) / size;
                theirs.displacement.push(d);
                theirs.sampled.push(s);
                let certified = surface_max_deviation(&surface, &new, domain) / size;
                assert!(
                    s <= certified * (1.0 + 1e-9) + 1e-12,
                    "{} Open CASCADE: sampled {s} above certified {certified}",
                    data.id
                );
                theirs.certified.push(certified);
                theirs.solve_seconds.push(row.seconds);
                Some((residual <= REACHED * size, d, s, n_u, n_v))
            }
            _ => {
                occt_errors.push(format!(
                    "{}: {}",
                    data.id,
                    row.error.as_deref().unwrap_or("no poles")
                ));
                None
            }
        };
        let none = SurfaceConstraints::none();
        let free = FixedNet::none(&surface);
        for (kind, column) in KINDS.iter().zip(&mut ours) {
            let methods = [*kind];
            let request = SurfaceEditRequest {
                surface: &surface,
                parameter: (u, v),
                target,
                methods: &methods,
                constraints: &none,
                fixed: &free,
                options: SurfaceEditOptions {
                    nearest: false,
                    keep_domain: true,
                },
            };
            let context = SurfaceEditContext {
                surface: &surface,
                parameter: (u, v),
                constraints: &none,
                fixed: &free,
                keep_domain: true,
            };
            let method = kind.method().unwrap();
            let (solve_seconds, _) = timed(|| method.solve(&context, target));
            let (edit_seconds, outcome) = timed(|| surface_edit(&request));
            column.tried += 1;
            column.solve_seconds.push(solve_seconds);
            column.edit_seconds.push(edit_seconds);
            let Some(best) = outcome.solutions.first() else {
                continue;
            };
            let residual = gap(best.surface.point(u, v), target);
            if residual > REACHED * size {
                continue;
            }
            column.reached += 1;
            let (n_u, n_v) = occt_result
                .map(|(_, _, _, n_u, n_v)| (n_u, n_v))
                .unwrap_or((rows, columns));
            let d = displacement(&surface, &best.surface, n_u, n_v) / size;
            let s = sampled(&best.surface) / size;
            let certified = best.max_deviation.unwrap() / size;
            assert!(
                s <= certified * (1.0 + 1e-9) + 1e-12,
                "{} {}: sampled {s} above certified {certified} (affected {:?})",
                data.id,
                kind.name(),
                best.affected_domain
            );
            column.displacement.push(d);
            column.sampled.push(s);
            column.certified.push(certified);
            if let Some((true, occt_d, occt_s, _, _)) = occt_result {
                if occt_d > 0.0 {
                    column.displacement_ratio.push(d / occt_d);
                }
                if occt_s > 0.0 {
                    column.sampled_ratio.push(s / occt_s);
                }
            }
        }
    }
    println!(
        "surfaces {}, Open CASCADE raised on {}: {:?}",
        file.surfaces.len(),
        occt_errors.len(),
        occt_errors
    );
    println!(
        "| method | reached / tried | pole displacement / size: sum, median | ours / Open CASCADE's displacement: median, max | sampled max deviation / size: median, max | ours / Open CASCADE's sampled deviation: median, min–max | certified deviation / size: median, max | time per move: median (solve alone; with certified deviations and ranking) |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    let print = |name: &str, column: &mut Column, edit: bool| {
        let sum: f64 = column.displacement.iter().sum();
        // Weights and knots keep the net: no displacement to compare.
        let net_kept = sum == 0.0;
        let ratio = |values: &mut Vec<f64>, with_min: bool| {
            if values.is_empty() {
                return "—".to_string();
            }
            let m = median(values);
            if with_min {
                format!("{m:.3}, {:.3}–{:.3}", min(values), max(values))
            } else {
                format!("{m:.3}, {:.3}", max(values))
            }
        };
        let time = if edit {
            format!(
                "{:.1} µs ({:.1} µs)",
                median(&mut column.solve_seconds) * 1e6,
                median(&mut column.edit_seconds) * 1e6
            )
        } else {
            format!(
                "{:.1} µs (the call through Python)",
                median(&mut column.solve_seconds) * 1e6
            )
        };
        println!(
            "| {name} | {} / {} | {} | {} | {:.3e}, {:.3e} | {} | {:.3e}, {:.3e} | {time} |",
            column.reached,
            column.tried,
            if net_kept {
                "0 (the net is kept)".to_string()
            } else {
                format!("{sum:.3e}, {:.3e}", median(&mut column.displacement))
            },
            if net_kept {
                "—".to_string()
            } else {
                ratio(&mut column.displacement_ratio, false)
            },
            median(&mut column.sampled),
            max(&column.sampled),
            ratio(&mut column.sampled_ratio, true),
            median(&mut column.certified),
            max(&column.certified),
        );
    };
    print("Open CASCADE `MovePoint`", &mut theirs, false);
    for (kind, column) in KINDS.iter().zip(&mut ours) {
        print(&format!("knotshape `{}`", kind.name()), column, true);
    }
}

//! knotshape's side of `bash benches/occt_surface_mesh.sh`: triangles against Open CASCADE's
//! `BRepMesh_IncrementalMesh` for the same measured deviation, over the real surfaces
//! (tests/data/real_surfaces.json.gz).
//!
//! For every mesh Open CASCADE made (benches/occt_surface_mesh.py: a deflection that is a
//! fraction of the surface's size, two angular deflections), its deviation is *measured* — the
//! largest distance between the surface and the mesh at the same parameters, over 45 points of
//! every triangle (its vertices, edges and inside) — and knotshape meshes the same surface with
//! that deviation as its `tolerance`; its mesh is measured the same way. Both measures bound
//! the two-way (Hausdorff) distance of the sampled points, since each mesh point is compared
//! with the surface point of the same `(u, v)`. Prints one row per (fraction, angle):
//! triangles of each, their ratio, per-surface wins, and the largest measured deviation of
//! knotshape's meshes over their tolerance (never above 1: the bound is certified).
//!
//! A second table compares at *equal measured deviation*: for every mesh, the largest
//! tolerance knotshape's search finds whose mesh's measured deviation is still at most
//! BRepMesh's (the tolerance doubled from BRepMesh's deviation while that holds, at most
//! [`MAX_DOUBLINGS`] times, then [`BISECTIONS`] geometric bisections between the last
//! tolerance that held and the first that did not), and the triangles of that mesh. Those
//! meshes are certified at their own, larger tolerance only: the column compares what both
//! meshers' meshes are measured to be, as BRepMesh's deflection is a target too. Where
//! BRepMesh's deviation is below `1e-8` of the coordinate magnitude (a flat surface, rounding
//! only) knotshape's tolerance is that floor instead; such meshes are counted in the last
//! column and left out of the largest ratio of measured deviations.
//!
//! Usage: `cargo bench --bench surface_mesh -- OCCT_MESHES_JSON`.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::collections::{BTreeMap, HashMap};
use std::io::Read;
use std::time::Instant;

use knotshape::spline::KnotForm;
use knotshape::surface::{Surface, SurfaceLimits};
use serde::Deserialize;

/// Barycentric steps per triangle side of the measure (`(k + 1)(k + 2) / 2` points).
const STEPS: usize = 8;

/// Most triangles knotshape may use on one surface.
const MAX_TRIANGLES: usize = 2_000_000;

/// Doublings of the tolerance in the equal-deviation search (module docs), at most.
const MAX_DOUBLINGS: usize = 5;

/// Geometric bisection steps of the equal-deviation search after the doublings.
const BISECTIONS: usize = 4;

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
struct OcctMesh {
    uv: Vec<[f64; 2]>,
    points: Vec<[f64; 3]>,
    triangles: Vec<[usize; 3]>,
    seconds: f64,
    fraction: f64,
    angle: f64,
}

#[derive(Deserialize)]
struct OcctRow {
    id: String,
    meshes: Vec<OcctMesh>,
}

#[derive(Deserialize)]
struct OcctFile {
    surfaces: Vec<OcctRow>,
}

/// The measured deviation of a mesh (module docs): the largest `|S(u, v) − L(u, v)|` over the
/// sample points of its triangles, `L` interpolating the mesh's points linearly. Stops early
/// (with a value above `limit`) once a point is farther than `limit`.
fn measured(
    surface: &Surface,
    uv: &[[f64; 2]],
    points: &[[f64; 3]],
    triangles: &[[usize; 3]],
    limit: f64,
) -> f64 {
    let [(u0, u1), (v0, v1)] = surface.domain();
    let mut worst = 0.0f64;
    for triangle in triangles {
        for i in 0..=STEPS {
            for j in 0..=STEPS - i {
                let (b, c) = (i as f64 / STEPS as f64, j as f64 / STEPS as f64);
                let a = 1.0 - b - c;
                let [ta, tb, tc] = triangle.map(|k| uv[k]);
                let u = (a * ta[0] + b * tb[0] + c * tc[0]).clamp(u0, u1);
                let v = (a * ta[1] + b * tb[1] + c * tc[1]).clamp(v0, v1);
                let [pa, pb, pc] = triangle.map(|k| points[k]);
                let on_mesh: [f64; 3] = std::array::from_fn(|k| a * pa[k] + b * pb[k] + c * pc[k]);
                let s = surface.point(u, v);
                let gap = (0..3)
                    .map(|k| (s[k] - on_mesh[k]).powi(2))
                    .sum::<f64>()
                    .sqrt();
                worst = worst.max(gap);
            }
        }
        if worst > limit {
            return worst;
        }
    }
    worst
}

/// knotshape's mesh at `tolerance`: its triangles and measured deviation (early-stopped
/// above `limit`), or `None` when refused.
fn ours(surface: &Surface, tolerance: f64, limit: f64) -> Option<(usize, f64)> {
    let mesh = surface.tessellate(tolerance, MAX_TRIANGLES).ok()?;
    let triangles: Vec<[usize; 3]> = mesh
        .triangles
        .iter()
        .map(|t| t.map(|k| k as usize))
        .collect();
    let deviation = measured(surface, &mesh.parameters, &mesh.vertices, &triangles, limit);
    Some((triangles.len(), deviation))
}

/// The equal-deviation search (module docs) from `tolerance`, whose mesh has `triangles` and
/// a measured deviation at most `deviation`: the largest tolerance found whose mesh's measured
/// deviation is at most `deviation`, with that mesh's triangles and measured deviation.
fn equal_deviation(
    surface: &Surface,
    deviation: f64,
    tolerance: f64,
    first: (usize, f64),
) -> (f64, usize, f64) {
    let mut good = (tolerance, first.0, first.1);
    let mut bad = None;
    for _ in 0..MAX_DOUBLINGS {
        let trial = 2.0 * good.0;
        match ours(surface, trial, deviation) {
            Some((n, d)) if d <= deviation => good = (trial, n, d),
            _ => {
                bad = Some(trial);
                break;
            }
        }
    }
    let Some(mut bad) = bad else {
        return good;
    };
    for _ in 0..BISECTIONS {
        let trial = (good.0 * bad).sqrt();
        match ours(surface, trial, deviation) {
            Some((n, d)) if d <= deviation => good = (trial, n, d),
            _ => bad = trial,
        }
    }
    good
}

#[derive(Default)]
struct Row {
    surfaces: usize,
    occt_triangles: usize,
    ours_triangles: usize,
    fewer: usize,
    equal: usize,
    more: usize,
    ratios: Vec<f64>,
    worst_over_tolerance: f64,
    occt_seconds: f64,
    ours_seconds: f64,
    refused: usize,
    /// The equal-deviation comparison (module docs): knotshape's triangles, per-surface ratios
    /// and wins, its tolerance over BRepMesh's deviation, its measured deviation over
    /// BRepMesh's.
    equal_triangles: usize,
    equal_ratios: Vec<f64>,
    equal_wins: [usize; 3],
    equal_stretch: Vec<f64>,
    equal_worst: f64,
    /// Meshes whose BRepMesh deviation is below the smallest tolerance used (`1e-8` of the
    /// coordinate magnitude: flat surfaces), where knotshape's mesh is certified at that
    /// tolerance instead and left out of `equal_worst`.
    below_floor: usize,
}

fn main() {
    let mut args = std::env::args().skip(1).filter(|a| !a.starts_with("--"));
    let occt_path = args.next().expect("usage: surface_mesh OCCT_MESHES_JSON");
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/real_surfaces.json.gz");
    let mut text = String::new();
    flate2::read::GzDecoder::new(std::fs::File::open(path).unwrap())
        .read_to_string(&mut text)
        .unwrap();
    let file: File = serde_json::from_str(&text).unwrap();
    let occt: OcctFile =
        serde_json::from_str(&std::fs::read_to_string(&occt_path).unwrap()).unwrap();
    let occt: HashMap<&str, &OcctRow> = occt.surfaces.iter().map(|r| (r.id.as_str(), r)).collect();
    let mut rows: BTreeMap<(u64, u64), Row> = BTreeMap::new();
    for data in &file.surfaces {
        let Some(theirs) = occt.get(data.id.as_str()) else {
            continue;
        };
        let surface = Surface::from_knot_forms(
            (data.degree_u, data.degree_v),
            &data.poles,
            (KnotForm::Flat(&data.knots_u), KnotForm::Flat(&data.knots_v)),
            data.weights.as_deref(),
            &SurfaceLimits::default(),
        )
        .unwrap();
        for mesh in &theirs.meshes {
            let row = rows
                .entry((mesh.fraction.to_bits(), mesh.angle.to_bits()))
                .or_default();
            let deviation = measured(
                &surface,
                &mesh.uv,
                &mesh.points,
                &mesh.triangles,
                f64::INFINITY,
            );
            // A flat surface meshes exactly: the tolerance is then the smallest it allows.
            let tolerance = deviation.max(1e-8 * surface.coordinate_magnitude());
            let started = Instant::now();
            let Ok(ours_mesh) = surface.tessellate(tolerance, MAX_TRIANGLES) else {
                row.refused += 1;
                continue;
            };
            row.ours_seconds += started.elapsed().as_secs_f64();
            row.occt_seconds += mesh.seconds;
            let triangles: Vec<[usize; 3]> = ours_mesh
                .triangles
                .iter()
                .map(|t| t.map(|k| k as usize))
                .collect();
            let ours_deviation = measured(
                &surface,
                &ours_mesh.parameters,
                &ours_mesh.vertices,
                &triangles,
                f64::INFINITY,
            );
            row.worst_over_tolerance = row.worst_over_tolerance.max(ours_deviation / tolerance);
            let (n_occt, n_ours) = (mesh.triangles.len(), triangles.len());
            row.surfaces += 1;
            row.occt_triangles += n_occt;
            row.ours_triangles += n_ours;
            let win = |ours: usize| match ours.cmp(&n_occt) {
                std::cmp::Ordering::Less => 0,
                std::cmp::Ordering::Equal => 1,
                std::cmp::Ordering::Greater => 2,
            };
            match win(n_ours) {
                0 => row.fewer += 1,
                1 => row.equal += 1,
                _ => row.more += 1,
            }
            // At equal measured deviation: the certified mesh's measure is at most the
            // tolerance, which is BRepMesh's deviation (or the floor on a flat surface).
            let (stretched, n_equal, d_equal) = if ours_deviation <= deviation {
                equal_deviation(&surface, deviation, tolerance, (n_ours, ours_deviation))
            } else {
                (tolerance, n_ours, ours_deviation)
            };
            row.equal_triangles += n_equal;
            row.equal_ratios.push(n_equal as f64 / n_occt.max(1) as f64);
            row.equal_wins[win(n_equal)] += 1;
            row.equal_stretch.push(stretched / tolerance);
            if tolerance == deviation {
                row.equal_worst = row.equal_worst.max(d_equal / deviation);
            } else {
                row.below_floor += 1;
            }
            row.ratios.push(n_ours as f64 / n_occt.max(1) as f64);
        }
    }
    let median = |values: &mut Vec<f64>| {
        values.sort_by(f64::total_cmp);
        values.get(values.len() / 2).copied().unwrap_or(f64::NAN)
    };
    println!("Tolerance = BRepMesh's measured deviation (knotshape's meshes certified at it):");
    println!(
        "| deflection / size | angular deflection | surfaces | BRepMesh triangles | knotshape triangles | ratio (sum) | median ratio per surface | knotshape fewer / equal / more | knotshape measured / tolerance, max | BRepMesh s | knotshape s |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    for ((fraction, angle), row) in rows.iter_mut() {
        println!(
            "| {:e} | {} | {}{} | {} | {} | {:.3} | {:.3} | {} / {} / {} | {:.3} | {:.2} | {:.2} |",
            f64::from_bits(*fraction),
            f64::from_bits(*angle),
            row.surfaces,
            if row.refused > 0 {
                format!(" ({} refused)", row.refused)
            } else {
                String::new()
            },
            row.occt_triangles,
            row.ours_triangles,
            row.ours_triangles as f64 / row.occt_triangles.max(1) as f64,
            median(&mut row.ratios),
            row.fewer,
            row.equal,
            row.more,
            row.worst_over_tolerance,
            row.occt_seconds,
            row.ours_seconds,
        );
    }
    println!();
    println!(
        "Equal measured deviation (the largest tolerance found whose mesh measures at most BRepMesh's deviation; certified at that tolerance only):"
    );
    println!(
        "| deflection / size | angular deflection | surfaces | BRepMesh triangles | knotshape triangles | ratio (sum) | median ratio per surface | knotshape fewer / equal / more | knotshape tolerance / BRepMesh deviation, median | knotshape measured / BRepMesh measured, max | BRepMesh deviation below 1e-8 of the magnitude (flat) |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    for ((fraction, angle), row) in rows.iter_mut() {
        println!(
            "| {:e} | {} | {} | {} | {} | {:.3} | {:.3} | {} / {} / {} | {:.2} | {:.3} | {} |",
            f64::from_bits(*fraction),
            f64::from_bits(*angle),
            row.surfaces,
            row.occt_triangles,
            row.equal_triangles,
            row.equal_triangles as f64 / row.occt_triangles.max(1) as f64,
            median(&mut row.equal_ratios),
            row.equal_wins[0],
            row.equal_wins[1],
            row.equal_wins[2],
            median(&mut row.equal_stretch),
            row.equal_worst,
            row.below_floor,
        );
    }
}

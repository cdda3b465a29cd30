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
/// sample points of its triangles, `L` interpolating the mesh's points linearly.
fn measured(
    surface: &Surface,
    uv: &[[f64; 2]],
    points: &[[f64; 3]],
    triangles: &[[usize; 3]],
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
    }
    worst
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
            let deviation = measured(&surface, &mesh.uv, &mesh.points, &mesh.triangles);
            // A flat surface meshes exactly: the tolerance is then the smallest it allows.
            let tolerance = deviation.max(1e-8 * surface.coordinate_magnitude());
            let started = Instant::now();
            let Ok(ours) = surface.tessellate(tolerance, MAX_TRIANGLES) else {
                row.refused += 1;
                continue;
            };
            row.ours_seconds += started.elapsed().as_secs_f64();
            row.occt_seconds += mesh.seconds;
            let ours_points: Vec<[f64; 3]> = ours.vertices.clone();
            let ours_uv = ours.parameters.clone();
            let triangles: Vec<[usize; 3]> = ours
                .triangles
                .iter()
                .map(|t| t.map(|k| k as usize))
                .collect();
            let ours_deviation = measured(&surface, &ours_uv, &ours_points, &triangles);
            row.worst_over_tolerance = row.worst_over_tolerance.max(ours_deviation / tolerance);
            let (n_occt, n_ours) = (mesh.triangles.len(), ours.triangles.len());
            row.surfaces += 1;
            row.occt_triangles += n_occt;
            row.ours_triangles += n_ours;
            match n_ours.cmp(&n_occt) {
                std::cmp::Ordering::Less => row.fewer += 1,
                std::cmp::Ordering::Equal => row.equal += 1,
                std::cmp::Ordering::Greater => row.more += 1,
            }
            row.ratios.push(n_ours as f64 / n_occt.max(1) as f64);
        }
    }
    println!(
        "| deflection / size | angular deflection | surfaces | BRepMesh triangles | knotshape triangles | ratio (sum) | median ratio per surface | knotshape fewer / equal / more | knotshape measured / tolerance, max | BRepMesh s | knotshape s |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    for ((fraction, angle), mut row) in rows {
        row.ratios.sort_by(f64::total_cmp);
        let median = row
            .ratios
            .get(row.ratios.len() / 2)
            .copied()
            .unwrap_or(f64::NAN);
        println!(
            "| {:e} | {} | {}{} | {} | {} | {:.3} | {:.3} | {} / {} / {} | {:.3} | {:.2} | {:.2} |",
            f64::from_bits(fraction),
            f64::from_bits(angle),
            row.surfaces,
            if row.refused > 0 {
                format!(" ({} refused)", row.refused)
            } else {
                String::new()
            },
            row.occt_triangles,
            row.ours_triangles,
            row.ours_triangles as f64 / row.occt_triangles.max(1) as f64,
            median,
            row.fewer,
            row.equal,
            row.more,
            row.worst_over_tolerance,
            row.occt_seconds,
            row.ours_seconds,
        );
    }
}

//! knotshape's side of `bash benches/occt_surface_closest.sh`: the closest point on every
//! surface of the real-surface corpus (tests/data/real_surfaces.json.gz) for seeded queries,
//! timed per query. Writes the queries and the answers (`u`, `v`, distance) as JSON, for
//! benches/occt_surface_closest.py to time Open CASCADE's `GeomAPI_ProjectPointOnSurf` on the
//! same queries and compare the distances.
//!
//! Queries per surface: points of the surface moved by `0`, `1e-6`, `1e-3`, `0.05`, `0.3` and
//! `2` times the surface's size in random directions (so on it, near it, and far from it),
//! at seeded random parameters.
//!
//! Usage: `cargo bench --bench surface_closest -- OUT_JSON [QUERIES_PER_SURFACE]`.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::io::Read;
use std::time::Instant;

use knotshape::spline::KnotForm;
use knotshape::surface::{Surface, SurfaceClosestSearch, SurfaceLimits};
use serde::Deserialize;
use serde_json::json;

/// Offsets of the queries from the surface, in its size.
const OFFSETS: [f64; 6] = [0.0, 1e-6, 1e-3, 0.05, 0.3, 2.0];

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

/// SplitMix64: a tiny seeded generator.
struct SplitMix64(u64);

impl SplitMix64 {
    fn unit(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn main() {
    let mut args = std::env::args().skip(1).filter(|a| !a.starts_with("--"));
    let out = args
        .next()
        .expect("usage: surface_closest OUT_JSON [QUERIES_PER_SURFACE]");
    let per_surface: usize = args.next().map_or(24, |n| n.parse().expect("a count"));
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/real_surfaces.json.gz");
    let mut text = String::new();
    flate2::read::GzDecoder::new(std::fs::File::open(path).unwrap())
        .read_to_string(&mut text)
        .unwrap();
    let file: File = serde_json::from_str(&text).unwrap();
    let mut rng = SplitMix64(0x0cc7_c105);
    let mut rows = Vec::new();
    let (mut total_queries, mut total_seconds, mut total_setup) = (0usize, 0.0f64, 0.0f64);
    let mut by_offset = [0.0f64; OFFSETS.len()];
    let mut count_by_offset = [0usize; OFFSETS.len()];
    for data in &file.surfaces {
        let surface = Surface::from_knot_forms(
            (data.degree_u, data.degree_v),
            &data.poles,
            (KnotForm::Flat(&data.knots_u), KnotForm::Flat(&data.knots_v)),
            data.weights.as_deref(),
            &SurfaceLimits::default(),
        )
        .unwrap();
        let [(u0, u1), (v0, v1)] = surface.domain();
        let size = surface.size();
        let queries: Vec<[f64; 3]> = (0..per_surface)
            .map(|k| {
                let p = surface.point(u0 + (u1 - u0) * rng.unit(), v0 + (v1 - v0) * rng.unit());
                let direction: [f64; 3] = std::array::from_fn(|_| 2.0 * rng.unit() - 1.0);
                let length = direction
                    .iter()
                    .map(|x| x * x)
                    .sum::<f64>()
                    .sqrt()
                    .max(1e-300);
                let offset = OFFSETS[k % OFFSETS.len()] * size;
                std::array::from_fn(|c| p[c] + offset * direction[c] / length)
            })
            .collect();
        let started = Instant::now();
        let search = SurfaceClosestSearch::new(&surface, None).unwrap();
        let setup = started.elapsed().as_secs_f64();
        let started = Instant::now();
        let mut found = Vec::with_capacity(queries.len());
        for (k, &q) in queries.iter().enumerate() {
            let one = Instant::now();
            found.push(search.closest(q));
            by_offset[k % OFFSETS.len()] += one.elapsed().as_secs_f64();
            count_by_offset[k % OFFSETS.len()] += 1;
        }
        let seconds = started.elapsed().as_secs_f64();
        total_queries += queries.len();
        total_seconds += seconds;
        total_setup += setup;
        rows.push(json!({
            "id": data.id,
            "queries": queries,
            "answers": found.iter().map(|f| [f.u, f.v, f.distance]).collect::<Vec<_>>(),
            "seconds": seconds,
            "setup_seconds": setup,
        }));
    }
    eprintln!(
        "knotshape: {} surfaces, {total_queries} queries: {:.2} µs per query (setup {:.1} µs per surface)",
        file.surfaces.len(),
        total_seconds / total_queries as f64 * 1e6,
        total_setup / file.surfaces.len() as f64 * 1e6
    );
    for ((offset, seconds), count) in OFFSETS.iter().zip(by_offset).zip(count_by_offset) {
        eprintln!(
            "  queries {offset} × size off the surface: {:.2} µs per query",
            seconds / count.max(1) as f64 * 1e6
        );
    }
    std::fs::write(
        &out,
        serde_json::to_string(&json!({"surfaces": rows})).unwrap(),
    )
    .unwrap();
}

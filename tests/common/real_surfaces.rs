//! The real-surface corpus (tests/data/real_surfaces.json.gz, provenance in
//! tests/data/real_curves.md) as plain data: B-spline surfaces read with Open CASCADE from
//! public CAD models, with its reference values. One loader for every test crate that reads
//! the corpus (each includes this file with `#[path]`).
#![allow(dead_code)]

use std::io::Read;

use serde::Deserialize;

/// The corpus file, relative to the package root.
pub const CORPUS: &str = "tests/data/real_surfaces.json.gz";

/// Open CASCADE's point and first partials at one parameter pair.
#[derive(Debug, Clone, Deserialize)]
pub struct Reference {
    /// `corner`, `centre`, `random` or `knot_left`.
    pub at: String,
    pub u: f64,
    pub v: f64,
    pub point: [f64; 3],
    pub du: [f64; 3],
    pub dv: [f64; 3],
}

/// Open CASCADE's own form of a surface.
#[derive(Debug, Clone, Deserialize)]
pub struct OcctForm {
    pub knots_u: Vec<f64>,
    pub mults_u: Vec<usize>,
    pub knots_v: Vec<f64>,
    pub mults_v: Vec<usize>,
    pub periodic_u: bool,
    pub periodic_v: bool,
    pub n_u: usize,
    pub n_v: usize,
}

/// A surface as data: full knot vectors, `poles[i][j]`, optional weights (the corpus's form,
/// and that of the random surfaces).
#[derive(Debug, Clone, Deserialize)]
pub struct SurfaceData {
    #[serde(default)]
    pub id: String,
    pub degree_u: usize,
    pub degree_v: usize,
    pub poles: Vec<Vec<[f64; 3]>>,
    #[serde(default)]
    pub weights: Option<Vec<Vec<f64>>>,
    pub knots_u: Vec<f64>,
    pub knots_v: Vec<f64>,
    #[serde(default)]
    pub occt: Option<OcctForm>,
    #[serde(default)]
    pub reference: Vec<Reference>,
}

#[derive(Deserialize)]
struct File {
    surfaces: Vec<SurfaceData>,
}

/// Every surface of the corpus.
pub fn load() -> Vec<SurfaceData> {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(CORPUS);
    let file = std::fs::File::open(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut text = String::new();
    flate2::read::GzDecoder::new(file)
        .read_to_string(&mut text)
        .unwrap();
    let file: File = serde_json::from_str(&text).unwrap();
    file.surfaces
}

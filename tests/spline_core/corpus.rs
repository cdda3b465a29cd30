//! The real-curve corpus (tests/data/real_curves.json.gz, provenance in
//! tests/data/real_curves.md): B-spline curves read with Open CASCADE from public CAD models,
//! and the parameters where evaluation is hardest on them.

use std::io::Read;

use knotshape::spline::{Curve, CurveLimits};
use serde::Deserialize;

use super::exact::Input;

/// The corpus file, relative to the package root.
pub const CORPUS: &str = "tests/data/real_curves.json.gz";

/// One curve of the corpus, as stored.
#[derive(Debug, Clone, Deserialize)]
pub struct RealCurve {
    /// `index:file:kind:element` of the source model.
    pub id: String,
    pub degree: usize,
    pub poles: Vec<Vec<f64>>,
    #[serde(default)]
    pub weights: Option<Vec<f64>>,
    /// The full knot vector (periodic curves unwrapped).
    pub knots: Vec<f64>,
    /// The edge's parameter range (the domain for iso-curves).
    pub range: [f64; 2],
    /// Whether Open CASCADE stores it as periodic (here in its unwrapped form).
    #[serde(default)]
    pub periodic: bool,
}

#[derive(Deserialize)]
struct File {
    curves: Vec<RealCurve>,
}

/// Every curve of the corpus.
pub fn load() -> Vec<RealCurve> {
    let path = std::env::var("KNOTSHAPE_CORPUS")
        .map(std::path::PathBuf::from)
        .unwrap_or_else(|_| std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(CORPUS));
    let file = std::fs::File::open(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut text = String::new();
    flate2::read::GzDecoder::new(file)
        .read_to_string(&mut text)
        .unwrap();
    let file: File = serde_json::from_str(&text).unwrap();
    file.curves
}

impl RealCurve {
    /// The validated curve (every corpus curve is valid).
    pub fn curve(&self) -> Curve {
        Curve::new(
            self.degree,
            &self.poles,
            &self.knots,
            self.weights.as_deref(),
            &CurveLimits::default(),
        )
        .unwrap_or_else(|e| panic!("{}: rejected: {e}", self.id))
    }

    /// The curve for the exact evaluator.
    pub fn input(&self) -> Input {
        Input {
            degree: self.degree,
            knots: self.knots.clone(),
            points: self
                .poles
                .iter()
                .map(|d| [d[0], d[1], d.get(2).copied().unwrap_or(0.0)])
                .collect(),
            weights: self.weights.clone(),
        }
    }

    /// The domain `[u_p, u_{n+1}]`.
    pub fn domain(&self) -> (f64, f64) {
        (self.knots[self.degree], self.knots[self.poles.len()])
    }

    /// Where evaluation is hardest, at most `budget` of them (the ends and the knots of the
    /// shortest spans come first): both ends of the domain and of the edge's range, the points
    /// `1e-8` of the domain inside its ends, every distinct interior knot with the doubles just
    /// left and right of it, the middle of every span, and seeded random parameters.
    pub fn hard_parameters(&self, budget: usize, seed: u64) -> Vec<f64> {
        let (lo, hi) = self.domain();
        let width = hi - lo;
        let mut out = vec![lo, hi, lo + 1e-8 * width, hi - 1e-8 * width];
        for end in self.range {
            if lo <= end && end <= hi {
                out.push(end);
            }
        }
        // Spans inside the domain, shortest first.
        let p = self.degree;
        let n = self.poles.len() - 1;
        let mut spans: Vec<(f64, f64)> = (p..=n)
            .map(|m| (self.knots[m], self.knots[m + 1]))
            .filter(|(a, b)| a < b)
            .collect();
        spans.sort_by(|x, y| (x.1 - x.0).total_cmp(&(y.1 - y.0)));
        for &(a, b) in &spans {
            for t in [
                a,
                next_up(a),
                next_down(b),
                b,
                a + 0.5 * (b - a),
                a + 0.999 * (b - a),
            ] {
                if lo <= t && t <= hi {
                    out.push(t);
                }
            }
        }
        let mut state = seed;
        for _ in 0..4 {
            state = split_mix(state);
            let f = (state >> 11) as f64 / (1u64 << 53) as f64;
            out.push(lo + f * width);
        }
        let mut seen = std::collections::HashSet::new();
        out.retain(|t| seen.insert(t.to_bits()));
        out.truncate(budget);
        out
    }
}

/// The double just above `x`.
pub fn next_up(x: f64) -> f64 {
    if x == 0.0 {
        f64::from_bits(1)
    } else if x > 0.0 {
        f64::from_bits(x.to_bits() + 1)
    } else {
        f64::from_bits(x.to_bits() - 1)
    }
}

/// The double just below `x`.
pub fn next_down(x: f64) -> f64 {
    -next_up(-x)
}

/// One step of SplitMix64.
pub fn split_mix(state: u64) -> u64 {
    let mut z = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

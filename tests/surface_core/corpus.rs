//! The real-surface corpus (tests/data/real_surfaces.json.gz, provenance in
//! tests/data/real_curves.md): B-spline surfaces read with Open CASCADE from public CAD models,
//! and random surfaces in the same form.

use knotshape::spline::KnotForm;
use knotshape::surface::{Surface, SurfaceLimits};

use crate::exact::basis_f64;

pub use crate::real_surfaces::{OcctForm, SurfaceData, load};

/// The corpus, read once per test binary.
pub fn surfaces() -> &'static [SurfaceData] {
    static SURFACES: std::sync::OnceLock<Vec<SurfaceData>> = std::sync::OnceLock::new();
    SURFACES.get_or_init(load)
}

impl SurfaceData {
    pub fn n_u(&self) -> usize {
        self.poles.len()
    }

    pub fn n_v(&self) -> usize {
        self.poles[0].len()
    }

    pub fn weight(&self, i: usize, j: usize) -> f64 {
        self.weights.as_ref().map_or(1.0, |w| w[i][j])
    }

    /// The domain `[[u_lo, u_hi], [v_lo, v_hi]]`.
    pub fn domain(&self) -> [(f64, f64); 2] {
        [
            (self.knots_u[self.degree_u], self.knots_u[self.n_u()]),
            (self.knots_v[self.degree_v], self.knots_v[self.n_v()]),
        ]
    }

    /// The validated surface (flat full knots).
    pub fn surface(&self) -> Surface {
        Surface::from_knot_forms(
            (self.degree_u, self.degree_v),
            &self.poles,
            (KnotForm::Flat(&self.knots_u), KnotForm::Flat(&self.knots_v)),
            self.weights.as_deref(),
            &SurfaceLimits::default(),
        )
        .unwrap_or_else(|e| panic!("{}: rejected: {e}", self.id))
    }

    /// The surface in Open CASCADE's form (distinct knots and multiplicities, periodic where
    /// it is), poles not repeated.
    pub fn occt_surface(&self) -> Option<Surface> {
        let occt = self.occt.as_ref()?;
        let poles: Vec<Vec<[f64; 3]>> = self.poles[..occt.n_u]
            .iter()
            .map(|row| row[..occt.n_v].to_vec())
            .collect();
        let weights: Option<Vec<Vec<f64>>> = self.weights.as_ref().map(|w| {
            w[..occt.n_u]
                .iter()
                .map(|row| row[..occt.n_v].to_vec())
                .collect()
        });
        let form = |knots: &'static [f64], mults: &'static [usize], periodic: bool| {
            if periodic {
                KnotForm::Periodic {
                    knots,
                    multiplicities: mults,
                }
            } else {
                KnotForm::Multiplicities {
                    knots,
                    multiplicities: mults,
                }
            }
        };
        // The corpus lives for the whole run (static), so its slices do too.
        let occt: &'static OcctForm = Box::leak(Box::new(occt.clone()));
        Some(
            Surface::from_knot_forms(
                (self.degree_u, self.degree_v),
                &poles,
                (
                    form(&occt.knots_u, &occt.mults_u, occt.periodic_u),
                    form(&occt.knots_v, &occt.mults_v, occt.periodic_v),
                ),
                weights.as_deref(),
                &SurfaceLimits::default(),
            )
            .unwrap_or_else(|e| panic!("{}: Open CASCADE's form rejected: {e}", self.id)),
        )
    }

    /// The diagonal of the control points' bounding box.
    pub fn size(&self) -> f64 {
        let mut min = [f64::INFINITY; 3];
        let mut max = [f64::NEG_INFINITY; 3];
        for d in self.poles.iter().flatten() {
            for c in 0..3 {
                min[c] = min[c].min(d[c]);
                max[c] = max[c].max(d[c]);
            }
        }
        (0..3)
            .map(|c| (max[c] - min[c]).powi(2))
            .sum::<f64>()
            .sqrt()
    }

    /// `S(u, v)` by the textbook tensor product in `f64` (Cox–de Boor bases, homogeneous
    /// sums): an independent evaluation, good to rounding of the coordinates' magnitude.
    pub fn point_f64(&self, u: f64, v: f64) -> [f64; 3] {
        let nu = basis_f64(&self.knots_u, self.degree_u, self.n_u(), u);
        let nv = basis_f64(&self.knots_v, self.degree_v, self.n_v(), v);
        let mut sum = [0.0; 4];
        for &(i, n) in &nu {
            for &(j, m) in &nv {
                let w = self.weight(i, j);
                let d = self.poles[i][j];
                for c in 0..3 {
                    sum[c] += n * m * w * d[c];
                }
                sum[3] += n * m * w;
            }
        }
        [sum[0] / sum[3], sum[1] / sum[3], sum[2] / sum[3]]
    }

    /// The distinct interior knots of one direction's domain.
    pub fn interior_knots(&self, u_direction: bool) -> Vec<f64> {
        let (knots, (lo, hi)) = if u_direction {
            (&self.knots_u, self.domain()[0])
        } else {
            (&self.knots_v, self.domain()[1])
        };
        let mut values: Vec<f64> = knots
            .iter()
            .copied()
            .filter(|&t| lo < t && t < hi)
            .collect();
        values.dedup();
        values
    }

    /// The shortest non-empty knot span of either direction's domain, relative to its domain.
    pub fn shortest_relative_span(&self) -> f64 {
        let shortest = |knots: &[f64], p: usize, n: usize| {
            let width = knots[n] - knots[p];
            (p..n)
                .map(|m| knots[m + 1] - knots[m])
                .filter(|&h| h > 0.0)
                .fold(f64::INFINITY, f64::min)
                / width
        };
        shortest(&self.knots_u, self.degree_u, self.n_u()).min(shortest(
            &self.knots_v,
            self.degree_v,
            self.n_v(),
        ))
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

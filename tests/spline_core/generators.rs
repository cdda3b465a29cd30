//! Random curves for the property tests: degree, 2D/3D, rational or not, clamped or not, knots
//! with repeated values, given to `Curve::new` in the full or the trimmed (openNURBS) convention.

use knotshape::spline::{Curve, CurveLimits};
use proptest::collection::vec;
use proptest::prelude::*;

use super::reference::{P3, Reference};

/// One random curve: the raw data given to `Curve::new`, and the same curve for the reference.
#[derive(Debug, Clone)]
pub struct CurveCase {
    pub degree: usize,
    pub control_points: Vec<Vec<f64>>,
    pub weights: Option<Vec<f64>>,
    /// The knots as given to `Curve::new` (full or trimmed).
    pub knots: Vec<f64>,
    pub trimmed: bool,
    pub clamped: bool,
    /// The reference's full knot vector. In the trimmed convention its two end values are
    /// arbitrary (`u_0 <= u_1`, `u_{n+p+1} >= u_{n+p}`): they do not influence the curve.
    pub reference: Reference,
}

impl CurveCase {
    /// The validated curve; the generated data are valid by construction.
    pub fn curve(&self) -> Curve {
        Curve::new(
            self.degree,
            &self.control_points,
            &self.knots,
            self.weights.as_deref(),
            &CurveLimits::default(),
        )
        .unwrap_or_else(|e| panic!("generated curve rejected: {e} ({self:?})"))
    }

    /// Parameters worth checking: both domain ends, every distinct knot value in the domain,
    /// and `lo + f (hi - lo)` for each fraction `f`, in the given (unsorted) order.
    pub fn parameters(&self, fractions: &[f64]) -> Vec<f64> {
        let (lo, hi) = self.reference.domain();
        let mut parameters: Vec<f64> = fractions.iter().map(|f| lo + f * (hi - lo)).collect();
        parameters.push(hi);
        let mut knots: Vec<f64> = self
            .reference
            .knots
            .iter()
            .copied()
            .filter(|&u| lo <= u && u <= hi)
            .collect();
        knots.dedup();
        // Interleave knots among the random values so the batch sees jumps both ways.
        for (i, u) in knots.into_iter().enumerate() {
            let at = (i * 7) % (parameters.len() + 1);
            parameters.insert(at, u);
        }
        parameters.insert(parameters.len() / 2, lo);
        parameters
    }
}

/// Knot gap for generating knot vectors: usually positive, sometimes 0 (a repeated knot).
fn gap() -> impl Strategy<Value = f64> {
    prop_oneof![4 => 0.05..1.0f64, 1 => Just(0.0)]
}

/// Turns gaps into knots starting at 0, lengthening any gap that would make a run of equal
/// values longer than `max_run`.
fn knots_from_gaps(gaps: &[f64], max_run: usize) -> Vec<f64> {
    let mut knots = vec![0.0];
    let mut run = 1;
    for &g in gaps {
        let g = if g == 0.0 && run >= max_run { 0.5 } else { g };
        run = if g == 0.0 { run + 1 } else { 1 };
        knots.push(knots[knots.len() - 1] + g);
    }
    knots
}

/// The full knot vector (`count + p + 1` values) of a random curve of degree `p`.
///
/// Clamped: `p + 1` equal values at each end, interior runs of at most `p + 1`. Unclamped: runs
/// of at most `p + 1` anywhere, and a non-empty domain `u_p < u_{n+1}`.
fn full_knots(
    p: usize,
    count: usize,
    clamped: bool,
    gaps: &[f64],
    start: f64,
    scale: f64,
) -> Vec<f64> {
    let knots = if clamped {
        // gaps: the n - p + 1 gaps between the end values and the n - p interior knots.
        let mut inner = gaps.to_vec();
        let last = inner.len() - 1;
        for end in [0, last] {
            if inner[end] == 0.0 {
                inner[end] = 0.5;
            }
        }
        let interior = knots_from_gaps(&inner, p + 1);
        let (a, b) = (interior[0], interior[interior.len() - 1]);
        let mut knots = vec![a; p];
        knots.extend_from_slice(&interior);
        knots.extend(std::iter::repeat_n(b, p));
        knots
    } else {
        let mut gaps = gaps.to_vec();
        let n = count - 1;
        if gaps[p..=n].iter().all(|&g| g == 0.0) {
            gaps[p] = 0.5;
        }
        knots_from_gaps(&gaps, p + 1)
    };
    assert_eq!(knots.len(), count + p + 1);
    knots.into_iter().map(|u| start + scale * u).collect()
}

/// Raw parts of a random curve, before assembly.
type Parts = (
    (usize, bool, bool, bool),
    Vec<Vec<f64>>,
    Vec<f64>,
    Vec<f64>,
    f64,
    f64,
    (f64, f64),
);

/// Assembles a [`CurveCase`] from its random parts.
fn assemble(parts: Parts) -> CurveCase {
    let ((degree, rational, clamped, trimmed), control_points, weights, gaps, start, scale, ends) =
        parts;
    let count = control_points.len();
    let full = full_knots(degree, count, clamped, &gaps, start, scale);
    let (knots, mut reference_knots) = if trimmed {
        (full[1..full.len() - 1].to_vec(), full.clone())
    } else {
        (full.clone(), full)
    };
    if trimmed {
        // The end values the trimmed convention leaves out are free: give the reference others.
        let last = reference_knots.len() - 1;
        reference_knots[0] -= ends.0 * scale;
        reference_knots[last] += ends.1 * scale;
    }
    let points: Vec<P3> = control_points
        .iter()
        .map(|c| [c[0], c[1], c.get(2).copied().unwrap_or(0.0)])
        .collect();
    let weights = rational.then_some(weights);
    CurveCase {
        degree,
        reference: Reference {
            degree,
            knots: reference_knots,
            points,
            weights: weights.clone(),
        },
        control_points,
        weights,
        knots,
        trimmed,
        clamped,
    }
}

/// Which random curves to draw.
#[derive(Debug, Clone, Copy)]
pub struct CaseOptions {
    pub min_degree: usize,
    pub max_degree: usize,
    /// `Some(c)` forces clamped (`true`) or unclamped knots.
    pub clamped: Option<bool>,
}

impl Default for CaseOptions {
    fn default() -> Self {
        Self {
            min_degree: 1,
            max_degree: 6,
            clamped: None,
        }
    }
}

/// Random curves of degree `min_degree..=max_degree`: 2D or 3D, rational or not, clamped or
/// not, full or trimmed knots; coordinates in `[-10, 10]`, weights in `[0.2, 5]`, knots starting
/// in `[-3, 3]` with gaps scaled by 0.01, 1 or 100.
pub fn curve_case(options: CaseOptions) -> impl Strategy<Value = CurveCase> {
    let clamped = match options.clamped {
        Some(c) => Just(c).boxed(),
        None => any::<bool>().boxed(),
    };
    (
        options.min_degree..=options.max_degree,
        0usize..=8,
        any::<bool>(),
        any::<bool>(),
        clamped,
        any::<bool>(),
    )
        .prop_flat_map(|(p, extra, three_d, rational, clamped, trimmed)| {
            let count = p + 1 + extra;
            let dimension = if three_d { 3 } else { 2 };
            let gap_count = if clamped { count - p } else { count + p };
            (
                Just((p, rational, clamped, trimmed)),
                vec(vec(-10.0..10.0f64, dimension), count),
                vec(0.2..5.0f64, count),
                vec(gap(), gap_count),
                -3.0..3.0f64,
                prop_oneof![Just(0.01), Just(1.0), Just(100.0)],
                (0.0..2.0f64, 0.0..2.0f64),
            )
        })
        .prop_map(assemble)
}

//! Points and derivatives of random curves with adversarial knots, against exact rational
//! arithmetic (tests/spline_core/exact.rs): every degree up to `MAX_DEGREE`, spans of `1e-8`
//! and near-multiple knots (`1e-13` apart), control points far from the origin, and the
//! parameters where rounding hurts most (the doubles just left and right of each knot, the
//! domain's ends and `1e-8` of the domain inside them).

use knotshape::spline::{BatchEvaluator, Curve, CurveLimits, MAX_DEGREE};
use proptest::collection::vec;
use proptest::prelude::*;

use super::config;
use super::corpus::{next_down, next_up};
use super::exact::{Input, Judge};

/// One random curve: its data, as given to `Curve::new` (full knot vector).
#[derive(Debug, Clone)]
struct Case {
    input: Input,
    dimension: usize,
}

impl Case {
    fn curve(&self) -> Curve {
        let points: Vec<Vec<f64>> = self
            .input
            .points
            .iter()
            .map(|d| d[..self.dimension].to_vec())
            .collect();
        Curve::new(
            self.input.degree,
            &points,
            &self.input.knots,
            self.input.weights.as_deref(),
            &CurveLimits::default(),
        )
        .unwrap_or_else(|e| panic!("generated curve rejected: {e} ({self:?})"))
    }
}

/// A knot gap: mostly ordinary, sometimes `1e-8` (a short span), `1e-13` (a near-multiple
/// knot) or zero (a repeated knot).
fn gap() -> impl Strategy<Value = f64> {
    prop_oneof![
        6 => 0.05..1.0f64,
        2 => Just(1e-8),
        1 => 1e-13..3e-13f64,
        2 => Just(0.0),
    ]
}

/// Random adversarial curves (module docs): degree `1..=MAX_DEGREE`, `p + 1` to `p + 6`
/// control points in 2D or 3D, `extent` times `[-1, 1]` moved by `offset` (up to `1e6`), with
/// weights in `[0.2, 5]` or none, clamped or not.
fn case() -> impl Strategy<Value = Case> {
    (
        1..=MAX_DEGREE,
        0usize..=5,
        any::<bool>(),
        any::<bool>(),
        any::<bool>(),
        prop_oneof![Just(0.0), Just(1e3), Just(1e6)],
        prop_oneof![Just(1e-3), Just(1.0), Just(100.0)],
    )
        .prop_flat_map(|(p, extra, three_d, rational, clamped, offset, extent)| {
            let count = p + 1 + extra;
            let dimension = if three_d { 3 } else { 2 };
            (
                Just((p, rational, clamped, offset, extent, dimension)),
                vec(vec(-1.0..1.0f64, dimension), count),
                vec(0.2..5.0f64, count),
                vec(gap(), count + p),
                -10.0..10.0f64,
            )
        })
        .prop_map(
            |(
                (p, rational, clamped, offset, extent, dimension),
                points,
                weights,
                mut gaps,
                start,
            )| {
                let count = points.len();
                let len = gaps.len();
                if clamped {
                    gaps[..p].iter_mut().for_each(|g| *g = 0.0);
                }
                // Runs of at most p zero gaps (p + 1 equal knots); a clamped end is such a run.
                let mut run = 0;
                for g in gaps.iter_mut() {
                    if *g == 0.0 {
                        run += 1;
                        if run > p {
                            *g = 0.5;
                            run = 0;
                        }
                    } else {
                        run = 0;
                    }
                }
                if clamped {
                    gaps[len - p..].iter_mut().for_each(|g| *g = 0.0);
                    if gaps[len - p - 1] == 0.0 {
                        gaps[len - p - 1] = 0.5;
                    }
                }
                // A non-empty domain: the gaps between u_p and u_{n+1}.
                if gaps[p..count].iter().all(|&g| g == 0.0) {
                    gaps[p] = 0.5;
                }
                let mut knots = vec![start];
                for g in &gaps {
                    knots.push(knots[knots.len() - 1] + g);
                }
                let points = points
                    .iter()
                    .map(|d| {
                        let mut point = [0.0; 3];
                        for (c, value) in d.iter().enumerate() {
                            point[c] = offset + extent * value;
                        }
                        point
                    })
                    .collect();
                Case {
                    input: Input {
                        degree: p,
                        knots,
                        points,
                        weights: rational.then_some(weights),
                    },
                    dimension,
                }
            },
        )
}

/// The parameters where rounding hurts most (module docs), and `lo + f (hi - lo)` for each
/// fraction `f`.
fn hard_parameters(input: &Input, fractions: &[f64]) -> Vec<f64> {
    let (lo, hi) = input.domain();
    let width = hi - lo;
    let mut out = vec![lo, hi, lo + 1e-8 * width, hi - 1e-8 * width];
    for &u in &input.knots {
        for t in [u, next_down(u), next_up(u)] {
            if lo <= t && t <= hi {
                out.push(t);
            }
        }
    }
    out.extend(fractions.iter().map(|f| lo + f * width));
    out.sort_by(f64::total_cmp);
    out.dedup();
    out
}

proptest! {
    #![proptest_config(config())]

    /// `Curve::point`, `Curve::derivatives`, `BatchEvaluator::points_into` and
    /// `derivatives_into` (points, first and second derivatives) are within the rule of
    /// tests/spline_core/exact.rs at every hard parameter.
    #[test]
    fn points_and_derivatives_are_as_exact_as_de_boor(case in case(), fractions in vec(0.0..=1.0f64, 0..4)) {
        let curve = case.curve();
        let judge = Judge::new(&case.input);
        let parameters = hard_parameters(&case.input, &fractions);
        let evaluator = BatchEvaluator::new(&curve);
        let n = parameters.len();
        let mut points = vec![[f64::NAN; 3]; n];
        evaluator.points_into(&parameters, &mut points).unwrap();
        let mut batch = vec![[f64::NAN; 3]; 3 * n];
        evaluator.derivatives_into(&parameters, 2, &mut batch).unwrap();
        for (i, &t) in parameters.iter().enumerate() {
            let exact = judge.at(t, 2);
            let mut single = [[f64::NAN; 3]; 3];
            curve.derivatives(t, &mut single).unwrap();
            let checks = [
                ("Curve::point", 0, curve.point(t).unwrap()),
                ("points_into", 0, points[i]),
                ("Curve::derivatives", 0, single[0]),
                ("Curve::derivatives", 1, single[1]),
                ("Curve::derivatives", 2, single[2]),
                ("derivatives_into", 0, batch[i]),
                ("derivatives_into", 1, batch[n + i]),
                ("derivatives_into", 2, batch[2 * n + i]),
            ];
            for (path, k, value) in checks {
                let verdict = exact.judge(k, value);
                prop_assert!(
                    verdict.passes(),
                    "{} order {} at {:e}: {:?} vs exact {:?}: error {:e} > allowed {:e} (textbook {:e})",
                    path, k, t, value, exact.value(k), verdict.error, verdict.allowed, verdict.textbook
                );
            }
        }
    }
}

//! A pair's admissible knots as the image of the unit square (docs/method.md §32), so that
//! regions and nearest points can walk it: a rectangle for two knots with a fixed knot
//! between them, a sheared triangle for two neighbours on one side of `t`, and, for the two
//! ends of `t`'s span, coordinates around their collapse `t_q = t_{q+1} = ũ` (where the point
//! has a limit for each direction of approach, not one value).

use super::local::LocalProblem;
use crate::spline::vector::Point;

/// The admissible knots of one pair.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PairDomain {
    /// `a ∈ [a_lo, a_hi]`, `b ∈ [b_lo, b_hi]` independently.
    Rectangle { a: (f64, f64), b: (f64, f64) },
    /// `lo ≤ a ≤ b ≤ hi`: `b = lo + u (hi - lo)`, `a = lo + v (b - lo)`.
    Triangle { lo: f64, hi: f64 },
    /// The span's ends `a = t_q ∈ [a_lo, ũ]`, `b = t_{q+1} ∈ [ũ, b_hi]`: with
    /// `x = (ũ - a) / (ũ - a_lo)`, `y = (b - ũ) / (b_hi - ũ)` in the unit square,
    /// `r = max(x, y) = u` and `v` running along the square's far edges (`v ≤ 1/2`:
    /// `(x, y) = r (1, 2v)`; `v ≥ 1/2`: `r (2 - 2v, 1)`); `r = 0` is the collapse, where the
    /// last ratio `α_{q,q} = (ũ - a) / (b - a)` keeps its directional limit.
    Span { a_lo: f64, b_hi: f64 },
}

impl PairDomain {
    /// The domain of `unknowns` (local indices, ascending) of `problem`, or `None` when a knot
    /// has no room.
    pub fn new(problem: &LocalProblem, unknowns: [usize; 2]) -> Option<PairDomain> {
        let search = problem.search_box(&unknowns, 0.0, 0.0)?;
        let [(a_lo, a_hi), (b_lo, b_hi)] = [search.admissible[0], search.admissible[1]];
        if a_hi <= a_lo || b_hi <= b_lo {
            return None;
        }
        let q = problem.degree;
        Some(if unknowns == [q, q + 1] {
            PairDomain::Span { a_lo, b_hi }
        } else if unknowns[1] == unknowns[0] + 1 {
            PairDomain::Triangle { lo: a_lo, hi: b_hi }
        } else {
            PairDomain::Rectangle {
                a: (a_lo, a_hi),
                b: (b_lo, b_hi),
            }
        })
    }

    /// The two knots at `(u, v)` of the unit square, and for the span's ends the last ratio
    /// `α_{q,q}` (which stays defined at the collapse).
    pub fn knots_at(&self, parameter: f64, (u, v): (f64, f64)) -> ([f64; 2], Option<f64>) {
        let lerp = |(lo, hi): (f64, f64), s: f64| if s >= 1.0 { hi } else { lo + s * (hi - lo) };
        match *self {
            PairDomain::Rectangle { a, b } => ([lerp(a, u), lerp(b, v)], None),
            PairDomain::Triangle { lo, hi } => {
                let b = lerp((lo, hi), u);
                ([lerp((lo, b), v), b], None)
            }
            PairDomain::Span { a_lo, b_hi } => {
                let (x, y) = if v <= 0.5 {
                    (1.0, 2.0 * v)
                } else {
                    (2.0 - 2.0 * v, 1.0)
                };
                let (da, db) = (x * (parameter - a_lo), y * (b_hi - parameter));
                let a = if u * x >= 1.0 {
                    a_lo
                } else {
                    parameter - u * da
                };
                let b = if u * y >= 1.0 {
                    b_hi
                } else {
                    parameter + u * db
                };
                // α_{q,q} = (ũ - a) / (b - a) = da / (da + db), whatever r is.
                let alpha = if da + db > 0.0 { da / (da + db) } else { 0.5 };
                ([a, b], Some(alpha))
            }
        }
    }
}

/// The point of `problem` with `unknowns` set to the domain's knots at `(u, v)`.
pub fn point_at(
    problem: &LocalProblem,
    unknowns: [usize; 2],
    domain: &PairDomain,
    (u, v): (f64, f64),
) -> Point {
    let (values, alpha) = domain.knots_at(problem.parameter, (u, v));
    let mut knots = problem.knots.clone();
    knots[unknowns[0]] = values[0];
    knots[unknowns[1]] = values[1];
    let q = problem.degree;
    let h = match alpha {
        Some(alpha) => problem.homogeneous_point_with(&knots, &[((q, q), alpha)]),
        None => problem.homogeneous_point(&knots),
    };
    [h[0] / h[3], h[1] / h[3], h[2] / h[3]]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn problem() -> LocalProblem {
        LocalProblem {
            degree: 3,
            knots: vec![-1.75, -1.37, -0.88, 0.0, 0.80, 1.47, 2.00, 2.69],
            full_index: (0..8).collect(),
            poles: vec![
                [0.43, 1.61, 0.0, 1.0],
                [0.72, 0.67, 0.0, 1.0],
                [-0.12, 1.18, 0.0, 1.0],
                [-0.53, -0.91, 0.0, 1.0],
            ],
            parameter: 0.431,
        }
    }

    /// The span domain covers the admissible rectangle and agrees with plain evaluation away
    /// from the collapse; at the collapse the limit is reached continuously.
    #[test]
    fn the_span_domain_walks_the_rectangle_and_keeps_the_limit() {
        let p = problem();
        let domain = PairDomain::new(&p, [3, 4]).unwrap();
        assert!(matches!(domain, PairDomain::Span { .. }));
        for (u, v) in [(0.3, 0.2), (1.0, 0.75), (0.6, 0.5)] {
            let (k, _) = domain.knots_at(p.parameter, (u, v));
            assert!(k[0] >= -0.88 && k[0] <= p.parameter && k[1] >= p.parameter && k[1] <= 1.47);
            let mut knots = p.knots.clone();
            knots[3] = k[0];
            knots[4] = k[1];
            let plain = p.point(&knots);
            let walked = point_at(&p, [3, 4], &domain, (u, v));
            for c in 0..2 {
                assert!((plain[c] - walked[c]).abs() < 1e-13);
            }
        }
        // Approaching r = 0 along a fixed direction converges to the r = 0 value.
        let limit = point_at(&p, [3, 4], &domain, (0.0, 0.3));
        let near = point_at(&p, [3, 4], &domain, (1e-9, 0.3));
        assert!((limit[0] - near[0]).abs() < 1e-7 && (limit[1] - near[1]).abs() < 1e-7);
        // The corners of the unit square reach the rectangle's corners.
        let (k, _) = domain.knots_at(p.parameter, (1.0, 0.5));
        assert_eq!(k, [-0.88, 1.47]);
    }
}

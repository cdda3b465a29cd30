//! The other way to move a curve point: move control points instead of knots, by the least
//! change of the poles that puts `s(t)` on the target.
//!
//! With fixed weights, `s(t) = Σ_i R_i(t) d_i` where `R_i = N_i w_i / Σ_l N_l w_l` (`R_i = N_i`
//! for a polynomial curve). Moving the poles `d_i`, `i ∈ I = { i : R_i(t) > 0 }`, by
//! `Δd_i` moves `s(t)` by `Σ_I R_i Δd_i`. The least `Σ_I |Δd_i|²` with `Σ_I R_i Δd_i = p - s(t)`
//! is (Lagrange multipliers)
//!
//! ```text
//! Δd_i = R_i(t) / Σ_{k∈I} R_k(t)² · (p - s(t))
//! ```
//!
//! Every displacement is parallel to `p - s(t)`, so the new curve differs from the old by
//! `φ(u) (p - s(t))` with `φ(t) = 1`: it reaches every target, whatever the knots. Open
//! CASCADE's `Geom_BSplineCurve::MovePoint` moves poles too, with its own weighting.

use super::deviation::max_deviation_of_moved_poles;
use crate::spline::vector::{Point, distance, sub};
use crate::spline::{Curve, MAX_DEGREE};

/// The new curve's point at `t` must lie within `CONTROL_POINT_RESIDUAL · size` of the target
/// (`size`: the largest coordinate of the moved poles and the target, at least 1), else the
/// move is refused as ill-conditioned (it never is for finite input: a guard).
pub const CONTROL_POINT_RESIDUAL: f64 = 1e-9;

/// The control-point move that puts `s(t)` on a target.
#[derive(Debug, Clone, PartialEq)]
pub struct ControlPointSolution {
    /// The whole new list of control points.
    pub control_points: Vec<Point>,
    /// Indices of the control points that moved, ascending.
    pub changed_control_points: Vec<usize>,
    /// The new curve's point at `t`.
    pub point: Point,
    /// `|point - target|`.
    pub residual: f64,
    /// `[lo, hi]`: outside it the new curve equals the old one.
    pub affected_domain: (f64, f64),
    /// Largest `|s_old(u) - s_new(u)|` over the domain, when measured.
    pub max_deviation: Option<f64>,
}

/// The least-squares pole move (module docs) that puts the point at `t` of `curve` on
/// `target`; the new point is evaluated with the spline core. `None` only when the numbers
/// overflow. Preconditions: `t` in the domain, `target` finite with `z = 0` for planar curves.
pub fn control_point_move(
    curve: &Curve,
    t: f64,
    target: Point,
    measure_deviation: bool,
) -> Option<ControlPointSolution> {
    let p = curve.degree();
    let mut basis = [0.0; MAX_DEGREE + 1];
    let first = curve.basis_at(t, &mut basis);
    // Rational basis R_i = N_i w_i / Σ N_l w_l over the p + 1 functions of the span.
    let weighted: Vec<f64> = (0..=p)
        .map(|r| basis[r] * curve.weight(first + r))
        .collect();
    let total: f64 = weighted.iter().sum();
    let rational_basis: Vec<f64> = weighted.iter().map(|w| w / total).collect();
    let squares: f64 = rational_basis.iter().map(|r| r * r).sum();
    let current = curve.point_unchecked(t);
    let gap = sub(target, current);
    let mut control_points = curve.control_points().to_vec();
    let mut changed_control_points = Vec::with_capacity(p + 1);
    for (r, &value) in rational_basis.iter().enumerate() {
        let factor = value / squares;
        if value <= 0.0 || gap == [0.0; 3] {
            continue;
        }
        let index = first + r;
        for c in 0..3 {
            control_points[index][c] += factor * gap[c];
        }
        changed_control_points.push(index);
    }
    let moved = curve.with_control_points(control_points)?;
    let point = moved.point_unchecked(t);
    let residual = distance(point, target);
    let size = moved
        .control_points()
        .iter()
        .flatten()
        .chain(target.iter())
        .fold(1.0f64, |m, v| m.max(v.abs()));
    if residual.is_nan() || residual > CONTROL_POINT_RESIDUAL * size {
        return None;
    }
    let affected_domain = affected_domain_of_poles(curve, &changed_control_points);
    let max_deviation =
        measure_deviation.then(|| max_deviation_of_moved_poles(curve, &moved, affected_domain));
    Some(ControlPointSolution {
        control_points: moved.control_points().to_vec(),
        changed_control_points,
        point,
        residual,
        affected_domain,
        max_deviation,
    })
}

/// `[lo, hi]` outside which moving the poles `changed` leaves the curve alone: pole `i`
/// acts on `[u_i, u_{i+p+1}]`, clipped to the domain.
fn affected_domain_of_poles(curve: &Curve, changed: &[usize]) -> (f64, f64) {
    let knots = curve.knots();
    let p = curve.degree();
    let (lo, hi) = curve.domain();
    match (changed.first(), changed.last()) {
        (Some(&first), Some(&last)) => (knots[first].max(lo), knots[last + p + 1].min(hi)),
        _ => (lo, lo),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::CurveLimits;

    #[test]
    fn a_move_onto_the_curve_itself_changes_nothing() {
        let points = [[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0], [6.0, 1.0]];
        let knots = [0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0];
        let curve = Curve::new(3, &points, &knots, None, &CurveLimits::default()).unwrap();
        let on_curve = curve.point(0.3).unwrap();
        let solution = control_point_move(&curve, 0.3, on_curve, true).unwrap();
        assert!(solution.changed_control_points.is_empty());
        assert_eq!(solution.max_deviation, Some(0.0));
    }
}

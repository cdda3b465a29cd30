//! Curvature from the first two derivatives: `κ = |s' × s''| / |s'|³`, and for a planar curve
//! the signed `κ = (x' y'' − y' x'') / |s'|³` (positive where the curve turns left, to the
//! counter-clockwise side of its direction of travel).
//!
//! Where `s'` vanishes the tangent is not defined and neither is the curvature (at a cusp it
//! is unbounded, and at an end whose first two control points coincide it is usually
//! infinite too: near `u = 0` the curve is `a u²/2 + b u³/6`, whose curvature grows like
//! `1/u`). Such parameters are reported as undefined rather than as a number.

use super::curve::Curve;
use super::eval::EvalError;
use super::fit_points::bounding_box_diagonal;

/// The tangent counts as vanishing when `|s'|` is at most this fraction of the scale of the
/// first derivative on the span, `p · size / (u_{m+1} − u_m)` (`size` the control points'
/// bounding-box diagonal): rounding in `s'` is about `1e-16` of that scale.
pub const CURVATURE_TANGENT_FLOOR: f64 = 1e-12;

impl Curve {
    /// The curvature at each parameter (module docs): `Some(κ)`, or `None` where the tangent
    /// vanishes. Parameters must be in the domain (snap them first).
    pub fn curvatures(&self, parameters: &[f64]) -> Result<Vec<Option<f64>>, EvalError> {
        let size = bounding_box_diagonal(self.control_points());
        let planar = self.dimension() == super::curve::Dimension::Two;
        let p = self.degree() as f64;
        let knots = self.knots();
        let mut derivatives = [[0.0; 3]; 3];
        parameters
            .iter()
            .enumerate()
            .map(|(index, &t)| {
                self.derivatives(t, &mut derivatives)
                    .map_err(|error| with_index(error, index))?;
                let [_, d1, d2] = derivatives;
                let speed = (d1[0] * d1[0] + d1[1] * d1[1] + d1[2] * d1[2]).sqrt();
                let span = self.span(t);
                let scale = p * size / (knots[span + 1] - knots[span]);
                if speed.is_nan() || speed <= CURVATURE_TANGENT_FLOOR * scale {
                    return Ok(None);
                }
                let cubed = speed * speed * speed;
                let value = if planar {
                    (d1[0] * d2[1] - d1[1] * d2[0]) / cubed
                } else {
                    let cross = [
                        d1[1] * d2[2] - d1[2] * d2[1],
                        d1[2] * d2[0] - d1[0] * d2[2],
                        d1[0] * d2[1] - d1[1] * d2[0],
                    ];
                    (cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]).sqrt() / cubed
                };
                Ok(value.is_finite().then_some(value))
            })
            .collect()
    }
}

/// The error of parameter `index` of a batch.
fn with_index(error: EvalError, index: usize) -> EvalError {
    match error {
        EvalError::NonFiniteParameter { .. } => EvalError::NonFiniteParameter { index },
        EvalError::OutsideDomain { value, domain, .. } => EvalError::OutsideDomain {
            index,
            value,
            domain,
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::CurveLimits;

    #[test]
    fn a_circle_of_radius_two_has_curvature_one_half_signed_by_turning() {
        let w = std::f64::consts::FRAC_1_SQRT_2;
        let counter_clockwise = Curve::new(
            2,
            &[[2.0, 0.0], [2.0, 2.0], [0.0, 2.0]],
            &[0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            Some(&[1.0, w, 1.0]),
            &CurveLimits::default(),
        )
        .unwrap();
        let values = counter_clockwise.curvatures(&[0.0, 0.3, 1.0]).unwrap();
        for value in values {
            assert!((value.unwrap() - 0.5).abs() < 1e-14);
        }
        let clockwise = Curve::new(
            2,
            &[[0.0, 2.0], [2.0, 2.0], [2.0, 0.0]],
            &[0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            Some(&[1.0, w, 1.0]),
            &CurveLimits::default(),
        )
        .unwrap();
        assert!((clockwise.curvatures(&[0.5]).unwrap()[0].unwrap() + 0.5).abs() < 1e-14);
        // A repeated first control point: no tangent at the start.
        let cusp = Curve::new(
            3,
            &[[0.0, 0.0], [0.0, 0.0], [1.0, 1.0], [2.0, 0.0]],
            &[0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
            None,
            &CurveLimits::default(),
        )
        .unwrap();
        assert_eq!(cusp.curvatures(&[0.0]).unwrap(), vec![None]);
    }
}

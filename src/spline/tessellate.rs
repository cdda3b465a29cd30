//! A polyline certified to lie within a tolerance of the curve: the convex-hull flatness bound
//! on Bézier pieces, split by de Casteljau until every piece is flat.
//!
//! A piece lies in the convex hull of its control points (for a rational piece with
//! positive weights, of its projected control points `B_i / w_i`: the curve point is
//! `Σ_i (b_i w_i / Σ_k b_k w_k) (B_i / w_i)`, a convex combination). The distance to the chord
//! from the first to the last control point is a convex function, so when every control point
//! is within `τ` of the chord, so is the whole piece. Conversely every chord point is within
//! `τ` of the piece: the piece's projection onto the chord's line runs continuously from one
//! end to the other, so each chord point is the foot of some curve point at most `τ` away.
//! The polyline of the pieces' ends is therefore within Hausdorff distance `τ` of the curve.
//!
//! A non-rational piece also has a tighter certified bound, taken when smaller: by linear
//! precision the chord's point `L(s) = (1 - s) B_0 + s B_p` is `Σ_i L(i/p) b_i(s)`, so
//! `|C(s) - L(s)| = |Σ_{0<i<p} (B_i - L(i/p)) b_i(s)| <= M (1 - (1 - s)^p - s^p)
//! <= M (1 - 2^(1-p))` with `M = max_i |B_i - L(i/p)|` (for a quadratic, half the hull
//! bound), and `L(s)` lies on the chord.

use super::bezier::BezierPiece;
use super::curve::Curve;
use super::vector::{Point, dot, norm, sub};

/// Smallest tolerance accepted, relative to the largest control-point coordinate magnitude:
/// below it the rounding of the subdivided points (and of the parameters' curve points) is
/// no longer negligible, and double precision cannot certify the bound.
pub const TOLERANCE_FLOOR: f64 = 1e-9;

/// The flatness test compares with `τ` less this margin times the largest coordinate
/// magnitude, which covers the rounding of de Casteljau's splits and of the evaluator
/// (well above `100 ε`, well below [`TOLERANCE_FLOOR`]).
pub const ROUNDING_MARGIN: f64 = 1e-11;

/// Why no certified polyline is given.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TessellationError {
    /// The tolerance is not a number `> 0`, or so small relative to the coordinates that
    /// double precision cannot certify it.
    #[error(
        "tolerance {tolerance} is below the smallest this curve allows, {floor:e} ({TOLERANCE_FLOOR:e} times its largest coordinate magnitude): double precision cannot certify a finer polyline"
    )]
    BelowFloor { tolerance: f64, floor: f64 },
    /// More points than allowed would be needed.
    #[error(
        "tolerance {tolerance} needs more than {max} points on this curve; give a larger tolerance"
    )]
    TooManyPoints { tolerance: f64, max: usize },
    /// The curve jumps at a knot of multiplicity `p + 1`; no polyline follows a jump.
    #[error(
        "the curve jumps at knot value {value} (multiplicity degree + 1); a polyline cannot stay close to it"
    )]
    Discontinuous { value: f64 },
}

impl Curve {
    /// Increasing parameters, both ends of the domain included, whose curve points make a
    /// polyline within `tolerance` of the curve everywhere (see the module's documentation).
    /// Every knot span's ends are among them; a span that is not flat is split in halves of
    /// its parameter interval, recursively, depth first, so the answer is deterministic.
    ///
    /// Bounded work: at most `max_points` parameters are produced (more needed:
    /// [`TessellationError::TooManyPoints`], as soon as the count is exceeded).
    pub fn tessellate(
        &self,
        tolerance: f64,
        max_points: usize,
    ) -> Result<Vec<f64>, TessellationError> {
        let scale = self
            .control_points()
            .iter()
            .flatten()
            .fold(0.0f64, |m, v| m.max(v.abs()));
        let floor = TOLERANCE_FLOOR * scale;
        if !(tolerance > 0.0 && tolerance >= floor) {
            return Err(TessellationError::BelowFloor { tolerance, floor });
        }
        if let Some(&value) = self.jump_knots().first() {
            return Err(TessellationError::Discontinuous { value });
        }
        let flat_within = tolerance - ROUNDING_MARGIN * scale;
        let too_many = || TessellationError::TooManyPoints {
            tolerance,
            max: max_points,
        };
        let mut parameters = vec![self.domain().0];
        let mut stack: Vec<BezierPiece> = Vec::new();
        for piece in self.bezier_pieces() {
            stack.push(piece);
            while let Some(piece) = stack.pop() {
                if is_flat(&piece, flat_within) {
                    if parameters.len() >= max_points {
                        return Err(too_many());
                    }
                    parameters.push(piece.domain.1);
                    continue;
                }
                let (a, b) = piece.domain;
                let middle = a + 0.5 * (b - a);
                if !(a < middle && middle < b) {
                    // The parameters cannot be split further in double precision.
                    return Err(TessellationError::BelowFloor { tolerance, floor });
                }
                let (left, right) = piece.split((middle - a) / (b - a), middle);
                stack.push(right);
                stack.push(left);
            }
        }
        Ok(parameters)
    }
}

/// Whether the piece is within `within` of the chord from its first to its last control
/// point: every control point is (the convex-hull bound), or, for a non-rational piece,
/// `(1 - 2^(1-p)) max_i |B_i - L(i/p)|` is (the linear-precision bound; see the module).
fn is_flat(piece: &BezierPiece, within: f64) -> bool {
    let p = piece.degree();
    let (first, last) = (piece.control_point(0), piece.control_point(p));
    let hull_flat =
        || (1..p).all(|i| distance_to_segment(piece.control_point(i), first, last) <= within);
    if piece.is_rational() || p < 2 {
        return hull_flat();
    }
    let interior_share = 1.0 - 0.5f64.powi(p as i32 - 1);
    let linear_flat = (1..p).all(|i| {
        let s = i as f64 / p as f64;
        let on_chord = std::array::from_fn(|c| (1.0 - s) * first[c] + s * last[c]);
        interior_share * norm(sub(piece.control_point(i), on_chord)) <= within
    });
    linear_flat || hull_flat()
}

/// The distance from `q` to the segment `[a, b]`.
pub fn distance_to_segment(q: Point, a: Point, b: Point) -> f64 {
    let direction = sub(b, a);
    let length_squared = dot(direction, direction);
    let along = if length_squared > 0.0 {
        (dot(sub(q, a), direction) / length_squared).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let foot = std::array::from_fn(|c| a[c] + along * direction[c]);
    norm(sub(q, foot))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::CurveLimits;

    #[test]
    fn a_polyline_curve_needs_only_its_knots() {
        let points = [[0.0, 0.0], [1.0, 5.0], [2.0, 0.0], [3.0, 5.0]];
        let knots = [0.0, 0.0, 1.0, 2.0, 3.0, 3.0];
        let curve = Curve::new(1, &points, &knots, None, &CurveLimits::default()).unwrap();
        assert_eq!(
            curve.tessellate(1e-6, 100).unwrap(),
            vec![0.0, 1.0, 2.0, 3.0]
        );
        assert!(matches!(
            curve.tessellate(1e-6, 3),
            Err(TessellationError::TooManyPoints { .. })
        ));
    }

    #[test]
    fn a_parabola_halves_until_its_sagitta_fits() {
        // y = x² on [0, 1] as a quadratic Bézier (0,0), (1/2, 0), (1, 1): over an interval of
        // width h the middle control point lies h²/2 below the chord, h²/2/√(1 + slope²) away
        // from it, so tolerance 1/64 is met by eighths at the latest and not by halves.
        let points = [[0.0, 0.0], [0.5, 0.0], [1.0, 1.0]];
        let knots = [0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
        let curve = Curve::new(2, &points, &knots, None, &CurveLimits::default()).unwrap();
        let parameters = curve.tessellate(1.0 / 64.0, 100).unwrap();
        assert!(
            parameters.len() > 3 && parameters.len() <= 9,
            "{parameters:?}"
        );
        assert!(parameters.windows(2).all(|w| w[0] < w[1]));
        assert_eq!(
            (parameters[0], parameters[parameters.len() - 1]),
            (0.0, 1.0)
        );
    }

    #[test]
    fn too_fine_a_tolerance_is_refused_at_once() {
        let points = [[1e6, 0.0], [1e6 + 1.0, 2.0], [1e6 + 2.0, 0.0]];
        let knots = [0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
        let curve = Curve::new(2, &points, &knots, None, &CurveLimits::default()).unwrap();
        assert!(matches!(
            curve.tessellate(1e-4, 10),
            Err(TessellationError::BelowFloor { .. })
        ));
        assert!(matches!(
            curve.tessellate(0.0, 10),
            Err(TessellationError::BelowFloor { .. })
        ));
        assert!(matches!(
            curve.tessellate(f64::NAN, 10),
            Err(TessellationError::BelowFloor { .. })
        ));
        assert!(curve.tessellate(1e-2, 1000).is_ok());
    }
}

//! A polyline certified to lie within a tolerance of the curve: the convex-hull flatness bound
//! on Bézier pieces, split by de Casteljau until every piece is flat.
//!
//! A piece is a convex combination of its control points (for a rational piece with
//! positive weights, of its projected control points `P_i`): `C(s) = Σ_i λ_i(s) P_i` with
//! `λ_i = w_i b_i(s) / Σ_k w_k b_k(s)`, `b_i` the Bernstein polynomials of degree `p`. The
//! distance to the chord `[P_0, P_p]` is a convex function that vanishes at both ends, so
//!
//! `dist(C(s), chord) <= Σ_{0<i<p} λ_i(s) d_i <= D · A / (A + E)`,
//!
//! `d_i` the distance of `P_i` to the chord, `D = max_i d_i`, `A = Σ_{0<i<p} w_i b_i <=
//! a (1 - e)` and `E = w_0 b_0 + w_p b_p >= c e` with `e = (1 - s)^p + s^p >= 2^(1-p)`,
//! `a` the largest interior weight and `c` the smaller end weight. The ratio grows with `A`,
//! falls with `E`, and `a (1 - e) / (a (1 - e) + c e)` falls with `e`, so
//!
//! `dist(C(s), chord) <= D · a (1 - 2^(1-p)) / (a (1 - 2^(1-p)) + c 2^(1-p))` (the flatness bound),
//!
//! at most `D` (every control point within `τ` of the chord: the convex-hull bound), and
//! `D (1 - 2^(1-p))` for a non-rational piece (half of `D` for a quadratic). A piece is flat
//! when the bound is at most `τ`; otherwise it is split. Conversely every chord point is
//! within `τ` of a flat piece: the piece's projection onto the chord's line runs
//! continuously from one end to the other, so each chord point is the foot of some curve
//! point at most `τ` away. The polyline of the flat pieces' ends is therefore within
//! Hausdorff distance `τ` of the curve.

use super::bezier::BezierPiece;
use super::curve::Curve;
use super::vector::{Point, dot, norm, sub};

/// Smallest tolerance accepted, relative to the largest control-point coordinate magnitude:
/// below it the rounding of the subdivided points (and of the parameters' curve points) is
/// no longer negligible, and double precision cannot certify the bound.
pub const TOLERANCE_FLOOR: f64 = 1e-9;

/// Most parts a piece that is not flat is split into at once; one farther from flatness is
/// halved instead.
const MAX_PARTS: usize = 16;

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
    /// Every knot span's ends are among them; a piece that is not flat is split (de Casteljau)
    /// into `k = ⌈√(bound / τ)⌉` parts of equal parameter length when `k <= 16` (the bound
    /// shrinks about as the square of the length), else into halves, recursively, depth
    /// first, left to right, so the answer is deterministic.
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
        if tolerance.is_nan() || tolerance <= 0.0 || tolerance < floor {
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
                let bound = flatness_bound(&piece);
                if bound <= flat_within {
                    if parameters.len() >= max_points {
                        return Err(too_many());
                    }
                    parameters.push(piece.domain.1);
                    continue;
                }
                // The bound shrinks about as the square of a part's length: near flatness aim
                // at parts that are flat at once; far from it (or for a NaN bound, from
                // overflow) halve, and look again at each half.
                let wanted = (bound / flat_within).sqrt().ceil();
                let parts = if wanted <= MAX_PARTS as f64 {
                    (wanted as usize).max(2)
                } else {
                    2
                };
                let (a, b) = piece.domain;
                let step = (b - a) / parts as f64;
                let first = stack.len();
                let mut rest = piece;
                for k in 1..parts {
                    let at = a + k as f64 * step;
                    let lo = rest.domain.0;
                    if at <= lo || at >= b {
                        // The parameters cannot be split further in double precision.
                        return Err(TessellationError::BelowFloor { tolerance, floor });
                    }
                    let (left, right) = rest.split((at - lo) / (b - lo), at);
                    stack.push(left);
                    rest = right;
                }
                stack.push(rest);
                // Left to right on the stack's top: reverse the parts just pushed.
                stack[first..].reverse();
            }
        }
        Ok(parameters)
    }
}

/// The flatness bound of `piece` (see the module): the curve is within it of its chord.
fn flatness_bound(piece: &BezierPiece) -> f64 {
    let p = piece.degree();
    if p < 2 {
        return 0.0;
    }
    let (first, last) = (piece.control_point(0), piece.control_point(p));
    let farthest = (1..p)
        .map(|i| distance_to_segment(piece.control_point(i), first, last))
        .fold(0.0f64, f64::max);
    let weights = piece.homogeneous();
    let interior_weight = weights[1..p].iter().fold(0.0f64, |m, h| m.max(h[3]));
    let end_weight = weights[0][3].min(weights[p][3]);
    let ends = 0.5f64.powi(p as i32 - 1);
    let interior = interior_weight * (1.0 - ends);
    let share = interior / (interior + end_weight * ends);
    // `share <= 1`; a NaN (overflowed coordinates) is never flat.
    share * farthest
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

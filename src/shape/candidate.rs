//! Candidates: which knot next to the picked parameter moves, its control triangle, and the
//! target's frame coordinates (docs/method.md §3.1, §3.3, §7, §8).

use crate::spline::Curve;
use crate::spline::vector::{Point, cross, dot, norm, sub};

/// A target farther than `PLANE_TOLERANCE · size` from the plane of a 3D control triangle is
/// off the plane and unreachable (`size` = the triangle's longest edge). Not projected.
pub const PLANE_TOLERANCE: f64 = 1e-9;

/// A control triangle with `|e1 × e2| <= DEGENERACY_TOLERANCE · size²` is degenerate
/// (collinear or coincident points): its frame is undefined.
pub const DEGENERACY_TOLERANCE: f64 = 1e-12;

/// Which knot next to `t` moves to `t`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Side {
    /// `u_{m+1}`, the knot right of `t` (`j = m`).
    Right,
    /// `u_m`, the knot left of (or at) `t` (`j = m - 1`).
    Left,
}

impl Side {
    /// The wire name: `"right"` or `"left"`.
    pub fn name(self) -> &'static str {
        match self {
            Side::Right => "right",
            Side::Left => "left",
        }
    }
}

/// The sides a request asks for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SideChoice {
    /// Only [`Side::Right`].
    Right,
    /// Only [`Side::Left`].
    Left,
    /// Both, right first.
    #[default]
    Both,
}

impl SideChoice {
    /// The sides, in answer order.
    pub fn sides(self) -> &'static [Side] {
        match self {
            SideChoice::Right => &[Side::Right],
            SideChoice::Left => &[Side::Left],
            SideChoice::Both => &[Side::Right, Side::Left],
        }
    }
}

/// The target in the control triangle's frame: the quadratic envelope's basis values
/// `x = N_{j-2}^3(t)`, `y = N_j^3(t)` that put the envelope point on the target.
///
/// Non-rational: `p = d_{j-1} + x (d_{j-2} - d_{j-1}) + y (d_j - d_{j-1})`. Rational (docs/method.md
/// §7): with barycentric `(λ0, λ1, λ2)` of `p`, `S = λ0/w_{j-2} + λ1/w_{j-1} + λ2/w_j`,
/// `x = (λ0/w_{j-2}) / S`, `y = (λ2/w_j) / S`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    /// Weight of `d_{j-2}`.
    pub x: f64,
    /// Weight of `d_j`.
    pub y: f64,
}

/// Why a side cannot move the curve point.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum NotApplicable {
    /// The span `j` leaves the indices `j - 2 ..= j + 4` outside the knot vector (`2 <= j <= n`).
    #[error("span {span} is out of range: the knot pairs need 2 <= j <= n")]
    SpanOutOfRange { span: usize },
    /// The three control points are (nearly) collinear.
    #[error("the control triangle is degenerate (its points are collinear)")]
    DegenerateTriangle,
    /// The 3D target is off the triangle's plane.
    #[error(
        "the target is {distance:e} away from the control triangle's plane (tolerance {tolerance:e})"
    )]
    OffPlane { distance: f64, tolerance: f64 },
}

/// One side's knot, triangle and (with a target) frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Candidate {
    /// Which knot moves.
    pub side: Side,
    /// The span index `j` (the moved knot is `u_{j+1}`).
    pub span: usize,
    /// Full-vector index of the moved knot, `j + 1`.
    pub moved_knot: usize,
    /// `d_{j-2}, d_{j-1}, d_j`, when the indices exist.
    pub triangle: Option<[Point; 3]>,
    /// The target's frame, when a target was given and the side applies.
    pub frame: Option<Frame>,
    /// Why the side does not apply; `None` when it does.
    pub not_applicable: Option<NotApplicable>,
}

impl Candidate {
    /// Whether the side applies.
    pub fn is_applicable(&self) -> bool {
        self.not_applicable.is_none()
    }
}

/// The longest edge of a triangle: the size that the tolerances are relative to.
pub(crate) fn triangle_size(triangle: &[Point; 3]) -> f64 {
    let [d0, d1, d2] = *triangle;
    norm(sub(d0, d1))
        .max(norm(sub(d2, d1)))
        .max(norm(sub(d2, d0)))
}

/// The candidate for `side` at parameter `t` of a cubic `curve`, with the target's frame
/// when `target` is given. Precondition: `t` in the domain.
pub fn candidate(curve: &Curve, t: f64, side: Side, target: Option<Point>) -> Candidate {
    let m = curve.span(t);
    let span = match side {
        Side::Right => m,
        Side::Left => m - 1,
    };
    let n = curve.control_points().len() - 1;
    let mut candidate = Candidate {
        side,
        span,
        moved_knot: span + 1,
        triangle: None,
        frame: None,
        not_applicable: None,
    };
    if span < 2 || span > n {
        candidate.not_applicable = Some(NotApplicable::SpanOutOfRange { span });
        return candidate;
    }
    let d = curve.control_points();
    let triangle = [d[span - 2], d[span - 1], d[span]];
    candidate.triangle = Some(triangle);
    let weights = [span - 2, span - 1, span].map(|i| curve.weight(i));
    match triangle_frame(&triangle, curve.is_rational().then_some(weights), target) {
        Ok(frame) => candidate.frame = frame,
        Err(reason) => candidate.not_applicable = Some(reason),
    }
    candidate
}

/// The target's frame in a control triangle `d_0, d_1, d_2` (with the poles' weights for a
/// rational curve): `Ok(None)` without a target; an error when the triangle is degenerate or
/// the target is off its plane (docs/method.md §3.3, §7, §8).
pub(crate) fn triangle_frame(
    triangle: &[Point; 3],
    weights: Option<[f64; 3]>,
    target: Option<Point>,
) -> Result<Option<Frame>, NotApplicable> {
    let size = triangle_size(triangle);
    let e1 = sub(triangle[0], triangle[1]);
    let e2 = sub(triangle[2], triangle[1]);
    let normal = cross(e1, e2);
    let area2 = norm(normal);
    if area2.is_nan() || area2 <= DEGENERACY_TOLERANCE * size * size {
        return Err(NotApplicable::DegenerateTriangle);
    }
    let Some(target) = target else {
        return Ok(None);
    };
    let r = sub(target, triangle[1]);
    let distance = dot(r, normal).abs() / area2;
    let tolerance = PLANE_TOLERANCE * size;
    if distance > tolerance {
        return Err(NotApplicable::OffPlane {
            distance,
            tolerance,
        });
    }
    // Barycentric coordinates in the plane: λ0 = r·(e2 × n)/|n|², λ2 = r·(n × e1)/|n|².
    let area2_sq = area2 * area2;
    let lambda0 = dot(r, cross(e2, normal)) / area2_sq;
    let lambda2 = dot(r, cross(normal, e1)) / area2_sq;
    Ok(Some(weighted_frame(weights, lambda0, lambda2)))
}

/// The basis-value frame of barycentric `(λ0, 1 - λ0 - λ2, λ2)` (docs/method.md §7); equal to
/// `(λ0, λ2)` for a non-rational curve. When `S <= 0` (only for targets far outside the
/// triangle, which no knot pair reaches) it falls back to the geometric `(λ0, λ2)`.
fn weighted_frame(weights: Option<[f64; 3]>, lambda0: f64, lambda2: f64) -> Frame {
    let Some([w0, w1, w2]) = weights else {
        return Frame {
            x: lambda0,
            y: lambda2,
        };
    };
    let lambda1 = 1.0 - lambda0 - lambda2;
    let q0 = lambda0 / w0;
    let q1 = lambda1 / w1;
    let q2 = lambda2 / w2;
    let s = q0 + q1 + q2;
    if s > 0.0 {
        Frame {
            x: q0 / s,
            y: q2 / s,
        }
    } else {
        Frame {
            x: lambda0,
            y: lambda2,
        }
    }
}

/// The curve-space point of frame coordinates `(x, y)` of the candidate at `span`: the
/// (rational) combination of `d_{j-2}, d_{j-1}, d_j` with basis values `x, 1 - x - y, y`.
pub fn frame_to_point(curve: &Curve, span: usize, x: f64, y: f64) -> Point {
    let d = curve.control_points();
    let basis = [x, 1.0 - x - y, y];
    let mut numerator = [0.0; 3];
    let mut denominator = 0.0;
    for (r, &n) in basis.iter().enumerate() {
        let w = curve.weight(span - 2 + r) * n;
        for c in 0..3 {
            numerator[c] += w * d[span - 2 + r][c];
        }
        denominator += w;
    }
    if curve.is_rational() {
        numerator.map(|v| v / denominator)
    } else {
        numerator
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::CurveLimits;

    /// Both sides of a cubic at any parameter of its domain have a control triangle (the
    /// span `m` of `t` lies in `[p, n]`, so `2 <= j <= n` for `j = m − 1` and `j = m`): the
    /// answers always carry `triangle`, and, with a planar target, an applicable side its
    /// frame (the OpenAPI document requires both).
    #[test]
    fn every_side_of_a_cubic_has_a_triangle_and_an_applicable_one_a_frame() {
        let points = [[0.0, 0.0], [1.0, 2.0], [3.0, 2.5], [4.0, 0.0], [6.0, 1.0]];
        let limits = CurveLimits::default();
        let curves = [
            // One Bézier piece (n = p), clamped.
            Curve::new(
                3,
                &points[..4],
                &[0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
                None,
                &limits,
            ),
            // Unclamped, two spans.
            Curve::new(
                3,
                &points,
                &[0.0, 0.1, 0.2, 0.3, 0.6, 0.8, 0.9, 1.0, 1.2],
                None,
                &limits,
            ),
        ];
        for curve in curves {
            let curve = curve.unwrap();
            let (lo, hi) = curve.domain();
            for k in 0..=20 {
                let t = lo + (hi - lo) * f64::from(k) / 20.0;
                for side in [Side::Left, Side::Right] {
                    let found = candidate(&curve, t, side, Some([2.0, 1.0, 0.0]));
                    assert!(found.triangle.is_some(), "{t} {side:?}: {found:?}");
                    assert_eq!(found.frame.is_some(), found.is_applicable(), "{t} {side:?}");
                }
            }
        }
    }
}

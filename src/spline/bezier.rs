//! A curve's Bézier pieces, one per non-empty knot span, and de Casteljau's split of a piece.
//!
//! The pieces come from the blossoms of [`Curve::bezier_span_rest_with_knots`], which is what
//! inserting every knot up to multiplicity `p` (The NURBS Book A5.6) computes, without
//! building the refined curve.

use super::basis::CAP;
use super::curve::Curve;
use super::vector::Point;

/// One polynomial (or rational) piece of a curve: `A(u) = Σ_i B_i C(p, i) s^i (1 - s)^(p-i)`
/// with `s = (u - lo) / (hi - lo)` for the homogeneous curve `A = (w x, w y, w z, w)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BezierPiece {
    /// `[lo, hi]`: the knot span the piece covers.
    pub domain: (f64, f64),
    degree: usize,
    rational: bool,
    points: [[f64; 4]; CAP],
}

impl BezierPiece {
    /// A piece of degree `degree` over `domain` with homogeneous points `points[..=degree]`.
    pub(crate) fn new(
        domain: (f64, f64),
        degree: usize,
        rational: bool,
        points: [[f64; 4]; CAP],
    ) -> Self {
        BezierPiece {
            domain,
            degree,
            rational,
            points,
        }
    }

    /// The degree `p`.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// Whether the curve it comes from has weights.
    pub fn is_rational(&self) -> bool {
        self.rational
    }

    /// The `p + 1` homogeneous points `(w x, w y, w z, w)` (`w = 1` when non-rational).
    pub fn homogeneous(&self) -> &[[f64; 4]] {
        &self.points[..=self.degree]
    }

    /// Control point `i` (`z = 0` for planar curves): the homogeneous point divided by its
    /// weight.
    pub fn control_point(&self, i: usize) -> Point {
        let [x, y, z, w] = self.points[i];
        if self.rational {
            [x / w, y / w, z / w]
        } else {
            [x, y, z]
        }
    }

    /// The `p + 1` control points.
    pub fn control_points(&self) -> impl ExactSizeIterator<Item = Point> + '_ {
        (0..self.degree + 1).map(|i| self.control_point(i))
    }

    /// The `p + 1` weights (all 1 when non-rational).
    pub fn weights(&self) -> impl ExactSizeIterator<Item = f64> + '_ {
        self.homogeneous().iter().map(|h| h[3])
    }

    /// De Casteljau's split at local parameter `s` in `(0, 1)`: the pieces over
    /// `[lo, lo + s (hi - lo)]` and `[lo + s (hi - lo), hi]`, whose points are the first and
    /// the last points of the triangle's rows `B_i^r = (1 - s) B_i^(r-1) + s B_(i+1)^(r-1)`.
    /// `at` is the parameter of the split, as the caller computed it (it becomes the pieces'
    /// common end).
    pub fn split(&self, s: f64, at: f64) -> (BezierPiece, BezierPiece) {
        let p = self.degree;
        let mut row = self.points;
        let mut left = [[0.0; 4]; CAP];
        let mut right = [[0.0; 4]; CAP];
        left[0] = row[0];
        right[p] = row[p];
        for r in 1..=p {
            for i in 0..=p - r {
                let (a, b) = (row[i], row[i + 1]);
                row[i] = std::array::from_fn(|c| (1.0 - s) * a[c] + s * b[c]);
            }
            left[r] = row[0];
            right[p - r] = row[p - r];
        }
        (
            BezierPiece {
                domain: (self.domain.0, at),
                points: left,
                ..*self
            },
            BezierPiece {
                domain: (at, self.domain.1),
                points: right,
                ..*self
            },
        )
    }
}

/// The pieces of a curve, left to right (see [`Curve::bezier_pieces`]).
#[derive(Debug, Clone)]
pub struct BezierPieces<'c> {
    curve: &'c Curve,
    next_start: f64,
}

impl Iterator for BezierPieces<'_> {
    type Item = BezierPiece;

    fn next(&mut self) -> Option<BezierPiece> {
        let (_, hi) = self.curve.domain();
        if self.next_start >= hi {
            return None;
        }
        let lo = self.next_start;
        let mut points = [[0.0; 4]; CAP];
        let end = self
            .curve
            .bezier_span_rest_with_knots(self.curve.knots(), lo, &mut points);
        self.next_start = end;
        Some(BezierPiece::new(
            (lo, end),
            self.curve.degree(),
            self.curve.is_rational(),
            points,
        ))
    }
}

impl Curve {
    /// One Bézier piece per non-empty knot span of the domain, in order: each span's
    /// `p + 1` points are the blossoms `A[lo, …, lo, hi, …, hi]` (`p - i` times `lo`, `i`
    /// times `hi`), the control points that inserting every knot value up to multiplicity
    /// `p` would give the span (The NURBS Book A5.6). Neighbouring pieces share their end
    /// point (up to rounding) unless a knot of multiplicity `p + 1` makes the curve jump.
    pub fn bezier_pieces(&self) -> BezierPieces<'_> {
        BezierPieces {
            curve: self,
            next_start: self.domain().0,
        }
    }

    /// The interior knot values of multiplicity `p + 1` or more, where the curve may jump (its
    /// pieces do not meet), ascending.
    pub fn jump_knots(&self) -> Vec<f64> {
        let (lo, hi) = self.domain();
        let order = self.order();
        self.knots()
            .chunk_by(|a, b| a == b)
            .filter(|run| run.len() >= order && lo < run[0] && run[0] < hi)
            .map(|run| run[0])
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::CurveLimits;

    #[test]
    fn pieces_cover_the_non_empty_spans_in_order() {
        let points: Vec<[f64; 2]> = (0..7).map(|i| [i as f64, ((i * 3) % 4) as f64]).collect();
        let knots = [0.0, 0.0, 0.0, 0.0, 0.5, 0.5, 1.5, 2.0, 2.0, 2.0, 2.0];
        let curve = Curve::new(3, &points, &knots, None, &CurveLimits::default()).unwrap();
        let domains: Vec<(f64, f64)> = curve.bezier_pieces().map(|piece| piece.domain).collect();
        assert_eq!(domains, vec![(0.0, 0.5), (0.5, 1.5), (1.5, 2.0)]);
        let first = curve.bezier_pieces().next().unwrap();
        assert_eq!(first.control_point(0), [0.0, 0.0, 0.0]);
        assert!(curve.jump_knots().is_empty());
    }

    #[test]
    fn a_split_at_one_half_is_de_casteljaus_midpoint_construction() {
        let mut points = [[0.0; 4]; CAP];
        for (slot, p) in points
            .iter_mut()
            .zip([[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]])
        {
            *slot = [p[0], p[1], 0.0, 1.0];
        }
        let piece = BezierPiece::new((0.0, 2.0), 3, false, points);
        let (left, right) = piece.split(0.5, 1.0);
        assert_eq!(left.domain, (0.0, 1.0));
        assert_eq!(right.domain, (1.0, 2.0));
        let left: Vec<Point> = left.control_points().collect();
        let right: Vec<Point> = right.control_points().collect();
        assert_eq!(
            left,
            [
                [0.0, 0.0, 0.0],
                [0.5, 1.0, 0.0],
                [1.25, 1.5, 0.0],
                [2.0, 1.5, 0.0]
            ]
        );
        assert_eq!(
            right,
            [
                [2.0, 1.5, 0.0],
                [2.75, 1.5, 0.0],
                [3.5, 1.0, 0.0],
                [4.0, 0.0, 0.0]
            ]
        );
    }
}

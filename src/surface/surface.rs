//! The validated surface type: two parameter directions (degree, knots in the caller's form,
//! possibly periodic) and a net of control points `d_ij` with optional weights, and the
//! curves it is made of: the columns (curves along `u`) and the rows (along `v`).
//!
//! `S(u, v) = Σ_i Σ_j N_i(u) M_j(v) w_ij d_ij / Σ_i Σ_j N_i(u) M_j(v) w_ij`, `i` along `u`.
//! A periodic direction is stored cut open at its first knot, as a periodic curve is
//! ([`crate::spline::Curve`]): the net's rows (or columns) past the period repeat the first
//! ones, and the direction remembers how to write itself in the periodic form again.

use crate::spline::{
    CallerKnots, Curve, Dimension, KnotConvention, Periodicity, Point, find_span, snap_parameter,
};

/// One of the two parameter directions.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Direction {
    /// `u`: along the first index `i` of `d_ij` (down the columns).
    U,
    /// `v`: along the second index `j` (along the rows).
    V,
}

impl Direction {
    /// `"u"` or `"v"`.
    pub fn name(self) -> &'static str {
        match self {
            Direction::U => "u",
            Direction::V => "v",
        }
    }

    /// The other direction.
    pub fn other(self) -> Direction {
        match self {
            Direction::U => Direction::V,
            Direction::V => Direction::U,
        }
    }
}

/// One direction of a surface: its degree and full knot vector (cut open at `k_0` when
/// periodic), the caller's knot convention and, when periodic, the layout of the periodic form.
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    degree: usize,
    knots: Vec<f64>,
    convention: KnotConvention,
    periodic: Option<Periodicity>,
}

impl Axis {
    /// An axis from parts that obey the rules (a valid knot vector for `degree`).
    pub(crate) fn from_valid_parts(
        degree: usize,
        knots: Vec<f64>,
        convention: KnotConvention,
        periodic: Option<Periodicity>,
    ) -> Axis {
        Axis {
            degree,
            knots,
            convention,
            periodic,
        }
    }

    /// The axis of a curve (its degree, knots, convention and periodic layout).
    pub(crate) fn of_curve(curve: &Curve) -> Axis {
        Axis {
            degree: curve.degree(),
            knots: curve.knots().to_vec(),
            convention: curve.convention(),
            periodic: curve.periodicity(),
        }
    }

    /// The degree.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The full knot vector (of the cut-open spline, when periodic).
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// The caller's knot convention.
    pub fn convention(&self) -> KnotConvention {
        self.convention
    }

    /// Whether the caller gave this direction in the periodic form.
    pub fn is_periodic(&self) -> bool {
        self.periodic.is_some()
    }

    /// The number of control points along this direction (of the cut-open spline).
    pub fn count(&self) -> usize {
        self.knots.len() - self.degree - 1
    }

    /// The number of control points along this direction as the caller gives them (a
    /// periodic direction's `N`, not repeated).
    pub fn caller_count(&self) -> usize {
        self.periodic.map_or(self.count(), |p| p.poles)
    }

    /// The parameter domain `[t_p, t_{n+1}]` (one period, when periodic).
    pub fn domain(&self) -> (f64, f64) {
        (self.knots[self.degree], self.knots[self.count()])
    }

    /// `t` in the domain, just outside it taken as the nearer end, or reduced into the period
    /// when periodic ([`snap_parameter`]); `None` when farther out or not finite.
    pub fn snap(&self, t: f64) -> Option<f64> {
        snap_parameter(t, self.domain(), self.is_periodic())
    }

    /// The span `m` with `t_m <= t < t_{m+1}` (the last non-empty one at the domain's end).
    pub fn span(&self, t: f64) -> usize {
        find_span(&self.knots, self.degree, t)
    }

    /// The non-empty knot spans of the domain: `(m, t_m, t_{m+1})`, in order.
    pub fn spans(&self) -> impl Iterator<Item = (usize, f64, f64)> + '_ {
        (self.degree..self.count())
            .map(|m| (m, self.knots[m], self.knots[m + 1]))
            .filter(|(_, lo, hi)| lo < hi)
    }

    /// The interior knot values of multiplicity `degree + 1` or more, where the surface may
    /// jump across this direction.
    pub fn jump_knots(&self) -> Vec<f64> {
        let (lo, hi) = self.domain();
        self.knots
            .chunk_by(|a, b| a == b)
            .filter(|run| run.len() > self.degree && lo < run[0] && run[0] < hi)
            .map(|run| run[0])
            .collect()
    }
}

/// A B-spline or NURBS surface whose data obey every rule: built by
/// [`Surface::from_knot_forms`] (or derived from another valid surface), so the rest of the
/// core never sees invalid data.
///
/// Invariants: each direction a valid [`Axis`] with `count` control points; `count_u ·
/// count_v` control points stored row by row (`d_ij` at `i · count_v + j`), all finite;
/// finite positive weights when rational.
#[derive(Debug, Clone, PartialEq)]
pub struct Surface {
    u: Axis,
    v: Axis,
    points: Vec<Point>,
    weights: Option<Vec<f64>>,
    /// `(w x, w y, w z, w)` per control point; `w = 1` when non-rational.
    homogeneous: Vec<[f64; 4]>,
}

impl Surface {
    /// Assembles a surface from parts that already satisfy the invariants.
    pub(crate) fn from_valid_parts(
        u: Axis,
        v: Axis,
        points: Vec<Point>,
        weights: Option<Vec<f64>>,
    ) -> Surface {
        debug_assert_eq!(points.len(), u.count() * v.count());
        let homogeneous = points
            .iter()
            .enumerate()
            .map(|(k, p)| {
                let w = weights.as_ref().map_or(1.0, |w| w[k]);
                [w * p[0], w * p[1], w * p[2], w]
            })
            .collect();
        Surface {
            u,
            v,
            points,
            weights,
            homogeneous,
        }
    }

    /// A surface from homogeneous control points (projected; weights kept when `rational`).
    pub(crate) fn from_homogeneous(
        u: Axis,
        v: Axis,
        homogeneous: &[[f64; 4]],
        rational: bool,
    ) -> Surface {
        let points = homogeneous
            .iter()
            .map(|h| {
                if rational {
                    [h[0] / h[3], h[1] / h[3], h[2] / h[3]]
                } else {
                    [h[0], h[1], h[2]]
                }
            })
            .collect();
        let weights = rational.then(|| homogeneous.iter().map(|h| h[3]).collect());
        Surface::from_valid_parts(u, v, points, weights)
    }

    /// The direction `direction`.
    pub fn axis(&self, direction: Direction) -> &Axis {
        match direction {
            Direction::U => &self.u,
            Direction::V => &self.v,
        }
    }

    /// The `u` direction.
    pub fn u(&self) -> &Axis {
        &self.u
    }

    /// The `v` direction.
    pub fn v(&self) -> &Axis {
        &self.v
    }

    /// `[[u_lo, u_hi], [v_lo, v_hi]]`.
    pub fn domain(&self) -> [(f64, f64); 2] {
        [self.u.domain(), self.v.domain()]
    }

    /// Whether the surface has weights.
    pub fn is_rational(&self) -> bool {
        self.weights.is_some()
    }

    /// The control point `d_ij`.
    #[inline]
    pub fn control_point(&self, i: usize, j: usize) -> Point {
        self.points[i * self.v.count() + j]
    }

    /// The weight `w_ij` (1 when non-rational).
    #[inline]
    pub fn weight(&self, i: usize, j: usize) -> f64 {
        self.weights
            .as_ref()
            .map_or(1.0, |w| w[i * self.v.count() + j])
    }

    /// Every control point, row by row (`d_ij` at `i · count_v + j`).
    pub fn control_points(&self) -> &[Point] {
        &self.points
    }

    /// Every weight, row by row, when rational.
    pub fn weights(&self) -> Option<&[f64]> {
        self.weights.as_deref()
    }

    /// The homogeneous control points, row by row.
    pub(crate) fn homogeneous(&self) -> &[[f64; 4]] {
        &self.homogeneous
    }

    /// The control points as the caller gave them: `caller_count_u` rows of
    /// `caller_count_v` points (a periodic direction's repeated ones left out).
    pub fn caller_control_points(&self) -> Vec<Vec<Point>> {
        (0..self.u.caller_count())
            .map(|i| {
                (0..self.v.caller_count())
                    .map(|j| self.control_point(i, j))
                    .collect()
            })
            .collect()
    }

    /// The weights as the caller gave them (see [`Surface::caller_control_points`]).
    pub fn caller_weights(&self) -> Option<Vec<Vec<f64>>> {
        self.is_rational().then(|| {
            (0..self.u.caller_count())
                .map(|i| {
                    (0..self.v.caller_count())
                        .map(|j| self.weight(i, j))
                        .collect()
                })
                .collect()
        })
    }

    /// The knots of `direction` in the caller's form (flat in its convention, or distinct
    /// values with multiplicities, of one period when periodic).
    pub fn caller_knots(&self, direction: Direction) -> CallerKnots {
        match direction {
            Direction::U => self.column(0).caller_knots(),
            Direction::V => self.row(0).caller_knots(),
        }
    }

    /// The curve along `u` through column `j`: `u ↦ Σ_i N_i(u) w_ij d_ij / Σ_i N_i(u) w_ij`,
    /// with the `u` direction's knots (periodic when it is). Every operation of a surface in
    /// `u` is that of the curves through its columns.
    pub fn column(&self, j: usize) -> Curve {
        let points = (0..self.u.count())
            .map(|i| self.control_point(i, j))
            .collect();
        let weights = self
            .is_rational()
            .then(|| (0..self.u.count()).map(|i| self.weight(i, j)).collect());
        curve_of(&self.u, points, weights)
    }

    /// The curve along `v` through row `i` (see [`Surface::column`]).
    pub fn row(&self, i: usize) -> Curve {
        let points = (0..self.v.count())
            .map(|j| self.control_point(i, j))
            .collect();
        let weights = self
            .is_rational()
            .then(|| (0..self.v.count()).map(|j| self.weight(i, j)).collect());
        curve_of(&self.v, points, weights)
    }

    /// The surface whose columns are `columns` (curves along `u` sharing their knots, as
    /// [`Surface::column`] gives them, e.g. after the same knot insertion) with this surface's
    /// `v` direction. Precondition: at least one column, all of one layout.
    pub(crate) fn with_columns(&self, columns: &[Curve]) -> Surface {
        let u = Axis::of_curve(&columns[0]);
        let (n_u, n_v) = (u.count(), columns.len());
        let mut homogeneous = vec![[0.0; 4]; n_u * n_v];
        for (j, column) in columns.iter().enumerate() {
            for (i, h) in column.homogeneous().iter().enumerate() {
                homogeneous[i * n_v + j] = *h;
            }
        }
        Surface::from_homogeneous(u, self.v.clone(), &homogeneous, self.is_rational())
    }

    /// The surface whose rows are `rows` (curves along `v`) with this surface's `u` direction
    /// (see [`Surface::with_columns`]).
    pub(crate) fn with_rows(&self, rows: &[Curve]) -> Surface {
        let v = Axis::of_curve(&rows[0]);
        let homogeneous: Vec<[f64; 4]> = rows
            .iter()
            .flat_map(|row| row.homogeneous().iter().copied())
            .collect();
        Surface::from_homogeneous(self.u.clone(), v, &homogeneous, self.is_rational())
    }

    /// The diagonal of the control points' bounding box.
    pub fn size(&self) -> f64 {
        let mut min = [f64::INFINITY; 3];
        let mut max = [f64::NEG_INFINITY; 3];
        for point in &self.points {
            for c in 0..3 {
                min[c] = min[c].min(point[c]);
                max[c] = max[c].max(point[c]);
            }
        }
        crate::spline::vector::distance(min, max)
    }

    /// The largest control-point coordinate magnitude.
    pub fn coordinate_magnitude(&self) -> f64 {
        self.points
            .iter()
            .flatten()
            .fold(0.0f64, |m, v| m.max(v.abs()))
    }
}

/// The curve of one direction's axis over `points` and `weights`.
fn curve_of(axis: &Axis, points: Vec<Point>, weights: Option<Vec<f64>>) -> Curve {
    let curve = Curve::from_valid_parts(
        axis.degree,
        Dimension::Three,
        points,
        weights,
        axis.knots.clone(),
        axis.convention,
    );
    match axis.periodic {
        Some(periodicity) => curve.into_periodic(periodicity),
        None => curve,
    }
}

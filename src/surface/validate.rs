//! Building a [`Surface`] from raw data: every rule, with typed errors that name the field
//! (a row, a control point `[i][j]`, a knot of one direction, a weight).
//!
//! The knots of each direction follow the curves' rules exactly: they are checked by the very
//! function that checks a curve's knots ([`crate::spline::validate_knots`]), the direction's
//! curve being a column (for `u`) or a row (for `v`) of the net.

use super::surface::{Axis, Direction, Surface};
use crate::spline::{CurveError, CurveField, KnotForm, MAX_DEGREE, Point, validate_knots};

/// Size limits applied while validating a surface (the service makes them configurable).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SurfaceLimits {
    /// Largest accepted degree in each direction; at most [`MAX_DEGREE`].
    pub max_degree: usize,
    /// Largest accepted number of control points (`rows × points per row`, as sent).
    pub max_control_points: usize,
}

impl Default for SurfaceLimits {
    fn default() -> Self {
        SurfaceLimits {
            max_degree: MAX_DEGREE,
            max_control_points: 10_000,
        }
    }
}

/// The element of the surface data that broke a rule. Indices are the caller's: `row` is
/// `i` (along `u`), `column` is `j` (along `v`); knot indices in the direction's convention.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SurfaceField {
    /// `degree_u` or `degree_v`.
    Degree(Direction),
    /// The control points as a whole.
    ControlPoints,
    /// One row `control_points[i]`.
    Row(usize),
    /// One control point `control_points[i][j]` or one of its coordinates.
    ControlPoint {
        row: usize,
        column: usize,
        coordinate: Option<usize>,
    },
    /// `knots_u` or `knots_v` as a whole.
    Knots(Direction),
    /// One knot of a direction.
    Knot(Direction, usize),
    /// `multiplicities_u` or `multiplicities_v` as a whole.
    Multiplicities(Direction),
    /// One multiplicity of a direction.
    Multiplicity(Direction, usize),
    /// `periodic_u` or `periodic_v`.
    Periodic(Direction),
    /// The weights as a whole.
    Weights,
    /// One row of weights.
    WeightRow(usize),
    /// One weight `weights[i][j]`.
    Weight { row: usize, column: usize },
}

/// A rule broken by raw surface data; [`SurfaceError::field`] names the offending element.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SurfaceError {
    #[error("degree_{} must be at least 1", direction.name())]
    DegreeTooLow { direction: Direction },
    #[error("degree_{} = {degree} exceeds the limit {max}", direction.name())]
    DegreeTooHigh {
        direction: Direction,
        degree: usize,
        max: usize,
    },
    #[error(
        "{count} rows of control points given; degree_u = {degree} needs at least {needed} (a row per control point along u)"
    )]
    TooFewRows {
        count: usize,
        degree: usize,
        needed: usize,
    },
    #[error(
        "row 0 has {count} control points; degree_v = {degree} needs at least {needed} per row"
    )]
    TooFewColumns {
        count: usize,
        degree: usize,
        needed: usize,
    },
    #[error("row {row} has {len} control points; every row must have {expected}, as row 0")]
    RaggedRow {
        row: usize,
        len: usize,
        expected: usize,
    },
    #[error("{count} control points exceed the limit {max}")]
    TooManyControlPoints { count: usize, max: usize },
    #[error(
        "control point [{row}][{column}] has {len} coordinates; a surface's control points are 3D ([x, y, z])"
    )]
    NotSpatial {
        row: usize,
        column: usize,
        len: usize,
    },
    #[error("control point [{row}][{column}] coordinate {coordinate} is not a finite number")]
    NonFiniteCoordinate {
        row: usize,
        column: usize,
        coordinate: usize,
    },
    #[error("{count} rows of weights given; expected one per row of control points ({expected})")]
    WrongWeightRows { count: usize, expected: usize },
    #[error("weight row {row} has {len} weights; expected {expected}, one per control point")]
    RaggedWeightRow {
        row: usize,
        len: usize,
        expected: usize,
    },
    #[error("weight [{row}][{column}] is not a finite number")]
    NonFiniteWeight { row: usize, column: usize },
    #[error("weight [{row}][{column}] must be greater than 0")]
    NonPositiveWeight { row: usize, column: usize },
    /// A rule of the knots of one direction (the rules of a curve's knots; that direction's
    /// curves have `count` control points).
    #[error("{} direction ({count} control points along it): {error}", direction.name())]
    Knots {
        direction: Direction,
        count: usize,
        error: CurveError,
    },
}

impl SurfaceError {
    /// The element of the input that is at fault.
    pub fn field(&self) -> SurfaceField {
        match *self {
            SurfaceError::DegreeTooLow { direction }
            | SurfaceError::DegreeTooHigh { direction, .. } => SurfaceField::Degree(direction),
            SurfaceError::TooFewRows { .. } | SurfaceError::TooManyControlPoints { .. } => {
                SurfaceField::ControlPoints
            }
            SurfaceError::TooFewColumns { .. } => SurfaceField::Row(0),
            SurfaceError::RaggedRow { row, .. } => SurfaceField::Row(row),
            SurfaceError::NotSpatial { row, column, .. } => SurfaceField::ControlPoint {
                row,
                column,
                coordinate: None,
            },
            SurfaceError::NonFiniteCoordinate {
                row,
                column,
                coordinate,
            } => SurfaceField::ControlPoint {
                row,
                column,
                coordinate: Some(coordinate),
            },
            SurfaceError::WrongWeightRows { .. } => SurfaceField::Weights,
            SurfaceError::RaggedWeightRow { row, .. } => SurfaceField::WeightRow(row),
            SurfaceError::NonFiniteWeight { row, column }
            | SurfaceError::NonPositiveWeight { row, column } => {
                SurfaceField::Weight { row, column }
            }
            SurfaceError::Knots {
                direction,
                ref error,
                ..
            } => match error.field() {
                CurveField::Knot(index) => SurfaceField::Knot(direction, index),
                CurveField::Multiplicities => SurfaceField::Multiplicities(direction),
                CurveField::Multiplicity(index) => SurfaceField::Multiplicity(direction, index),
                CurveField::Periodic => SurfaceField::Periodic(direction),
                // Only knot rules reach here; the count of a direction is its knots' to fit.
                _ => SurfaceField::Knots(direction),
            },
        }
    }
}

impl Surface {
    /// Validates raw surface data: `control_points[i][j]` with `i` along `u`, knots of each
    /// direction in any [`KnotForm`], optional `weights[i][j]`.
    ///
    /// Rules, in order: `1 <= degree <= limits.max_degree` in each direction; at least
    /// `degree_u + 1` rows (`max(degree_u, 2)` when periodic in `u`) of at least
    /// `degree_v + 1` points (likewise), every row as long as row 0, at most
    /// `limits.max_control_points` in all; every point 3D with finite coordinates; when
    /// weighted, one row of weights per row of points, one finite weight `> 0` per point;
    /// then the knots of each direction by the curves' rules for that many control points.
    pub fn from_knot_forms<R, C, W>(
        (degree_u, degree_v): (usize, usize),
        control_points: &[R],
        (knots_u, knots_v): (KnotForm<'_>, KnotForm<'_>),
        weights: Option<&[W]>,
        limits: &SurfaceLimits,
    ) -> Result<Surface, SurfaceError>
    where
        R: AsRef<[C]>,
        C: AsRef<[f64]>,
        W: AsRef<[f64]>,
    {
        let max = limits.max_degree.min(MAX_DEGREE);
        for (direction, degree) in [(Direction::U, degree_u), (Direction::V, degree_v)] {
            if degree < 1 {
                return Err(SurfaceError::DegreeTooLow { direction });
            }
            if degree > max {
                return Err(SurfaceError::DegreeTooHigh {
                    direction,
                    degree,
                    max,
                });
            }
        }
        let periodic = |form: &KnotForm<'_>| matches!(form, KnotForm::Periodic { .. });
        let needed = |degree: usize, periodic: bool| {
            if periodic { degree.max(2) } else { degree + 1 }
        };
        let n_u = control_points.len();
        let needed_u = needed(degree_u, periodic(&knots_u));
        if n_u < needed_u {
            return Err(SurfaceError::TooFewRows {
                count: n_u,
                degree: degree_u,
                needed: needed_u,
            });
        }
        let n_v = control_points[0].as_ref().len();
        let needed_v = needed(degree_v, periodic(&knots_v));
        if n_v < needed_v {
            return Err(SurfaceError::TooFewColumns {
                count: n_v,
                degree: degree_v,
                needed: needed_v,
            });
        }
        // The count first (one pass over the rows), so that a huge net costs nothing more.
        let count = control_points
            .iter()
            .fold(0usize, |sum, row| sum.saturating_add(row.as_ref().len()));
        if count > limits.max_control_points {
            return Err(SurfaceError::TooManyControlPoints {
                count,
                max: limits.max_control_points,
            });
        }
        let mut points: Vec<Point> = Vec::with_capacity(count);
        for (row, raw) in control_points.iter().enumerate() {
            let raw = raw.as_ref();
            if raw.len() != n_v {
                return Err(SurfaceError::RaggedRow {
                    row,
                    len: raw.len(),
                    expected: n_v,
                });
            }
            for (column, coordinates) in raw.iter().enumerate() {
                let coordinates = coordinates.as_ref();
                if coordinates.len() != 3 {
                    return Err(SurfaceError::NotSpatial {
                        row,
                        column,
                        len: coordinates.len(),
                    });
                }
                if let Some(coordinate) = coordinates.iter().position(|x| !x.is_finite()) {
                    return Err(SurfaceError::NonFiniteCoordinate {
                        row,
                        column,
                        coordinate,
                    });
                }
                points.push([coordinates[0], coordinates[1], coordinates[2]]);
            }
        }
        let weights = weights.map(|w| checked_weights(w, n_u, n_v)).transpose()?;
        let u = checked_axis(Direction::U, degree_u, n_u, knots_u)?;
        let v = checked_axis(Direction::V, degree_v, n_v, knots_v)?;
        Ok(unwrapped(u, v, n_v, &points, weights.as_deref()))
    }
}

/// The weights, row by row, once one finite weight `> 0` is given per control point.
fn checked_weights<W: AsRef<[f64]>>(
    weights: &[W],
    n_u: usize,
    n_v: usize,
) -> Result<Vec<f64>, SurfaceError> {
    if weights.len() != n_u {
        return Err(SurfaceError::WrongWeightRows {
            count: weights.len(),
            expected: n_u,
        });
    }
    let mut flat = Vec::with_capacity(n_u * n_v);
    for (row, raw) in weights.iter().enumerate() {
        let raw = raw.as_ref();
        if raw.len() != n_v {
            return Err(SurfaceError::RaggedWeightRow {
                row,
                len: raw.len(),
                expected: n_v,
            });
        }
        for (column, &w) in raw.iter().enumerate() {
            if !w.is_finite() {
                return Err(SurfaceError::NonFiniteWeight { row, column });
            }
            if w <= 0.0 {
                return Err(SurfaceError::NonPositiveWeight { row, column });
            }
            flat.push(w);
        }
    }
    Ok(flat)
}

/// One direction's knots checked by the curves' rules for `count` control points.
fn checked_axis(
    direction: Direction,
    degree: usize,
    count: usize,
    form: KnotForm<'_>,
) -> Result<Axis, SurfaceError> {
    let valid = validate_knots(degree, count, form).map_err(|error| SurfaceError::Knots {
        direction,
        count,
        error,
    })?;
    Ok(Axis::from_valid_parts(
        degree,
        valid.full,
        valid.convention,
        valid.periodicity,
    ))
}

/// The surface over validated axes and the caller's `n_v`-wide rows of points (and weights):
/// a periodic direction cut open at its first knot, its control point `k` being the caller's
/// `k mod N` ([`crate::spline::validate_knots`]).
fn unwrapped(u: Axis, v: Axis, n_v: usize, points: &[Point], weights: Option<&[f64]>) -> Surface {
    let (rows, columns) = (u.count(), v.count());
    let (caller_rows, caller_columns) = (u.caller_count(), v.caller_count());
    let mut net = Vec::with_capacity(rows * columns);
    let mut net_weights = weights.map(|_| Vec::with_capacity(rows * columns));
    for i in 0..rows {
        for j in 0..columns {
            let k = (i % caller_rows) * n_v + j % caller_columns;
            net.push(points[k]);
            if let (Some(out), Some(w)) = (net_weights.as_mut(), weights) {
                out.push(w[k]);
            }
        }
    }
    Surface::from_valid_parts(u, v, net, net_weights)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A bicubic net of 4 × 5 points over clamped knots (5 points need one interior v-knot).
    fn net(rows: usize, columns: usize) -> Vec<Vec<Vec<f64>>> {
        (0..rows)
            .map(|i| {
                (0..columns)
                    .map(|j| vec![i as f64, j as f64, ((i * j) % 3) as f64])
                    .collect()
            })
            .collect()
    }

    const KNOTS_U: [f64; 8] = [0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0];
    const KNOTS_V: [f64; 9] = [0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0];

    fn build(
        points: &[Vec<Vec<f64>>],
        knots_u: &[f64],
        knots_v: &[f64],
        weights: Option<&[Vec<f64>]>,
    ) -> Result<Surface, SurfaceError> {
        Surface::from_knot_forms(
            (3, 3),
            points,
            (KnotForm::Flat(knots_u), KnotForm::Flat(knots_v)),
            weights,
            &SurfaceLimits::default(),
        )
    }

    fn field_of(result: Result<Surface, SurfaceError>) -> SurfaceField {
        result.expect_err("the data break a rule").field()
    }

    #[test]
    fn a_valid_net_keeps_its_points_row_by_row() {
        let surface = build(&net(4, 5), &KNOTS_U, &KNOTS_V, None).unwrap();
        assert_eq!((surface.u().count(), surface.v().count()), (4, 5));
        assert_eq!(surface.control_point(2, 3), [2.0, 3.0, 0.0]);
        assert_eq!(surface.domain(), [(0.0, 1.0), (0.0, 1.0)]);
        // Trimmed knots in v are detected by length, as for curves.
        let trimmed = build(&net(4, 5), &KNOTS_U, &KNOTS_V[1..8], None).unwrap();
        assert_eq!(trimmed.v().knots(), &KNOTS_V);
    }

    #[test]
    fn ragged_rows_and_planar_points_are_named() {
        let mut ragged = net(4, 5);
        ragged[2].pop();
        assert_eq!(
            field_of(build(&ragged, &KNOTS_U, &KNOTS_V, None)),
            SurfaceField::Row(2)
        );
        let mut planar = net(4, 5);
        planar[1][3] = vec![1.0, 3.0];
        let err = build(&planar, &KNOTS_U, &KNOTS_V, None).unwrap_err();
        assert_eq!(
            err.field(),
            SurfaceField::ControlPoint {
                row: 1,
                column: 3,
                coordinate: None
            }
        );
        assert!(err.to_string().contains("3D"), "{err}");
        let mut nan = net(4, 5);
        nan[3][4][2] = f64::NAN;
        assert_eq!(
            field_of(build(&nan, &KNOTS_U, &KNOTS_V, None)),
            SurfaceField::ControlPoint {
                row: 3,
                column: 4,
                coordinate: Some(2)
            }
        );
    }

    #[test]
    fn counts_follow_the_degrees_and_the_limit() {
        assert_eq!(
            field_of(build(&net(3, 5), &KNOTS_U[1..], &KNOTS_V, None)),
            SurfaceField::ControlPoints
        );
        assert_eq!(
            field_of(build(&net(4, 3), &KNOTS_U, &KNOTS_V, None)),
            SurfaceField::Row(0)
        );
        let limits = SurfaceLimits {
            max_control_points: 19,
            ..SurfaceLimits::default()
        };
        let err = Surface::from_knot_forms(
            (3, 3),
            &net(4, 5),
            (KnotForm::Flat(&KNOTS_U), KnotForm::Flat(&KNOTS_V)),
            None::<&[Vec<f64>]>,
            &limits,
        )
        .unwrap_err();
        assert_eq!(
            err,
            SurfaceError::TooManyControlPoints { count: 20, max: 19 }
        );
    }

    #[test]
    fn knot_errors_name_their_direction() {
        let err = build(&net(4, 5), &KNOTS_U, &KNOTS_V[..8], None).unwrap_err();
        assert_eq!(err.field(), SurfaceField::Knots(Direction::V));
        assert!(err.to_string().starts_with("v direction"), "{err}");
        let mut decreasing = KNOTS_U;
        decreasing[4] = -1.0;
        assert_eq!(
            field_of(build(&net(4, 5), &decreasing, &KNOTS_V, None)),
            SurfaceField::Knot(Direction::U, 4)
        );
    }

    #[test]
    fn weights_are_checked_per_point() {
        let mut weights = vec![vec![1.0; 5]; 4];
        weights[2][1] = 0.0;
        assert_eq!(
            field_of(build(&net(4, 5), &KNOTS_U, &KNOTS_V, Some(&weights))),
            SurfaceField::Weight { row: 2, column: 1 }
        );
        weights[2][1] = -2.0;
        assert!(matches!(
            build(&net(4, 5), &KNOTS_U, &KNOTS_V, Some(&weights)),
            Err(SurfaceError::NonPositiveWeight { row: 2, column: 1 })
        ));
        weights[2] = vec![1.0; 4];
        assert_eq!(
            field_of(build(&net(4, 5), &KNOTS_U, &KNOTS_V, Some(&weights))),
            SurfaceField::WeightRow(2)
        );
        assert_eq!(
            field_of(build(&net(4, 5), &KNOTS_U, &KNOTS_V, Some(&weights[..3]))),
            SurfaceField::Weights
        );
    }

    #[test]
    fn a_periodic_direction_repeats_its_first_rows() {
        // Periodic in u: 4 distinct knots of one period, multiplicities 1, cubic: 3 rows
        // (Σ m - m_last = 3), cut open to 3 + 3 + 1 - 1 = 6 rows.
        let knots = [0.0, 1.0, 2.0, 3.0];
        let multiplicities = [1, 1, 1, 1];
        let surface = Surface::from_knot_forms(
            (3, 3),
            &net(3, 5),
            (
                KnotForm::Periodic {
                    knots: &knots,
                    multiplicities: &multiplicities,
                },
                KnotForm::Flat(&KNOTS_V),
            ),
            None::<&[Vec<f64>]>,
            &SurfaceLimits::default(),
        )
        .unwrap();
        assert_eq!(surface.u().count(), 6);
        assert_eq!(surface.u().caller_count(), 3);
        assert_eq!(surface.control_point(4, 2), surface.control_point(1, 2));
        assert_eq!(surface.u().domain(), (0.0, 3.0));
        let caller = surface.caller_knots(Direction::U);
        assert!(caller.periodic);
        assert_eq!(caller.knots, knots);
        assert_eq!(surface.caller_control_points().len(), 3);
    }
}

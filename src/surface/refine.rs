//! Knot insertion and splitting: the curves' own operations on the curves a surface is made
//! of. Inserting `u` values inserts them into every column (curve along `u`, The NURBS Book
//! A5.4 on the homogeneous points, periodic columns in every period); splitting at `u` values
//! splits every column into clamped pieces, piece `k` of the surface being the columns'
//! pieces `k` (the same in `v` with the rows). The shape is unchanged: each column is the
//! same curve over a finer knot vector, or the same curve cut.

use super::surface::{Direction, Surface};
use crate::spline::{Curve, InsertError, SplitError};

/// Why knots cannot be inserted into a surface: the direction whose values are at fault, or
/// the size of the result.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SurfaceInsertError {
    /// A value of one direction breaks a rule of the curves' insertion.
    #[error("{} direction: {error}", direction.name())]
    Value {
        direction: Direction,
        error: InsertError,
    },
    /// The refined surface would have more control points than allowed.
    #[error("the refined surface would have {count} control points, above the limit {max}")]
    TooManyControlPoints { count: usize, max: usize },
}

/// Why a surface cannot be split.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SurfaceSplitError {
    /// A split value breaks a rule of the curves' split (finite, strictly inside the domain,
    /// not too many).
    #[error("{0}")]
    Value(SplitError),
    /// The pieces together would have more control points than allowed.
    #[error("the pieces would have up to {count} control points together, above the limit {max}")]
    TooManyControlPoints { count: usize, max: usize },
}

impl Surface {
    /// The same surface with `knots_u` inserted in `u` and `knots_v` in `v` (each value may
    /// repeat to raise its multiplicity), in the same knot conventions: each direction's
    /// values follow the rules of [`Curve::insert_knots`] for its curves. At most
    /// `max_control_points` control points (as the caller counts them) in the result.
    pub fn insert_knots(
        &self,
        knots_u: &[f64],
        knots_v: &[f64],
        max_control_points: usize,
    ) -> Result<Surface, SurfaceInsertError> {
        let value_error = |direction| move |error| SurfaceInsertError::Value { direction, error };
        let sorted_u = self
            .column(0)
            .checked_insertions(knots_u)
            .map_err(value_error(Direction::U))?;
        let sorted_v = self
            .row(0)
            .checked_insertions(knots_v)
            .map_err(value_error(Direction::V))?;
        let count = (self.u().caller_count() + sorted_u.len())
            .saturating_mul(self.v().caller_count() + sorted_v.len());
        if count > max_control_points {
            return Err(SurfaceInsertError::TooManyControlPoints {
                count,
                max: max_control_points,
            });
        }
        let mut surface = self.clone();
        if !sorted_u.is_empty() {
            let columns: Vec<Curve> = (0..surface.v().count())
                .map(|j| surface.column(j).refined(&sorted_u))
                .collect();
            surface = surface.with_columns(&columns);
        }
        if !sorted_v.is_empty() {
            let rows: Vec<Curve> = (0..surface.u().count())
                .map(|i| surface.row(i).refined(&sorted_v))
                .collect();
            surface = surface.with_rows(&rows);
        }
        Ok(surface)
    }

    /// The clamped pieces between the `parameters` of direction `fixed` (any order; repeats
    /// count once), in order: `fixed = U` cuts at `u` values (pieces side by side in `u`, each
    /// with the whole `v` range), `V` at `v` values. Each piece is clamped in the cut
    /// direction (`degree + 1` equal end knots; a periodic direction is cut open first) and
    /// keeps the other direction as it is; together they are the surface. The parameters
    /// follow the rules of [`Curve::split_at`] (finite, strictly inside the domain, at most
    /// `max_parameters`); the pieces have at most `max_control_points` control points
    /// together.
    pub fn split(
        &self,
        fixed: Direction,
        parameters: &[f64],
        max_parameters: usize,
        max_control_points: usize,
    ) -> Result<Vec<Surface>, SurfaceSplitError> {
        let cut = self.axis(fixed);
        let across = self.axis(fixed.other()).count();
        // Each cut adds at most degree + 1 control points along the cut direction.
        let along = cut
            .count()
            .saturating_add(parameters.len().saturating_mul(cut.degree() + 1));
        let count = along.saturating_mul(across);
        if count > max_control_points {
            return Err(SurfaceSplitError::TooManyControlPoints {
                count,
                max: max_control_points,
            });
        }
        let curve_of = |k: usize| match fixed {
            Direction::U => self.column(k).as_ordinary(),
            Direction::V => self.row(k).as_ordinary(),
        };
        let mut pieces_per_curve: Vec<Vec<Curve>> = Vec::with_capacity(across);
        for k in 0..across {
            let pieces = curve_of(k)
                .split_at(parameters, max_parameters)
                .map_err(SurfaceSplitError::Value)?;
            pieces_per_curve.push(pieces);
        }
        let piece_count = pieces_per_curve.first().map_or(0, Vec::len);
        Ok((0..piece_count)
            .map(|piece| {
                let curves: Vec<Curve> = pieces_per_curve
                    .iter()
                    .map(|pieces| pieces[piece].clone())
                    .collect();
                match fixed {
                    Direction::U => self.with_columns(&curves),
                    Direction::V => self.with_rows(&curves),
                }
            })
            .collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::KnotForm;
    use crate::surface::SurfaceLimits;

    fn bicubic() -> Surface {
        let points: Vec<Vec<[f64; 3]>> = (0..4)
            .map(|i| {
                (0..5)
                    .map(|j| [i as f64, j as f64, ((i * 3 + j * 2) % 4) as f64 * 0.5])
                    .collect()
            })
            .collect();
        let weights: Vec<Vec<f64>> = (0..4)
            .map(|i| (0..5).map(|j| 1.0 + ((i + j) % 3) as f64 * 0.5).collect())
            .collect();
        Surface::from_knot_forms(
            (3, 3),
            &points,
            (
                KnotForm::Flat(&[0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0]),
                KnotForm::Flat(&[0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0]),
            ),
            Some(&weights),
            &SurfaceLimits::default(),
        )
        .unwrap()
    }

    fn gap(a: [f64; 3], b: [f64; 3]) -> f64 {
        (0..3).map(|c| (a[c] - b[c]).abs()).fold(0.0, f64::max)
    }

    #[test]
    fn insertion_keeps_the_shape() {
        let surface = bicubic();
        let refined = surface.insert_knots(&[0.3, 0.3], &[0.75], 1000).unwrap();
        assert_eq!(refined.u().count(), 6);
        assert_eq!(refined.v().count(), 6);
        for (u, v) in [(0.0, 0.0), (0.3, 0.75), (0.55, 0.2), (1.0, 1.0)] {
            assert!(
                gap(surface.point(u, v), refined.point(u, v)) < 1e-14,
                "{u} {v}"
            );
        }
        assert!(matches!(
            surface.insert_knots(&[0.5], &[1.5], 1000),
            Err(SurfaceInsertError::Value {
                direction: Direction::V,
                ..
            })
        ));
        assert!(matches!(
            surface.insert_knots(&[0.5], &[], 24),
            Err(SurfaceInsertError::TooManyControlPoints { count: 25, max: 24 })
        ));
    }

    #[test]
    fn pieces_are_the_surface_cut() {
        let surface = bicubic();
        let pieces = surface.split(Direction::V, &[0.8, 0.25], 10, 1000).unwrap();
        assert_eq!(pieces.len(), 3);
        let domains: Vec<(f64, f64)> = pieces.iter().map(|p| p.v().domain()).collect();
        assert_eq!(domains, [(0.0, 0.25), (0.25, 0.8), (0.8, 1.0)]);
        for piece in &pieces {
            let (lo, hi) = piece.v().domain();
            for k in 0..=4 {
                let v = lo + (hi - lo) * f64::from(k) / 4.0;
                for u in [0.0, 0.4, 1.0] {
                    assert!(
                        gap(piece.point(u, v), surface.point(u, v)) < 1e-14,
                        "{u} {v}"
                    );
                }
            }
            // Clamped in v: the first and last knots repeat degree + 1 times.
            let knots = piece.v().knots();
            assert!(
                knots[..4].iter().all(|&t| t == lo)
                    && knots[knots.len() - 4..].iter().all(|&t| t == hi)
            );
        }
        assert!(matches!(
            surface.split(Direction::U, &[1.0], 10, 1000),
            Err(SurfaceSplitError::Value(SplitError::NotInside {
                index: 0,
                ..
            }))
        ));
    }
}

//! Points a curve is to pass through or near, validated once, and their parameters: chord
//! length, centripetal or uniform (The NURBS Book §9.2.1, eqs. 9.4–9.6), or given.

use super::curve::Dimension;
use super::vector::{Point, distance};

/// Two consecutive points closer than this fraction of the points' bounding-box diagonal
/// count as coincident: their chord gives no direction, and parameters that close make the
/// interpolation system singular to working precision.
pub const COINCIDENT_POINT_TOLERANCE: f64 = 1e-12;

/// How the parameters of the points are chosen.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Parametrization {
    /// `ū_k − ū_{k−1} ∝ |Q_k − Q_{k−1}|` (The NURBS Book eq. 9.5).
    #[default]
    ChordLength,
    /// `ū_k − ū_{k−1} ∝ |Q_k − Q_{k−1}|^{1/2}` (eq. 9.6; Lee 1989): follows sharp turns more
    /// tightly than chord length.
    Centripetal,
    /// Equally spaced (eq. 9.4).
    Uniform,
}

/// A rule broken by points or their parameters; the index is the position in the caller's list.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PointsError {
    #[error("{count} points given; at least {needed} are needed{reason}")]
    TooFewPoints {
        count: usize,
        needed: usize,
        /// Why that many (for example, for the degree), with a leading space, or empty.
        reason: String,
    },
    #[error("{count} points exceed the limit of {max}")]
    TooManyPoints { count: usize, max: usize },
    #[error("point 0 has {len} coordinates; points have 2 (planar) or 3 (spatial)")]
    UnsupportedDimension { len: usize },
    #[error("point {index} has {len} coordinates; all must have {expected}, as the first")]
    WrongDimension {
        index: usize,
        len: usize,
        expected: usize,
    },
    #[error("point {index} coordinate {coordinate} is not a finite number")]
    NonFiniteCoordinate { index: usize, coordinate: usize },
    #[error(
        "point {index} coincides with point {previous} (their distance is within {COINCIDENT_POINT_TOLERANCE:e} of the points' size): consecutive points must differ{hint}"
    )]
    CoincidentPoints {
        index: usize,
        previous: usize,
        /// Extra advice, with a leading space, or empty.
        hint: String,
    },
    #[error("all points coincide: there is no curve to fit")]
    AllPointsCoincide,
    #[error("the points' coordinates are too large to measure the distances between them")]
    Overflow,
    #[error("{count} parameters given; expected {expected}{reason}")]
    WrongParameterCount {
        count: usize,
        expected: usize,
        reason: String,
    },
    #[error("parameter {index} is not a finite number")]
    NonFiniteParameter { index: usize },
    #[error("parameters must be strictly increasing: parameter {index} is not above parameter {}", index - 1)]
    ParametersNotIncreasing { index: usize },
}

/// The element of the request that a [`PointsError`] names.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PointsField {
    /// The list of points as a whole.
    Points,
    /// One point, or one of its coordinates.
    Point {
        index: usize,
        coordinate: Option<usize>,
    },
    /// The parameter list as a whole.
    Parameters,
    /// One parameter.
    Parameter(usize),
}

impl PointsError {
    /// The element at fault.
    pub fn field(&self) -> PointsField {
        match *self {
            PointsError::TooFewPoints { .. }
            | PointsError::TooManyPoints { .. }
            | PointsError::AllPointsCoincide
            | PointsError::Overflow => PointsField::Points,
            PointsError::UnsupportedDimension { .. } => PointsField::Point {
                index: 0,
                coordinate: None,
            },
            PointsError::WrongDimension { index, .. }
            | PointsError::CoincidentPoints { index, .. } => PointsField::Point {
                index,
                coordinate: None,
            },
            PointsError::NonFiniteCoordinate { index, coordinate } => PointsField::Point {
                index,
                coordinate: Some(coordinate),
            },
            PointsError::WrongParameterCount { .. } => PointsField::Parameters,
            PointsError::NonFiniteParameter { index }
            | PointsError::ParametersNotIncreasing { index } => PointsField::Parameter(index),
        }
    }
}

/// Validated points: between 2 and a limit, all 2D or all 3D, finite (`z = 0` when planar).
#[derive(Debug, Clone, PartialEq)]
pub struct PointSet {
    points: Vec<Point>,
    dimension: Dimension,
    size: f64,
}

impl PointSet {
    /// Validates raw points: at least 2 and at most `max_points`, all with 2 or all with 3
    /// finite coordinates, their bounding box of finite size.
    pub fn new(raw: &[impl AsRef<[f64]>], max_points: usize) -> Result<PointSet, PointsError> {
        if raw.len() < 2 {
            return Err(PointsError::TooFewPoints {
                count: raw.len(),
                needed: 2,
                reason: String::new(),
            });
        }
        if raw.len() > max_points {
            return Err(PointsError::TooManyPoints {
                count: raw.len(),
                max: max_points,
            });
        }
        let expected = raw[0].as_ref().len();
        let dimension = match expected {
            2 => Dimension::Two,
            3 => Dimension::Three,
            len => return Err(PointsError::UnsupportedDimension { len }),
        };
        let mut points = Vec::with_capacity(raw.len());
        for (index, coordinates) in raw.iter().enumerate() {
            let coordinates = coordinates.as_ref();
            if coordinates.len() != expected {
                return Err(PointsError::WrongDimension {
                    index,
                    len: coordinates.len(),
                    expected,
                });
            }
            let mut point = [0.0; 3];
            for (coordinate, (&value, slot)) in coordinates.iter().zip(&mut point).enumerate() {
                if !value.is_finite() {
                    return Err(PointsError::NonFiniteCoordinate { index, coordinate });
                }
                *slot = value;
            }
            points.push(point);
        }
        let size = bounding_box_diagonal(&points);
        if !size.is_finite() {
            return Err(PointsError::Overflow);
        }
        Ok(PointSet {
            points,
            dimension,
            size,
        })
    }

    /// The points.
    pub fn points(&self) -> &[Point] {
        &self.points
    }

    /// 2D or 3D.
    pub fn dimension(&self) -> Dimension {
        self.dimension
    }

    /// The diagonal of the points' bounding box.
    pub fn size(&self) -> f64 {
        self.size
    }

    /// The centre of the points' bounding box.
    pub fn centre(&self) -> Point {
        let mut low = [f64::INFINITY; 3];
        let mut high = [f64::NEG_INFINITY; 3];
        for point in &self.points {
            for c in 0..3 {
                low[c] = low[c].min(point[c]);
                high[c] = high[c].max(point[c]);
            }
        }
        std::array::from_fn(|c| 0.5 * (low[c] + high[c]))
    }

    /// The largest coordinate magnitude.
    pub fn magnitude(&self) -> f64 {
        self.points
            .iter()
            .flatten()
            .fold(0.0, |m: f64, v| m.max(v.abs()))
    }

    /// How many points.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// Never: a point set has at least two points.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// The first consecutive pair that coincides (within [`COINCIDENT_POINT_TOLERANCE`] of the
    /// size), the closing pair (last, first) included when `closed`.
    pub fn check_distinct_neighbours(&self, closed: bool) -> Result<(), PointsError> {
        let threshold = COINCIDENT_POINT_TOLERANCE * self.size;
        if self.size == 0.0 {
            return Err(PointsError::AllPointsCoincide);
        }
        for index in 1..self.points.len() {
            if distance(self.points[index], self.points[index - 1]) <= threshold {
                return Err(PointsError::CoincidentPoints {
                    index,
                    previous: index - 1,
                    hint: String::new(),
                });
            }
        }
        let last = self.points.len() - 1;
        if closed && distance(self.points[0], self.points[last]) <= threshold {
            return Err(PointsError::CoincidentPoints {
                index: last,
                previous: 0,
                hint: " (for a closed curve give each point once: do not repeat the first point at the end)".to_owned(),
            });
        }
        Ok(())
    }

    /// The parameters of the points by `kind`, on `[0, 1]`: one per point, increasing from 0
    /// to 1 (`ū_0 = 0`, `ū_{m−1} = 1`); for `closed`, one more (1), the parameter at which
    /// the curve returns to the first point, the closing chord counted.
    ///
    /// Consecutive coincident points give equal parameters (allowed for approximation; call
    /// [`PointSet::check_distinct_neighbours`] first where they are not); the total chord
    /// must not vanish.
    pub fn parameters(&self, kind: Parametrization, closed: bool) -> Result<Vec<f64>, PointsError> {
        let points = &self.points;
        let count = points.len();
        let steps = if closed { count } else { count - 1 };
        let step = |k: usize| -> f64 {
            let chord = distance(points[k % count], points[k - 1]);
            match kind {
                Parametrization::ChordLength => chord,
                Parametrization::Centripetal => chord.sqrt(),
                Parametrization::Uniform => 1.0,
            }
        };
        let mut parameters = Vec::with_capacity(steps + 1);
        parameters.push(0.0);
        let mut total = 0.0;
        for k in 1..=steps {
            total += step(k);
            parameters.push(total);
        }
        if !total.is_finite() {
            return Err(PointsError::Overflow);
        }
        if total <= 0.0 {
            return Err(PointsError::AllPointsCoincide);
        }
        for value in &mut parameters {
            *value /= total;
        }
        parameters[steps] = 1.0;
        Ok(parameters)
    }
}

/// Checks parameters given by the caller: `expected` finite values (`reason` says why that
/// many), strictly increasing.
pub fn check_given_parameters(
    parameters: &[f64],
    expected: usize,
    reason: &str,
) -> Result<(), PointsError> {
    if parameters.len() != expected {
        return Err(PointsError::WrongParameterCount {
            count: parameters.len(),
            expected,
            reason: reason.to_owned(),
        });
    }
    for (index, &value) in parameters.iter().enumerate() {
        if !value.is_finite() {
            return Err(PointsError::NonFiniteParameter { index });
        }
        if index > 0 && value <= parameters[index - 1] {
            return Err(PointsError::ParametersNotIncreasing { index });
        }
    }
    Ok(())
}

/// The diagonal of the points' bounding box.
pub(crate) fn bounding_box_diagonal(points: &[Point]) -> f64 {
    let mut min = [f64::INFINITY; 3];
    let mut max = [f64::NEG_INFINITY; 3];
    for point in points {
        for c in 0..3 {
            min[c] = min[c].min(point[c]);
            max[c] = max[c].max(point[c]);
        }
    }
    if points.is_empty() {
        return 0.0;
    }
    distance(min, max)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn set(points: &[[f64; 2]]) -> PointSet {
        PointSet::new(points, 100).unwrap()
    }

    #[test]
    fn chord_length_parameters_follow_the_distances() {
        let points = set(&[[0.0, 0.0], [3.0, 4.0], [3.0, 9.0], [3.0, 19.0]]);
        let t = points
            .parameters(Parametrization::ChordLength, false)
            .unwrap();
        assert_eq!(t, vec![0.0, 0.25, 0.5, 1.0]);
        let closed = points.parameters(Parametrization::Uniform, true).unwrap();
        assert_eq!(closed, vec![0.0, 0.25, 0.5, 0.75, 1.0]);
        let centripetal = set(&[[0.0, 0.0], [4.0, 0.0], [4.0, 1.0]])
            .parameters(Parametrization::Centripetal, false)
            .unwrap();
        assert!((centripetal[1] - 2.0 / 3.0).abs() < 1e-15);
    }

    #[test]
    fn bad_points_are_named() {
        let too_few = PointSet::new(&[[0.0, 0.0]], 10).unwrap_err();
        assert_eq!(too_few.field(), PointsField::Points);
        let mixed: Vec<Vec<f64>> = vec![vec![0.0, 0.0], vec![1.0, 2.0, 3.0]];
        let error = PointSet::new(&mixed, 10).unwrap_err();
        assert_eq!(
            error.field(),
            PointsField::Point {
                index: 1,
                coordinate: None
            }
        );
        let nan = PointSet::new(&[[0.0, 0.0], [1.0, f64::NAN]], 10).unwrap_err();
        assert_eq!(
            nan.field(),
            PointsField::Point {
                index: 1,
                coordinate: Some(1)
            }
        );
        let many = PointSet::new(&[[0.0, 0.0]; 11], 10).unwrap_err();
        assert!(matches!(many, PointsError::TooManyPoints { .. }));
        let repeated = set(&[[0.0, 0.0], [1.0, 0.0], [1.0, 0.0]]);
        let error = repeated.check_distinct_neighbours(false).unwrap_err();
        assert_eq!(
            error.field(),
            PointsField::Point {
                index: 2,
                coordinate: None
            }
        );
        let closing = set(&[[0.0, 0.0], [1.0, 0.0], [0.0, 0.0]]);
        assert!(closing.check_distinct_neighbours(false).is_ok());
        assert!(closing.check_distinct_neighbours(true).is_err());
        assert!(check_given_parameters(&[0.0, 0.5, 0.5], 3, "").is_err());
        assert!(check_given_parameters(&[0.0, 0.5], 3, "").is_err());
        assert!(check_given_parameters(&[0.0, 0.5, 2.0], 3, "").is_ok());
    }
}

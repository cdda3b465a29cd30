//! The control points that no solution of an edit may move (nor change the weight of),
//! validated once from the request's indices.

/// Why a list of fixed control points is malformed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FixedPoleError {
    /// No such control point.
    #[error("control point {index} does not exist: the curve has {count} (indices 0 to {})", count - 1)]
    OutOfRange { index: usize, count: usize },
    /// Listed twice.
    #[error("control point {index} is listed twice (first at fixed_control_points[{first}])")]
    Repeated { index: usize, first: usize },
}

/// The control points that no solution may move (nor change the weight of).
#[derive(Debug, Clone, PartialEq)]
pub struct FixedPoles {
    fixed: Vec<bool>,
}

impl FixedPoles {
    /// None fixed, for a curve with `count` control points.
    pub fn none(count: usize) -> FixedPoles {
        FixedPoles {
            fixed: vec![false; count],
        }
    }

    /// Validates the indices for a curve with `count` control points: each in range, none
    /// repeated (every malformed entry reported with its position in the list).
    pub fn new(
        count: usize,
        indices: &[usize],
    ) -> Result<FixedPoles, Vec<(usize, FixedPoleError)>> {
        let mut fixed = vec![false; count];
        let mut issues = Vec::new();
        for (position, &index) in indices.iter().enumerate() {
            if index >= count {
                issues.push((position, FixedPoleError::OutOfRange { index, count }));
            } else if fixed[index] {
                let first = indices[..position]
                    .iter()
                    .position(|&i| i == index)
                    .unwrap_or(0);
                issues.push((position, FixedPoleError::Repeated { index, first }));
            } else {
                fixed[index] = true;
            }
        }
        if issues.is_empty() {
            Ok(FixedPoles { fixed })
        } else {
            Err(issues)
        }
    }

    /// For a curve with `count` control points, those for which `fixed(index)` holds.
    pub fn from_fn(count: usize, fixed: impl Fn(usize) -> bool) -> FixedPoles {
        FixedPoles {
            fixed: (0..count).map(fixed).collect(),
        }
    }

    /// Whether control point `index` is fixed.
    pub fn is_fixed(&self, index: usize) -> bool {
        self.fixed.get(index).copied().unwrap_or(false)
    }

    /// The number of control points.
    pub fn len(&self) -> usize {
        self.fixed.len()
    }

    /// Whether the curve has no control points (never, for a valid curve).
    pub fn is_empty(&self) -> bool {
        self.fixed.is_empty()
    }

    /// Whether every control point is fixed.
    pub fn all_fixed(&self) -> bool {
        self.fixed.iter().all(|&f| f)
    }
}

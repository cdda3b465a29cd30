//! Conditions that a surface edit keeps (docs/method.md §41): pins and prescribed values of
//! the point (order 0) or of both first partials `S_u, S_v` (order 1) at chosen parameter
//! pairs, and the control points no solution may move (listed ones, or the four boundary
//! rows and columns). Validated once into a [`SurfaceConstraints`] and a [`FixedNet`]; every
//! method's new surface is checked by evaluating it ([`SurfaceConstraints::check`]).

use super::basis::SurfaceBasis;
use crate::shape::{CONSTRAINT_TOLERANCE, FixedPoles, MAX_CONSTRAINTS};
use crate::spline::vector::{Point, distance};
use crate::surface::Surface;

/// A constraint as a client states it, before validation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceConstraintSpec<'a> {
    /// `[u, v]` (inside the domain; snapped onto an end just outside it).
    pub parameter: [f64; 2],
    /// 0 (the point) or 1 (both first partials).
    pub order: u64,
    /// The values: one point for order 0, `[S_u, S_v]` for order 1; `None`: a pin.
    pub value: Option<&'a [Vec<f64>]>,
}

/// The part of a constraint entry an error is about.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SurfaceConstraintField {
    /// The list as a whole.
    List,
    /// The whole entry.
    Entry,
    /// `parameter[c]` (`c = 0` for `u`, `1` for `v`).
    Parameter(usize),
    /// `order`.
    Order,
    /// `value` as a whole.
    Value,
    /// `value[vector]` (for order 1: 0 is `S_u`, 1 is `S_v`).
    ValueVector(usize),
}

/// Why a constraint is malformed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SurfaceConstraintError {
    /// More than [`MAX_CONSTRAINTS`].
    #[error("at most {max} constraints are allowed, not {count}")]
    TooMany { count: usize, max: usize },
    /// Not finite or outside the domain.
    #[error("{name} = {value} lies outside the domain [{}, {}]", domain.0, domain.1)]
    OutsideDomain {
        name: &'static str,
        value: f64,
        domain: (f64, f64),
    },
    /// Orders 0 and 1 only.
    #[error(
        "order {order} is not supported: surface constraints have order 0 (the point) or 1 (both first partials)"
    )]
    UnsupportedOrder { order: u64 },
    /// A point condition at the picked parameter, which the target fixes.
    #[error(
        "a point constraint (order 0) at the picked parameter: the target already fixes that point"
    )]
    PointAtPickedParameter,
    /// Wrong shape of `value`.
    #[error("{0}")]
    ValueShape(String),
    /// A value that is not finite.
    #[error("the value's coordinates must be finite numbers")]
    NonFiniteValue,
    /// The same entry twice.
    #[error("the same constraint as constraints[{first}]")]
    Duplicate { first: usize },
}

/// A malformed constraint: which entry (`None`: the list), which field, and why.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceConstraintIssue {
    /// Position in the list.
    pub index: Option<usize>,
    /// The field at fault.
    pub field: SurfaceConstraintField,
    /// What is wrong.
    pub error: SurfaceConstraintError,
}

/// A validated condition: the new surface must have `values` (one point for order 0,
/// `[S_u, S_v]` for order 1) at `parameter`.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceCondition {
    /// Position in the request's list.
    pub index: usize,
    /// `(u, v)` in the domain.
    pub parameter: (f64, f64),
    /// 0 or 1.
    pub order: usize,
    /// Whether the values are the current ones (no `value` given).
    pub pinned: bool,
    /// What the new surface must have.
    pub values: Vec<Point>,
    /// The current surface's values there.
    pub current: Vec<Point>,
    /// Allowed gap per vector: `CONSTRAINT_TOLERANCE · size · Σ_ij |R_ij^(k,l)|` (for the
    /// point the sum is 1; for partials it carries their scale).
    pub tolerance: Vec<f64>,
}

impl SurfaceCondition {
    /// "the pinned point at (u, v) = (0.2, 0.3) (constraints[1])".
    pub fn describe(&self) -> String {
        let quantity = if self.order == 0 {
            "point"
        } else {
            "first partials"
        };
        let kind = if self.pinned { "pinned" } else { "prescribed" };
        format!(
            "the {kind} {quantity} at (u, v) = ({}, {}) (constraints[{}])",
            self.parameter.0, self.parameter.1, self.index
        )
    }

    /// Whether `values` (the new surface's quantities there) meet the condition.
    pub fn holds(&self, values: &[Point]) -> bool {
        values
            .iter()
            .zip(&self.values)
            .zip(&self.tolerance)
            .all(|((new, wanted), tolerance)| distance(*new, *wanted) <= *tolerance)
    }
}

/// The size the tolerances are relative to: the larger of the net's bounding-box diagonal and
/// its largest coordinate magnitude (as [`crate::shape::edit_size`] for curves).
pub fn surface_edit_size(surface: &Surface) -> f64 {
    surface.size().max(surface.coordinate_magnitude())
}

/// The values of order `order` of `surface` at `(u, v)`: `[S]` or `[S_u, S_v]`.
pub fn surface_values(surface: &Surface, (u, v): (f64, f64), order: usize) -> Vec<Point> {
    let partials = surface.partials(u, v, order);
    if order == 0 {
        vec![partials.point()]
    } else {
        vec![partials.du(), partials.dv()]
    }
}

/// The validated constraints of one request.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SurfaceConstraints {
    conditions: Vec<SurfaceCondition>,
    clash: Option<(usize, usize)>,
}

impl SurfaceConstraints {
    /// No constraints.
    pub fn none() -> SurfaceConstraints {
        SurfaceConstraints::default()
    }

    /// Validates `specs` for `surface` and the picked parameter `(u, v)` (snapped), reporting
    /// every malformed entry. Two entries at the same place and order asking different values
    /// are not malformed: they clash ([`SurfaceConstraints::clash`]).
    pub fn new(
        surface: &Surface,
        picked: (f64, f64),
        specs: &[SurfaceConstraintSpec],
    ) -> Result<SurfaceConstraints, Vec<SurfaceConstraintIssue>> {
        let issue = |index, field, error| SurfaceConstraintIssue {
            index,
            field,
            error,
        };
        if specs.len() > MAX_CONSTRAINTS {
            return Err(vec![issue(
                None,
                SurfaceConstraintField::List,
                SurfaceConstraintError::TooMany {
                    count: specs.len(),
                    max: MAX_CONSTRAINTS,
                },
            )]);
        }
        let mut issues = Vec::new();
        let mut accepted = Vec::new();
        for (index, spec) in specs.iter().enumerate() {
            let before = issues.len();
            let mut parameter = [0.0; 2];
            for (c, (axis, name)) in [(surface.u(), "u"), (surface.v(), "v")]
                .into_iter()
                .enumerate()
            {
                match axis.snap(spec.parameter[c]) {
                    Some(t) => parameter[c] = t,
                    None => issues.push(issue(
                        Some(index),
                        SurfaceConstraintField::Parameter(c),
                        SurfaceConstraintError::OutsideDomain {
                            name,
                            value: spec.parameter[c],
                            domain: axis.domain(),
                        },
                    )),
                }
            }
            if spec.order > 1 {
                issues.push(issue(
                    Some(index),
                    SurfaceConstraintField::Order,
                    SurfaceConstraintError::UnsupportedOrder { order: spec.order },
                ));
            } else if let Some(value) = spec.value {
                let vectors = spec.order as usize + 1;
                if value.len() != vectors {
                    let message = if spec.order == 0 {
                        format!(
                            "an order-0 value is one point [[x, y, z]], not {} vectors",
                            value.len()
                        )
                    } else {
                        format!(
                            "an order-1 value is the two partials [[S_u], [S_v]], not {} vectors",
                            value.len()
                        )
                    };
                    issues.push(issue(
                        Some(index),
                        SurfaceConstraintField::Value,
                        SurfaceConstraintError::ValueShape(message),
                    ));
                } else {
                    for (k, vector) in value.iter().enumerate() {
                        if vector.len() != 3 {
                            issues.push(issue(
                                Some(index),
                                SurfaceConstraintField::ValueVector(k),
                                SurfaceConstraintError::ValueShape(format!(
                                    "a value vector has 3 coordinates, not {}",
                                    vector.len()
                                )),
                            ));
                        } else if vector.iter().any(|x| !x.is_finite()) {
                            issues.push(issue(
                                Some(index),
                                SurfaceConstraintField::ValueVector(k),
                                SurfaceConstraintError::NonFiniteValue,
                            ));
                        }
                    }
                }
            }
            if issues.len() > before {
                continue;
            }
            let parameter = (parameter[0], parameter[1]);
            if spec.order == 0 && parameter == picked {
                issues.push(issue(
                    Some(index),
                    SurfaceConstraintField::Parameter(0),
                    SurfaceConstraintError::PointAtPickedParameter,
                ));
                continue;
            }
            if let Some(first) = specs[..index].iter().position(|other| other == spec) {
                issues.push(issue(
                    Some(index),
                    SurfaceConstraintField::Entry,
                    SurfaceConstraintError::Duplicate { first },
                ));
                continue;
            }
            accepted.push((index, spec, parameter));
        }
        if !issues.is_empty() {
            return Err(issues);
        }
        let size = surface_edit_size(surface);
        let conditions: Vec<SurfaceCondition> = accepted
            .into_iter()
            .map(|(index, spec, parameter)| {
                let order = spec.order as usize;
                let current = surface_values(surface, parameter, order);
                let values = match spec.value {
                    Some(value) => value.iter().map(|v| [v[0], v[1], v[2]]).collect(),
                    None => current.clone(),
                };
                let basis = SurfaceBasis::at(surface, parameter.0, parameter.1);
                let tolerance = if order == 0 {
                    vec![CONSTRAINT_TOLERANCE * size]
                } else {
                    (1..=2)
                        .map(|k| {
                            let scale: f64 = basis.values[k].iter().map(|r| r.abs()).sum();
                            CONSTRAINT_TOLERANCE * size * scale.max(1.0)
                        })
                        .collect()
                };
                SurfaceCondition {
                    index,
                    parameter,
                    order,
                    pinned: spec.value.is_none(),
                    values,
                    current,
                    tolerance,
                }
            })
            .collect();
        let clash = first_clash(&conditions);
        Ok(SurfaceConstraints { conditions, clash })
    }

    /// The conditions, in the request's order.
    pub fn conditions(&self) -> &[SurfaceCondition] {
        &self.conditions
    }

    /// Two conditions at one place and order that ask different values (positions in the
    /// request): no surface meets both.
    pub fn clash(&self) -> Option<(usize, usize)> {
        self.clash
    }

    /// The first condition that `surface` breaks (its position in the request), if any.
    pub fn check(&self, surface: &Surface) -> Result<(), usize> {
        for condition in &self.conditions {
            let values = surface_values(surface, condition.parameter, condition.order);
            if !condition.holds(&values) {
                return Err(condition.index);
            }
        }
        Ok(())
    }
}

/// The first pair of conditions at the same parameter and order whose values differ by more
/// than their tolerance.
fn first_clash(conditions: &[SurfaceCondition]) -> Option<(usize, usize)> {
    for (k, second) in conditions.iter().enumerate() {
        for first in &conditions[..k] {
            if first.parameter == second.parameter
                && first.order == second.order
                && !first.holds(&second.values)
            {
                return Some((first.index, second.index));
            }
        }
    }
    None
}

/// Why a list of fixed control points is malformed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FixedNetError {
    /// No such control point.
    #[error("control point [{i}, {j}] does not exist: the net has {rows} × {columns} (as sent)")]
    OutOfRange {
        i: usize,
        j: usize,
        rows: usize,
        columns: usize,
    },
    /// Listed twice.
    #[error("control point [{i}, {j}] is listed twice (first at fixed_control_points[{first}])")]
    Repeated { i: usize, j: usize, first: usize },
}

/// The control points of a surface that no solution may move (nor change the weight of), in
/// the stored net's flat indices (`i · count_v + j`; a periodic direction's repeated copies
/// of a fixed pole are fixed too).
#[derive(Debug, Clone, PartialEq)]
pub struct FixedNet {
    fixed: FixedPoles,
}

impl FixedNet {
    /// Validates `indices` (the caller's `[i, j]`, periodic directions not repeated) and adds
    /// the boundary rows and columns when `keep_boundary` (those of the non-periodic
    /// directions: a periodic direction has no boundary).
    pub fn new(
        surface: &Surface,
        indices: &[[usize; 2]],
        keep_boundary: bool,
    ) -> Result<FixedNet, Vec<(usize, FixedNetError)>> {
        let (rows, columns) = (surface.u().caller_count(), surface.v().caller_count());
        let mut caller = vec![false; rows * columns];
        let mut issues = Vec::new();
        for (position, &[i, j]) in indices.iter().enumerate() {
            if i >= rows || j >= columns {
                issues.push((
                    position,
                    FixedNetError::OutOfRange {
                        i,
                        j,
                        rows,
                        columns,
                    },
                ));
            } else if caller[i * columns + j] {
                let first = indices[..position]
                    .iter()
                    .position(|&other| other == [i, j])
                    .unwrap_or(0);
                issues.push((position, FixedNetError::Repeated { i, j, first }));
            } else {
                caller[i * columns + j] = true;
            }
        }
        if !issues.is_empty() {
            return Err(issues);
        }
        if keep_boundary {
            let (periodic_u, periodic_v) = (surface.u().is_periodic(), surface.v().is_periodic());
            for i in 0..rows {
                for j in 0..columns {
                    let on_u = !periodic_u && (i == 0 || i + 1 == rows);
                    let on_v = !periodic_v && (j == 0 || j + 1 == columns);
                    caller[i * columns + j] |= on_u || on_v;
                }
            }
        }
        let n_v = surface.v().count();
        let fixed = FixedPoles::from_fn(surface.u().count() * n_v, |flat| {
            let (i, j) = (flat / n_v, flat % n_v);
            caller[(i % rows) * columns + j % columns]
        });
        Ok(FixedNet { fixed })
    }

    /// Nothing fixed.
    pub fn none(surface: &Surface) -> FixedNet {
        FixedNet {
            fixed: FixedPoles::none(surface.u().count() * surface.v().count()),
        }
    }

    /// Whether the stored pole at flat index `i · count_v + j` is fixed.
    pub fn is_fixed(&self, flat: usize) -> bool {
        self.fixed.is_fixed(flat)
    }

    /// The fixed poles as the curves' [`FixedPoles`] over flat indices.
    pub fn poles(&self) -> &FixedPoles {
        &self.fixed
    }
}

/// The caller's index `[i, j]` of the stored pole at `flat` (periodic copies folded back).
pub fn caller_index(surface: &Surface, flat: usize) -> [usize; 2] {
    let n_v = surface.v().count();
    [
        (flat / n_v) % surface.u().caller_count(),
        (flat % n_v) % surface.v().caller_count(),
    ]
}

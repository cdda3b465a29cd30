//! Conditions that a shape edit keeps (docs/method.md §19): pins and prescribed values of the
//! curve's point and first two derivatives at chosen parameters, kept tangent directions, and
//! fixed control points. Validated once into a [`ConstraintSet`] and [`FixedPoles`] (in
//! fixed_poles.rs), so every method sees the same checked list; a method's new curve is
//! checked against the set by evaluating it ([`ConstraintSet::check`]).

use crate::spline::vector::{Point, dot, norm, scale, sub};
use crate::spline::{Curve, MAX_BASIS_ORDER};

pub use super::fixed_poles::{FixedPoleError, FixedPoles};

/// How closely a returned solution meets every condition, relative to the curve's size
/// ([`edit_size`]): a condition of order `r` at `u` holds when
/// `|s^(r)(u) - v| <= CONSTRAINT_TOLERANCE · size · Σ_i |R_i^(r)(u)|` (for `r = 0` the sum is 1;
/// for derivatives it carries their units and scale, `1 / h^r` on a span of length `h`). A kept
/// direction holds when the tangent's component across the direction is within the same bound
/// and its component along it is positive beyond that bound (a vanishing tangent keeps no
/// direction). The target itself is met within
/// `CONSTRAINT_TOLERANCE · size` (the knot pairs are stricter, [`super::RESIDUAL_TOLERANCE`]).
pub const CONSTRAINT_TOLERANCE: f64 = 1e-9;

/// The most constraints one request may give (each adds a few rows to the control-point
/// system, whose solution costs the cube of their number).
pub const MAX_CONSTRAINTS: usize = 32;

/// A constraint as a client states it, before validation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConstraintSpec<'a> {
    /// The parameter `u` (inside the domain; snapped onto an end just outside it).
    pub parameter: f64,
    /// 0 (the point), 1 or 2 (the first, second derivative with respect to the parameter).
    pub order: u64,
    /// The value the quantity must take; `None`: it keeps its current value (a pin).
    pub value: Option<&'a [f64]>,
    /// Order 1 only: keep (or prescribe) only the tangent's direction, not its length.
    pub direction_only: bool,
}

/// The part of a constraint entry that an error is about.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ConstraintField {
    /// The list as a whole.
    List,
    /// The whole entry.
    Entry,
    /// `parameter`.
    Parameter,
    /// `order`.
    Order,
    /// `value` as a whole.
    Value,
    /// One coordinate of `value`.
    ValueCoordinate(usize),
    /// `direction_only`.
    DirectionOnly,
}

/// Why a constraint is malformed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ConstraintError {
    /// More than [`MAX_CONSTRAINTS`].
    #[error("at most {max} constraints are allowed, not {count}")]
    TooMany { count: usize, max: usize },
    /// The parameter is NaN or infinite.
    #[error("the constraint's parameter is not a finite number")]
    NonFiniteParameter,
    /// The parameter lies outside the domain.
    #[error("parameter {value} lies outside the domain [{}, {}]", domain.0, domain.1)]
    ParameterOutsideDomain { value: f64, domain: (f64, f64) },
    /// Orders are 0, 1 or 2.
    #[error(
        "order {order} is not supported: constraints have order 0 (the point), 1 or 2 (the first, second derivative)"
    )]
    UnsupportedOrder { order: u64 },
    /// The derivative of that order vanishes identically.
    #[error("order {order} is above the curve's degree {degree}")]
    OrderAboveDegree { order: u64, degree: usize },
    /// A point condition at the picked parameter, which the target already fixes.
    #[error(
        "a point constraint (order 0) at the picked parameter: the target already fixes that point"
    )]
    PointAtPickedParameter,
    /// `value` has the wrong number of coordinates.
    #[error("the value has {found} coordinates; the curve's control points have {expected}")]
    ValueDimension { expected: usize, found: usize },
    /// A coordinate of `value` is not finite.
    #[error("value coordinate {coordinate} is not a finite number")]
    NonFiniteValue { coordinate: usize },
    /// `direction_only` on a point or second derivative.
    #[error("`direction_only` applies to tangents (order 1), not to order {order}")]
    DirectionOnlyOrder { order: u64 },
    /// A direction of length zero.
    #[error("a direction (`direction_only` with a `value`) must not be the zero vector")]
    ZeroDirection,
    /// The same entry twice.
    #[error("the same constraint as constraints[{first}]")]
    Duplicate { first: usize },
}

/// A malformed constraint: which entry (`None`: the list), which field, and why.
#[derive(Debug, Clone, PartialEq)]
pub struct ConstraintIssue {
    /// Position in the list.
    pub index: Option<usize>,
    /// The field at fault.
    pub field: ConstraintField,
    /// What is wrong.
    pub error: ConstraintError,
}

/// What a condition requires of the new curve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Requirement {
    /// `s^(r)(u)` equals this vector (the current value for a pin).
    Value(Point),
    /// `s'(u)` is a positive multiple of this unit vector.
    Direction(Point),
    /// A kept direction of a tangent that vanishes on the current curve: there is none.
    UndefinedDirection,
}

/// A validated constraint with what it requires and how closely.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Condition {
    /// Position in the request's list.
    pub index: usize,
    /// The parameter `u` (in the domain).
    pub parameter: f64,
    /// 0, 1 or 2.
    pub order: usize,
    /// Whether it keeps the current value (no `value` given).
    pub pinned: bool,
    /// What the new curve must satisfy.
    pub requirement: Requirement,
    /// `s^(r)(u)` on the current curve.
    pub current: Point,
    /// The allowed gap ([`CONSTRAINT_TOLERANCE`]).
    pub tolerance: f64,
}

impl Condition {
    /// A short description: "the pinned first derivative at u = 0.8 (constraints[2])".
    pub fn describe(&self) -> String {
        let quantity = match (self.order, &self.requirement) {
            (1, Requirement::Direction(_) | Requirement::UndefinedDirection) => "tangent direction",
            (0, _) => "point",
            (1, _) => "first derivative",
            _ => "second derivative",
        };
        let kind = if self.pinned { "pinned" } else { "prescribed" };
        format!(
            "the {kind} {quantity} at u = {} (constraints[{}])",
            self.parameter, self.index
        )
    }
}

/// How a new curve fails a condition.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Breach {
    /// The quantity misses its value (or direction) by more than the tolerance.
    Missed {
        /// The condition's position in the request.
        index: usize,
    },
    /// The tangent points the other way.
    Reversed {
        /// The condition's position in the request.
        index: usize,
    },
    /// The new curve's domain no longer holds the parameter (a knot edit without
    /// `keep_domain`).
    OutsideDomain {
        /// The condition's position in the request.
        index: usize,
    },
}

impl Breach {
    /// The position in the request of the condition that fails.
    pub fn index(&self) -> usize {
        match *self {
            Breach::Missed { index }
            | Breach::Reversed { index }
            | Breach::OutsideDomain { index } => index,
        }
    }
}

/// The size that [`CONSTRAINT_TOLERANCE`] is relative to: the larger of the control points'
/// bounding-box diagonal and their largest coordinate magnitude (the latter keeps the bound
/// above the rounding of far-off coordinates).
pub fn edit_size(curve: &Curve) -> f64 {
    let points = curve.control_points();
    let mut low = [f64::INFINITY; 3];
    let mut high = [f64::NEG_INFINITY; 3];
    let mut magnitude = 0.0f64;
    for point in points {
        for c in 0..3 {
            low[c] = low[c].min(point[c]);
            high[c] = high[c].max(point[c]);
            magnitude = magnitude.max(point[c].abs());
        }
    }
    norm(sub(high, low)).max(magnitude)
}

/// The validated constraints of one request.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ConstraintSet {
    conditions: Vec<Condition>,
    /// The first two conditions that cannot both hold, by position in the request.
    clash: Option<(usize, usize)>,
}

impl ConstraintSet {
    /// No constraints.
    pub fn none() -> ConstraintSet {
        ConstraintSet::default()
    }

    /// Validates `specs` against `curve` and the picked parameter `t` (every malformed entry is
    /// reported), and works out what each requires on the current curve. A pin and a different
    /// value at the same place are not malformed: they clash ([`ConstraintSet::clash`]).
    pub fn new(
        curve: &Curve,
        t: f64,
        specs: &[ConstraintSpec],
    ) -> Result<ConstraintSet, Vec<ConstraintIssue>> {
        if specs.len() > MAX_CONSTRAINTS {
            return Err(vec![ConstraintIssue {
                index: None,
                field: ConstraintField::List,
                error: ConstraintError::TooMany {
                    count: specs.len(),
                    max: MAX_CONSTRAINTS,
                },
            }]);
        }
        let mut issues = Vec::new();
        let mut parameters = Vec::with_capacity(specs.len());
        for (index, spec) in specs.iter().enumerate() {
            let mut issue = |field, error| {
                issues.push(ConstraintIssue {
                    index: Some(index),
                    field,
                    error,
                })
            };
            let parameter = check_spec(curve, t, spec, &mut issue);
            parameters.push(parameter);
            if let Some(first) = specs[..index].iter().position(|other| other == spec) {
                issue(ConstraintField::Entry, ConstraintError::Duplicate { first });
            }
        }
        if !issues.is_empty() {
            return Err(issues);
        }
        let size = edit_size(curve);
        let conditions = specs
            .iter()
            .zip(parameters)
            .enumerate()
            .map(|(index, (spec, parameter))| {
                condition(curve, index, spec, parameter.unwrap_or(t), size)
            })
            .collect::<Vec<_>>();
        let clash = first_clash(&conditions);
        Ok(ConstraintSet { conditions, clash })
    }

    /// The same conditions at other parameters, `parameter(u)` for each `u` (e.g. the
    /// window parameters of a periodic curve cut open elsewhere: the curve, so what each
    /// condition requires, is the same there).
    pub fn with_parameters(&self, parameter: impl Fn(f64) -> f64) -> ConstraintSet {
        ConstraintSet {
            conditions: self
                .conditions
                .iter()
                .map(|condition| Condition {
                    parameter: parameter(condition.parameter),
                    ..*condition
                })
                .collect(),
            clash: self.clash,
        }
    }

    /// The conditions, in the request's order.
    pub fn conditions(&self) -> &[Condition] {
        &self.conditions
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.conditions.is_empty()
    }

    /// Two conditions at the same parameter and order that no curve meets together (positions
    /// in the request), e.g. a pin and a different prescribed value.
    pub fn clash(&self) -> Option<(usize, usize)> {
        self.clash
    }

    /// A kept direction whose tangent vanishes on the current curve, if any.
    pub fn undefined_direction(&self) -> Option<&Condition> {
        self.conditions
            .iter()
            .find(|c| c.requirement == Requirement::UndefinedDirection)
    }

    /// The condition at a position of the request.
    pub fn by_index(&self, index: usize) -> Option<&Condition> {
        self.conditions.iter().find(|c| c.index == index)
    }

    /// Whether every condition surely holds on any edit of `curve` that changes it only on
    /// `affected = [lo, hi]` (a conservative test, for drawing only what solving reaches):
    /// each holds on `curve` itself, and lies where such an edit leaves the curve alone.
    /// Outside `[lo, hi]` the edit is the old curve. At `lo` or `hi` so is its point where the
    /// curve is continuous there (an end of the domain, or a knot of multiplicity at most the
    /// degree), but not necessarily its derivatives; inside, anything may change.
    pub fn surely_kept_outside(&self, curve: &Curve, affected: (f64, f64)) -> bool {
        if self.clash.is_some()
            || self
                .check_values(|condition| Some(condition.current))
                .is_err()
        {
            return false;
        }
        let (lo, hi) = affected;
        let (start, end) = curve.domain();
        let continuous_at = |u: f64| {
            u == start
                || u == end
                || curve.knots().iter().filter(|&&knot| knot == u).count() <= curve.degree()
        };
        self.conditions.iter().all(|condition| {
            let u = condition.parameter;
            u < lo || u > hi || ((u == lo || u == hi) && condition.order == 0 && continuous_at(u))
        })
    }

    /// Checks every condition on `curve` (a new curve of the edit), evaluated by the spline
    /// core: the first condition it breaks, if any.
    pub fn check(&self, curve: &Curve) -> Result<(), Breach> {
        self.check_values(|condition| {
            let mut values = [[0.0; 3]; MAX_BASIS_ORDER + 1];
            let values = &mut values[..=condition.order];
            curve
                .derivatives(condition.parameter, values)
                .ok()
                .map(|()| values[condition.order])
        })
    }

    /// Checks every condition against the new curve's value of its quantity, as `value_of`
    /// gives it (`None`: the parameter is outside the new curve's domain).
    pub fn check_values(
        &self,
        mut value_of: impl FnMut(&Condition) -> Option<Point>,
    ) -> Result<(), Breach> {
        for condition in &self.conditions {
            let index = condition.index;
            let Some(value) = value_of(condition) else {
                return Err(Breach::OutsideDomain { index });
            };
            match condition.requirement {
                Requirement::Value(required) => {
                    let gap = norm(sub(value, required));
                    if gap.is_nan() || gap > condition.tolerance {
                        return Err(Breach::Missed { index });
                    }
                }
                Requirement::Direction(unit) => {
                    let along = dot(value, unit);
                    let across = norm(sub(value, scale(unit, along)));
                    if across.is_nan() || across > condition.tolerance {
                        return Err(Breach::Missed { index });
                    }
                    // A tangent that vanishes (within the tolerance) has no direction.
                    if along.is_nan() || along <= condition.tolerance {
                        return Err(Breach::Reversed { index });
                    }
                }
                Requirement::UndefinedDirection => return Err(Breach::Missed { index }),
            }
        }
        Ok(())
    }
}

/// Checks one entry (reporting each problem through `issue`); the parameter snapped onto the
/// domain when it is valid.
fn check_spec(
    curve: &Curve,
    t: f64,
    spec: &ConstraintSpec,
    issue: &mut impl FnMut(ConstraintField, ConstraintError),
) -> Option<f64> {
    let parameter = if !spec.parameter.is_finite() {
        issue(
            ConstraintField::Parameter,
            ConstraintError::NonFiniteParameter,
        );
        None
    } else {
        let snapped = curve.snap_to_domain(spec.parameter);
        if snapped.is_none() {
            issue(
                ConstraintField::Parameter,
                ConstraintError::ParameterOutsideDomain {
                    value: spec.parameter,
                    domain: curve.domain(),
                },
            );
        }
        snapped
    };
    let order = spec.order;
    if order > MAX_BASIS_ORDER as u64 {
        issue(
            ConstraintField::Order,
            ConstraintError::UnsupportedOrder { order },
        );
    } else if order > curve.degree() as u64 {
        issue(
            ConstraintField::Order,
            ConstraintError::OrderAboveDegree {
                order,
                degree: curve.degree(),
            },
        );
    }
    if order == 0 && parameter == Some(t) {
        issue(
            ConstraintField::Parameter,
            ConstraintError::PointAtPickedParameter,
        );
    }
    if spec.direction_only && order != 1 {
        issue(
            ConstraintField::DirectionOnly,
            ConstraintError::DirectionOnlyOrder { order },
        );
    }
    if let Some(value) = spec.value {
        let expected = curve.dimension().count();
        if value.len() != expected {
            issue(
                ConstraintField::Value,
                ConstraintError::ValueDimension {
                    expected,
                    found: value.len(),
                },
            );
        } else if let Some(coordinate) = value.iter().position(|v| !v.is_finite()) {
            issue(
                ConstraintField::ValueCoordinate(coordinate),
                ConstraintError::NonFiniteValue { coordinate },
            );
        } else if spec.direction_only && value.iter().all(|&v| v == 0.0) {
            issue(ConstraintField::Value, ConstraintError::ZeroDirection);
        }
    }
    parameter
}

/// What a valid entry requires on `curve`.
fn condition(
    curve: &Curve,
    index: usize,
    spec: &ConstraintSpec,
    parameter: f64,
    size: f64,
) -> Condition {
    let order = spec.order as usize;
    let mut values = [[0.0; 3]; MAX_BASIS_ORDER + 1];
    // The parameter is in the domain: evaluation cannot fail.
    let _ = curve.derivatives(parameter, &mut values[..=order]);
    let current = values[order];
    let basis = curve.rational_basis_derivatives(parameter, order);
    let spread: f64 = basis.rows[order][..=curve.degree()]
        .iter()
        .map(|r| r.abs())
        .sum();
    let tolerance = CONSTRAINT_TOLERANCE * size * spread.max(f64::MIN_POSITIVE);
    let value = spec.value.map(|v| {
        let mut point = [0.0; 3];
        point[..v.len()].copy_from_slice(v);
        point
    });
    let requirement = if spec.direction_only {
        let direction = value.unwrap_or(current);
        let length = norm(direction);
        if value.is_none() && (length.is_nan() || length <= tolerance) {
            Requirement::UndefinedDirection
        } else {
            Requirement::Direction(scale(direction, 1.0 / length))
        }
    } else {
        Requirement::Value(value.unwrap_or(current))
    };
    Condition {
        index,
        parameter,
        order,
        pinned: spec.value.is_none(),
        requirement,
        current,
        tolerance,
    }
}

/// The first pair of conditions at the same parameter and order that cannot hold together.
fn first_clash(conditions: &[Condition]) -> Option<(usize, usize)> {
    for (i, first) in conditions.iter().enumerate() {
        for second in &conditions[i + 1..] {
            if first.parameter != second.parameter || first.order != second.order {
                continue;
            }
            let tolerance = first.tolerance.max(second.tolerance);
            if !compatible(first.requirement, second.requirement, tolerance) {
                return Some((first.index, second.index));
            }
        }
    }
    None
}

/// Whether one vector can meet both requirements.
fn compatible(first: Requirement, second: Requirement, tolerance: f64) -> bool {
    use Requirement::{Direction, UndefinedDirection, Value};
    match (first, second) {
        (Value(a), Value(b)) => norm(sub(a, b)) <= tolerance,
        (Value(v), Direction(e)) | (Direction(e), Value(v)) => {
            let along = dot(v, e);
            along > 0.0 && norm(sub(v, scale(e, along))) <= tolerance
        }
        (Direction(a), Direction(b)) => norm(sub(a, b)) <= DIRECTION_MATCH,
        // Reported on its own (there is no direction to keep).
        (UndefinedDirection, _) | (_, UndefinedDirection) => true,
    }
}

/// Two unit directions closer than this are the same direction.
const DIRECTION_MATCH: f64 = 1e-12;

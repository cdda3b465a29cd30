//! The other way to move a curve point: move control points instead of knots, by the least
//! change of the free poles that puts `s(t)` on the target and meets every constraint (Fowler &
//! Bartels 1993; The NURBS Book §11.5; docs/method.md §19).
//!
//! With fixed knots and weights every derivative is linear in the poles,
//! `s^(r)(u) = Σ_i R_i^(r)(u) d_i` ([`Curve::rational_basis_derivatives`]). The target and the
//! constraints are therefore a linear system `B Δ = c` in the displacements `Δ` of the free
//! poles: one row per condition and coordinate (`s(t) = p`, a pin `Δs^(r)(u) = 0`, a value
//! `Δs^(r)(u) = v - s^(r)(u)`), and for a kept tangent direction `e` the `dims - 1` rows
//! `n · Δs'(u) = -n · s'(u)` for the normals `n ⟂ e`. Its least-norm solution
//! `Δ = Bᵀ (B Bᵀ)⁻¹ c` (of `Σ |Δd_i|²`) comes from a rank-revealing factorisation
//! ([`super::least_norm`]); without direction rows the coordinates separate and share one
//! factorisation. Without constraints it is the single row `Σ_I R_i Δd_i = p - s(t)`:
//!
//! ```text
//! Δd_i = R_i(t) / Σ_{k∈I} R_k(t)² · (p - s(t))
//! ```
//!
//! (every displacement parallel to `p - s(t)`; it reaches every target). Open CASCADE's
//! `Geom_BSplineCurve::MovePoint` and `MovePointAndTangent` move poles too, with their own
//! weighting. The new curve is evaluated by the spline core and every condition re-checked; a
//! move that fails (dependent rows that disagree, or rounding on an ill-conditioned system) is
//! not returned.

use super::constraints::{
    CONSTRAINT_TOLERANCE, Condition, ConstraintSet, FixedPoles, Requirement, edit_size,
};
use super::deviation::max_deviation_of_moved_poles;
use super::least_norm::DenseSystem;
use super::method::{
    EditContext, EditMethod, EditSolution, MethodFailure, MethodKind, MethodMembership,
    MethodNearest, MethodSolutions, Reachable, SolutionDetail,
};
use super::regions::PolygonOptions;
use super::solve::ShapeError;
use crate::spline::vector::{Point, cross, distance, dot, norm, scale, sub};
use crate::spline::{Curve, RationalBasis};

/// The unconstrained move's new point at `t` must lie within `CONTROL_POINT_RESIDUAL · size`
/// of the target (`size`: the largest coordinate of the moved poles and the target, at least
/// 1), else the move is refused as ill-conditioned (it never is for finite input: a guard).
pub const CONTROL_POINT_RESIDUAL: f64 = 1e-9;

/// A pole displacement shorter than this fraction of the curve's size (and the target's
/// distance from the origin) is rounding: the pole stays where it is.
pub const DISPLACEMENT_ROUNDING: f64 = 4.0 * f64::EPSILON;

/// The control-point move that puts `s(t)` on a target.
#[derive(Debug, Clone, PartialEq)]
pub struct ControlPointSolution {
    /// The whole new list of control points.
    pub control_points: Vec<Point>,
    /// Indices of the control points that moved, ascending.
    pub changed_control_points: Vec<usize>,
    /// The new curve's point at `t`.
    pub point: Point,
    /// `|point - target|`.
    pub residual: f64,
    /// `[lo, hi]`: outside it the new curve equals the old one.
    pub affected_domain: (f64, f64),
    /// Largest `|s_old(u) - s_new(u)|` over the domain, when measured.
    pub max_deviation: Option<f64>,
}

/// Why the constrained move has no solution.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ControlPointFailure {
    /// Every control point is fixed.
    NoFreeControlPoint,
    /// Every control point acting at `t` is fixed (and the target is not the current point).
    NoFreeControlPointAtTarget,
    /// The free poles cannot meet the target and the constraints together (dependent
    /// conditions that disagree, or more conditions than the free poles can meet).
    Unmet,
}

/// The free pole *variables* of the move: each is one column of the system and moves one or
/// more control points together by the same displacement.
///
/// Today every free control point is its own variable. The seam for periodic curves: the
/// repeated poles of a periodic curve in unclamped form (the first `p` equal to the last `p`)
/// become one variable each, so the move keeps them equal. A variable of `m` poles counts `m`
/// times in the norm `Σ_i |Δd_i|²`; the system scales its column by `1/√m` for that.
#[derive(Debug, Clone, PartialEq)]
pub struct PoleVariables {
    /// The variable of each control point (`None`: fixed).
    variable_of: Vec<Option<usize>>,
    /// The number of control points of each variable.
    multiplicity: Vec<usize>,
    /// `1 / √multiplicity` of each variable: its column's scale.
    column_scale: Vec<f64>,
}

impl PoleVariables {
    /// One variable per control point that is not fixed.
    pub fn free_poles(fixed: &FixedPoles) -> PoleVariables {
        let mut variable_of = Vec::with_capacity(fixed.len());
        let mut multiplicity = Vec::new();
        for index in 0..fixed.len() {
            if fixed.is_fixed(index) {
                variable_of.push(None);
            } else {
                variable_of.push(Some(multiplicity.len()));
                multiplicity.push(1);
            }
        }
        let column_scale = multiplicity
            .iter()
            .map(|&m| 1.0 / (m as f64).sqrt())
            .collect();
        PoleVariables {
            variable_of,
            multiplicity,
            column_scale,
        }
    }

    /// One variable per group of free control points: `group(index)` names the group of each
    /// (a periodic curve's copies of one control point share a group). Unlike a tied run of
    /// [`PoleVariables`] in general, each group counts once in the norm (column scale 1): it is
    /// one control point that the data happen to hold several times. A group with a fixed
    /// member is fixed.
    pub fn tied(fixed: &FixedPoles, group: impl Fn(usize) -> usize) -> PoleVariables {
        let groups: Vec<usize> = (0..fixed.len()).map(&group).collect();
        let group_count = groups.iter().max().map_or(0, |&g| g + 1);
        let mut group_fixed = vec![false; group_count];
        for (index, &g) in groups.iter().enumerate() {
            group_fixed[g] |= fixed.is_fixed(index);
        }
        let mut variable_of_group = vec![None; group_count];
        let mut multiplicity = Vec::new();
        let mut variable_of = Vec::with_capacity(fixed.len());
        for &g in &groups {
            if group_fixed[g] {
                variable_of.push(None);
                continue;
            }
            let variable = *variable_of_group[g].get_or_insert_with(|| {
                multiplicity.push(0);
                multiplicity.len() - 1
            });
            multiplicity[variable] += 1;
            variable_of.push(Some(variable));
        }
        let column_scale = vec![1.0; multiplicity.len()];
        PoleVariables {
            variable_of,
            multiplicity,
            column_scale,
        }
    }

    /// The variable that moves control point `index`, if it is free.
    pub fn variable_of(&self, index: usize) -> Option<usize> {
        self.variable_of.get(index).copied().flatten()
    }

    /// The number of variables.
    pub fn count(&self) -> usize {
        self.multiplicity.len()
    }
}

/// The least-squares pole move (module docs) that puts the point at `t` of `curve` on
/// `target`, with every pole free and no constraint; the new point is evaluated with the
/// spline core. `None` only when the numbers overflow. Preconditions: `t` in the domain,
/// `target` finite with `z = 0` for planar curves.
pub fn control_point_move(
    curve: &Curve,
    t: f64,
    target: Point,
    measure_deviation: bool,
) -> Option<ControlPointSolution> {
    let fixed = FixedPoles::none(curve.control_points().len());
    let variables = PoleVariables::free_poles(&fixed);
    let solution = constrained_control_point_move(
        curve,
        t,
        target,
        &ConstraintSet::none(),
        &variables,
        measure_deviation,
    )
    .ok()?;
    // The guard of the second release: relative to the moved poles' and the target's largest
    // coordinate (at least 1).
    let size = solution
        .control_points
        .iter()
        .flatten()
        .chain(target.iter())
        .fold(1.0f64, |m, v| m.max(v.abs()));
    (solution.residual <= CONTROL_POINT_RESIDUAL * size).then_some(solution)
}

/// One scalar condition `Σ_k coefficient_k Δ_k = rhs` over the variables, for every
/// coordinate (or, for a kept direction, the rows across it).
struct Row {
    basis: RationalBasis,
    order: usize,
    /// The change the condition asks of `s^(order)(u)`.
    change: Point,
    /// For a kept direction: the unit direction `e`; the rows are `n · Δs' = n · change`.
    direction: Option<Point>,
}

/// The least-norm move of the free poles (module docs) that puts `s(t)` on `target` and meets
/// every condition of `constraints`, verified on the new curve.
///
/// Preconditions: `t` in the domain, `target` finite with `z = 0` for planar curves, the
/// constraints validated for this curve and `t`, and no clash among them.
pub fn constrained_control_point_move(
    curve: &Curve,
    t: f64,
    target: Point,
    constraints: &ConstraintSet,
    variables: &PoleVariables,
    measure_deviation: bool,
) -> Result<ControlPointSolution, ControlPointFailure> {
    if variables.count() == 0 {
        return Err(ControlPointFailure::NoFreeControlPoint);
    }
    let current = curve.point_unchecked(t);
    let mut rows = Vec::with_capacity(1 + constraints.conditions().len());
    rows.push(Row {
        basis: curve.rational_basis_derivatives(t, 0),
        order: 0,
        change: sub(target, current),
        direction: None,
    });
    for condition in constraints.conditions() {
        rows.push(condition_row(curve, condition));
    }
    let p = curve.degree();
    // The columns: variables acting on some row (the others stay put in the least-norm move).
    let mut column_of = vec![usize::MAX; variables.count()];
    let mut columns = Vec::new();
    for row in &rows {
        for k in 0..=p {
            if row.basis.rows[row.order][k] == 0.0 {
                continue;
            }
            if let Some(variable) = variables.variable_of(row.basis.first + k) {
                if column_of[variable] == usize::MAX {
                    column_of[variable] = columns.len();
                    columns.push(variable);
                }
            }
        }
    }
    let target_moves = rows[0].change != [0.0; 3];
    let target_column_free = (0..=p).any(|k| {
        rows[0].basis.rows[0][k] != 0.0 && variables.variable_of(rows[0].basis.first + k).is_some()
    });
    if target_moves && !target_column_free {
        return Err(ControlPointFailure::NoFreeControlPointAtTarget);
    }
    let dims = curve.dimension().count();
    let size = edit_size(curve).max(norm(target));
    let displacements = solve_rows(curve, &rows, variables, &column_of, columns.len(), dims);
    let mut control_points = curve.control_points().to_vec();
    let mut changed_control_points = Vec::new();
    for (index, point) in control_points.iter_mut().enumerate() {
        let Some(variable) = variables.variable_of(index) else {
            continue;
        };
        let column = column_of[variable];
        if column == usize::MAX {
            continue;
        }
        let delta = displacements[column];
        // A displacement within rounding of zero (a pole the conditions hold still) is none.
        if norm(delta) > DISPLACEMENT_ROUNDING * size {
            for c in 0..dims {
                point[c] += delta[c];
            }
            changed_control_points.push(index);
        }
    }
    let moved = curve
        .with_control_points(control_points)
        .ok_or(ControlPointFailure::Unmet)?;
    let point = moved.point_unchecked(t);
    let residual = distance(point, target);
    // Every condition on the new poles: with the knots and weights kept, the new value of
    // `s^(r)(u)` is `Σ_i R_i^(r)(u) d_i` over the same basis (rows 1.. are the conditions',
    // in order).
    let new_values = |condition: &Condition| {
        let position = constraints
            .conditions()
            .iter()
            .position(|c| c.index == condition.index)?;
        let row = &rows[position + 1];
        let points = moved.control_points();
        let mut value = [0.0; 3];
        for k in 0..=p {
            let r = row.basis.rows[row.order][k];
            for c in 0..3 {
                value[c] += r * points[row.basis.first + k][c];
            }
        }
        Some(value)
    };
    if residual.is_nan()
        || residual > CONSTRAINT_TOLERANCE * size
        || constraints.check_values(new_values).is_err()
    {
        return Err(ControlPointFailure::Unmet);
    }
    let affected_domain = affected_domain_of_poles(curve, &changed_control_points);
    let max_deviation =
        measure_deviation.then(|| max_deviation_of_moved_poles(curve, &moved, affected_domain));
    Ok(ControlPointSolution {
        control_points: moved.control_points().to_vec(),
        changed_control_points,
        point,
        residual,
        affected_domain,
        max_deviation,
    })
}

/// The row of one validated condition.
fn condition_row(curve: &Curve, condition: &Condition) -> Row {
    let basis = curve.rational_basis_derivatives(condition.parameter, condition.order);
    let (change, direction) = match condition.requirement {
        Requirement::Value(value) => (sub(value, condition.current), None),
        // The rows across `e` ask `n · Δs' = -n · s'`; `change = -s'` carries that.
        Requirement::Direction(unit) => (scale(condition.current, -1.0), Some(unit)),
        // Never solved: the edit reports it first. A pin keeps the system consistent.
        Requirement::UndefinedDirection => ([0.0; 3], None),
    };
    Row {
        basis,
        order: condition.order,
        change,
        direction,
    }
}

/// Unit normals spanning the directions across `e` in `dims` dimensions.
fn normals_across(e: Point, dims: usize) -> Vec<Point> {
    if dims == 2 {
        return vec![[-e[1], e[0], 0.0]];
    }
    // The axis least aligned with e, crossed with e, and e crossed with that.
    let axis = (0..3)
        .min_by(|&a, &b| e[a].abs().total_cmp(&e[b].abs()))
        .unwrap_or(0);
    let mut unit = [0.0; 3];
    unit[axis] = 1.0;
    let first = cross(e, unit);
    let first = scale(first, 1.0 / norm(first));
    let second = cross(e, first);
    vec![first, scale(second, 1.0 / norm(second))]
}

/// The least-norm displacement of each column's variable (`[0; 3]` beyond `dims`).
fn solve_rows(
    curve: &Curve,
    rows: &[Row],
    variables: &PoleVariables,
    column_of: &[usize],
    columns: usize,
    dims: usize,
) -> Vec<Point> {
    let p = curve.degree();
    let coefficients = |row| coefficients(row, variables, column_of, p);
    // Δ = y / √m for the solution y of the scaled columns.
    let unscale = |variable: usize, value: f64| value * variables.column_scale[variable];
    let column_variables: Vec<usize> = {
        let mut v = vec![0; columns];
        for (variable, &column) in column_of.iter().enumerate() {
            if column != usize::MAX {
                v[column] = variable;
            }
        }
        v
    };
    let mut displacements = vec![[0.0; 3]; columns];
    if let [row] = rows {
        if row.direction.is_none() {
            // One condition (the target alone): the closed form of the module docs, over
            // the scaled columns, `y_j = a_j c / Σ_k a_k²`.
            let mut coefficient = vec![0.0; columns];
            for (column, value) in coefficients(row) {
                coefficient[column] += value;
            }
            let squares: f64 = coefficient.iter().map(|a| a * a).sum();
            if squares > 0.0 {
                for (column, displacement) in displacements.iter_mut().enumerate() {
                    let factor = unscale(column_variables[column], coefficient[column] / squares);
                    for (c, value) in displacement.iter_mut().take(dims).enumerate() {
                        *value = factor * row.change[c];
                    }
                }
            }
            return displacements;
        }
    }
    if rows.iter().all(|row| row.direction.is_none()) {
        // The coordinates separate: one system, `dims` right-hand sides.
        let mut system = DenseSystem::zeros(rows.len(), columns, dims);
        for (r, row) in rows.iter().enumerate() {
            for (column, value) in coefficients(row) {
                *system.coefficient_mut(r, column) += value;
            }
            for c in 0..dims {
                *system.rhs_mut(r, c) = row.change[c];
            }
        }
        let solution = system.solve();
        for (column, displacement) in displacements.iter_mut().enumerate() {
            for (c, value) in displacement.iter_mut().take(dims).enumerate() {
                *value = unscale(column_variables[column], solution.x[column * dims + c]);
            }
        }
        return displacements;
    }
    // Coupled: unknown (column, coordinate) at column * dims + coordinate.
    let count: usize = rows
        .iter()
        .map(|row| {
            if row.direction.is_some() {
                dims - 1
            } else {
                dims
            }
        })
        .sum();
    let mut system = DenseSystem::zeros(count, columns * dims, 1);
    let mut r = 0;
    for row in rows {
        match row.direction {
            None => {
                for c in 0..dims {
                    for (column, value) in coefficients(row) {
                        *system.coefficient_mut(r, column * dims + c) += value;
                    }
                    *system.rhs_mut(r, 0) = row.change[c];
                    r += 1;
                }
            }
            Some(e) => {
                for normal in normals_across(e, dims) {
                    for (column, value) in coefficients(row) {
                        for (c, &n) in normal.iter().take(dims).enumerate() {
                            *system.coefficient_mut(r, column * dims + c) += value * n;
                        }
                    }
                    *system.rhs_mut(r, 0) = dot(normal, row.change);
                    r += 1;
                }
            }
        }
    }
    let solution = system.solve();
    for (column, displacement) in displacements.iter_mut().enumerate() {
        for (c, value) in displacement.iter_mut().take(dims).enumerate() {
            *value = unscale(column_variables[column], solution.x[column * dims + c]);
        }
    }
    displacements
}

/// The non-zero coefficients `(column, Σ_{poles i of the variable} R_i^(r)(u) / √m)` of a row
/// (a variable may appear once per pole it owns: the caller adds them up).
fn coefficients<'a>(
    row: &'a Row,
    variables: &'a PoleVariables,
    column_of: &'a [usize],
    p: usize,
) -> impl Iterator<Item = (usize, f64)> + 'a {
    (0..=p).filter_map(move |k| {
        let value = row.basis.rows[row.order][k];
        let variable = variables.variable_of(row.basis.first + k)?;
        let weight = variables.column_scale[variable];
        (value != 0.0).then_some((column_of[variable], value * weight))
    })
}

/// `[lo, hi]` outside which moving the poles `changed` leaves the curve alone: pole `i`
/// acts on `[u_i, u_{i+p+1}]`, clipped to the domain.
pub(crate) fn affected_domain_of_poles(curve: &Curve, changed: &[usize]) -> (f64, f64) {
    let knots = curve.knots();
    let p = curve.degree();
    let (lo, hi) = curve.domain();
    match (changed.first(), changed.last()) {
        (Some(&first), Some(&last)) => (knots[first].max(lo), knots[last + p + 1].min(hi)),
        _ => (lo, lo),
    }
}

/// The control-point move behind the edit's interface ([`EditMethod`]): any degree; it builds
/// the constraints and fixed poles into its system, and reaches every target it can solve for.
#[derive(Debug, Clone, Copy)]
pub struct ControlPoints;

impl EditMethod for ControlPoints {
    fn kind(&self) -> MethodKind {
        MethodKind::ControlPoints
    }

    fn refuses(&self, _curve: &Curve) -> Option<ShapeError> {
        None
    }

    fn solve(&self, edit: &EditContext, target: Point) -> MethodSolutions {
        let curve = edit.query.curve;
        let moved = constrained_control_point_move(
            curve,
            edit.query.parameter,
            target,
            edit.constraints,
            edit.variables,
            false,
        );
        let (solutions, failure) = match moved {
            Ok(solution) => {
                let new_curve = curve.with_control_points(solution.control_points);
                let solutions = new_curve
                    .map(|new_curve| EditSolution {
                        detail: SolutionDetail::ControlPoints {
                            changed_control_points: solution.changed_control_points,
                        },
                        curve: new_curve,
                        point: solution.point,
                        residual: solution.residual,
                        affected_domain: solution.affected_domain,
                        max_deviation: None,
                    })
                    .into_iter()
                    .collect();
                (solutions, None)
            }
            Err(failure) => (Vec::new(), Some(MethodFailure::ControlPoints(failure))),
        };
        MethodSolutions {
            solutions,
            failure,
            membership: MethodMembership::Single,
        }
    }

    fn reachable(&self, _edit: &EditContext, _options: PolygonOptions) -> Reachable {
        Reachable::Everywhere
    }

    fn nearest(&self, _edit: &EditContext, _target: Point) -> Option<MethodNearest> {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::CurveLimits;

    #[test]
    fn a_move_onto_the_curve_itself_changes_nothing() {
        let points = [[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0], [6.0, 1.0]];
        let knots = [0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0];
        let curve = Curve::new(3, &points, &knots, None, &CurveLimits::default()).unwrap();
        let on_curve = curve.point(0.3).unwrap();
        let solution = control_point_move(&curve, 0.3, on_curve, true).unwrap();
        assert!(solution.changed_control_points.is_empty());
        assert_eq!(solution.max_deviation, Some(0.0));
    }
}

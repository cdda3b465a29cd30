//! The least-norm move of a surface's free control points (docs/method.md §41): the smallest
//! change `Σ_ij |Δd_ij|²` of the free poles that puts `S(u, v)` on the target and meets every
//! constraint, as for curves (Fowler & Bartels 1993; The NURBS Book §11.5).
//!
//! With fixed knots and weights the point and first partials are linear in the poles,
//! `S^(k,l) = Σ_ij R_ij^(k,l) d_ij` ([`SurfaceBasis`]). The target and the conditions are the
//! system `B Δ = c`: one row for the target (`Σ R_ij(u, v) Δd_ij = p - S(u, v)`), one per
//! order-0 condition and two (`∂/∂u`, `∂/∂v`) per order-1 condition, each with the change it
//! asks as right-hand side in every coordinate. The coordinates separate, so one factorisation
//! of `B` serves all three; its least-norm solution `Δ = Bᵀ (B Bᵀ)⁻¹ c` comes from the curves'
//! rank-revealing solver ([`DenseSystem`]). Without constraints it is the closed form
//!
//! ```text
//! Δd_ij = R_ij(u, v) / Σ_kl R_kl(u, v)² · (p - S(u, v)).
//! ```
//!
//! A periodic direction's repeated poles are one variable (the curves' [`PoleVariables::tied`]).
//! The new surface is evaluated and every condition re-checked; a move that misses (dependent
//! rows that disagree, rounding on an ill-conditioned system) is not returned.

use super::basis::SurfaceBasis;
use super::constraints::{FixedNet, SurfaceConstraints, caller_index, surface_edit_size};
use super::method::{
    SurfaceEditContext, SurfaceEditMethod, SurfaceExclusion, SurfaceExclusionReason,
    SurfaceMethodKind, SurfaceMethodSolutions, SurfaceNearest, SurfaceReachable, SurfaceSolution,
    SurfaceSolutionDetail,
};
use crate::shape::control_points::DISPLACEMENT_ROUNDING;
use crate::shape::{CONSTRAINT_TOLERANCE, ControlPointFailure, DenseSystem, PoleVariables};
use crate::spline::vector::{Point, distance, dot, norm, sub};
use crate::surface::Surface;

/// A control-point move of a surface.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfacePoleMove {
    /// The new surface (same knots and weights).
    pub surface: Surface,
    /// Flat indices (`i · count_v + j`) of the stored poles that moved, ascending.
    pub changed: Vec<usize>,
    /// The new `S(u, v)`.
    pub point: Point,
    /// `|point - target|`.
    pub residual: f64,
    /// `[[u0, u1], [v0, v1]]` outside which the surface is unchanged.
    pub affected_domain: [(f64, f64); 2],
    /// `sqrt(Σ |Δd_ij|²)` over the stored poles (a periodic copy counts once per copy).
    pub displacement_norm: f64,
}

/// The free poles of `surface` as variables: a periodic direction's copies of one pole share
/// one.
pub fn pole_variables(surface: &Surface, fixed: &FixedNet) -> PoleVariables {
    let (rows, columns) = (surface.u().caller_count(), surface.v().caller_count());
    let n_v = surface.v().count();
    PoleVariables::tied(fixed.poles(), |flat| {
        ((flat / n_v) % rows) * columns + (flat % n_v) % columns
    })
}

/// The least-norm move (module docs) of the free poles that puts `S(u, v)` on `target` and
/// meets `constraints`, verified on the new surface.
///
/// Preconditions: `(u, v)` in the domain, `target` finite, `constraints` validated for this
/// surface and without a clash.
pub fn surface_control_point_move(
    surface: &Surface,
    (u, v): (f64, f64),
    target: Point,
    constraints: &SurfaceConstraints,
    fixed: &FixedNet,
) -> Result<SurfacePoleMove, ControlPointFailure> {
    let variables = pole_variables(surface, fixed);
    if variables.count() == 0 {
        return Err(ControlPointFailure::NoFreeControlPoint);
    }
    let current = surface.point(u, v);
    // (basis, which value of it: 0 point, 1 ∂u, 2 ∂v, the change asked)
    let mut rows: Vec<(SurfaceBasis, usize, Point)> = Vec::new();
    rows.push((SurfaceBasis::at(surface, u, v), 0, sub(target, current)));
    for condition in constraints.conditions() {
        let (cu, cv) = condition.parameter;
        let basis = SurfaceBasis::at(surface, cu, cv);
        if condition.order == 0 {
            rows.push((basis, 0, sub(condition.values[0], condition.current[0])));
        } else {
            rows.push((
                basis.clone(),
                1,
                sub(condition.values[0], condition.current[0]),
            ));
            rows.push((basis, 2, sub(condition.values[1], condition.current[1])));
        }
    }
    let n_v = surface.v().count();
    let flat = |(i, j): (usize, usize)| i * n_v + j;
    // Columns: the variables acting on some row.
    let mut column_of = vec![usize::MAX; variables.count()];
    let mut columns = 0;
    for (basis, k, _) in &rows {
        for (pole, values) in basis.entries() {
            if values[*k] == 0.0 {
                continue;
            }
            if let Some(variable) = variables.variable_of(flat(pole)) {
                if column_of[variable] == usize::MAX {
                    column_of[variable] = columns;
                    columns += 1;
                }
            }
        }
    }
    let target_moves = rows[0].2 != [0.0; 3];
    let free_at_target = rows[0]
        .0
        .entries()
        .any(|(pole, values)| values[0] != 0.0 && variables.variable_of(flat(pole)).is_some());
    if target_moves && !free_at_target {
        return Err(ControlPointFailure::NoFreeControlPointAtTarget);
    }
    let mut system = DenseSystem::zeros(rows.len(), columns.max(1), 3);
    for (r, (basis, k, change)) in rows.iter().enumerate() {
        for (pole, values) in basis.entries() {
            if let Some(variable) = variables.variable_of(flat(pole)) {
                if values[*k] != 0.0 {
                    *system.coefficient_mut(r, column_of[variable]) += values[*k];
                }
            }
        }
        for (c, value) in change.iter().enumerate() {
            *system.rhs_mut(r, c) = *value;
        }
    }
    let solution = system.solve();
    let size = surface_edit_size(surface).max(norm(target));
    let mut points = surface.control_points().to_vec();
    let mut changed = Vec::new();
    let mut squares = 0.0;
    for (index, point) in points.iter_mut().enumerate() {
        let Some(variable) = variables.variable_of(index) else {
            continue;
        };
        let column = column_of[variable];
        if column == usize::MAX {
            continue;
        }
        let delta = [
            solution.x[column * 3],
            solution.x[column * 3 + 1],
            solution.x[column * 3 + 2],
        ];
        if norm(delta) > DISPLACEMENT_ROUNDING * size {
            for c in 0..3 {
                point[c] += delta[c];
            }
            squares += delta.iter().map(|d| d * d).sum::<f64>();
            changed.push(index);
        }
    }
    if points.iter().flatten().any(|x| !x.is_finite()) {
        return Err(ControlPointFailure::Unmet);
    }
    let moved = Surface::from_valid_parts(
        surface.u().clone(),
        surface.v().clone(),
        points,
        surface.weights().map(<[f64]>::to_vec),
    );
    let point = moved.point(u, v);
    let residual = distance(point, target);
    if residual.is_nan()
        || residual > CONSTRAINT_TOLERANCE * size
        || constraints.check(&moved).is_err()
    {
        return Err(ControlPointFailure::Unmet);
    }
    let affected_domain = affected_domain_of_poles(surface, &changed);
    Ok(SurfacePoleMove {
        surface: moved,
        changed,
        point,
        residual,
        affected_domain,
        displacement_norm: squares.sqrt(),
    })
}

/// `[[u0, u1], [v0, v1]]` outside which changing the stored poles `changed` (flat indices)
/// leaves the surface alone: pole `(i, j)` acts on `[t_i, t_{i+p+1}] × [s_j, s_{j+q+1}]`;
/// the bounding rectangle of those, clipped to the domain. Empty (`[lo, lo]` in both) when
/// nothing changed.
pub fn affected_domain_of_poles(surface: &Surface, changed: &[usize]) -> [(f64, f64); 2] {
    let n_v = surface.v().count();
    let [(u_lo, u_hi), (v_lo, v_hi)] = surface.domain();
    if changed.is_empty() {
        return [(u_lo, u_lo), (v_lo, v_lo)];
    }
    let (mut i0, mut i1, mut j0, mut j1) = (usize::MAX, 0, usize::MAX, 0);
    for &flat in changed {
        let (i, j) = (flat / n_v, flat % n_v);
        i0 = i0.min(i);
        i1 = i1.max(i);
        j0 = j0.min(j);
        j1 = j1.max(j);
    }
    let (ku, kv) = (surface.u().knots(), surface.v().knots());
    let (p, q) = (surface.u().degree(), surface.v().degree());
    [
        (ku[i0].max(u_lo), ku[i1 + p + 1].min(u_hi)),
        (kv[j0].max(v_lo), kv[j1 + q + 1].min(v_hi)),
    ]
}

/// The control-point move behind the surface edit's interface ([`SurfaceEditMethod`]).
#[derive(Debug, Clone, Copy)]
pub struct ControlPointsMethod;

impl SurfaceEditMethod for ControlPointsMethod {
    fn kind(&self) -> SurfaceMethodKind {
        SurfaceMethodKind::ControlPoints
    }

    fn solve(&self, edit: &SurfaceEditContext, target: Point) -> SurfaceMethodSolutions {
        let surface = edit.surface;
        match surface_control_point_move(
            surface,
            edit.parameter,
            target,
            edit.constraints,
            edit.fixed,
        ) {
            Ok(moved) => {
                // The caller's poles (a periodic copy once) and their displacement norm.
                let mut changed_control_points: Vec<[usize; 2]> = moved
                    .changed
                    .iter()
                    .map(|&flat| caller_index(surface, flat))
                    .collect();
                changed_control_points.sort_unstable();
                changed_control_points.dedup();
                let displacement_norm = changed_control_points
                    .iter()
                    .map(|&[i, j]| {
                        let delta = sub(
                            moved.surface.control_point(i, j),
                            surface.control_point(i, j),
                        );
                        dot(delta, delta)
                    })
                    .sum::<f64>()
                    .sqrt();
                SurfaceMethodSolutions {
                    solutions: vec![SurfaceSolution {
                        detail: SurfaceSolutionDetail::ControlPoints {
                            changed_control_points,
                            displacement_norm,
                        },
                        surface: moved.surface,
                        point: moved.point,
                        residual: moved.residual,
                        affected_domain: moved.affected_domain,
                        conditioning: 1.0,
                        max_deviation: None,
                    }],
                    excluded: Vec::new(),
                }
            }
            Err(failure) => SurfaceMethodSolutions {
                solutions: Vec::new(),
                excluded: vec![SurfaceExclusion {
                    method: SurfaceMethodKind::ControlPoints,
                    count: 1,
                    reason: match failure {
                        ControlPointFailure::NoFreeControlPoint => {
                            SurfaceExclusionReason::NoFreeControlPoint
                        }
                        ControlPointFailure::NoFreeControlPointAtTarget => {
                            SurfaceExclusionReason::NoFreeControlPointAtTarget
                        }
                        ControlPointFailure::Unmet => SurfaceExclusionReason::Unmet,
                    },
                }],
            },
        }
    }

    fn reachable(&self, edit: &SurfaceEditContext) -> SurfaceReachable {
        if pole_variables(edit.surface, edit.fixed).count() == 0 {
            SurfaceReachable::Nothing(SurfaceExclusionReason::NoFreeControlPoint)
        } else {
            SurfaceReachable::Everywhere
        }
    }

    fn nearest(&self, _edit: &SurfaceEditContext, _target: Point) -> Option<SurfaceNearest> {
        None
    }
}

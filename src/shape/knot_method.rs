//! The knot method behind the edit's interface ([`EditMethod`]): every requested knot family
//! ([`super::family`]) on curves of degree 2 and more.

use super::family::family_regions;
use super::family::{KnotSolution, nearest_across_families, solve_families};
use super::method::{
    EditContext, EditMethod, EditSolution, MethodKind, MethodMembership, MethodNearest,
    MethodSolutions, Reachable, SolutionDetail,
};
use super::nearest::nearest_reachable;
use super::regions::PolygonOptions;
use super::solve::{ShapeError, Solution, affected_domain};
use crate::spline::Curve;
use crate::spline::vector::{Point, distance};

/// The knot method.
#[derive(Debug, Clone, Copy)]
pub struct KnotPairs;

/// The edit's form of a knot solution (its new curve built from the new knots).
fn edit_solution(curve: &Curve, solution: KnotSolution) -> Option<EditSolution> {
    let new_curve = curve.with_full_knots(solution.knots)?;
    Some(EditSolution {
        detail: SolutionDetail::Knots {
            family: solution.family,
            pair: solution.omega,
            side: solution.side,
            span: solution.span,
            moved_knot: solution.moved_knot,
            knots_moved: solution.knots_moved,
            changed_knots: solution.changed_knots,
            conditioning: solution.conditioning,
        },
        curve: new_curve,
        point: solution.point,
        residual: solution.residual,
        affected_domain: solution.affected_domain,
        max_deviation: None,
    })
}

/// The edit's form of a cubic envelope solution of the nearest-point search.
fn envelope_edit_solution(curve: &Curve, solution: Solution) -> Option<EditSolution> {
    let [first, second] = solution.pair.unknowns();
    let knots_moved = super::family::KnotSet::new(&[
        first.full_index(solution.span),
        second.full_index(solution.span),
    ]);
    let new_curve = curve.with_full_knots(solution.knots)?;
    Some(EditSolution {
        detail: SolutionDetail::Knots {
            family: super::family::Family::Envelope,
            pair: Some(solution.pair),
            side: Some(solution.side),
            span: solution.span,
            moved_knot: Some(solution.moved_knot),
            knots_moved,
            changed_knots: solution.changed_knots,
            conditioning: 0.0,
        },
        curve: new_curve,
        point: solution.point,
        residual: solution.residual,
        affected_domain: solution.affected_domain,
        max_deviation: solution.max_deviation,
    })
}

impl EditMethod for KnotPairs {
    fn kind(&self) -> MethodKind {
        MethodKind::Knots
    }

    fn refuses(&self, curve: &Curve) -> Option<ShapeError> {
        (curve.degree() < 2).then_some(ShapeError::DegreeOne)
    }

    fn solve(&self, edit: &EditContext, target: Point) -> MethodSolutions {
        let curve = edit.query.curve;
        let outcome = solve_families(&edit.query, edit.query.families, target);
        MethodSolutions {
            solutions: outcome
                .solutions
                .into_iter()
                .filter_map(|s| edit_solution(curve, s))
                .collect(),
            failure: None,
            membership: MethodMembership::Knots {
                candidates: outcome.candidates,
                groups: outcome.groups,
            },
        }
    }

    /// The regions of the pairs whose edits surely keep the constraints: a knot edit changes
    /// the envelope's moved knot and the pair's, so the curve only on
    /// `[u_{qmin-p}, u_{qmax+p}]` (the whole domain when one of them is an end of it).
    fn reachable(&self, edit: &EditContext, options: PolygonOptions) -> Reachable {
        let (mut candidates, mut families) =
            family_regions(&edit.query, edit.query.families, options);
        if !edit.constraints.is_empty() {
            let curve = edit.query.curve;
            let keeps = |moved: Option<usize>, knots: &[usize]| {
                let p = curve.degree();
                let n = curve.control_points().len() - 1;
                let all = moved.into_iter().chain(knots.iter().copied());
                let (qmin, qmax) = all.fold((usize::MAX, 0), |(lo, hi), k| (lo.min(k), hi.max(k)));
                let affected = if qmin <= p || qmax > n {
                    (f64::NEG_INFINITY, f64::INFINITY)
                } else {
                    affected_domain(curve, curve.knots(), &[qmin, qmax])
                };
                edit.constraints.surely_kept_outside(curve, affected)
            };
            for entry in &mut candidates {
                let moved = entry.candidate.moved_knot;
                entry
                    .regions
                    .retain(|region| keeps(Some(moved), &region.knots));
            }
            for family in &mut families {
                let moved = family.problem.moved_knot;
                family
                    .regions
                    .retain(|region| keeps(moved, region.knots.indices()));
            }
        }
        Reachable::KnotRegions {
            candidates,
            families,
        }
    }

    /// The nearest point over every requested family: the cubic's envelope pairs by their
    /// boundary search ([`nearest_reachable`]), every other family by
    /// [`nearest_across_families`]; the closer wins.
    fn nearest(&self, edit: &EditContext, target: Point) -> Option<MethodNearest> {
        let curve = edit.query.curve;
        let query = &edit.query;
        let envelope = (curve.degree() == 3
            && query
                .families
                .includes(super::family::Family::Envelope, curve))
        .then(|| nearest_reachable(query, target, false).ok().flatten())
        .flatten()
        .map(|nearest| MethodNearest {
            point: nearest.point,
            solutions: nearest
                .solutions
                .into_iter()
                .filter_map(|s| envelope_edit_solution(curve, s))
                .collect(),
        });
        let families =
            nearest_across_families(query, query.families, target).map(|nearest| MethodNearest {
                point: nearest.point,
                solutions: nearest
                    .solutions
                    .into_iter()
                    .filter_map(|s| edit_solution(curve, s))
                    .collect(),
            });
        match (envelope, families) {
            (Some(a), Some(b)) => Some(if distance(a.point, target) <= distance(b.point, target) {
                a
            } else {
                b
            }),
            (a, b) => a.or(b),
        }
    }
}

//! One edit of the picked curve point (docs/method.md §21): runs the requested methods
//! ([`super::method`]), checks every solution against the constraints and fixed poles, ranks
//! all methods' solutions together by `max_deviation`, says per method what was excluded and
//! why, and finds the nearest reachable point when nothing reaches the target. The HTTP layer
//! only parses and converts.

use std::fmt;

use super::candidate::Side;
use super::constraints::{Breach, ConstraintSet};
use super::control_points::ControlPointFailure;
use super::family::{Family, FamilyGroup, FamilyRegions, KnotSet};
use super::method::{
    EditContext, EditSolution, MethodFailure, MethodKind, MethodMembership, MethodNearest,
    Reachable, RegionKey, WeightRegion,
};
use super::regions::{CandidateRegions, PolygonOptions};
use super::solve::{CandidateOutcome, ShapeError, target_point};
use crate::spline::vector::{Point, distance};

/// Options of [`edit`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct EditOptions {
    /// Measure each solution's `max_deviation` (and rank by it).
    pub measure_deviation: bool,
    /// When nothing reaches the target, look for the nearest reachable point.
    pub nearest: bool,
}

/// Why solutions of a method were dropped, or why it has none.
#[derive(Debug, Clone, PartialEq)]
pub enum ExclusionReason {
    /// A condition does not hold on the new curve.
    Breaks {
        /// Position of the constraint in the request.
        constraint: usize,
        /// What the constraint is ([`super::Condition::describe`]).
        description: String,
    },
    /// A kept tangent direction would reverse.
    Reverses {
        /// Position of the constraint in the request.
        constraint: usize,
        /// What the constraint is.
        description: String,
    },
    /// The new curve's domain no longer holds the constraint's parameter.
    LeavesDomain {
        /// Position of the constraint in the request.
        constraint: usize,
        /// What the constraint is.
        description: String,
    },
    /// The solution changes a fixed control point (its weight, for the weight method).
    MovesFixedPole {
        /// The control point.
        index: usize,
    },
    /// Two constraints no curve meets together.
    Contradiction {
        /// Positions in the request.
        first: usize,
        /// Positions in the request.
        second: usize,
    },
    /// A kept direction of a tangent that vanishes.
    UndefinedDirection {
        /// Position of the constraint in the request.
        constraint: usize,
        /// Its parameter.
        parameter: f64,
    },
    /// Every control point is fixed.
    NoFreeControlPoint,
    /// Every control point acting at the picked parameter is fixed.
    NoFreeControlPointAtTarget,
    /// The free control points cannot meet the target and the constraints together.
    Unmet,
    /// On a periodic curve: the change reaches a knot or control point that the data hold
    /// twice, in one copy only (the period is too short for the change to stay away from its
    /// other copy).
    PeriodTooShort,
    /// On a periodic curve: the knots change how often the first knot repeats, which in
    /// Open CASCADE's form renumbers the control points.
    RenumbersPoles,
}

impl ExclusionReason {
    /// The constraint it is about, if one.
    pub fn constraint(&self) -> Option<usize> {
        match *self {
            ExclusionReason::Breaks { constraint, .. }
            | ExclusionReason::Reverses { constraint, .. }
            | ExclusionReason::LeavesDomain { constraint, .. }
            | ExclusionReason::UndefinedDirection { constraint, .. } => Some(constraint),
            ExclusionReason::Contradiction { first, .. } => Some(first),
            _ => None,
        }
    }
}

impl fmt::Display for ExclusionReason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ExclusionReason::Breaks { description, .. } => write!(
                f,
                "{description} lies inside the affected domain and does not hold"
            ),
            ExclusionReason::Reverses { description, .. } => {
                write!(
                    f,
                    "{description} would reverse: the new tangent points the other way"
                )
            }
            ExclusionReason::LeavesDomain { description, .. } => write!(
                f,
                "{description} lies outside the new curve's domain (the edit moves an end of the domain)"
            ),
            ExclusionReason::MovesFixedPole { index } => {
                write!(f, "it changes control point {index}, which is fixed")
            }
            ExclusionReason::Contradiction { first, second } => write!(
                f,
                "the constraints contradict each other: constraints[{first}] and constraints[{second}] ask different values of the same quantity"
            ),
            ExclusionReason::UndefinedDirection {
                constraint,
                parameter,
            } => write!(
                f,
                "the tangent at u = {parameter} vanishes, so constraints[{constraint}] has no direction to keep"
            ),
            ExclusionReason::NoFreeControlPoint => {
                write!(f, "the constraints leave no free control point")
            }
            ExclusionReason::NoFreeControlPointAtTarget => write!(
                f,
                "the constraints leave no free control point acting at the picked parameter"
            ),
            ExclusionReason::Unmet => write!(
                f,
                "the free control points cannot meet the target and every constraint together"
            ),
            ExclusionReason::RenumbersPoles => write!(
                f,
                "it changes how often the periodic curve's first knot repeats, which renumbers the control points of the periodic form; pick a point farther from the seam"
            ),
            ExclusionReason::PeriodTooShort => write!(
                f,
                "the periodic curve's period is too short: the change would also reach another copy of a changed knot or control point"
            ),
        }
    }
}

/// How many solutions of one method a reason dropped (1 for a method that has none at all).
#[derive(Debug, Clone, PartialEq)]
pub struct Exclusion {
    /// The method.
    pub method: MethodKind,
    /// Solutions dropped.
    pub count: usize,
    /// Why.
    pub reason: ExclusionReason,
}

/// Whether a weight pair holds the target (a kept solution).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct WeightPairMembership {
    /// `[k, l]`.
    pub poles: [usize; 2],
    /// A kept solution of this pair exists.
    pub contains: bool,
}

/// The answer to one edit.
#[derive(Debug, Clone, PartialEq)]
pub struct EditOutcome {
    /// The knot pairs' candidates, with membership of the requested pairs (`contains` exactly
    /// when a kept solution has that side and pair); empty unless the knot method ran.
    pub candidates: Vec<CandidateOutcome>,
    /// Every requested knot family with the membership of its pairs or triples (`contains`
    /// exactly when a kept solution moves those knots); empty unless the knot method ran.
    pub families: Vec<FamilyGroup>,
    /// Weight pairs active at `t`, when the weight method ran.
    pub weight_pairs: Option<Vec<WeightPairMembership>>,
    /// The kept control-point move's changed poles, when the method ran: `Some(None)` when it
    /// gave none.
    pub control_points: Option<Option<Vec<usize>>>,
    /// Every kept solution of every method, by `max_deviation` (smallest first) when measured.
    pub solutions: Vec<EditSolution>,
    /// Per method and reason, the solutions dropped, in the order of the requested methods.
    pub excluded: Vec<Exclusion>,
    /// The nearest reachable point, when asked, nothing reaches the target and something is
    /// reachable.
    pub nearest: Option<MethodNearest>,
}

impl EditOutcome {
    /// Whether any kept solution reaches the target.
    pub fn reachable(&self) -> bool {
        !self.solutions.is_empty()
    }
}

/// Tally of the exclusions of one method.
#[derive(Default)]
struct Tally(Vec<(ExclusionReason, usize)>);

impl Tally {
    fn add(&mut self, reason: ExclusionReason) {
        match self.0.iter_mut().find(|(r, _)| *r == reason) {
            Some((_, count)) => *count += 1,
            None => self.0.push((reason, 1)),
        }
    }
}

/// What holds every solution back whatever it is: clashing constraints or a direction that
/// does not exist.
fn blocker(constraints: &ConstraintSet) -> Option<ExclusionReason> {
    if let Some((first, second)) = constraints.clash() {
        return Some(ExclusionReason::Contradiction { first, second });
    }
    constraints
        .undefined_direction()
        .map(|condition| ExclusionReason::UndefinedDirection {
            constraint: condition.index,
            parameter: condition.parameter,
        })
}

/// Why `solution` may not be returned: it changes a fixed control point, or breaks a
/// constraint on its new curve.
pub fn admissibility(edit: &EditContext, solution: &EditSolution) -> Result<(), ExclusionReason> {
    let old = edit.query.curve;
    let new = &solution.curve;
    for index in 0..old.control_points().len() {
        if edit.fixed.is_fixed(index)
            && (old.control_points()[index] != new.control_points()[index]
                || old.weight(index) != new.weight(index))
        {
            return Err(ExclusionReason::MovesFixedPole { index });
        }
    }
    edit.constraints.check(new).map_err(|breach| {
        let index = breach.index();
        let description = edit
            .constraints
            .by_index(index)
            .map_or_else(String::new, |c| c.describe());
        match breach {
            Breach::Missed { .. } => ExclusionReason::Breaks {
                constraint: index,
                description,
            },
            Breach::Reversed { .. } => ExclusionReason::Reverses {
                constraint: index,
                description,
            },
            Breach::OutsideDomain { .. } => ExclusionReason::LeavesDomain {
                constraint: index,
                description,
            },
        }
    })
}

/// Checks the parameter, the target and that every requested method takes the curve.
fn validate(edit: &EditContext, methods: &[MethodKind]) -> Result<(), ShapeError> {
    for &kind in methods {
        if let Some(error) = kind.method().refuses(edit.query.curve) {
            return Err(error);
        }
    }
    edit.query.validate_parameter()
}

/// Moves `s(t)` onto `target` by every requested method (module docs).
///
/// Each method's solutions are checked against the fixed poles and the constraints (the new
/// curve evaluated at every constraint's parameter); the kept ones of all methods are ranked
/// together by `max_deviation` (when measured), the dropped ones counted per method and
/// reason. With `options.nearest` and no kept solution, the nearest point that the methods
/// with a bounded reachable set (knot pairs, weights) reach under the same rules, with every
/// requested method's kept solutions there.
pub fn edit(
    edit: &EditContext,
    methods: &[MethodKind],
    target: &[f64],
    options: EditOptions,
) -> Result<EditOutcome, ShapeError> {
    if let Some(periodic) = super::periodic_edit::edit_periodic(edit, methods, target, options) {
        return periodic;
    }
    validate(edit, methods)?;
    let curve = edit.query.curve;
    let target = target_point(curve, target)?;
    let blocked = blocker(edit.constraints);
    let mut outcome = EditOutcome {
        candidates: Vec::new(),
        families: Vec::new(),
        weight_pairs: None,
        control_points: None,
        solutions: Vec::new(),
        excluded: Vec::new(),
        nearest: None,
    };
    let mut knot_candidates = None;
    for &kind in methods {
        let method = kind.method();
        let mut tally = Tally::default();
        let mut found = method.solve(edit, target);
        if let Some(reason) = &blocked {
            // Nothing can be returned; the control-point move counts as one.
            let count = found
                .solutions
                .len()
                .max(usize::from(kind == MethodKind::ControlPoints));
            for _ in 0..count {
                tally.add(reason.clone());
            }
            found.solutions.clear();
            found.failure = None;
        }
        if let Some(MethodFailure::ControlPoints(failure)) = found.failure {
            tally.add(match failure {
                ControlPointFailure::NoFreeControlPoint => ExclusionReason::NoFreeControlPoint,
                ControlPointFailure::NoFreeControlPointAtTarget => {
                    ExclusionReason::NoFreeControlPointAtTarget
                }
                ControlPointFailure::Unmet => ExclusionReason::Unmet,
            });
        }
        let mut kept = Vec::with_capacity(found.solutions.len());
        for solution in found.solutions {
            match admissibility(edit, &solution) {
                Ok(()) => kept.push(solution),
                Err(reason) => tally.add(reason),
            }
        }
        for (reason, count) in tally.0 {
            outcome.excluded.push(Exclusion {
                method: kind,
                count,
                reason,
            });
        }
        let holds = |key: RegionKey| kept.iter().any(|s| s.region_key() == key);
        match found.membership {
            MethodMembership::Knots { candidates, groups } => {
                knot_candidates = Some(
                    candidates
                        .into_iter()
                        .map(|mut entry| {
                            let side: Side = entry.candidate.side;
                            for region in &mut entry.regions {
                                region.contains = holds(RegionKey::Knots {
                                    family: Family::Envelope,
                                    side: Some(side),
                                    knots: KnotSet::new(&region.knots),
                                });
                            }
                            entry
                        })
                        .collect(),
                );
                outcome.families = groups
                    .into_iter()
                    .map(|mut group| {
                        for member in &mut group.members {
                            member.contains = holds(RegionKey::Knots {
                                family: group.problem.family,
                                side: group.problem.side,
                                knots: member.knots,
                            });
                        }
                        group
                    })
                    .collect();
            }
            MethodMembership::WeightPairs(pairs) => {
                outcome.weight_pairs = Some(
                    pairs
                        .into_iter()
                        .map(|poles| WeightPairMembership {
                            poles,
                            contains: holds(RegionKey::Weights(poles)),
                        })
                        .collect(),
                );
            }
            MethodMembership::Single => {
                outcome.control_points = Some(kept.first().and_then(|s| match &s.detail {
                    super::SolutionDetail::ControlPoints {
                        changed_control_points,
                    } => Some(changed_control_points.clone()),
                    _ => None,
                }));
            }
        }
        outcome.solutions.extend(kept);
    }
    outcome.candidates = knot_candidates.unwrap_or_default();
    if options.measure_deviation {
        measure_and_rank(curve, &mut outcome.solutions);
    }
    if options.nearest && outcome.solutions.is_empty() && blocked.is_none() {
        outcome.nearest = nearest(edit, methods, target, options.measure_deviation);
    }
    Ok(outcome)
}

/// Deviations within this relative difference of each other are near-ties: among them the
/// better determined knot solution comes first.
pub const NEAR_TIE: f64 = 1e-6;

/// Solutions at least this many (on a curve of degree 4 or more) before their deviations
/// are measured on several threads ([`measure_and_rank`]).
const PARALLEL_DEVIATIONS: usize = 8;

/// Measures every solution's deviation and sorts by it, smallest first (stable, so ties keep
/// the order of the methods); within a run of near-ties ([`NEAR_TIE`]), knot solutions by
/// their conditioning, best first (the other methods' solutions count as well determined).
fn measure_and_rank(curve: &crate::spline::Curve, solutions: &mut [EditSolution]) {
    use rayon::prelude::*;
    let measure = |solution: &mut EditSolution| {
        let method = solution.detail.method().method();
        solution.max_deviation = Some(method.deviation(curve, solution));
    };
    // Each bound is independent; on the pool when there are many and each is worth it
    // (degree 4 and up: a quintic's takes some 60,000 instructions, a cubic's a few
    // thousand, less than waking the pool).
    if solutions.len() >= PARALLEL_DEVIATIONS && curve.degree() >= 4 && crate::parallel::allowed() {
        solutions.par_iter_mut().for_each(measure);
    } else {
        solutions.iter_mut().for_each(measure);
    }
    let key = |s: &EditSolution| s.max_deviation.unwrap_or(f64::INFINITY);
    solutions.sort_by(|p, q| key(p).total_cmp(&key(q)));
    let conditioning = |s: &EditSolution| match s.detail {
        super::SolutionDetail::Knots { conditioning, .. } => conditioning,
        _ => f64::INFINITY,
    };
    let mut start = 0;
    while start < solutions.len() {
        let first = key(&solutions[start]);
        let mut end = start + 1;
        while end < solutions.len() && key(&solutions[end]) - first <= NEAR_TIE * first.abs() {
            end += 1;
        }
        solutions[start..end].sort_by(|p, q| conditioning(q).total_cmp(&conditioning(p)));
        start = end;
    }
}

/// The nearest reachable point over the requested methods that have one (module docs).
fn nearest(
    edit: &EditContext,
    methods: &[MethodKind],
    target: Point,
    measure_deviation: bool,
) -> Option<MethodNearest> {
    let mut best: Option<(MethodKind, MethodNearest)> = None;
    for &kind in methods {
        let Some(mut found) = kind.method().nearest(edit, target) else {
            continue;
        };
        found
            .solutions
            .retain(|solution| admissibility(edit, solution).is_ok());
        let Some(first) = found.solutions.first() else {
            continue;
        };
        found.point = first.point;
        let closer = best
            .as_ref()
            .is_none_or(|(_, b)| distance(found.point, target) < distance(b.point, target));
        if closer {
            best = Some((kind, found));
        }
    }
    let (from, mut found) = best?;
    let point = found.point;
    for &kind in methods.iter().filter(|&&kind| kind != from) {
        let others = kind.method().solve(edit, point);
        found.solutions.extend(
            others
                .solutions
                .into_iter()
                .filter(|solution| admissibility(edit, solution).is_ok())
                .map(|solution| EditSolution {
                    residual: distance(solution.point, point),
                    ..solution
                }),
        );
    }
    if measure_deviation {
        measure_and_rank(edit.query.curve, &mut found.solutions);
    }
    Some(found)
}

/// What the requested methods can reach at the picked parameter, for drawing.
#[derive(Debug, Clone, PartialEq)]
pub struct ReachableRegions {
    /// The knot pairs' candidates with their regions, cut to what `keep_domain` allows (empty
    /// unless the knot method is requested).
    pub candidates: Vec<CandidateRegions>,
    /// Every requested knot family's regions (empty unless the knot method is requested).
    pub families: Vec<FamilyRegions>,
    /// The weight pairs' quadrilaterals, when the weight method is requested (pairs with a
    /// fixed pole left out).
    pub weight_regions: Vec<WeightRegion>,
}

/// The reachable sets of the requested methods (the control-point move reaches everything and
/// draws nothing).
pub fn reachable_regions(
    edit: &EditContext,
    methods: &[MethodKind],
    options: PolygonOptions,
) -> Result<ReachableRegions, ShapeError> {
    if let Some(periodic) = super::periodic_edit::reachable_regions_periodic(edit, methods, options)
    {
        return periodic;
    }
    validate(edit, methods)?;
    let mut regions = ReachableRegions {
        candidates: Vec::new(),
        families: Vec::new(),
        weight_regions: Vec::new(),
    };
    for &kind in methods {
        match kind.method().reachable(edit, options) {
            Reachable::Everywhere => {}
            Reachable::KnotRegions {
                candidates,
                families,
            } => {
                regions.candidates = candidates;
                regions.families = families;
            }
            Reachable::WeightRegions(weight_regions) => regions.weight_regions = weight_regions,
        }
    }
    Ok(regions)
}

//! Editing a periodic curve (Open CASCADE's form): cut it open far from the picked point, edit
//! the ordinary curve over one period with every method, and write each solution back.
//!
//! The window ([`PeriodicWindow`]) is the periodic curve over `[a, a + T]`, cut at the knot
//! `a` cyclically farthest from `t`; as a function it *is* the periodic curve over that
//! period. Its data hold some periodic knots and control points twice (the last `p + 1 - m_a`
//! control points repeat the first ones, the end knots repeat shifted by `T`). The edit runs
//! on the window with
//!
//! * constraints at the window's parameters of theirs (any parameter is reduced into the
//!   period first),
//! * every copy of a fixed control point fixed,
//! * the control-point system over one variable per periodic control point (its copies move
//!   together; each counts once in the norm, as the periodic form holds it once),
//!
//! and each solution is written back with [`PeriodicWindow::wrap`]. A solution whose change
//! reaches a copy that it did not change the same way (a knot or weight solution on a curve
//! whose period is too short for the change to stay away from the cut) is dropped and counted
//! in `excluded`: written back, that copy would change too, and the curve would no longer be
//! the one that was measured. Every other solution's point, residual, constraints and
//! deviation carry over unchanged, because the written-back curve equals the edited window
//! over the whole period.
//!
//! Indices in the outcome are the periodic form's: a knot index counts the period's knots each
//! repeated its multiplicity times (without the last value), a control point index the `N`
//! control points. `affected_domain` starts inside the period and may reach past its end when
//! the change crosses the seam (read it modulo the period).

use super::constraints::{ConstraintSet, FixedPoles};
use super::control_points::PoleVariables;
use super::edit::{
    EditOptions, EditOutcome, Exclusion, ExclusionReason, ReachableRegions, WeightPairMembership,
    edit, reachable_regions,
};
use super::family::{Family, KnotSet};
use super::method::{EditContext, EditSolution, MethodKind, RegionKey, SolutionDetail};
use super::regions::PolygonOptions;
use super::solve::{ShapeError, ShapeQuery};
use crate::spline::{Curve, PeriodicWindow};

/// Relative agreement asked of two copies changed by one edit (the same computation on two
/// copies of one value differs by roundoff at most).
const COPY_AGREEMENT: f64 = 64.0 * f64::EPSILON;

/// A periodic curve's edit context on its window.
struct WindowEdit {
    window: PeriodicWindow,
    /// The periodic curve's period `[k_0, k_m]`.
    period: (f64, f64),
    /// How often `k_0` repeats.
    seam_multiplicity: usize,
    parameter: f64,
    constraints: ConstraintSet,
    fixed: FixedPoles,
    variables: PoleVariables,
}

impl WindowEdit {
    /// The window of `edit`'s periodic curve around the picked parameter, with the
    /// constraints, fixed poles and pole variables carried over; `None` for a curve that is
    /// not periodic.
    fn new(edit: &EditContext) -> Option<WindowEdit> {
        let curve = edit.query.curve;
        let window = curve.periodic_window(edit.query.parameter)?;
        let parameter = window.window_parameter(edit.query.parameter);
        let constraints = edit
            .constraints
            .with_parameters(|u| window.window_parameter(u));
        let count = window.curve().control_points().len();
        let fixed = FixedPoles::from_fn(count, |k| {
            edit.fixed.is_fixed(window.periodic_pole_index(k))
        });
        let variables = PoleVariables::tied(&fixed, |k| window.periodic_pole_index(k));
        Some(WindowEdit {
            window,
            period: curve.domain(),
            seam_multiplicity: curve.caller_knots().multiplicities.map_or(1, |m| m[0]),
            parameter,
            constraints,
            fixed,
            variables,
        })
    }

    /// The edit context on the window.
    fn context<'a>(&'a self, edit: &'a EditContext) -> EditContext<'a> {
        EditContext {
            query: ShapeQuery {
                curve: self.window.curve(),
                parameter: self.parameter,
                ..edit.query
            },
            constraints: &self.constraints,
            fixed: &self.fixed,
            variables: &self.variables,
        }
    }

    /// The periodic knot index of window knot `i`.
    fn knot(&self, i: usize) -> usize {
        self.window.periodic_knot_index(i)
    }

    /// A window knot set in periodic indices (in the window's order).
    fn knot_set(&self, set: KnotSet) -> KnotSet {
        let indices: Vec<usize> = set.indices().iter().map(|&i| self.knot(i)).collect();
        KnotSet::new(&indices)
    }

    /// The periodic control point index of window control point `k`.
    fn pole(&self, k: usize) -> usize {
        self.window.periodic_pole_index(k)
    }

    /// `indices` of window control points as periodic ones, ascending and without repeats.
    fn poles(&self, indices: &[usize]) -> Vec<usize> {
        let mut poles: Vec<usize> = indices.iter().map(|&k| self.pole(k)).collect();
        poles.sort_unstable();
        poles.dedup();
        poles
    }

    /// Whether every periodic knot and control point that `edited` changes is changed the
    /// same way in each of its copies in the window (so that the written-back curve is
    /// `edited` over the whole period).
    fn copies_agree(&self, edited: &Curve) -> bool {
        let window = self.window.curve();
        let period = window.domain().1 - window.domain().0;
        let knot_changes: Vec<(usize, f64)> = edited
            .knots()
            .iter()
            .zip(window.knots())
            .enumerate()
            .map(|(i, (&new, &old))| (self.knot(i), new - old))
            .collect();
        let knots_agree = knot_changes.iter().all(|&(index, change)| {
            knot_changes
                .iter()
                .filter(|&&(other, _)| other == index)
                .all(|&(_, other)| agree(change, other, period))
        });
        let pole_changes: Vec<(usize, [f64; 4])> = edited
            .control_points()
            .iter()
            .zip(window.control_points())
            .enumerate()
            .map(|(k, (new, old))| {
                let (w_new, w_old) = (edited.weight(k), window.weight(k));
                (
                    self.pole(k),
                    [
                        new[0] - old[0],
                        new[1] - old[1],
                        new[2] - old[2],
                        w_new - w_old,
                    ],
                )
            })
            .collect();
        let scale = window
            .control_points()
            .iter()
            .flatten()
            .fold(1.0f64, |m, v| m.max(v.abs()));
        let poles_agree = pole_changes.iter().all(|&(index, change)| {
            pole_changes
                .iter()
                .filter(|&&(other, _)| other == index)
                .all(|&(_, other)| (0..4).all(|c| agree(change[c], other[c], scale)))
        });
        knots_agree && poles_agree
    }

    /// The periodic form of a window solution, or why it cannot be written back.
    fn wrapped(&self, solution: EditSolution) -> Result<EditSolution, ExclusionReason> {
        if !self.copies_agree(&solution.curve) {
            return Err(ExclusionReason::PeriodTooShort);
        }
        let curve = self
            .window
            .wrap(&solution.curve)
            .map_err(|_| ExclusionReason::PeriodTooShort)?;
        // Open CASCADE numbers the control points from the first knot's multiplicity
        // (`BSplCLib::PoleIndex`): a knot edit that changes it would renumber them, which a
        // knot solution (new knots, the same control points) cannot say.
        if curve.caller_knots().multiplicities.map(|m| m[0]) != Some(self.seam_multiplicity) {
            return Err(ExclusionReason::RenumbersPoles);
        }
        let detail = match solution.detail {
            SolutionDetail::Knots {
                family,
                pair,
                side,
                span,
                moved_knot,
                knots_moved,
                changed_knots,
                conditioning,
            } => {
                let mut changed: Vec<usize> = changed_knots.iter().map(|&i| self.knot(i)).collect();
                changed.sort_unstable();
                changed.dedup();
                SolutionDetail::Knots {
                    family,
                    pair,
                    side,
                    span: self.knot(span),
                    moved_knot: moved_knot.map(|i| self.knot(i)),
                    knots_moved: self.knot_set(knots_moved),
                    changed_knots: changed,
                    conditioning,
                }
            }
            SolutionDetail::ControlPoints {
                changed_control_points,
            } => SolutionDetail::ControlPoints {
                changed_control_points: self.poles(&changed_control_points),
            },
            SolutionDetail::Weights {
                poles,
                changed_weights,
            } => SolutionDetail::Weights {
                poles: [self.pole(poles[0]), self.pole(poles[1])],
                changed_weights: self.poles(&changed_weights),
            },
        };
        Ok(EditSolution {
            detail,
            curve,
            affected_domain: self.periodic_interval(solution.affected_domain),
            ..solution
        })
    }

    /// A window interval `[lo, hi]` shifted by whole periods so that `lo` lies in the
    /// periodic curve's period (`hi` may then pass its end).
    fn periodic_interval(&self, (lo, hi): (f64, f64)) -> (f64, f64) {
        let (first, last) = self.period;
        let mut start = first + (lo - first).rem_euclid(last - first);
        if start >= last {
            start = first;
        }
        (start, start + (hi - lo))
    }

    /// The outcome of the window's edit in the periodic form: solutions written back (or
    /// dropped and counted), indices renumbered, membership recounted from what is kept.
    fn outcome(&self, outcome: EditOutcome) -> EditOutcome {
        let mut excluded = outcome.excluded;
        let mut solutions = Vec::with_capacity(outcome.solutions.len());
        for solution in outcome.solutions {
            let method = solution.detail.method();
            match self.wrapped(solution) {
                Ok(solution) => solutions.push(solution),
                Err(reason) => count_exclusion(&mut excluded, method, reason),
            }
        }
        let holds = |key: RegionKey| solutions.iter().any(|s| s.region_key() == key);
        let candidates = outcome
            .candidates
            .into_iter()
            .map(|mut entry| {
                entry.candidate.span = self.knot(entry.candidate.span);
                entry.candidate.moved_knot = self.knot(entry.candidate.moved_knot);
                for region in &mut entry.regions {
                    let knots = self.knot_set(KnotSet::new(&region.knots));
                    region.knots = region.knots.map(|i| self.knot(i));
                    region.contains = holds(RegionKey::Knots {
                        family: Family::Envelope,
                        side: Some(entry.candidate.side),
                        knots,
                    });
                }
                entry
            })
            .collect();
        let families = outcome
            .families
            .into_iter()
            .map(|mut group| {
                group.problem.span = self.knot(group.problem.span);
                group.problem.moved_knot = group.problem.moved_knot.map(|i| self.knot(i));
                for member in &mut group.members {
                    member.knots = self.knot_set(member.knots);
                    member.contains = holds(RegionKey::Knots {
                        family: group.problem.family,
                        side: group.problem.side,
                        knots: member.knots,
                    });
                }
                group
            })
            .collect();
        let weight_pairs = outcome.weight_pairs.map(|pairs| {
            pairs
                .into_iter()
                .map(|pair| {
                    let poles = [self.pole(pair.poles[0]), self.pole(pair.poles[1])];
                    WeightPairMembership {
                        poles,
                        contains: holds(RegionKey::Weights(poles)),
                    }
                })
                .collect()
        });
        let control_points = outcome.control_points.map(|_| {
            solutions.iter().find_map(|s| match &s.detail {
                SolutionDetail::ControlPoints {
                    changed_control_points,
                } => Some(changed_control_points.clone()),
                _ => None,
            })
        });
        let nearest = outcome.nearest.and_then(|mut nearest| {
            nearest.solutions = nearest
                .solutions
                .into_iter()
                .filter_map(|s| self.wrapped(s).ok())
                .collect();
            (!nearest.solutions.is_empty()).then_some(nearest)
        });
        EditOutcome {
            candidates,
            families,
            weight_pairs,
            control_points,
            solutions,
            excluded,
            nearest,
        }
    }
}

/// Adds one solution dropped for `reason` to `method`'s tally.
fn count_exclusion(excluded: &mut Vec<Exclusion>, method: MethodKind, reason: ExclusionReason) {
    match excluded
        .iter_mut()
        .find(|e| e.method == method && e.reason == reason)
    {
        Some(entry) => entry.count += 1,
        None => excluded.push(Exclusion {
            method,
            count: 1,
            reason,
        }),
    }
}

/// Whether two changes of copies of one value agree up to roundoff (relative to their
/// magnitude and `scale`).
fn agree(a: f64, b: f64, scale: f64) -> bool {
    (a - b).abs() <= COPY_AGREEMENT * a.abs().max(b.abs()).max(scale)
}

/// [`edit`] for a periodic curve (module docs); `None` when the curve is not periodic.
pub(super) fn edit_periodic(
    context: &EditContext,
    methods: &[MethodKind],
    target: &[f64],
    options: EditOptions,
) -> Option<Result<EditOutcome, ShapeError>> {
    let window = WindowEdit::new(context)?;
    let outcome = edit(&window.context(context), methods, target, options);
    Some(outcome.map(|outcome| window.outcome(outcome)))
}

/// [`reachable_regions`] for a periodic curve, indices renumbered; `None` when the curve is
/// not periodic.
pub(super) fn reachable_regions_periodic(
    context: &EditContext,
    methods: &[MethodKind],
    options: PolygonOptions,
) -> Option<Result<ReachableRegions, ShapeError>> {
    let window = WindowEdit::new(context)?;
    let regions = reachable_regions(&window.context(context), methods, options);
    Some(regions.map(|mut regions| {
        for entry in &mut regions.candidates {
            entry.candidate.span = window.knot(entry.candidate.span);
            entry.candidate.moved_knot = window.knot(entry.candidate.moved_knot);
            for region in &mut entry.regions {
                region.knots = region.knots.map(|i| window.knot(i));
            }
        }
        for family in &mut regions.families {
            family.problem.span = window.knot(family.problem.span);
            family.problem.moved_knot = family.problem.moved_knot.map(|i| window.knot(i));
            for region in &mut family.regions {
                region.knots = window.knot_set(region.knots);
            }
        }
        for region in &mut regions.weight_regions {
            region.pair.poles = region.pair.poles.map(|k| window.pole(k));
        }
        regions
    }))
}

#[cfg(test)]
mod tests {
    use crate::spline::{Curve, CurveLimits, KnotForm};

    /// A periodic cubic of 8 poles, knots 0, 0.25, …, 2.
    fn periodic_cubic() -> Curve {
        let poles: Vec<[f64; 2]> = (0..8)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / 8.0;
                [2.0 * a.cos() + 0.1 * i as f64, 2.0 * a.sin()]
            })
            .collect();
        let knots: Vec<f64> = (0..=8).map(|i| 0.25 * i as f64).collect();
        Curve::from_knot_form(
            3,
            &poles,
            KnotForm::Periodic {
                knots: &knots,
                multiplicities: &[1; 9],
            },
            None,
            &CurveLimits::default(),
        )
        .unwrap()
    }

    /// Moving the window's copy of `k_0` (below the seam) and writing back gives the curve
    /// that the edited window is, over the whole period.
    #[test]
    fn a_knot_moved_across_the_seam_is_written_back_as_the_edited_window() {
        let curve = periodic_cubic();
        let window = curve.periodic_window(0.004).unwrap();
        let mut knots = window.curve().knots().to_vec();
        let copy = knots.iter().position(|&u| u == 2.0).unwrap();
        knots[copy] = 1.95;
        let edited = window.curve().with_full_knots(knots).unwrap();
        let wrapped = window.wrap(&edited).unwrap();
        let (lo, hi) = edited.domain();
        for i in 0..=200 {
            let s = lo + (hi - lo) * i as f64 / 200.0;
            let a = edited.point(s).unwrap();
            let b = wrapped.point(wrapped.snap_to_domain(s).unwrap()).unwrap();
            let gap = ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt();
            assert!(gap < 1e-12, "s = {s}: {a:?} vs {b:?}");
        }
    }
}

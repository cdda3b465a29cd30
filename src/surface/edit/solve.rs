//! One edit of the picked surface point (docs/method.md §44): runs the requested methods
//! ([`super::method`]; side by side on the rayon pool when allowed), checks every solution
//! against the constraints, measures and ranks all methods' solutions together by the
//! certified `max_deviation` (ties: better conditioned first), says per method what was
//! excluded and why, and finds the nearest reachable point when nothing reaches the target.

use super::constraints::{FixedNet, SurfaceConstraints};
use super::method::{
    SurfaceEditContext, SurfaceEditMethod, SurfaceExclusion, SurfaceExclusionReason,
    SurfaceMethodKind, SurfaceReachable, SurfaceSolution,
};
use crate::spline::vector::{Point, distance};
use crate::surface::Surface;

/// Options of [`surface_edit`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct SurfaceEditOptions {
    /// When nothing reaches the target, look for the nearest reachable point.
    pub nearest: bool,
    /// Knot edits keep the domain.
    pub keep_domain: bool,
}

/// The nearest reachable point and its ranked solutions.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceNearestOutcome {
    /// The point.
    pub point: Point,
    /// Its distance from the target.
    pub distance: f64,
    /// Solutions reaching it, ranked.
    pub solutions: Vec<SurfaceSolution>,
}

/// The answer of one edit.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceEditOutcome {
    /// Every solution of every requested method, measured and ranked.
    pub solutions: Vec<SurfaceSolution>,
    /// What was dropped, per method and reason.
    pub excluded: Vec<SurfaceExclusion>,
    /// With `nearest` and no solution: the nearest reachable point.
    pub nearest: Option<SurfaceNearestOutcome>,
}

/// The request of one edit, validated.
#[derive(Debug, Clone, Copy)]
pub struct SurfaceEditRequest<'a> {
    /// The surface.
    pub surface: &'a Surface,
    /// `(u, v)` in the domain.
    pub parameter: (f64, f64),
    /// The target.
    pub target: Point,
    /// The requested methods (each once).
    pub methods: &'a [SurfaceMethodKind],
    /// The constraints.
    pub constraints: &'a SurfaceConstraints,
    /// The fixed poles.
    pub fixed: &'a FixedNet,
    /// Options.
    pub options: SurfaceEditOptions,
}

/// Adds `count` exclusions for `reason`, merging with an equal entry.
fn exclude(
    excluded: &mut Vec<SurfaceExclusion>,
    method: SurfaceMethodKind,
    count: usize,
    reason: SurfaceExclusionReason,
) {
    match excluded
        .iter_mut()
        .find(|e| e.method == method && e.reason == reason)
    {
        Some(entry) => entry.count += count,
        None => excluded.push(SurfaceExclusion {
            method,
            count,
            reason,
        }),
    }
}

/// Runs the edit (module docs). Preconditions: as [`SurfaceEditRequest`] states.
pub fn surface_edit(request: &SurfaceEditRequest) -> SurfaceEditOutcome {
    let mut excluded = Vec::new();
    let context = SurfaceEditContext {
        surface: request.surface,
        parameter: request.parameter,
        constraints: request.constraints,
        fixed: request.fixed,
        keep_domain: request.options.keep_domain,
    };
    let mut methods = Vec::new();
    for &kind in request.methods {
        match kind.method() {
            Some(method) => methods.push(method),
            None => exclude(&mut excluded, kind, 1, SurfaceExclusionReason::NotAvailable),
        }
    }
    if let Some((first, second)) = request.constraints.clash() {
        for method in &methods {
            exclude(
                &mut excluded,
                method.kind(),
                1,
                SurfaceExclusionReason::Contradiction { first, second },
            );
        }
        return SurfaceEditOutcome {
            solutions: Vec::new(),
            excluded,
            nearest: None,
        };
    }
    // Each method solves, checks and measures its own solutions (on the pool when allowed:
    // one method's deviations are measured while another still solves); their exclusions
    // are then merged in the order of the methods.
    let solve_one = |method: &&'static dyn SurfaceEditMethod| {
        let found = method.solve(&context, request.target);
        let mut broken = Vec::new();
        let mut solutions = checked(request, found.solutions, &mut broken);
        measure(request.surface, &mut solutions);
        (found.excluded, broken, solutions)
    };
    let answers: Vec<_> = if methods.len() >= 2 && crate::parallel::allowed() {
        use rayon::prelude::*;
        methods.par_iter().map(solve_one).collect()
    } else {
        methods.iter().map(solve_one).collect()
    };
    let mut solutions = Vec::new();
    for (found_excluded, broken, found) in answers {
        for exclusion in found_excluded.into_iter().chain(broken) {
            exclude(
                &mut excluded,
                exclusion.method,
                exclusion.count,
                exclusion.reason,
            );
        }
        solutions.extend(found);
    }
    let mut nearest = None;
    if solutions.is_empty() && request.options.nearest {
        let mut best: Option<SurfaceNearestOutcome> = None;
        for method in &methods {
            let Some(found) = method.nearest(&context, request.target) else {
                continue;
            };
            let found_solutions = checked(request, found.solutions, &mut Vec::new());
            let gap = distance(found.point, request.target);
            if !found_solutions.is_empty() && best.as_ref().is_none_or(|b| gap < b.distance) {
                best = Some(SurfaceNearestOutcome {
                    point: found.point,
                    distance: gap,
                    solutions: found_solutions,
                });
            }
        }
        nearest = best.map(|mut outcome| {
            outcome.solutions = ranked(request.surface, outcome.solutions);
            outcome
        });
    }
    SurfaceEditOutcome {
        solutions: ranked(request.surface, solutions),
        excluded,
        nearest,
    }
}

/// The solutions whose new surface keeps every constraint; the others counted in `excluded`.
fn checked(
    request: &SurfaceEditRequest,
    solutions: Vec<SurfaceSolution>,
    excluded: &mut Vec<SurfaceExclusion>,
) -> Vec<SurfaceSolution> {
    solutions
        .into_iter()
        .filter(
            |solution| match request.constraints.check(&solution.surface) {
                Ok(()) => true,
                Err(constraint) => {
                    exclude(
                        excluded,
                        solution.detail.method(),
                        1,
                        SurfaceExclusionReason::Breaks { constraint },
                    );
                    false
                }
            },
        )
        .collect()
}

/// Measures each solution's certified deviation from `surface` (those not measured yet) and
/// sorts by it (ties: the better conditioned first).
pub fn ranked(surface: &Surface, mut solutions: Vec<SurfaceSolution>) -> Vec<SurfaceSolution> {
    measure(surface, &mut solutions);
    solutions.sort_by(|a, b| {
        let key = |s: &SurfaceSolution| s.max_deviation.unwrap_or(f64::INFINITY);
        key(a)
            .total_cmp(&key(b))
            .then(b.conditioning.total_cmp(&a.conditioning))
    });
    solutions
}

/// Sets the certified deviation from `surface` of each solution not measured yet.
///
/// Each bound is independent and costly (tens to hundreds of microseconds: a branch and bound
/// over the changed patches), so two or more are measured on the rayon pool.
fn measure(surface: &Surface, solutions: &mut [SurfaceSolution]) {
    use rayon::prelude::*;
    let measure_one = |solution: &mut SurfaceSolution| {
        if solution.max_deviation.is_none() {
            let deviation = match solution.detail.method().method() {
                Some(method) => method.deviation(surface, solution),
                None => super::deviation::surface_max_deviation(
                    surface,
                    &solution.surface,
                    solution.affected_domain,
                ),
            };
            solution.max_deviation = Some(deviation);
        }
    };
    let unmeasured = solutions
        .iter()
        .filter(|s| s.max_deviation.is_none())
        .count();
    if unmeasured >= 2 && crate::parallel::allowed() {
        solutions.par_iter_mut().for_each(measure_one);
    } else {
        solutions.iter_mut().for_each(measure_one);
    }
}

/// What each requested method can reach, for drawing (a method not offered: `Nothing`).
pub fn surface_regions(
    context: &SurfaceEditContext,
    methods: &[SurfaceMethodKind],
) -> Vec<(SurfaceMethodKind, SurfaceReachable)> {
    methods
        .iter()
        .map(|&kind| {
            let reachable = match kind.method() {
                Some(method) => method.reachable(context),
                None => SurfaceReachable::Nothing(SurfaceExclusionReason::NotAvailable),
            };
            (kind, reachable)
        })
        .collect()
}

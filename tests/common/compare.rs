//! The per-case comparison of the shape core with the independent search: for every side and
//! knot pair, "the search reaches the target" against `membership`, the solutions both ways,
//! and an independent check of every closed-form solution.

use super::{
    DISTINCT_KNOTS, Search, SearchOptions, de_boor, dist, full_index, local_knots, max_gap,
    pair_unknowns, span_of, triangle_of, triangle_size,
};
use knotshape::shape::{KnotPair, NotApplicable, ShapeQuery, SideChoice, Solution, membership};
use knotshape::spline::{Curve, Point};

/// Frame residual (barycentric units of the control triangle) up to which the search counts
/// a point as a solution. The refinement stops at 1e-14; inside targets end below 1e-13 (see
/// `residual_decades`), while the closed form accepts roots whose frame error is up to 1e-11
/// (`FRAME_RESIDUAL_TOLERANCE`), so targets between this and [`ABSENT`] are undecided.
pub const FOUND: f64 = 1e-12;

/// Frame residual above which the search says "no solution": the target is at least this far
/// (frame units) from the region. Targets whose distance to a region lies between [`FOUND`]
/// and this are within `ABSENT` of that region's boundary and are excluded (counted). The
/// search's residuals have a gap there: below 1e-12 when it reaches a target, at least 1e-9
/// otherwise (`residual_decades` over 20000 cases).
pub const ABSENT: f64 = 1e-6;

/// A disagreement on a domain's edge is excused only when the target pins the knots down
/// this loosely (relative to `R - L`): a thousand times the core's `KNOT_TOLERANCE`, so that a
/// well-conditioned target on an edge (coincident knots) must be decided right.
pub const ILL_CONDITIONED: f64 = 1e-9;

/// A closed-form solution, re-evaluated at `t` by two evaluators, lands within this fraction of
/// the triangle's size of the target (MATH.md: 1e-9).
pub const LANDING: f64 = 1e-9;

/// Statistics of a run of comparisons.
#[derive(Debug, Default)]
pub struct Tally {
    /// Treat disagreements on a domain's edge as failures too (for hand-made edge cases).
    pub strict_edges: bool,
    pub cases: usize,
    pub three_d: usize,
    pub rational: usize,
    pub clamped: usize,
    pub coincident_interior: usize,
    pub reachable_cases: usize,
    pub pair_checks: usize,
    pub found: usize,
    pub absent: usize,
    /// Pair checks whose search residual lies between `FOUND` and `ABSENT` (the target is
    /// within `ABSENT` of the region's boundary, in frame units).
    pub excluded: usize,
    /// Pair checks whose search solution lies within floating-point reach of the domain's edge
    /// (as decided by the conditioning: `Search::edge_uncertainty`).
    pub on_edge: usize,
    /// Disagreements among those (excused; listed).
    pub excused_on_edge: Vec<String>,
    /// Disagreements at an edge the keep-domain rule forbids (see `Search::touches_forbidden_end`):
    /// the search's solutions approach a target no allowed knot vector reaches (listed).
    pub open_end: Vec<String>,
    pub off_plane_checks: usize,
    pub solutions: usize,
    pub keep_domain_cases: usize,
    /// Largest knot difference (relative to `R - L`) between a closed-form and a searched
    /// solution where the target pins the knots down well.
    pub max_knot_disagreement: f64,
    /// Matches accepted only through the widened radius (the target pins the knots loosely).
    pub loosely_pinned: usize,
    pub max_landing: f64,
    pub max_excluded_residual: f64,
    pub evaluations: usize,
    /// Best search residuals by decade: `[0]` below 1e-16, `[k]` in `[1e-17+k, 1e-16+k)`.
    pub residual_decades: [usize; 18],
    pub failures: Vec<String>,
}

/// Checks one closed-form solution independently: monotone full knot vector, `u_{j+1} = t`,
/// only the pair's knots changed, keep-domain respected, and it lands on the target when
/// re-evaluated (by the crate's `Curve::point` and by this file's de Boor).
pub fn check_solution(
    curve: &Curve,
    t: f64,
    target: Point,
    solution: &Solution,
    keep_domain: bool,
    size: f64,
) -> Result<f64, String> {
    let old = curve.knots();
    let new = &solution.knots;
    let j = solution.span;
    let n = curve.control_points().len() - 1;
    if new.len() != old.len() || new.iter().any(|u| !u.is_finite()) {
        return Err(format!("bad knot vector {new:?}"));
    }
    if new.windows(2).any(|w| w[0] > w[1]) {
        return Err(format!("knots not monotone: {new:?}"));
    }
    if new[j + 1] != t {
        return Err(format!("u_{{j+1}} = {} != t = {t}", new[j + 1]));
    }
    let [l, a, b, c, e, r] = local_knots(new, j);
    // c > b, except the triple knot b = c = t by which Ω2 alone reaches d_{j-1} (MATH.md).
    let triple = solution.pair == KnotPair::Omega2 && b == t && c == t;
    let ordered = l <= a && a <= b && b <= t && t <= c && c <= e && e <= r && (c > b || triple);
    if !ordered {
        return Err(format!("monotonicity violated: {:?}", local_knots(new, j)));
    }
    let allowed: Vec<usize> = pair_unknowns(solution.pair)
        .iter()
        .map(|&k| full_index(j, k))
        .chain([j + 1])
        .collect();
    for i in 0..old.len() {
        if new[i] != old[i] && !allowed.contains(&i) {
            return Err(format!("knot {i} changed but is not the pair's"));
        }
    }
    if keep_domain && (new[3] != old[3] || new[n + 1] != old[n + 1]) {
        return Err("keep_domain violated".into());
    }
    let moved = curve.with_full_knots(new.clone()).ok_or("invalid knots")?;
    let by_core = moved.point(t).map_err(|e| e.to_string())?;
    let by_de_boor = de_boor(curve, new, t).ok_or("empty domain")?;
    let landing = dist(by_core, target).max(dist(by_de_boor, target)) / size;
    if landing.is_nan() || landing > LANDING {
        return Err(format!(
            "solution misses the target by {landing:e} (relative)"
        ));
    }
    Ok(landing)
}

/// Compares the shape core with the search for one curve, parameter and target (both sides,
/// all six pairs, `keep_domain` applied by both); `context` prefixes every message.
pub fn compare_with_search(
    curve: &Curve,
    t: f64,
    target: Point,
    keep_domain: bool,
    options: SearchOptions,
    context: &str,
    tally: &mut Tally,
) {
    let n = curve.control_points().len() - 1;
    let coordinates = &target[..curve.dimension().count()];
    let query = ShapeQuery {
        curve,
        parameter: t,
        side: SideChoice::Both,
        pairs: &KnotPair::ALL,
        families: Default::default(),
        keep_domain,
    };
    let outcome = membership(&query, coordinates).unwrap();
    for candidate in &outcome.candidates {
        let side = candidate.candidate.side;
        let j = span_of(curve, t, side);
        if candidate.candidate.span != j {
            tally.failures.push(format!(
                "{context}: {side:?} span {} != {j}",
                candidate.candidate.span
            ));
            continue;
        }
        if !(2..=n).contains(&j) {
            if candidate.candidate.is_applicable() {
                tally.failures.push(format!(
                    "{context}: {side:?} span {j} out of range but applicable"
                ));
            }
            continue;
        }
        let triangle = triangle_of(curve, j);
        let size = triangle_size(&triangle);
        let off_plane = match candidate.candidate.not_applicable {
            None => false,
            Some(NotApplicable::OffPlane { .. }) => true,
            Some(other) => {
                tally.failures.push(format!(
                    "{context}: {side:?} unexpectedly not applicable: {other:?}"
                ));
                continue;
            }
        };
        for pair in KnotPair::ALL {
            let mut search = Search::new(curve, j, t, target, pair, keep_domain);
            let result = search.run(options, FOUND);
            tally.evaluations += result.evaluations;
            tally.pair_checks += 1;
            let decade = if result.best_residual > 0.0 {
                (result.best_residual.log10().floor() + 17.0).clamp(0.0, 17.0) as usize
            } else {
                0
            };
            tally.residual_decades[decade] += 1;
            let label = format!("{context}: {side:?} j = {j} {pair:?}");
            let found = result.best_residual <= FOUND;
            let absent = result.best_residual > ABSENT;
            if off_plane {
                tally.off_plane_checks += 1;
                if found {
                    tally.failures.push(format!(
                        "{label}: off the plane per the core, but the search reaches it: {result:?}"
                    ));
                }
                continue;
            }
            let region = candidate.regions.iter().find(|r| r.pair == pair).unwrap();
            let ours: Vec<&Solution> = outcome
                .solutions
                .iter()
                .filter(|s| s.side == side && s.pair == pair)
                .collect();
            if region.contains == ours.is_empty() {
                tally
                    .failures
                    .push(format!("{label}: contains disagrees with the solutions"));
            }
            if region.knots != pair_unknowns(pair).map(|k| full_index(j, k)) {
                tally
                    .failures
                    .push(format!("{label}: region knots {:?}", region.knots));
            }
            for solution in &ours {
                tally.solutions += 1;
                match check_solution(curve, t, target, solution, keep_domain, size) {
                    Ok(landing) => tally.max_landing = tally.max_landing.max(landing),
                    Err(why) => tally.failures.push(format!("{label}: {why}")),
                }
            }
            let edge_uncertainty = search.edge_uncertainty(result.best_knots, result.best_residual);
            let on_edge = found && result.best_edge_slack <= edge_uncertainty;
            tally.on_edge += usize::from(on_edge);
            if !found && !absent {
                tally.excluded += 1;
                tally.max_excluded_residual = tally.max_excluded_residual.max(result.best_residual);
                continue;
            }
            tally.found += usize::from(found);
            tally.absent += usize::from(absent);
            let open_end = search.touches_forbidden_end(result.best_knots, edge_uncertainty);
            let ill_conditioned = edge_uncertainty >= ILL_CONDITIONED * search.scale();
            let excusable = on_edge && (open_end || (ill_conditioned && !tally.strict_edges));
            if found != region.contains && excusable {
                // Within floating-point reach of the domain's edge (a frozen keep-domain knot
                // counts as an edge): either verdict is right. An "open end" is an edge that
                // the keep-domain rule forbids (more than 4 knots at a domain end): the search
                // approaches it arbitrarily closely, but no allowed knot vector reaches it.
                let list = if open_end {
                    &mut tally.open_end
                } else {
                    &mut tally.excused_on_edge
                };
                list.push(format!(
                    "{label}: search residual {:e} at slack {:e} <= {edge_uncertainty:e}, membership {}",
                    result.best_residual, result.best_edge_slack, region.contains
                ));
                continue;
            }
            if found != region.contains {
                tally.failures.push(format!(
                    "{label}: search {} (residual {:e} relative, at knots {:?}, slack {:e}) but membership says {}; closed form: {:?}",
                    if found { "reaches it" } else { "does not reach it" },
                    result.best_residual,
                    result.best_knots,
                    result.best_edge_slack,
                    region.contains,
                    ours.iter().map(|s| local_knots(&s.knots, j)).collect::<Vec<_>>()
                ));
                continue;
            }
            if !found {
                continue;
            }
            // Same solutions, both ways: within the search's conditioning-aware radius.
            let [l, .., r] = local_knots(curve.knots(), j);
            let scale = r - l;
            let closed: Vec<([f64; 4], f64)> = ours
                .iter()
                .map(|s| {
                    let [_, a, b, c, e, _] = local_knots(&s.knots, j);
                    let v = [a, b, c, e];
                    let residual = search.frame_residual(v);
                    let radius = search.same_solution_radius(v, residual);
                    (v, radius)
                })
                .collect();
            let mut matched = |v: &[f64; 4], radius: f64, w: &[f64; 4], radius_w: f64| {
                let gap = max_gap(v, w);
                let ok = gap <= radius.max(radius_w);
                if ok && radius.max(radius_w) <= DISTINCT_KNOTS * scale {
                    tally.max_knot_disagreement = tally.max_knot_disagreement.max(gap / scale);
                } else if ok {
                    tally.loosely_pinned += 1;
                }
                ok
            };
            let mut missing = Vec::new();
            for found in &result.solutions {
                if !closed
                    .iter()
                    .any(|(w, rw)| matched(&found.knots, found.radius, w, *rw))
                {
                    missing.push(format!(
                        "search solution {found:?} is not the closed form's"
                    ));
                }
            }
            for (w, rw) in &closed {
                if !result
                    .solutions
                    .iter()
                    .any(|found| matched(&found.knots, found.radius, w, *rw))
                {
                    missing.push(format!("closed-form solution {w:?} was not found"));
                }
            }
            for why in missing {
                tally.failures.push(format!(
                    "{label}: {why}; search {:?}, closed form {closed:?}",
                    result.solutions
                ));
            }
        }
    }
}

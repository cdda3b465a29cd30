//! The nearest reachable target (`nearest_reachable`) against brute force: a dense grid over
//! each pair's knot domain, every grid point's knot vector evaluated at `t` by the test's own
//! de Boor, the keep-domain rule applied by the test itself. The search must be at least as
//! close as every grid point, and every solution it returns must reach its point.
#![allow(clippy::unwrap_used)]

mod common;

use common::{
    CurveMix, Search, SplitMix64, de_boor, dist, grid_nodes, random_curve, span_of, triangle_of,
    triangle_size,
};
use knotshape::shape::{
    KnotPair, ShapeQuery, Side, SideChoice, SolveOptions, nearest_reachable, solve,
};
use knotshape::spline::{Curve, Point};

/// Random curves tried.
const CURVES: usize = 120;

/// Grid nodes per axis of each pair's (unit-square parametrised) domain: Chebyshev–Lobatto,
/// crowded at the edges, where the nearest points lie.
const GRID: usize = 48;

/// Whether `new` is an edit the keep-domain rule allows (written here, not taken from the
/// crate): the domain's ends keep their values and no end value gains copies beyond
/// `max(old, 4)`; and the vector is non-decreasing with a non-empty domain.
fn allowed(curve: &Curve, new: &[f64], keep_domain: bool) -> bool {
    let old = curve.knots();
    let n = curve.control_points().len() - 1;
    if new.windows(2).any(|w| w[0] > w[1]) || new[3] >= new[n + 1] {
        return false;
    }
    if !keep_domain {
        return true;
    }
    let count = |knots: &[f64], value: f64| knots.iter().filter(|&&u| u == value).count();
    [3, n + 1]
        .into_iter()
        .all(|i| new[i] == old[i] && count(new, new[i]) <= count(old, old[i]).max(4))
}

/// The least distance from `target` to a point some allowed grid edit reaches, or `None`.
fn brute_force(curve: &Curve, t: f64, target: Point, keep_domain: bool) -> Option<f64> {
    let n = curve.control_points().len() - 1;
    let nodes = grid_nodes(GRID);
    let mut best: Option<f64> = None;
    for side in [Side::Right, Side::Left] {
        let span = span_of(curve, t, side);
        if span < 2 || span > n {
            continue;
        }
        let triangle = triangle_of(curve, span);
        let size = triangle_size(&triangle);
        let e1 = common::sub(triangle[0], triangle[1]);
        let e2 = common::sub(triangle[2], triangle[1]);
        let cross = [
            e1[1] * e2[2] - e1[2] * e2[1],
            e1[2] * e2[0] - e1[0] * e2[2],
            e1[0] * e2[1] - e1[1] * e2[0],
        ];
        if common::norm(cross) <= 1e-9 * size * size {
            continue; // degenerate: the service does not apply this side
        }
        for pair in KnotPair::ALL {
            let search = Search::new(curve, span, t, target, pair, keep_domain);
            for &z0 in &nodes {
                for &z1 in &nodes {
                    let knots = search.full_knots(search.knots_at([z0, z1]));
                    if !allowed(curve, &knots, keep_domain) {
                        continue;
                    }
                    let Some(point) = de_boor(curve, &knots, t) else {
                        continue;
                    };
                    let d = dist(point, target);
                    if d.is_finite() && best.is_none_or(|b| d < b) {
                        best = Some(d);
                    }
                }
            }
        }
    }
    best
}

#[test]
fn nearest_reachable_beats_a_dense_grid_and_every_solution_reaches_it() {
    let mut rng = SplitMix64::new(2026);
    let mut checked = 0;
    for _ in 0..CURVES {
        let curve = random_curve(&mut rng, CurveMix::default());
        let (lo, hi) = curve.domain();
        let t = rng.range(lo, hi);
        let keep_domain = rng.chance(0.7);
        let dimension = curve.dimension().count();
        // Targets around the curve: some near the picked point, some anywhere in the box.
        let base = curve.point(t).unwrap();
        let spread = if rng.chance(0.5) { 1.0 } else { 6.0 };
        let mut target = [0.0; 3];
        for (c, value) in target.iter_mut().enumerate().take(dimension) {
            *value = base[c] + rng.range(-spread, spread);
        }
        let query = ShapeQuery {
            keep_domain,
            ..ShapeQuery::new(&curve, t)
        };
        let direct = solve(
            &query,
            &target[..dimension],
            SolveOptions {
                measure_deviation: false,
            },
        )
        .unwrap();
        if direct.reachable() {
            continue;
        }
        let brute = brute_force(&curve, t, target, keep_domain);
        let nearest = nearest_reachable(&query, target, true).unwrap();
        let (Some(brute), Some(nearest)) = (brute, nearest.as_ref()) else {
            assert!(
                brute.is_none() && nearest.is_none(),
                "grid {brute:?} vs search {nearest:?} (t = {t}, keep {keep_domain}, {curve:?})"
            );
            continue;
        };
        checked += 1;
        let size = curve
            .control_points()
            .iter()
            .flatten()
            .fold(1.0f64, |m, v| m.max(v.abs()));
        assert!(
            nearest.distance <= brute + 1e-9 * size,
            "search {} farther than grid {brute} (t = {t}, keep {keep_domain}, target {target:?}, {curve:?})",
            nearest.distance
        );
        assert!((dist(nearest.point, target) - nearest.distance).abs() <= 1e-12 * size);
        assert!(!nearest.solutions.is_empty());
        for solution in &nearest.solutions {
            assert!(
                allowed(&curve, &solution.knots, keep_domain),
                "{solution:?}"
            );
            let reached = de_boor(&curve, &solution.knots, t).unwrap();
            assert!(
                dist(reached, nearest.point) <= 1e-9 * size,
                "a solution misses its point: {reached:?} vs {:?}",
                nearest.point
            );
            assert!(solution.max_deviation.is_some());
        }
        let deviations: Vec<f64> = nearest
            .solutions
            .iter()
            .map(|s| s.max_deviation.unwrap())
            .collect();
        assert!(deviations.windows(2).all(|w| w[0] <= w[1]), "sorted");
    }
    assert!(checked >= CURVES / 3, "only {checked} unreachable targets");
}

#[test]
fn a_side_choice_limits_the_search() {
    let mut rng = SplitMix64::new(7);
    let curve = random_curve(
        &mut rng,
        CurveMix {
            three_d: 0.0,
            rational: 0.0,
            ..CurveMix::default()
        },
    );
    let (lo, hi) = curve.domain();
    let t = lo + 0.5 * (hi - lo);
    let far = [100.0, 100.0, 0.0];
    let both = nearest_reachable(&ShapeQuery::new(&curve, t), far, false).unwrap();
    let right = nearest_reachable(
        &ShapeQuery {
            side: SideChoice::Right,
            ..ShapeQuery::new(&curve, t)
        },
        far,
        false,
    )
    .unwrap();
    if let (Some(both), Some(right)) = (both, right) {
        assert!(both.distance <= right.distance + 1e-12);
        assert!(right.solutions.iter().all(|s| s.side == Side::Right));
    }
}

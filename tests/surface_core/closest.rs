//! The closest point against a brute-force reference: a grid over every patch of the searched
//! rectangle (knot lines, edges and corners included), evaluated by the test's own textbook
//! evaluator, its best points refined by a derivative-free pattern search. The search must
//! never be farther than the reference (beyond the tolerance): on random surfaces (degrees
//! 1–7, rational, coincident knots, tiny spans), on real ones, and on adversarial queries
//! (near edges and corners, near-ties between two sheets, points on the surface, far away,
//! whole lines and sheets of ties).

use knotshape::surface::{COORDINATE_ROUNDING, SURFACE_CLOSEST_TOLERANCE, SurfaceClosestSearch};
use proptest::prelude::*;

use crate::common::SplitMix64;
use crate::config;
use crate::corpus::{SurfaceData, surfaces};
use crate::generators::surface_data;

/// Grid points per patch and direction of the reference.
const GRID: usize = 7;

/// Grid points refined by the reference's pattern search.
const REFINED: usize = 6;

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// The reference: `(distance, u, v)` of the nearest point found by brute force over
/// `range` (module docs).
fn brute_force(data: &SurfaceData, q: [f64; 3], range: [(f64, f64); 2]) -> (f64, f64, f64) {
    let lines = |knots: &[f64], (lo, hi): (f64, f64)| {
        let mut cuts: Vec<f64> = knots
            .iter()
            .copied()
            .filter(|&t| lo < t && t < hi)
            .collect();
        cuts.insert(0, lo);
        cuts.push(hi);
        cuts.dedup();
        let mut values = Vec::new();
        for pair in cuts.windows(2) {
            for k in 0..GRID {
                values.push(pair[0] + (pair[1] - pair[0]) * k as f64 / (GRID - 1) as f64);
            }
        }
        values.dedup();
        if values.is_empty() {
            values.push(lo);
        }
        values
    };
    let us = lines(&data.knots_u, range[0]);
    let vs = lines(&data.knots_v, range[1]);
    let mut grid: Vec<(f64, f64, f64)> = Vec::with_capacity(us.len() * vs.len());
    for &u in &us {
        for &v in &vs {
            grid.push((dist(data.point_f64(u, v), q), u, v));
        }
    }
    grid.sort_by(|a, b| a.0.total_cmp(&b.0));
    let step = (
        (range[0].1 - range[0].0) / us.len().max(2) as f64,
        (range[1].1 - range[1].0) / vs.len().max(2) as f64,
    );
    grid.iter()
        .take(REFINED)
        .map(|&start| pattern_search(data, q, range, start, step))
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .unwrap()
}

/// Evaluations of one pattern search at most (a crawl along a narrow valley ends there; the
/// reference then is a point of the surface farther than the true minimum, never nearer).
const MAX_PATTERN_EVALUATIONS: usize = 4000;

/// A compass search from `start`: try the eight neighbours at the current step (clamped to
/// the range), move to the best improvement, else halve the step, until the step is below
/// `1e-13` of the range or [`MAX_PATTERN_EVALUATIONS`] are spent.
fn pattern_search(
    data: &SurfaceData,
    q: [f64; 3],
    range: [(f64, f64); 2],
    start: (f64, f64, f64),
    step: (f64, f64),
) -> (f64, f64, f64) {
    let (mut best, mut u, mut v) = start;
    let (mut hu, mut hv) = step;
    let floor = (
        1e-13 * (range[0].1 - range[0].0).max(1e-300),
        1e-13 * (range[1].1 - range[1].0).max(1e-300),
    );
    let mut evaluations = 0;
    while (hu > floor.0 || hv > floor.1) && evaluations < MAX_PATTERN_EVALUATIONS {
        evaluations += 8;
        let mut moved = false;
        for (du, dv) in [
            (1.0, 0.0),
            (-1.0, 0.0),
            (0.0, 1.0),
            (0.0, -1.0),
            (1.0, 1.0),
            (-1.0, -1.0),
            (1.0, -1.0),
            (-1.0, 1.0),
        ] {
            let a = (u + du * hu).clamp(range[0].0, range[0].1);
            let b = (v + dv * hv).clamp(range[1].0, range[1].1);
            let d = dist(data.point_f64(a, b), q);
            if d < best {
                (best, u, v) = (d, a, b);
                moved = true;
            }
        }
        if !moved {
            hu *= 0.5;
            hv *= 0.5;
        }
    }
    (best, u, v)
}

/// The verdict on one query: the search's answer is a point of the surface at its
/// parameters, inside the range, and not farther than the reference beyond the tolerance.
fn check(data: &SurfaceData, q: [f64; 3], range: Option<[(f64, f64); 2]>) -> Result<(), String> {
    let surface = data.surface();
    let search = SurfaceClosestSearch::new(&surface, range).map_err(|e| e.to_string())?;
    let range = search.range();
    let found = search.closest(q);
    let (reference, ru, rv) = brute_force(data, q, range);
    let size = data.size();
    let inside = range[0].0 <= found.u
        && found.u <= range[0].1
        && range[1].0 <= found.v
        && found.v <= range[1].1;
    let at = data.point_f64(found.u, found.v);
    let consistent = dist(at, found.point) <= 1e-12 * (size + dist(at, [0.0; 3]))
        && (dist(found.point, q) - found.distance).abs() <= 1e-14 * (size + found.distance);
    let magnitude = data
        .poles
        .iter()
        .flatten()
        .flatten()
        .fold(0.0f64, |m, x| m.max(x.abs()));
    let allowance =
        SURFACE_CLOSEST_TOLERANCE * (size + reference) + COORDINATE_ROUNDING * magnitude;
    if !inside || !consistent || found.distance > reference + allowance {
        return Err(format!(
            "{} q {q:?}: found ({}, {}) at {:e}, reference ({ru}, {rv}) at {reference:e} (inside {inside}, consistent {consistent})",
            data.id, found.u, found.v, found.distance
        ));
    }
    Ok(())
}

/// Adversarial queries for a surface: points on it, just off its edges and corners (along the
/// outward continuation of the edge), near and far.
fn queries(data: &SurfaceData, rng: &mut SplitMix64) -> Vec<[f64; 3]> {
    let [(u0, u1), (v0, v1)] = data.domain();
    let size = data.size().max(1e-300);
    let mut out = Vec::new();
    // On the surface.
    let (u, v) = (rng.range(u0, u1), rng.range(v0, v1));
    out.push(data.point_f64(u, v));
    // Just off an edge and a corner: a point beyond the edge along the surface's continuation.
    let edge = data.point_f64(u1, rng.range(v0, v1));
    let inside = data.point_f64(u1 - 1e-3 * (u1 - u0), rng.range(v0, v1));
    out.push(std::array::from_fn(|c| {
        edge[c] + (edge[c] - inside[c]) * 10.0
    }));
    let corner = data.point_f64(u0, v0);
    out.push(std::array::from_fn(|c| {
        corner[c] + 1e-3 * size * rng.range(-1.0, 1.0)
    }));
    // Near and far.
    let centre = data.point_f64(0.5 * (u0 + u1), 0.5 * (v0 + v1));
    out.push(std::array::from_fn(|c| {
        centre[c] + 0.3 * size * rng.range(-1.0, 1.0)
    }));
    out.push(std::array::from_fn(|c| {
        centre[c] + 1e3 * size * rng.range(-1.0, 1.0)
    }));
    out
}

proptest! {
    #![proptest_config(proptest::test_runner::Config { cases: 48, ..config() })]

    /// Random surfaces, random and adversarial queries, the whole domain and a sub-range.
    #[test]
    fn the_closest_point_is_never_farther_than_brute_force(data in surface_data(), seed in any::<u64>()) {
        let mut rng = SplitMix64::new(seed);
        let [(u0, u1), (v0, v1)] = data.domain();
        for q in queries(&data, &mut rng) {
            prop_assert!(check(&data, q, None).is_ok(), "{}", check(&data, q, None).unwrap_err());
        }
        let a = rng.range(u0, u1);
        let b = rng.range(v0, v1);
        let range = [(u0.min(a), a.max(u0)), (b, v1)];
        let q = data.point_f64(u1, v0);
        prop_assert!(check(&data, q, Some(range)).is_ok(), "{}", check(&data, q, Some(range)).unwrap_err());
    }
}

/// Real surfaces spread over the corpus (every 15th, so every kind is met), three
/// adversarial queries each.
#[test]
fn real_surfaces_closest_points_are_never_farther_than_brute_force() {
    let mut rng = SplitMix64::new(0x5eed_c105);
    let mut failures = Vec::new();
    for data in surfaces().iter().step_by(15) {
        for q in queries(data, &mut rng).into_iter().take(4) {
            if let Err(failure) = check(data, q, None) {
                failures.push(failure);
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} failures: {failures:#?}",
        failures.len()
    );
}

/// The surface from flat data (poles `[i][j]`, full knots).
fn surface_of(
    degrees: (usize, usize),
    poles: &[Vec<[f64; 3]>],
    knots: (&[f64], &[f64]),
    weights: Option<&[Vec<f64>]>,
) -> knotshape::surface::Surface {
    knotshape::surface::Surface::from_knot_forms(
        degrees,
        poles,
        (
            knotshape::spline::KnotForm::Flat(knots.0),
            knotshape::spline::KnotForm::Flat(knots.1),
        ),
        weights,
        &knotshape::surface::SurfaceLimits::default(),
    )
    .unwrap()
}

/// A "U" folded in `u` (a quadratic from the lip `(0, v, 1)` round to the lip `(0, v, -1)`,
/// straight in `v`): a query left of the lips at height `δ` is nearer the upper lip (`u = 0`)
/// for `δ > 0`, the lower (`u = 1`) for `δ < 0`, by about `1.8 δ`; at `δ = 0` they tie and the
/// smaller `u` wins. (Along `u` the distance is flat at the lips, so points a little inside a
/// lip tie with it.)
#[test]
fn near_ties_between_two_sheets_go_to_the_nearer_one() {
    let poles: Vec<Vec<[f64; 3]>> = [[0.0, 1.0], [2.0, 0.0], [0.0, -1.0]]
        .iter()
        .map(|xz| (0..2).map(|j| [xz[0], j as f64, xz[1]]).collect())
        .collect();
    let knots_u = [0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
    let knots_v = [0.0, 0.0, 1.0, 1.0];
    for rational in [false, true] {
        let weights = [vec![1.0; 2], vec![3.0; 2], vec![1.0; 2]];
        let surface = surface_of(
            (2, 1),
            &poles,
            (&knots_u, &knots_v),
            rational.then_some(&weights[..]),
        );
        let search = SurfaceClosestSearch::new(&surface, None).unwrap();
        for (delta, upper) in [(1e-6, true), (1e-9, true), (-1e-9, false), (-1e-6, false)] {
            let found = search.closest([-0.5, 0.3, delta]);
            assert_eq!(
                found.u < 0.5,
                upper,
                "δ = {delta}, rational {rational}: {found:?}"
            );
            assert_eq!(found.point[2] > 0.0, upper, "{found:?}");
            assert!((found.v - 0.3).abs() < 1e-12, "{found:?}");
            let expected = (0.25f64 + (1.0 - delta.abs()).powi(2)).sqrt();
            assert!((found.distance - expected).abs() < 1e-14, "{found:?}");
        }
        // An exact tie: the smaller u.
        let found = search.closest([-0.5, 0.3, 0.0]);
        assert_eq!(found.u, 0.0, "rational {rational}: {found:?}");
    }
}

/// The octant of the unit sphere (as tests/api/surfaces.rs builds it).
fn octant() -> knotshape::surface::Surface {
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let arc = [([1.0, 0.0], 1.0), ([1.0, 1.0], w), ([0.0, 1.0], 1.0)];
    let poles: Vec<Vec<[f64; 3]>> = arc
        .iter()
        .map(|(xz, _)| {
            arc.iter()
                .map(|(xy, _)| [xz[0] * xy[0], xz[0] * xy[1], xz[1]])
                .collect()
        })
        .collect();
    let weights: Vec<Vec<f64>> = arc
        .iter()
        .map(|(_, a)| arc.iter().map(|(_, b)| a * b).collect())
        .collect();
    let knots = [0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
    surface_of((2, 2), &poles, (&knots, &knots), Some(&weights))
}

/// From the centre of a sphere every point is as near: the first corner `(0, 0)` is the
/// answer; off the centre, the point in that direction.
#[test]
fn the_centre_of_a_sphere_ties_everywhere_and_takes_the_first_corner() {
    let sphere = octant();
    let search = SurfaceClosestSearch::new(&sphere, None).unwrap();
    let found = search.closest([0.0, 0.0, 0.0]);
    assert_eq!((found.u, found.v), (0.0, 0.0), "{found:?}");
    assert!((found.distance - 1.0).abs() < 1e-15);
    let direction = [0.3f64, 0.5, 0.4];
    let length = dist(direction, [0.0; 3]);
    let q = direction.map(|c| 0.1 * c / length);
    let found = search.closest(q);
    let expected = direction.map(|c| c / length);
    // The distance is flat there (it changes by 0.1 θ² / 2 for a point θ away), so points
    // within about 7e-6 tie within the tolerance (and the smallest u of them is answered).
    assert!(dist(found.point, expected) < 1e-4, "{found:?}");
    let tolerance = SURFACE_CLOSEST_TOLERANCE * (3f64.sqrt() + 0.9);
    assert!((found.distance - 0.9).abs() <= tolerance, "{found:?}");
}

/// From a point of a cylinder's axis the whole circle at that height is as near: the
/// smallest `u` wins, at the height's `v`.
#[test]
fn the_axis_of_a_cylinder_takes_the_smallest_u() {
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let poles: Vec<Vec<[f64; 3]>> = [[1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
        .iter()
        .map(|xy| (0..2).map(|j| [xy[0], xy[1], 2.0 * j as f64]).collect())
        .collect();
    let weights = vec![vec![1.0; 2], vec![w; 2], vec![1.0; 2]];
    let cylinder = surface_of(
        (2, 1),
        &poles,
        (&[0.0, 0.0, 0.0, 1.0, 1.0, 1.0], &[0.0, 0.0, 1.0, 1.0]),
        Some(&weights),
    );
    let search = SurfaceClosestSearch::new(&cylinder, None).unwrap();
    let found = search.closest([0.0, 0.0, 0.5]);
    assert_eq!(found.u, 0.0, "{found:?}");
    assert!((found.v - 0.25).abs() < 1e-9, "{found:?}");
    assert!((found.distance - 1.0).abs() < 1e-15);
    // Restricted to u in [0.5, 1]: the range's smallest u.
    let restricted = SurfaceClosestSearch::new(&cylinder, Some([(0.5, 1.0), (0.0, 1.0)])).unwrap();
    assert_eq!(restricted.closest([0.0, 0.0, 0.5]).u, 0.5);
}

/// Points of real surfaces are found at distance zero, within the tolerance.
#[test]
fn points_on_real_surfaces_are_found() {
    let mut rng = SplitMix64::new(0x0f5_0f5);
    for data in surfaces().iter().step_by(7) {
        let surface = data.surface();
        let search = SurfaceClosestSearch::new(&surface, None).unwrap();
        let [(u0, u1), (v0, v1)] = data.domain();
        let magnitude = data
            .poles
            .iter()
            .flatten()
            .flatten()
            .fold(0.0f64, |m, x| m.max(x.abs()));
        for _ in 0..3 {
            let q = surface.point(rng.range(u0, u1), rng.range(v0, v1));
            let found = search.closest(q);
            assert!(
                found.distance
                    <= SURFACE_CLOSEST_TOLERANCE * data.size() + COORDINATE_ROUNDING * magnitude,
                "{}: {q:?} found at {:e}",
                data.id,
                found.distance
            );
        }
    }
}

/// A periodic direction is searched across its seam: a query next to the seam finds the
/// seam's neighbourhood on either side, and the seam itself (both `u = 0` and the period's
/// end) ties to `u = 0`.
#[test]
fn a_periodic_surface_is_searched_across_its_seam() {
    let rows = [[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]];
    let poles: Vec<Vec<[f64; 3]>> = rows
        .iter()
        .map(|xy| vec![[xy[0], xy[1], 0.0], [xy[0], xy[1], 1.0]])
        .collect();
    let band = knotshape::surface::Surface::from_knot_forms(
        (3, 1),
        &poles,
        (
            knotshape::spline::KnotForm::Periodic {
                knots: &[0.0, 1.0, 2.0, 3.0, 4.0],
                multiplicities: &[1, 1, 1, 1, 1],
            },
            knotshape::spline::KnotForm::Flat(&[0.0, 0.0, 1.0, 1.0]),
        ),
        None::<&[Vec<f64>]>,
        &knotshape::surface::SurfaceLimits::default(),
    )
    .unwrap();
    let search = SurfaceClosestSearch::new(&band, None).unwrap();
    let seam = band.point(0.0, 0.5);
    let outward = [seam[0] * 2.0, seam[1] * 2.0, 0.5];
    let found = search.closest(outward);
    assert_eq!(found.u, 0.0, "{found:?}");
    // Just before and after the seam: found there (not across the period), as near as the
    // point the query was made from, with the distance's gradient zero (an interior minimum).
    for u in [3.99, 0.01] {
        let p = band.point(u, 0.5);
        let q = [2.0 * p[0], 2.0 * p[1], 0.5];
        let found = search.closest(q);
        assert!((found.u - u).abs() < 0.05, "{u}: {found:?}");
        assert!(found.distance <= dist(p, q));
        let partials = band.partials(found.u, found.v, 1);
        let gap: [f64; 3] = std::array::from_fn(|c| found.point[c] - q[c]);
        let along =
            gap[0] * partials.du()[0] + gap[1] * partials.du()[1] + gap[2] * partials.du()[2];
        assert!(along.abs() < 1e-12, "{u}: gradient {along:e}");
    }
}

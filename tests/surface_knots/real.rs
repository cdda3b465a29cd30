//! The real surfaces of the corpus (tests/data/real_surfaces.json.gz) through the solve:
//! at a point inside each surface, targets planted by the envelope step and one moved knot in
//! each direction of degree ≥ 3 with interior knots (reachable by an envelope pair of that
//! direction) and a 3D offset; every solution is checked by the independent evaluator.

use knotshape::shape::family::Family;
use knotshape::surface::Direction;
use knotshape::surface::edit::knots::{SurfaceKnotFamily, solve_surface_knots};

use crate::properties::check_solution;
use crate::random::Rng;
use crate::real_surfaces::SurfaceData;
use crate::reference::Net;

/// Every surface of the corpus.
fn corpus() -> Vec<SurfaceData> {
    crate::real_surfaces::load()
}

/// The iso-curve's control points along `direction` through `(u, v)`, by the reference
/// basis: `D_i = Σ_l M_l w_il d_il / Σ_l M_l w_il` (`U`: `M` the `v` basis at `v`).
fn iso_poles(net: &Net, direction: Direction, (u, v): (f64, f64)) -> Vec<[f64; 3]> {
    let (nu, nv) = (net.poles.len(), net.poles[0].len());
    let weight = |i: usize, j: usize| net.weights.as_ref().map_or(1.0, |w| w[i][j]);
    match direction {
        Direction::U => {
            let m = crate::reference::basis(&net.knots_v, net.degrees.1, v);
            (0..nu)
                .map(|i| {
                    let w: f64 = (0..nv).map(|j| m[j] * weight(i, j)).sum();
                    std::array::from_fn(|c| {
                        (0..nv)
                            .map(|j| m[j] * weight(i, j) * net.poles[i][j][c])
                            .sum::<f64>()
                            / w
                    })
                })
                .collect()
        }
        Direction::V => {
            let m = crate::reference::basis(&net.knots_u, net.degrees.0, u);
            (0..nv)
                .map(|j| {
                    let w: f64 = (0..nu).map(|i| m[i] * weight(i, j)).sum();
                    std::array::from_fn(|c| {
                        (0..nu)
                            .map(|i| m[i] * weight(i, j) * net.poles[i][j][c])
                            .sum::<f64>()
                            / w
                    })
                })
                .collect()
        }
    }
}

/// The largest triangle of `points` over their extent squared (0 for collinear points).
fn flatness(points: &[[f64; 3]]) -> f64 {
    let mut extent = 0.0f64;
    let mut area = 0.0f64;
    for a in 0..points.len() {
        for b in a + 1..points.len() {
            extent = extent.max(crate::reference::distance(points[a], points[b]));
            for c in b + 1..points.len() {
                let (e, f) = (
                    std::array::from_fn::<f64, 3, _>(|k| points[b][k] - points[a][k]),
                    std::array::from_fn::<f64, 3, _>(|k| points[c][k] - points[a][k]),
                );
                let cross = [
                    e[1] * f[2] - e[2] * f[1],
                    e[2] * f[0] - e[0] * f[2],
                    e[0] * f[1] - e[1] * f[0],
                ];
                area = area
                    .max((cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]).sqrt());
            }
        }
    }
    if extent > 0.0 {
        area / (extent * extent)
    } else {
        0.0
    }
}

#[test]
fn real_surfaces_solve_planted_and_offset_targets() {
    let surfaces = corpus();
    assert!(!surfaces.is_empty());
    let mut rng = Rng::new(28);
    let (mut planted, mut planted_found, mut solutions_checked) = (0, 0, 0);
    for (index, data) in surfaces.iter().enumerate() {
        let net = Net {
            degrees: (data.degree_u, data.degree_v),
            knots_u: data.knots_u.clone(),
            knots_v: data.knots_v.clone(),
            poles: data.poles.clone(),
            weights: data.weights.clone(),
        };
        let surface = net.surface();
        let (du, dv) = net.domain();
        // A parameter in the middle of a span near the middle of each direction.
        let middle = |knots: &[f64], p: usize, (lo, hi): (f64, f64)| {
            let t = 0.5 * (lo + hi);
            let n = knots.len() - p - 1;
            let j = (p..n)
                .rfind(|&j| knots[j] <= t && knots[j] < knots[j + 1])
                .unwrap();
            (j, knots[j] + 0.37 * (knots[j + 1] - knots[j]))
        };
        let (ju, u) = middle(&net.knots_u, net.degrees.0, du);
        let (jv, v) = middle(&net.knots_v, net.degrees.1, dv);
        let point = net.point(u, v);
        let size = surface.size();
        let mut targets: Vec<(Option<Direction>, [f64; 3])> = Vec::new();
        // Planted in each direction of degree ≥ 3: t_{j+1} := t̃, and t_{j+2} moved a third of
        // its room (interior knots only): an envelope pair holding t_{j+2} reaches it.
        for (direction, j, t) in [(Direction::U, ju, u), (Direction::V, jv, v)] {
            let (knots, p) = match direction {
                Direction::U => (&net.knots_u, net.degrees.0),
                Direction::V => (&net.knots_v, net.degrees.1),
            };
            let n = knots.len() - p - 1;
            let flat = flatness(&iso_poles(&net, direction, (u, v))[j + 1 - p..=j]);
            if flat < 1e-6 {
                // The poles acting are (nearly) collinear: knot moves only slide the point
                // along a line, and the pairs' regions are slivers (the curve method's rule).
                continue;
            }
            if p >= 3 && j + 2 < n && j + 1 > p && knots[j + 1] < knots[j + 3] {
                let mut k = knots.clone();
                k[j + 1] = t;
                k[j + 2] += (k[j + 3] - k[j + 2]) / 3.0;
                let target = match direction {
                    Direction::U => net.point_with(&k, &net.knots_v, u, v),
                    Direction::V => net.point_with(&net.knots_u, &k, u, v),
                };
                targets.push((Some(direction), target));
            }
        }
        // A 3D offset on every fourth surface (the debug build's time).
        if index % 4 == 0 {
            let d = [rng.normal(), rng.normal(), rng.normal()];
            let l = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            targets.push((
                None,
                std::array::from_fn(|k| point[k] + 0.01 * size * d[k] / l),
            ));
        }
        for (is_planted, target) in targets {
            let solutions = solve_surface_knots(&surface, u, v, target, true);
            for solution in &solutions {
                check_solution(&net, (u, v), target, solution, &mut rng)
                    .unwrap_or_else(|breach| panic!("{}: {breach}", data.id));
                solutions_checked += 1;
            }
            if let Some(direction) = is_planted {
                planted += 1;
                let envelope = SurfaceKnotFamily::Iso {
                    direction,
                    family: Family::Envelope,
                };
                if solutions.iter().any(|s| s.family == envelope) {
                    planted_found += 1;
                } else {
                    eprintln!("{}: planted target not reached", data.id);
                }
            }
        }
    }
    eprintln!("planted {planted_found}/{planted}, solutions checked {solutions_checked}");
    assert!(planted > 0 && solutions_checked > 0);
    // A planted target is a solution of every envelope pair holding the moved knot; the
    // solver may only miss one whose pair is degenerate (collinear poles acting).
    assert!(
        planted_found * 10 >= planted * 9,
        "planted {planted_found}/{planted}"
    );
}

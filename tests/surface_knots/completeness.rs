//! Completeness of the mixed moves against brute force: for every mixed set (as the method
//! defines them, enumerated here independently of the solver), a grid over the unknown
//! knots' box, Newton's method from every grid local minimum of `|S(ũ, ṽ) − p|` (finite
//! differences on the reference evaluator), and every solution found inside the box must be
//! among the solver's.

use crate::random::{Rng, net, parameter};
use crate::reference::{Net, distance};
use knotshape::surface::Direction;
use knotshape::surface::edit::knots::{
    SurfaceKnotFamily, SurfaceKnotOptions, SurfaceKnotSolution, nearest_surface_knot_target,
    solve_surface_knots, solve_surface_knots_with,
};

/// One direction's part of a mixed set: the knot set to the parameter (envelope), and the
/// unknown knots (full indices).
#[derive(Debug, Clone)]
struct Part {
    moved: Option<usize>,
    unknowns: Vec<usize>,
}

/// The parts of one direction (degree `p`, knots, parameter `t`): as the pair direction
/// (`size = 2`): the envelope (both sides) of degree ≥ 3 or a quadratic's own knots; as the
/// single direction (`size = 1`): the envelope on either side (degree ≥ 2) and the direct
/// knots. Domain ends never move (`keep_domain`).
fn parts(knots: &[f64], p: usize, t: f64, size: usize) -> Vec<Part> {
    let n = knots.len() - p - 1;
    let j = (p..n)
        .rfind(|&j| knots[j] <= t && knots[j] < knots[j + 1])
        .unwrap();
    let mut out = Vec::new();
    let mut sets = |relevant: Vec<usize>, moved: Option<usize>| {
        let relevant: Vec<usize> = relevant.into_iter().filter(|&k| k > p && k < n).collect();
        if size == 1 {
            for &k in &relevant {
                out.push(Part {
                    moved,
                    unknowns: vec![k],
                });
            }
        } else {
            for (x, &a) in relevant.iter().enumerate() {
                for &b in &relevant[x + 1..] {
                    out.push(Part {
                        moved,
                        unknowns: vec![a, b],
                    });
                }
            }
        }
    };
    let envelope = if size == 2 { p >= 3 } else { p >= 2 };
    if envelope {
        for r in [j + 1, j] {
            if r < p
                || r > n
                || ((r == p || r == n) && knots[r] != t)
                || knots[r - 1] >= knots[r + 1]
            {
                continue;
            }
            let relevant: Vec<usize> = (r + 1 - p..r).chain(r + 1..r + p).collect();
            sets(relevant, Some(r));
        }
    }
    if size == 1 || p == 2 {
        sets((j + 1 - p..=j + p).collect(), None);
    }
    out
}

/// Every mixed set with two unknown knots along `pair`: the pair direction's parts (size 2)
/// with each of the other direction's (size 1).
fn mixed_parts(net: &Net, pair: Direction, (u, v): (f64, f64)) -> Vec<(Part, Part)> {
    let u_side = (&net.knots_u, net.degrees.0, u);
    let v_side = (&net.knots_v, net.degrees.1, v);
    let ((ka, pa, ta), (kb, pb, tb)) = match pair {
        Direction::U => (u_side, v_side),
        Direction::V => (v_side, u_side),
    };
    let singles = parts(kb, pb, tb, 1);
    parts(ka, pa, ta, 2)
        .into_iter()
        .flat_map(|a| singles.iter().map(move |b| (a.clone(), b.clone())))
        .collect()
}

/// Whether a full knot vector keeps the rules: ordered, `t` in a non-empty span between the
/// original span's knots `j` and `j + 1`, interior multiplicities ≤ p.
fn valid(knots: &[f64], p: usize, t: f64, j: usize) -> bool {
    let n = knots.len() - p - 1;
    knots.windows(2).all(|w| w[0] <= w[1])
        && knots[j] <= t
        && t <= knots[j + 1]
        && knots[j] < knots[j + 1]
        && knots
            .chunk_by(|a, b| a == b)
            .all(|w| w.len() <= p || w[0] <= knots[p] || w[0] >= knots[n])
}

/// The box of each unknown: between the nearest knots that do not move.
fn bounds(knots: &[f64], unknowns: &[usize]) -> Vec<(f64, f64)> {
    unknowns
        .iter()
        .map(|&k| {
            let below = (0..k).rev().find(|i| !unknowns.contains(i)).unwrap();
            let above = (k + 1..knots.len())
                .find(|i| !unknowns.contains(i))
                .unwrap();
            (knots[below], knots[above])
        })
        .collect()
}

/// Brute-force solutions of one mixed set: full `(knots_u, knots_v)`.
#[allow(clippy::too_many_arguments)]
fn brute_force(
    net: &Net,
    (u, v): (f64, f64),
    target: [f64; 3],
    pair: Direction,
    a: &Part,
    b: &Part,
) -> Vec<(Vec<f64>, Vec<f64>)> {
    let (mut ku, mut kv) = (net.knots_u.clone(), net.knots_v.clone());
    let (pu, pv) = net.degrees;
    let span = |k: &[f64], p: usize, t: f64| {
        let n = k.len() - p - 1;
        (p..n).rfind(|&j| k[j] <= t && k[j] < k[j + 1]).unwrap()
    };
    let (ju, jv) = (span(&ku, pu, u), span(&kv, pv, v));
    let (pu_part, pv_part) = match pair {
        Direction::U => (a, b),
        Direction::V => (b, a),
    };
    if let Some(r) = pu_part.moved {
        ku[r] = u;
    }
    if let Some(s) = pv_part.moved {
        kv[s] = v;
    }
    // The unknowns as (direction is u, index), bounds.
    let mut unknowns: Vec<(bool, usize)> = pu_part.unknowns.iter().map(|&k| (true, k)).collect();
    unknowns.extend(pv_part.unknowns.iter().map(|&k| (false, k)));
    let mut boxes = bounds(&ku, &pu_part.unknowns);
    boxes.extend(bounds(&kv, &pv_part.unknowns));
    let apply = |x: &[f64; 3]| {
        let (mut a, mut b) = (ku.clone(), kv.clone());
        for (&(is_u, k), &value) in unknowns.iter().zip(x) {
            if is_u { a[k] = value } else { b[k] = value }
        }
        (a, b)
    };
    let residual = |x: &[f64; 3]| {
        let (a, b) = apply(x);
        let p = net.point_with(&a, &b, u, v);
        [p[0] - target[0], p[1] - target[1], p[2] - target[2]]
    };
    let norm = |r: [f64; 3]| (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt();
    const G: usize = 9;
    let at = |i: [usize; 3]| -> [f64; 3] {
        std::array::from_fn(|k| {
            boxes[k].0 + (boxes[k].1 - boxes[k].0) * i[k] as f64 / (G - 1) as f64
        })
    };
    let mut grid = vec![f64::INFINITY; G * G * G];
    let index = |i: [usize; 3]| (i[0] * G + i[1]) * G + i[2];
    for i0 in 0..G {
        for i1 in 0..G {
            for i2 in 0..G {
                let x = at([i0, i1, i2]);
                let (a, b) = apply(&x);
                if a.windows(2).all(|w| w[0] <= w[1]) && b.windows(2).all(|w| w[0] <= w[1]) {
                    grid[index([i0, i1, i2])] = norm(residual(&x));
                }
            }
        }
    }
    let mut found: Vec<(Vec<f64>, Vec<f64>)> = Vec::new();
    for i0 in 0..G {
        for i1 in 0..G {
            for i2 in 0..G {
                let here = grid[index([i0, i1, i2])];
                if !here.is_finite() {
                    continue;
                }
                let mut minimum = true;
                for d in [[1, 0, 0], [0, 1, 0], [0, 0, 1]] {
                    for sign in [-1i64, 1] {
                        let n: Vec<i64> = (0..3)
                            .map(|k| [i0, i1, i2][k] as i64 + sign * d[k])
                            .collect();
                        if n.iter().all(|&c| (0..G as i64).contains(&c)) {
                            let there = grid[index([n[0] as usize, n[1] as usize, n[2] as usize])];
                            if there < here {
                                minimum = false;
                            }
                        }
                    }
                }
                if !minimum {
                    continue;
                }
                // Newton with a finite-difference Jacobian, projected onto the box.
                let mut x = at([i0, i1, i2]);
                for _ in 0..40 {
                    let r = residual(&x);
                    let mut jac = [[0.0; 3]; 3];
                    for k in 0..3 {
                        let h = 1e-7 * (boxes[k].1 - boxes[k].0);
                        let mut y = x;
                        y[k] += h;
                        let ry = residual(&y);
                        for c in 0..3 {
                            jac[c][k] = (ry[c] - r[c]) / h;
                        }
                    }
                    let Some(step) = solve3(jac, r) else { break };
                    for k in 0..3 {
                        x[k] = (x[k] - step[k]).clamp(boxes[k].0, boxes[k].1);
                    }
                }
                let scale = 1.0 + target.iter().fold(0.0f64, |m, c| m.max(c.abs()));
                if norm(residual(&x)) > 1e-10 * scale {
                    continue;
                }
                // Strictly inside the box (1e-6 of its widths), and valid.
                let inside = (0..3).all(|k| {
                    let w = boxes[k].1 - boxes[k].0;
                    x[k] > boxes[k].0 + 1e-6 * w && x[k] < boxes[k].1 - 1e-6 * w
                });
                let (a, b) = apply(&x);
                let ordered = (0..2).all(|k| {
                    let (first, second) = (unknowns[k], unknowns[k + 1]);
                    first.0 != second.0
                        || second.1 != first.1 + 1
                        || x[k] < x[k + 1] - 1e-6 * (boxes[k].1 - boxes[k].0)
                });
                if inside
                    && ordered
                    && valid(&a, pu, u, ju)
                    && valid(&b, pv, v, jv)
                    && !found
                        .iter()
                        .any(|(fa, fb)| close(fa, &a, 1e-7) && close(fb, &b, 1e-7))
                {
                    found.push((a, b));
                }
            }
        }
    }
    found
}

fn close(a: &[f64], b: &[f64], tolerance: f64) -> bool {
    a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tolerance)
}

/// `J⁻¹ r` by Cramer's rule, `None` when singular.
fn solve3(j: [[f64; 3]; 3], r: [f64; 3]) -> Option<[f64; 3]> {
    let det = |m: [[f64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    let d = det(j);
    if d == 0.0 || !d.is_finite() {
        return None;
    }
    Some(std::array::from_fn(|k| {
        let mut m = j;
        for c in 0..3 {
            m[c][k] = r[c];
        }
        det(m) / d
    }))
}

/// Every brute-force solution of every mixed set is among the solver's.
fn complete(net: &Net, (u, v): (f64, f64), target: [f64; 3]) -> (usize, usize) {
    let surface = net.surface();
    // The single knot of the direct problems too (the option's superset of the default).
    let options = SurfaceKnotOptions {
        mixed_direct: true,
        ..SurfaceKnotOptions::all(true)
    };
    let solutions: Vec<SurfaceKnotSolution> =
        solve_surface_knots_with(&surface, u, v, target, &options);
    let mut brute = 0;
    for pair in [Direction::U, Direction::V] {
        for (a, b) in mixed_parts(net, pair, (u, v)) {
            for (fu, fv) in brute_force(net, (u, v), target, pair, &a, &b) {
                brute += 1;
                let hit = solutions.iter().any(|s| {
                    s.family == SurfaceKnotFamily::Mixed { pair }
                        && close(s.knots_u.as_deref().unwrap_or(&net.knots_u), &fu, 1e-6)
                        && close(s.knots_v.as_deref().unwrap_or(&net.knots_v), &fv, 1e-6)
                });
                assert!(hit, "missed {pair:?} {a:?} {b:?}: u {fu:?} v {fv:?}");
            }
        }
    }
    let mixed = solutions
        .iter()
        .filter(|s| matches!(s.family, SurfaceKnotFamily::Mixed { .. }))
        .count();
    (brute, mixed)
}

#[test]
fn mixed_moves_find_every_brute_force_solution() {
    every_brute_force_solution_found(0xC0FFEE, &[(3, 3), (3, 2), (2, 3), (2, 2)], 6, 10);
}

/// A pair direction of degree ≥ 4: its pair reaches a curved patch (no plane condition), so
/// the three unknowns are solved together.
#[test]
fn mixed_moves_with_a_pair_direction_of_degree_4_or_5_find_every_brute_force_solution() {
    every_brute_force_solution_found(
        0xD1CE,
        &[(4, 3), (3, 4), (5, 2), (4, 4), (5, 3), (4, 5)],
        6,
        10,
    );
}

/// Random nets of `degrees` (in turn, `seeds` of them, every third rational), two targets
/// within `0.05` of the picked point each: every brute-force solution is found, and at least
/// `least` were there to find.
fn every_brute_force_solution_found(
    first_seed: u64,
    degrees: &[(usize, usize)],
    seeds: u64,
    least: usize,
) {
    let mut total = (0, 0);
    for seed in 0..seeds {
        let mut rng = Rng::new(first_seed + seed);
        let degrees = degrees[seed as usize % degrees.len()];
        let net = net(&mut rng, degrees, (3, 3), seed % 3 == 2);
        let u = parameter(&mut rng, &net.knots_u, degrees.0);
        let v = parameter(&mut rng, &net.knots_v, degrees.1);
        let point = net.point(u, v);
        for _ in 0..2 {
            let r = rng.range(0.0, 0.05);
            let d = [rng.normal(), rng.normal(), rng.normal()];
            let l = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            let target = std::array::from_fn(|k| point[k] + r * d[k] / l);
            let (brute, mixed) = complete(&net, (u, v), target);
            total.0 += brute;
            total.1 += mixed;
            assert!(distance(point, target) <= 0.05 + 1e-12);
        }
    }
    // The search is not vacuous: brute force found solutions to compare.
    assert!(
        total.0 >= least,
        "brute force found only {} solutions",
        total.0
    );
    eprintln!(
        "brute-force solutions {} (all found), mixed solutions {}",
        total.0, total.1
    );
}

/// The nearest distance to `target` over every mixed set of the default options (the single
/// knot after the envelope step only): a `9³` grid over each set's box, each grid point's
/// knots checked by the rules and evaluated by the reference evaluator.
fn brute_force_nearest_mixed(net: &Net, (u, v): (f64, f64), target: [f64; 3]) -> f64 {
    let mut best = f64::INFINITY;
    for pair in [Direction::U, Direction::V] {
        for (a, b) in mixed_parts(net, pair, (u, v)) {
            if b.moved.is_none() {
                continue;
            }
            let (pu_part, pv_part) = match pair {
                Direction::U => (&a, &b),
                Direction::V => (&b, &a),
            };
            let (mut ku, mut kv) = (net.knots_u.clone(), net.knots_v.clone());
            let span = |k: &[f64], p: usize, t: f64| {
                let n = k.len() - p - 1;
                (p..n).rfind(|&j| k[j] <= t && k[j] < k[j + 1]).unwrap()
            };
            let (ju, jv) = (span(&ku, net.degrees.0, u), span(&kv, net.degrees.1, v));
            if let Some(r) = pu_part.moved {
                ku[r] = u;
            }
            if let Some(s) = pv_part.moved {
                kv[s] = v;
            }
            let mut unknowns: Vec<(bool, usize)> =
                pu_part.unknowns.iter().map(|&k| (true, k)).collect();
            unknowns.extend(pv_part.unknowns.iter().map(|&k| (false, k)));
            let mut boxes = bounds(&ku, &pu_part.unknowns);
            boxes.extend(bounds(&kv, &pv_part.unknowns));
            const G: usize = 9;
            for i in 0..G * G * G {
                let index = [i % G, (i / G) % G, i / (G * G)];
                let (mut a_knots, mut b_knots) = (ku.clone(), kv.clone());
                for (k, &(is_u, m)) in unknowns.iter().enumerate() {
                    let value =
                        boxes[k].0 + (boxes[k].1 - boxes[k].0) * index[k] as f64 / (G - 1) as f64;
                    if is_u {
                        a_knots[m] = value;
                    } else {
                        b_knots[m] = value;
                    }
                }
                if valid(&a_knots, net.degrees.0, u, ju) && valid(&b_knots, net.degrees.1, v, jv) {
                    best = best.min(distance(net.point_with(&a_knots, &b_knots, u, v), target));
                }
            }
        }
    }
    best
}

/// For targets no knot move reaches, the nearest point is reached (the solver, then the
/// reference evaluator) and no farther than the best point of a brute-force grid over the
/// mixed moves (so the mixed moves are searched: one-direction moves barely leave the
/// tangent plane).
#[test]
fn the_nearest_point_is_no_farther_than_a_brute_force_grid_over_the_mixed_moves() {
    let mut beyond_one_direction = 0;
    for seed in 0..6u64 {
        let mut rng = Rng::new(0x5EED + seed);
        let degrees = [(3, 3), (3, 2), (2, 3), (2, 2)][seed as usize % 4];
        let net = net(&mut rng, degrees, (3, 3), seed % 3 == 2);
        let surface = net.surface();
        let u = parameter(&mut rng, &net.knots_u, degrees.0);
        let v = parameter(&mut rng, &net.knots_v, degrees.1);
        let point = net.point(u, v);
        let r = rng.range(0.2, 0.4);
        let d = [rng.normal(), rng.normal(), rng.normal()];
        let l = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        let target: [f64; 3] = std::array::from_fn(|k| point[k] + r * d[k] / l);
        let near = nearest_surface_knot_target(&surface, u, v, target, true).unwrap();
        let reached = solve_surface_knots(&surface, u, v, near, true);
        assert!(!reached.is_empty(), "seed {seed}: {near:?} not reached");
        for s in &reached {
            let ku = s.knots_u.clone().unwrap_or_else(|| net.knots_u.clone());
            let kv = s.knots_v.clone().unwrap_or_else(|| net.knots_v.clone());
            assert!(distance(net.point_with(&ku, &kv, u, v), near) < 1e-9);
        }
        let ours = distance(near, target);
        let brute = brute_force_nearest_mixed(&net, (u, v), target);
        assert!(
            ours <= brute * (1.0 + 1e-3) + 1e-9,
            "seed {seed}: nearest {ours} farther than the grid's {brute}"
        );
        if reached
            .iter()
            .any(|s| matches!(s.family, SurfaceKnotFamily::Mixed { .. }))
        {
            beyond_one_direction += 1;
        }
    }
    assert!(
        beyond_one_direction >= 3,
        "{beyond_one_direction} of 6 by mixed moves"
    );
}

/// Planted curved-pair moves: on random nets whose pair direction has degree 4 or 5, a mixed
/// set's three unknown knots are moved to random values inside their boxes (the rules kept),
/// the target is the reference evaluator's point of the planted knots, and the solver's mixed
/// moves of that orientation hold the planted knots.
#[test]
fn planted_moves_of_a_curved_pair_are_recovered() {
    let mut recovered = 0;
    for seed in 0..8u64 {
        let mut rng = Rng::new(0xFACE + seed);
        let degrees = [(4, 3), (5, 2), (4, 4), (5, 3)][seed as usize % 4];
        let net = net(&mut rng, degrees, (3, 3), seed % 2 == 1);
        let u = parameter(&mut rng, &net.knots_u, degrees.0);
        let v = parameter(&mut rng, &net.knots_v, degrees.1);
        let sets = mixed_parts(&net, Direction::U, (u, v));
        assert!(!sets.is_empty(), "seed {seed}: no mixed set");
        let (a, b) = &sets[rng.int(0, sets.len() - 1)];
        let (mut ku, mut kv) = (net.knots_u.clone(), net.knots_v.clone());
        if let Some(r) = a.moved {
            ku[r] = u;
        }
        if let Some(s) = b.moved {
            kv[s] = v;
        }
        // Each unknown anywhere strictly inside its box, the pair in order.
        let boxes_u = bounds(&ku, &a.unknowns);
        let box_v = bounds(&kv, &b.unknowns)[0];
        let mut draws: Vec<f64> = boxes_u
            .iter()
            .map(|&(lo, hi)| rng.range(lo + 0.05 * (hi - lo), hi - 0.05 * (hi - lo)))
            .collect();
        if a.unknowns[1] == a.unknowns[0] + 1 && draws[0] > draws[1] {
            draws.swap(0, 1);
        }
        for (&k, &value) in a.unknowns.iter().zip(&draws) {
            ku[k] = value;
        }
        kv[b.unknowns[0]] = rng.range(
            box_v.0 + 0.05 * (box_v.1 - box_v.0),
            box_v.1 - 0.05 * (box_v.1 - box_v.0),
        );
        let span = |k: &[f64], p: usize, t: f64| {
            let n = k.len() - p - 1;
            (p..n).rfind(|&j| k[j] <= t && k[j] < k[j + 1]).unwrap()
        };
        let (ju, jv) = (
            span(&net.knots_u, degrees.0, u),
            span(&net.knots_v, degrees.1, v),
        );
        if !valid(&ku, degrees.0, u, ju) || !valid(&kv, degrees.1, v, jv) {
            continue;
        }
        let target = net.point_with(&ku, &kv, u, v);
        let options = SurfaceKnotOptions {
            mixed_direct: true,
            ..SurfaceKnotOptions::all(true)
        };
        let solutions = solve_surface_knots_with(&net.surface(), u, v, target, &options);
        let found = solutions.iter().any(|s| {
            s.family == (SurfaceKnotFamily::Mixed { pair: Direction::U })
                && close(s.knots_u.as_deref().unwrap(), &ku, 1e-7)
                && close(s.knots_v.as_deref().unwrap(), &kv, 1e-7)
        });
        assert!(
            found,
            "seed {seed}: planted {a:?} {b:?} not recovered: u {ku:?} v {kv:?}"
        );
        recovered += 1;
    }
    assert!(
        recovered >= 6,
        "{recovered} of 8 planted moves were admissible"
    );
}

//! Properties of the surface edit (issue 28) on random surfaces: degrees 2–5 in each
//! direction, rational or not, repeated interior knots, 3D targets. Every solution is checked
//! by the brute-force evaluator of `surface_edit_common` (not the code under test): the new
//! surface meets the target and every constraint, equals the old one outside
//! `affected_domain`, keeps the fixed poles, and its certified `max_deviation` is at least
//! every sampled distance and not far above the largest; the unconstrained control-point
//! move is the closed form; weight solutions lie in their tetrahedron; contradictory
//! constraints give no move and an exclusion.

#![allow(clippy::unwrap_used)]

mod surface_edit_common;

use nalgebra::{Matrix3, Vector3};
use proptest::prelude::*;

use knotshape::surface::edit::{
    FixedNet, SurfaceConstraintSpec, SurfaceConstraints, SurfaceEditOptions, SurfaceEditRequest,
    SurfaceExclusionReason, SurfaceMethodKind, SurfaceSolution, SurfaceSolutionDetail,
    surface_edit,
};
use surface_edit_common::{Plain, basis_all, distance, sampled_deviation};

/// A clamped knot vector for `n` poles of degree `p` from interior values in `(0, 1)`, one of
/// them repeated when `repeat` (multiplicity 2 <= p).
fn knots(p: usize, n: usize, mut interior: Vec<f64>, repeat: bool) -> Vec<f64> {
    interior.truncate(n - p - 1);
    if repeat && interior.len() >= 2 {
        interior[1] = interior[0];
    }
    interior.sort_by(f64::total_cmp);
    let mut knots = vec![0.0; p + 1];
    knots.extend(interior);
    knots.extend(vec![1.0; p + 1]);
    knots
}

/// A random surface (module docs) with a picked parameter pair and a target near its point.
#[derive(Debug, Clone)]
struct Case {
    plain: Plain,
    picked: (f64, f64),
    offset: [f64; 3],
    extra: [(f64, f64); 2],
    fixed: [usize; 2],
    keep_boundary: bool,
}

fn case() -> impl Strategy<Value = Case> {
    (
        2usize..=5,
        2usize..=5,
        0usize..=3,
        0usize..=3,
        any::<bool>(),
        any::<bool>(),
    )
        .prop_flat_map(|(p, q, eu, ev, rational, repeat)| {
            let (n_u, n_v) = (p + 1 + eu, q + 1 + ev);
            (
                Just((p, q, n_u, n_v, rational, repeat)),
                proptest::collection::vec(0.05..0.95f64, 3),
                proptest::collection::vec(0.05..0.95f64, 3),
                proptest::collection::vec(
                    proptest::collection::vec([-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64], n_v),
                    n_u,
                ),
                proptest::collection::vec(proptest::collection::vec(0.3..3.0f64, n_v), n_u),
                (0.0..1.0f64, 0.0..1.0f64),
                [-0.4..0.4f64, -0.4..0.4f64, -0.4..0.4f64],
                [(0.0..1.0f64, 0.0..1.0f64), (0.0..1.0f64, 0.0..1.0f64)],
                (0..n_u, 0..n_v, any::<bool>()),
            )
        })
        .prop_map(
            |(
                (p, q, n_u, n_v, rational, repeat),
                iu,
                iv,
                poles,
                weights,
                picked,
                offset,
                extra,
                fixed,
            )| {
                Case {
                    plain: Plain {
                        p,
                        q,
                        knots_u: knots(p, n_u, iu, repeat),
                        knots_v: knots(q, n_v, iv, repeat),
                        poles,
                        weights: rational.then_some(weights),
                    },
                    picked,
                    offset,
                    extra,
                    fixed: [fixed.0, fixed.1],
                    keep_boundary: fixed.2,
                }
            },
        )
}

/// A constraint as the test states it: parameter pair, order, the values wanted.
type Wanted = ((f64, f64), usize, Vec<[f64; 3]>);

/// Every check of one solution against the brute-force evaluator (module docs).
fn check_solution(
    old: &Plain,
    picked: (f64, f64),
    target: [f64; 3],
    wanted: &[Wanted],
    fixed: &[[usize; 2]],
    solution: &SurfaceSolution,
) -> Result<(), TestCaseError> {
    let new = Plain::of(&solution.surface);
    let size = old.size();
    let reached = new.point(picked.0, picked.1);
    prop_assert!(
        distance(reached, target) <= 1e-8 * size,
        "target missed by {}",
        distance(reached, target)
    );
    for (parameter, order, values) in wanted {
        let found = new.eval(parameter.0, parameter.1);
        let old_found = old.eval(parameter.0, parameter.1);
        let quantities: Vec<usize> = if *order == 0 { vec![0] } else { vec![1, 2] };
        for (k, &quantity) in quantities.iter().enumerate() {
            let scale = 1.0 + distance(old_found[quantity], [0.0; 3]);
            prop_assert!(
                distance(found[quantity], values[k]) <= 1e-6 * size * scale,
                "constraint of order {order} at {parameter:?} missed by {}",
                distance(found[quantity], values[k])
            );
        }
    }
    // Unchanged outside the affected rectangle.
    let [(u0, u1), (v0, v1)] = solution.affected_domain;
    let domain = old.domain();
    for k in 0..=12 {
        for l in 0..=12 {
            let u = domain[0].0 + (domain[0].1 - domain[0].0) * k as f64 / 12.0;
            let v = domain[1].0 + (domain[1].1 - domain[1].0) * l as f64 / 12.0;
            if (u0..=u1).contains(&u) && (v0..=v1).contains(&v) {
                continue;
            }
            prop_assert!(
                distance(old.point(u, v), new.point(u, v)) <= 1e-12 * size,
                "the surface changed outside the affected domain at ({u}, {v})"
            );
        }
    }
    // Fixed poles keep their place and weight.
    for &[i, j] in fixed {
        prop_assert_eq!(old.poles[i][j], new.poles[i][j]);
        let weight = |plain: &Plain| plain.weights.as_ref().map_or(1.0, |w| w[i][j]);
        prop_assert_eq!(weight(old), weight(&new));
    }
    // The certified deviation: at least every sampled distance, not far above the largest.
    let bound = solution.max_deviation.expect("measured");
    let at_pick = distance(old.point(picked.0, picked.1), target);
    let sampled = sampled_deviation(old, &new, solution.affected_domain, 25).max(at_pick);
    prop_assert!(
        sampled <= bound * (1.0 + 1e-6) + 1e-12 * size,
        "bound {bound} below a sampled distance {sampled}"
    );
    // A sharp peak (weights far from the old ones) may fall between the grid's points:
    // then a finer grid and a local search from its best point.
    let sampled = if bound > 1.5 * sampled + 1e-9 * size {
        refined_deviation(old, &new, solution.affected_domain).max(sampled)
    } else {
        sampled
    };
    prop_assert!(
        bound <= 1.5 * sampled + 1e-9 * size,
        "bound {bound} far above the sampled maximum {sampled} ({:?})",
        solution.detail.method()
    );
    match &solution.detail {
        SurfaceSolutionDetail::Weights {
            poles,
            weights,
            tetrahedron,
        } => {
            // Only the three weights changed, to positive values.
            for (i, row) in old.poles.iter().enumerate() {
                for j in 0..row.len() {
                    prop_assert_eq!(old.poles[i][j], new.poles[i][j]);
                    let w_old = old.weights.as_ref().map_or(1.0, |w| w[i][j]);
                    let w_new = new.weights.as_ref().map_or(1.0, |w| w[i][j]);
                    match poles.iter().position(|&pole| pole == [i, j]) {
                        Some(t) => prop_assert!(w_new == weights[t] && w_new > 0.0),
                        None => prop_assert_eq!(w_old, w_new),
                    }
                }
            }
            // The target lies inside the tetrahedron of the three poles and s₀ (the point of
            // the other active poles, computed here from the brute-force basis).
            let (nu, _) = basis_all(&old.knots_u, old.p, picked.0);
            let (nv, _) = basis_all(&old.knots_v, old.q, picked.1);
            let mut rest = [0.0; 4];
            for (i, row) in old.poles.iter().enumerate() {
                for (j, pole) in row.iter().enumerate() {
                    if poles.contains(&[i, j]) {
                        continue;
                    }
                    let w = nu[i] * nv[j] * old.weights.as_ref().map_or(1.0, |w| w[i][j]);
                    for c in 0..3 {
                        rest[c] += w * pole[c];
                    }
                    rest[3] += w;
                }
            }
            let s0 = [rest[0] / rest[3], rest[1] / rest[3], rest[2] / rest[3]];
            prop_assert!(distance(s0, tetrahedron[0]) <= 1e-9 * size);
            let vertex = |t: usize| {
                let [i, j] = poles[t];
                Vector3::from(old.poles[i][j]) - Vector3::from(s0)
            };
            let m = Matrix3::from_columns(&[vertex(0), vertex(1), vertex(2)]);
            let lambda = m
                .lu()
                .solve(&(Vector3::from(target) - Vector3::from(s0)))
                .expect("a solid tetrahedron");
            prop_assert!(lambda.iter().all(|&l| l > -1e-9) && lambda.sum() < 1.0 + 1e-9);
        }
        SurfaceSolutionDetail::Knots { .. } => {
            // Only knots changed.
            prop_assert_eq!(&old.poles, &new.poles);
            prop_assert_eq!(&old.weights, &new.weights);
        }
        SurfaceSolutionDetail::ControlPoints { .. } => {
            for (i, row) in old.poles.iter().enumerate() {
                for j in 0..row.len() {
                    prop_assert_eq!(
                        old.weights.as_ref().map(|w| w[i][j]),
                        new.weights.as_ref().map(|w| w[i][j])
                    );
                }
            }
        }
    }
    Ok(())
}

/// The largest `|S_a − S_b|` found by a 120 × 120 grid of `rect` and a pattern search (step
/// halving) from its best point.
fn refined_deviation(a: &Plain, b: &Plain, rect: [(f64, f64); 2]) -> f64 {
    let gap = |u: f64, v: f64| {
        let (u, v) = (u.clamp(rect[0].0, rect[0].1), v.clamp(rect[1].0, rect[1].1));
        distance(a.point(u, v), b.point(u, v))
    };
    let n = 120;
    let (mut best, mut at) = (0.0f64, (rect[0].0, rect[1].0));
    for k in 0..=n {
        for l in 0..=n {
            let u = rect[0].0 + (rect[0].1 - rect[0].0) * k as f64 / n as f64;
            let v = rect[1].0 + (rect[1].1 - rect[1].0) * l as f64 / n as f64;
            let g = gap(u, v);
            if g > best {
                (best, at) = (g, (u, v));
            }
        }
    }
    let mut step = [
        (rect[0].1 - rect[0].0) / n as f64,
        (rect[1].1 - rect[1].0) / n as f64,
    ];
    for _ in 0..60 {
        let mut moved = false;
        for (du, dv) in [(1.0, 0.0), (-1.0, 0.0), (0.0, 1.0), (0.0, -1.0)] {
            let candidate = (at.0 + du * step[0], at.1 + dv * step[1]);
            let g = gap(candidate.0, candidate.1);
            if g > best {
                (best, at, moved) = (g, candidate, true);
            }
        }
        if !moved {
            step = [step[0] / 2.0, step[1] / 2.0];
        }
    }
    best
}

/// The closed form of the unconstrained move: `Δd_ij = R_ij / Σ R² · (p − S)`.
fn check_closed_form(
    old: &Plain,
    picked: (f64, f64),
    target: [f64; 3],
    new: &Plain,
) -> Result<(), TestCaseError> {
    let (nu, _) = basis_all(&old.knots_u, old.p, picked.0);
    let (nv, _) = basis_all(&old.knots_v, old.q, picked.1);
    let weight = |i: usize, j: usize| old.weights.as_ref().map_or(1.0, |w| w[i][j]);
    let total: f64 = (0..nu.len())
        .flat_map(|i| (0..nv.len()).map(move |j| (i, j)))
        .map(|(i, j)| nu[i] * nv[j] * weight(i, j))
        .sum();
    let r = |i: usize, j: usize| nu[i] * nv[j] * weight(i, j) / total;
    let squares: f64 = (0..nu.len())
        .flat_map(|i| (0..nv.len()).map(move |j| (i, j)))
        .map(|(i, j)| r(i, j).powi(2))
        .sum();
    let gap: Vec<f64> = (0..3)
        .map(|c| target[c] - old.point(picked.0, picked.1)[c])
        .collect();
    for (i, row) in old.poles.iter().enumerate() {
        for (j, pole) in row.iter().enumerate() {
            for c in 0..3 {
                let expected = pole[c] + r(i, j) / squares * gap[c];
                prop_assert!(
                    (new.poles[i][j][c] - expected).abs() <= 1e-9 * old.size(),
                    "pole [{i}, {j}] differs from the closed form"
                );
            }
        }
    }
    Ok(())
}

fn domain_point(plain: &Plain, (a, b): (f64, f64)) -> (f64, f64) {
    let [(u0, u1), (v0, v1)] = plain.domain();
    (u0 + a * (u1 - u0), v0 + b * (v1 - v0))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 128, max_shrink_iters: 200, ..ProptestConfig::default() })]

    /// Without constraints: the control-point move is the closed form, and every solution
    /// of both methods passes every check.
    #[test]
    fn unconstrained_moves_meet_the_target(case in case()) {
        let surface = case.plain.surface();
        let picked = domain_point(&case.plain, case.picked);
        let old = case.plain.point(picked.0, picked.1);
        let target = [old[0] + case.offset[0], old[1] + case.offset[1], old[2] + case.offset[2]];
        let constraints = SurfaceConstraints::none();
        let fixed = FixedNet::none(&surface);
        let outcome = surface_edit(&SurfaceEditRequest {
            surface: &surface,
            parameter: picked,
            target,
            methods: &[SurfaceMethodKind::ControlPoints, SurfaceMethodKind::Weights],
            constraints: &constraints,
            fixed: &fixed,
            options: SurfaceEditOptions::default(),
        });
        let poles = outcome
            .solutions
            .iter()
            .find(|s| s.detail.method() == SurfaceMethodKind::ControlPoints);
        prop_assert!(poles.is_some(), "the control-point move always reaches the target");
        check_closed_form(&case.plain, picked, target, &Plain::of(&poles.unwrap().surface))?;
        for solution in &outcome.solutions {
            check_solution(&case.plain, picked, target, &[], &[], solution)?;
        }
        // Ranked by the certified deviation.
        for pair in outcome.solutions.windows(2) {
            prop_assert!(pair[0].max_deviation <= pair[1].max_deviation);
        }
    }

    /// With a pinned point, pinned first partials elsewhere, a fixed pole and maybe the kept
    /// boundary: every solution keeps all of them.
    #[test]
    fn constrained_moves_keep_every_condition(case in case()) {
        let surface = case.plain.surface();
        let picked = domain_point(&case.plain, case.picked);
        let old = case.plain.point(picked.0, picked.1);
        let target = [old[0] + case.offset[0], old[1] + case.offset[1], old[2] + case.offset[2]];
        let (a, b) = (domain_point(&case.plain, case.extra[0]), domain_point(&case.plain, case.extra[1]));
        prop_assume!(a != picked && a != b);
        let specs = [
            SurfaceConstraintSpec { parameter: [a.0, a.1], order: 0, value: None },
            SurfaceConstraintSpec { parameter: [b.0, b.1], order: 1, value: None },
        ];
        let constraints = SurfaceConstraints::new(&surface, picked, &specs).expect("valid");
        let fixed = FixedNet::new(&surface, &[case.fixed], case.keep_boundary).expect("valid");
        let outcome = surface_edit(&SurfaceEditRequest {
            surface: &surface,
            parameter: picked,
            target,
            methods: &[SurfaceMethodKind::ControlPoints, SurfaceMethodKind::Weights],
            constraints: &constraints,
            fixed: &fixed,
            options: SurfaceEditOptions::default(),
        });
        let at_a = case.plain.eval(a.0, a.1);
        let at_b = case.plain.eval(b.0, b.1);
        let wanted = vec![(a, 0, vec![at_a[0]]), (b, 1, vec![at_b[1], at_b[2]])];
        let mut fixed_poles = vec![case.fixed];
        if case.keep_boundary {
            let (n_u, n_v) = (case.plain.poles.len(), case.plain.poles[0].len());
            for i in 0..n_u {
                for j in 0..n_v {
                    if i == 0 || j == 0 || i + 1 == n_u || j + 1 == n_v {
                        fixed_poles.push([i, j]);
                    }
                }
            }
        }
        for solution in &outcome.solutions {
            check_solution(&case.plain, picked, target, &wanted, &fixed_poles, solution)?;
        }
        // The control-point move either reaches the target or says why not.
        let has_poles = outcome.solutions.iter().any(|s| s.detail.method() == SurfaceMethodKind::ControlPoints);
        let excluded = outcome.excluded.iter().any(|e| e.method == SurfaceMethodKind::ControlPoints);
        prop_assert!(has_poles != excluded);
    }

    /// Two different prescribed values of one point: no move at all, an exclusion per method
    /// naming the pair.
    #[test]
    fn contradictory_constraints_move_nothing(case in case()) {
        let surface = case.plain.surface();
        let picked = domain_point(&case.plain, case.picked);
        let a = domain_point(&case.plain, case.extra[0]);
        prop_assume!(a != picked);
        let here = case.plain.point(a.0, a.1);
        let first = vec![vec![here[0], here[1], here[2]]];
        let second = vec![vec![here[0] + 0.5, here[1], here[2]]];
        let specs = [
            SurfaceConstraintSpec { parameter: [a.0, a.1], order: 0, value: Some(&first) },
            SurfaceConstraintSpec { parameter: [a.0, a.1], order: 0, value: Some(&second) },
        ];
        let constraints = SurfaceConstraints::new(&surface, picked, &specs).expect("valid");
        let fixed = FixedNet::none(&surface);
        let outcome = surface_edit(&SurfaceEditRequest {
            surface: &surface,
            parameter: picked,
            target: [here[0], here[1], here[2] + 1.0],
            methods: &[SurfaceMethodKind::ControlPoints, SurfaceMethodKind::Weights],
            constraints: &constraints,
            fixed: &fixed,
            options: SurfaceEditOptions { nearest: true, keep_domain: false },
        });
        prop_assert!(outcome.solutions.is_empty() && outcome.nearest.is_none());
        prop_assert_eq!(outcome.excluded.len(), 2);
        for exclusion in &outcome.excluded {
            prop_assert_eq!(&exclusion.reason, &SurfaceExclusionReason::Contradiction { first: 0, second: 1 });
        }
    }
}

/// A polynomial bicubic of 7 × 7 poles, `pole(i, j)` at the indices, clamped knots with
/// three uneven interior values in both directions.
fn bicubic_7x7(pole: impl Fn(f64, f64) -> [f64; 3]) -> Plain {
    let clamped = vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.55, 0.8, 1.0, 1.0, 1.0, 1.0];
    Plain {
        p: 3,
        q: 3,
        knots_u: clamped.clone(),
        knots_v: clamped,
        poles: (0..7)
            .map(|i| (0..7).map(|j| pole(i as f64, j as f64)).collect())
            .collect(),
        weights: None,
    }
}

/// The knot method through the edit: a target planted by moving one interior `u`-knot of a
/// planar bicubic (every iso-curve lies in `z = 0`, so the pairs reach targets there) is
/// reached by knot solutions, each passing every check of the brute-force evaluator (the
/// target, the surface unchanged outside its rectangle, the deviation bound against the
/// sampled distance, poles and weights untouched). The domain is kept, so that the old and
/// new surfaces compare on one rectangle.
#[test]
fn the_knot_method_reaches_a_planted_target() {
    let plain = bicubic_7x7(|x, y| [x + 0.2 * (0.9 * y).sin(), y + 0.3 * (0.7 * x).cos(), 0.0]);
    let picked = (0.62, 0.45);
    let mut planted = plain.clone();
    planted.knots_u[5] = 0.5;
    let target = planted.point(picked.0, picked.1);
    assert!(distance(target, plain.point(picked.0, picked.1)) > 1e-3);
    let surface = plain.surface();
    let constraints = SurfaceConstraints::none();
    let fixed = FixedNet::none(&surface);
    let outcome = surface_edit(&SurfaceEditRequest {
        surface: &surface,
        parameter: picked,
        target,
        methods: &[SurfaceMethodKind::Knots],
        constraints: &constraints,
        fixed: &fixed,
        options: SurfaceEditOptions {
            nearest: false,
            keep_domain: true,
        },
    });
    assert!(!outcome.solutions.is_empty(), "{:?}", outcome.excluded);
    for solution in &outcome.solutions {
        assert_eq!(solution.detail.method(), SurfaceMethodKind::Knots);
        check_solution(&plain, picked, target, &[], &[], solution).unwrap();
    }
    // The planted single knot is among the solutions (a pair holding u_5 whose other knot
    // keeps its value).
    assert!(outcome.solutions.iter().any(|s| {
        let new = Plain::of(&s.surface);
        (new.knots_u[5] - 0.5).abs() < 1e-7
            && new
                .knots_u
                .iter()
                .zip(&planted.knots_u)
                .all(|(a, b)| (a - b).abs() < 1e-7)
    }));
}

/// The methods solve and measure side by side on the rayon pool: the whole answer (every
/// solution in rank order with its deviation, every exclusion in order) is the same on one
/// thread and on two, for a target that knots, control points and weights all reach, with
/// a pinned point that some solutions break.
#[test]
fn the_answer_does_not_depend_on_the_threads_solving_it() {
    let plain = bicubic_7x7(|x, y| {
        [
            x + 0.2 * (0.9 * y).sin(),
            y,
            0.4 * (0.7 * x).cos() * (0.5 * y).sin(),
        ]
    });
    let surface = plain.surface();
    let picked = (0.62, 0.45);
    // Targets a knot move reaches: one interior knot moved in u, then in v.
    let planted = |direction: usize, index: usize, value: f64| {
        let mut moved = plain.clone();
        if direction == 0 {
            moved.knots_u[index] = value;
        } else {
            moved.knots_v[index] = value;
        }
        moved.point(picked.0, picked.1)
    };
    let fixed = FixedNet::none(&surface);
    let specs = [SurfaceConstraintSpec {
        parameter: [0.2, 0.5],
        order: 0,
        value: None,
    }];
    let pinned = SurfaceConstraints::new(&surface, picked, &specs).unwrap();
    let mut every_method_reached = false;
    for (target, constraints) in [
        (planted(0, 5, 0.5), SurfaceConstraints::none()),
        (planted(1, 4, 0.35), pinned),
    ] {
        let on = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| {
                surface_edit(&SurfaceEditRequest {
                    surface: &surface,
                    parameter: picked,
                    target,
                    methods: &SurfaceMethodKind::ALL,
                    constraints: &constraints,
                    fixed: &fixed,
                    options: SurfaceEditOptions {
                        nearest: true,
                        keep_domain: true,
                    },
                })
            })
        };
        let (one, two) = (on(1), on(2));
        every_method_reached |= SurfaceMethodKind::ALL
            .iter()
            .all(|kind| one.solutions.iter().any(|s| s.detail.method() == *kind));
        assert_eq!(one, two);
    }
    assert!(
        every_method_reached,
        "some target is reached by every method"
    );
}

//! The knot method on every degree: the worked examples of the fourth release's study (a
//! cubic's direct pairs, a quadratic's direct pairs, a quintic's envelope pairs, and a local
//! problem with three solutions of one pair), each value computed independently with SciPy's
//! `BSpline` by the study's scripts; the solutions are checked again here by the test's own
//! de Boor.
#![allow(clippy::unwrap_used)]

mod common;

use common::de_boor;
use knotshape::shape::family::{Family, FamilyChoice, KnotSolution, solve_families};
use knotshape::shape::{ShapeQuery, Side, SideChoice};
use knotshape::spline::{Curve, CurveLimits};

fn curve(degree: usize, points: &[[f64; 2]], knots: &[f64]) -> Curve {
    Curve::new(degree, points, knots, None, &CurveLimits::default()).unwrap()
}

/// The cubic of the study's first example (§2.8): eleven points, knots clamped with
/// interior 0.1, 0.2, 0.35, 0.5, 0.6, 0.7, 0.85.
fn example_cubic() -> Curve {
    curve(
        3,
        &[
            [0.0, 0.0],
            [1.0, 2.0],
            [2.5, 3.0],
            [4.0, 3.2],
            [5.5, 2.0],
            [6.5, 0.5],
            [8.0, 0.8],
            [9.0, 2.5],
            [10.0, 3.0],
            [11.5, 2.0],
            [12.0, 0.0],
        ],
        &[
            0.0, 0.0, 0.0, 0.0, 0.1, 0.2, 0.35, 0.5, 0.6, 0.7, 0.85, 1.0, 1.0, 1.0, 1.0,
        ],
    )
}

fn only(family: Family) -> FamilyChoice {
    FamilyChoice::Only {
        envelope: family == Family::Envelope,
        direct: family == Family::Direct,
        triples: family == Family::Triples,
    }
}

/// The solutions of `family` at `t`, each checked by the test's own de Boor.
fn solutions(
    curve: &Curve,
    t: f64,
    target: [f64; 2],
    family: Family,
    side: SideChoice,
) -> Vec<KnotSolution> {
    let query = ShapeQuery {
        side,
        ..ShapeQuery::new(curve, t)
    };
    let target3 = [target[0], target[1], 0.0];
    let outcome = solve_families(&query, only(family), target3);
    for solution in &outcome.solutions {
        let point = de_boor(curve, &solution.knots, t).unwrap();
        let miss = ((point[0] - target[0]).powi(2) + (point[1] - target[1]).powi(2)).sqrt();
        assert!(miss < 1e-12, "{solution:?} misses by {miss}");
    }
    outcome.solutions
}

/// The solution moving exactly `knots`, as `(value of first, value of second)`.
fn pair_values(found: &[KnotSolution], knots: [usize; 2]) -> Vec<[f64; 2]> {
    found
        .iter()
        .filter(|s| s.knots_moved.indices() == knots)
        .map(|s| [s.knots[knots[0]], s.knots[knots[1]]])
        .collect()
}

fn assert_close(found: &[[f64; 2]], expected: [f64; 2], tolerance: f64) {
    assert_eq!(found.len(), 1, "{found:?}, expected {expected:?}");
    for k in 0..2 {
        assert!(
            (found[0][k] - expected[k]).abs() < tolerance,
            "{found:?} vs {expected:?}"
        );
    }
}

/// §2.8: the cubic's direct pairs at t = 0.42 (span 6, relevant knots u_4 … u_9), target
/// (6.0, 1.3): seven of the fifteen pairs reach it, one solution each.
#[test]
fn the_cubic_direct_pairs_reach_the_worked_target_seven_times() {
    let cubic = example_cubic();
    let found = solutions(&cubic, 0.42, [6.0, 1.3], Family::Direct, SideChoice::Both);
    let expected = [
        ([5, 6], [0.238806861, 0.342152709]),
        ([5, 7], [0.253583847, 0.485053681]),
        ([5, 8], [0.297513610, 0.526764137]),
        ([5, 9], [0.228093125, 0.631173101]),
        ([6, 7], [0.322793494, 0.537951826]),
        ([6, 8], [0.337707605, 0.649148048]),
        ([7, 8], [0.470255780, 0.690246011]),
    ];
    assert_eq!(found.len(), expected.len(), "{found:#?}");
    for (knots, values) in expected {
        assert_close(&pair_values(&found, knots), values, 5e-9);
    }
}

/// ex02: the quadratic's direct pairs are the paper's closed forms verbatim: target
/// (6.4375, 0.7875) at t = 0.5 is reached by (u_5, u_6), (u_6, u_7), (u_7, u_8) only.
#[test]
fn the_quadratic_direct_pairs_are_the_papers_closed_forms() {
    let quadratic = curve(
        2,
        &[
            [0.0, 0.0],
            [1.0, 2.0],
            [2.5, 3.0],
            [4.0, 3.2],
            [5.5, 2.0],
            [6.5, 0.5],
            [8.0, 0.8],
            [9.0, 2.5],
            [10.0, 3.0],
            [11.5, 2.0],
            [12.0, 0.0],
        ],
        &[
            0.0, 0.0, 0.0, 0.1, 0.2, 0.3, 0.45, 0.55, 0.65, 0.75, 0.9, 1.0, 1.0, 1.0,
        ],
    );
    let found = solutions(
        &quadratic,
        0.5,
        [6.4375, 0.7875],
        Family::Direct,
        SideChoice::Both,
    );
    assert_eq!(found.len(), 3, "{found:#?}");
    assert_close(&pair_values(&found, [5, 6]), [0.382114, 0.465618], 5e-7);
    assert_close(&pair_values(&found, [6, 7]), [0.458936, 0.575093], 5e-7);
    assert_close(&pair_values(&found, [7, 8]), [0.580268, 0.702581], 5e-7);
    // The envelope family needs degree 3.
    let query = ShapeQuery::new(&quadratic, 0.5);
    let outcome = solve_families(&query, only(Family::Envelope), [6.4375, 0.7875, 0.0]);
    assert!(outcome.groups.is_empty() && outcome.solutions.is_empty());
}

/// ex02: the quintic's envelope (q = 4) at t = 0.5, u_11 := 0.5 (the right side), with the
/// target planted by moving u_7 by +0.02 and u_15 by −0.03: the outermost pair gets exactly
/// those knots back (closed form), and three inner pairs reach the target too.
/// The study's worked quintic (ex02): sixteen points, ten uniform interior knots in
/// [0.08, 0.92].
fn worked_quintic() -> (Curve, Vec<f64>) {
    let interior: Vec<f64> = (0..10)
        .map(|i| ((0.08 + (0.92 - 0.08) * i as f64 / 9.0) * 1e4).round() / 1e4)
        .collect();
    let mut knots = vec![0.0; 6];
    knots.extend(&interior);
    knots.extend([1.0; 6]);
    let points = [
        [0.0, 0.0],
        [1.0, 1.5],
        [2.0, 2.5],
        [3.2, 3.0],
        [4.5, 2.8],
        [5.5, 1.8],
        [6.3, 0.6],
        [7.5, 0.2],
        [8.8, 0.9],
        [9.8, 2.2],
        [11.0, 3.0],
        [12.2, 2.6],
        [13.0, 1.2],
        [14.0, 0.0],
        [15.0, 0.5],
        [16.0, 2.0],
    ];
    (curve(5, &points, &knots), knots)
}

#[test]
fn the_quintic_envelope_finds_the_planted_outermost_pair_and_three_more() {
    let (quintic, knots) = worked_quintic();
    // The planted knots: u_11 := 0.5, u_7 += 0.02, u_15 -= 0.03.
    let mut planted = knots.clone();
    planted[11] = 0.5;
    planted[7] += 0.02;
    planted[15] -= 0.03;
    let target = de_boor(&quintic, &planted, 0.5).unwrap();
    assert!((target[0] - 8.257504).abs() < 1e-6 && (target[1] - 0.716366).abs() < 1e-6);
    let found = solutions(
        &quintic,
        0.5,
        [target[0], target[1]],
        Family::Envelope,
        SideChoice::Right,
    );
    assert!(
        found
            .iter()
            .all(|s| s.side == Some(Side::Right) && s.moved_knot == Some(11))
    );
    assert_close(
        &pair_values(&found, [7, 15]),
        [planted[7], planted[15]],
        1e-9,
    );
    assert_close(&pair_values(&found, [10, 12]), [0.45113, 0.643085], 5e-6);
    assert_close(&pair_values(&found, [9, 13]), [0.349794, 0.750593], 5e-6);
    assert_close(&pair_values(&found, [8, 12]), [0.249612, 0.649079], 5e-6);
}

/// The pairs and triples are solved on the rayon pool when there are many: the answer (every
/// solution, in order, and every set's membership) is the same on one thread and on two,
/// for a quintic with every family on both sides, triples too and a target reached by
/// many of them.
#[test]
fn the_answer_does_not_depend_on_the_threads_solving_it() {
    let (quintic, _) = worked_quintic();
    let query = ShapeQuery {
        side: SideChoice::Both,
        ..ShapeQuery::new(&quintic, 0.5)
    };
    let p = quintic.point(0.5).unwrap();
    let mut reached = 0;
    for target in [
        [p[0] + 0.1, p[1] + 0.05, 0.0],
        [p[0] - 0.02, p[1] + 0.03, 0.0],
    ] {
        let on = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let every = FamilyChoice::Only {
                envelope: true,
                direct: true,
                triples: true,
            };
            pool.install(|| solve_families(&query, every, target))
        };
        let (one, two) = (on(1), on(2));
        reached += one.solutions.len();
        assert_eq!(one, two);
    }
    assert!(reached >= 20, "{reached} solutions");
}

/// ex03: one pair with three admissible solutions (a folded map): the span's two ends of a
/// Π_3, i.e. a cubic whose only span is [u_3, u_4] = [0, 0.8], both ends free
/// (`keep_domain: false`).
#[test]
fn one_pair_with_three_solutions_has_all_three() {
    let cubic = curve(
        3,
        &[[0.43, 1.61], [0.72, 0.67], [-0.12, 1.18], [-0.53, -0.91]],
        &[-1.75, -1.37, -0.88, 0.0, 0.80, 1.47, 2.00, 2.69],
    );
    let query = ShapeQuery {
        keep_domain: false,
        ..ShapeQuery::new(&cubic, 0.431)
    };
    let outcome = solve_families(&query, only(Family::Direct), [0.303, 0.936, 0.0]);
    let mut found = pair_values(&outcome.solutions, [3, 4]);
    found.sort_by(|a, b| a[0].total_cmp(&b[0]));
    let expected = [
        [0.0024323064, 1.2678791730],
        [0.0612153804, 1.1602584966],
        [0.3172349431, 0.7531202133],
    ];
    assert_eq!(found.len(), 3, "{found:?}");
    for (f, e) in found.iter().zip(expected) {
        assert!(
            (f[0] - e[0]).abs() < 2e-9 && (f[1] - e[1]).abs() < 2e-9,
            "{f:?} vs {e:?}"
        );
    }
}

/// A 3D cubic: moving three of the direct family's knots puts s(t) off every pair's plane;
/// the triples find the planted knots again (default families on a 3D curve).
#[test]
fn a_planted_triple_is_found_on_a_3d_cubic() {
    let points: Vec<[f64; 3]> = (0..9)
        .map(|i| {
            let a = 0.8 * i as f64;
            [
                3.0 * a.cos(),
                3.0 * a.sin(),
                0.6 * i as f64 + 0.3 * (1.7 * a).sin(),
            ]
        })
        .collect();
    let knots = [
        0.0, 0.0, 0.0, 0.0, 0.15, 0.3, 0.45, 0.6, 0.8, 1.0, 1.0, 1.0, 1.0,
    ];
    let cubic = Curve::new(3, &points, &knots, None, &CurveLimits::default()).unwrap();
    let t = 0.4; // span 5 (u_5 = 0.3 ≤ t < u_6 = 0.45): relevant knots u_3 … u_8
    let mut planted = knots.to_vec();
    planted[5] = 0.25;
    planted[6] = 0.48;
    planted[7] = 0.62;
    let target = de_boor(&cubic, &planted, t).unwrap();
    let query = ShapeQuery::new(&cubic, t);
    let outcome = solve_families(&query, FamilyChoice::Default, target);
    let found: Vec<&KnotSolution> = outcome
        .solutions
        .iter()
        .filter(|s| s.family == Family::Triples && s.knots_moved.indices() == [5, 6, 7])
        .collect();
    assert!(!found.is_empty(), "{:#?}", outcome.solutions);
    assert!(
        found
            .iter()
            .any(|s| (5..=7).all(|k| (s.knots[k] - planted[k]).abs() < 1e-9))
    );
    for solution in &outcome.solutions {
        let point = de_boor(&cubic, &solution.knots, t).unwrap();
        let miss = (0..3)
            .map(|c| (point[c] - target[c]).powi(2))
            .sum::<f64>()
            .sqrt();
        assert!(miss < 1e-12, "{solution:?}");
    }
}

/// Nearest across families on a quintic, for targets no pair reaches: the point returned is
/// reached (its solution's new curve passes through it, by the test's de Boor), and it is at
/// least as close as every point of a brute-force lattice over each pair's knots (the test's
/// own enumeration of the envelope and direct pairs).
#[test]
fn the_nearest_point_across_families_beats_a_brute_force_lattice() {
    use knotshape::shape::family::nearest_across_families;
    let quintic = curve(
        5,
        &[
            [0.0, 0.0],
            [1.0, 1.5],
            [2.0, 2.5],
            [3.2, 3.0],
            [4.5, 2.8],
            [5.5, 1.8],
            [6.3, 0.6],
            [7.5, 0.2],
            [8.8, 0.9],
            [9.8, 2.2],
            [11.0, 3.0],
            [12.2, 2.6],
            [13.0, 1.2],
        ],
        &[
            0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.12, 0.25, 0.4, 0.5, 0.62, 0.75, 0.88, 1.0, 1.0, 1.0,
            1.0, 1.0, 1.0,
        ],
    );
    let p = 5;
    let n = 12;
    let t = 0.45;
    let knots = quintic.knots().to_vec();
    let j = (p..=n).rev().find(|&m| knots[m] <= t).unwrap();
    // The brute force: each family's pairs over a lattice of their knots.
    let mut reachable: Vec<[f64; 3]> = Vec::new();
    let mut lattice = |base: &[f64], relevant: Vec<usize>, span: (usize, usize)| {
        let movable: Vec<usize> = relevant
            .into_iter()
            .filter(|&k| k != p && k != n + 1)
            .collect();
        for (x, &a) in movable.iter().enumerate() {
            for &b in &movable[x + 1..] {
                let (lo_a, hi_a) = (base[a - 1], base[a + 1]);
                let (lo_b, hi_b) = (base[b - 1], base[b + 1]);
                let (lo_a, hi_a) = (lo_a.min(base[a]), if b == a + 1 { hi_b } else { hi_a });
                let lo_b = if b == a + 1 { lo_a } else { lo_b };
                for i in 0..=24 {
                    for k in 0..=24 {
                        let mut v = base.to_vec();
                        v[a] = lo_a + (hi_a - lo_a) * i as f64 / 24.0;
                        v[b] = lo_b + (hi_b - lo_b) * k as f64 / 24.0;
                        let ordered = v.windows(2).all(|w| w[0] <= w[1]);
                        let in_span = v[span.0] <= t && t <= v[span.1] && v[span.0] < v[span.1];
                        if ordered && in_span {
                            if let Some(q) = de_boor(&quintic, &v, t) {
                                reachable.push(q);
                            }
                        }
                    }
                }
            }
        }
    };
    lattice(&knots, (j - p + 1..=j + p).collect(), (j, j + 1));
    for i in [j, j + 1] {
        let mut moved = knots.clone();
        moved[i] = t;
        let relevant: Vec<usize> = (i - p + 1..i).chain(i + 1..i + p).collect();
        lattice(&moved, relevant, (i - 1, i + 1));
    }
    let query = ShapeQuery::new(&quintic, t);
    let picked = quintic.point(t).unwrap();
    for (dx, dy) in [(3.0, 2.0), (-2.5, 1.5), (0.5, -3.0), (4.0, -1.0)] {
        let target = [picked[0] + dx, picked[1] + dy, 0.0];
        let reached = solve_families(&query, FamilyChoice::Default, target);
        assert!(reached.solutions.is_empty(), "({dx}, {dy}) is reachable");
        let nearest = nearest_across_families(&query, FamilyChoice::Default, target).unwrap();
        let first = &nearest.solutions[0];
        let point = de_boor(&quintic, &first.knots, t).unwrap();
        assert!(
            (point[0] - nearest.point[0]).abs() < 1e-12
                && (point[1] - nearest.point[1]).abs() < 1e-12
        );
        let distance =
            |q: [f64; 3]| ((q[0] - target[0]).powi(2) + (q[1] - target[1]).powi(2)).sqrt();
        let brute = reachable
            .iter()
            .map(|&q| distance(q))
            .fold(f64::INFINITY, f64::min);
        assert!(
            distance(nearest.point) <= brute + 1e-9,
            "({dx}, {dy}): nearest {} vs lattice {brute}",
            distance(nearest.point)
        );
    }
}

/// Triples on a 2D curve, when asked: two equations in three knots leave a curve of
/// solutions, and the answer holds its points where the knots' change is stationary; each is
/// a solution (the test's de Boor) and moves three of the six knots nearest t.
#[test]
fn triples_asked_on_a_2d_curve_give_stationary_solutions() {
    let cubic = example_cubic();
    let found = solutions(&cubic, 0.42, [6.0, 1.3], Family::Triples, SideChoice::Both);
    assert!(!found.is_empty());
    for solution in &found {
        assert_eq!(solution.family, Family::Triples);
        assert_eq!(solution.knots_moved.indices().len(), 3);
        assert!(
            solution
                .knots_moved
                .indices()
                .iter()
                .all(|&k| (4..=9).contains(&k))
        );
        assert!(solution.knots.windows(2).all(|w| w[0] <= w[1]));
    }
}

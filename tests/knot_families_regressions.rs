//! Regression cases of five solver defects in src/shape/family, each found by
//! tests/knot_families_properties.rs and fixed since. One deterministic case per defect: a
//! curve, `t`, a family, the unknown set and the solution planted there (the target is the
//! new curve's point at `t`, by the tests' own de Boor); the answer of that family must hold
//! the planted solution (within 1e-7 of each knot's room, or the conditioning's share of
//! rounding), and every solution it gives must pass the independent checks of
//! tests/common/families.rs.
//!
//! * D1 — a pair with one outermost knot whose other knot is its neighbour (local `(1, 2)` or
//!   `(2q − 1, 2q)`): the other knot was searched only between the outer knot's *old* value
//!   and its far neighbour, so solutions with the other knot past that old value were lost.
//!   It now ranges over its interval in the pair's admissible box.
//! * D2 — a pair with one outermost knot: the univariate root was taken at the centre of its
//!   isolating box, the outer knot extrapolated from `α_A` there, and Newton's polish on
//!   de Boor could not recover from that start: the solution was dropped. The root is now
//!   refined by Newton's method on the univariate polynomial first.
//! * D3 — a pair `(t_1, t_{q+1})` (or `(t_q, t_{2q})`) with `t` on a knot, so `t_q = ũ` (or
//!   `t_{q+1} = ũ`) is fixed: the factor divided out of `G` at the span's collapse has a lower
//!   order than `q − 1` there (forced ratios), it was not divided out at all, and the spurious
//!   root at the collapse took the pair's 4096 boxes. The order is now read off the
//!   coefficients.
//! * D4 — two solutions closing in on a fold (1.5e-4 of the box apart, conditioning 1.2e-6):
//!   the subdivision spent its 4096 boxes tiling a sliver around the first root (where the
//!   equations stay within the rounding margin of zero, so no test decides), and the 16
//!   uncertified candidates kept all lay at that root: the second was lost. Now a
//!   neighbourhood narrower than 1e-6 of the box gets 64 boxes of its own, and the
//!   candidates left are one per cluster of touching boxes (docs/method.md §31.4).
//!
//! * D5 — a degree-4 curve's direct pair of two neighbouring knots below `t` (local
//!   `(q − 1, q)`) with `t` 3e-9 below the next knot: the span nearly collapses at the box's
//!   edge `t_q = ũ`, where `F` stays within the rounding margin of zero all along the edge;
//!   the depth-first subdivision spent its 4096 boxes on that sliver before it reached the
//!   well-conditioned root at `(2.231, 2.901)`. The subdivision now takes the largest boxes
//!   first, so a budget that runs out leaves only the narrowest boxes undecided.
#![allow(clippy::unwrap_used)]

mod common;

use common::families::{
    Net, Planted, SetBox, check_solution, conditioning, only, planted_found, query, setup,
};
use knotshape::shape::Side;
use knotshape::shape::family::{Family, solve_families};
use knotshape::spline::{Curve, CurveLimits};

/// The quintic of these cases: 16 points on a sine, clamped knots with a double knot at 0.36.
fn quintic() -> Curve {
    let mut knots = vec![0.0; 6];
    knots.extend([
        0.08, 0.1733, 0.2667, 0.36, 0.36, 0.4533, 0.5467, 0.64, 0.7333, 0.8267,
    ]);
    knots.extend([1.0; 6]);
    let points: Vec<[f64; 2]> = (0..16)
        .map(|i| {
            let x = i as f64;
            [x, (0.7 * x).sin() * 2.0 + 0.1 * x]
        })
        .collect();
    Curve::new(5, &points, &knots, None, &CurveLimits::default()).unwrap()
}

/// The study's ex03 cubic (knot-family.md §2.3).
fn ex03() -> Curve {
    Curve::new(
        3,
        &[[0.43, 1.61], [0.72, 0.67], [-0.12, 1.18], [-0.53, -0.91]],
        &[-1.75, -1.37, -0.88, 0.0, 0.80, 1.47, 2.00, 2.69],
        None,
        &CurveLimits::default(),
    )
    .unwrap()
}

/// Solves for the target of the planted `x` with `family` alone; checks every solution and
/// that each of `expected` (the planted one first) is among them.
fn assert_found(
    curve: &Curve,
    t: f64,
    family: Family,
    side: Option<Side>,
    keep_domain: bool,
    unknowns: &[usize],
    expected: &[Vec<f64>],
) {
    let problem = setup(curve, t, family, side, keep_domain).unwrap();
    let sbox = SetBox::new(&problem, unknowns).unwrap();
    let knots = problem.knots_with(unknowns, &expected[0]);
    let target = common::de_boor(curve, &knots, t).unwrap();
    let outcome = solve_families(&query(curve, t, side, keep_domain), only(family), target);
    for solution in &outcome.solutions {
        check_solution(curve, &problem, target, solution).unwrap_or_else(|e| panic!("{e}"));
    }
    let answer: Vec<Vec<f64>> =
        common::families::answers_of(&outcome.solutions, &problem, unknowns)
            .iter()
            .map(|s| unknowns.iter().map(|&g| s.knots[g]).collect())
            .collect();
    for x in expected {
        let planted = Planted {
            unknowns: unknowns.to_vec(),
            x: x.clone(),
            target,
            inside: sbox.inside(x),
            conditioning: conditioning(&Net::of(curve), &problem, &sbox, x),
        };
        assert!(
            planted.required(),
            "the case itself: {x:?} inside {:.1e} conditioning {:.1e}",
            planted.inside,
            planted.conditioning
        );
        assert!(
            planted_found(curve, &problem, &planted, &outcome.solutions),
            "{family:?} {side:?} set {unknowns:?} at t = {t}: the solution {x:?} (inside {:.1e} of the box, conditioning {:.1e}) is missing; target {target:?}; the answer for the set: {answer:?}",
            planted.inside,
            planted.conditioning
        );
    }
}

/// D1: quintic, t = 0.5 (span 11), envelope right side (u_12 := 0.5), pair (u_8, u_9) =
/// local (1, 2): planted u_8 = 0.17331867, u_9 = 0.266659335 (u_9 below u_8's old value
/// 0.2667, which bounds the solver's search for u_9).
#[test]
fn d1_one_outermost_neighbour_pair_searches_past_the_outer_knots_old_value() {
    assert_found(
        &quintic(),
        0.5,
        Family::Envelope,
        Some(Side::Right),
        true,
        &[8, 9],
        &[vec![0.17331867, 0.266659335]],
    );
}

/// D2: quintic, t = 0.4 (span 10), direct family, pair (u_6, u_7) = local (1, 2), planted
/// u_6 = 0.08001, u_7 = 0.192024 (inside the solver's search for u_7, [0.08, 0.2667]): the
/// univariate equation's root is isolated near u_7 ≈ 0.192 but its box centre (u_7 ≈ 0.2046)
/// is used, α_A there gives u_6 ≈ 1.15 and the polish cannot recover.
#[test]
fn d2_one_outermost_root_is_refined_before_the_outer_knot_is_computed() {
    assert_found(
        &quintic(),
        0.4,
        Family::Direct,
        None,
        true,
        &[6, 7],
        &[vec![0.08001, 0.192024]],
    );
}

/// D2 (the other end): quintic, t = 0.45, envelope left side (u_10 := 0.45), pair
/// (u_9, u_14) = local (q, 2q): planted u_9 = 0.32169, u_14 = 0.75202; the box centre gives
/// (0.3118, 0.8929), which is dropped.
#[test]
fn d2_one_outermost_root_is_refined_at_the_far_end_too() {
    assert_found(
        &quintic(),
        0.45,
        Family::Envelope,
        Some(Side::Left),
        true,
        &[9, 14],
        &[vec![0.32169, 0.75202]],
    );
}

/// D3: quintic, t = 0.36 on its double knot (u_9 = u_10), envelope left side (u_10 := t, the
/// envelope's t_q = u_9 = t fixed), pair (u_6, u_11) = local (1, q + 1): planted
/// u_6 = 0.05199, u_11 = 0.47202.
#[test]
fn d3_one_outermost_with_t_on_a_knot_keeps_its_solution() {
    assert_found(
        &quintic(),
        0.36,
        Family::Envelope,
        Some(Side::Left),
        true,
        &[6, 11],
        &[vec![0.05199, 0.47202]],
    );
}

/// D4: ex03 (domain free), t = 0.431, direct family, the span pair (u_3, u_4): the target
/// (0.2955581377462337, 0.9306050887207246), planted at u_3 = −0.0934497409159008,
/// u_4 = 1.3894138647693457 next to a fold, has a second solution 1.5e-4 of the box away,
/// u_3 = −0.0933502617166108, u_4 = 1.3892216075004733; the answer has only the second.
#[test]
fn d4_both_solutions_next_to_a_fold_are_found() {
    assert_found(
        &ex03(),
        0.431,
        Family::Direct,
        None,
        false,
        &[3, 4],
        &[
            vec![-0.0934497409159008, 1.3894138647693457],
            vec![-0.0933502617166108, 1.3892216075004733],
        ],
    );
}

/// D5: the regions property's case 0x0b0ff5ffb45fdb51 (a random degree-4 2D curve): the
/// direct pair (u_5, u_6) has one well-conditioned root for this target, which the answer
/// must hold (and every solution it gives must check out).
#[test]
fn d5_neighbour_pair_below_a_near_collapsed_span_finds_its_root() {
    use common::SplitMix64;
    use common::families::{BruteOptions, CurveKind, brute_force, random_curve, random_parameter};
    let mut rng = SplitMix64::new(0x0b0f_f5ff_b45f_db51);
    let mut kind = CurveKind::random(&mut rng, 2..=5);
    kind.dimension = 2;
    let curve = random_curve(&mut rng, &kind);
    let t = random_parameter(&mut rng, &curve);
    assert_eq!(curve.degree(), 4);
    let target = [4.044620269805664, -1.0312627713553562, 0.0];
    let problem = setup(&curve, t, Family::Direct, None, true).unwrap();
    let sbox = SetBox::new(&problem, &[5, 6]).unwrap();
    let brute = brute_force(
        &Net::of(&curve),
        &problem,
        &sbox,
        target,
        BruteOptions::pairs(),
    );
    let required: Vec<_> = brute
        .roots
        .iter()
        .filter(|r| r.inside > 0.1 && r.conditioning > 1e-2)
        .collect();
    assert_eq!(required.len(), 1, "{:?}", brute.roots);
    let outcome = solve_families(&query(&curve, t, None, true), only(Family::Direct), target);
    for solution in &outcome.solutions {
        check_solution(&curve, &problem, target, solution).unwrap_or_else(|e| panic!("{e}"));
    }
    let planted = Planted {
        unknowns: vec![5, 6],
        x: required[0].x.clone(),
        target,
        inside: required[0].inside,
        conditioning: required[0].conditioning,
    };
    assert!(planted.required());
    assert!(
        planted_found(&curve, &problem, &planted, &outcome.solutions),
        "the root {:?} is missing",
        required[0].x
    );
}

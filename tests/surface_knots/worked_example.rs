//! The worked example of the study (knot-family.md §6, ex02): the 10 × 10 bicubic net
//! `d_ij = (i, j, round(sin i · cos 0.7 j, 3))`, `ũ = ṽ = 0.5`, `u_7 := ũ`, and a target in
//! the plane of `D_4, D_5, D_6(ṽ)` planted by the Ω5 pair `(u_5, u_9) = (0.32, 0.82)`.

use knotshape::shape::family::Family;
use knotshape::surface::Direction;
use knotshape::surface::edit::knots::{
    SurfaceKnotFamily, nearest_surface_knot_target, solve_surface_knots, surface_knot_membership,
    surface_knot_regions,
};

use crate::reference::{Net, clamped, distance};

/// The example's net.
pub fn example() -> Net {
    let poles = (0..10)
        .map(|i| {
            (0..10)
                .map(|j| {
                    let z = ((i as f64).sin() * (0.7 * j as f64).cos() * 1000.0).round() / 1000.0;
                    [i as f64, j as f64, z]
                })
                .collect()
        })
        .collect();
    Net {
        degrees: (3, 3),
        knots_u: clamped(3, &[0.15, 0.3, 0.45, 0.6, 0.75, 0.85]),
        knots_v: clamped(3, &[0.1, 0.3, 0.45, 0.6, 0.7, 0.85]),
        poles,
        weights: None,
    }
}

fn close(a: [f64; 3], b: [f64; 3], tolerance: f64) -> bool {
    distance(a, b) <= tolerance
}

#[test]
fn the_worked_example_has_the_study_numbers() {
    let net = example();
    // s(ũ, ṽ) and the envelope point after u_7 := ũ (the study's six digits).
    assert!(close(
        net.point(0.5, 0.5),
        [4.334105, 4.386111, 0.71864],
        2e-6
    ));
    let mut envelope = net.knots_u.clone();
    envelope[7] = 0.5;
    let h = net.point_with(&envelope, &net.knots_v, 0.5, 0.5);
    assert!(close(h, [4.55787, 4.386111, 0.780395], 2e-6), "{h:?}");
    // The planted target: Ω5 (u_5, u_9) = (0.32, 0.82).
    let mut planted = envelope.clone();
    planted[5] = 0.32;
    planted[9] = 0.82;
    let target = net.point_with(&planted, &net.knots_v, 0.5, 0.5);
    assert!(
        close(target, [4.538026, 4.386111, 0.775349], 2e-6),
        "{target:?}"
    );

    let surface = net.surface();
    let solutions = solve_surface_knots(&surface, 0.5, 0.5, target, true);
    let right: Vec<_> = solutions
        .iter()
        .filter(|s| {
            s.family
                == SurfaceKnotFamily::Iso {
                    direction: Direction::U,
                    family: Family::Envelope,
                }
                && s.knots_u.as_ref().is_some_and(|k| k[7] == 0.5)
        })
        .collect();
    // The study's five u-pairs (the sixth, (u_6, u_9), reaches nothing).
    let expected: [([usize; 2], [f64; 2]); 5] = [
        ([5, 6], [0.323332, 0.447657]),
        ([5, 8], [0.342545, 0.7275]),
        ([5, 9], [0.32, 0.82]),
        ([6, 8], [0.44496, 0.777044]),
        ([8, 9], [0.769798, 0.797094]),
    ];
    assert_eq!(
        right.len(),
        expected.len(),
        "{:#?}",
        right.iter().map(|s| &s.region).collect::<Vec<_>>()
    );
    for (pair, values) in expected {
        let found = right
            .iter()
            .find(|s| {
                let k = s.knots_u.as_ref().unwrap();
                let changed: Vec<usize> = s
                    .changed_knots_u
                    .iter()
                    .copied()
                    .filter(|&i| i != 7)
                    .collect();
                changed == pair
                    && (k[pair[0]] - values[0]).abs() < 2e-6
                    && (k[pair[1]] - values[1]).abs() < 2e-6
            })
            .unwrap_or_else(|| panic!("pair {pair:?} not found"));
        // Independent evaluation of the new surface.
        let k = found.knots_u.as_ref().unwrap();
        let point = net.point_with(k, &net.knots_v, 0.5, 0.5);
        assert!(distance(point, target) < 1e-12, "{pair:?}: {point:?}");
        assert!(found.residual < 1e-12);
        assert_eq!(found.knots_v, None);
        assert_eq!(found.affected_domain[1], (0.0, 1.0));
    }
    // The planted Ω5 values are recovered to rounding.
    assert!(right.iter().any(|s| {
        let k = s.knots_u.as_ref().unwrap();
        (k[5] - 0.32).abs() < 1e-12 && (k[9] - 0.82).abs() < 1e-12
    }));
    // Every solution of every family moves the surface through the target.
    for s in &solutions {
        let ku = s.knots_u.clone().unwrap_or_else(|| net.knots_u.clone());
        let kv = s.knots_v.clone().unwrap_or_else(|| net.knots_v.clone());
        let point = net.point_with(&ku, &kv, 0.5, 0.5);
        assert!(distance(point, target) < 1e-9, "{}: {point:?}", s.region);
    }
    // Membership agrees; the nearest reachable point of a reachable target is itself.
    let members = surface_knot_membership(&surface, 0.5, 0.5, target, true);
    assert!(members.iter().filter(|m| m.contains).count() >= 5);
    for s in &solutions {
        assert!(
            members
                .iter()
                .any(|m| m.contains && m.family == s.family && s.region.starts_with(&m.region)),
            "{} has no member",
            s.region
        );
    }
    for m in members.iter().filter(|m| m.contains) {
        assert!(
            solutions
                .iter()
                .any(|s| s.family == m.family && s.region.starts_with(&m.region))
        );
    }
    let nearest = nearest_surface_knot_target(&surface, 0.5, 0.5, target, true).unwrap();
    assert!(distance(nearest, target) < 1e-9);
    // The right envelope side's regions lie in the plane of D_4, D_5, D_6(ṽ) (y = 4.386111).
    let regions = surface_knot_regions(&surface, 0.5, 0.5, true);
    let envelope_u: Vec<_> = regions
        .iter()
        .filter(|r| r.region.starts_with("u envelope right"))
        .collect();
    assert_eq!(envelope_u.len(), 6);
    for region in envelope_u {
        for ring in &region.rings {
            for point in ring {
                assert!((point[1] - h[1]).abs() < 1e-9, "{point:?}");
            }
        }
    }
}

#[test]
fn a_target_out_of_reach_gets_a_nearer_reachable_point() {
    let net = example();
    let surface = net.surface();
    let point = net.point(0.5, 0.5);
    let far = [point[0] + 0.6, point[1] - 0.4, point[2] + 0.5];
    assert!(solve_surface_knots(&surface, 0.5, 0.5, far, true).is_empty());
    let members = surface_knot_membership(&surface, 0.5, 0.5, far, true);
    assert!(!members.is_empty() && members.iter().all(|m| !m.contains));
    let near = nearest_surface_knot_target(&surface, 0.5, 0.5, far, true).unwrap();
    assert!(
        distance(near, far) < distance(point, far) - 1e-3,
        "{near:?}"
    );
    // The point claimed is reached (the solver, then the independent evaluator).
    let reached = solve_surface_knots(&surface, 0.5, 0.5, near, true);
    assert!(!reached.is_empty());
    for s in &reached {
        let ku = s.knots_u.clone().unwrap_or_else(|| net.knots_u.clone());
        let kv = s.knots_v.clone().unwrap_or_else(|| net.knots_v.clone());
        assert!(distance(net.point_with(&ku, &kv, 0.5, 0.5), near) < 1e-9);
    }
}

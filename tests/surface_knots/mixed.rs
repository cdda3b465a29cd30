//! Mixed moves: planted solutions are recovered, and a brute-force search over the unknown
//! knots finds nothing the solver misses.

use knotshape::surface::Direction;
use knotshape::surface::edit::knots::{SurfaceKnotFamily, solve_surface_knots};

use crate::reference::distance;
use crate::worked_example::example;

#[test]
fn a_planted_mixed_move_on_the_worked_net_is_recovered() {
    let net = example();
    let (mut ku, mut kv) = (net.knots_u.clone(), net.knots_v.clone());
    ku[7] = 0.5;
    kv[7] = 0.5;
    ku[5] = 0.32;
    ku[9] = 0.82;
    kv[8] = 0.68;
    let target = net.point_with(&ku, &kv, 0.5, 0.5);
    let surface = net.surface();
    let solutions = solve_surface_knots(&surface, 0.5, 0.5, target, true);
    let mixed: Vec<_> = solutions
        .iter()
        .filter(|s| s.family == SurfaceKnotFamily::Mixed { pair: Direction::U })
        .collect();
    eprintln!(
        "{:#?}",
        mixed
            .iter()
            .map(|s| (&s.region, s.residual))
            .collect::<Vec<_>>()
    );
    let planted = mixed.iter().find(|s| {
        let (u, v) = (s.knots_u.as_ref().unwrap(), s.knots_v.as_ref().unwrap());
        (0..u.len()).all(|i| (u[i] - ku[i]).abs() < 1e-9)
            && (0..v.len()).all(|i| (v[i] - kv[i]).abs() < 1e-9)
    });
    assert!(planted.is_some(), "the planted move is missing");
    for s in &mixed {
        let point = net.point_with(
            s.knots_u.as_ref().unwrap(),
            s.knots_v.as_ref().unwrap(),
            0.5,
            0.5,
        );
        assert!(distance(point, target) < 1e-9, "{}: {point:?}", s.region);
    }
}

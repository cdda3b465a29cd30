//! Iso-curves, knot insertion and splitting on the real surfaces, against exact rational
//! arithmetic: the iso-curve's points, the refined surface's and the pieces' are the exact
//! points of the original surface (within `1e-12` of its size, or the rounding of the
//! coordinates' magnitude).

use knotshape::surface::{Direction, Surface};

use crate::common::SplitMix64;
use crate::corpus::{SurfaceData, surfaces};
use crate::curve_exact::distance;
use crate::exact::exact_partials;

/// Surfaces of the corpus used (every `STEP`-th) and points checked per operation.
const STEP: usize = 9;
const POINTS: usize = 3;

/// The allowance for a point of `data`: `1e-12` of its size, or `16 ε` of its largest
/// coordinate, whichever is larger (insertion and splitting round the control points once,
/// each a convex combination of the old ones).
fn allowance(data: &SurfaceData) -> f64 {
    let magnitude = data
        .poles
        .iter()
        .flatten()
        .flatten()
        .fold(0.0f64, |m, x| m.max(x.abs()));
    (1e-12 * data.size()).max(16.0 * f64::EPSILON * magnitude)
}

/// Checks `computed` against the exact point of `data` at `(u, v)`.
fn check(
    data: &SurfaceData,
    (u, v): (f64, f64),
    computed: [f64; 3],
    what: &str,
    failures: &mut Vec<String>,
) {
    let exact = &exact_partials(data, u, v, 0)[0][0];
    let error = distance(exact, computed);
    if error > allowance(data) {
        failures.push(format!(
            "{} {what} at ({u}, {v}): off by {error:e}",
            data.id
        ));
    }
}

fn random_pair(surface: &Surface, rng: &mut SplitMix64) -> (f64, f64) {
    let [(u0, u1), (v0, v1)] = surface.domain();
    (rng.range(u0, u1), rng.range(v0, v1))
}

#[test]
fn iso_curves_insertion_and_pieces_are_the_exact_surface() {
    let mut rng = SplitMix64::new(0x1500);
    let mut failures = Vec::new();
    for data in surfaces().iter().step_by(STEP) {
        let surface = data.surface();
        let [(u0, u1), (v0, v1)] = surface.domain();
        // Iso-curves in both directions.
        for (fixed, value) in [
            (Direction::V, rng.range(v0, v1)),
            (Direction::U, rng.range(u0, u1)),
        ] {
            let curve = surface.iso_curve(fixed, value);
            assert_eq!(curve.is_rational(), surface.is_rational(), "{}", data.id);
            let (lo, hi) = curve.domain();
            for _ in 0..POINTS {
                let t = rng.range(lo, hi);
                let pair = match fixed {
                    Direction::V => (t, value),
                    Direction::U => (value, t),
                };
                check(
                    data,
                    pair,
                    curve.point(t).unwrap(),
                    "iso-curve",
                    &mut failures,
                );
            }
        }
        // Insertion of two values per direction (one of them twice where the degree allows).
        let (a, b) = random_pair(&surface, &mut rng);
        let knots_u = if surface.u().degree() >= 2 {
            vec![a, a]
        } else {
            vec![a]
        };
        let refined = surface.insert_knots(&knots_u, &[b], usize::MAX).unwrap();
        for _ in 0..POINTS {
            let pair = random_pair(&surface, &mut rng);
            check(
                data,
                pair,
                refined.point(pair.0, pair.1),
                "refined",
                &mut failures,
            );
        }
        // Split at two values in u, then one piece checked at its own parameters.
        let cuts = [u0 + 0.3 * (u1 - u0), u0 + 0.7 * (u1 - u0)];
        let pieces = surface.split(Direction::U, &cuts, 10, usize::MAX).unwrap();
        assert_eq!(pieces.len(), 3, "{}", data.id);
        for piece in &pieces {
            let [(a0, a1), _] = piece.domain();
            for _ in 0..POINTS {
                let pair = (rng.range(a0, a1), rng.range(v0, v1));
                check(
                    data,
                    pair,
                    piece.point(pair.0, pair.1),
                    "piece",
                    &mut failures,
                );
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} failures: {:#?}",
        failures.len(),
        &failures[..failures.len().min(8)]
    );
}

proptest::proptest! {
    #![proptest_config(proptest::test_runner::Config { cases: 48, ..crate::config() })]

    /// Random surfaces (degrees 1–7 in each direction, rational, coincident knots, tiny
    /// spans): the iso-curves, the surface after inserting a value in each direction (twice
    /// in `u` where the degree allows) and the pieces of a split in `v` are the exact surface.
    #[test]
    fn random_surfaces_keep_their_shape_through_iso_curves_insertion_and_split(
        data in crate::generators::surface_data(),
        s in 0.05..0.95f64,
        t in 0.05..0.95f64,
    ) {
        let surface = data.surface();
        let [(u0, u1), (v0, v1)] = surface.domain();
        let (u, v) = (u0 + s * (u1 - u0), v0 + t * (v1 - v0));
        let mut failures = Vec::new();
        let mut rng = SplitMix64::new(s.to_bits() ^ t.to_bits());
        let along_u = surface.iso_curve(Direction::V, v);
        let along_v = surface.iso_curve(Direction::U, u);
        for _ in 0..POINTS {
            let (a, b) = random_pair(&surface, &mut rng);
            check(&data, (a, v), along_u.point(a).unwrap(), "iso-curve in u", &mut failures);
            check(&data, (u, b), along_v.point(b).unwrap(), "iso-curve in v", &mut failures);
        }
        let knots_u = if surface.u().degree() >= 2 { vec![u, u] } else { vec![u] };
        if let Ok(refined) = surface.insert_knots(&knots_u, &[v], usize::MAX) {
            for _ in 0..POINTS {
                let pair = random_pair(&surface, &mut rng);
                check(&data, pair, refined.point(pair.0, pair.1), "refined", &mut failures);
            }
        }
        // A cut strictly inside the domain (a value at a knot of full multiplicity may be
        // refused; the others must succeed).
        if let Ok(pieces) = surface.split(Direction::V, &[v], 10, usize::MAX) {
            for piece in &pieces {
                let [_, (b0, b1)] = piece.domain();
                let pair = (rng.range(u0, u1), rng.range(b0, b1));
                check(&data, pair, piece.point(pair.0, pair.1), "piece", &mut failures);
            }
        }
        proptest::prop_assert!(failures.is_empty(), "{:#?}", failures);
    }
}

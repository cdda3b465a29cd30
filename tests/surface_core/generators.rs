//! Random surfaces for the properties: degrees 1–7 in each direction, rational or not,
//! clamped or not, with coincident knots (up to the degree), spans of `1e-8` and knots
//! `1e-13` apart, control points moved far from the origin.

use proptest::collection::vec;
use proptest::prelude::*;

use crate::corpus::SurfaceData;

/// Highest degree per direction the properties draw.
pub const MAX_RANDOM_DEGREE: usize = 7;

/// A knot gap: mostly ordinary, sometimes `1e-8` (a short span), `1e-13` (a near-multiple
/// knot) or zero (a repeated knot).
fn gap() -> impl Strategy<Value = f64> {
    prop_oneof![
        6 => 0.05..1.0f64,
        1 => Just(1e-8),
        1 => 1e-13..3e-13f64,
        2 => Just(0.0),
    ]
}

/// One direction's full knot vector for `count` control points of degree `p` from `gaps`
/// (`count + p` of them): runs of at most `p` zero gaps (multiplicity `p` inside, so the
/// surface stays continuous), `p + 1` equal end knots when `clamped`, a non-empty domain.
fn knots_from(gaps: &mut [f64], p: usize, count: usize, clamped: bool, start: f64) -> Vec<f64> {
    let len = gaps.len();
    let mut run = 0;
    for (index, g) in gaps.iter_mut().enumerate() {
        let at_end = clamped && (index < p || index >= len - p);
        if *g == 0.0 && !at_end {
            run += 1;
            if run >= p {
                *g = 0.5;
                run = 0;
            }
        } else {
            run = 0;
        }
    }
    if clamped {
        gaps[..p].iter_mut().for_each(|g| *g = 0.0);
        gaps[len - p..].iter_mut().for_each(|g| *g = 0.0);
        if gaps[len - p - 1] == 0.0 {
            gaps[len - p - 1] = 0.5;
        }
        if gaps[p] == 0.0 {
            gaps[p] = 0.5;
        }
    }
    if gaps[p..count].iter().all(|&g| g == 0.0) {
        gaps[p] = 0.5;
    }
    let mut knots = vec![start];
    for g in gaps.iter() {
        knots.push(knots[knots.len() - 1] + g);
    }
    knots
}

/// Random surfaces (module docs): `p + 1` to `p + 4` control points per direction in
/// `extent · [-1, 1]³` moved by `offset`, weights in `[0.2, 5]` or none.
pub fn surface_data() -> impl Strategy<Value = SurfaceData> {
    (
        1..=MAX_RANDOM_DEGREE,
        1..=MAX_RANDOM_DEGREE,
        0usize..=3,
        0usize..=3,
        any::<bool>(),
        (any::<bool>(), any::<bool>()),
        prop_oneof![Just(0.0), Just(1e3)],
        prop_oneof![Just(1e-2), Just(1.0), Just(100.0)],
    )
        .prop_flat_map(
            |(p, q, extra_u, extra_v, rational, clamped, offset, extent)| {
                let (n_u, n_v) = (p + 1 + extra_u, q + 1 + extra_v);
                (
                    Just((p, q, rational, clamped, offset, extent)),
                    vec(vec([-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64], n_v), n_u),
                    vec(vec(0.2..5.0f64, n_v), n_u),
                    vec(gap(), n_u + p),
                    vec(gap(), n_v + q),
                    (-5.0..5.0f64, -5.0..5.0f64),
                )
            },
        )
        .prop_map(
            |(
                (p, q, rational, (clamped_u, clamped_v), offset, extent),
                poles,
                weights,
                mut gaps_u,
                mut gaps_v,
                (start_u, start_v),
            )| {
                let (n_u, n_v) = (poles.len(), poles[0].len());
                let knots_u = knots_from(&mut gaps_u, p, n_u, clamped_u, start_u);
                let knots_v = knots_from(&mut gaps_v, q, n_v, clamped_v, start_v);
                let poles = poles
                    .into_iter()
                    .map(|row| {
                        row.into_iter()
                            .map(|d| d.map(|x| offset + extent * x))
                            .collect()
                    })
                    .collect();
                SurfaceData {
                    id: format!("random {p}x{q}"),
                    degree_u: p,
                    degree_v: q,
                    poles,
                    weights: rational.then_some(weights),
                    knots_u,
                    knots_v,
                    occt: None,
                    reference: Vec::new(),
                }
            },
        )
}

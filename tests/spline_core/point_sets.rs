//! Random point sets for the curves-through-points properties: clustered (chords of very
//! different lengths), nearly collinear, zig-zag and scattered, in 2D or 3D.

use proptest::collection::vec;
use proptest::prelude::*;

/// The kind of a random point set.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Shape {
    /// Groups of close points far apart: chord lengths spread over five orders of magnitude.
    Clustered,
    /// Points along a line, off it by `1e-7` of the size.
    NearlyCollinear,
    /// Alternating up and down along a line.
    ZigZag,
    /// Anywhere in a box.
    Scattered,
}

/// A point set: its shape and the points (each 2 or 3 coordinates), consecutive points
/// distinct.
#[derive(Debug, Clone)]
pub struct PointCase {
    pub shape: Shape,
    pub points: Vec<Vec<f64>>,
}

impl PointCase {
    /// The points with `z = 0` added when planar.
    pub fn points_3d(&self) -> Vec<[f64; 3]> {
        self.points
            .iter()
            .map(|p| [p[0], p[1], p.get(2).copied().unwrap_or(0.0)])
            .collect()
    }

    /// The diagonal of the bounding box.
    pub fn size(&self) -> f64 {
        let points = self.points_3d();
        let mut low = [f64::INFINITY; 3];
        let mut high = [f64::NEG_INFINITY; 3];
        for p in &points {
            for c in 0..3 {
                low[c] = low[c].min(p[c]);
                high[c] = high[c].max(p[c]);
            }
        }
        (0..3)
            .map(|c| (high[c] - low[c]).powi(2))
            .sum::<f64>()
            .sqrt()
    }
}

/// Builds the points of `shape` from uniform random numbers in `[0, 1)` (`count` points of
/// `dimension` coordinates; `randoms` has at least `4 · count` values).
fn build(shape: Shape, count: usize, dimension: usize, randoms: &[f64]) -> Vec<Vec<f64>> {
    let r = |i: usize| randoms[i % randoms.len()];
    (0..count)
        .map(|k| {
            let base = 4 * k;
            let mut point = match shape {
                Shape::Clustered => {
                    // Clusters of 3 points: centres 10 apart, members within 1e-4 .. 1e-2.
                    let cluster = (k / 3) as f64;
                    let spread = 10f64.powf(-4.0 + 2.0 * r(base));
                    vec![
                        10.0 * cluster + spread * (k % 3) as f64,
                        5.0 * (cluster * 1.7).sin() + spread * r(base + 1),
                        3.0 * (cluster * 0.9).cos() + spread * r(base + 2),
                    ]
                }
                Shape::NearlyCollinear => vec![
                    k as f64 + 0.5 * r(base),
                    1e-7 * (2.0 * r(base + 1) - 1.0) * count as f64,
                    1e-7 * (2.0 * r(base + 2) - 1.0) * count as f64,
                ],
                Shape::ZigZag => vec![
                    k as f64 + 0.2 * r(base),
                    if k % 2 == 0 { 1.0 } else { -1.0 } * (0.5 + r(base + 1)),
                    r(base + 2),
                ],
                Shape::Scattered => vec![10.0 * r(base), 10.0 * r(base + 1), 10.0 * r(base + 2)],
            };
            point.truncate(dimension);
            point
        })
        .collect()
}

/// Random point sets of `min..=max` points, every shape, 2D and 3D.
pub fn point_case(min: usize, max: usize) -> impl Strategy<Value = PointCase> {
    (
        prop_oneof![
            Just(Shape::Clustered),
            Just(Shape::NearlyCollinear),
            Just(Shape::ZigZag),
            Just(Shape::Scattered),
        ],
        min..=max,
        prop_oneof![Just(2usize), Just(3usize)],
        vec(0.0..1.0f64, 4 * max),
    )
        .prop_map(|(shape, count, dimension, randoms)| PointCase {
            shape,
            points: build(shape, count, dimension, &randoms),
        })
        .prop_filter("consecutive points distinct", |case| {
            case.points.windows(2).all(|w| {
                w[0].iter()
                    .zip(&w[1])
                    .map(|(a, b)| (a - b).powi(2))
                    .sum::<f64>()
                    .sqrt()
                    > 1e-9 * case.size()
            })
        })
}

//! A cheap exclusion before a set is solved: the point the set can
//! reach lies in the convex hull of the *frontier* of de Boor's triangle, so a target
//! farther than the accepted residual from that hull needs no polynomial system at all.
//!
//! In de Boor's triangle of [`LocalProblem`] the entry `d_l^[r]` combines `d_{l-1}^[r-1]` and
//! `d_l^[r-1]` with the ratio `α_{l,r} = (ũ - t_l) / (t_{l+q+1-r} - t_l)`. An entry is
//! *constant* for a set of unknown knots when neither knot of its ratio is unknown and both
//! its inputs are constant (the control points `d_l^[0]` always are). For every admissible
//! value of the unknowns (ordered knots, `ũ` in the span) each ratio lies in `[0, 1]`, so the
//! point `d_q^[q]` is a convex combination of the constant entries met first on the way down
//! from it (the frontier), and of homogeneous entries with positive weights, so their
//! cartesian points combine convexly too. The test runs in the plane of the equations'
//! directions (`rows`): a solution's point has the target's coordinates there. For triples
//! on 3D curves (three rows) each pair of rows gives a necessary test (docs/method.md §31.4).

use smallvec::SmallVec;

use super::local::LocalProblem;
use crate::spline::vector::{Point, dot};

/// De Boor's whole triangle at the problem's own knots: entry `(l, r)` at `r (q + 1) + l`,
/// homogeneous.
pub struct Triangle {
    degree: usize,
    entries: Vec<[f64; 4]>,
}

impl Triangle {
    /// Runs de Boor at `problem`'s knots and keeps every entry.
    pub fn of(problem: &LocalProblem) -> Triangle {
        let q = problem.degree;
        let u = problem.parameter;
        let k = &problem.knots;
        let mut entries = vec![[0.0; 4]; (q + 1) * (q + 1)];
        entries[..=q].copy_from_slice(&problem.poles);
        for r in 1..=q {
            for l in r..=q {
                let (lo, hi) = (l, l + q + 1 - r);
                let span = k[hi] - k[lo];
                let alpha = if span > 0.0 { (u - k[lo]) / span } else { 0.0 };
                let previous = entries[(r - 1) * (q + 1) + l - 1];
                let current = entries[(r - 1) * (q + 1) + l];
                let entry = &mut entries[r * (q + 1) + l];
                for c in 0..4 {
                    entry[c] = previous[c] + alpha * (current[c] - previous[c]);
                }
            }
        }
        Triangle { degree: q, entries }
    }

    /// The cartesian points of the frontier for the local unknowns `unknowns` (module docs).
    fn frontier(&self, unknowns: &[usize]) -> SmallVec<[Point; 16]> {
        let q = self.degree;
        let at = |l: usize, r: usize| r * (q + 1) + l;
        // constant[(l, r)]: the entry does not depend on any unknown.
        let mut constant: SmallVec<[bool; 64]> = SmallVec::from_elem(true, (q + 1) * (q + 1));
        for r in 1..=q {
            for l in r..=q {
                let moved = unknowns.contains(&l) || unknowns.contains(&(l + q + 1 - r));
                constant[at(l, r)] = !moved && constant[at(l - 1, r - 1)] && constant[at(l, r - 1)];
            }
        }
        let mut reached: SmallVec<[bool; 64]> = SmallVec::from_elem(false, (q + 1) * (q + 1));
        reached[at(q, q)] = true;
        let mut points: SmallVec<[Point; 16]> = SmallVec::new();
        for r in (0..=q).rev() {
            for l in r..=q {
                if !reached[at(l, r)] {
                    continue;
                }
                if constant[at(l, r)] {
                    let h = self.entries[at(l, r)];
                    points.push([h[0] / h[3], h[1] / h[3], h[2] / h[3]]);
                } else {
                    reached[at(l - 1, r - 1)] = true;
                    reached[at(l, r - 1)] = true;
                }
            }
        }
        points
    }

    /// Whether no admissible value of `unknowns` can bring the point within `margin` of
    /// `target` along `rows` (module docs): then the set has no solution.
    pub fn excludes(&self, unknowns: &[usize], target: Point, rows: &[Point], margin: f64) -> bool {
        let frontier = self.frontier(unknowns);
        let planes: &[(usize, usize)] = if rows.len() == 2 {
            &[(0, 1)]
        } else {
            &[(0, 1), (0, 2), (1, 2)]
        };
        planes.iter().any(|&(a, b)| {
            let project = |p: &Point| [dot(rows[a], *p), dot(rows[b], *p)];
            let points: SmallVec<[[f64; 2]; 16]> = frontier.iter().map(project).collect();
            outside_by(&points, project(&target)) > margin
        })
    }
}

/// A lower bound on the distance from `point` to the convex hull of `points` (0 inside): the
/// largest distance of `point` beyond a hull edge's line, or the distance to the segment or
/// point the hull degenerates to.
fn outside_by(points: &[[f64; 2]], point: [f64; 2]) -> f64 {
    let hull = convex_hull(points);
    match hull.len() {
        0 => 0.0,
        1 => length(sub(point, hull[0])),
        2 => segment_distance(hull[0], hull[1], point),
        n => (0..n)
            .map(|i| {
                let (a, b) = (hull[i], hull[(i + 1) % n]);
                let edge = sub(b, a);
                // Counter-clockwise hull: outside is to the right of each edge.
                let cross = edge[0] * (point[1] - a[1]) - edge[1] * (point[0] - a[0]);
                -cross / length(edge)
            })
            .fold(f64::NEG_INFINITY, f64::max)
            .max(0.0),
    }
}

/// The convex hull, counter-clockwise, without collinear points (Andrew's monotone chain).
fn convex_hull(points: &[[f64; 2]]) -> SmallVec<[[f64; 2]; 16]> {
    let mut sorted: SmallVec<[[f64; 2]; 16]> = SmallVec::from_slice(points);
    sorted.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    sorted.dedup();
    if sorted.len() < 3 {
        return sorted;
    }
    let turn = |o: [f64; 2], a: [f64; 2], b: [f64; 2]| {
        (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    };
    let mut hull: SmallVec<[[f64; 2]; 16]> = SmallVec::new();
    for pass in 0..2 {
        let start = hull.len();
        let ordered: SmallVec<[[f64; 2]; 16]> = if pass == 0 {
            sorted.clone()
        } else {
            sorted.iter().rev().copied().collect()
        };
        for p in ordered {
            while hull.len() >= start + 2
                && turn(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0.0
            {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    if hull.len() < 2 {
        // All points coincide after all (only possible with signed zeros): keep one.
        hull.truncate(1);
    }
    hull
}

fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

fn length(v: [f64; 2]) -> f64 {
    v[0].hypot(v[1])
}

fn segment_distance(a: [f64; 2], b: [f64; 2], p: [f64; 2]) -> f64 {
    let ab = sub(b, a);
    let denominator = ab[0] * ab[0] + ab[1] * ab[1];
    let s = if denominator > 0.0 {
        ((p[0] - a[0]) * ab[0] + (p[1] - a[1]) * ab[1]) / denominator
    } else {
        0.0
    };
    let s = s.clamp(0.0, 1.0);
    length(sub(p, [a[0] + s * ab[0], a[1] + s * ab[1]]))
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use super::*;

    /// Random local problems: every point reached by admissible knots (drawn at random) lies
    /// within rounding of the frontier's hull of its set, whatever the set.
    #[test]
    fn reached_points_lie_in_the_frontier_hull() {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let rows = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        for case in 0..400 {
            let q = 2 + case % 5;
            let mut knots: Vec<f64> = (0..2 * q + 2).map(|_| next()).collect();
            knots.sort_by(f64::total_cmp);
            if knots[q + 1] - knots[q] < 1e-3 {
                continue;
            }
            let parameter = knots[q] + next() * (knots[q + 1] - knots[q]);
            let poles: Vec<[f64; 4]> = (0..=q)
                .map(|_| {
                    let w = 0.5 + next();
                    [w * next(), w * next(), 0.0, w]
                })
                .collect();
            let problem = LocalProblem {
                degree: q,
                knots: knots.clone(),
                full_index: (0..2 * q + 2).collect(),
                poles,
                parameter,
            };
            let triangle = Triangle::of(&problem);
            let a = 1 + (next() * (2 * q) as f64) as usize % (2 * q);
            let b = 1 + (next() * (2 * q) as f64) as usize % (2 * q);
            if a == b {
                continue;
            }
            let unknowns = [a.min(b), a.max(b)];
            for _ in 0..20 {
                // Admissible values: redraw the unknowns within their neighbours, keeping
                // the parameter inside the span.
                let mut moved = knots.clone();
                for &m in &unknowns {
                    let lo = moved[m - 1];
                    let hi = moved[m + 1];
                    let (lo, hi) = match m {
                        _ if m == q => (lo, hi.min(parameter)),
                        _ if m == q + 1 => (lo.max(parameter), hi),
                        _ => (lo, hi),
                    };
                    moved[m] = lo + next() * (hi - lo);
                }
                if !(moved[q] <= parameter && parameter <= moved[q + 1] && moved[q] < moved[q + 1])
                {
                    continue;
                }
                let point = problem.point(&moved);
                assert!(triangle.excludes(
                    &unknowns,
                    [point[0] + 2.0, point[1], 0.0],
                    &rows,
                    1e-12
                ));
                assert!(
                    !triangle.excludes(&unknowns, point, &rows, 1e-12),
                    "degree {q}, unknowns {unknowns:?}: a reached point outside the hull"
                );
            }
        }
    }

    #[test]
    fn the_hull_distance_of_a_square() {
        let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.5, 0.5]];
        assert_eq!(outside_by(&square, [0.5, 0.25]), 0.0);
        assert!((outside_by(&square, [1.5, 0.5]) - 0.5).abs() < 1e-15);
        assert!((outside_by(&[[0.0, 0.0], [2.0, 0.0]], [1.0, 3.0]) - 3.0).abs() < 1e-15);
        assert!((outside_by(&[[1.0, 1.0]], [4.0, 5.0]) - 5.0).abs() < 1e-15);
    }
}

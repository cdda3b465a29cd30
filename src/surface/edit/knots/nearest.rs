//! The nearest point the mixed moves reach (docs/method.md §47), for a target none of them
//! reaches.
//!
//! A mixed set (the pair in `A`, the single knot `c` in `B`, as [`super::mixed`] defines
//! them) maps its three unknowns, in their unit box, to `S(ũ, ṽ)` by de Boor alone: the rows
//! of `B` at `c` give the three poles `D_k(c)`, the pair's primitive on them the point.
//! Searched are a `4³` grid over every set's box, then a pattern search (each unit
//! coordinate moved by ± a step that halves when no move helps, down to `10⁻⁷`) from the
//! best grid points of the best [`REFINED`] sets; the nearest point found is returned only
//! when the mixed solver itself reaches it (the answer is verified, not certified: a narrow
//! well between grid points can be missed).

use super::SurfaceKnotOptions;
use super::iso::{iso_curve_along, movable};
use super::mixed::{Oriented, Side1, direction_problems, rows_of, singles, solve_mixed};
use crate::shape::family::local::{LocalProblem, SearchBox};
use crate::shape::family::problems::unknown_sets;
use crate::shape::family::roots::SEARCH_MARGIN;
use crate::spline::vector::{Point, distance};
use crate::surface::{Direction, Surface};

/// Grid points per unknown of the first search.
const GRID: usize = 4;

/// The best sets after the grid that the pattern search refines (and the solver verifies).
const REFINED: usize = 6;

/// The pattern search's first step and its last (unit-box coordinates).
const FIRST_STEP: f64 = 0.125;
const LAST_STEP: f64 = 1e-7;

/// One mixed set, ready to evaluate at unit-box coordinates `(s_a, s_a', s_c)`.
struct MixedSet {
    pair: Direction,
    /// `A`'s primitive; its poles are replaced by `D_k(c)` at each evaluation.
    a: LocalProblem,
    a_box: SearchBox,
    /// `B`'s rows, one per pole of `A` (homogeneous, unshifted).
    rows: Vec<LocalProblem>,
    c_box: SearchBox,
}

impl MixedSet {
    /// `S(ũ, ṽ)` with the unknowns at `s` (unit-box coordinates), or `None` where the knots
    /// are out of order or the point is not finite.
    fn point(&self, s: [f64; 3], scratch: &mut LocalProblem) -> Option<Point> {
        let b_local = self.rows[0].knots_at(&self.c_box, [s[2], 0.0, 0.0]);
        let a_local = self.a.knots_at(&self.a_box, [s[0], s[1], 0.0]);
        let ordered = |k: &[f64]| k.windows(2).all(|w| w[0] <= w[1]);
        if !ordered(&a_local) || !ordered(&b_local) {
            return None;
        }
        for (pole, row) in scratch.poles.iter_mut().zip(&self.rows) {
            *pole = row.homogeneous_point(&b_local);
        }
        let point = scratch.point(&a_local);
        point.iter().all(|x| x.is_finite()).then_some(point)
    }

    /// The nearest point from `start` by the pattern search (module docs), and its
    /// distance.
    fn refine(&self, start: [f64; 3], target: Point, scratch: &mut LocalProblem) -> (f64, Point) {
        let mut s = start;
        let Some(mut best) = self.point(s, scratch) else {
            return (f64::INFINITY, target);
        };
        let mut d = distance(best, target);
        let mut step = FIRST_STEP;
        while step >= LAST_STEP {
            let mut moved = false;
            for k in 0..3 {
                for sign in [-1.0, 1.0] {
                    let mut trial = s;
                    trial[k] = (trial[k] + sign * step).clamp(0.0, 1.0);
                    if trial[k] == s[k] {
                        continue;
                    }
                    if let Some(point) = self.point(trial, scratch) {
                        let e = distance(point, target);
                        if e < d {
                            (s, best, d, moved) = (trial, point, e, true);
                        }
                    }
                }
            }
            if !moved {
                step *= 0.5;
            }
        }
        (d, best)
    }
}

/// Every mixed set of both orientations at `(u, v)`.
fn mixed_sets(surface: &Surface, u: f64, v: f64, options: &SurfaceKnotOptions) -> Vec<MixedSet> {
    let keep = options.keep_domain;
    let mut sets = Vec::new();
    for pair in [Direction::U, Direction::V] {
        let single = pair.other();
        if !movable(surface, pair) || !movable(surface, single) {
            continue;
        }
        let (ta, tb) = (super::along(pair, u, v), super::along(single, u, v));
        let curve_a = iso_curve_along(surface, pair, u, v);
        let curve_b = iso_curve_along(surface, single, u, v);
        let net = Oriented { surface, pair };
        let b_problems: Vec<Side1> =
            direction_problems(&curve_b, tb, keep, false, options.mixed_direct);
        for a in direction_problems(&curve_a, ta, keep, true, false) {
            let pairs = unknown_sets(&a.local, 2, &curve_a, keep);
            for b in &b_problems {
                let rows = rows_of(net, &a, b, tb, [0.0; 3]);
                for m in singles(&b.local, &curve_b, keep) {
                    let Some(c_box) = rows[0].search_box(&[m], SEARCH_MARGIN, 0.0) else {
                        continue;
                    };
                    if c_box.admissible[0].1 <= c_box.admissible[0].0 {
                        continue;
                    }
                    for set in &pairs {
                        let Some(a_box) = a.local.search_box(set, SEARCH_MARGIN, 0.0) else {
                            continue;
                        };
                        if a_box.admissible.iter().any(|(lo, hi)| hi <= lo) {
                            continue;
                        }
                        sets.push(MixedSet {
                            pair,
                            a: a.local.clone(),
                            a_box,
                            rows: rows.clone(),
                            c_box: c_box.clone(),
                        });
                    }
                }
            }
        }
    }
    sets
}

/// The point nearest `target` that a mixed move reaches from `(u, v)` (module docs) and its
/// distance, verified by the mixed solver; `None` when no set has one.
pub(crate) fn nearest_mixed(
    surface: &Surface,
    u: f64,
    v: f64,
    target: Point,
    options: &SurfaceKnotOptions,
) -> Option<(f64, Point)> {
    let sets = mixed_sets(surface, u, v, options);
    // The grid's best point of every set.
    let mut starts: Vec<(f64, usize, [f64; 3])> = Vec::new();
    for (index, set) in sets.iter().enumerate() {
        let mut scratch = set.a.clone();
        let mut best: Option<(f64, [f64; 3])> = None;
        for i in 0..GRID * GRID * GRID {
            let s = [i % GRID, (i / GRID) % GRID, i / (GRID * GRID)]
                .map(|g| (g as f64 + 0.5) / GRID as f64);
            if let Some(point) = set.point(s, &mut scratch) {
                let d = distance(point, target);
                if best.is_none_or(|(b, _)| d < b) {
                    best = Some((d, s));
                }
            }
        }
        if let Some((d, s)) = best {
            starts.push((d, index, s));
        }
    }
    starts.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut found: Vec<(f64, Point, Direction)> = starts
        .iter()
        .take(REFINED)
        .map(|&(_, index, s)| {
            let set = &sets[index];
            let (d, point) = set.refine(s, target, &mut set.a.clone());
            (d, point, set.pair)
        })
        .collect();
    found.sort_by(|a, b| a.0.total_cmp(&b.0));
    found.into_iter().find_map(|(d, point, pair)| {
        let reached = d.is_finite() && !solve_mixed(surface, pair, u, v, point, options).is_empty();
        reached.then_some((d, point))
    })
}

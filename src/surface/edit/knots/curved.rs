//! Mixed moves whose pair direction has degree ≥ 4 (docs/method.md §46): the pair's primitive
//! has `q = p_A − 1 ≥ 3` poles beyond the first, so for a fixed `c` it reaches a curved patch,
//! not a plane, and there is no plane condition to solve first. The three unknowns are solved
//! together instead: with `N_k(a, a')` the numerators of `A`'s basis values (the pair's de Boor
//! triangle, common denominator `D_A`) and `(X_k − p W_k)(c)` those of the rows of `B`
//! (common denominator `D_B`), shifted by the target,
//!
//! ```text
//! F(a, a', c) = Σ_k N_k(a, a') · (X_k − p W_k)(c) = D_A D_B W (S(ũ, ṽ) − p) = 0,
//! ```
//!
//! three polynomial equations in three variables, built exactly as products of the two
//! directions' Bernstein forms (the pair's in the first two variables, `c` in the third) and
//! isolated by the certified subdivision of the curve families
//! ([`crate::shape::family::isolate`]: Bernstein exclusion, Krawczyk), each root refined by
//! Newton's method on `F`. `D_A, D_B, W > 0` on admissible knots, so the roots of `F` are
//! exactly the mixed moves of the set.

use crate::shape::family::isolate::{IsolationOptions, isolate, refine};
use crate::shape::family::local::{LocalProblem, SearchBox};
use crate::shape::family::roots::{SEARCH_MARGIN, TRIPLE_BOXES, admissible, disordered};
use crate::shape::family::tensor::{MAX_VARIABLES, Tensor};

/// One root of a curved mixed set: `A`'s local knots with the pair solved, `B`'s with `c`.
pub(crate) struct CurvedRoot {
    pub a_local: Vec<f64>,
    pub b_local: Vec<f64>,
}

/// `A`'s side of a curved mixed set: the pair's search box and the numerators `N_k` of the
/// basis values (scaled Bernstein basis, variables 0 and 1), shared by every `B` side.
pub(crate) struct PairBasis {
    search: SearchBox,
    numerators: Vec<Tensor>,
}

/// `B`'s side of a curved mixed set: the single unknown's search box and the rows'
/// numerators `(X_k − p W_k)(c)` (scaled Bernstein basis, variable 2, three components),
/// shared by every pair of `A`.
pub(crate) struct SingleRows {
    search: SearchBox,
    numerators: Vec<Tensor>,
}

/// [`PairBasis`] of `A`'s local problem `a` (its poles are not used) and the pair `set`;
/// `None` when a knot of the pair has no room.
pub(crate) fn pair_basis(a: &LocalProblem, set: &[usize]) -> Option<PairBasis> {
    let search = a.search_box(set, SEARCH_MARGIN, 0.0)?;
    if search.admissible.iter().any(|(lo, hi)| hi <= lo) {
        return None;
    }
    let q = a.degree;
    let numerators = (0..=q)
        .map(|k| {
            // The point whose only nonzero pole is the unit at `k` (de Boor is linear in the
            // homogeneous poles).
            let basis = LocalProblem {
                poles: (0..=q)
                    .map(|j| {
                        if j == k {
                            [1.0, 0.0, 0.0, 0.0]
                        } else {
                            [0.0; 4]
                        }
                    })
                    .collect(),
                ..a.clone()
            };
            basis
                .numerator(&search)
                .combine(&[1.0, 0.0, 0.0, 0.0])
                .scaled()
        })
        .collect();
    Some(PairBasis { search, numerators })
}

/// [`SingleRows`] of the rows `shifted` (`B`'s primitive for `A`'s poles, the target
/// subtracted: [`super::mixed::rows_of`]) with the unknown local knot `m`; `None` when it has
/// no room.
pub(crate) fn single_rows(shifted: &[LocalProblem], m: usize) -> Option<SingleRows> {
    let search = shifted[0].search_box(&[m], SEARCH_MARGIN, 0.0)?;
    if search.admissible[0].1 <= search.admissible[0].0 {
        return None;
    }
    let numerators = shifted
        .iter()
        .map(|row| {
            let numerator = row.numerator(&search);
            let coordinates: Vec<Tensor> = (0..3)
                .map(|c| {
                    let mut weights = [0.0; 4];
                    weights[c] = 1.0;
                    numerator.combine(&weights)
                })
                .collect();
            in_third_variable(Tensor::stack(&coordinates)).scaled()
        })
        .collect();
    Some(SingleRows { search, numerators })
}

/// Every root of the mixed system of `A`'s pair (`a` its local problem, `pair` its basis)
/// and `B`'s single unknown (`single`, built from the rows of `shifted`); `budget` boxes at
/// most (this set takes what it uses).
pub(crate) fn curved_roots(
    a: &LocalProblem,
    pair: &PairBasis,
    shifted: &[LocalProblem],
    single: &SingleRows,
    budget: &mut usize,
) -> Vec<CurvedRoot> {
    if *budget == 0 {
        return Vec::new();
    }
    let system = curved_system(pair, single);
    if system.coefficients.iter().any(|c| !c.is_finite()) {
        return Vec::new();
    }
    let options = IsolationOptions {
        max_boxes: TRIPLE_BOXES.min(*budget),
        ..IsolationOptions::default()
    };
    // Boxes where `A`'s neighbouring unknowns are out of order throughout hold no move.
    let outside = |lo: [f64; MAX_VARIABLES], width: [f64; MAX_VARIABLES]| {
        disordered(a, &pair.search, lo, width)
    };
    let isolation = isolate(&system, 3, options, &outside);
    *budget = budget.saturating_sub(isolation.boxes);
    if isolation.roots.is_empty() {
        return Vec::new();
    }
    let (c_lo, c_hi) = single.search.admissible[0];
    let m = single.search.unknowns[0];
    isolation
        .roots
        .iter()
        .filter_map(|root| {
            let s = refine(&system, 3, root.point);
            let a_local = admissible(a, &pair.search, a.knots_at(&pair.search, [s[0], s[1], 0.0]))?;
            let mut b_local = shifted[0].knots_at(&single.search, [s[2], 0.0, 0.0]);
            b_local[m] = b_local[m].clamp(c_lo, c_hi);
            Some(CurvedRoot { a_local, b_local })
        })
        .collect()
}

/// `F` (module docs) on the unit box of the pair's search (variables 0 and 1) times that of
/// the single unknown's (variable 2): `Σ_k N_k G_k`, ordinary Bernstein basis, three
/// components.
pub(crate) fn curved_system(pair: &PairBasis, single: &SingleRows) -> Tensor {
    let mut terms = pair
        .numerators
        .iter()
        .zip(&single.numerators)
        .map(|(n_k, g_k)| g_k.times(n_k));
    let first = terms.next().expect("q + 1 ≥ 1 rows");
    terms.fold(first, |sum, term| sum.plus(&term)).unscaled()
}

/// A tensor in the first variable only, as the same polynomial in the third (the storage is
/// the same: the other variables have degree 0).
fn in_third_variable(t: Tensor) -> Tensor {
    debug_assert_eq!(t.degrees[1..], [0, 0]);
    Tensor {
        degrees: [0, 0, t.degrees[0]],
        ..t
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shape::family::problems::unknown_sets;
    use crate::spline::KnotForm;
    use crate::surface::edit::knots::iso::iso_curve_along;
    use crate::surface::edit::knots::mixed::{Oriented, direction_problems, rows_of, singles};
    use crate::surface::{Direction, Surface, SurfaceLimits};

    /// The system's value at points of its box is `D_A D_B W (S − p)` up to the positive
    /// factor: its direction agrees with the point's offset from the target computed by de
    /// Boor alone (rows at `c`, then the pair's primitive on them).
    #[test]
    fn the_curved_system_points_where_de_boor_puts_the_point() {
        let points: Vec<Vec<[f64; 3]>> = (0..8)
            .map(|i| {
                (0..6)
                    .map(|j| {
                        [
                            i as f64,
                            j as f64 + 0.2 * i as f64,
                            ((i * 3 + j * 5) % 4) as f64 * 0.3,
                        ]
                    })
                    .collect()
            })
            .collect();
        let weights: Vec<Vec<f64>> = (0..8)
            .map(|i| (0..6).map(|j| 0.7 + ((i + j) % 3) as f64 * 0.4).collect())
            .collect();
        let surface = Surface::from_knot_forms(
            (4, 2),
            &points,
            (
                KnotForm::Flat(&[
                    0.0, 0.0, 0.0, 0.0, 0.0, 0.3, 0.55, 0.8, 1.0, 1.0, 1.0, 1.0, 1.0,
                ]),
                KnotForm::Flat(&[0.0, 0.0, 0.0, 0.3, 0.5, 0.8, 1.0, 1.0, 1.0]),
            ),
            Some(&weights),
            &SurfaceLimits::default(),
        )
        .unwrap();
        let (u, v) = (0.47, 0.62);
        let target = [3.1, 2.9, 0.4];
        let net = Oriented {
            surface: &surface,
            pair: Direction::U,
        };
        let curve_a = iso_curve_along(&surface, Direction::U, u, v);
        let curve_b = iso_curve_along(&surface, Direction::V, u, v);
        let mut compared = 0;
        for a in direction_problems(&curve_a, u, true, true, false) {
            assert_eq!(a.local.degree, 3);
            for b in direction_problems(&curve_b, v, true, false, true) {
                let shifted = rows_of(net, &a, &b, v, target);
                let rows = rows_of(net, &a, &b, v, [0.0; 3]);
                for m in singles(&b.local, &curve_b, true) {
                    for set in unknown_sets(&a.local, 2, &curve_a, true) {
                        let (Some(pair), Some(single)) =
                            (pair_basis(&a.local, &set), single_rows(&shifted, m))
                        else {
                            continue;
                        };
                        let system = curved_system(&pair, &single);
                        let (search_a, search_b) = (&pair.search, &single.search);
                        for s in [[0.2, 0.7, 0.4], [0.9, 0.1, 0.6], [0.5, 0.5, 0.05]] {
                            let a_knots = a.local.knots_at(search_a, s);
                            let b_knots = shifted[0].knots_at(search_b, [s[2], 0.0, 0.0]);
                            let poles: Vec<[f64; 4]> =
                                rows.iter().map(|r| r.homogeneous_point(&b_knots)).collect();
                            let point = LocalProblem {
                                poles,
                                ..a.local.clone()
                            }
                            .point(&a_knots);
                            let offset = [0, 1, 2].map(|c| point[c] - target[c]);
                            let mut f = [0.0; 3];
                            system.evaluate(s, &mut f);
                            let (nf, no) = (
                                f[0].hypot(f[1]).hypot(f[2]),
                                offset[0].hypot(offset[1]).hypot(offset[2]),
                            );
                            let cosine = (0..3).map(|c| f[c] * offset[c]).sum::<f64>() / (nf * no);
                            assert!(
                                cosine > 1.0 - 1e-9,
                                "m {m} set {set:?} s {s:?}: {f:?} vs {offset:?}"
                            );
                            compared += 1;
                        }
                    }
                }
            }
        }
        assert!(compared >= 30, "{compared}");
    }
}

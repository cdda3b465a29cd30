//! The real-curve corpus (tests/data/real_curves.json.gz: 625 curve forms from public CAD
//! models, degrees 1–12, spans down to 1e-9 of the domain) through every part of the spline
//! core that evaluates: points and derivatives (single and batch), closest points, knot
//! insertion, Bézier pieces, certified polylines and, on cubics, the shape solver with its
//! deviation measure. Every answer is checked against exact rational arithmetic
//! (tests/spline_core/exact.rs) or the exact evaluator's rounded values.

use std::sync::OnceLock;

use knotshape::shape::{ShapeQuery, SolveOptions, solve};
use knotshape::spline::{
    BatchEvaluator, CLOSEST_POINT_TOLERANCE, ClosestPointSearch, Curve, MAX_DEGREE,
};

use super::corpus::{self, RealCurve, split_mix};
use super::exact::{Exact, Input, Judge, Verdict, textbook};

/// Parameters per curve form at most (the hardest first, see [`RealCurve::hard_parameters`]).
const PARAMETERS_PER_CURVE: usize = 24;

/// Uniformly spaced points checked per form (`uniform_points_into`).
const UNIFORM_POINTS: usize = 5;

/// Rounding allowance of results built by convex combinations of control points (inserted
/// knots' control points, Bézier points, de Casteljau): `1e-12` of the size plus this many
/// `(p + 1) ε` of the largest control point coordinate. Each of the `p` levels of de Boor's
/// algorithm (or of blossoming) rounds about `2 ε` of the magnitude, and the test's own
/// de Casteljau as much again.
const CONVEX_ROUNDING: f64 = 8.0;

/// The corpus, read once per test binary.
fn curves() -> &'static [RealCurve] {
    static CURVES: OnceLock<Vec<RealCurve>> = OnceLock::new();
    CURVES.get_or_init(corpus::load)
}

/// Failures collected over the corpus; the test fails listing the first few.
#[derive(Default)]
struct Failures(Vec<String>);

impl Failures {
    fn check(&mut self, ok: bool, what: impl FnOnce() -> String) {
        if !ok {
            self.0.push(what());
        }
    }

    fn assert_none(&self, test: &str) {
        assert!(
            self.0.is_empty(),
            "{test}: {} failures, the first: {:#?}",
            self.0.len(),
            &self.0[..self.0.len().min(8)]
        );
    }
}

/// The worst error of one kind over the corpus, relative to the rule and to the scale.
#[derive(Default)]
struct Worst {
    ratio: f64,
    relative: f64,
    at: String,
}

impl Worst {
    fn add(&mut self, verdict: &Verdict, at: impl FnOnce() -> String) {
        if verdict.ratio() > self.ratio {
            self.ratio = verdict.ratio();
            self.at = at();
        }
        self.relative = self.relative.max(verdict.relative());
    }
}

/// `1e-12` of the size plus [`CONVEX_ROUNDING`] `(p + 1) ε` of the largest coordinate.
fn convex_tolerance(real: &RealCurve, judge: &Judge) -> f64 {
    let magnitude = real
        .poles
        .iter()
        .flatten()
        .fold(0.0f64, |m, x| m.max(x.abs()));
    1e-12 * judge.size() + CONVEX_ROUNDING * (real.degree + 1) as f64 * f64::EPSILON * magnitude
}

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|c| (a[c] - b[c]).powi(2)).sum::<f64>().sqrt()
}

fn input_of(curve: &Curve) -> Input {
    Input {
        degree: curve.degree(),
        knots: curve.knots().to_vec(),
        points: curve.control_points().to_vec(),
        weights: curve.weights().map(<[f64]>::to_vec),
    }
}

/// Points and first and second derivatives at the hardest parameters, by `Curve::point`,
/// `Curve::derivatives`, `BatchEvaluator::points_into`, `derivatives_into` and
/// `uniform_points_into`, all within the rule of tests/spline_core/exact.rs (the largest of
/// 1e-12 of the size, 4 × the textbook de Boor's error, the rounding floor
/// `(p + 1) 2^-52 M_k` and de Boor's own running error bound).
#[test]
fn evaluation_is_as_exact_as_de_boor() {
    let mut failures = Failures::default();
    let mut worst: [Worst; 3] = Default::default();
    let mut count = 0;
    for (index, real) in curves().iter().enumerate() {
        let curve = real.curve();
        let judge = Judge::new(&real.input());
        let parameters = real.hard_parameters(PARAMETERS_PER_CURVE, index as u64);
        let evaluator = BatchEvaluator::new(&curve);
        let n = parameters.len();
        let mut batch_points = vec![[f64::NAN; 3]; n];
        evaluator
            .points_into(&parameters, &mut batch_points)
            .unwrap();
        let mut batch = vec![[f64::NAN; 3]; 3 * n];
        evaluator
            .derivatives_into(&parameters, 2, &mut batch)
            .unwrap();
        let mut judge_all = |exact: &Exact, t: f64, path: &str, values: &[[f64; 3]]| {
            for (k, &value) in values.iter().enumerate() {
                let verdict = exact.judge(k, value);
                count += 1;
                worst[k].add(&verdict, || format!("{} at {t:e} ({path})", real.id));
                failures.check(verdict.passes(), || {
                    format!(
                        "{} (degree {}) {path} order {k} at {t:e}: error {:e} > {:e} (textbook de Boor's {:e})",
                        real.id, real.degree, verdict.error, verdict.allowed, verdict.textbook
                    )
                });
            }
        };
        for (i, &t) in parameters.iter().enumerate() {
            let exact = judge.at(t, 2);
            let mut single = [[f64::NAN; 3]; 3];
            curve.derivatives(t, &mut single).unwrap();
            judge_all(&exact, t, "Curve::derivatives", &single);
            judge_all(&exact, t, "Curve::point", &[curve.point(t).unwrap()]);
            judge_all(&exact, t, "points_into", &[batch_points[i]]);
            judge_all(
                &exact,
                t,
                "derivatives_into",
                &[batch[i], batch[n + i], batch[2 * n + i]],
            );
        }
        let mut uniform = [[f64::NAN; 3]; UNIFORM_POINTS];
        evaluator.uniform_points_into(&mut uniform);
        for (t, value) in curve.uniform_parameters(UNIFORM_POINTS).zip(uniform) {
            judge_all(&judge.at(t, 0), t, "uniform_points_into", &[value]);
        }
    }
    for (k, w) in worst.iter().enumerate() {
        eprintln!(
            "order {k}: worst error {:.2e} of what the rule allows ({}), {:.2e} of the scale; {count} values",
            w.ratio, w.at, w.relative
        );
    }
    failures.assert_none("evaluation");
}

/// Closest points to queries on the curve, just off it and far from it: the answer's point is
/// the curve's at the answer's parameter, and its distance is at most the distance to the
/// curve at any of the hardest parameters and at the ends and middle of up to
/// [`SAMPLED_SPANS`] spans (within the search's tie tolerance).
#[test]
fn closest_points_are_never_farther_than_any_sample() {
    /// Spans sampled per curve at most (spread evenly).
    const SAMPLED_SPANS: usize = 32;
    /// Curve points (the hardest parameters first) that queries are made from, each giving a
    /// query on the curve, one `1e-9` of the size off it and one `1e-3` off it.
    const QUERY_BASES: usize = 5;
    let mut failures = Failures::default();
    let mut queries = 0;
    for (index, real) in curves().iter().enumerate() {
        let curve = real.curve();
        let judge = Judge::new(&real.input());
        let size = judge.size();
        let search = ClosestPointSearch::new(&curve, None).unwrap();
        // Samples: the hardest parameters and every span's ends and middle, by the textbook
        // de Boor (tests/spline_core/exact.rs) in f64.
        let mut samples: Vec<f64> = real.hard_parameters(PARAMETERS_PER_CURVE, index as u64);
        let p = real.degree;
        let spans: Vec<usize> = (p..real.poles.len())
            .filter(|&m| real.knots[m] < real.knots[m + 1])
            .collect();
        for &m in spans.iter().step_by(spans.len().div_ceil(SAMPLED_SPANS)) {
            let (a, b) = (real.knots[m], real.knots[m + 1]);
            samples.extend([a, 0.5 * (a + b), b]);
        }
        let input = real.input();
        let sample_points: Vec<[f64; 3]> = samples
            .iter()
            .map(|&t| textbook(&input, t, 0).values[0])
            .collect();
        let mut state = index as u64;
        let mut direction = || {
            let mut v = [0.0; 3];
            for c in v.iter_mut().take(real.poles[0].len()) {
                state = split_mix(state);
                *c = (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
            }
            let length = distance(v, [0.0; 3]).max(1e-300);
            v.map(|x| x / length)
        };
        let mut query_points = Vec::new();
        for &base in sample_points.iter().take(QUERY_BASES) {
            query_points.push(base);
            let d = direction();
            query_points.push(std::array::from_fn(|c| base[c] + 1e-3 * size * d[c]));
            let d = direction();
            query_points.push(std::array::from_fn(|c| base[c] + 1e-9 * size * d[c]));
        }
        let d = direction();
        query_points.push(std::array::from_fn(|c| {
            sample_points[0][c] + 3.0 * size * d[c]
        }));
        for q in query_points {
            queries += 1;
            let found = search.closest(q);
            let exact = judge.at(found.parameter, 0);
            let verdict = exact.judge(0, found.point);
            failures.check(verdict.passes(), || {
                format!(
                    "{}: closest point {:?} is not s({}): {verdict:?}",
                    real.id, found.point, found.parameter
                )
            });
            failures.check(
                (distance(found.point, q) - found.distance).abs()
                    <= 1e-15 * (size + found.distance),
                || format!("{}: distance {} != |point - q|", real.id, found.distance),
            );
            let nearest_sample = sample_points
                .iter()
                .map(|&s| distance(s, q))
                .fold(f64::INFINITY, f64::min);
            let slack = CLOSEST_POINT_TOLERANCE * (size + nearest_sample) + verdict.allowed;
            failures.check(found.distance <= nearest_sample + slack, || {
                format!(
                    "{}: query {q:?} at distance {} but a sample is at {nearest_sample}",
                    real.id, found.distance
                )
            });
        }
    }
    eprintln!("{queries} closest-point queries");
    failures.assert_none("closest points");
}

/// Inserting knots (in the shortest spans, next to knots, at random) leaves every curve as it
/// was: the refined curve, evaluated exactly, equals the original, evaluated exactly, at the
/// hardest parameters.
#[test]
fn knot_insertion_keeps_every_curve() {
    let mut failures = Failures::default();
    for (index, real) in curves().iter().enumerate() {
        let curve = real.curve();
        let judge = Judge::new(&real.input());
        let p = real.degree;
        let (lo, hi) = real.domain();
        // The middle of each of the three shortest spans, a quarter into the first span, and
        // a random value: each at most once, so no multiplicity exceeds p.
        let mut spans: Vec<(f64, f64)> = (p..real.poles.len())
            .map(|m| (real.knots[m], real.knots[m + 1]))
            .filter(|(a, b)| a < b)
            .collect();
        spans.sort_by(|x, y| (x.1 - x.0).total_cmp(&(y.1 - y.0)));
        let mut values: Vec<f64> = spans
            .iter()
            .take(3)
            .map(|(a, b)| a + 0.5 * (b - a))
            .collect();
        values.push(lo + 0.25 * (spans[0].1 - spans[0].0).min(hi - lo));
        let state = split_mix(index as u64 ^ 0xABCD);
        values.push(lo + (state >> 11) as f64 / (1u64 << 53) as f64 * (hi - lo));
        values.retain(|&v| real.knots.iter().filter(|&&u| u == v).count() < p);
        values.sort_by(f64::total_cmp);
        values.dedup();
        let refined = curve.insert_knots(&values, usize::MAX).unwrap();
        let refined_judge = Judge::new(&input_of(&refined));
        let tolerance = convex_tolerance(real, &judge);
        for t in real.hard_parameters(PARAMETERS_PER_CURVE, index as u64) {
            // At an inserted value the refined curve takes the span on its right, as the
            // original does: the same point.
            let before = judge.at(t, 0).value(0);
            let after = refined_judge.at(t, 0).value(0);
            let gap = distance(before, after);
            failures.check(gap <= tolerance, || {
                format!(
                    "{}: inserting {values:?} moves s({t}) by {gap:e} (allowed {tolerance:e})",
                    real.id
                )
            });
        }
    }
    failures.assert_none("knot insertion");
}

/// Each Bézier piece, evaluated by the test's own de Casteljau, is the curve on its span (the
/// exact curve at the rounded parameter), and the pieces are the non-empty spans in order.
#[test]
fn bezier_pieces_are_the_curve() {
    let mut failures = Failures::default();
    for real in curves() {
        let curve = real.curve();
        let judge = Judge::new(&real.input());
        let tolerance = convex_tolerance(real, &judge);
        let p = real.degree;
        let spans: Vec<(f64, f64)> = (p..real.poles.len())
            .map(|m| (real.knots[m], real.knots[m + 1]))
            .filter(|(a, b)| a < b)
            .collect();
        let pieces: Vec<_> = curve.bezier_pieces().collect();
        failures.check(
            pieces
                .iter()
                .map(|piece| piece.domain)
                .eq(spans.iter().copied()),
            || format!("{}: pieces do not follow the spans", real.id),
        );
        for piece in &pieces {
            let (a, b) = piece.domain;
            let jumps = b < real.domain().1 && real.knots.iter().filter(|&&u| u == b).count() > p;
            for fraction in [0.0, 0.25, 0.5, 1.0] {
                if fraction == 1.0 && jumps {
                    continue;
                }
                let u = if fraction == 1.0 {
                    b
                } else {
                    a + fraction * (b - a)
                };
                let s = (u - a) / (b - a);
                let found = de_casteljau(piece.homogeneous(), s);
                let expected = judge.at(u, 0).value(0);
                let gap = distance(found, expected);
                failures.check(gap <= tolerance, || {
                    format!(
                        "{}: piece {:?} at u = {u}: {gap:e} off (allowed {tolerance:e})",
                        real.id, piece.domain
                    )
                });
            }
        }
    }
    failures.assert_none("Bézier pieces");
}

/// De Casteljau's algorithm on homogeneous points, projected.
fn de_casteljau(points: &[[f64; 4]], s: f64) -> [f64; 3] {
    let mut work = points.to_vec();
    for level in 1..work.len() {
        for i in 0..work.len() - level {
            let next = work[i + 1];
            for (value, later) in work[i].iter_mut().zip(next) {
                *value = (1.0 - s) * *value + s * later;
            }
        }
    }
    let [x, y, z, w] = work[0];
    [x / w, y / w, z / w]
}

/// The distance from `q` to the segment `[a, b]` (written here, independent of the core's).
fn to_segment(q: [f64; 3], a: [f64; 3], b: [f64; 3]) -> f64 {
    let ab: [f64; 3] = std::array::from_fn(|c| b[c] - a[c]);
    let aq: [f64; 3] = std::array::from_fn(|c| q[c] - a[c]);
    let length = (0..3).map(|c| ab[c] * ab[c]).sum::<f64>();
    let along = if length > 0.0 {
        ((0..3).map(|c| aq[c] * ab[c]).sum::<f64>() / length).clamp(0.0, 1.0)
    } else {
        0.0
    };
    distance(q, std::array::from_fn(|c| a[c] + along * ab[c]))
}

/// Certified polylines at `1e-4` of each curve's size: the parameters are increasing, hold
/// every knot of the domain, their points (by the batch evaluator, as the service computes
/// them) lie on the curve within the rule, and the curve between two vertices stays within
/// the tolerance of their segment (both checked on up to [`CHECKED`] segments per curve).
#[test]
fn certified_polylines_stay_within_the_tolerance() {
    /// Vertices judged exactly and segments sampled per curve at most (spread evenly).
    const CHECKED: usize = 40;
    let mut failures = Failures::default();
    let mut vertices = 0;
    for real in curves() {
        let curve = real.curve();
        let judge = Judge::new(&real.input());
        let tolerance = 1e-4 * judge.size().max(1e-300);
        let Ok(parameters) = curve.tessellate(tolerance, 1_000_000) else {
            let discontinuous = !curve.jump_knots().is_empty();
            failures.check(discontinuous, || {
                format!("{}: no polyline at {tolerance:e}", real.id)
            });
            continue;
        };
        vertices += parameters.len();
        let input = real.input();
        let (lo, hi) = real.domain();
        failures.check(
            parameters.first() == Some(&lo)
                && parameters.last() == Some(&hi)
                && parameters.windows(2).all(|w| w[0] < w[1]),
            || format!("{}: parameters not increasing from end to end", real.id),
        );
        failures.check(
            real.knots
                .iter()
                .filter(|&&u| lo <= u && u <= hi)
                .all(|u| parameters.binary_search_by(|x| x.total_cmp(u)).is_ok()),
            || format!("{}: a knot is missing from the polyline", real.id),
        );
        let mut points = vec![[0.0; 3]; parameters.len()];
        BatchEvaluator::new(&curve)
            .points_into(&parameters, &mut points)
            .unwrap();
        let step = (parameters.len() / CHECKED).max(1);
        for i in (0..parameters.len() - 1).step_by(step) {
            let (a, b) = (parameters[i], parameters[i + 1]);
            let verdict = judge.at(a, 0).judge(0, points[i]);
            failures.check(verdict.passes(), || {
                format!("{}: vertex at {a} off the curve: {verdict:?}", real.id)
            });
            for fraction in [0.25, 0.5, 0.75] {
                // The textbook de Boor suffices here: its error is far below the tolerance.
                let u = a + fraction * (b - a);
                let on_curve = textbook(&input, u, 0).values[0];
                let gap = to_segment(on_curve, points[i], points[i + 1]);
                failures.check(gap <= tolerance * (1.0 + 1e-9), || {
                    format!(
                        "{}: s({u}) is {gap:e} from its segment (tolerance {tolerance:e})",
                        real.id
                    )
                });
            }
        }
    }
    eprintln!("{vertices} polyline vertices");
    failures.assert_none("certified polylines");
}

/// On the cubics, moving `s(t)` a little towards a control point: every solution's curve
/// (exactly evaluated) passes through the target at `t`, its reported point is that curve's,
/// and its measured deviation is at least the exact distance between the old and the new
/// curve at sampled parameters.
#[test]
fn cubics_reach_their_targets() {
    let mut failures = Failures::default();
    let mut solutions = 0;
    let mut cubics = 0;
    for (index, real) in curves().iter().enumerate() {
        if real.degree != 3 {
            continue;
        }
        cubics += 1;
        let curve = real.curve();
        let judge = Judge::new(&real.input());
        let size = judge.size();
        let (lo, hi) = real.domain();
        let parameters: Vec<f64> = real
            .hard_parameters(PARAMETERS_PER_CURVE, index as u64)
            .into_iter()
            .filter(|&t| lo < t && t < hi)
            .step_by(5)
            .take(4)
            .collect();
        for t in parameters {
            let here = judge.at(t, 0).value(0);
            let span = (3..real.poles.len())
                .find(|&m| real.knots[m] <= t && t < real.knots[m + 1])
                .unwrap();
            let pole = curve.control_points()[span - 1];
            let target: Vec<f64> = (0..real.poles[0].len())
                .map(|c| here[c] + 1e-3 * (pole[c] - here[c]))
                .collect();
            let target3 = [target[0], target[1], target.get(2).copied().unwrap_or(0.0)];
            let outcome = solve(
                &ShapeQuery::new(&curve, t),
                &target,
                SolveOptions {
                    measure_deviation: true,
                },
            )
            .unwrap();
            for solution in &outcome.solutions {
                solutions += 1;
                let moved = curve.with_full_knots(solution.knots.clone()).unwrap();
                let moved_judge = Judge::new(&input_of(&moved));
                let reached = moved_judge.at(t, 0);
                let miss = distance(reached.value(0), target3);
                failures.check(miss <= 1e-9 * size, || {
                    format!(
                        "{}: {:?} misses the target at {t} by {miss:e}",
                        real.id, solution.pair
                    )
                });
                let verdict = reached.judge(0, solution.point);
                failures.check(verdict.passes(), || {
                    format!(
                        "{}: solution point is not the new curve's: {verdict:?}",
                        real.id
                    )
                });
                let Some(deviation) = solution.max_deviation else {
                    failures.check(false, || format!("{}: deviation not measured", real.id));
                    continue;
                };
                let (a, b) = solution.affected_domain;
                for k in 0..=16 {
                    let u = (a + (b - a) * f64::from(k) / 16.0).clamp(lo, hi);
                    let gap = distance(judge.at(u, 0).value(0), moved_judge.at(u, 0).value(0));
                    failures.check(gap <= deviation * (1.0 + 1e-10) + 1e-12 * size, || {
                        format!(
                            "{}: curves {gap:e} apart at {u}, deviation {deviation:e}",
                            real.id
                        )
                    });
                }
            }
        }
    }
    eprintln!("{cubics} cubics, {solutions} solutions");
    assert!(solutions > 50, "too few solutions to test: {solutions}");
    failures.assert_none("solve");
}

/// The corpus holds what the tests above rely on: every degree from 1 to 12, rational and
/// non-rational, 2D and 3D, periodic (unwrapped) forms, and spans below 1e-8 of the domain.
#[test]
fn the_corpus_holds_the_hard_cases() {
    let curves = curves();
    assert_eq!(curves.len(), 625);
    for degree in 1..=12 {
        assert!(curves.iter().any(|c| c.degree == degree), "degree {degree}");
    }
    assert!(curves.iter().all(|c| c.degree <= MAX_DEGREE));
    assert!(curves.iter().any(|c| c.weights.is_some()));
    assert!(curves.iter().any(|c| c.poles[0].len() == 2));
    assert!(curves.iter().any(|c| c.poles[0].len() == 3));
    assert_eq!(curves.iter().filter(|c| c.periodic).count(), 5);
    let shortest = curves
        .iter()
        .map(|c| {
            let (lo, hi) = c.domain();
            c.knots
                .windows(2)
                .filter(|w| w[0] < w[1] && lo <= w[0] && w[1] <= hi)
                .map(|w| (w[1] - w[0]) / (hi - lo))
                .fold(f64::INFINITY, f64::min)
        })
        .fold(f64::INFINITY, f64::min);
    assert!(shortest < 1e-8, "{shortest}");
}

//! The envelope of moving a run of equal knots (MATH.md §2): the moved curve touches the
//! envelope at the moved value `τ`, with a common tangent.

use knotshape::spline::vector::{cross, norm};
use knotshape::spline::{Curve, CurveLimits, KnotRun};
use proptest::collection::vec;
use proptest::prelude::*;

use super::config;
use super::reference::{P3, Reference};

/// Contact of the moved curve and the envelope at `τ`, relative to the point scale.
const CONTACT_TOL: f64 = 1e-9;
/// Tangency: `|s' × h'| <= TANGENT_TOL · |s'| |h'|` (the sine of the angle between them).
const TANGENT_TOL: f64 = 1e-9;

/// A curve with a deliberately placed interior run of multiplicity `m`, and a value `τ` for it.
#[derive(Debug, Clone)]
struct EnvelopeCase {
    degree: usize,
    control_points: Vec<Vec<f64>>,
    weights: Option<Vec<f64>>,
    /// The full knot vector.
    full: Vec<f64>,
    trimmed: bool,
    /// Full index of the run's first knot, and its multiplicity.
    run_start: usize,
    multiplicity: usize,
    /// Which knot of the run the caller names (`0..m`).
    run_offset: usize,
    /// Where in the run's range `τ` lies, as a fraction.
    tau_fraction: f64,
}

impl EnvelopeCase {
    fn curve(&self) -> Curve {
        let knots = if self.trimmed {
            &self.full[1..self.full.len() - 1]
        } else {
            &self.full[..]
        };
        Curve::new(
            self.degree,
            &self.control_points,
            knots,
            self.weights.as_deref(),
            &CurveLimits::default(),
        )
        .unwrap_or_else(|e| panic!("generated curve rejected: {e}"))
    }

    /// The reference curve of degree `degree` over `knots`, with this case's control points.
    fn reference(&self, degree: usize, knots: Vec<f64>) -> Reference {
        Reference {
            degree,
            knots,
            points: self
                .control_points
                .iter()
                .map(|c| [c[0], c[1], c.get(2).copied().unwrap_or(0.0)])
                .collect(),
            weights: self.weights.clone(),
        }
    }
}

/// Raw parts of an envelope case, before assembly.
type Parts = (
    (usize, usize, bool, bool, bool),
    (Vec<usize>, Vec<usize>),
    Vec<f64>,
    Vec<f64>,
    Vec<f64>,
    (usize, f64),
);

/// Assembles the full knot vector: `p + 1` start knots (clamped: equal), the interior runs
/// `before`, the run of `m`, the runs `after` (distinct values, increasing), `p + 1` end knots.
fn assemble(parts: Parts, three_d: bool, control: Vec<f64>) -> EnvelopeCase {
    let (
        (p, m, clamped, trimmed, rational),
        (before, after),
        gaps,
        end_gaps,
        weights,
        (run_offset, tau_fraction),
    ) = parts;
    let mut full = Vec::new();
    let mut value = 0.0;
    for j in 0..=p {
        if j > 0 && !clamped {
            value += end_gaps[j - 1];
        }
        full.push(value);
    }
    let runs: Vec<usize> = before
        .iter()
        .copied()
        .chain([m])
        .chain(after.iter().copied())
        .collect();
    for (r, &count) in runs.iter().enumerate() {
        value += gaps[r];
        full.extend(std::iter::repeat_n(value, count));
    }
    value += gaps[runs.len()];
    for j in 0..=p {
        if j > 0 && !clamped {
            value += end_gaps[p + j - 1];
        }
        full.push(value);
    }
    let count = full.len() - p - 1;
    let dimension = if three_d { 3 } else { 2 };
    EnvelopeCase {
        degree: p,
        // A helix-like base polygon plus noise: shrinking the noise never makes points coincide.
        control_points: control
            .chunks(3)
            .take(count)
            .enumerate()
            .map(|(j, c)| {
                let angle = j as f64;
                let base = [4.0 * angle.cos(), 4.0 * angle.sin(), angle];
                (0..dimension).map(|x| base[x] + c[x]).collect()
            })
            .collect(),
        weights: rational.then(|| weights[..count].to_vec()),
        full,
        trimmed,
        run_start: p + 1 + before.iter().sum::<usize>(),
        multiplicity: m,
        run_offset: run_offset % m,
        tau_fraction,
    }
}

/// Degree 2..=6, a run of multiplicity `1..=p-1` with up to three other interior runs (of
/// multiplicity `1..=p`) on each side, clamped or not, rational or not, 2D or 3D, full or
/// trimmed knots; `τ` anywhere in the run's range, its ends included.
fn envelope_case() -> impl Strategy<Value = EnvelopeCase> {
    (2usize..=6)
        .prop_flat_map(|p| (Just(p), 1..p, any::<bool>(), any::<bool>(), any::<bool>()))
        .prop_flat_map(|(p, m, clamped, trimmed, rational)| {
            let runs = (vec(1..=p, 0..=3), vec(1..=p, 0..=3));
            (
                Just((p, m, clamped, trimmed, rational)),
                runs,
                vec(0.1..1.0f64, 8),
                vec(prop_oneof![3 => 0.1..1.0f64, 1 => Just(0.0)], 2 * p),
                vec(0.2..5.0f64, 64),
                (
                    0usize..6,
                    prop_oneof![1 => Just(0.0), 1 => Just(1.0), 4 => 0.0..=1.0f64],
                ),
                any::<bool>(),
                vec(-1.0..1.0f64, 3 * 64),
            )
        })
        .prop_map(|(a, b, c, d, e, f, three_d, control)| {
            assemble((a, b, c, d, e, f), three_d, control)
        })
}

/// The sine of the angle between `a` and `b`.
fn sine(a: P3, b: P3) -> f64 {
    norm(cross(a, b)) / (norm(a) * norm(b))
}

proptest! {
    #![proptest_config(config())]

    /// `knot_run` finds the run from any of its knots (caller's convention), and the moved curve
    /// `s(u; τ)` touches the envelope `h` at `u = τ` with a common tangent — checked on the
    /// curves the code builds (`with_run_moved`, `envelope`) and, independently, on reference
    /// curves built here from the knot vectors the theorem names.
    #[test]
    fn moved_curve_touches_envelope(case in envelope_case()) {
        let curve = case.curve();
        let (p, m, i) = (case.degree, case.multiplicity, case.run_start);
        let caller_index = i + case.run_offset - usize::from(case.trimmed);
        let run = curve.knot_run(caller_index).unwrap();
        let u = &case.full;
        prop_assert_eq!(run, KnotRun { start: i, multiplicity: m, range: (u[i - 1], u[i + m]) });

        // Clamped: the interpolation can round one ulp past the range's end.
        let tau = (run.range.0 + case.tau_fraction * (run.range.1 - run.range.0)).min(run.range.1);
        let moved = curve.with_run_moved(&run, tau).unwrap();
        let envelope = curve.envelope(&run);
        prop_assert_eq!(envelope.degree(), p - m);
        prop_assert!(moved.contains_parameter(tau) && envelope.contains_parameter(tau));

        let mut moved_knots = u.clone();
        moved_knots[i..i + m].fill(tau);
        let envelope_knots: Vec<f64> = u[..i].iter().chain(&u[i + m..]).copied().collect();
        let moved_reference = case.reference(p, moved_knots);
        let envelope_reference = case.reference(p - m, envelope_knots);
        let scale = moved_reference.point_scale();

        let mut s = [[0.0; 3]; 2];
        let mut h = [[0.0; 3]; 2];
        moved.derivatives(tau, &mut s).unwrap();
        envelope.derivatives(tau, &mut h).unwrap();
        let s_ref = moved_reference.derivatives(tau, 1);
        let h_ref = envelope_reference.derivatives(tau, 1);
        // The code's curves are the reference's curves (points and first derivatives).
        for (what, code, reference) in [("moved curve", s, &s_ref), ("envelope", h, &h_ref)] {
            for k in 0..2 {
                let tol = CONTACT_TOL * scale * if k == 0 { 1.0 } else { norm(reference[1]) };
                for c in 0..3 {
                    prop_assert!((code[k][c] - reference[k][c]).abs() <= tol,
                        "{what}: derivative {k} is {:?}, the reference's {:?}", code[k], reference[k]);
                }
            }
        }
        // Contact with a common tangent, on the side the moved curve is evaluated from: the
        // right, except at the right end of its domain (limit from the left). The envelope's
        // domain reaches further, so there its limit from the left is the one that touches:
        // when τ merges with the knots at the domain's end, the envelope can have a corner or
        // a jump at τ.
        let h_side = if tau == moved.domain().1 {
            let left = envelope_reference.derivatives_from_left(tau, 1);
            [left[0], left[1]]
        } else {
            h
        };
        for c in 0..3 {
            prop_assert!((s[0][c] - h_side[0][c]).abs() <= CONTACT_TOL * scale,
                "s(τ) = {:?} but h(τ) = {:?} at τ = {tau}", s[0], h_side[0]);
        }
        prop_assert!(sine(s[1], h_side[1]) <= TANGENT_TOL,
            "tangents {:?} and {:?} not parallel at τ = {tau}", s[1], h_side[1]);
    }
}

/// Found by the property above: a quartic whose triple knot moves onto the end of the domain,
/// where it merges with a double knot (multiplicity 5 = p + 1). The moved curve ends at `d_4`
/// (limit from the left); the envelope, of degree 1 and with a double knot at τ, jumps there: its
/// limit from the left is the contact point `d_4`, its value (span on the right) is `d_5`.
#[test]
fn contact_at_the_domain_end_is_the_limit_from_the_left() {
    let control_points: Vec<Vec<f64>> = (0..8)
        .map(|j| {
            let angle = f64::from(j);
            vec![4.0 * angle.cos(), 4.0 * angle.sin()]
        })
        .collect();
    let knots = [
        0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.5, 0.5, 0.6, 0.6, 0.7, 0.8, 0.9,
    ];
    let curve = Curve::new(4, &control_points, &knots, None, &CurveLimits::default()).unwrap();
    let run = curve.knot_run(6).unwrap();
    assert_eq!(
        run,
        KnotRun {
            start: 5,
            multiplicity: 3,
            range: (0.4, 0.6)
        }
    );
    let moved = curve.with_run_moved(&run, 0.6).unwrap();
    assert_eq!(moved.domain(), (0.4, 0.6));
    let envelope = curve.envelope(&run);
    assert_eq!(
        envelope.knots(),
        &[0.0, 0.1, 0.2, 0.3, 0.4, 0.6, 0.6, 0.7, 0.8, 0.9]
    );
    let d = |j: usize| [control_points[j][0], control_points[j][1], 0.0];
    let reference = Reference {
        degree: 1,
        knots: envelope.knots().to_vec(),
        points: (0..8).map(d).collect(),
        weights: None,
    };
    let end = moved.point(0.6).unwrap();
    let left = reference.derivatives_from_left(0.6, 0)[0];
    let right = envelope.point(0.6).unwrap();
    for c in 0..3 {
        assert!((end[c] - d(4)[c]).abs() <= CONTACT_TOL);
        assert!((left[c] - d(4)[c]).abs() <= CONTACT_TOL);
        assert!((right[c] - d(5)[c]).abs() <= CONTACT_TOL);
    }
}

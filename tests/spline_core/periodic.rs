//! Periodic curves in Open CASCADE's form and the multiplicities form: evaluation against
//! Open CASCADE's own (tests/data/interop/periodic_occt.json, made with OCP by
//! make_periodic_occt.py there) and against the unwrapped forms of real periodic curves
//! (real_periodic_curves.json); insertion, Bézier pieces and the window (cut open, edited,
//! written back) against evaluation of the curve before.

use knotshape::spline::{Curve, CurveLimits, KnotConvention, KnotForm, Point};
use proptest::prelude::*;
use serde_json::Value;

use crate::reference::Reference;

/// The JSON of a file under tests/data/interop.
fn data(name: &str) -> Value {
    let path = format!("{}/tests/data/interop/{name}", env!("CARGO_MANIFEST_DIR"));
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn numbers(value: &Value) -> Vec<f64> {
    value
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect()
}

fn points(value: &Value) -> Vec<Vec<f64>> {
    value.as_array().unwrap().iter().map(numbers).collect()
}

/// A periodic curve from a JSON curve object in the periodic form.
fn periodic_curve(curve: &Value) -> Curve {
    let multiplicities: Vec<usize> = curve["multiplicities"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| m.as_u64().unwrap() as usize)
        .collect();
    let weights = curve.get("weights").map(numbers);
    Curve::from_knot_form(
        curve["degree"].as_u64().unwrap() as usize,
        &points(&curve["control_points"]),
        KnotForm::Periodic {
            knots: &numbers(&curve["knots"]),
            multiplicities: &multiplicities,
        },
        weights.as_deref(),
        &CurveLimits::default(),
    )
    .unwrap()
}

/// The largest absolute control-point coordinate (the scale of roundoff).
fn scale(curve: &Curve) -> f64 {
    curve
        .control_points()
        .iter()
        .flatten()
        .fold(1.0f64, |m, v| m.max(v.abs()))
}

fn distance(a: Point, b: &[f64]) -> f64 {
    a.iter()
        .zip(b.iter().chain(std::iter::repeat(&0.0)))
        .map(|(x, y)| (x - y).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// The point at any parameter (reduced into the period first).
fn point(curve: &Curve, t: f64) -> Point {
    curve.point(curve.snap_to_domain(t).unwrap()).unwrap()
}

#[test]
fn periodic_curves_evaluate_as_open_cascade_evaluates_them() {
    let cases = data("periodic_occt.json");
    let mut checked = 0;
    for case in cases["cases"].as_array().unwrap() {
        let curve = periodic_curve(&case["curve"]);
        assert!(curve.is_periodic());
        let tolerance = 1e-11 * scale(&curve);
        let parameters = numbers(&case["parameters"]);
        let expected = points(&case["points"]);
        let expected_derivatives = points(&case["first_derivatives"]);
        for ((&t, p), d) in parameters.iter().zip(&expected).zip(&expected_derivatives) {
            let u = curve.snap_to_domain(t).unwrap();
            let mut out = [[0.0; 3]; 2];
            curve.derivatives(u, &mut out).unwrap();
            assert!(
                distance(out[0], p) <= tolerance,
                "{case} at {t}: {:?}",
                out[0]
            );
            let derivative_scale = d.iter().fold(scale(&curve), |m, v| m.max(v.abs()));
            assert!(
                distance(out[1], d) <= 1e-10 * derivative_scale,
                "{case} at {t}: {:?} vs {d:?}",
                out[1]
            );
            checked += 1;
        }
        // The answer's form is the caller's.
        let knots = curve.caller_knots();
        assert!(knots.periodic);
        assert_eq!(knots.knots, numbers(&case["curve"]["knots"]));
        assert_eq!(
            curve.caller_control_points().len(),
            case["curve"]["control_points"].as_array().unwrap().len()
        );
    }
    assert!(checked > 500, "{checked}");
}

#[test]
fn real_periodic_curves_are_their_unwrapped_and_not_periodic_forms() {
    let file = data("real_periodic_curves.json");
    for entry in file["curves"].as_array().unwrap() {
        let occt = &entry["occt"];
        let n = occt["poles"].as_u64().unwrap() as usize;
        let poles = &entry["poles"].as_array().unwrap()[..n];
        let mut periodic = serde_json::json!({
            "degree": entry["degree"], "control_points": poles,
            "knots": occt["knots"], "multiplicities": occt["mults"],
        });
        if let Some(weights) = entry.get("weights") {
            periodic["weights"] = Value::from(&weights.as_array().unwrap()[..n]);
        }
        let curve = periodic_curve(&periodic);
        let unwrapped = Reference {
            degree: entry["degree"].as_u64().unwrap() as usize,
            knots: numbers(&entry["knots"]),
            points: reference_points(&entry["poles"]),
            weights: entry.get("weights").map(numbers),
        };
        let flat = &entry["not_periodic"];
        let not_periodic = Reference {
            degree: unwrapped.degree,
            knots: numbers(&flat["knots"]),
            points: reference_points(&flat["poles"]),
            weights: flat.get("weights").map(numbers),
        };
        let (lo, hi) = curve.domain();
        let tolerance = 1e-9 * scale(&curve);
        for k in 0..=200 {
            let t = lo + (hi - lo) * k as f64 / 200.0;
            let ours = point(&curve, t);
            for reference in [&unwrapped, &not_periodic] {
                let theirs = reference.point(t);
                assert!(
                    distance(ours, &theirs) <= tolerance,
                    "{} at {t}",
                    entry["id"]
                );
            }
            // One period later, the same point.
            assert!(distance(point(&curve, t + (hi - lo)), &ours) <= tolerance);
        }
    }
}

fn reference_points(value: &Value) -> Vec<[f64; 3]> {
    points(value)
        .iter()
        .map(|p| [p[0], p[1], p.get(2).copied().unwrap_or(0.0)])
        .collect()
}

/// The periodic test curves of periodic_occt.json.
fn occt_curves() -> Vec<Curve> {
    data("periodic_occt.json")["cases"]
        .as_array()
        .unwrap()
        .iter()
        .map(|case| periodic_curve(&case["curve"]))
        .collect()
}

/// The largest distance between two curves at many parameters of `curve`'s period.
fn max_difference(curve: &Curve, other: &Curve, shift: f64) -> f64 {
    let (lo, hi) = curve.domain();
    (0..=300)
        .map(|k| lo + (hi - lo) * k as f64 / 300.0)
        .map(|t| distance(point(curve, t), &point(other, t + shift)))
        .fold(0.0, f64::max)
}

proptest! {
    #![proptest_config(crate::config())]

    #[test]
    fn insertion_keeps_a_periodic_curve_periodic_and_its_shape(
        index in 0usize..40,
        fractions in prop::collection::vec(0.0f64..1.0, 1..4),
        at_seam in any::<bool>(),
    ) {
        let curves = occt_curves();
        let curve = &curves[index];
        let (lo, hi) = curve.domain();
        let mut values: Vec<f64> = fractions.iter().map(|f| lo + f * (hi - lo)).collect();
        let seam = curve.caller_knots().multiplicities.unwrap()[0];
        if at_seam && seam < curve.degree() {
            // k_m stands for k_0.
            values.push(hi);
        }
        let refined = curve.insert_knots(&values, 10_000).unwrap();
        prop_assert!(refined.is_periodic());
        prop_assert_eq!(refined.convention(), KnotConvention::Multiplicities);
        prop_assert_eq!(
            refined.caller_control_points().len(),
            curve.caller_control_points().len() + values.len()
        );
        let knots = refined.caller_knots();
        let multiplicities = knots.multiplicities.unwrap();
        let new_seam = multiplicities[0];
        prop_assert_eq!(new_seam, seam + usize::from(at_seam && seam < curve.degree()));
        prop_assert_eq!(*multiplicities.last().unwrap(), new_seam);
        prop_assert_eq!(knots.knots[0], lo);
        prop_assert_eq!(*knots.knots.last().unwrap(), hi);
        prop_assert!(max_difference(curve, &refined, 0.0) <= 1e-11 * scale(curve));
    }

    #[test]
    fn a_window_evaluates_as_the_periodic_curve_and_wraps_back_unchanged(
        index in 0usize..40,
        around in 0.0f64..1.0,
    ) {
        let curves = occt_curves();
        let curve = &curves[index];
        let (lo, hi) = curve.domain();
        let t = lo + around * (hi - lo);
        let window = curve.periodic_window(t).unwrap();
        let open = window.curve();
        prop_assert!(!open.is_periodic());
        let (a, b) = open.domain();
        prop_assert_eq!(a, window.cut_value());
        prop_assert!(((b - a) - (hi - lo)).abs() <= 1e-12 * (hi - lo).max(hi.abs()));
        // The window parameter of t is t shifted by whole periods.
        let s = window.window_parameter(t);
        prop_assert!((a..=b).contains(&s));
        let back = window.periodic_parameter(s);
        let cyclic = (back - t).rem_euclid(hi - lo);
        prop_assert!(cyclic.min(hi - lo - cyclic) <= 1e-12 * (1.0 + t.abs()));
        let tolerance = 1e-11 * scale(curve);
        for k in 0..=100 {
            let s = (a + (b - a) * k as f64 / 100.0).min(b);
            let periodic = point(curve, window.periodic_parameter(s));
            prop_assert!(distance(open.point(s).unwrap(), &periodic) <= tolerance);
        }
        // Each window knot is its periodic knot shifted by whole periods, and each window pole
        // is its periodic pole.
        let flat = {
            let knots = curve.caller_knots();
            let mut flat = Vec::new();
            let m = knots.multiplicities.unwrap();
            for (u, m) in knots.knots.iter().zip(&m).take(m.len() - 1) {
                flat.extend(std::iter::repeat_n(*u, *m));
            }
            flat
        };
        for (i, &u) in open.knots().iter().enumerate() {
            let base = flat[window.periodic_knot_index(i)];
            let periods = ((u - base) / (hi - lo)).round();
            prop_assert!((u - base - periods * (hi - lo)).abs() <= 1e-12 * (1.0 + u.abs()) * 4.0);
        }
        for (k, q) in open.control_points().iter().enumerate() {
            prop_assert_eq!(*q, curve.caller_control_points()[window.periodic_pole_index(k)]);
        }
        let back = window.wrap(open).unwrap();
        prop_assert_eq!(back.caller_knots(), curve.caller_knots());
        prop_assert_eq!(back.caller_control_points(), curve.caller_control_points());
        prop_assert_eq!(back.caller_weights(), curve.caller_weights());
    }
}

/// A periodic cubic with 12 control points on a circle-like loop, uniform knots.
fn loop_curve() -> Curve {
    let points: Vec<Vec<f64>> = (0..12)
        .map(|i| {
            let a = i as f64 * std::f64::consts::TAU / 12.0;
            vec![3.0 * a.cos(), 2.0 * a.sin() + 0.1 * i as f64]
        })
        .collect();
    let knots: Vec<f64> = (0..=12).map(|i| i as f64 / 12.0).collect();
    let mut multiplicities = vec![1; 13];
    multiplicities[0] = 1;
    Curve::from_knot_form(
        3,
        &points,
        KnotForm::Periodic {
            knots: &knots,
            multiplicities: &multiplicities,
        },
        None,
        &CurveLimits::default(),
    )
    .unwrap()
}

#[test]
fn an_edit_inside_the_window_wraps_back_to_every_copy() {
    let curve = loop_curve();
    // Near the seam: the window is cut on the far side, so the edit is in its middle.
    let t = 0.02;
    let window = curve.periodic_window(t).unwrap();
    assert!((window.cut_value() - 0.5).abs() < 1e-12);
    let open = window.curve();
    let s = window.window_parameter(t);
    assert!((s - 1.02).abs() < 1e-12, "{s}");
    // Move the window knot just right of s and the control point under it.
    let i = open.knots().partition_point(|&u| u <= s);
    let mut knots = open.knots().to_vec();
    knots[i] += 0.02;
    let moved = open.with_full_knots(knots).unwrap();
    let mut points = moved.control_points().to_vec();
    let k = i - 2;
    points[k][1] += 0.5;
    let edited = moved.with_control_points(points).unwrap();
    let wrapped = window.wrap(&edited).unwrap();
    assert!(wrapped.is_periodic());
    // The periodic result is the edited window everywhere in the window.
    let (a, b) = edited.domain();
    for step in 0..=400 {
        let s = (a + (b - a) * step as f64 / 400.0).min(b);
        let expected = edited.point(s).unwrap();
        let got = point(&wrapped, window.periodic_parameter(s));
        assert!(
            distance(got, &expected) < 1e-12,
            "at {s}: {got:?} {expected:?}"
        );
    }
    // Exactly one knot and one control point of the periodic form changed.
    let before = curve.caller_knots();
    let after = wrapped.caller_knots();
    assert_eq!(after.multiplicities, before.multiplicities);
    let changed_knots = before
        .knots
        .iter()
        .zip(&after.knots)
        .filter(|(a, b)| a != b)
        .count();
    assert_eq!(changed_knots, 1);
    let changed_points = curve
        .caller_control_points()
        .iter()
        .zip(wrapped.caller_control_points())
        .filter(|(a, b)| a != b)
        .count();
    assert_eq!(changed_points, 1);
    // Two copies changed differently cannot be written back.
    let copy = (0..open.control_points().len())
        .find(|&c| c != 0 && window.periodic_pole_index(c) == window.periodic_pole_index(0))
        .unwrap();
    let mut points = open.control_points().to_vec();
    points[0][0] += 1.0;
    points[copy][0] -= 1.0;
    let bad = open.with_control_points(points).unwrap();
    assert!(window.wrap(&bad).is_err());
}

#[test]
fn a_knot_moved_onto_the_seam_joins_its_run() {
    let curve = loop_curve();
    let window = curve.periodic_window(0.5).unwrap();
    assert_eq!(window.cut_value(), 0.0);
    let open = window.curve();
    // Window cut at k_0 = 0: the knot 1/12 moves onto 0, the seam's multiplicity becomes 2.
    let i = open.knots().iter().position(|&u| u == 1.0 / 12.0).unwrap();
    let mut knots = open.knots().to_vec();
    knots[i] = 0.0;
    let edited = open.with_full_knots(knots).unwrap();
    let wrapped = window.wrap(&edited).unwrap();
    let form = wrapped.caller_knots();
    let multiplicities = form.multiplicities.unwrap();
    assert_eq!(multiplicities[0], 2);
    assert_eq!(*multiplicities.last().unwrap(), 2);
    // Up to the spans whose basis functions reach the moved knot's copy one period later.
    for step in 0..=200 {
        let s = 0.05 + 0.65 * step as f64 / 200.0;
        assert!(distance(point(&wrapped, s), &edited.point(s).unwrap()) < 1e-12);
    }
}

#[test]
fn bezier_pieces_of_a_periodic_curve_cover_one_period() {
    for curve in occt_curves() {
        let spans = curve.caller_knots().knots.len() - 1;
        let pieces: Vec<_> = curve.bezier_pieces().collect();
        assert_eq!(pieces.len(), spans);
        let (lo, hi) = curve.domain();
        assert_eq!(pieces[0].domain.0, lo);
        assert_eq!(pieces[spans - 1].domain.1, hi);
    }
}

#[test]
fn the_clamped_curve_over_a_period_is_the_same_curve() {
    for curve in occt_curves() {
        let clamped = curve.clamped();
        assert!(!clamped.is_periodic());
        let p = clamped.degree();
        let knots = clamped.knots();
        let (lo, hi) = curve.domain();
        assert_eq!(clamped.domain(), (lo, hi));
        assert!(knots[..=p].iter().all(|&u| u == lo), "{knots:?}");
        assert!(
            knots[knots.len() - p - 1..].iter().all(|&u| u == hi),
            "{knots:?}"
        );
        assert!(max_difference(&curve, &clamped, 0.0) <= 1e-11 * scale(&curve));
        // The first control point is the curve's start.
        assert!(distance(point(&curve, lo), &clamped.control_points()[0]) <= 1e-11 * scale(&curve));
    }
}

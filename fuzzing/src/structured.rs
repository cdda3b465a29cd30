//! The check shared by the fuzz target `structured` (`fuzz/`) and the corpus replay test: bytes
//! become a valid random curve (degree 1–5, 2D or 3D, rational or not, clamped or not,
//! repeated knots) through `arbitrary`, then go through the core's operations, each answer
//! checked against a property that must hold, computed another way:
//!
//! * evaluation: every point is finite;
//! * closest point: the answer is a curve point in the range, and no sampled parameter is
//!   closer;
//! * knot insertion: the refined curve is the same curve (sampled);
//! * Bézier pieces: each piece starts and ends on the curve;
//! * tessellation: every vertex is a curve point, parameters increasing, ends included;
//! * cubic curves, shape editing: every knot or control-point solution lands on its target
//!   (re-evaluated by the spline core), `nearest` solutions land on the nearest point, region
//!   polygons are finite;
//! * every degree, the one edit (`shape::edit`) with every applicable method under pins, a
//!   prescribed or kept tangent and a fixed control point drawn from the case: every kept
//!   solution lands on its target, keeps each condition (the old and new curves' derivatives
//!   compared here, not by the constraint code), leaves the fixed control point and its
//!   weight alone, has positive finite weights and a finite deviation.

use arbitrary::{Arbitrary, Unstructured};

use knotshape::shape::{
    self, ConstraintSet, ConstraintSpec, EditContext, EditOptions, FixedPoles, KnotPair,
    MethodKind, PoleVariables, PolygonOptions, ShapeQuery, SideChoice, SolveOptions,
    nearest_reachable,
};
use knotshape::spline::vector::{Point, distance};
use knotshape::spline::{ClosestPointSearch, Curve, CurveLimits};

/// Largest number of control points drawn.
const MAX_EXTRA_POINTS: usize = 12;

/// Points per answer compared with the curve.
const SAMPLES: usize = 33;

/// A random curve and the operations' arguments, drawn from the fuzzer's bytes.
#[derive(Debug, Clone)]
pub struct Case {
    /// The curve (always valid).
    pub curve: Curve,
    /// Fractions of the domain in `[0, 1]`: parameters for the operations.
    pub fractions: [f64; 4],
    /// A query point near the curve's box.
    pub query: Point,
    /// Tolerance of the tessellation, relative to the curve's size.
    pub relative_tolerance: f64,
}

impl Case {
    /// Draws a case, or `None` when the bytes run out or the drawn data are not a curve.
    pub fn draw(data: &[u8]) -> Option<Case> {
        let mut u = Unstructured::new(data);
        let degree = 1 + usize::from(u8::arbitrary(&mut u).ok()? % 5);
        let three_d = bool::arbitrary(&mut u).ok()?;
        let rational = bool::arbitrary(&mut u).ok()?;
        let clamped = bool::arbitrary(&mut u).ok()?;
        let count = degree + 1 + usize::from(u8::arbitrary(&mut u).ok()?) % MAX_EXTRA_POINTS;
        let dimension = if three_d { 3 } else { 2 };
        let mut points = Vec::with_capacity(count);
        for _ in 0..count {
            let point: Vec<f64> = (0..dimension)
                .map(|_| i16::arbitrary(&mut u).map(|v| f64::from(v) / 256.0))
                .collect::<Result<_, _>>()
                .ok()?;
            points.push(point);
        }
        let weights: Option<Vec<f64>> = if rational {
            Some(
                (0..count)
                    .map(|_| u8::arbitrary(&mut u).map(|v| 0.05 + f64::from(v) / 16.0))
                    .collect::<Result<_, _>>()
                    .ok()?,
            )
        } else {
            None
        };
        let knot_count = count + degree + 1;
        let mut knots = Vec::with_capacity(knot_count);
        let mut value = f64::from(i8::arbitrary(&mut u).ok()?) / 16.0;
        let mut run = 0;
        for i in 0..knot_count {
            let clamped_end = clamped && (i <= degree || i >= count);
            let step = u8::arbitrary(&mut u).ok()?;
            // A repeat now and then (never more than the degree in a row inside).
            let repeat = clamped_end || (step % 5 == 0 && run < degree);
            if i > 0 && !repeat {
                value += 0.01 + f64::from(step) / 64.0;
            }
            run = if repeat && i > 0 { run + 1 } else { 0 };
            knots.push(value);
        }
        let curve = Curve::new(
            degree,
            &points,
            &knots,
            weights.as_deref(),
            &CurveLimits::default(),
        )
        .ok()?;
        let mut fractions = [0.0; 4];
        for fraction in &mut fractions {
            *fraction = f64::from(u16::arbitrary(&mut u).ok()?) / f64::from(u16::MAX);
        }
        let mut query = [0.0; 3];
        for coordinate in query.iter_mut().take(dimension) {
            *coordinate = f64::from(i16::arbitrary(&mut u).ok()?) / 200.0;
        }
        let relative_tolerance = 1e-3 + f64::from(u8::arbitrary(&mut u).ok()?) / 2560.0;
        Some(Case {
            curve,
            fractions,
            query,
            relative_tolerance,
        })
    }

    fn parameter(&self, index: usize) -> f64 {
        let (lo, hi) = self.curve.domain();
        (lo + self.fractions[index] * (hi - lo)).min(hi)
    }

    /// The largest coordinate magnitude (at least 1): the scale of rounding errors.
    fn size(&self) -> f64 {
        self.curve
            .control_points()
            .iter()
            .flatten()
            .fold(1.0f64, |m, v| m.max(v.abs()))
    }
}

/// Runs every operation on the case drawn from `data`; `Err` names the broken property.
pub fn check(data: &[u8]) -> Result<(), String> {
    let Some(case) = Case::draw(data) else {
        return Ok(());
    };
    check_case(&case)
}

/// [`check`] on a drawn case.
pub fn check_case(case: &Case) -> Result<(), String> {
    let curve = &case.curve;
    let size = case.size();
    let (lo, hi) = curve.domain();
    let samples: Vec<f64> = (0..SAMPLES)
        .map(|i| (lo + (hi - lo) * i as f64 / (SAMPLES - 1) as f64).min(hi))
        .collect();
    for &u in &samples {
        let point = curve.point_unchecked(u);
        if !point.iter().all(|v| v.is_finite()) {
            return Err(format!("evaluation: non-finite point at {u}"));
        }
    }
    check_closest(case, &samples, size)?;
    check_insertion(case, &samples, size)?;
    check_pieces(case, size)?;
    check_tessellation(case, size)?;
    if curve.degree() == 3 {
        check_shape(case, size)?;
    }
    check_edit(case, size)?;
    Ok(())
}

fn check_closest(case: &Case, samples: &[f64], size: f64) -> Result<(), String> {
    let curve = &case.curve;
    let (a, b) = (case.parameter(0), case.parameter(1));
    let range = (a.min(b), a.max(b));
    let search = ClosestPointSearch::new(curve, Some(range)).map_err(|e| e.to_string())?;
    let found = search.closest(case.query);
    if !(range.0 <= found.parameter && found.parameter <= range.1) {
        return Err(format!(
            "closest point: {} outside {range:?}",
            found.parameter
        ));
    }
    let truth = curve.point_unchecked(found.parameter);
    if distance(truth, found.point) > 1e-9 * size {
        return Err("closest point: the point is not the curve's at its parameter".into());
    }
    let tolerance = 1e-9 * (size + found.distance);
    for &u in samples.iter().filter(|&&u| range.0 <= u && u <= range.1) {
        let sampled = distance(curve.point_unchecked(u), case.query);
        if sampled + tolerance < found.distance {
            return Err(format!(
                "closest point: parameter {u} is closer ({sampled}) than the answer {} ({})",
                found.parameter, found.distance
            ));
        }
    }
    Ok(())
}

fn check_insertion(case: &Case, samples: &[f64], size: f64) -> Result<(), String> {
    let curve = &case.curve;
    let values = [case.parameter(2), case.parameter(3)];
    let Ok(refined) = curve.insert_knots(&values, usize::MAX) else {
        return Ok(()); // a refused multiplicity is a rule, not a finding
    };
    for &u in samples {
        let gap = distance(curve.point_unchecked(u), refined.point_unchecked(u));
        if gap > 1e-9 * size {
            return Err(format!("insertion: the curve moved by {gap} at {u}"));
        }
    }
    Ok(())
}

fn check_pieces(case: &Case, size: f64) -> Result<(), String> {
    let curve = &case.curve;
    let jumps = curve.jump_knots();
    for piece in curve.bezier_pieces() {
        let (a, b) = piece.domain;
        let first = piece.control_point(0);
        if distance(first, curve.point_unchecked(a)) > 1e-9 * size {
            return Err(format!(
                "Bézier pieces: the piece on [{a}, {b}] does not start on the curve"
            ));
        }
        let last = piece.control_point(piece.degree());
        if !jumps.contains(&b) && distance(last, curve.point_unchecked(b)) > 1e-9 * size {
            return Err(format!(
                "Bézier pieces: the piece on [{a}, {b}] does not end on the curve"
            ));
        }
    }
    Ok(())
}

fn check_tessellation(case: &Case, size: f64) -> Result<(), String> {
    let curve = &case.curve;
    let Ok(parameters) = curve.tessellate(case.relative_tolerance * size, 20_000) else {
        return Ok(()); // too fine for the budget, or a jump: refused by rule
    };
    let (lo, hi) = curve.domain();
    if parameters.first() != Some(&lo) || parameters.last() != Some(&hi) {
        return Err("tessellation: the ends are missing".into());
    }
    if parameters.windows(2).any(|w| w[0] >= w[1]) {
        return Err("tessellation: parameters not increasing".into());
    }
    Ok(())
}

fn check_shape(case: &Case, size: f64) -> Result<(), String> {
    let curve = &case.curve;
    let t = case.parameter(2);
    let dimension = curve.dimension().count();
    let base = curve.point_unchecked(t);
    let target: Point = std::array::from_fn(|c| {
        if c < dimension {
            base[c] + case.query[c] / 16.0
        } else {
            0.0
        }
    });
    let query = ShapeQuery {
        side: SideChoice::Both,
        pairs: &KnotPair::ALL,
        families: Default::default(),
        keep_domain: case.fractions[3] < 0.7,
        ..ShapeQuery::new(curve, t)
    };
    let options = SolveOptions {
        measure_deviation: true,
    };
    let outcome = shape::solve(&query, &target[..dimension], options).map_err(|e| e.to_string())?;
    for solution in &outcome.solutions {
        let reached = curve.point_with_knots(&solution.knots, t);
        if distance(reached, target) > 1e-6 * size {
            return Err(format!(
                "solve: a solution misses its target ({solution:?})"
            ));
        }
        if !solution.max_deviation.is_some_and(f64::is_finite) {
            return Err("solve: a deviation is not finite".into());
        }
    }
    if let Some(moved) = shape::control_point_move(curve, t, target, true) {
        if moved.residual > 1e-6 * size {
            return Err(format!("control points: residual {}", moved.residual));
        }
    } else {
        return Err("control points: no move for a finite target".into());
    }
    if !outcome.reachable() {
        if let Some(nearest) = nearest_reachable(&query, target, true).map_err(|e| e.to_string())? {
            for solution in &nearest.solutions {
                let reached = curve.point_with_knots(&solution.knots, t);
                if distance(reached, nearest.point) > 1e-6 * size {
                    return Err("nearest: a solution misses the nearest point".into());
                }
            }
        }
    }
    let polygons = shape::region_polygons(
        &query,
        PolygonOptions {
            tolerance: None,
            max_vertices: 512,
        },
    )
    .map_err(|e| e.to_string())?;
    for candidate in &polygons {
        for region in &candidate.regions {
            if !region.polygon.iter().flatten().all(|v| v.is_finite()) {
                return Err("regions: a polygon has a non-finite vertex".into());
            }
        }
    }
    Ok(())
}

/// The conditions of [`check_edit`], drawn from the case: a pin of the point at the first
/// fraction, and at the second a pinned or kept tangent (or none), chosen by the query's signs.
fn drawn_conditions(case: &Case, t: f64) -> Vec<ConstraintSpec<'static>> {
    let mut specs = Vec::new();
    let pin = case.parameter(0);
    if (pin - t).abs() > 1e-3 * (case.curve.domain().1 - case.curve.domain().0) {
        specs.push(ConstraintSpec {
            parameter: pin,
            order: 0,
            value: None,
            direction_only: false,
        });
    }
    if case.query[0] > 0.0 {
        specs.push(ConstraintSpec {
            parameter: case.parameter(1),
            order: 1,
            value: None,
            direction_only: case.query[1] > 0.0,
        });
    }
    specs
}

/// The `order`-th derivative of `curve` at `u`, or `None` outside its domain.
fn derivative(curve: &Curve, u: f64, order: usize) -> Option<Point> {
    let mut values = [[0.0; 3]; 3];
    curve.derivatives(u, &mut values[..=order]).ok()?;
    Some(values[order])
}

/// A loose scale of the `order`-th derivative's rounding on `curve` at `u`: the size over the
/// span's width to the `order` (times the degree's factor), the basis derivatives' growth.
fn derivative_scale(curve: &Curve, u: f64, order: usize, size: f64) -> f64 {
    let knots = curve.knots();
    let p = curve.degree();
    let right = knots.partition_point(|&k| k <= u).min(knots.len() - 1);
    let left = right.saturating_sub(1);
    let mut width = knots[right] - knots[left];
    if width <= 0.0 {
        width = curve.domain().1 - curve.domain().0;
    }
    size * (4.0 * p as f64 / width).powi(order as i32)
}

fn check_edit(case: &Case, size: f64) -> Result<(), String> {
    let curve = &case.curve;
    let t = case.parameter(2);
    let dimension = curve.dimension().count();
    let base = curve.point_unchecked(t);
    let target: Vec<f64> = (0..dimension)
        .map(|c| base[c] + case.query[c] / 16.0)
        .collect();
    let specs = drawn_conditions(case, t);
    let Ok(constraints) = ConstraintSet::new(curve, t, &specs) else {
        return Ok(());
    };
    let count = curve.control_points().len();
    let fixed_index = (case.relative_tolerance * 2560.0) as usize % (count + 1);
    let fixed = FixedPoles::from_fn(count, |i| i == fixed_index);
    let variables = PoleVariables::free_poles(&fixed);
    let query = ShapeQuery {
        keep_domain: case.fractions[3] < 0.7,
        ..ShapeQuery::new(curve, t)
    };
    let context = EditContext {
        query,
        constraints: &constraints,
        fixed: &fixed,
        variables: &variables,
    };
    let methods: &[MethodKind] = if curve.degree() == 3 {
        &[
            MethodKind::Knots,
            MethodKind::ControlPoints,
            MethodKind::Weights,
        ]
    } else {
        &[MethodKind::ControlPoints, MethodKind::Weights]
    };
    let options = EditOptions {
        measure_deviation: true,
        nearest: true,
    };
    let Ok(outcome) = shape::edit(&context, methods, &target, options) else {
        return Ok(());
    };
    let mut target_point = [0.0; 3];
    target_point[..dimension].copy_from_slice(&target);
    for solution in &outcome.solutions {
        let method = solution.detail.method();
        let new = &solution.curve;
        let reached = new
            .point(t)
            .map_err(|e| format!("edit {method:?}: the new curve has no point at t: {e}"))?;
        if distance(reached, target_point) > 1e-6 * size {
            return Err(format!(
                "edit {method:?}: misses the target by {}",
                distance(reached, target_point)
            ));
        }
        if !solution.max_deviation.is_some_and(f64::is_finite) {
            return Err(format!("edit {method:?}: a deviation is not finite"));
        }
        if (0..count).any(|i| !(new.weight(i).is_finite() && new.weight(i) > 0.0)) {
            return Err(format!(
                "edit {method:?}: a weight is not positive and finite"
            ));
        }
        if fixed_index < count
            && (new.control_points()[fixed_index] != curve.control_points()[fixed_index]
                || new.weight(fixed_index) != curve.weight(fixed_index))
        {
            return Err(format!(
                "edit {method:?}: the fixed control point {fixed_index} changed"
            ));
        }
        for spec in &specs {
            let order = spec.order as usize;
            let u = curve
                .snap_to_domain(spec.parameter)
                .unwrap_or(spec.parameter);
            let (Some(old), Some(now)) = (derivative(curve, u, order), derivative(new, u, order))
            else {
                return Err(format!(
                    "edit {method:?}: a condition's parameter {u} left the domain"
                ));
            };
            let scale = derivative_scale(curve, u, order, size);
            if spec.direction_only {
                // The contract bounds the new tangent's component across the old direction
                // (absolute, like a value), and its component along it must stay positive.
                let length = distance(old, [0.0; 3]);
                if length > 1e-6 * scale {
                    let unit = old.map(|v| v / length);
                    let along: f64 = (0..3).map(|c| now[c] * unit[c]).sum();
                    let across = distance(now, unit.map(|v| v * along));
                    if across > 1e-6 * scale || along <= 0.0 {
                        return Err(format!(
                            "edit {method:?}: the tangent direction at {u} turned ({old:?} -> {now:?})"
                        ));
                    }
                }
            } else if distance(old, now) > 1e-6 * scale {
                return Err(format!(
                    "edit {method:?}: the order-{order} pin at {u} moved by {} ({old:?} -> {now:?})",
                    distance(old, now)
                ));
            }
        }
    }
    Ok(())
}

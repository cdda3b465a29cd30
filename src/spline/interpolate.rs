//! Global interpolation (The NURBS Book §9.2.1–9.2.2): the curve of degree `p` through points
//! `Q_0 … Q_{m−1}` at parameters `ū_k`, with optional end derivatives, open or closed.
//!
//! * Open: knots by averaging (eq. 9.8) `u_{j+p} = (1/p) Σ_{i=j}^{j+p−1} ū_i` with `p + 1`
//!   equal values at each end, or given; the collocation system `Σ_j N_j(ū_k) P_j = Q_k` is
//!   banded (each row has at most `p + 1` neighbouring non-zeros) and totally positive when
//!   `N_k(ū_k) > 0` (Schoenberg–Whitney), so Gaussian elimination without pivoting solves
//!   it in `O(m p²)`. A given end derivative `D` adds a pole and the row
//!   `Σ_j N_j'(ū) P_j = D` next to the end's own row (§9.2.2); the averaging windows then
//!   include the first (or last) one (eq. 9.22).
//! * Closed: `m` distinct poles `P_0 … P_{m−1}`, the first `p` repeated at the end (`m + p`
//!   control points), an unclamped knot vector with periodic spacing: the knots in the
//!   domain are the parameters (odd `p`) or the midpoints between them (even `p`, where
//!   interpolating at knots would be singular), as SciPy's `make_interp_spline(...,
//!   bc_type="periodic")` chooses them; the curve is `C^{p−1}` everywhere, across the seam
//!   too. The system is cyclic-banded; it is split into a totally positive banded block of
//!   `m − p` interior poles and `p` border poles and solved by the Schur complement
//!   ([`BorderedSystem`]), `O(m p²)`.

use super::banded::{BandedMatrix, BorderedSystem};
use super::basis::{CAP, MAX_DEGREE, basis_derivatives, basis_functions, find_span};
use super::curve::{Curve, CurveError, CurveLimits, Dimension, KnotConvention};
use super::fit_points::{Parametrization, PointSet, PointsError, check_given_parameters};
use super::vector::Point;

/// Where the parameters of the points come from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ParameterChoice<'a> {
    /// Computed from the points.
    By(Parametrization),
    /// Given by the caller: one per point, strictly increasing; for a closed curve one more,
    /// where the curve returns to the first point (the end of the domain).
    Given(&'a [f64]),
}

/// What to interpolate with.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InterpolationSpec<'a> {
    /// Degree `p >= 1`.
    pub degree: usize,
    /// How the parameters are chosen.
    pub parameters: ParameterChoice<'a>,
    /// A knot vector to use instead of averaging (full or trimmed convention, detected by
    /// length: `m + t + p + 1` or `m + t + p − 1` values for `m` points and `t` tangents);
    /// open curves only. Computed parameters are mapped onto its domain.
    pub knots: Option<&'a [f64]>,
    /// First derivatives at the start and at the end (open curves, degree >= 2).
    pub end_tangents: [Option<Point>; 2],
    /// A closed curve, `C^{p−1}` across the seam at the first point.
    pub closed: bool,
}

/// The interpolating curve and the parameter of each point on it.
#[derive(Debug, Clone, PartialEq)]
pub struct Interpolation {
    /// The curve: `s(parameters[k]) = points[k]`.
    pub curve: Curve,
    /// One parameter per point.
    pub parameters: Vec<f64>,
}

/// Why no curve is given.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum InterpolationError {
    /// The points or the given parameters break a rule.
    #[error(transparent)]
    Points(#[from] PointsError),
    #[error("degree must be at least 1")]
    DegreeTooLow,
    #[error("degree {degree} exceeds the limit {max}")]
    DegreeTooHigh { degree: usize, max: usize },
    #[error("end tangents need degree 2 or more (a degree-1 curve has no room for them)")]
    TangentsNeedDegreeTwo,
    #[error("a closed curve has no ends: give no `end_tangents` with `closed`")]
    ClosedWithTangents,
    #[error(
        "a closed curve takes its periodic knots from its parameters: give no `knots` with `closed`"
    )]
    ClosedWithKnots,
    /// The given knot vector breaks a rule of curves (its count fits the points and tangents
    /// as control points).
    #[error("{0}")]
    Knots(CurveError),
    #[error("parameter {index} = {value} lies outside the knots' domain [{}, {}]", domain.0, domain.1)]
    ParameterOutsideKnots {
        index: usize,
        value: f64,
        domain: (f64, f64),
    },
    #[error("the curve would have {count} control points, above the limit {max}")]
    TooManyControlPoints { count: usize, max: usize },
    /// The system is singular: with given knots, the Schoenberg–Whitney condition fails
    /// (a basis function vanishes at the parameter of its row).
    #[error(
        "the interpolation system is singular: {}",
        if *given_knots {
            "the knots do not fit the parameters (each basis function N_k must be non-zero at the parameter of point k: u_k < ū_k < u_(k+p+1))"
        } else {
            "the parameters are too close together for double precision"
        }
    )]
    Singular { given_knots: bool },
    #[error("the result is not finite: the points are too extreme for double precision")]
    NonFiniteResult,
}

/// The part of the request an [`InterpolationError`] names.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum InterpolationField {
    Degree,
    Points(super::fit_points::PointsField),
    EndTangents,
    Knots(super::curve::CurveField),
    Closed,
    Parameters,
}

impl InterpolationError {
    /// The part of the request at fault.
    pub fn field(&self) -> InterpolationField {
        use super::curve::CurveField;
        use super::fit_points::PointsField;
        match self {
            InterpolationError::Points(error) => InterpolationField::Points(error.field()),
            InterpolationError::DegreeTooLow | InterpolationError::DegreeTooHigh { .. } => {
                InterpolationField::Degree
            }
            InterpolationError::TangentsNeedDegreeTwo | InterpolationError::ClosedWithTangents => {
                InterpolationField::EndTangents
            }
            InterpolationError::ClosedWithKnots => InterpolationField::Knots(CurveField::Knots),
            InterpolationError::Knots(error) => InterpolationField::Knots(error.field()),
            InterpolationError::ParameterOutsideKnots { index, .. } => {
                InterpolationField::Points(PointsField::Parameter(*index))
            }
            InterpolationError::TooManyControlPoints { .. }
            | InterpolationError::NonFiniteResult => {
                InterpolationField::Points(PointsField::Points)
            }
            InterpolationError::Singular { given_knots: true } => {
                InterpolationField::Knots(CurveField::Knots)
            }
            InterpolationError::Singular { given_knots: false } => InterpolationField::Parameters,
        }
    }
}

/// The curve of degree `spec.degree` through every point (module docs).
///
/// Rules: `1 <= p <=` the limit; open: `m + t >= p + 1` for `t` given tangents (so
/// `p <= m − 1 + t`), tangents only for `p >= 2`; closed: `m >= p + 1`, no tangents, no
/// knots; consecutive points distinct (the last and the first too, when closed); given
/// parameters finite and strictly increasing; given knots a valid knot vector whose domain
/// holds the parameters; at most `limits.max_control_points` control points.
pub fn interpolate(
    points: &PointSet,
    spec: &InterpolationSpec<'_>,
    limits: &CurveLimits,
) -> Result<Interpolation, InterpolationError> {
    let p = spec.degree;
    if p < 1 {
        return Err(InterpolationError::DegreeTooLow);
    }
    let max_degree = limits.max_degree.min(MAX_DEGREE);
    if p > max_degree {
        return Err(InterpolationError::DegreeTooHigh {
            degree: p,
            max: max_degree,
        });
    }
    let m = points.len();
    let tangents = spec.end_tangents.iter().flatten().count();
    if spec.closed && tangents > 0 {
        return Err(InterpolationError::ClosedWithTangents);
    }
    if spec.closed && spec.knots.is_some() {
        return Err(InterpolationError::ClosedWithKnots);
    }
    let needed = p + 1 - tangents.min(p + 1);
    if m < needed.max(2) {
        let reason = if spec.closed || tangents == 0 {
            format!(" for degree {p} (degree + 1)")
        } else {
            format!(" for degree {p} with {tangents} end tangent(s) (degree + 1 − tangents)")
        };
        return Err(PointsError::TooFewPoints {
            count: m,
            needed: needed.max(2),
            reason,
        }
        .into());
    }
    if tangents > 0 && p < 2 {
        return Err(InterpolationError::TangentsNeedDegreeTwo);
    }
    points.check_distinct_neighbours(spec.closed)?;
    let count = if spec.closed { m + p } else { m + tangents };
    if count > limits.max_control_points {
        return Err(InterpolationError::TooManyControlPoints {
            count,
            max: limits.max_control_points,
        });
    }
    if spec.closed {
        let parameters = match spec.parameters {
            ParameterChoice::By(kind) => points.parameters(kind, true)?,
            ParameterChoice::Given(given) => {
                check_given_parameters(
                    given,
                    m + 1,
                    " (one per point and one more for the return to the first point)",
                )?;
                given.to_vec()
            }
        };
        let curve = interpolate_closed(points, &parameters, p)?;
        let mut parameters = parameters;
        parameters.pop();
        return Ok(Interpolation { curve, parameters });
    }
    let mut parameters = match spec.parameters {
        ParameterChoice::By(kind) => points.parameters(kind, false)?,
        ParameterChoice::Given(given) => {
            check_given_parameters(given, m, " (one per point)")?;
            given.to_vec()
        }
    };
    let (knots, convention) = match spec.knots {
        None => (
            averaged_knots(&parameters, p, spec.end_tangents.map(|t| t.is_some())),
            KnotConvention::Full,
        ),
        Some(given) => {
            let zeros = vec![[0.0; 3]; count];
            let template = Curve::new(
                p,
                &zeros,
                given,
                None,
                &CurveLimits {
                    max_degree,
                    max_control_points: limits.max_control_points,
                },
            )
            .map_err(InterpolationError::Knots)?;
            let domain = template.domain();
            if let ParameterChoice::By(_) = spec.parameters {
                let (lo, hi) = domain;
                for value in &mut parameters {
                    *value = lo + *value * (hi - lo);
                }
                let last = parameters.len() - 1;
                parameters[0] = lo;
                parameters[last] = hi;
            }
            for (index, value) in parameters.iter_mut().enumerate() {
                *value = template.snap_to_domain(*value).ok_or(
                    InterpolationError::ParameterOutsideKnots {
                        index,
                        value: *value,
                        domain,
                    },
                )?;
            }
            (template.knots().to_vec(), template.convention())
        }
    };
    let columns = points.dimension().count();
    let control_points = solve_open(
        points.points(),
        &parameters,
        &knots,
        p,
        spec.end_tangents,
        columns,
    )
    .map_err(|_| InterpolationError::Singular {
        given_knots: spec.knots.is_some(),
    })?;
    if control_points.iter().flatten().any(|v| !v.is_finite()) {
        return Err(InterpolationError::NonFiniteResult);
    }
    let curve = Curve::from_valid_parts(
        p,
        points.dimension(),
        planar(control_points, points.dimension()),
        None,
        knots,
        convention,
    );
    Ok(Interpolation { curve, parameters })
}

/// `z = 0` for planar points (rounding never makes it otherwise, but the invariant is cheap).
fn planar(mut points: Vec<Point>, dimension: Dimension) -> Vec<Point> {
    if dimension == Dimension::Two {
        for point in &mut points {
            point[2] = 0.0;
        }
    }
    points
}

/// The full clamped knot vector of an open interpolant by averaging (The NURBS Book eq. 9.8;
/// eq. 9.22 with both end derivatives): `p + 1` copies of each end parameter and the means
/// of `p` consecutive parameters, the windows starting at `1 ..= m − p − 1` without
/// tangents, at `0` too with a start tangent, at `m − p` too with an end tangent.
///
/// Preconditions: `p >= 1` (`p >= 2` with tangents), parameters strictly increasing, and
/// `m + t >= p + 1`.
pub fn averaged_knots(parameters: &[f64], p: usize, tangents: [bool; 2]) -> Vec<f64> {
    let m = parameters.len();
    let given = tangents.iter().filter(|&&t| t).count();
    let interior = (m + given).saturating_sub(p + 1);
    let first_window = usize::from(!tangents[0]);
    let (lo, hi) = (parameters[0], parameters[m - 1]);
    let mut knots = vec![lo; p + 1];
    for j in first_window..first_window + interior {
        let sum: f64 = parameters[j..j + p].iter().sum();
        knots.push(sum / p as f64);
    }
    knots.extend(std::iter::repeat_n(hi, p + 1));
    knots
}

/// Which condition a row of the open system states.
#[derive(Debug, Clone, Copy)]
enum Row {
    /// `s(ū_k) = Q_k`.
    Value(usize),
    /// `s'(ū) = D` at the start (`0`) or the end (`1`).
    Derivative(usize),
}

/// Solves the open collocation system (module docs) for the `m + t` control points, with
/// `columns` coordinates (2 or 3).
fn solve_open(
    points: &[Point],
    parameters: &[f64],
    knots: &[f64],
    p: usize,
    tangents: [Option<Point>; 2],
    columns: usize,
) -> Result<Vec<Point>, super::banded::SingularSystem> {
    let m = points.len();
    let (start, end) = (tangents[0].is_some(), tangents[1].is_some());
    let n = m + usize::from(start) + usize::from(end);
    // Rows: Q_0, [D_0], Q_1 … Q_{m−2}, [D_1], Q_{m−1}.
    let row = |r: usize| -> Row {
        if r == 0 {
            Row::Value(0)
        } else if start && r == 1 {
            Row::Derivative(0)
        } else if r == n - 1 {
            Row::Value(m - 1)
        } else if end && r == n - 2 {
            Row::Derivative(1)
        } else {
            Row::Value(r - usize::from(start))
        }
    };
    let parameter = |row: Row| match row {
        Row::Value(k) => parameters[k],
        Row::Derivative(0) => parameters[0],
        Row::Derivative(_) => parameters[m - 1],
    };
    // The rows' parameters never decrease: their spans are found by walking the knots.
    let last_span = find_span(knots, p, parameters[m - 1]);
    let mut spans = Vec::with_capacity(n);
    let mut span = p;
    let (mut lower, mut upper) = (0, 0);
    for r in 0..n {
        let t = parameter(row(r));
        while span < last_span && knots[span + 1] <= t {
            span += 1;
        }
        lower = lower.max(r.saturating_sub(span - p));
        upper = upper.max(span.saturating_sub(r));
        spans.push(span);
    }
    let mut matrix = BandedMatrix::zeros(n, lower, upper);
    let mut rhs = vec![0.0; n * columns];
    let mut values = [0.0; CAP];
    let mut ders = [[0.0; CAP]; CAP];
    for (r, &s) in spans.iter().enumerate() {
        let kind = row(r);
        let t = parameter(kind);
        let (target, coefficients) = match kind {
            Row::Value(k) => {
                basis_functions(knots, p, s, t, &mut values);
                (points[k], &values)
            }
            Row::Derivative(end) => {
                basis_derivatives(knots, p, s, t, 1, &mut ders);
                (tangents[end].unwrap_or_default(), &ders[1])
            }
        };
        for (i, &value) in coefficients.iter().enumerate().take(p + 1) {
            if value != 0.0 {
                matrix.add(r, s - p + i, value);
            }
        }
        rhs[r * columns..(r + 1) * columns].copy_from_slice(&target[..columns]);
    }
    matrix.factor_lu()?;
    matrix.solve_lu(&mut rhs, columns);
    Ok(rhs
        .chunks_exact(columns)
        .map(|c| {
            let mut point = [0.0; 3];
            point[..columns].copy_from_slice(c);
            point
        })
        .collect())
}

/// The full unclamped knot vector of a closed interpolant (`m + 2p + 1` values) from the
/// `m + 1` parameters `t_0 < … < t_m`: in the domain the parameters themselves (odd `p`) or
/// `t_0`, the midpoints `(t_{k−1} + t_k) / 2` for `k = 1 … m − 1`, and `t_m` (even `p`);
/// outside it the spacing repeated with period `t_m − t_0` (SciPy's `_periodic_knots`).
pub fn periodic_knots(parameters: &[f64], p: usize) -> Vec<f64> {
    let m = parameters.len() - 1;
    let mut inner = parameters.to_vec();
    if p % 2 == 0 {
        for k in (1..m).rev() {
            inner[k] = 0.5 * (parameters[k - 1] + parameters[k]);
        }
    }
    let gaps: Vec<f64> = inner.windows(2).map(|w| w[1] - w[0]).collect();
    let mut knots = vec![0.0; m + 1 + 2 * p];
    knots[p..=p + m].copy_from_slice(&inner);
    for i in 0..p {
        knots[p - i - 1] = knots[p - i] - gaps[m - 1 - (i % m)];
        knots[p + m + 1 + i] = knots[p + m + i] + gaps[i % m];
    }
    knots
}

/// The closed interpolant through the `m` points at `t_0 … t_{m−1}` with period `t_m − t_0`
/// (module docs). Precondition: `m >= p + 1`, parameters strictly increasing.
fn interpolate_closed(
    points: &PointSet,
    parameters: &[f64],
    p: usize,
) -> Result<Curve, InterpolationError> {
    let data = points.points();
    let m = data.len();
    let knots = periodic_knots(parameters, p);
    // Interior rows a .. a + m − p (their diagonal N_{p+k−a}(t_k) > 0), interior poles p .. m.
    let interior = m - p;
    let a = p.div_ceil(2);
    let spans: Vec<usize> = (0..m)
        .map(|k| find_span(&knots, p, parameters[k]))
        .collect();
    let (mut lower, mut upper) = (0usize, 0usize);
    for row in 0..interior {
        let s = spans[row + a];
        for j in s - p..=s {
            if (p..m).contains(&j) {
                let column = j - p;
                lower = lower.max(row.saturating_sub(column));
                upper = upper.max(column.saturating_sub(row));
            }
        }
    }
    let mut system = BorderedSystem::zeros(interior, lower, upper, p);
    let mut interior_rhs = vec![0.0; interior * 3];
    let mut border_rhs = vec![0.0; p * 3];
    let mut values = [0.0; CAP];
    for (k, &s) in spans.iter().enumerate() {
        basis_functions(&knots, p, s, parameters[k], &mut values);
        let interior_row = (a..a + interior).contains(&k).then(|| k - a);
        let border_row = if k < a { k } else { k.wrapping_sub(interior) };
        for (i, &value) in values.iter().enumerate().take(p + 1) {
            if value == 0.0 {
                continue;
            }
            let pole = (s - p + i) % m;
            match (interior_row, pole >= p) {
                (Some(row), true) => system.interior.add(row, pole - p, value),
                (Some(row), false) => system.interior_border[row * p + pole] += value,
                (None, true) => system.border_interior[border_row * interior + pole - p] += value,
                (None, false) => system.border_border[border_row * p + pole] += value,
            }
        }
        let target = match interior_row {
            Some(row) => &mut interior_rhs[row * 3..row * 3 + 3],
            None => &mut border_rhs[border_row * 3..border_row * 3 + 3],
        };
        target.copy_from_slice(&data[k]);
    }
    system
        .solve(&mut interior_rhs, &mut border_rhs, 3)
        .map_err(|_| InterpolationError::Singular { given_knots: false })?;
    let pole = |w: usize| -> Point {
        let source = if w < p {
            &border_rhs[w * 3..w * 3 + 3]
        } else {
            &interior_rhs[(w - p) * 3..(w - p) * 3 + 3]
        };
        [source[0], source[1], source[2]]
    };
    let control_points: Vec<Point> = (0..m + p).map(|j| pole(j % m)).collect();
    if control_points.iter().flatten().any(|v| !v.is_finite()) {
        return Err(InterpolationError::NonFiniteResult);
    }
    Ok(Curve::from_valid_parts(
        p,
        points.dimension(),
        planar(control_points, points.dimension()),
        None,
        knots,
        KnotConvention::Full,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn averaged_knots_follow_the_book() {
        // The NURBS Book Ex. 9.1: ū = 0, 5/17, 9/17, 14/17, 1, cubic: one interior knot 28/51.
        let parameters = [0.0, 5.0 / 17.0, 9.0 / 17.0, 14.0 / 17.0, 1.0];
        let knots = averaged_knots(&parameters, 3, [false, false]);
        assert_eq!(knots.len(), 5 + 3 + 1);
        assert!((knots[4] - 28.0 / 51.0).abs() < 1e-15);
        let both = averaged_knots(&parameters, 3, [true, true]);
        assert_eq!(both.len(), 7 + 3 + 1);
        assert!((both[4] - 14.0 / 51.0).abs() < 1e-15);
        assert!((both[6] - 40.0 / 51.0).abs() < 1e-15);
    }

    #[test]
    fn periodic_knots_repeat_the_spacing() {
        let t = [0.0, 0.1, 0.4, 0.6, 1.0];
        let knots = periodic_knots(&t, 3);
        assert_eq!(knots.len(), 4 + 1 + 6);
        for j in 0..knots.len() - 4 - 1 {
            if j + 5 < knots.len() {
                assert!(((knots[j + 4] - knots[j]) - 1.0).abs() < 1e-15 || j + 4 >= knots.len());
            }
        }
        let even = periodic_knots(&t, 2);
        assert_eq!(&even[2..7], &[0.0, 0.05, 0.25, 0.5, 1.0]);
    }
}

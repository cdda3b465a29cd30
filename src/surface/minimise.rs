//! Minimising on a rectangle: projected Newton steps, and certified lower bounds of a
//! polynomial in tensor-product Bernstein form on `[0, 1]²` where its shape allows one.
//!
//! A certificate ([`certified_minimum`]) is a point `x̂` and a bound `L <= f` on the whole
//! square, in three cases, tried in order:
//!
//! * `f` strictly convex (`f_ss >= a > 0`, `f_tt >= b > 0`, `|f_st| <= c`, `a b > c²` from the
//!   coefficients of the second derivatives): `x̂` from projected Newton, and the first-order
//!   condition of convexity `f(y) >= f(x̂) + ∇f(x̂) · (y − x̂)` minimised over the square,
//!   `L = f(x̂) + Σ_i min(∂_i f(x̂) (0 − x̂_i), ∂_i f(x̂) (1 − x̂_i))`, valid however close `x̂`
//!   came to the minimum;
//! * `f` monotone in one variable (every coefficient of `f_t`, or `f_s`, of one sign): its
//!   minimum lies on the edge where that variable is least for `f`, and that edge's
//!   polynomial (a row or column of coefficients) is bounded in one variable: monotone (the
//!   lower end's value), or strictly convex (the same first-order bound on `[0, 1]`);
//! * otherwise, none.

use super::bernstein2::{Degrees, evaluate_2d, second_derivative_bounds, with_derivatives};

/// A Newton iteration stops after a step of at most this fraction of the box's width.
const NEWTON_STEP_TOLERANCE: f64 = 1e-15;

/// A step may raise the value by this much relative to it (rounding) if it lowers the
/// gradient.
const VALUE_ROUNDING: f64 = 8.0 * f64::EPSILON;

/// Projected Newton iterations at most.
pub(crate) const MAX_NEWTON: usize = 24;

/// A certified minimum on `[0, 1]²` (module docs): `value = f(point) >= bound`, and
/// `f >= bound` everywhere on the square.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Minimum {
    pub(crate) point: [f64; 2],
    pub(crate) value: f64,
    pub(crate) bound: f64,
}

/// The certificate of module docs for `coefficients` of `degrees`, when one of its cases
/// applies.
pub(crate) fn certified_minimum(coefficients: &[f64], degrees: Degrees) -> Option<Minimum> {
    let [ss, tt, st] = second_derivative_bounds(coefficients, degrees);
    if ss > 0.0 && tt > 0.0 && ss * tt > st * st {
        let (point, value, gradient) = projected_newton([0.5, 0.5], [0.0; 2], [1.0; 2], |x| {
            evaluate_2d(coefficients, degrees, x[0], x[1])
        });
        let bound = value
            + (0..2)
                .map(|i| (gradient[i] * -point[i]).min(gradient[i] * (1.0 - point[i])))
                .sum::<f64>();
        return Some(Minimum {
            point,
            value,
            bound,
        });
    }
    let Degrees { m, n } = degrees;
    let at = |i: usize, j: usize| coefficients[i * (n + 1) + j];
    // Monotone in t: the sign of every t-difference; then the edge t = 0 or t = 1.
    let sign = |differences: &mut dyn Iterator<Item = f64>| {
        let (mut up, mut down) = (true, true);
        for d in differences {
            up &= d >= 0.0;
            down &= d <= 0.0;
        }
        (up, down)
    };
    let (up_t, down_t) = sign(
        &mut (0..=m)
            .flat_map(|i| (0..n).map(move |j| (i, j)))
            .map(|(i, j)| at(i, j + 1) - at(i, j)),
    );
    if up_t || down_t {
        let j = if up_t { 0 } else { n };
        let edge: Vec<f64> = (0..=m).map(|i| at(i, j)).collect();
        return edge_minimum(&edge).map(|(s, value, bound)| Minimum {
            point: [s, j as f64 / n.max(1) as f64],
            value,
            bound,
        });
    }
    let (up_s, down_s) = sign(
        &mut (0..m)
            .flat_map(|i| (0..=n).map(move |j| (i, j)))
            .map(|(i, j)| at(i + 1, j) - at(i, j)),
    );
    if up_s || down_s {
        let i = if up_s { 0 } else { m };
        let edge: Vec<f64> = (0..=n).map(|j| at(i, j)).collect();
        return edge_minimum(&edge).map(|(t, value, bound)| Minimum {
            point: [i as f64 / m.max(1) as f64, t],
            value,
            bound,
        });
    }
    None
}

/// Where projected Newton steps on `f` lead from its least coefficient's place
/// `(i / m, j / n)`: a point no higher than that start (no certificate of a minimum).
pub(crate) fn descend(coefficients: &[f64], degrees: Degrees) -> ([f64; 2], f64, [f64; 2]) {
    let Degrees { m, n } = degrees;
    let least = (0..coefficients.len())
        .min_by(|&a, &b| coefficients[a].total_cmp(&coefficients[b]))
        .unwrap_or(0);
    let start = [
        (least / (n + 1)) as f64 / m.max(1) as f64,
        (least % (n + 1)) as f64 / n.max(1) as f64,
    ];
    projected_newton(start, [0.0; 2], [1.0; 2], |x| {
        evaluate_2d(coefficients, degrees, x[0], x[1])
    })
}

/// A certified minimum of a polynomial of one variable on `[0, 1]` with Bernstein
/// `coefficients`: `(x̂, f(x̂), bound)` when it is monotone or strictly convex.
fn edge_minimum(coefficients: &[f64]) -> Option<(f64, f64, f64)> {
    let d = coefficients.len() - 1;
    if coefficients.windows(2).all(|w| w[1] >= w[0]) {
        return Some((0.0, coefficients[0], coefficients[0]));
    }
    if coefficients.windows(2).all(|w| w[1] <= w[0]) {
        return Some((1.0, coefficients[d], coefficients[d]));
    }
    if d >= 2
        && coefficients
            .windows(3)
            .all(|w| w[2] - 2.0 * w[1] + w[0] > 0.0)
    {
        let (point, value, gradient) = projected_newton([0.5, 0.0], [0.0; 2], [1.0, 0.0], |x| {
            let [f, f_x, f_xx] = with_derivatives(coefficients, x[0]);
            (f, [f_x, 0.0], [f_xx, 0.0, 1.0])
        });
        let x = point[0];
        let bound = value + (gradient[0] * -x).min(gradient[0] * (1.0 - x));
        return Some((x, value, bound));
    }
    None
}

/// Projected Newton iteration for a function on the box `[lower, upper]` with value, gradient
/// and Hessian `(f, [f_x, f_y], [f_xx, f_xy, f_yy])`: at each step the variables at a bound
/// with the gradient pointing out of the box are held, the Newton step is taken in the others
/// (a gradient step where the Hessian is not positive there), projected onto the box, and
/// halved while it does not lower `f` (or, within the rounding of `f`, its gradient). Stops after [`MAX_NEWTON`] steps or when a step
/// moves the point by at most [`NEWTON_STEP_TOLERANCE`] of the box. Returns the last point,
/// its value and gradient.
pub(crate) fn projected_newton(
    start: [f64; 2],
    lower: [f64; 2],
    upper: [f64; 2],
    evaluate: impl Fn([f64; 2]) -> (f64, [f64; 2], [f64; 3]),
) -> ([f64; 2], f64, [f64; 2]) {
    let clamp = |x: [f64; 2]| {
        [
            x[0].clamp(lower[0], upper[0]),
            x[1].clamp(lower[1], upper[1]),
        ]
    };
    let width = (upper[0] - lower[0]).max(upper[1] - lower[1]);
    let mut x = clamp(start);
    let (mut f, mut gradient, mut hessian) = evaluate(x);
    for _ in 0..MAX_NEWTON {
        let held = [0, 1].map(|i| {
            (x[i] <= lower[i] && gradient[i] >= 0.0) || (x[i] >= upper[i] && gradient[i] <= 0.0)
        });
        let [hxx, hxy, hyy] = hessian;
        let step = match held {
            [false, false] => {
                let det = hxx * hyy - hxy * hxy;
                if hxx > 0.0 && det > 0.0 {
                    [
                        -(hyy * gradient[0] - hxy * gradient[1]) / det,
                        -(hxx * gradient[1] - hxy * gradient[0]) / det,
                    ]
                } else {
                    descent(gradient, lower, upper)
                }
            }
            [true, false] if hyy > 0.0 => [0.0, -gradient[1] / hyy],
            [false, true] if hxx > 0.0 => [-gradient[0] / hxx, 0.0],
            [true, true] => break,
            [true, false] => descent([0.0, gradient[1]], lower, upper),
            [false, true] => descent([gradient[0], 0.0], lower, upper),
        };
        let mut scale = 1.0;
        let mut moved = 0.0f64;
        for _ in 0..40 {
            let next = clamp([x[0] + scale * step[0], x[1] + scale * step[1]]);
            if next == x {
                break;
            }
            let (g, next_gradient, next_hessian) = evaluate(next);
            // Lower, or as low within rounding with a smaller gradient (near the minimum the
            // values stop telling points apart; the gradient still does).
            let level = g <= f
                || (g <= f + VALUE_ROUNDING * f.abs() && norm2(next_gradient) < norm2(gradient));
            if level {
                moved = (next[0] - x[0]).abs().max((next[1] - x[1]).abs());
                x = next;
                (f, gradient, hessian) = (g, next_gradient, next_hessian);
                break;
            }
            scale *= 0.5;
        }
        if moved <= NEWTON_STEP_TOLERANCE * width {
            break;
        }
    }
    (x, f, gradient)
}

/// `|g|²`.
fn norm2(g: [f64; 2]) -> f64 {
    g[0] * g[0] + g[1] * g[1]
}

/// A steepest-descent step along `−∇f`, as long as the box's diagonal (the line search
/// halves it).
fn descent(gradient: [f64; 2], lower: [f64; 2], upper: [f64; 2]) -> [f64; 2] {
    let length = (gradient[0] * gradient[0] + gradient[1] * gradient[1]).sqrt();
    if length == 0.0 {
        return [0.0; 2];
    }
    let diagonal = ((upper[0] - lower[0]).powi(2) + (upper[1] - lower[1]).powi(2)).sqrt();
    [
        -gradient[0] / length * diagonal,
        -gradient[1] / length * diagonal,
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `f(s, t) = (s − c)² + (t − d)²` in Bernstein form of degrees (2, 2): per variable,
    /// `(x − c)²` has coefficients `c², −c (1 − c), (1 − c)²`; the sum's are
    /// `a_i + b_j` (degree elevation of a constant is itself).
    fn bowl(c: f64, d: f64) -> Vec<f64> {
        let a = [c * c, -c * (1.0 - c), (1.0 - c) * (1.0 - c)];
        let b = [d * d, -d * (1.0 - d), (1.0 - d) * (1.0 - d)];
        (0..9).map(|k| a[k / 3] + b[k % 3]).collect()
    }

    #[test]
    fn a_bowl_inside_and_outside_the_square_is_certified() {
        let degrees = Degrees { m: 2, n: 2 };
        let inside = certified_minimum(&bowl(0.3, 0.8), degrees).unwrap();
        assert!((inside.point[0] - 0.3).abs() < 1e-12 && (inside.point[1] - 0.8).abs() < 1e-12);
        assert!(inside.value.abs() < 1e-15 && inside.bound <= inside.value + 1e-15);
        assert!(inside.bound > -1e-15);
        // Centre outside: the minimum on the square is at (1, 0.5), value 0.25.
        let outside = certified_minimum(&bowl(1.5, 0.5), degrees).unwrap();
        assert!((outside.point[0] - 1.0).abs() < 1e-15 && (outside.point[1] - 0.5).abs() < 1e-12);
        assert!((outside.value - 0.25).abs() < 1e-14);
        assert!(outside.bound <= 0.25 + 1e-14 && outside.bound > 0.25 - 1e-12);
    }

    #[test]
    fn a_saddle_monotone_in_t_is_bounded_on_its_lower_edge() {
        // f(s, t) = (s − 0.4)² − (s − 0.4)² t + 3 t: f_t = 3 − (s − 0.4)² > 0, not convex.
        // Bernstein: degree (2, 1); at t = 0 (s − 0.4)², at t = 1 that plus (3 − (s − 0.4)²).
        let a = [0.16, -0.24, 0.36];
        let coefficients: Vec<f64> = (0..3).flat_map(|i| [a[i], 3.0]).collect();
        let found = certified_minimum(&coefficients, Degrees { m: 2, n: 1 }).unwrap();
        assert!((found.point[0] - 0.4).abs() < 1e-12 && found.point[1] == 0.0);
        assert!(found.value.abs() < 1e-15 && found.bound.abs() < 1e-15);
    }
}

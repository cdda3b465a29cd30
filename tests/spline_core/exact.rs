//! Exact evaluation for judging the evaluator's rounding: de Boor's algorithm in exact rational
//! arithmetic (big integers, `num-bigint`), every `f64` of the input (knots, control points,
//! weights, the parameter) converted exactly, and the same textbook algorithm in `f64`, whose
//! error is the yardstick of "as exact as de Boor".
//!
//! The algorithm: on the span `m` of `t`, the `p + 1` active homogeneous control points
//! `(w d, w)`; for the `k`-th derivative their hodographs
//! `Q^(k)_i = (p - k + 1) (Q^(k-1)_i - Q^(k-1)_{i-1}) / (u_{i+p-k+1} - u_i)` (the coefficients
//! of `N_{i,p-k}`); de Boor of degree `p - k` on those; and the quotient rule on `A = w C`:
//! `C^(k) = (A^(k) - Σ_{i=1..k} binom(k, i) w^(i) C^(k-i)) / w`.
//!
//! Exactly: every `f64` is `m 2^e`; scaled by a common power of two the active knots, the
//! parameter and the control points are integers, and each level of the hodographs and of
//! de Boor keeps one common denominator (the least common multiple of that level's knot
//! differences), so the whole computation is integer multiply-adds without a single gcd of
//! large numbers (a rational library reducing after every operation is about a hundred times
//! slower here).
//!
//! The rule ([`Judge`]): an error is acceptable when it is at most the largest of
//!
//! * `1e-12` of the size: for points the diagonal of the control points' bounding box, for a
//!   derivative its magnitude `M_k` (below);
//! * `4 ×` the error of the textbook algorithm in `f64` at the same parameter;
//! * the rounding floor `(p + 1) · 2^-52 · M_k`, with `M_0` the largest active control point
//!   `|d_i|` and, for `k >= 1`, `M_k` the largest active `|Q^(k)_i|` (non-rational) or the
//!   quotient rule's first-order propagation of errors
//!   `M_k = (|Q^(k)|_xyz + |Q^(k)|_w |C| + Σ_{i=1..k} binom(k, i) |w^(i)| M_{k-i}) / w`
//!   (rational; `|Q^(k)|_xyz`, `|Q^(k)|_w` the largest active homogeneous ones).

use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};

/// A curve as given: degree, full knot vector, control points (`z = 0` in 2D), weights.
#[derive(Debug, Clone)]
pub struct Input {
    pub degree: usize,
    pub knots: Vec<f64>,
    pub points: Vec<[f64; 3]>,
    pub weights: Option<Vec<f64>>,
}

impl Input {
    /// The domain `[u_p, u_{n+1}]`.
    pub fn domain(&self) -> (f64, f64) {
        (self.knots[self.degree], self.knots[self.points.len()])
    }

    /// The span `m` (`p <= m <= n`, `u_m < u_{m+1}`) whose polynomial gives the curve at `t`:
    /// `u_m <= t < u_{m+1}`, and the last non-empty one at (or beyond) the domain's right end.
    pub fn span(&self, t: f64) -> usize {
        let p = self.degree;
        let u = &self.knots;
        let n = self.points.len() - 1;
        if t >= self.domain().1 {
            return (p..=n).rev().find(|&m| u[m] < u[m + 1]).expect("a span");
        }
        (p..=n).find(|&m| u[m] <= t && t < u[m + 1]).unwrap_or(p)
    }

    fn weight(&self, i: usize) -> f64 {
        self.weights.as_ref().map_or(1.0, |w| w[i])
    }
}

/// An exact fraction `num / den`, `den > 0`, kept unreduced (few operations follow).
#[derive(Debug, Clone)]
pub struct Fraction {
    num: BigInt,
    den: BigInt,
}

impl Fraction {
    fn new(num: BigInt, den: BigInt) -> Self {
        if den.is_negative() {
            Fraction {
                num: -num,
                den: -den,
            }
        } else {
            Fraction { num, den }
        }
    }

    /// The exact value of a finite `x`.
    pub fn of(x: f64) -> Self {
        let (mantissa, exponent) = dyadic(x);
        if exponent >= 0 {
            Fraction::new(mantissa << exponent as usize, BigInt::one())
        } else {
            Fraction::new(mantissa, BigInt::one() << (-exponent) as usize)
        }
    }

    /// `self + other` (the surfaces' tensor sums, tests/surface_core/exact.rs).
    #[allow(dead_code)]
    pub fn add(&self, other: &Fraction) -> Fraction {
        Fraction::new(
            &self.num * &other.den + &other.num * &self.den,
            &self.den * &other.den,
        )
    }

    pub fn sub(&self, other: &Fraction) -> Fraction {
        Fraction::new(
            &self.num * &other.den - &other.num * &self.den,
            &self.den * &other.den,
        )
    }

    pub fn mul(&self, other: &Fraction) -> Fraction {
        Fraction::new(&self.num * &other.num, &self.den * &other.den)
    }

    pub fn div(&self, other: &Fraction) -> Fraction {
        Fraction::new(&self.num * &other.den, &self.den * &other.num)
    }

    /// The nearest `f64` (the conversion does not need a reduced fraction).
    pub fn to_f64(&self) -> f64 {
        BigRational::new_raw(self.num.clone(), self.den.clone())
            .to_f64()
            .unwrap_or(f64::NAN)
    }

    /// `|x - self|`, computed exactly and then rounded.
    pub fn distance_to(&self, x: f64) -> f64 {
        Fraction::of(x).sub(self).to_f64().abs()
    }
}

/// `x = mantissa · 2^exponent` exactly (`x` finite).
fn dyadic(x: f64) -> (BigInt, i64) {
    assert!(x.is_finite(), "finite input");
    if x == 0.0 {
        return (BigInt::zero(), 0);
    }
    let bits = x.to_bits();
    let exponent_bits = ((bits >> 52) & 0x7ff) as i64;
    let fraction = bits & ((1u64 << 52) - 1);
    let (mantissa, exponent) = if exponent_bits == 0 {
        (fraction, -1074)
    } else {
        (fraction | (1u64 << 52), exponent_bits - 1075)
    };
    let mantissa = BigInt::from(mantissa);
    (if x < 0.0 { -mantissa } else { mantissa }, exponent)
}

/// Dyadic numbers `m_i 2^(e_i)` as integers `M_i` with one scale: `value_i = M_i 2^scale`.
fn common_scale(values: &[(BigInt, i64)]) -> (Vec<BigInt>, i64) {
    let scale = values
        .iter()
        .filter(|(m, _)| !m.is_zero())
        .map(|&(_, e)| e)
        .min()
        .unwrap_or(0);
    let integers = values
        .iter()
        .map(|(m, e)| m.clone() << (e - scale) as usize)
        .collect();
    (integers, scale)
}

/// The least common multiple of positive integers.
fn lcm_of<'a>(values: impl Iterator<Item = &'a BigInt>) -> BigInt {
    values.fold(BigInt::one(), |l, d| l.lcm(d))
}

/// The exact homogeneous derivatives `A^(k)(t)`, `k = 0..=order` (zero above the degree).
pub fn exact_homogeneous(input: &Input, t: f64, order: usize) -> Vec<[Fraction; 4]> {
    let p = input.degree;
    let m = input.span(t);
    // Knots u_{m-p+1} ..= u_{m+p} (index i at i - (m - p + 1)) and t, as integers.
    let first = m + 1 - p;
    let mut scaled: Vec<(BigInt, i64)> = input.knots[first..=m + p]
        .iter()
        .map(|&u| dyadic(u))
        .collect();
    scaled.push(dyadic(t));
    let (mut knots, knot_scale) = common_scale(&scaled);
    let t_int = knots.pop().expect("t");
    let u = |i: usize| &knots[i - first];
    // The active homogeneous control points as integers (products of two mantissas).
    let mut coordinates = Vec::with_capacity(4 * (p + 1));
    for i in m - p..=m {
        let (mw, ew) = dyadic(input.weight(i));
        for c in 0..3 {
            let (mx, ex) = dyadic(input.points[i][c]);
            coordinates.push((&mx * &mw, ex + ew));
        }
        coordinates.push((mw, ew));
    }
    let (integers, point_scale) = common_scale(&coordinates);
    let mut level: Vec<[BigInt; 4]> = integers
        .chunks(4)
        .map(|c| std::array::from_fn(|i| c[i].clone()))
        .collect();
    // level[l] / den · 2^scale is the exact Q^(k)_{m-p+l}.
    let mut den = BigInt::one();
    let mut scale = point_scale;
    let mut out = Vec::with_capacity(order + 1);
    for k in 0..=order {
        if k > p {
            out.push(std::array::from_fn(|_| Fraction::of(0.0)));
            continue;
        }
        if k > 0 {
            let differences: Vec<BigInt> = (k..=p)
                .map(|l| {
                    let i = m - p + l;
                    u(i + p - k + 1) - u(i)
                })
                .collect();
            let common = lcm_of(differences.iter());
            let factor = BigInt::from(p - k + 1);
            for l in (k..=p).rev() {
                let multiplier = &factor * (&common / &differences[l - k]);
                let previous = level[l - 1].clone();
                for (value, before) in level[l].iter_mut().zip(previous) {
                    *value = (&*value - before) * &multiplier;
                }
            }
            den *= common;
            // Each level divides by knot differences that are `2^knot_scale` times the integers.
            scale -= knot_scale;
        }
        // De Boor of degree q on level[k..=p], one common denominator per level.
        let q = p - k;
        let mut d: Vec<[BigInt; 4]> = level[k..=p].to_vec();
        let mut de_boor_den = BigInt::one();
        for r in 1..=q {
            let widths: Vec<BigInt> = (r..=q).map(|j| u(j + 1 + m - r) - u(j + m - q)).collect();
            let common = lcm_of(widths.iter());
            for j in (r..=q).rev() {
                let lo = u(j + m - q);
                let hi = u(j + 1 + m - r);
                let multiplier = &common / &widths[j - r];
                let after = (&t_int - lo) * &multiplier;
                let before = (hi - &t_int) * &multiplier;
                let previous = d[j - 1].clone();
                for (value, left) in d[j].iter_mut().zip(previous) {
                    *value = &before * left + &after * &*value;
                }
            }
            de_boor_den *= common;
        }
        let total = &den * &de_boor_den;
        out.push(std::array::from_fn(|c| {
            let num = d[q][c].clone();
            if scale >= 0 {
                Fraction::new(num << scale as usize, total.clone())
            } else {
                Fraction::new(num, total.clone() << (-scale) as usize)
            }
        }));
    }
    out
}

/// The exact curve derivatives `C^(k)(t)`, `k = 0..=order`, by the quotient rule.
pub fn exact_derivatives(input: &Input, t: f64, order: usize) -> Vec<[Fraction; 3]> {
    let a = exact_homogeneous(input, t, order);
    let w = a[0][3].clone();
    let mut c: Vec<[Fraction; 3]> = Vec::with_capacity(order + 1);
    for k in 0..=order {
        let mut v: [Fraction; 3] = std::array::from_fn(|x| a[k][x].clone());
        for i in 1..=k {
            let f = Fraction::new(BigInt::from(binomial(k, i) as u64), BigInt::one()).mul(&a[i][3]);
            for (x, value) in v.iter_mut().enumerate() {
                *value = value.sub(&f.mul(&c[k - i][x]));
            }
        }
        c.push(v.map(|x| x.div(&w)));
    }
    c
}

/// The same algorithm in `f64`, with what the rule needs about it.
pub struct Textbook {
    /// `C^(k)(t)`.
    pub values: Vec<[f64; 3]>,
    /// The magnitudes `M_k` (module docs).
    pub magnitudes: Vec<f64>,
    /// A first-order bound of the algorithm's own rounding error (see [`textbook`]).
    pub bounds: Vec<f64>,
}

/// Relative error of one rounding, `2^-53`.
const UNIT: f64 = f64::EPSILON / 2.0;

/// The textbook algorithm in `f64` at `t`, orders `0..=order`, with a running bound of its
/// rounding error (first order in the unit roundoff `u = 2^-53`, Wilkinson's running error
/// analysis): a product `w d` of the input is off by `u |w d|`; a hodograph point
/// `f (a - b) / Δ` by `4 u |Q| + f (δa + δb) / Δ` (three roundings and `Δ`'s own, plus what
/// `a` and `b` bring); de Boor of degree `q` adds `4 u |Q|` per level (a convex combination
/// with a rounded weight) to the largest error of its points; the quotient rule adds
/// `(k + 2) u` of the sizes of its terms and propagates the errors of the lower orders.
pub fn textbook(input: &Input, t: f64, order: usize) -> Textbook {
    let p = input.degree;
    let m = input.span(t);
    let u = &input.knots;
    let rational = input.weights.is_some();
    let xyz = |h: &[f64; 4]| norm3([h[0], h[1], h[2]]);
    let mut level: Vec<[f64; 4]> = (m - p..=m)
        .map(|i| {
            let w = input.weight(i);
            let d = input.points[i];
            [w * d[0], w * d[1], w * d[2], w]
        })
        .collect();
    // Error bounds of each level point, (xyz, w).
    let mut errors: Vec<(f64, f64)> = level
        .iter()
        .map(|h| (if rational { UNIT * xyz(h) } else { 0.0 }, 0.0))
        .collect();
    let mut a = Vec::with_capacity(order + 1);
    let mut a_errors = Vec::with_capacity(order + 1);
    let mut magnitudes = Vec::with_capacity(order + 1);
    for k in 0..=order {
        if k > p {
            a.push([0.0; 4]);
            a_errors.push((0.0, 0.0));
            magnitudes.push((0.0, 0.0));
            continue;
        }
        if k > 0 {
            let factor = (p - k + 1) as f64;
            for l in (k..=p).rev() {
                let i = m - p + l;
                let den = u[i + p - k + 1] - u[i];
                let previous = level[l - 1];
                for (value, before) in level[l].iter_mut().zip(previous) {
                    *value = factor * (*value - before) / den;
                }
                let (ex, ew) = (errors[l], errors[l - 1]);
                errors[l] = (
                    4.0 * UNIT * xyz(&level[l]) + factor * (ex.0 + ew.0) / den,
                    4.0 * UNIT * level[l][3].abs() + factor * (ex.1 + ew.1) / den,
                );
            }
        }
        let active = &level[k..=p];
        let largest_xyz = active.iter().map(xyz).fold(0.0, f64::max);
        let largest_w = active.iter().map(|h| h[3].abs()).fold(0.0, f64::max);
        magnitudes.push((
            if k == 0 {
                // The control points themselves, |w d| / w.
                active.iter().map(|h| xyz(h) / h[3]).fold(0.0, f64::max)
            } else {
                largest_xyz
            },
            largest_w,
        ));
        let q = p - k;
        let mut d = active.to_vec();
        for r in 1..=q {
            for j in (r..=q).rev() {
                let lo = u[j + m - q];
                let alpha = (t - lo) / (u[j + 1 + m - r] - lo);
                let previous = d[j - 1];
                for (value, before) in d[j].iter_mut().zip(previous) {
                    *value = (1.0 - alpha) * before + alpha * *value;
                }
            }
        }
        let propagated = errors[k..=p]
            .iter()
            .fold((0.0f64, 0.0f64), |m, e| (m.0.max(e.0), m.1.max(e.1)));
        a.push(d[q]);
        a_errors.push((
            propagated.0 + 4.0 * q as f64 * UNIT * largest_xyz,
            propagated.1 + 4.0 * q as f64 * UNIT * largest_w,
        ));
    }
    let w = a[0][3];
    let mut c: Vec<[f64; 3]> = Vec::with_capacity(order + 1);
    let mut bounds: Vec<f64> = Vec::with_capacity(order + 1);
    for k in 0..=order {
        let mut v = [a[k][0], a[k][1], a[k][2]];
        let mut terms = xyz(&a[k]);
        let mut error = a_errors[k].0;
        for i in 1..=k {
            let f = binomial(k, i) * a[i][3];
            for (x, value) in v.iter_mut().enumerate() {
                *value -= f * c[k - i][x];
            }
            let lower = norm3(c[k - i]);
            terms += f.abs() * lower;
            error += binomial(k, i) * (a_errors[i].1 * lower + a[i][3].abs() * bounds[k - i]);
        }
        let value = v.map(|x| x / w);
        if rational {
            error =
                (error + (k + 2) as f64 * UNIT * terms + a_errors[0].1 * norm3(value)) / w.abs();
        }
        c.push(value);
        bounds.push(error);
    }
    let magnitudes = if rational {
        let point = norm3(c[0]);
        let mut scales: Vec<f64> = Vec::with_capacity(order + 1);
        for k in 0..=order {
            let (xyz, weight) = magnitudes[k];
            let mut s = if k == 0 {
                xyz
            } else {
                (xyz + weight * point) / w.abs()
            };
            for i in 1..=k {
                s += binomial(k, i) * a[i][3].abs() * scales[k - i] / w.abs();
            }
            scales.push(s);
        }
        scales
    } else {
        magnitudes.iter().map(|&(xyz, _)| xyz).collect()
    };
    Textbook {
        values: c,
        magnitudes,
        bounds,
    }
}

fn binomial(k: usize, i: usize) -> f64 {
    (0..i).fold(1.0, |acc, r| acc * (k - r) as f64 / (r + 1) as f64)
}

fn norm3(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

/// The exact curve and the rule, judging computed points and derivatives.
pub struct Judge {
    input: Input,
    /// Diagonal of the control points' bounding box.
    size: f64,
}

/// How far one computed value is from the exact one, against what the rule allows.
#[derive(Debug, Clone, Copy)]
pub struct Verdict {
    /// `|computed - exact|` (Euclidean).
    pub error: f64,
    /// The rule's allowance (module docs).
    pub allowed: f64,
    /// The textbook `f64` algorithm's error at the same place.
    pub textbook: f64,
    /// The size errors are reported relative to (points: the curve's size; derivatives `M_k`).
    pub scale: f64,
}

impl Verdict {
    pub fn passes(&self) -> bool {
        self.error <= self.allowed
    }

    /// `error / allowed` (0 when both vanish).
    pub fn ratio(&self) -> f64 {
        if self.error == 0.0 {
            0.0
        } else {
            self.error / self.allowed
        }
    }

    /// `error / scale` (0 when the error vanishes).
    pub fn relative(&self) -> f64 {
        if self.error == 0.0 {
            0.0
        } else {
            self.error / self.scale
        }
    }
}

/// The exact values at one parameter, to judge any number of computed ones.
pub struct Exact {
    values: Vec<[Fraction; 3]>,
    textbook_errors: Vec<f64>,
    allowed: Vec<f64>,
    scales: Vec<f64>,
}

impl Exact {
    /// The exact `C^(k)`, rounded.
    pub fn value(&self, k: usize) -> [f64; 3] {
        std::array::from_fn(|c| self.values[k][c].to_f64())
    }

    /// The verdict on `computed = C^(k)(t)`.
    pub fn judge(&self, k: usize, computed: [f64; 3]) -> Verdict {
        Verdict {
            error: distance(&self.values[k], computed),
            allowed: self.allowed[k],
            textbook: self.textbook_errors[k],
            scale: self.scales[k],
        }
    }
}

/// The Euclidean distance from the exact `exact` to `x`.
pub fn distance(exact: &[Fraction; 3], x: [f64; 3]) -> f64 {
    norm3(std::array::from_fn(|c| exact[c].distance_to(x[c])))
}

impl Judge {
    pub fn new(input: &Input) -> Self {
        let mut min = [f64::INFINITY; 3];
        let mut max = [f64::NEG_INFINITY; 3];
        for d in &input.points {
            for c in 0..3 {
                min[c] = min[c].min(d[c]);
                max[c] = max[c].max(d[c]);
            }
        }
        Judge {
            input: input.clone(),
            size: norm3(std::array::from_fn(|c| max[c] - min[c])),
        }
    }

    /// The diagonal of the control points' bounding box.
    pub fn size(&self) -> f64 {
        self.size
    }

    /// The exact derivatives `0..=order` at `t` and the rule's allowances.
    pub fn at(&self, t: f64, order: usize) -> Exact {
        let values = exact_derivatives(&self.input, t, order);
        let textbook = textbook(&self.input, t, order);
        let magnitudes = &textbook.magnitudes;
        let p = self.input.degree;
        let textbook_errors: Vec<f64> = (0..=order)
            .map(|k| distance(&values[k], textbook.values[k]))
            .collect();
        let scales: Vec<f64> = (0..=order)
            .map(|k| if k == 0 { self.size } else { magnitudes[k] })
            .collect();
        let allowed = (0..=order)
            .map(|k| {
                let floor = (p + 1) as f64 * f64::EPSILON * magnitudes[k];
                (1e-12 * scales[k])
                    .max(4.0 * textbook_errors[k])
                    .max(floor)
                    .max(textbook.bounds[k])
            })
            .collect();
        Exact {
            values,
            textbook_errors,
            allowed,
            scales,
        }
    }
}

//! Polynomials in up to three variables in tensor-product Bernstein form on the unit box, with
//! one or more values per coefficient: built exactly from products of affine factors (the
//! unnormalised de Boor recursion), then cut, differentiated, bounded and evaluated by the
//! root isolation ([`super::isolate`]).
//!
//! Construction works in the *scaled* Bernstein basis `(1 - s)^{n-i} s^i` (a coefficient times
//! `C(n, i)`), where a product is a plain convolution of coefficient arrays and raising the
//! degree by one is a convolution with `[1, 1]` (multiplication by `(1 - s) + s`); every
//! operation there is a sum of products of the inputs, so it adds only rounding.
//! [`Tensor::unscaled`] divides by the binomials once at the end. Halving, derivatives,
//! ranges and evaluation work in the ordinary basis: the coefficients of a box bound the
//! polynomial on it (convex hull property).

/// Variables at most.
pub const MAX_VARIABLES: usize = 3;

use smallvec::SmallVec;

/// A polynomial `f: [0, 1]^3 → R^components` in tensor-product Bernstein form (unused
/// variables have degree 0). Coefficient `(i0, i1, i2)` is stored at
/// `((i2 (d1 + 1) + i1) (d0 + 1) + i0) · components`, its values following each other.
#[derive(Debug, Clone, PartialEq)]
pub struct Tensor {
    /// Degree in each variable.
    pub degrees: [usize; MAX_VARIABLES],
    /// Values per coefficient.
    pub components: usize,
    /// The coefficients.
    pub coefficients: Vec<f64>,
}

/// `C(n, k)` as a float (exact for every `n` used here, `n < 128`).
pub fn binomial(n: usize, k: usize) -> f64 {
    if k > n {
        return 0.0;
    }
    let k = k.min(n - k);
    let mut value = 1.0;
    for i in 0..k {
        value = value * (n - i) as f64 / (i + 1) as f64;
    }
    value.round()
}

impl Tensor {
    /// The constant `values` (degree 0 in every variable).
    pub fn constant(values: &[f64]) -> Tensor {
        Tensor {
            degrees: [0; MAX_VARIABLES],
            components: values.len(),
            coefficients: values.to_vec(),
        }
    }

    /// A scalar function that is affine in each variable of `variables` separately and
    /// independent of the others, from its values at the corners of the unit box: these are
    /// its Bernstein coefficients of degree 1 in those variables (scaled or not: `C(1, i) = 1`).
    pub fn multi_affine(
        variables: [bool; MAX_VARIABLES],
        value: impl Fn([f64; 3]) -> f64,
    ) -> Tensor {
        let degrees = variables.map(usize::from);
        let mut coefficients = Vec::with_capacity(8);
        for i2 in 0..=degrees[2] {
            for i1 in 0..=degrees[1] {
                for i0 in 0..=degrees[0] {
                    coefficients.push(value([i0 as f64, i1 as f64, i2 as f64]));
                }
            }
        }
        Tensor {
            degrees,
            components: 1,
            coefficients,
        }
    }

    /// Coefficients per variable, `d_k + 1`.
    fn extents(&self) -> [usize; MAX_VARIABLES] {
        self.degrees.map(|d| d + 1)
    }

    /// How many coefficients.
    pub fn len(&self) -> usize {
        self.extents().iter().product()
    }

    /// Whether it has no coefficient (never: a degree-0 tensor has one).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Flat coefficient index of `(i0, i1, i2)` (times `components` for the storage offset).
    fn index(&self, i: [usize; MAX_VARIABLES]) -> usize {
        let e = self.extents();
        (i[2] * e[1] + i[1]) * e[0] + i[0]
    }

    /// Scaled basis: the product `scalar · self` (`scalar` has one component), degrees added.
    pub fn times(&self, scalar: &Tensor) -> Tensor {
        debug_assert_eq!(scalar.components, 1);
        let c = self.components;
        let degrees = [0, 1, 2].map(|k| self.degrees[k] + scalar.degrees[k]);
        let mut out = Tensor {
            degrees,
            components: c,
            coefficients: vec![0.0; degrees.iter().map(|d| d + 1).product::<usize>() * c],
        };
        let (ea, eb) = (scalar.extents(), self.extents());
        for a2 in 0..ea[2] {
            for a1 in 0..ea[1] {
                for a0 in 0..ea[0] {
                    let factor = scalar.coefficients[scalar.index([a0, a1, a2])];
                    if factor == 0.0 {
                        continue;
                    }
                    for b2 in 0..eb[2] {
                        for b1 in 0..eb[1] {
                            let row_in = self.index([0, b1, b2]) * c;
                            let row_out = out.index([a0, a1 + b1, a2 + b2]) * c;
                            for v in 0..eb[0] * c {
                                out.coefficients[row_out + v] +=
                                    factor * self.coefficients[row_in + v];
                            }
                        }
                    }
                }
            }
        }
        out
    }

    /// Scaled basis: the same polynomial written with degrees `degrees` (each at least the
    /// current one): one convolution with `[1, 1]` per added degree.
    pub fn raised_to(&self, degrees: [usize; MAX_VARIABLES]) -> Tensor {
        let mut out = self.clone();
        for k in 0..MAX_VARIABLES {
            debug_assert!(degrees[k] >= self.degrees[k]);
            while out.degrees[k] < degrees[k] {
                out = out.raised_once(k);
            }
        }
        out
    }

    /// Scaled basis: degree in `variable` raised by one.
    fn raised_once(&self, variable: usize) -> Tensor {
        let mut degrees = self.degrees;
        degrees[variable] += 1;
        let c = self.components;
        let mut out = Tensor {
            degrees,
            components: c,
            coefficients: vec![0.0; degrees.iter().map(|d| d + 1).product::<usize>() * c],
        };
        let e = self.extents();
        for i2 in 0..e[2] {
            for i1 in 0..e[1] {
                for i0 in 0..e[0] {
                    let from = self.index([i0, i1, i2]) * c;
                    let mut at = [i0, i1, i2];
                    for shift in 0..2 {
                        at[variable] = [i0, i1, i2][variable] + shift;
                        let to = out.index(at) * c;
                        for v in 0..c {
                            out.coefficients[to + v] += self.coefficients[from + v];
                        }
                    }
                }
            }
        }
        out
    }

    /// Scaled basis: `self + other`, both raised to the larger degrees.
    pub fn plus(&self, other: &Tensor) -> Tensor {
        debug_assert_eq!(self.components, other.components);
        let degrees = [0, 1, 2].map(|k| self.degrees[k].max(other.degrees[k]));
        let mut out = self.raised_to(degrees);
        let other = other.raised_to(degrees);
        for (o, v) in out.coefficients.iter_mut().zip(&other.coefficients) {
            *o += v;
        }
        out
    }

    /// The scalar component combination `Σ_c weights[c] · component_c` (any basis).
    pub fn combine(&self, weights: &[f64]) -> Tensor {
        debug_assert_eq!(weights.len(), self.components);
        let coefficients = self
            .coefficients
            .chunks_exact(self.components)
            .map(|values| values.iter().zip(weights).map(|(v, w)| v * w).sum())
            .collect();
        Tensor {
            degrees: self.degrees,
            components: 1,
            coefficients,
        }
    }

    /// Stacks scalar tensors of equal degrees as the components of one tensor.
    pub fn stack(parts: &[Tensor]) -> Tensor {
        let degrees = parts[0].degrees;
        let count = parts[0].len();
        let mut coefficients = Vec::with_capacity(count * parts.len());
        for i in 0..count {
            for part in parts {
                debug_assert_eq!(part.degrees, degrees);
                coefficients.push(part.coefficients[i]);
            }
        }
        Tensor {
            degrees,
            components: parts.len(),
            coefficients,
        }
    }

    /// From the scaled to the ordinary Bernstein basis: coefficient `(i0, i1, i2)` divided by
    /// `C(d0, i0) C(d1, i1) C(d2, i2)`.
    pub fn unscaled(mut self) -> Tensor {
        let e = self.extents();
        let c = self.components;
        let table: [Vec<f64>; MAX_VARIABLES] = [0, 1, 2].map(|k| {
            (0..e[k])
                .map(|i| 1.0 / binomial(self.degrees[k], i))
                .collect()
        });
        for i2 in 0..e[2] {
            for i1 in 0..e[1] {
                for i0 in 0..e[0] {
                    let factor = table[0][i0] * table[1][i1] * table[2][i2];
                    let at = self.index([i0, i1, i2]) * c;
                    for v in &mut self.coefficients[at..at + c] {
                        *v *= factor;
                    }
                }
            }
        }
        self
    }

    /// From the ordinary to the scaled basis (inverse of [`Tensor::unscaled`]), to multiply.
    pub fn scaled(mut self) -> Tensor {
        let e = self.extents();
        let c = self.components;
        let table: [Vec<f64>; MAX_VARIABLES] =
            [0, 1, 2].map(|k| (0..e[k]).map(|i| binomial(self.degrees[k], i)).collect());
        for i2 in 0..e[2] {
            for i1 in 0..e[1] {
                for i0 in 0..e[0] {
                    let factor = table[0][i0] * table[1][i1] * table[2][i2];
                    let at = self.index([i0, i1, i2]) * c;
                    for v in &mut self.coefficients[at..at + c] {
                        *v *= factor;
                    }
                }
            }
        }
        self
    }

    /// Ordinary basis, one variable: `f / s^k` (`at_start`) or `f / (1 - s)^k`, for `f` with
    /// that factor (its first, or last, `k` coefficients zero up to rounding, which is
    /// dropped): `B_{i+k}^n = s^k B_i^{n-k} C(n, i+k) / C(n-k, i)`.
    pub fn divided_at_end(&self, k: usize, at_start: bool) -> Tensor {
        let n = self.degrees[0];
        let c = self.components;
        if k == 0 || k > n {
            return self.clone();
        }
        let m = n - k;
        let mut coefficients = Vec::with_capacity((m + 1) * c);
        for i in 0..=m {
            let (source, factor) = if at_start {
                (i + k, binomial(n, i + k) / binomial(m, i))
            } else {
                (i, binomial(n, i) / binomial(m, i))
            };
            for v in 0..c {
                coefficients.push(self.coefficients[source * c + v] * factor);
            }
        }
        Tensor {
            degrees: [m, 0, 0],
            components: c,
            coefficients,
        }
    }

    /// Ordinary basis: the two parts `s_k ∈ [0, at]` and `[at, 1]`, each on its own unit box
    /// (de Casteljau at `at` along `variable`).
    pub fn split(&self, variable: usize, at: f64) -> (Tensor, Tensor) {
        let mut left = Tensor {
            degrees: self.degrees,
            components: self.components,
            coefficients: vec![0.0; self.coefficients.len()],
        };
        let mut right = left.clone();
        let e = self.extents();
        let c = self.components;
        let d = self.degrees[variable];
        let mut fiber: SmallVec<[f64; 64]> = SmallVec::from_elem(0.0, (d + 1) * c);
        let others: [usize; 2] = match variable {
            0 => [1, 2],
            1 => [0, 2],
            _ => [0, 1],
        };
        let mut stride = [1usize; MAX_VARIABLES];
        stride[1] = e[0];
        stride[2] = e[0] * e[1];
        let step = stride[variable] * c;
        for j1 in 0..e[others[1]] {
            for j0 in 0..e[others[0]] {
                let base = (j0 * stride[others[0]] + j1 * stride[others[1]]) * c;
                for i in 0..=d {
                    let from = base + i * step;
                    fiber[i * c..(i + 1) * c].copy_from_slice(&self.coefficients[from..from + c]);
                }
                // Row r of de Casteljau's triangle: fiber[0] is left's r-th, fiber[d - r]
                // right's (d - r)-th coefficient.
                for v in 0..c {
                    left.coefficients[base + v] = fiber[v];
                    right.coefficients[base + d * step + v] = fiber[d * c + v];
                }
                for r in 1..=d {
                    for i in 0..=d - r {
                        for v in 0..c {
                            fiber[i * c + v] += at * (fiber[(i + 1) * c + v] - fiber[i * c + v]);
                        }
                    }
                    for v in 0..c {
                        left.coefficients[base + r * step + v] = fiber[v];
                        right.coefficients[base + (d - r) * step + v] = fiber[(d - r) * c + v];
                    }
                }
            }
        }
        (left, right)
    }

    /// Ordinary basis: the part `s_k ∈ [a, b]` of `variable` on its own unit box (de
    /// Casteljau at `b`, keeping the left part, then at `a / b`, keeping the right one).
    pub fn part(&self, variable: usize, a: f64, b: f64) -> Tensor {
        let mut out = self.clone();
        let e = self.extents();
        let c = self.components;
        let d = self.degrees[variable];
        let mut stride = [1usize; MAX_VARIABLES];
        stride[1] = e[0];
        stride[2] = e[0] * e[1];
        let step = stride[variable] * c;
        let others: [usize; 2] = match variable {
            0 => [1, 2],
            1 => [0, 2],
            _ => [0, 1],
        };
        let cut_right = b < 1.0;
        let cut_left = a > 0.0;
        let at_left = if cut_right { a / b } else { a };
        let mut fiber: SmallVec<[f64; 64]> = SmallVec::from_elem(0.0, (d + 1) * c);
        for j1 in 0..e[others[1]] {
            for j0 in 0..e[others[0]] {
                let base = (j0 * stride[others[0]] + j1 * stride[others[1]]) * c;
                for i in 0..=d {
                    let from = base + i * step;
                    fiber[i * c..(i + 1) * c].copy_from_slice(&self.coefficients[from..from + c]);
                }
                if cut_right {
                    // Left part at b: the first entries of each row of the triangle.
                    let mut left: SmallVec<[f64; 64]> = SmallVec::from_elem(0.0, (d + 1) * c);
                    left[..c].copy_from_slice(&fiber[..c]);
                    for r in 1..=d {
                        for i in 0..=d - r {
                            for v in 0..c {
                                fiber[i * c + v] += b * (fiber[(i + 1) * c + v] - fiber[i * c + v]);
                            }
                        }
                        left[r * c..(r + 1) * c].copy_from_slice(&fiber[..c]);
                    }
                    fiber.copy_from_slice(&left);
                }
                if cut_left {
                    // Right part at a/b: the last entries of each row.
                    let mut right: SmallVec<[f64; 64]> = SmallVec::from_elem(0.0, (d + 1) * c);
                    right[d * c..].copy_from_slice(&fiber[d * c..]);
                    for r in 1..=d {
                        for i in 0..=d - r {
                            for v in 0..c {
                                fiber[i * c + v] +=
                                    at_left * (fiber[(i + 1) * c + v] - fiber[i * c + v]);
                            }
                        }
                        right[(d - r) * c..(d - r + 1) * c]
                            .copy_from_slice(&fiber[(d - r) * c..(d - r + 1) * c]);
                    }
                    fiber.copy_from_slice(&right);
                }
                for i in 0..=d {
                    let to = base + i * step;
                    out.coefficients[to..to + c].copy_from_slice(&fiber[i * c..(i + 1) * c]);
                }
            }
        }
        out
    }

    /// Ordinary basis: for each component, the range of the derivative with respect to
    /// `variable` on this unit box — the smallest and largest of `d (c_{i+1} - c_i)` —
    /// written to `out[..components]` (zero for a degree-0 variable).
    pub fn derivative_ranges(&self, variable: usize, out: &mut [(f64, f64)]) {
        let d = self.degrees[variable];
        let c = self.components;
        for range in out.iter_mut().take(c) {
            *range = if d == 0 {
                (0.0, 0.0)
            } else {
                (f64::INFINITY, f64::NEG_INFINITY)
            };
        }
        if d == 0 {
            return;
        }
        let e = self.extents();
        let mut stride = [1usize; MAX_VARIABLES];
        stride[1] = e[0];
        stride[2] = e[0] * e[1];
        let step = stride[variable] * c;
        let scale = d as f64;
        for i2 in 0..e[2] {
            for i1 in 0..e[1] {
                for i0 in 0..e[0] {
                    if [i0, i1, i2][variable] == d {
                        continue;
                    }
                    let at = (i0 + i1 * stride[1] + i2 * stride[2]) * c;
                    for (v, range) in out.iter_mut().enumerate().take(c) {
                        let slope =
                            scale * (self.coefficients[at + step + v] - self.coefficients[at + v]);
                        range.0 = range.0.min(slope);
                        range.1 = range.1.max(slope);
                    }
                }
            }
        }
    }

    /// Ordinary basis: the derivative with respect to `variable` on this unit box,
    /// `d (c_{i+1} - c_i)` (degree one less; a degree-0 variable gives zero).
    pub fn derivative(&self, variable: usize) -> Tensor {
        let d = self.degrees[variable];
        let c = self.components;
        if d == 0 {
            return Tensor {
                degrees: self.degrees,
                components: c,
                coefficients: vec![0.0; self.coefficients.len()],
            };
        }
        let mut degrees = self.degrees;
        degrees[variable] = d - 1;
        let mut out = Tensor {
            degrees,
            components: c,
            coefficients: vec![0.0; degrees.iter().map(|d| d + 1).product::<usize>() * c],
        };
        let e = out.extents();
        for i2 in 0..e[2] {
            for i1 in 0..e[1] {
                for i0 in 0..e[0] {
                    let at = [i0, i1, i2];
                    let mut next = at;
                    next[variable] += 1;
                    let (to, lo, hi) =
                        (out.index(at) * c, self.index(at) * c, self.index(next) * c);
                    for v in 0..c {
                        out.coefficients[to + v] =
                            d as f64 * (self.coefficients[hi + v] - self.coefficients[lo + v]);
                    }
                }
            }
        }
        out
    }

    /// Ordinary basis: the smallest and largest coefficient of component `component`, which
    /// bound its values on the box.
    pub fn range(&self, component: usize) -> (f64, f64) {
        self.coefficients
            .iter()
            .skip(component)
            .step_by(self.components)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
                (lo.min(v), hi.max(v))
            })
    }

    /// Ordinary basis: the largest coefficient magnitude of component `component`.
    pub fn magnitude(&self, component: usize) -> f64 {
        let (lo, hi) = self.range(component);
        lo.abs().max(hi.abs())
    }

    /// Ordinary basis: the values at `s` in the unit box (de Casteljau along each variable),
    /// written to `out[..components]`.
    pub fn evaluate(&self, s: [f64; MAX_VARIABLES], out: &mut [f64]) {
        let c = self.components;
        let e = self.extents();
        // Reduce variable 0, then 1, then 2, in a scratch copy: after each variable the
        // first coefficient of every fiber along it remains, and those are the next
        // variable's fibers.
        let mut work: SmallVec<[f64; 512]> = SmallVec::from_slice(&self.coefficients);
        let mut rows = e[1] * e[2];
        let mut length = e[0];
        for (k, &x) in s.iter().enumerate() {
            let d = self.degrees[k];
            for row in 0..rows {
                let base = row * length * c;
                for r in 1..=d {
                    for i in 0..=d - r {
                        for v in 0..c {
                            let a = work[base + i * c + v];
                            let b = work[base + (i + 1) * c + v];
                            work[base + i * c + v] = a + x * (b - a);
                        }
                    }
                }
                // Compact: fiber `row`'s first coefficient moves to position `row`.
                for v in 0..c {
                    work[row * c + v] = work[base + v];
                }
            }
            if k + 1 < MAX_VARIABLES {
                length = e[k + 1];
                rows /= length;
            }
        }
        out[..c].copy_from_slice(&work[..c]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The polynomial value by brute force: `Σ b_i B_i(s)` with the basis written out.
    fn brute(t: &Tensor, s: [f64; 3]) -> Vec<f64> {
        let e = t.extents();
        let basis = |d: usize, i: usize, x: f64| {
            binomial(d, i) * x.powi(i as i32) * (1.0 - x).powi((d - i) as i32)
        };
        let mut out = vec![0.0; t.components];
        for i2 in 0..e[2] {
            for i1 in 0..e[1] {
                for i0 in 0..e[0] {
                    let b = basis(t.degrees[0], i0, s[0])
                        * basis(t.degrees[1], i1, s[1])
                        * basis(t.degrees[2], i2, s[2]);
                    for v in 0..t.components {
                        out[v] += b * t.coefficients[t.index([i0, i1, i2]) * t.components + v];
                    }
                }
            }
        }
        out
    }

    fn linear(variable: usize, at0: f64, at1: f64) -> Tensor {
        let mut mask = [false; 3];
        mask[variable] = true;
        Tensor::multi_affine(mask, |s| at0 + s[variable] * (at1 - at0))
    }

    #[test]
    fn products_and_sums_in_the_scaled_basis_equal_the_pointwise_ones() {
        // f = (1 + 2 s0)(3 - s1)(2 + s2 s0) + (0.5 - s1)^2, evaluated at a few points.
        let a = linear(0, 1.0, 3.0);
        let b = linear(1, 3.0, 2.0);
        let c = Tensor::multi_affine([true, false, true], |s| 2.0 + s[2] * s[0]);
        let d = linear(1, 0.5, -0.5);
        let f = c.times(&b).times(&a).plus(&d.times(&d)).unscaled();
        for s in [
            [0.0f64, 0.0, 0.0],
            [0.3, 0.7, 0.2],
            [1.0, 0.25, 0.9],
            [0.5, 1.0, 1.0],
        ] {
            let exact =
                (1.0 + 2.0 * s[0]) * (3.0 - s[1]) * (2.0 + s[2] * s[0]) + (0.5 - s[1]).powi(2);
            let mut value = [0.0];
            f.evaluate(s, &mut value);
            assert!(
                (value[0] - exact).abs() < 1e-13,
                "{s:?}: {} vs {exact}",
                value[0]
            );
            assert!((brute(&f, s)[0] - exact).abs() < 1e-13);
        }
    }

    #[test]
    fn parts_derivatives_and_ranges_agree_with_the_polynomial() {
        let a = linear(0, -1.0, 2.0);
        let b = linear(1, 0.5, -1.5);
        let f = a
            .times(&a)
            .times(&b)
            .plus(&Tensor::constant(&[0.25]))
            .unscaled();
        let value = |s: [f64; 3]| (-1.0 + 3.0 * s[0]).powi(2) * (0.5 - 2.0 * s[1]) + 0.25;
        for variable in 0..2 {
            let (left, right) = f.split(variable, 0.5);
            let middle = f.part(variable, 0.25, 0.75);
            for s in [[0.1, 0.6, 0.0], [0.9, 0.3, 0.0]] {
                let mut inner = s;
                inner[variable] = 0.25 + 0.5 * s[variable];
                assert!((brute(&middle, s)[0] - value(inner)).abs() < 1e-13);
            }
            for s in [[0.2, 0.9, 0.0], [0.75, 0.1, 0.0]] {
                let mut inner = s;
                inner[variable] = 0.5 * s[variable];
                assert!((brute(&left, s)[0] - value(inner)).abs() < 1e-13);
                inner[variable] = 0.5 + 0.5 * s[variable];
                assert!((brute(&right, s)[0] - value(inner)).abs() < 1e-13);
            }
            // Derivative against a central difference.
            let derivative = f.derivative(variable);
            let s = [0.37, 0.61, 0.0];
            let h = 1e-6;
            let (mut up, mut down) = (s, s);
            up[variable] += h;
            down[variable] -= h;
            let fd = (value(up) - value(down)) / (2.0 * h);
            assert!((brute(&derivative, s)[0] - fd).abs() < 1e-7);
        }
        let (lo, hi) = f.range(0);
        for i in 0..=20 {
            for j in 0..=20 {
                let v = value([i as f64 / 20.0, j as f64 / 20.0, 0.0]);
                assert!(v >= lo - 1e-12 && v <= hi + 1e-12);
            }
        }
    }

    #[test]
    fn a_factor_at_an_end_divides_out() {
        // f = s^2 (1 + 2 s) and g = (1 - s)^3 (2 - s).
        let s = linear(0, 0.0, 1.0);
        let one_minus = linear(0, 1.0, 0.0);
        let f = s.times(&s).times(&linear(0, 1.0, 3.0)).unscaled();
        let g = one_minus
            .times(&one_minus)
            .times(&one_minus)
            .times(&linear(0, 2.0, 1.0))
            .unscaled();
        for (tensor, at_start, k, rest) in [
            (
                f,
                true,
                2,
                Box::new(|x: f64| 1.0 + 2.0 * x) as Box<dyn Fn(f64) -> f64>,
            ),
            (g, false, 3, Box::new(|x: f64| 2.0 - x)),
        ] {
            let divided = tensor.divided_at_end(k, at_start);
            assert_eq!(divided.degrees[0], 1);
            for x in [0.0, 0.3, 1.0] {
                let mut v = [0.0];
                divided.evaluate([x, 0.0, 0.0], &mut v);
                assert!(
                    (v[0] - rest(x)).abs() < 1e-14,
                    "{x}: {} vs {}",
                    v[0],
                    rest(x)
                );
            }
        }
    }

    #[test]
    fn binomials_are_exact() {
        assert_eq!(binomial(10, 3), 120.0);
        assert_eq!(binomial(40, 20), 137846528820.0);
        assert_eq!(binomial(3, 5), 0.0);
    }
}

//! The six knot pairs Ω1–Ω6 and their closed-form solutions (docs/method.md §4, paper §3.1–3.2).
//!
//! Every pair solves the paper's equations (2) for two of the four knots `a, b, c, e`
//! around the moved knot, the other two staying fixed:
//!
//! ```text
//! x = (c - t)^2 / ((c - a)(c - b))        y = (t - b)^2 / ((e - b)(c - b))
//! ```
//!
//! under the monotonicity condition `L <= a <= b <= t <= c <= e <= R`, `c > b`. Each pair
//! reduces to at most one quadratic; there is no iterative root finding.

/// A solved knot within `KNOT_TOLERANCE · (R - L)` of its old value keeps its old value
/// exactly (so unchanged knots are bit-identical and not reported as changed).
pub const KNOT_TOLERANCE: f64 = 1e-12;

/// Relative tolerance of the monotonicity condition: a root may violate a bound by at most
/// `CLAMP_TOLERANCE · (R - L)`; it is then clamped onto the bound. Near a region's edge the
/// rounding of the target's frame is amplified (e.g. `∂e/∂y = -(e-b)/y`), so this is looser
/// than rounding; the solver keeps a clamped root only if the new curve still lands on the
/// target ([`crate::shape::RESIDUAL_TOLERANCE`]).
pub const CLAMP_TOLERANCE: f64 = 1e-8;

/// Frame coordinates with `|x| <= FRAME_ZERO_TOLERANCE` (likewise `y`) count as exactly 0, and
/// within it of 1 as exactly 1, so that targets on the triangle's edges and vertices meet the
/// forced cases `c = t` (x = 0), `b = t` (y = 0) despite rounding.
pub const FRAME_ZERO_TOLERANCE: f64 = 1e-12;

/// One of the six knot pairs: which two of `a = v_{j-1}`, `b = v_j`, `c = v_{j+1}`,
/// `e = v_{j+2}` move. Its region `Ω_r` is the set of targets it reaches.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum KnotPair {
    /// `(a, b) = (v_{j-1}, v_j)`, consecutive (paper §3.1).
    Omega1,
    /// `(b, c) = (v_j, v_{j+1})`, consecutive (paper §3.1).
    Omega2,
    /// `(c, e) = (v_{j+1}, v_{j+2})`, consecutive (paper §3.1).
    Omega3,
    /// `(a, c) = (v_{j-1}, v_{j+1})`, non-consecutive (paper §3.2.1).
    Omega4,
    /// `(a, e) = (v_{j-1}, v_{j+2})`, non-consecutive (paper §3.2.2).
    Omega5,
    /// `(b, e) = (v_j, v_{j+2})`, non-consecutive (paper §3.2.3).
    Omega6,
}

/// One of the four knots around the moved one.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LocalKnot {
    /// `a = v_{j-1} = u_{j-1}`.
    A,
    /// `b = v_j = u_j`.
    B,
    /// `c = v_{j+1} = u_{j+2}`.
    C,
    /// `e = v_{j+2} = u_{j+3}`.
    E,
}

impl LocalKnot {
    /// Its full-vector index for span `j`.
    pub fn full_index(self, span: usize) -> usize {
        match self {
            LocalKnot::A => span - 1,
            LocalKnot::B => span,
            LocalKnot::C => span + 2,
            LocalKnot::E => span + 3,
        }
    }
}

impl KnotPair {
    /// All six, in order.
    pub const ALL: [KnotPair; 6] = [
        KnotPair::Omega1,
        KnotPair::Omega2,
        KnotPair::Omega3,
        KnotPair::Omega4,
        KnotPair::Omega5,
        KnotPair::Omega6,
    ];

    /// The wire name: `"omega1"` ..= `"omega6"`.
    pub fn name(self) -> &'static str {
        match self {
            KnotPair::Omega1 => "omega1",
            KnotPair::Omega2 => "omega2",
            KnotPair::Omega3 => "omega3",
            KnotPair::Omega4 => "omega4",
            KnotPair::Omega5 => "omega5",
            KnotPair::Omega6 => "omega6",
        }
    }

    /// The two knots that move.
    pub fn unknowns(self) -> [LocalKnot; 2] {
        match self {
            KnotPair::Omega1 => [LocalKnot::A, LocalKnot::B],
            KnotPair::Omega2 => [LocalKnot::B, LocalKnot::C],
            KnotPair::Omega3 => [LocalKnot::C, LocalKnot::E],
            KnotPair::Omega4 => [LocalKnot::A, LocalKnot::C],
            KnotPair::Omega5 => [LocalKnot::A, LocalKnot::E],
            KnotPair::Omega6 => [LocalKnot::B, LocalKnot::E],
        }
    }
}

/// The knots around the moved one for span `j` and the picked parameter `t`:
/// `L = u_{j-2}`, `a = u_{j-1}`, `b = u_j`, (`u_{j+1}` := `t`), `c = u_{j+2}`, `e = u_{j+3}`,
/// `R = u_{j+4}`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LocalKnots {
    /// Fixed lower bound `L = v_{j-2}`.
    pub l: f64,
    /// `a = v_{j-1}`.
    pub a: f64,
    /// `b = v_j`.
    pub b: f64,
    /// The picked parameter `t` (the moved knot's new value).
    pub t: f64,
    /// `c = v_{j+1}`.
    pub c: f64,
    /// `e = v_{j+2}`.
    pub e: f64,
    /// Fixed upper bound `R = v_{j+3}`.
    pub r: f64,
}

impl LocalKnots {
    /// Reads the local knots of span `j` from a full cubic knot vector (`2 <= j`, `j + 4 < len`).
    pub fn from_full(knots: &[f64], span: usize, t: f64) -> LocalKnots {
        LocalKnots {
            l: knots[span - 2],
            a: knots[span - 1],
            b: knots[span],
            t,
            c: knots[span + 2],
            e: knots[span + 3],
            r: knots[span + 4],
        }
    }

    /// The value of one of the four local knots.
    pub fn get(&self, knot: LocalKnot) -> f64 {
        match knot {
            LocalKnot::A => self.a,
            LocalKnot::B => self.b,
            LocalKnot::C => self.c,
            LocalKnot::E => self.e,
        }
    }

    /// The frame coordinates `(x, y)` that these knots give (equations (2)): the quadratic
    /// envelope's basis values `N_{j-2}^3(t)`, `N_j^3(t)`. Precondition: `c > b`.
    pub fn frame(&self) -> (f64, f64) {
        let (a, b, c, e, t) = (self.a, self.b, self.c, self.e, self.t);
        let x = (c - t) * (c - t) / ((c - a) * (c - b));
        let y = (t - b) * (t - b) / ((e - b) * (c - b));
        (x, y)
    }
}

/// The value of one unknown, from an equation that may leave it undetermined.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Unknown {
    /// The equation fixes it.
    Value(f64),
    /// The equation holds for every value (`0 = 0`): keep the old value, clamped into range.
    Free,
}

/// `a` from the x-equation with `b, c` known: `a = c - (c-t)^2 / (x (c - b))`.
/// `x = 0` forces `c = t` and then leaves `a` free.
fn a_from_x(x: f64, k: &LocalKnots, b: f64, c: f64) -> Option<Unknown> {
    if x == 0.0 {
        return (c == k.t).then_some(Unknown::Free);
    }
    Some(Unknown::Value(c - (c - k.t) * (c - k.t) / (x * (c - b))))
}

/// `b` from the x-equation with `a, c` known: `b = c - (c-t)^2 / (x (c - a))`.
/// `x = 0` forces `c = t` and then leaves `b` free.
fn b_from_x(x: f64, k: &LocalKnots, a: f64, c: f64) -> Option<Unknown> {
    if x == 0.0 {
        return (c == k.t).then_some(Unknown::Free);
    }
    (c > a).then(|| Unknown::Value(c - (c - k.t) * (c - k.t) / (x * (c - a))))
}

/// `c` from the y-equation with `b, e` known: `c = b + (t-b)^2 / (y (e - b))`.
/// `y = 0` forces `b = t` and then leaves `c` free.
fn c_from_y(y: f64, k: &LocalKnots, b: f64, e: f64) -> Option<Unknown> {
    if y == 0.0 {
        return (b == k.t).then_some(Unknown::Free);
    }
    (e > b).then(|| Unknown::Value(b + (k.t - b) * (k.t - b) / (y * (e - b))))
}

/// `e` from the y-equation with `b, c` known: `e = b + (t-b)^2 / (y (c - b))`.
/// `y = 0` forces `b = t` and then leaves `e` free.
fn e_from_y(y: f64, k: &LocalKnots, b: f64, c: f64) -> Option<Unknown> {
    if y == 0.0 {
        return (b == k.t).then_some(Unknown::Free);
    }
    (c > b).then(|| Unknown::Value(b + (k.t - b) * (k.t - b) / (y * (c - b))))
}

/// How far a free knot may move from `t` before the knot that depends on it leaves its range
/// (which has `room` between `t` and its bound): `room · w / (1 - w)` for `w < 1` (unbounded at `w = 1`). When there is no room
/// (the bound equals `t`), the clamp tolerance `slack` stands in for it, so that rounding in
/// `w` near 1 does not empty the interval; otherwise the exact room is used, so the dependent
/// knot lands on its bound exactly.
fn free_reach(room: f64, w: f64, slack: f64) -> f64 {
    if w >= 1.0 {
        return f64::INFINITY;
    }
    let room = if room > 0.0 { room } else { slack };
    room * w / (1.0 - w)
}

/// A free knot's value in `(lo, hi]`: its old value when inside, else the nearest admissible
/// one (`hi`, or the midpoint when the old value is at the open end). `None` when empty.
fn choose_free_above(old: f64, lo: f64, hi: f64) -> Option<f64> {
    if hi <= lo {
        None
    } else if old > hi {
        Some(hi)
    } else if old > lo {
        Some(old)
    } else {
        Some(0.5 * (lo + hi))
    }
}

/// A free knot's value in `[lo, hi)`: its old value when inside, else the nearest admissible
/// one (`lo`, or the midpoint when the old value is at the open end). `None` when empty.
fn choose_free_below(old: f64, lo: f64, hi: f64) -> Option<f64> {
    if hi <= lo {
        None
    } else if old < lo {
        Some(lo)
    } else if old < hi {
        Some(old)
    } else {
        Some(0.5 * (lo + hi))
    }
}

/// Coefficients (normalised as below) at most this large count as zero.
const COEFFICIENT_ZERO: f64 = 1e-13;

/// A discriminant `D = B² - 4AC` with `|D| <= DISCRIMINANT_ROUNDING · (B² + |4AC|)` counts
/// as 0 (a double root).
const DISCRIMINANT_ROUNDING: f64 = 1e-14;

/// The real roots of a quadratic, or every value when it vanishes identically.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Roots {
    /// The listed roots (0, 1 or 2 of them).
    Some([f64; 2], usize),
    /// `0 = 0`: the unknown is left free.
    All,
}

/// Roots of `A z^2 + B z + C = 0` where `z` is a knot offset of typical size `scale`.
///
/// The coefficients are normalised to `A`, `B / scale`, `C / scale^2` (all dimensionless);
/// all three within [`COEFFICIENT_ZERO`] of 0 means the equation holds for every `z`.
/// Otherwise the numerically stable formula `q = -(B + sign(B) √D) / 2`, roots `q / A` and
/// `C / q`; `A = 0` makes it linear, and a discriminant negative only by rounding counts as a
/// double root.
fn quadratic_roots(a: f64, b: f64, c: f64, scale: f64) -> Roots {
    let (b, c) = (b / scale, c / scale / scale);
    if a.abs().max(b.abs()).max(c.abs()) <= COEFFICIENT_ZERO {
        return Roots::All;
    }
    if a == 0.0 {
        return if b == 0.0 {
            Roots::Some([0.0; 2], 0)
        } else {
            Roots::Some([-c / b * scale, 0.0], 1)
        };
    }
    let mut discriminant = b * b - 4.0 * a * c;
    // Within rounding of zero (either sign) it is a double root: rounding would otherwise
    // split it into two roots about √ε apart, or lose it.
    if discriminant.abs() <= DISCRIMINANT_ROUNDING * (b * b + (4.0 * a * c).abs()) {
        discriminant = 0.0;
    } else if discriminant < 0.0 {
        return Roots::Some([0.0; 2], 0);
    }
    let q = -0.5 * (b + b.signum() * discriminant.sqrt());
    if q == 0.0 {
        return Roots::Some([0.0; 2], 1);
    }
    Roots::Some([q / a * scale, c / q * scale], 2)
}

/// The roots of a quadratic as candidate values of one unknown; a vanishing quadratic leaves
/// the unknown free, so it keeps its old value `old`.
fn roots_or_old(roots: Roots, old: f64) -> ([f64; 2], usize) {
    match roots {
        Roots::Some(values, count) => (values, count),
        Roots::All => ([old, 0.0], 1),
    }
}

/// Candidate values `[a, b, c, e]` for `pair` before the monotonicity check; `Free` unknowns
/// keep their old value, clamped into range. At most two (one per quadratic root).
///
/// `k` is shifted so that `t = 0` (better conditioned, and the forced cases become exact
/// zeros); `scale` is the local knot scale `R - L`.
fn raw_solutions(
    pair: KnotPair,
    k: &LocalKnots,
    x: f64,
    y: f64,
    scale: f64,
) -> ([[f64; 4]; 2], usize) {
    let mut out = [[0.0; 4]; 2];
    let mut count = 0;
    let mut push = |a: Option<Unknown>, b: f64, c: f64, e: Option<Unknown>, old: &LocalKnots| {
        let (Some(a), Some(e)) = (a, e) else { return };
        // A free knot keeps its old value, clamped into its range (a <= b, e >= c).
        let a = match a {
            Unknown::Value(v) => v,
            Unknown::Free => old.a.min(b),
        };
        let e = match e {
            Unknown::Value(v) => v,
            Unknown::Free => old.e.max(c),
        };
        if count < 2 {
            out[count] = [a, b, c, e];
            count += 1;
        }
    };
    let t = k.t;
    // An unknown that feeds the second equation snaps onto t (= 0 here) when rounding left it
    // within the knot tolerance, so that the forced cases (x = 0 needs c = t, y = 0 needs
    // b = t) are recognised exactly.
    let snap_to_t = |v: f64| {
        if (v - t).abs() <= CLAMP_TOLERANCE * scale {
            t
        } else {
            v
        }
    };
    match pair {
        KnotPair::Omega1 => {
            // y-equation, quadratic in b: (1-y) b^2 + (y(e+c) - 2t) b + (t^2 - y e c) = 0.
            let roots = quadratic_roots(
                1.0 - y,
                y * (k.e + k.c) - 2.0 * t,
                t * t - y * k.e * k.c,
                scale,
            );
            let (roots, n) = roots_or_old(roots, k.b);
            for &b in &roots[..n] {
                push(a_from_x(x, k, b, k.c), b, k.c, Some(Unknown::Value(k.e)), k);
            }
        }
        KnotPair::Omega2 => {
            if y == 0.0 && x > 0.0 {
                // y = 0 forces b = t; the x-equation x (c - a)(c - t) = (c - t)^2 with c > t
                // is then linear: (1 - x) c = t - x a. At x = 1 it needs a = t and leaves c free.
                let c = if x < 1.0 {
                    (t - x * k.a) / (1.0 - x)
                } else if (k.a - t).abs() <= CLAMP_TOLERANCE * scale {
                    k.c
                } else {
                    return (out, 0);
                };
                push(
                    Some(Unknown::Value(k.a)),
                    t,
                    c,
                    Some(Unknown::Value(k.e)),
                    k,
                );
            } else if x == 0.0 {
                // x = 0 forces c = t; the y-equation then gives b = (t - y e) / (1 - y), or,
                // at y = 0, b = t: a triple knot at t, where the curve passes through d_{j-1}.
                // At y = 1 with e = t every b in [a, t) gives y = 1: b is free.
                let b = if y == 0.0 {
                    t
                } else if y < 1.0 {
                    (t - y * k.e) / (1.0 - y)
                } else if y == 1.0 && (k.e - t).abs() <= CLAMP_TOLERANCE * scale {
                    match choose_free_below(k.b, k.a, t) {
                        Some(b) => b,
                        None => return (out, 0),
                    }
                } else {
                    return (out, 0);
                };
                push(
                    Some(Unknown::Value(k.a)),
                    b,
                    t,
                    Some(Unknown::Value(k.e)),
                    k,
                );
            } else {
                // (1-x)(1-x-y) c^2 + (2ty - 2(1-x)(t - xa) - xy(a+e)) c
                //   + ((t - xa)^2 - y t^2 + x y a e) = 0, then b from the x-equation.
                let s = t - x * k.a;
                let roots = quadratic_roots(
                    (1.0 - x) * (1.0 - x - y),
                    2.0 * t * y - 2.0 * (1.0 - x) * s - x * y * (k.a + k.e),
                    s * s - y * t * t + x * y * k.a * k.e,
                    scale,
                );
                let (roots, n) = roots_or_old(roots, k.c);
                for &c in &roots[..n] {
                    if let Some(Unknown::Value(b)) = b_from_x(x, k, k.a, c) {
                        push(
                            Some(Unknown::Value(k.a)),
                            b,
                            c,
                            Some(Unknown::Value(k.e)),
                            k,
                        );
                    }
                }
            }
        }
        KnotPair::Omega3 => {
            // x-equation, quadratic in c: (1-x) c^2 + (x(a+b) - 2t) c + (t^2 - x a b) = 0.
            let roots = quadratic_roots(
                1.0 - x,
                x * (k.a + k.b) - 2.0 * t,
                t * t - x * k.a * k.b,
                scale,
            );
            let (roots, n) = roots_or_old(roots, k.c);
            for &c in &roots[..n] {
                push(Some(Unknown::Value(k.a)), k.b, c, e_from_y(y, k, k.b, c), k);
            }
        }
        KnotPair::Omega4 => {
            // c from the y-equation (linear), then a from the x-equation.
            let c = match c_from_y(y, k, k.b, k.e) {
                Some(Unknown::Value(c)) => snap_to_t(c),
                // y = 0 with b = t: any c in (t, e] whose a = c - (c-t)/x stays >= L, i.e.
                // c - t <= (t - L) x / (1 - x), L (see `free_reach`).
                Some(Unknown::Free) => {
                    let reach = free_reach(t - k.l, x, CLAMP_TOLERANCE * scale);
                    match choose_free_above(k.c, t, k.e.min(t + reach)) {
                        Some(c) => c,
                        None => return (out, 0),
                    }
                }
                None => return (out, 0),
            };
            push(a_from_x(x, k, k.b, c), k.b, c, Some(Unknown::Value(k.e)), k);
        }
        KnotPair::Omega5 => {
            // Separable: a from the x-equation, e from the y-equation.
            push(
                a_from_x(x, k, k.b, k.c),
                k.b,
                k.c,
                e_from_y(y, k, k.b, k.c),
                k,
            );
        }
        KnotPair::Omega6 => {
            // b from the x-equation (linear), then e from the y-equation.
            let b = match b_from_x(x, k, k.a, k.c) {
                Some(Unknown::Value(b)) => snap_to_t(b),
                // x = 0 with c = t: any b in [a, t) whose e = b + (t-b)/y stays <= R, i.e.
                // t - b <= (R - t) y / (1 - y), R (see `free_reach`).
                Some(Unknown::Free) => {
                    let reach = free_reach(k.r - t, y, CLAMP_TOLERANCE * scale);
                    match choose_free_below(k.b, k.a.max(t - reach), t) {
                        Some(b) => b,
                        None => return (out, 0),
                    }
                }
                None => return (out, 0),
            };
            push(Some(Unknown::Value(k.a)), b, k.c, e_from_y(y, k, b, k.c), k);
        }
    }
    (out, count)
}

/// `value` in `[lo, hi]`: clamped onto a bound when outside by at most `tol`, snapped onto a
/// bound when inside within `snap` (so coincident knots come out exactly equal); `None` when
/// further out.
fn clamp_within(value: f64, lo: f64, hi: f64, tol: f64, snap: f64) -> Option<f64> {
    if !value.is_finite() || value < lo - tol || value > hi + tol {
        return None;
    }
    Some(if value <= lo + snap {
        lo
    } else if value >= hi - snap {
        hi
    } else {
        value
    })
}

/// The solutions `[a, b, c, e]` of `pair` for the frame coordinates `(x, y)` that satisfy the
/// monotonicity condition `L <= a <= b <= t <= c <= e <= R` with `c > b` (within
/// [`CLAMP_TOLERANCE`]; small violations clamped onto the bound; values within
/// [`KNOT_TOLERANCE`] of the old ones snapped back to them). Duplicates are removed; at most two are returned.
///
/// `x` and `y` within [`FRAME_ZERO_TOLERANCE`] of 0 (or 1) count as 0 (or 1). Edge cases: `x = 0` forces
/// `c = t` and `y = 0` forces `b = t`; a knot that the equations then leave undetermined
/// (also a quadratic that vanishes identically, e.g. Ω2 with `a = b = t` and `x = 1`) keeps
/// its old value (clamped into its range). The target `d_{j-1}` (`x = y = 0`) is
/// reached only by Ω2, through the triple knot `b = c = t` (the curve interpolates
/// `d_{j-1}` there); every other solution has `c > b`.
pub fn solve_pair(pair: KnotPair, k: &LocalKnots, x: f64, y: f64) -> ([[f64; 4]; 2], usize) {
    let snap = |v: f64| {
        if v.abs() <= FRAME_ZERO_TOLERANCE {
            0.0
        } else if (v - 1.0).abs() <= FRAME_ZERO_TOLERANCE {
            1.0
        } else {
            v
        }
    };
    let (x, y) = (snap(x), snap(y));
    let mut result = [[0.0; 4]; 2];
    let mut count = 0;
    if !(x.is_finite() && y.is_finite()) {
        return (result, 0);
    }
    let scale = (k.r - k.l).max(f64::MIN_POSITIVE);
    let tol = KNOT_TOLERANCE * scale;
    let clamp_tol = CLAMP_TOLERANCE * scale;
    let shifted = LocalKnots {
        l: k.l - k.t,
        a: k.a - k.t,
        b: k.b - k.t,
        t: 0.0,
        c: k.c - k.t,
        e: k.e - k.t,
        r: k.r - k.t,
    };
    let (raw, n) = raw_solutions(pair, &shifted, x, y, scale);
    let [unknown_1, unknown_2] = pair.unknowns();
    for &[a, b, c, e] in &raw[..n] {
        let (a, b, c, e) = (a + k.t, b + k.t, c + k.t, e + k.t);
        let keep_old = |value: f64, old: f64| {
            if (value - old).abs() <= tol {
                old
            } else {
                value
            }
        };
        let (a, b, c, e) = (
            keep_old(a, k.a),
            keep_old(b, k.b),
            keep_old(c, k.c),
            keep_old(e, k.e),
        );
        // Bounds of each knot; a bound set by a fixed neighbour (a below b, e above c) is that
        // neighbour's value, so clamping only ever moves an unknown onto a fixed knot.
        let moves = |knot: LocalKnot| knot == unknown_1 || knot == unknown_2;
        let b_floor = if moves(LocalKnot::A) { k.l } else { k.a };
        let c_ceiling = if moves(LocalKnot::E) { k.r } else { k.e };
        let Some(b) = clamp_within(b, b_floor, k.t, clamp_tol, tol) else {
            continue;
        };
        let Some(a) = clamp_within(a, k.l, b, clamp_tol, tol) else {
            continue;
        };
        let Some(c) = clamp_within(c, k.t, c_ceiling, clamp_tol, tol) else {
            continue;
        };
        let Some(e) = clamp_within(e, c, k.r, clamp_tol, tol) else {
            continue;
        };
        let triple_knot = x == 0.0 && y == 0.0 && pair == KnotPair::Omega2 && b == k.t && c == k.t;
        if !(c > b || triple_knot) {
            continue;
        }
        let candidate = [a, b, c, e];
        // The fixed knots must not have moved (clamping only touches the unknowns' bounds).
        let fixed_ok = [LocalKnot::A, LocalKnot::B, LocalKnot::C, LocalKnot::E]
            .into_iter()
            .zip(candidate)
            .all(|(knot, value)| knot == unknown_1 || knot == unknown_2 || value == k.get(knot));
        let duplicate = result[..count].iter().any(|s| {
            s.iter()
                .zip(&candidate)
                .all(|(p, q)| (p - q).abs() <= clamp_tol)
        });
        if fixed_ok && !duplicate {
            result[count] = candidate;
            count += 1;
        }
    }
    (result, count)
}

//! Periodic curves in Open CASCADE's form: the layout, cutting one open into an ordinary curve
//! over one period (and writing an edited one back), and knot insertion.
//!
//! The periodic form (`Geom_BSplineCurve` with `Periodic`): distinct knots `k_0 < … < k_m`
//! with multiplicities `m_0 … m_m`, `m_m = m_0 <= p`, period `T = k_m - k_0`, and
//! `N = m_0 + … + m_{m-1}` control points `P_0 … P_{N-1}`, none repeated. Its flat knots of
//! one period are `τ_0 … τ_{N-1}` (`k_0` `m_0` times, …, `k_{m-1}` `m_{m-1}` times), extended
//! to every integer index by `τ_{j+N} = τ_j + T`; the curve is
//! `C(t) = Σ_j N_{j,p}(t) B_j` with `B_j = P_{(j + p + 1 - m_0) mod N}` (so the span
//! `[k_0, k_1)` uses `P_0 … P_p`, as Open CASCADE's `BSplCLib::PoleIndex` has it).
//!
//! Cut open at the last copy `τ_c` of a knot value `a` (`m_a` copies), it is the ordinary
//! curve with knots `u_i = τ_{c - p + i}` (`N + 2p + 2 - m_a` of them), control points
//! `Q_k = B_{c - p + k}` (`N + p + 1 - m_a`; the last `p + 1 - m_a` repeat the first) and
//! domain `[u_p, u_{n+1}] = [a, a + T]`. [`Curve`] stores a periodic curve cut at `k_0`
//! (`c = m_0 - 1`); [`PeriodicWindow`] cuts one elsewhere, so that an edit near a parameter
//! is far from the cut, and writes the edited curve back in the periodic form.
//!
//! Knots outside the stored period are computed from the nearer end, `k_m + (τ_j - k_0)` and
//! `k_0 - (k_m - τ_j)`, so that the knots next to the seam are as exact as the data.

use super::curve::{CallerKnots, Curve, CurveError, CurveLimits, Dimension, KnotForm};
use super::curve::{KnotConvention, distinct_knots};
use super::vector::Point;

/// What the cut-open data of a periodic curve need to be written in the periodic form again.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Periodicity {
    /// `N`: the periodic form's number of control points.
    pub(crate) poles: usize,
    /// `m_0`: the multiplicity of the first (and the last) knot.
    pub(crate) seam_multiplicity: usize,
}

/// A periodic curve as data of one period, with the infinite sequences `τ_j` and `B_j`.
#[derive(Debug, Clone)]
struct PeriodData {
    degree: usize,
    dimension: Dimension,
    rational: bool,
    /// `τ_0 … τ_{N-1}`.
    flat: Vec<f64>,
    /// `k_m = k_0 + T`.
    last: f64,
    /// `P_0 … P_{N-1}`, homogeneous `(w x, w y, w z, w)`.
    poles: Vec<[f64; 4]>,
    /// `m_0`.
    seam_multiplicity: usize,
}

impl PeriodData {
    fn first(&self) -> f64 {
        self.flat[0]
    }

    fn period(&self) -> f64 {
        self.last - self.first()
    }

    fn count(&self) -> i64 {
        self.flat.len() as i64
    }

    /// `τ_j` for any integer `j`.
    fn knot(&self, j: i64) -> f64 {
        let periods = j.div_euclid(self.count());
        let base = self.flat[j.rem_euclid(self.count()) as usize];
        let period = self.period();
        match periods {
            0 => base,
            q if q > 0 => self.last + (base - self.first()) + (q - 1) as f64 * period,
            q => self.first() - (self.last - base) - (-q - 1) as f64 * period,
        }
    }

    /// The index into `P` of `B_j`.
    fn pole_index(&self, j: i64) -> usize {
        let offset = (self.degree + 1 - self.seam_multiplicity) as i64;
        (j + offset).rem_euclid(self.count()) as usize
    }

    /// `B_j`.
    fn pole(&self, j: i64) -> [f64; 4] {
        self.poles[self.pole_index(j)]
    }

    /// The flat index of the last copy of `τ_j`'s value among `τ_j … τ_{j+N-1}`.
    fn last_copy(&self, j: usize) -> usize {
        let value = self.flat[j];
        j + self.flat[j..].iter().take_while(|&&u| u == value).count() - 1
    }

    /// The data of a periodic curve stored cut open at `k_0`.
    fn of_curve(curve: &Curve, periodicity: Periodicity) -> PeriodData {
        let p = curve.degree();
        let n_poles = periodicity.poles;
        let start = p + 1 - periodicity.seam_multiplicity;
        PeriodData {
            degree: p,
            dimension: curve.dimension(),
            rational: curve.is_rational(),
            flat: curve.knots()[start..start + n_poles].to_vec(),
            last: curve.domain().1,
            poles: curve.homogeneous()[..n_poles].to_vec(),
            seam_multiplicity: periodicity.seam_multiplicity,
        }
    }

    /// The ordinary curve cut open at the last copy `c` of a knot value: its knots and
    /// control points.
    fn cut_open(&self, c: usize) -> (Vec<f64>, Vec<[f64; 4]>) {
        let knots = self.cut_open_knots(c);
        let first = c as i64 - self.degree as i64;
        let n_poles = knots.len() - self.degree - 1;
        let poles = (0..n_poles).map(|k| self.pole(first + k as i64)).collect();
        (knots, poles)
    }

    /// The knots of the ordinary curve cut open at the last copy `c` of a knot value `a`
    /// (`m_a` copies): `τ_{c-p} …`, `N + 2p + 2 - m_a` of them.
    fn cut_open_knots(&self, c: usize) -> Vec<f64> {
        let p = self.degree;
        let value = self.flat[c];
        let copies = self.flat.iter().filter(|&&u| u == value).count();
        let first = c as i64 - p as i64;
        let n_poles = self.flat.len() + p + 1 - copies;
        (0..n_poles + p + 1)
            .map(|i| self.knot(first + i as i64))
            .collect()
    }

    /// The ordinary curve cut open at `c` (convention `convention`).
    fn window_curve(&self, c: usize, convention: KnotConvention) -> Curve {
        let (knots, homogeneous) = self.cut_open(c);
        let (points, weights) = split_homogeneous(&homogeneous, self.rational);
        Curve::from_valid_parts(
            self.degree,
            self.dimension,
            points,
            weights,
            knots,
            convention,
        )
    }

    /// The periodic curve of these data (stored cut open at `k_0`).
    fn into_curve(self) -> Curve {
        let periodicity = Periodicity {
            poles: self.flat.len(),
            seam_multiplicity: self.seam_multiplicity,
        };
        self.window_curve(self.seam_multiplicity - 1, KnotConvention::Multiplicities)
            .into_periodic(periodicity)
    }

    /// Inserts `u` (in `[k_0, k_m)`) once into every period (Boehm: the new `B'_j` is
    /// `α_j B_j + (1 - α_j) B_{j-1}`, `α_j = (u - τ_j) / (τ_{j+p} - τ_j)`, for
    /// `s - p < j <= s` where `τ_s <= u < τ_{s+1}`; `B_j` below, `B_{j-1}` above). The
    /// copies of `u` one period away change the copies of these poles only, since `N >= p`.
    fn insert(&mut self, u: f64) {
        let p = self.degree as i64;
        let u = if u >= self.last { self.first() } else { u };
        let s = self.flat.partition_point(|&v| v <= u) as i64 - 1;
        let n = self.count();
        let mut blended = Vec::with_capacity(self.flat.len() + 1);
        for j in s - p + 1..=s - p + 1 + n {
            let pole = if j <= s {
                let (lo, hi) = (self.knot(j), self.knot(j + p));
                let alpha = if hi > lo { (u - lo) / (hi - lo) } else { 0.0 };
                let (right, left) = (self.pole(j), self.pole(j - 1));
                std::array::from_fn(|c| alpha * right[c] + (1.0 - alpha) * left[c])
            } else {
                self.pole(j - 1)
            };
            blended.push((j, pole));
        }
        self.flat.insert((s + 1) as usize, u);
        if u == self.first() {
            self.seam_multiplicity += 1;
        }
        let mut poles = vec![[0.0; 4]; self.flat.len()];
        for (j, pole) in blended {
            poles[self.pole_index(j)] = pole;
        }
        self.poles = poles;
    }
}

/// Cartesian points and weights (when rational) of homogeneous points.
fn split_homogeneous(homogeneous: &[[f64; 4]], rational: bool) -> (Vec<Point>, Option<Vec<f64>>) {
    if rational {
        let points = homogeneous
            .iter()
            .map(|h| [h[0] / h[3], h[1] / h[3], h[2] / h[3]])
            .collect();
        (points, Some(homogeneous.iter().map(|h| h[3]).collect()))
    } else {
        (
            homogeneous.iter().map(|h| [h[0], h[1], h[2]]).collect(),
            None,
        )
    }
}

/// The periodic curve of validated periodic-form data (the rules of [`KnotForm::Periodic`]
/// hold), stored cut open at `k_0`.
pub(crate) fn unwrapped(
    degree: usize,
    dimension: Dimension,
    points: Vec<Point>,
    weights: Option<Vec<f64>>,
    knots: &[f64],
    multiplicities: &[usize],
) -> Curve {
    let last = knots.len() - 1;
    let mut flat = Vec::with_capacity(points.len());
    for (&u, &m) in knots[..last].iter().zip(multiplicities) {
        flat.extend(std::iter::repeat_n(u, m));
    }
    let poles = points
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let w = weights.as_ref().map_or(1.0, |w| w[i]);
            [w * p[0], w * p[1], w * p[2], w]
        })
        .collect();
    PeriodData {
        degree,
        dimension,
        rational: weights.is_some(),
        flat,
        last: knots[last],
        poles,
        seam_multiplicity: multiplicities[0],
    }
    .into_curve()
}

/// The knots of validated periodic-form data cut open at `k_0` (as [`unwrapped`] stores a
/// periodic curve) and the layout: control point `k` of the cut-open spline is the periodic
/// form's `P_{k mod N}` (module docs). Each direction of a periodic surface is stored so.
pub(crate) fn unwrapped_knots(
    degree: usize,
    knots: &[f64],
    multiplicities: &[usize],
) -> (Vec<f64>, Periodicity) {
    let last = knots.len() - 1;
    let mut flat = Vec::new();
    for (&u, &m) in knots[..last].iter().zip(multiplicities) {
        flat.extend(std::iter::repeat_n(u, m));
    }
    let periodicity = Periodicity {
        poles: flat.len(),
        seam_multiplicity: multiplicities[0],
    };
    let data = PeriodData {
        degree,
        dimension: Dimension::Three,
        rational: false,
        flat,
        last: knots[last],
        poles: Vec::new(),
        seam_multiplicity: multiplicities[0],
    };
    (data.cut_open_knots(multiplicities[0] - 1), periodicity)
}

/// The periodic form's knots of a periodic curve: the distinct values of one period and
/// `k_m` with the seam's multiplicity.
pub(crate) fn period_knots(curve: &Curve, periodicity: Periodicity) -> CallerKnots {
    let data = PeriodData::of_curve(curve, periodicity);
    let (mut knots, mut multiplicities) = distinct_knots(&data.flat);
    knots.push(data.last);
    multiplicities.push(data.seam_multiplicity);
    CallerKnots {
        knots,
        multiplicities: Some(multiplicities),
        periodic: true,
    }
}

/// A periodic curve with the sorted values `inserted` (in its period, each multiplicity at
/// most the degree afterwards) inserted into every period; `k_m` stands for `k_0`.
pub(crate) fn refined(curve: &Curve, periodicity: Periodicity, inserted: &[f64]) -> Curve {
    let mut data = PeriodData::of_curve(curve, periodicity);
    for &u in inserted {
        data.insert(u);
    }
    data.into_curve()
}

/// Why an edited window cannot be written back as a periodic curve.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum WrapError {
    /// The edited curve's degree or number of knots or control points differs from the
    /// window's.
    #[error("the edited curve has another degree or number of knots or control points")]
    LayoutChanged,
    /// Two copies of one periodic knot were changed to different values.
    #[error("two copies of periodic knot {index} were changed differently")]
    KnotCopiesDisagree { index: usize },
    /// Two copies of one periodic control point were changed to different values.
    #[error("two copies of periodic control point {index} were changed differently")]
    PoleCopiesDisagree { index: usize },
    /// The edited knots are not non-decreasing around the period.
    #[error("the edited knots do not increase around the period")]
    KnotsOutOfOrder,
    /// The result breaks a rule of the periodic form (e.g. the seam's multiplicity).
    #[error("the edited curve is not a valid periodic curve: {0}")]
    Invalid(CurveError),
}

/// Relative agreement asked of two changed copies of one value (they are computed from the
/// same edit, so they differ by roundoff at most).
const COPY_AGREEMENT: f64 = 64.0 * f64::EPSILON;

/// A periodic curve cut open at a knot: an ordinary curve over one period `[a, a + T]`, with
/// the maps between its knots and control points and the periodic curve's (each periodic one
/// has one or two copies in the window), and the way back ([`PeriodicWindow::wrap`]).
///
/// Use: `curve.periodic_window(t)` cuts at the knot farthest from `t`; edit `window.curve()`
/// at `window.window_parameter(t)` with any method for ordinary curves; `window.wrap(&edited)`
/// is the periodic curve with every change made to every copy.
#[derive(Debug, Clone)]
pub struct PeriodicWindow {
    data: PeriodData,
    /// Flat index `c` of the cut: the last copy of the knot value `a`.
    cut: usize,
    curve: Curve,
}

impl Curve {
    /// For a periodic curve, the window cut at the distinct knot farthest from `around`
    /// (cyclically), so that an edit near `around` stays away from the cut; `None` for a
    /// curve that is not periodic.
    pub fn periodic_window(&self, around: f64) -> Option<PeriodicWindow> {
        let periodicity = self.periodicity()?;
        let data = PeriodData::of_curve(self, periodicity);
        let t = self.snap_to_domain(around).unwrap_or(data.first());
        let period = data.period();
        let farthest = |u: f64| {
            let d = (t - u).rem_euclid(period);
            d.min(period - d)
        };
        let mut cut = data.last_copy(0);
        let mut best = farthest(data.flat[0]);
        let mut j = cut + 1;
        while j < data.flat.len() {
            let last = data.last_copy(j);
            let distance = farthest(data.flat[j]);
            if distance > best {
                (cut, best) = (last, distance);
            }
            j = last + 1;
        }
        let curve = data.window_curve(cut, KnotConvention::Full);
        Some(PeriodicWindow { data, cut, curve })
    }
}

impl PeriodicWindow {
    /// The ordinary curve over `[a, a + T]` (full knot convention).
    pub fn curve(&self) -> &Curve {
        &self.curve
    }

    /// The knot value `a` where the window is cut.
    pub fn cut_value(&self) -> f64 {
        self.data.flat[self.cut]
    }

    /// The window parameter (in `[a, a + T]`) of the periodic parameter `t` (any finite
    /// value: the curve repeats with the period).
    pub fn window_parameter(&self, t: f64) -> f64 {
        let (lo, hi) = self.curve.domain();
        if (lo..=hi).contains(&t) {
            return t;
        }
        (lo + (t - lo).rem_euclid(self.data.period())).clamp(lo, hi)
    }

    /// The periodic parameter (in `[k_0, k_m]`) of the window parameter `s`.
    pub fn periodic_parameter(&self, s: f64) -> f64 {
        let (lo, hi) = (self.data.first(), self.data.last);
        if (lo..=hi).contains(&s) {
            return s;
        }
        (lo + (s - lo).rem_euclid(self.data.period())).clamp(lo, hi)
    }

    /// The flat index of window knot `i` in the infinite sequence (`τ_0` = the first copy of
    /// `k_0`).
    fn flat_index(&self, i: usize) -> i64 {
        self.cut as i64 - self.data.degree as i64 + i as i64
    }

    /// The index in one period's flat knots `τ_0 … τ_{N-1}` (the periodic form's knots, each
    /// repeated its multiplicity times, without the last) of window knot `i`.
    pub fn periodic_knot_index(&self, i: usize) -> usize {
        self.flat_index(i).rem_euclid(self.data.count()) as usize
    }

    /// The periodic form's control point index of window control point `k`.
    pub fn periodic_pole_index(&self, k: usize) -> usize {
        self.data.pole_index(self.flat_index(k))
    }

    /// The periodic curve whose window is `edited` (the window's curve with knots, control
    /// points or weights changed): every change is made to every copy; copies left alone
    /// keep their values. Knots need not stay at their places in the period: the result's
    /// first knot is the run that holds `τ_0` afterwards.
    pub fn wrap(&self, edited: &Curve) -> Result<Curve, WrapError> {
        let window = &self.curve;
        if edited.degree() != window.degree()
            || edited.knots().len() != window.knots().len()
            || edited.control_points().len() != window.control_points().len()
        {
            return Err(WrapError::LayoutChanged);
        }
        let data = &self.data;
        let period = data.period();
        let count = data.flat.len();
        let mut flat = data.flat.clone();
        let mut knot_changed = vec![false; count];
        for (i, (&new, &old)) in edited.knots().iter().zip(window.knots()).enumerate() {
            if new == old {
                continue;
            }
            let j = self.flat_index(i);
            let index = j.rem_euclid(data.count()) as usize;
            let base = match j.div_euclid(data.count()) {
                0 => new,
                q if q > 0 => data.first() + (new - data.last - (q - 1) as f64 * period),
                q => data.last + (new - data.first() + (-q - 1) as f64 * period),
            };
            if knot_changed[index] && !agree(flat[index], base, period) {
                return Err(WrapError::KnotCopiesDisagree { index });
            }
            (flat[index], knot_changed[index]) = (base, true);
        }
        let mut poles = data.poles.clone();
        let mut pole_changed = vec![false; count];
        for (k, (new, old)) in edited
            .homogeneous()
            .iter()
            .zip(window.homogeneous())
            .enumerate()
        {
            if new == old {
                continue;
            }
            let index = self.periodic_pole_index(k);
            if pole_changed[index] && !(0..4).all(|c| agree(poles[index][c], new[c], 0.0)) {
                return Err(WrapError::PoleCopiesDisagree { index });
            }
            (poles[index], pole_changed[index]) = (*new, true);
        }
        let edited_data = PeriodData {
            flat,
            poles,
            rational: data.rational || edited.is_rational(),
            ..data.clone()
        };
        edited_data.normalized(data.first())
    }
}

/// Whether two computations of one value agree up to roundoff (relative to their magnitude
/// and `scale`).
fn agree(a: f64, b: f64, scale: f64) -> bool {
    (a - b).abs() <= COPY_AGREEMENT * a.abs().max(b.abs()).max(scale)
}

impl PeriodData {
    /// The periodic curve of edited data (`flat` and `poles` changed, `last` still the old
    /// `k_m`): knots that reached `k_0 + T` become copies of the first value, the seam's
    /// multiplicity is counted again (the poles `B_j` keep their basis indices, `P`
    /// re-indexes), and the result is validated.
    fn normalized(mut self, old_first: f64) -> Result<Curve, WrapError> {
        let old_last = self.last;
        let period = old_last - old_first;
        let n = self.flat.len();
        let first = self.flat[0];
        let last = if first == old_first {
            old_last
        } else {
            first + period
        };
        if self.flat.windows(2).any(|w| w[0] > w[1]) || self.flat[n - 1] > last {
            return Err(WrapError::KnotsOutOfOrder);
        }
        let moved_back = self.flat.iter().rev().take_while(|&&u| u == last).count();
        let poles_by_basis: Vec<[f64; 4]> = (0..n as i64)
            .map(|j| self.pole(j - moved_back as i64))
            .collect();
        self.flat.rotate_right(moved_back);
        for u in &mut self.flat[..moved_back] {
            *u = first;
        }
        self.seam_multiplicity = self.flat.iter().take_while(|&&u| u == first).count();
        self.last = last;
        let mut poles = vec![[0.0; 4]; n];
        for (j, pole) in poles_by_basis.into_iter().enumerate() {
            poles[self.pole_index(j as i64)] = pole;
        }
        self.poles = poles;
        self.validated()
    }

    /// The periodic curve of these data through [`Curve::from_knot_form`], which checks the
    /// periodic form's rules.
    fn validated(self) -> Result<Curve, WrapError> {
        let (mut knots, mut multiplicities) = distinct_knots(&self.flat);
        knots.push(self.last);
        multiplicities.push(multiplicities[0]);
        let (points, weights) = split_homogeneous(&self.poles, self.rational);
        let dimension = self.dimension.count();
        let coordinates: Vec<&[f64]> = points.iter().map(|p| &p[..dimension]).collect();
        let limits = CurveLimits {
            max_control_points: usize::MAX,
            ..CurveLimits::default()
        };
        Curve::from_knot_form(
            self.degree,
            &coordinates,
            KnotForm::Periodic {
                knots: &knots,
                multiplicities: &multiplicities,
            },
            weights.as_deref(),
            &limits,
        )
        .map_err(WrapError::Invalid)
    }
}

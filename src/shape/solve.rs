//! The knot-pair solver: new knot vectors that move the curve point `s(t)` to a target
//! (docs/method.md §3–§8), and region membership through the very same code path.

use super::candidate::{Candidate, Side, SideChoice, candidate, triangle_size};
use super::deviation::max_deviation;
use super::pairs::{KnotPair, LocalKnots, solve_pair};
use crate::spline::vector::{Point, distance};
use crate::spline::{Curve, Dimension};

/// Why a shape request cannot be answered.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ShapeError {
    /// The method is for cubic curves only (the envelope pairs Ω1–Ω6 of §4).
    #[error(
        "the knot-pair method (\"knots\") needs a cubic curve (degree 3), not degree {degree}; the \"control_points\" and \"weights\" methods take any degree"
    )]
    NotCubic { degree: usize },
    /// Knots cannot move a point of a degree-1 curve.
    #[error(
        "the knot method (\"knots\") needs degree 2 or more: a degree-1 curve is the polyline of its control points, whose shape does not depend on its knots; the \"control_points\" and \"weights\" methods take degree 1"
    )]
    DegreeOne,
    /// The picked parameter is not a finite number.
    #[error("the parameter is not a finite number")]
    NonFiniteParameter,
    /// The picked parameter lies outside the curve's domain.
    #[error("parameter {value} lies outside the domain [{}, {}]", domain.0, domain.1)]
    ParameterOutsideDomain { value: f64, domain: (f64, f64) },
    /// The target has the wrong number of coordinates.
    #[error("the target has {found} coordinates; the curve's control points have {expected}")]
    TargetDimension { expected: usize, found: usize },
    /// A target coordinate is not finite.
    #[error("target coordinate {coordinate} is not a finite number")]
    NonFiniteTarget { coordinate: usize },
}

/// The request element a [`ShapeError`] is about.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ShapeField {
    /// The curve's degree.
    Degree,
    /// The picked parameter.
    Parameter,
    /// The target as a whole.
    Target,
    /// One target coordinate.
    TargetCoordinate(usize),
}

impl ShapeError {
    /// The element of the request that is at fault.
    pub fn field(&self) -> ShapeField {
        match *self {
            ShapeError::NotCubic { .. } | ShapeError::DegreeOne => ShapeField::Degree,
            ShapeError::NonFiniteParameter | ShapeError::ParameterOutsideDomain { .. } => {
                ShapeField::Parameter
            }
            ShapeError::TargetDimension { .. } => ShapeField::Target,
            ShapeError::NonFiniteTarget { coordinate } => ShapeField::TargetCoordinate(coordinate),
        }
    }
}

/// What a shape request asks about: a cubic curve, the picked parameter `t`, the sides and
/// knot pairs to try, and whether the curve's domain must stay put.
#[derive(Debug, Clone, Copy)]
pub struct ShapeQuery<'a> {
    /// The cubic curve.
    pub curve: &'a Curve,
    /// The picked parameter `t` (the point `s(t)` moves).
    pub parameter: f64,
    /// Which knot(s) next to `t` may move to `t`.
    pub side: SideChoice,
    /// The knot pairs to try.
    pub pairs: &'a [KnotPair],
    /// The knot families to try (docs/method.md §31); the cubic's envelope pairs are the
    /// ones of `pairs`.
    pub families: crate::shape::family::FamilyChoice,
    /// Drop solutions that change `u_{k-1}` or `u_{n+1}` (docs/method.md §6),
    /// or that move a knot onto a clamped end (which moves the end point just the same).
    pub keep_domain: bool,
}

impl<'a> ShapeQuery<'a> {
    /// All sides, all six pairs, domain kept: the API's defaults. A `parameter` just outside
    /// the domain is snapped onto its end ([`Curve::snap_to_domain`]).
    pub fn new(curve: &'a Curve, parameter: f64) -> Self {
        ShapeQuery {
            curve,
            parameter: curve.snap_to_domain(parameter).unwrap_or(parameter),
            side: SideChoice::Both,
            pairs: &KnotPair::ALL,
            families: crate::shape::family::FamilyChoice::Default,
            keep_domain: true,
        }
    }

    /// Checks that the curve is cubic and `t` is finite and in the domain.
    pub(crate) fn validate(&self) -> Result<(), ShapeError> {
        if self.curve.degree() != 3 {
            return Err(ShapeError::NotCubic {
                degree: self.curve.degree(),
            });
        }
        self.validate_parameter()
    }

    /// Checks that `t` is finite and in the domain (any degree).
    pub(crate) fn validate_parameter(&self) -> Result<(), ShapeError> {
        let t = self.parameter;
        if !t.is_finite() {
            return Err(ShapeError::NonFiniteParameter);
        }
        if !self.curve.contains_parameter(t) {
            return Err(ShapeError::ParameterOutsideDomain {
                value: t,
                domain: self.curve.domain(),
            });
        }
        Ok(())
    }

    /// The candidates of the requested sides (with the target's frames when given).
    pub fn candidates(&self, target: Option<Point>) -> Result<Vec<Candidate>, ShapeError> {
        self.validate()?;
        Ok(self
            .side
            .sides()
            .iter()
            .map(|&side| candidate(self.curve, self.parameter, side, target))
            .collect())
    }
}

/// Reads a target of the curve's dimension into a point (`z = 0` for 2D).
pub fn target_point(curve: &Curve, target: &[f64]) -> Result<Point, ShapeError> {
    let expected = curve.dimension().count();
    if target.len() != expected {
        return Err(ShapeError::TargetDimension {
            expected,
            found: target.len(),
        });
    }
    if let Some(coordinate) = target.iter().position(|v| !v.is_finite()) {
        return Err(ShapeError::NonFiniteTarget { coordinate });
    }
    let mut point = [0.0; 3];
    point[..expected].copy_from_slice(target);
    if curve.dimension() == Dimension::Two {
        point[2] = 0.0;
    }
    Ok(point)
}

/// One way to move `s(t)` onto the target.
#[derive(Debug, Clone, PartialEq)]
pub struct Solution {
    /// The knot pair (region) that reached the target.
    pub pair: KnotPair,
    /// Which knot moved to `t`.
    pub side: Side,
    /// The span `j`.
    pub span: usize,
    /// Full-vector index of the knot set to `t`.
    pub moved_knot: usize,
    /// Full-vector indices whose values changed, ascending.
    pub changed_knots: Vec<usize>,
    /// The whole new full knot vector.
    pub knots: Vec<f64>,
    /// The new curve's point at `t`.
    pub point: Point,
    /// `|point - target|`.
    pub residual: f64,
    /// `[lo, hi]`: outside it the new curve equals the old one.
    pub affected_domain: (f64, f64),
    /// Largest `|s_old(u) - s_new(u)|` over the domain, when measured.
    pub max_deviation: Option<f64>,
}

/// Whether a pair of a candidate holds the target.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RegionMembership {
    /// The pair.
    pub pair: KnotPair,
    /// Full-vector indices of the pair's two knots.
    pub knots: [usize; 2],
    /// Whether the pair has a (kept) solution: the target lies in `Ω_r`.
    pub contains: bool,
}

/// A candidate with the membership of each requested pair.
#[derive(Debug, Clone, PartialEq)]
pub struct CandidateOutcome {
    /// The side's candidate.
    pub candidate: Candidate,
    /// One entry per requested pair (empty when the side does not apply).
    pub regions: Vec<RegionMembership>,
}

/// The answer to a shape request.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SolveOutcome {
    /// One entry per requested side.
    pub candidates: Vec<CandidateOutcome>,
    /// Every kept solution, sorted by `max_deviation` (smallest first) when measured.
    pub solutions: Vec<Solution>,
}

impl SolveOutcome {
    /// Whether any region of any candidate holds the target.
    pub fn reachable(&self) -> bool {
        !self.solutions.is_empty()
    }
}

/// Options of [`solve`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SolveOptions {
    /// Measure each solution's `max_deviation` (and sort by it).
    pub measure_deviation: bool,
}

/// Solves `s(t) → target` for every requested side and knot pair (docs/method.md §3).
///
/// Per applicable candidate `j`: the new knots are `u_{j+1} := t` plus the pair's two
/// unknowns from [`solve_pair`]. A solution is dropped when `keep_domain` is set and it
/// moves an end of the curve (changes `u_3` or `u_{n+1}`, or moves a knot onto a clamped end). Each solution is evaluated with the spline core at `t`.
/// Membership (`contains`) is "this pair kept a solution", so it can never disagree with the
/// solutions.
pub fn solve(
    query: &ShapeQuery,
    target: &[f64],
    options: SolveOptions,
) -> Result<SolveOutcome, ShapeError> {
    query.validate()?;
    let curve = query.curve;
    let target = target_point(curve, target)?;
    let t = query.parameter;
    let knots = curve.knots();
    let mut candidates = Vec::with_capacity(2);
    let mut solutions = Vec::new();
    // Each root's knot vector is tried in this buffer; only kept solutions get their own copy.
    let mut new_knots = knots.to_vec();
    for &side in query.side.sides() {
        let candidate = candidate(curve, t, side, Some(target));
        let (Some(frame), Some(triangle)) = (candidate.frame, candidate.triangle) else {
            candidates.push(CandidateOutcome {
                candidate,
                regions: Vec::new(),
            });
            continue;
        };
        let j = candidate.span;
        let local = LocalKnots::from_full(knots, j, t);
        let accepted_residual = accepted_residual(&triangle, target);
        let mut regions = Vec::with_capacity(query.pairs.len());
        for &pair in query.pairs {
            let [first, second] = pair.unknowns();
            let mut contains = false;
            let (roots, count) = solve_pair(pair, &local, frame.x, frame.y);
            for &local_knots in &roots[..count] {
                let edit = KnotEdit {
                    pair,
                    side,
                    span: j,
                    local_knots,
                };
                let solution = knot_solution(
                    query,
                    &edit,
                    target,
                    accepted_residual,
                    &mut new_knots,
                    options.measure_deviation,
                );
                if let Some(solution) = solution {
                    contains = true;
                    solutions.push(solution);
                }
            }
            regions.push(RegionMembership {
                pair,
                knots: [first.full_index(j), second.full_index(j)],
                contains,
            });
        }
        candidates.push(CandidateOutcome { candidate, regions });
    }
    if options.measure_deviation {
        sort_by_deviation(&mut solutions);
    }
    Ok(SolveOutcome {
        candidates,
        solutions,
    })
}

/// A proposed knot edit of one candidate: `u_{j+1} := t` and the pair's new local knots.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct KnotEdit {
    pub pair: KnotPair,
    pub side: Side,
    pub span: usize,
    /// The new `[a, b, c, e]` (two of them changed by the pair).
    pub local_knots: [f64; 4],
}

/// The solution of `edit`, or `None` when a rule drops it: it moves the domain's ends under
/// `keep_domain`, empties the domain, has a non-finite knot, or its new curve, evaluated by the
/// spline core at `t`, misses `target` by more than `accepted_residual`. `buffer` is scratch of
/// the knot vector's length.
pub(crate) fn knot_solution(
    query: &ShapeQuery,
    edit: &KnotEdit,
    target: Point,
    accepted_residual: f64,
    buffer: &mut [f64],
    measure_deviation: bool,
) -> Option<Solution> {
    let curve = query.curve;
    let knots = curve.knots();
    let n = curve.control_points().len() - 1;
    let (j, t) = (edit.span, query.parameter);
    let [a, b, c, e] = edit.local_knots;
    buffer.copy_from_slice(knots);
    buffer[j - 1] = a;
    buffer[j] = b;
    buffer[j + 1] = t;
    buffer[j + 2] = c;
    buffer[j + 3] = e;
    if query.keep_domain && moves_domain_ends(knots, buffer) {
        return None;
    }
    let domain_ok = buffer[3] < buffer[n + 1];
    if !domain_ok || !buffer[3..=n + 1].iter().all(|&u| u.is_finite()) {
        return None;
    }
    let point = curve.point_with_knots(buffer, t);
    let residual = distance(point, target);
    if residual.is_nan() || residual > accepted_residual {
        return None;
    }
    let changed_knots: Vec<usize> = (0..knots.len())
        .filter(|&i| buffer[i] != knots[i])
        .collect();
    let affected_domain = affected_domain(curve, buffer, &changed_knots);
    let max_deviation = measure_deviation.then(|| max_deviation(curve, buffer, affected_domain));
    Some(Solution {
        pair: edit.pair,
        side: edit.side,
        span: j,
        moved_knot: j + 1,
        changed_knots,
        knots: buffer.to_vec(),
        point,
        residual,
        affected_domain,
        max_deviation,
    })
}

/// The residual a solution may have: `RESIDUAL_TOLERANCE` times the control triangle's
/// longest edge, plus the rounding floor `64 ε |target|`.
pub(crate) fn accepted_residual(triangle: &[Point; 3], target: Point) -> f64 {
    let target_magnitude = target.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    RESIDUAL_TOLERANCE * triangle_size(triangle) + 64.0 * f64::EPSILON * target_magnitude
}

/// Sorts solutions by `max_deviation`, smallest first (unmeasured ones last).
pub(crate) fn sort_by_deviation(solutions: &mut [Solution]) {
    solutions.sort_by(|p, q| {
        let key = |s: &Solution| s.max_deviation.unwrap_or(f64::INFINITY);
        key(p).total_cmp(&key(q))
    });
}

/// Every solution is verified: the new curve, evaluated by the spline core at `t`, lands within
/// `RESIDUAL_TOLERANCE · size` of the target (`size`: the control triangle's longest edge),
/// plus the rounding floor `64 ε |target|`. A root that fails (ill-conditioned, or clamped too
/// far onto a bound) is discarded.
pub const RESIDUAL_TOLERANCE: f64 = 1e-9;

/// Whether `new_knots` move an end of the curve: they change `u_p` or `u_{n+1}` (the domain),
/// or raise the multiplicity of either end value above `p + 1` (a knot moved onto a clamped
/// end takes `d_0` or `d_n` out of the curve, so its end point moves just the same).
fn moves_domain_ends(old: &[f64], new: &[f64]) -> bool {
    const P: usize = 3;
    let end = old.len() - P - 1;
    [P, end].into_iter().any(|i| {
        let count = |knots: &[f64]| knots.iter().filter(|&&u| u == knots[i]).count();
        new[i] != old[i] || count(new) > count(old).max(P + 1)
    })
}

/// Membership of the target in every requested region of every requested side: [`solve`]
/// without the deviation measure.
pub fn membership(query: &ShapeQuery, target: &[f64]) -> Result<SolveOutcome, ShapeError> {
    solve(
        query,
        target,
        SolveOptions {
            measure_deviation: false,
        },
    )
}

/// `[lo, hi]` outside which the curve with `new_knots` equals `curve`.
///
/// On span `r` a degree-`p` curve depends on the knots `u_{r-p+1} ..= u_{r+p}` only, so
/// changing the indices `qmin ..= qmax` can change the curve only on
/// `[u_{qmin-p}, u_{qmax+p}]` (indices clipped to the domain's `p ..= n+1`; the wider of the
/// old and new value at each end).
pub fn affected_domain(curve: &Curve, new_knots: &[f64], changed_knots: &[usize]) -> (f64, f64) {
    let old = curve.knots();
    let p = curve.degree();
    let n = curve.control_points().len() - 1;
    let (Some(&qmin), Some(&qmax)) = (changed_knots.first(), changed_knots.last()) else {
        return (old[p], old[p]);
    };
    let lo_index = qmin.saturating_sub(p).clamp(p, n + 1);
    let hi_index = (qmax + p).clamp(p, n + 1);
    (
        old[lo_index].min(new_knots[lo_index]),
        old[hi_index].max(new_knots[hi_index]),
    )
}

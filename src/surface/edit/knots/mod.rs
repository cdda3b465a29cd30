//! The knot method for surfaces (docs/method.md §45–§48): new knots that move the surface
//! point `S(ũ, ṽ)` onto a target, the net unchanged.
//!
//! * **Iso-curve families** ([`iso`]): `c(u) = S(u, ṽ)` has control points
//!   `D_i(ṽ) = Σ_l d_il M_l(ṽ)` (homogeneous for NURBS) that the `u` knots do not change, so
//!   every solution of the curve knot families (envelope, direct, triples; every degree ≥ 2,
//!   both sides) on that iso-curve moves `S(ũ, ṽ)` onto the target with the new `knots_u`;
//!   likewise in `v` with `E_l(ũ) = Σ_i d_il N_i(ũ)`. The curve solver itself runs on the
//!   iso-curve ([`crate::shape::family::solve_families`]).
//! * **Mixed moves** ([`mixed`]): knots in both directions for 3D targets, two unknown knots
//!   in one direction and one in the other, after the envelope step in both: on a pair
//!   direction of degree 2 or 3 by the plane condition (`plane.rs`) and the closed forms, on
//!   degree 4 or more by the three unknowns' polynomial system (`curved.rs`).
//!
//! Pure geometry: knots are the surface's full (internal) vectors; the caller's convention
//! is the HTTP edge's business.

mod curved;
mod iso;
mod mixed;
mod nearest;
mod plane;
mod reach;

use crate::shape::family::{Family, FamilyChoice};
use crate::spline::vector::Point;
use crate::surface::{Axis, Direction, Surface};

pub use mixed::MIXED_BOXES;
pub use reach::{
    DEFAULT_REGION_VERTICES, SurfaceKnotMembership, SurfaceKnotRegion, nearest_surface_knot_target,
    surface_knot_membership, surface_knot_regions, surface_knot_regions_with,
};

/// A family of surface knot moves.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SurfaceKnotFamily {
    /// A curve family on the iso-curve along `direction` (through `S(ũ, ṽ)`): new knots in
    /// that direction only.
    Iso {
        /// The direction whose knots move (`U`: the curve `u ↦ S(u, ṽ)`).
        direction: Direction,
        /// The curve family.
        family: Family,
    },
    /// Knots in both directions: the envelope step in each, then two unknown knots in
    /// `pair` and one in the other direction.
    Mixed {
        /// The direction with two unknown knots.
        pair: Direction,
    },
}

impl SurfaceKnotFamily {
    /// The wire name: `"iso_u_envelope"`, `"iso_v_direct"`, `"iso_u_triples"`, …, `"mixed"`.
    pub fn name(self) -> &'static str {
        match self {
            SurfaceKnotFamily::Iso { direction, family } => match (direction, family) {
                (Direction::U, Family::Envelope) => "iso_u_envelope",
                (Direction::U, Family::Direct) => "iso_u_direct",
                (Direction::U, Family::Triples) => "iso_u_triples",
                (Direction::V, Family::Envelope) => "iso_v_envelope",
                (Direction::V, Family::Direct) => "iso_v_direct",
                (Direction::V, Family::Triples) => "iso_v_triples",
            },
            SurfaceKnotFamily::Mixed { .. } => "mixed",
        }
    }

    /// Whether the family's reach lies in one plane (a one-direction pair whose control
    /// points are coplanar): these have drawable regions.
    pub fn is_iso(self) -> bool {
        matches!(self, SurfaceKnotFamily::Iso { .. })
    }
}

/// What a surface knot solve runs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceKnotOptions {
    /// Drop solutions that move a domain end in either direction.
    pub keep_domain: bool,
    /// The curve families run on each iso-curve ([`FamilyChoice::Default`]: envelope and
    /// direct pairs, and triples, since iso-curves are 3D).
    pub iso_families: FamilyChoice,
    /// Run the iso-curve families along `u` and along `v`.
    pub iso_u: bool,
    /// See `iso_u`.
    pub iso_v: bool,
    /// Run the mixed moves.
    pub mixed: bool,
    /// Let the mixed moves' single knot also be one of the direct problem's (no knot set to
    /// the parameter in that direction), beside the envelope's of both sides: more reach,
    /// some 40 % more time (docs/method.md §46, §48).
    pub mixed_direct: bool,
}

impl SurfaceKnotOptions {
    /// Everything: every iso family in both directions and the mixed moves.
    pub fn all(keep_domain: bool) -> SurfaceKnotOptions {
        SurfaceKnotOptions {
            keep_domain,
            iso_families: FamilyChoice::Default,
            iso_u: true,
            iso_v: true,
            mixed: true,
            mixed_direct: false,
        }
    }
}

/// One way to move `S(ũ, ṽ)` onto the target by knots.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceKnotSolution {
    /// The new surface (the old net with the new knots).
    pub surface: Surface,
    /// The new full `u` knot vector, when the `u` knots changed.
    pub knots_u: Option<Vec<f64>>,
    /// The new full `v` knot vector, when the `v` knots changed.
    pub knots_v: Option<Vec<f64>>,
    /// Full-vector indices of the `u` knots whose values changed, ascending.
    pub changed_knots_u: Vec<usize>,
    /// The same in `v`.
    pub changed_knots_v: Vec<usize>,
    /// The family.
    pub family: SurfaceKnotFamily,
    /// The knot set, e.g. `"u right: u_7 := ũ; u_5, u_9"` or
    /// `"u right, v left: u_7 := ũ, v_6 := ṽ; u_5, u_9; v_8"`.
    pub region: String,
    /// The new surface's point at `(ũ, ṽ)` (evaluated by the surface core).
    pub point: Point,
    /// `|point - target|`.
    pub residual: f64,
    /// `[(u_lo, u_hi), (v_lo, v_hi)]`: outside this rectangle the new surface equals the old
    /// one. A one-direction move changes a strip (its range × the other direction's whole
    /// domain); a mixed move changes the union of a `u` strip and a `v` strip, whose
    /// bounding rectangle is the whole domain ([`SurfaceKnotSolution::changed_ranges`] is
    /// finer).
    pub affected_domain: [(f64, f64); 2],
    /// `[u range, v range]` of the strips that change: the new surface equals the old one
    /// wherever `u` lies outside the first and `v` outside the second (`None`: that
    /// direction's knots did not change). Each range is `[t_{k_min − p}, t_{k_max + p}]` of
    /// the changed knots `k`, over the old and the new values.
    pub changed_ranges: [Option<(f64, f64)>; 2],
    /// The smallest singular value of `∂S(ũ, ṽ)/∂(unknown knots)`, each knot scaled by its
    /// room, over the local control points' extent: small near a fold or for a knot far
    /// from the point (for tie-breaking: larger is better determined).
    pub conditioning: f64,
}

/// Every admissible knot solution that moves `S(u, v)` onto `target` (every iso family in
/// both directions, and the mixed moves), in that order. Preconditions: `(u, v)` in the
/// domain (just outside is snapped onto it); nothing is returned otherwise.
pub fn solve_surface_knots(
    surface: &Surface,
    u: f64,
    v: f64,
    target: Point,
    keep_domain: bool,
) -> Vec<SurfaceKnotSolution> {
    solve_surface_knots_with(surface, u, v, target, &SurfaceKnotOptions::all(keep_domain))
}

/// [`solve_surface_knots`] with the families chosen by `options`.
pub fn solve_surface_knots_with(
    surface: &Surface,
    u: f64,
    v: f64,
    target: Point,
    options: &SurfaceKnotOptions,
) -> Vec<SurfaceKnotSolution> {
    let Some((u, v)) = snap(surface, u, v) else {
        return Vec::new();
    };
    if target.iter().any(|c| !c.is_finite()) {
        return Vec::new();
    }
    let mut solutions = Vec::new();
    for (direction, wanted) in [(Direction::U, options.iso_u), (Direction::V, options.iso_v)] {
        if wanted {
            solutions.extend(iso::solve_iso(surface, direction, u, v, target, options));
        }
    }
    if options.mixed {
        for pair in [Direction::U, Direction::V] {
            solutions.extend(mixed::solve_mixed(surface, pair, u, v, target, options));
        }
    }
    solutions
}

/// `(u, v)` snapped into the domain, `None` when farther out or not finite.
pub(crate) fn snap(surface: &Surface, u: f64, v: f64) -> Option<(f64, f64)> {
    Some((surface.u().snap(u)?, surface.v().snap(v)?))
}

/// The parameter along `direction` of `(u, v)`.
pub(crate) fn along(direction: Direction, u: f64, v: f64) -> f64 {
    match direction {
        Direction::U => u,
        Direction::V => v,
    }
}

/// `surface` with the full knot vector of `direction` replaced by `knots` (same degree and
/// length; the direction not periodic).
pub(crate) fn with_knots(surface: &Surface, direction: Direction, knots: Vec<f64>) -> Surface {
    let axis = surface.axis(direction);
    let new = Axis::from_valid_parts(axis.degree(), knots, axis.convention(), None);
    let (u, v) = match direction {
        Direction::U => (new, surface.v().clone()),
        Direction::V => (surface.u().clone(), new),
    };
    Surface::from_valid_parts(
        u,
        v,
        surface.control_points().to_vec(),
        surface.weights().map(<[f64]>::to_vec),
    )
}

/// `surface` with both full knot vectors replaced (same degrees and lengths; neither
/// direction periodic).
pub(crate) fn with_both_knots(surface: &Surface, knots_u: Vec<f64>, knots_v: Vec<f64>) -> Surface {
    let axis = |direction: Direction, knots: Vec<f64>| {
        let old = surface.axis(direction);
        Axis::from_valid_parts(old.degree(), knots, old.convention(), None)
    };
    Surface::from_valid_parts(
        axis(Direction::U, knots_u),
        axis(Direction::V, knots_v),
        surface.control_points().to_vec(),
        surface.weights().map(<[f64]>::to_vec),
    )
}

/// The rows of `[lo, hi]` a knot change in one direction affects: from `knots[i_min - p]` to
/// `knots[i_max + p]` (clamped to the domain), over the old and the new knots.
pub(crate) fn affected_range(
    axis: &Axis,
    new_knots: &[f64],
    changed: &[usize],
) -> Option<(f64, f64)> {
    let (first, last) = (*changed.first()?, *changed.last()?);
    let p = axis.degree();
    let n = axis.count() - 1;
    let old = axis.knots();
    let lo = first.saturating_sub(p).clamp(p, n + 1);
    let hi = (last + p).clamp(p, n + 1);
    Some((old[lo].min(new_knots[lo]), old[hi].max(new_knots[hi])))
}

/// The residual a surface solution may have: [`crate::shape::RESIDUAL_TOLERANCE`] times the
/// extent of the `(p_u + 1) × (p_v + 1)` control points acting at `(u, v)`, plus the
/// rounding floor `64 ε |target|`.
pub(crate) fn accepted_residual(surface: &Surface, u: f64, v: f64, target: Point) -> f64 {
    let (su, sv) = (surface.u().span(u), surface.v().span(v));
    let (pu, pv) = (surface.u().degree(), surface.v().degree());
    let mut poles = Vec::with_capacity((pu + 1) * (pv + 1));
    for i in su - pu..=su {
        for j in sv - pv..=sv {
            poles.push(surface.control_point(i, j));
        }
    }
    let magnitude = target.iter().fold(0.0f64, |m, c| m.max(c.abs()));
    crate::shape::RESIDUAL_TOLERANCE * crate::shape::family::problems::extent(&poles)
        + 64.0 * f64::EPSILON * magnitude
}

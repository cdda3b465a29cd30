//! The knot families and the local problem each poses at a picked parameter (docs/method.md
//! §30): which knots are relevant, which control points act, and which sets of
//! unknowns (pairs, triples) may move.

use super::local::LocalProblem;
use crate::shape::candidate::Side;
use crate::spline::Curve;
use crate::spline::vector::{Point, cross, norm, sub};

/// A family of knot moves.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Family {
    /// The paper's construction on any degree `p ≥ 3`: the knot on the chosen side of `t`
    /// moves to `t`, then a pair of the degree-`p−1` envelope's `2p − 2` relevant knots.
    Envelope,
    /// A pair of the curve's own `2p` relevant knots (degree `p ≥ 2`), no knot set to `t`.
    Direct,
    /// Three of the curve's own `2p` relevant knots: 3D targets off every pair's plane.
    Triples,
}

impl Family {
    /// Every family, in answer order.
    pub const ALL: [Family; 3] = [Family::Envelope, Family::Direct, Family::Triples];

    /// The wire name.
    pub fn name(self) -> &'static str {
        match self {
            Family::Envelope => "envelope",
            Family::Direct => "direct",
            Family::Triples => "triples",
        }
    }

    /// The family of a wire name.
    pub fn from_name(name: &str) -> Option<Family> {
        Family::ALL.into_iter().find(|f| f.name() == name)
    }
}

/// Which families a request asks for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FamilyChoice {
    /// Every family that applies: the envelope (degree ≥ 3) and direct pairs, and triples on
    /// 3D curves.
    #[default]
    Default,
    /// Exactly these (each only where it applies).
    Only {
        /// `"envelope"`.
        envelope: bool,
        /// `"direct"`.
        direct: bool,
        /// `"triples"` (on 2D curves too).
        triples: bool,
    },
}

impl FamilyChoice {
    /// The families of a list of names (`None` for the default); `Err(index)` for the first
    /// unknown name.
    pub fn from_names<'a>(names: impl IntoIterator<Item = &'a str>) -> Result<FamilyChoice, usize> {
        let mut chosen = [false; 3];
        for (index, name) in names.into_iter().enumerate() {
            let family = Family::from_name(name).ok_or(index)?;
            chosen[family as usize] = true;
        }
        Ok(FamilyChoice::Only {
            envelope: chosen[0],
            direct: chosen[1],
            triples: chosen[2],
        })
    }

    /// Whether `family` runs on `curve` (the default adds triples on 3D curves only).
    pub fn includes(self, family: Family, curve: &Curve) -> bool {
        let applies = match family {
            Family::Envelope => curve.degree() >= 3,
            Family::Direct | Family::Triples => curve.degree() >= 2,
        };
        let chosen = match self {
            FamilyChoice::Default => family != Family::Triples || curve.dimension().count() == 3,
            FamilyChoice::Only {
                envelope,
                direct,
                triples,
            } => match family {
                Family::Envelope => envelope,
                Family::Direct => direct,
                Family::Triples => triples,
            },
        };
        applies && chosen
    }
}

/// Why a family's local problem does not apply at the picked parameter.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum FamilyNotApplicable {
    /// The moved knot's index leaves the envelope's knots outside the knot vector.
    #[error(
        "the knot {moved_knot} next to t cannot move to t: the envelope's knots would lie outside the knot vector"
    )]
    OutOfRange { moved_knot: usize },
    /// The moved knot is an end of the domain (and `keep_domain` holds).
    #[error("moving knot {moved_knot} to t would move an end of the domain")]
    MovesDomainEnd { moved_knot: usize },
    /// The knots on either side of the moved one coincide: the envelope's span at `t` is
    /// empty.
    #[error(
        "the knots on either side of knot {moved_knot} coincide, so the envelope has no span at t"
    )]
    EmptySpan { moved_knot: usize },
    /// The local control points are (nearly) collinear: knot moves only slide the point
    /// along a line.
    #[error(
        "the control points acting at t are collinear, so knot moves only slide the point along a line"
    )]
    Collinear,
}

/// One family's local problem at the picked parameter (one side, for the envelope).
#[derive(Debug, Clone, PartialEq)]
pub struct FamilyProblem {
    /// The family (`Direct` also serves `Triples`).
    pub family: Family,
    /// The envelope's side.
    pub side: Option<Side>,
    /// The span `j` (the envelope: the moved knot is `u_{j+1}`; direct: `u_j ≤ t < u_{j+1}`).
    pub span: usize,
    /// The envelope's moved knot (full index).
    pub moved_knot: Option<usize>,
    /// The primitive, when the family applies.
    pub problem: Option<LocalProblem>,
    /// Why not, when it does not.
    pub not_applicable: Option<FamilyNotApplicable>,
}

impl FamilyProblem {
    /// The local control points in the curve's coordinates.
    pub fn control_points(&self) -> Vec<Point> {
        self.problem.as_ref().map_or_else(Vec::new, |problem| {
            problem
                .poles
                .iter()
                .map(|h| [h[0] / h[3], h[1] / h[3], h[2] / h[3]])
                .collect()
        })
    }
}

/// Relative size below which the local control points count as collinear: the largest
/// triangle they span has area below this times the square of their extent.
pub const COLLINEAR_TOLERANCE: f64 = 1e-12;

/// The local problem of the envelope family on `side` at `t`: `u_i := t` for the knot `i` on
/// that side, then `Π_{p−1}` on the knots without `u_i`, poles `d_{i−p} … d_{i−1}`.
pub fn envelope_problem(curve: &Curve, t: f64, side: Side, keep_domain: bool) -> FamilyProblem {
    let p = curve.degree();
    let knots = curve.knots();
    let n = curve.control_points().len() - 1;
    let m = curve.span(t);
    let i = match side {
        Side::Right => m + 1,
        Side::Left => m,
    };
    let mut family = FamilyProblem {
        family: Family::Envelope,
        side: Some(side),
        span: i - 1,
        moved_knot: Some(i),
        problem: None,
        not_applicable: None,
    };
    if i < p || i > n + 1 {
        family.not_applicable = Some(FamilyNotApplicable::OutOfRange { moved_knot: i });
        return family;
    }
    if keep_domain && (i == p || i == n + 1) && knots[i] != t {
        family.not_applicable = Some(FamilyNotApplicable::MovesDomainEnd { moved_knot: i });
        return family;
    }
    if knots[i - 1] >= knots[i + 1] {
        family.not_applicable = Some(FamilyNotApplicable::EmptySpan { moved_knot: i });
        return family;
    }
    let full_index: Vec<usize> = (i - p..i).chain(i + 1..=i + p).collect();
    let problem = LocalProblem {
        degree: p - 1,
        knots: full_index.iter().map(|&k| knots[k]).collect(),
        full_index,
        poles: curve.homogeneous()[i - p..i].to_vec(),
        parameter: t,
    };
    finish(family, problem)
}

/// The local problem of the direct family at `t`: `Π_p` on the curve itself, span `j` of `t`.
pub fn direct_problem(curve: &Curve, t: f64, family: Family) -> FamilyProblem {
    let p = curve.degree();
    let knots = curve.knots();
    let j = curve.span(t);
    let full_index: Vec<usize> = (j - p..=j + p + 1).collect();
    let problem = LocalProblem {
        degree: p,
        knots: full_index.iter().map(|&k| knots[k]).collect(),
        full_index,
        poles: curve.homogeneous()[j - p..=j].to_vec(),
        parameter: t,
    };
    let family = FamilyProblem {
        family,
        side: None,
        span: j,
        moved_knot: None,
        problem: None,
        not_applicable: None,
    };
    finish(family, problem)
}

/// Attaches the problem, or the reason it does not apply (collinear local poles).
fn finish(mut family: FamilyProblem, problem: LocalProblem) -> FamilyProblem {
    let points: Vec<Point> = problem
        .poles
        .iter()
        .map(|h| [h[0] / h[3], h[1] / h[3], h[2] / h[3]])
        .collect();
    if plane_of(&points).is_none() {
        family.not_applicable = Some(FamilyNotApplicable::Collinear);
    }
    family.problem = Some(problem);
    family
}

/// The largest distance between two of `points`.
pub fn extent(points: &[Point]) -> f64 {
    let mut largest = 0.0f64;
    for (k, a) in points.iter().enumerate() {
        for b in &points[k + 1..] {
            largest = largest.max(norm(sub(*a, *b)));
        }
    }
    largest
}

/// An orthonormal basis `(e1, e2)` of the plane of the largest triangle of `points`, and its
/// unit normal; `None` when they are collinear ([`COLLINEAR_TOLERANCE`]).
pub fn plane_of(points: &[Point]) -> Option<[Point; 3]> {
    let size = extent(points);
    let mut best = (0.0, [0.0; 3], [0.0; 3]);
    for (a, &pa) in points.iter().enumerate() {
        for (b, &pb) in points.iter().enumerate().skip(a + 1) {
            for &pc in &points[b + 1..] {
                let (e, f) = (sub(pb, pa), sub(pc, pa));
                let normal = cross(e, f);
                let area = norm(normal);
                if area > best.0 {
                    best = (area, normal, if norm(e) >= norm(f) { e } else { f });
                }
            }
        }
    }
    let (area, normal, edge) = best;
    if area.is_nan() || area <= COLLINEAR_TOLERANCE * size * size {
        return None;
    }
    let unit = |v: Point| {
        let l = norm(v);
        [v[0] / l, v[1] / l, v[2] / l]
    };
    let normal = unit(normal);
    let e1 = unit(edge);
    let e2 = cross(normal, e1);
    Some([e1, e2, normal])
}

/// Triples are drawn from the `TRIPLE_WINDOW` relevant knots nearest `t` (`t_{q-2} …
/// t_{q+3}`): all of a cubic's, and on higher degrees the ones with leverage (a knot `k`
/// places from `t`'s span moves the point by about `distance^q`).
pub const TRIPLE_WINDOW: usize = 6;

/// The unknown sets of `size` (2 or 3) among local relevant knots `1 ..= 2q` (triples: the
/// [`TRIPLE_WINDOW`] nearest `t`), without the domain's ends (full indices `p` and `n + 1`)
/// while `keep_domain` holds.
pub fn unknown_sets(
    problem: &LocalProblem,
    size: usize,
    curve: &Curve,
    keep_domain: bool,
) -> Vec<Vec<usize>> {
    let q = problem.degree;
    let p = curve.degree();
    let n = curve.control_points().len() - 1;
    let (first, last) = if size == 3 {
        let half = TRIPLE_WINDOW / 2;
        ((q + 1).saturating_sub(half).max(1), (q + half).min(2 * q))
    } else {
        (1, 2 * q)
    };
    let movable: Vec<usize> = (first..=last)
        .filter(|&m| {
            let full = problem.full_index[m];
            !(keep_domain && (full == p || full == n + 1))
        })
        .collect();
    let mut sets = Vec::new();
    for (a, &ma) in movable.iter().enumerate() {
        for (b, &mb) in movable.iter().enumerate().skip(a + 1) {
            if size == 2 {
                sets.push(vec![ma, mb]);
            } else {
                for &mc in &movable[b + 1..] {
                    sets.push(vec![ma, mb, mc]);
                }
            }
        }
    }
    sets
}

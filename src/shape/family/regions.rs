//! The regions of every family's pairs, for drawing (docs/method.md §32): a cubic's envelope
//! pairs Ω1–Ω6 as the third release drew them, every other pair's outline by
//! [`super::outline`], in the plane of the control points acting (pairs whose control points
//! do not lie in one plane reach a curved surface, and triples a solid: neither is drawn).

use super::outline::{Outline, PlaneFrame, pair_outline};
use super::problems::{Family, FamilyChoice, FamilyProblem, extent, plane_of, unknown_sets};
use super::solve::{KnotSet, family_problems};
use crate::shape::candidate::PLANE_TOLERANCE;
use crate::shape::pairs::KnotPair;
use crate::shape::regions::{
    CandidateRegions, DEFAULT_RELATIVE_TOLERANCE, PolygonOptions, region_polygons,
};
use crate::shape::solve::ShapeQuery;
use crate::spline::vector::{Point, dot, sub};

/// One pair's region.
#[derive(Debug, Clone, PartialEq)]
pub struct SetRegion {
    /// The knots it moves.
    pub knots: KnotSet,
    /// Ω1–Ω6 for a cubic's envelope pairs.
    pub omega: Option<KnotPair>,
    /// Its outline.
    pub outline: Outline,
    /// For a cubic's envelope pairs: the polygon in the frame coordinates of §3.3.
    pub polygon_frame: Option<Vec<[f64; 2]>>,
}

/// One family's (and envelope side's) regions.
#[derive(Debug, Clone, PartialEq)]
pub struct FamilyRegions {
    /// The family and its local problem.
    pub problem: FamilyProblem,
    /// Why nothing is drawn, when so.
    pub reason: Option<String>,
    /// One entry per pair.
    pub regions: Vec<SetRegion>,
}

/// The regions of the requested families at `query.parameter`, with the cubic's envelope
/// candidates (for their original answer).
pub fn family_regions(
    query: &ShapeQuery,
    choice: FamilyChoice,
    options: PolygonOptions,
) -> (Vec<CandidateRegions>, Vec<FamilyRegions>) {
    let curve = query.curve;
    let mut candidates = Vec::new();
    let mut families = Vec::new();
    for problem in family_problems(query, choice) {
        if problem.family == Family::Envelope && curve.degree() == 3 {
            let Some(side) = problem.side else { continue };
            let side_query = ShapeQuery {
                side: match side {
                    crate::shape::Side::Right => crate::shape::SideChoice::Right,
                    crate::shape::Side::Left => crate::shape::SideChoice::Left,
                },
                ..*query
            };
            let drawn = region_polygons(&side_query, options).unwrap_or_default();
            for entry in drawn {
                families.push(FamilyRegions {
                    reason: entry.candidate.not_applicable.map(|r| r.to_string()),
                    regions: entry
                        .regions
                        .iter()
                        .map(|region| SetRegion {
                            knots: KnotSet::new(&region.knots),
                            omega: Some(region.pair),
                            outline: Outline {
                                rings: vec![region.polygon.clone()],
                                folded: false,
                                tolerance_met: region.tolerance_met,
                            },
                            polygon_frame: Some(region.polygon_frame.clone()),
                        })
                        .collect(),
                    problem: problem.clone(),
                });
                candidates.push(entry);
            }
            continue;
        }
        families.push(regions_of(query, problem, options));
    }
    (candidates, families)
}

/// The regions of one family that is not a cubic's envelope.
fn regions_of(
    query: &ShapeQuery,
    problem: FamilyProblem,
    options: PolygonOptions,
) -> FamilyRegions {
    let mut entry = FamilyRegions {
        reason: problem.not_applicable.map(|r| r.to_string()),
        regions: Vec::new(),
        problem,
    };
    let Some(local) = entry.problem.problem.clone() else {
        return entry;
    };
    if entry.reason.is_some() {
        return entry;
    }
    if entry.problem.family == Family::Triples {
        entry.reason = Some(
            "three knots reach a solid, not a region of a plane: triples are not drawn".to_string(),
        );
        return entry;
    }
    let poles = entry.problem.control_points();
    let size = extent(&poles);
    let Some(plane) = region_plane(query, &poles) else {
        entry.reason = Some(
            "the control points acting do not lie in one plane: each pair reaches a curved surface, which is not drawn"
                .to_string(),
        );
        return entry;
    };
    let tolerance = options
        .tolerance
        .unwrap_or(DEFAULT_RELATIVE_TOLERANCE * size);
    for unknowns in unknown_sets(&local, 2, query.curve, query.keep_domain) {
        let full: Vec<usize> = unknowns.iter().map(|&m| local.full_index[m]).collect();
        if let Some(outline) = pair_outline(
            &local,
            [unknowns[0], unknowns[1]],
            &plane,
            tolerance,
            options.max_vertices,
        ) {
            entry.regions.push(SetRegion {
                knots: KnotSet::new(&full),
                omega: None,
                outline,
                polygon_frame: None,
            });
        }
    }
    entry
}

/// The plane regions are drawn in: the curve's own for a 2D curve; for a 3D curve the plane
/// of the control points acting, when they lie in one (within [`PLANE_TOLERANCE`] of their
/// extent).
fn region_plane(query: &ShapeQuery, poles: &[Point]) -> Option<PlaneFrame> {
    if query.curve.dimension().count() == 2 {
        return Some(PlaneFrame {
            origin: [0.0; 3],
            e1: [1.0, 0.0, 0.0],
            e2: [0.0, 1.0, 0.0],
        });
    }
    let [e1, e2, normal] = plane_of(poles)?;
    let origin = poles[0];
    let size = extent(poles);
    let flat = poles
        .iter()
        .all(|&p| dot(sub(p, origin), normal).abs() <= PLANE_TOLERANCE * size);
    flat.then_some(PlaneFrame { origin, e1, e2 })
}

//! Wire types of the knot families (docs/api.md, "The knot method on every degree"): the
//! family names a request lists, each family's membership answer, and the region labels of
//! their pairs and triples, with knot indices in the caller's convention.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use crate::http::curve::{WirePoint, point_to_wire};
use crate::http::error::FieldError;
use crate::http::pointer::JsonPointer;
use crate::http::wire::shape_answer::caller_knot_index;
use crate::http::wire::shape_request::CandidateSide;
use crate::shape::KnotPair;
use crate::shape::family::{Family, FamilyChoice, FamilyGroup, FamilyRegions, KnotSet};
use crate::spline::Curve;

/// A knot family.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "lowercase")]
#[schema(example = json!("direct"))]
pub enum KnotFamily {
    /// The knot next to `t` on the chosen side moves to `t`, then a pair of the envelope's
    /// `2p − 2` relevant knots (degree ≥ 3; a cubic's pairs are Ω1–Ω6).
    Envelope,
    /// A pair of the curve's own `2p` relevant knots (degree ≥ 2).
    Direct,
    /// Three of the curve's own `2p` relevant knots: reaches 3D targets off the pairs' planes.
    Triples,
}

impl From<Family> for KnotFamily {
    fn from(family: Family) -> Self {
        match family {
            Family::Envelope => KnotFamily::Envelope,
            Family::Direct => KnotFamily::Direct,
            Family::Triples => KnotFamily::Triples,
        }
    }
}

/// The families of a request's `knot_families` (`None`: every family that applies); each
/// unknown name, repeat or an empty list is an error at its pointer.
pub fn parse_families(names: Option<&[String]>, errors: &mut Vec<FieldError>) -> FamilyChoice {
    let Some(names) = names else {
        return FamilyChoice::Default;
    };
    if names.is_empty() {
        errors.push(FieldError::new(
            "/knot_families",
            "`knot_families` must name at least one family (omit it for every family that applies)",
        ));
        return FamilyChoice::Default;
    }
    for (index, name) in names.iter().enumerate() {
        let pointer = JsonPointer::from("/knot_families").push(index);
        if Family::from_name(name).is_none() {
            errors.push(FieldError::new(
                pointer,
                format!("unknown knot family {name:?}: the families are \"envelope\", \"direct\" and \"triples\""),
            ));
        } else if names[..index].contains(name) {
            errors.push(FieldError::new(
                pointer,
                format!("knot family {name:?} is listed twice"),
            ));
        }
    }
    FamilyChoice::from_names(names.iter().map(String::as_str)).unwrap_or_default()
}

/// The region label of a pair or triple: `"omega1"` … `"omega6"` for a cubic's envelope
/// pairs, otherwise `"<family>:<a>,<b>"` (or `<a>,<b>,<c>`) with the knots' indices in the
/// caller's convention.
pub fn region_label(
    curve: &Curve,
    family: Family,
    omega: Option<KnotPair>,
    knots: &KnotSet,
) -> String {
    if let Some(pair) = omega {
        return pair.name().to_string();
    }
    let indices: Vec<String> = knots
        .indices()
        .iter()
        .map(|&full| caller_knot_index(curve, full).to_string())
        .collect();
    format!("{}:{}", family.name(), indices.join(","))
}

/// Whether one pair or triple of a family reaches the target.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[schema(example = json!({"region": "direct:4,6", "knots": [4, 6], "contains": true}))]
pub struct SetMembershipBody {
    /// The region label (`"omega1"` … `"omega6"` for a cubic's envelope pairs, otherwise
    /// `"<family>:<a>,<b>"` or `"triples:<a>,<b>,<c>"`).
    #[schema(example = "direct:4,6")]
    pub region: String,
    /// Indices (caller's convention) of the knots it moves.
    pub knots: Vec<usize>,
    /// True exactly when `/v1/shape/solve` gives a solution of these knots.
    pub contains: bool,
}

/// One knot family (one side of the envelope) at the picked parameter, with the membership
/// of its pairs or triples.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[schema(example = json!({"family": "direct", "applicable": true, "span": 5,
    "control_points": [[1, 3], [3, 4], [5, 3.5], [6, 1]],
    "pairs": [{"region": "direct:4,6", "knots": [4, 6], "contains": true}]}))]
pub struct FamilyMembershipBody {
    /// The family.
    pub family: KnotFamily,
    /// The envelope's side.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub side: Option<CandidateSide>,
    /// Whether the family can move the point here; when not, `reason` says why.
    pub applicable: bool,
    /// Why not.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reason: Option<String>,
    /// The span `j` (full-vector numbering): the envelope's moved knot is `u_{j+1}`; the
    /// direct pairs and triples work on the span `u_j ≤ t < u_{j+1}`.
    pub span: usize,
    /// Index (caller's convention) of the envelope's knot set to `t`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub moved_knot: Option<usize>,
    /// The control points acting: no knot move reaches a target outside their convex hull.
    #[schema(value_type = Vec<Vec<f64>>)]
    pub control_points: Vec<WirePoint>,
    /// One entry per pair (or triple) tried.
    pub pairs: Vec<SetMembershipBody>,
}

/// The wire form of the families' membership.
pub fn family_memberships(curve: &Curve, groups: &[FamilyGroup]) -> Vec<FamilyMembershipBody> {
    let dimension = curve.dimension();
    groups
        .iter()
        .map(|group| {
            let problem = &group.problem;
            FamilyMembershipBody {
                family: problem.family.into(),
                side: problem.side.map(Into::into),
                applicable: group.reason.is_none(),
                reason: group.reason.clone(),
                span: problem.span,
                moved_knot: problem.moved_knot.map(|i| caller_knot_index(curve, i)),
                control_points: problem
                    .control_points()
                    .into_iter()
                    .map(|p| point_to_wire(p, dimension))
                    .collect(),
                pairs: group
                    .members
                    .iter()
                    .map(|member| SetMembershipBody {
                        region: region_label(curve, problem.family, member.omega, &member.knots),
                        knots: member
                            .knots
                            .indices()
                            .iter()
                            .map(|&i| caller_knot_index(curve, i))
                            .collect(),
                        contains: member.contains,
                    })
                    .collect(),
            }
        })
        .collect()
}

/// One pair's region: the targets it reaches, as closed rings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[schema(example = json!({"region": "direct:5,7", "knots": [5, 7],
    "polygon": [[5.9, 1.2], [6.1, 1.2], [6.0, 1.4], [5.9, 1.2]],
    "polygons": [[[5.9, 1.2], [6.1, 1.2], [6.0, 1.4], [5.9, 1.2]]], "folded": false, "tolerance_met": true}))]
pub struct FamilyRegionBody {
    /// The region label, as in solve.
    #[schema(example = "direct:5,7")]
    pub region: String,
    /// Indices (caller's convention) of the pair's knots.
    pub knots: Vec<usize>,
    /// The outline of the largest part (first vertex repeated last), in the curve's
    /// coordinates.
    #[schema(value_type = Vec<Vec<f64>>)]
    pub polygon: Vec<WirePoint>,
    /// Every ring of the region (first vertex repeated last): outer rings counter-clockwise
    /// in the plane, each followed by its holes, clockwise. The region is what they enclose
    /// (non-zero winding).
    #[schema(value_type = Vec<Vec<Vec<f64>>>)]
    pub polygons: Vec<Vec<WirePoint>>,
    /// Whether the pair's map folds here: its region's outline then also follows the images
    /// of fold curves, and some targets have several solutions.
    pub folded: bool,
    /// Whether the outline is within `tolerance` of the true one everywhere.
    pub tolerance_met: bool,
    /// A cubic's envelope pairs: the polygon in frame coordinates `[x, y]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub polygon_frame: Option<Vec<[f64; 2]>>,
}

/// One knot family (one side of the envelope) with its pairs' regions.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[schema(example = json!({"family": "direct", "applicable": true, "span": 5,
    "control_points": [[1, 3], [3, 4], [5, 3.5], [6, 1]],
    "regions": [{"region": "direct:5,7", "knots": [5, 7],
        "polygon": [[5.9, 1.2], [6.1, 1.2], [6.0, 1.4], [5.9, 1.2]],
        "polygons": [[[5.9, 1.2], [6.1, 1.2], [6.0, 1.4], [5.9, 1.2]]], "folded": false, "tolerance_met": true}]}))]
pub struct FamilyRegionsBody {
    /// The family.
    pub family: KnotFamily,
    /// The envelope's side.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub side: Option<CandidateSide>,
    /// Whether regions are drawn; when not, `reason` says why (a family that does not apply,
    /// triples, or control points off one plane).
    pub applicable: bool,
    /// Why not.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reason: Option<String>,
    /// The span `j` (as in membership).
    pub span: usize,
    /// Index (caller's convention) of the envelope's knot set to `t`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub moved_knot: Option<usize>,
    /// The control points acting.
    #[schema(value_type = Vec<Vec<f64>>)]
    pub control_points: Vec<WirePoint>,
    /// One entry per pair drawn.
    pub regions: Vec<FamilyRegionBody>,
}

/// The wire form of the families' regions.
pub fn family_regions_bodies(curve: &Curve, families: &[FamilyRegions]) -> Vec<FamilyRegionsBody> {
    let dimension = curve.dimension();
    let ring = |points: &[crate::spline::vector::Point]| -> Vec<WirePoint> {
        points
            .iter()
            .map(|&p| point_to_wire(p, dimension))
            .collect()
    };
    families
        .iter()
        .map(|family| {
            let problem = &family.problem;
            FamilyRegionsBody {
                family: problem.family.into(),
                side: problem.side.map(Into::into),
                applicable: family.reason.is_none(),
                reason: family.reason.clone(),
                span: problem.span,
                moved_knot: problem.moved_knot.map(|i| caller_knot_index(curve, i)),
                control_points: ring(&problem.control_points()),
                regions: family
                    .regions
                    .iter()
                    .map(|region| {
                        let largest = region
                            .outline
                            .rings
                            .iter()
                            .max_by(|a, b| ring_area(a).total_cmp(&ring_area(b)))
                            .cloned()
                            .unwrap_or_default();
                        FamilyRegionBody {
                            region: region_label(
                                curve,
                                problem.family,
                                region.omega,
                                &region.knots,
                            ),
                            knots: region
                                .knots
                                .indices()
                                .iter()
                                .map(|&i| caller_knot_index(curve, i))
                                .collect(),
                            polygon: ring(&largest),
                            polygons: region.outline.rings.iter().map(|r| ring(r)).collect(),
                            folded: region.outline.folded,
                            tolerance_met: region.outline.tolerance_met,
                            polygon_frame: region.polygon_frame.clone(),
                        }
                    })
                    .collect(),
            }
        })
        .collect()
}

/// The area a closed ring encloses (its shoelace magnitude, over the plane it spans: the
/// length of the summed cross products).
fn ring_area(ring: &[crate::spline::vector::Point]) -> f64 {
    let mut sum = [0.0; 3];
    for w in ring.windows(2) {
        let c = crate::spline::vector::cross(w[0], w[1]);
        for k in 0..3 {
            sum[k] += c[k];
        }
    }
    0.5 * crate::spline::vector::norm(sum)
}

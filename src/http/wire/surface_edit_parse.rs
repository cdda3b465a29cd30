//! Validation of the surface-edit requests ([`super::surface_edit`]) into the core's
//! [`crate::surface::edit`] types, every broken rule a field error with its JSON pointer, and
//! the conversion of the core's answers back to the wire.

use crate::http::error::FieldError;
use crate::http::pointer::JsonPointer;
use crate::http::wire::surface_edit::{
    SurfaceConstraintBody, SurfaceConstraintValue, SurfaceExclusionBody, SurfaceKnotRegionBody,
    SurfaceMethod, SurfaceMethodRegionBody, SurfaceSolutionBody, TetrahedronBody,
};
use crate::spline::Point;
use crate::surface::edit::{
    FixedNet, SurfaceConstraintField, SurfaceConstraintSpec, SurfaceConstraints, SurfaceExclusion,
    SurfaceExclusionReason, SurfaceMethodKind, SurfaceReachable, SurfaceSolution,
    SurfaceSolutionDetail,
};
use crate::surface::{Direction, Surface, SurfaceLimits};

impl From<SurfaceMethodKind> for SurfaceMethod {
    fn from(kind: SurfaceMethodKind) -> Self {
        match kind {
            SurfaceMethodKind::Knots => SurfaceMethod::Knots,
            SurfaceMethodKind::ControlPoints => SurfaceMethod::ControlPoints,
            SurfaceMethodKind::Weights => SurfaceMethod::Weights,
        }
    }
}

/// The common part of solve and regions requests, validated.
#[derive(Debug, Clone)]
pub struct ParsedSurfaceEdit {
    /// The surface.
    pub surface: Surface,
    /// The picked `(u, v)`, snapped into the domain.
    pub parameter: (f64, f64),
    /// The requested methods.
    pub methods: Vec<SurfaceMethodKind>,
    /// The constraints.
    pub constraints: SurfaceConstraints,
    /// The fixed poles.
    pub fixed: FixedNet,
}

/// The fields of a request that [`parse_surface_edit`] checks.
pub struct SurfaceEditFields<'a> {
    /// `surface`.
    pub surface: &'a crate::http::surface::SurfaceBody,
    /// `parameter`.
    pub parameter: [f64; 2],
    /// `methods`.
    pub methods: Option<&'a [String]>,
    /// `constraints`.
    pub constraints: Option<&'a [SurfaceConstraintBody]>,
    /// `fixed_control_points`.
    pub fixed: Option<&'a [[usize; 2]]>,
    /// `keep_boundary`.
    pub keep_boundary: bool,
}

/// Validates every field, collecting all errors (a surface that does not parse stops the
/// checks that need it).
pub fn parse_surface_edit(
    fields: &SurfaceEditFields,
    limits: &SurfaceLimits,
    errors: &mut Vec<FieldError>,
) -> Option<ParsedSurfaceEdit> {
    let methods = parse_methods(fields.methods, errors);
    let surface = fields
        .surface
        .parse_collecting(limits, "/surface", errors)?;
    let mut parameter = [0.0; 2];
    for (c, axis) in [surface.u(), surface.v()].into_iter().enumerate() {
        match axis.snap(fields.parameter[c]) {
            Some(t) => parameter[c] = t,
            None => {
                let (lo, hi) = axis.domain();
                errors.push(FieldError::new(
                    JsonPointer::from("/parameter").push(c),
                    format!(
                        "{} = {} lies outside the domain [{lo}, {hi}]",
                        ["u", "v"][c],
                        fields.parameter[c]
                    ),
                ));
            }
        }
    }
    let picked = (parameter[0], parameter[1]);
    let fixed = match FixedNet::new(&surface, fields.fixed.unwrap_or(&[]), fields.keep_boundary) {
        Ok(fixed) => Some(fixed),
        Err(issues) => {
            errors.extend(issues.into_iter().map(|(position, error)| {
                FieldError::new(
                    JsonPointer::from("/fixed_control_points").push(position),
                    error.to_string(),
                )
            }));
            None
        }
    };
    if !errors.is_empty() {
        return None;
    }
    let constraints = parse_constraints(&surface, picked, fields.constraints, errors)?;
    Some(ParsedSurfaceEdit {
        surface,
        parameter: picked,
        methods: methods?,
        constraints,
        fixed: fixed?,
    })
}

/// Reads `methods` (default: all three): each name once, at least one.
fn parse_methods(
    names: Option<&[String]>,
    errors: &mut Vec<FieldError>,
) -> Option<Vec<SurfaceMethodKind>> {
    let Some(names) = names else {
        return Some(SurfaceMethodKind::ALL.to_vec());
    };
    if names.is_empty() {
        errors.push(FieldError::new(
            "/methods",
            "`methods` must name at least one method (omit it for all)",
        ));
        return None;
    }
    let before = errors.len();
    let mut kinds = Vec::new();
    for (index, name) in names.iter().enumerate() {
        let Some(kind) = SurfaceMethodKind::ALL
            .into_iter()
            .find(|k| k.name() == name)
        else {
            errors.push(FieldError::new(
                JsonPointer::from("/methods").push(index),
                format!(
                    "unknown method {name:?}: expected \"knots\", \"control_points\" or \"weights\""
                ),
            ));
            continue;
        };
        if kinds.contains(&kind) {
            errors.push(FieldError::new(
                JsonPointer::from("/methods").push(index),
                format!("method {name:?} is listed twice"),
            ));
        } else {
            kinds.push(kind);
        }
    }
    (errors.len() == before).then_some(kinds)
}

/// Validates `constraints` for `surface` and the picked parameter.
fn parse_constraints(
    surface: &Surface,
    picked: (f64, f64),
    bodies: Option<&[SurfaceConstraintBody]>,
    errors: &mut Vec<FieldError>,
) -> Option<SurfaceConstraints> {
    let Some(bodies) = bodies else {
        return Some(SurfaceConstraints::none());
    };
    // An order-0 value `[x, y, z]` is held as one vector, so both orders read alike.
    let values: Vec<Option<Vec<Vec<f64>>>> = bodies
        .iter()
        .map(|body| {
            body.value.as_ref().map(|value| match value {
                SurfaceConstraintValue::Point(point) => vec![point.clone()],
                SurfaceConstraintValue::Partials(vectors) => vectors.clone(),
            })
        })
        .collect();
    let specs: Vec<SurfaceConstraintSpec> = bodies
        .iter()
        .zip(&values)
        .map(|(body, value)| SurfaceConstraintSpec {
            parameter: body.parameter,
            order: body.order,
            value: value.as_deref(),
        })
        .collect();
    match SurfaceConstraints::new(surface, picked, &specs) {
        Ok(set) => Some(set),
        Err(issues) => {
            for issue in issues {
                let list = JsonPointer::from("/constraints");
                let pointer = match issue.index {
                    None => list,
                    Some(index) => {
                        let entry = list.push(index);
                        match issue.field {
                            SurfaceConstraintField::List | SurfaceConstraintField::Entry => entry,
                            SurfaceConstraintField::Parameter(c) => entry.push("parameter").push(c),
                            SurfaceConstraintField::Order => entry.push("order"),
                            SurfaceConstraintField::Value => entry.push("value"),
                            SurfaceConstraintField::ValueVector(k) => {
                                // An order-0 value is the point itself, not a list of vectors.
                                if matches!(
                                    bodies[index].value,
                                    Some(SurfaceConstraintValue::Point(_))
                                ) {
                                    entry.push("value")
                                } else {
                                    entry.push("value").push(k)
                                }
                            }
                        }
                    }
                };
                errors.push(FieldError::new(pointer, issue.error.to_string()));
            }
            None
        }
    }
}

/// `[x, y, z]`.
fn wire(point: Point) -> [f64; 3] {
    point
}

/// The wire form of one solution; `surface` is the edited one (for the caller's indices).
pub fn solution_body(solution: &SurfaceSolution) -> SurfaceSolutionBody {
    let [(u0, u1), (v0, v1)] = solution.affected_domain;
    let mut body = SurfaceSolutionBody {
        method: solution.detail.method().into(),
        point: wire(solution.point),
        residual: solution.residual,
        affected_domain: [[u0, u1], [v0, v1]],
        max_deviation: solution.max_deviation.unwrap_or(f64::NAN),
        conditioning: solution.conditioning,
        changed_control_points: None,
        displacement_norm: None,
        control_points: None,
        changed_weights: None,
        tetrahedron: None,
        weights: None,
        family: None,
        region: None,
        knots_u: None,
        knots_v: None,
        multiplicities_u: None,
        multiplicities_v: None,
        changed_knots_u: None,
        changed_knots_v: None,
    };
    match &solution.detail {
        SurfaceSolutionDetail::Knots {
            family,
            region,
            changed_knots_u,
            changed_knots_v,
            ..
        } => {
            body.family = Some((*family).to_string());
            body.region = Some(region.clone());
            let caller_indices = |direction: Direction, changed: &[usize]| {
                let axis = solution.surface.axis(direction);
                changed
                    .iter()
                    .map(|&i| {
                        axis.convention()
                            .caller_index(i, axis.knots().len())
                            .unwrap_or(i)
                    })
                    .collect::<Vec<usize>>()
            };
            if !changed_knots_u.is_empty() {
                let knots = solution.surface.caller_knots(Direction::U);
                body.knots_u = Some(knots.knots);
                body.multiplicities_u = knots.multiplicities;
                body.changed_knots_u = Some(caller_indices(Direction::U, changed_knots_u));
            }
            if !changed_knots_v.is_empty() {
                let knots = solution.surface.caller_knots(Direction::V);
                body.knots_v = Some(knots.knots);
                body.multiplicities_v = knots.multiplicities;
                body.changed_knots_v = Some(caller_indices(Direction::V, changed_knots_v));
            }
        }
        SurfaceSolutionDetail::ControlPoints {
            changed_control_points,
            displacement_norm,
        } => {
            body.changed_control_points = Some(changed_control_points.clone());
            body.displacement_norm = Some(*displacement_norm);
            body.control_points = Some(solution.surface.caller_control_points());
        }
        SurfaceSolutionDetail::Weights {
            poles, tetrahedron, ..
        } => {
            body.changed_weights = Some(poles.to_vec());
            body.tetrahedron = Some(tetrahedron.map(wire));
            body.weights = solution.surface.caller_weights();
        }
    }
    body
}

/// Whether every number of a solution is finite (JSON has no others).
pub fn solution_is_finite(body: &SurfaceSolutionBody) -> bool {
    let finite = |x: &f64| x.is_finite();
    body.point.iter().all(finite)
        && body.residual.is_finite()
        && body.max_deviation.is_finite()
        && body.affected_domain.iter().flatten().all(finite)
        && body
            .control_points
            .iter()
            .flatten()
            .flatten()
            .flatten()
            .all(finite)
        && body.weights.iter().flatten().flatten().all(finite)
        && body.knots_u.iter().flatten().all(finite)
        && body.knots_v.iter().flatten().all(finite)
        && body.tetrahedron.iter().flatten().flatten().all(finite)
}

/// The wire form of an exclusion.
pub fn exclusion_body(exclusion: &SurfaceExclusion) -> SurfaceExclusionBody {
    SurfaceExclusionBody {
        method: exclusion.method.into(),
        count: exclusion.count,
        reason: exclusion.reason.to_string(),
        constraint: exclusion.reason.constraint(),
        fixed_control_point: match exclusion.reason {
            SurfaceExclusionReason::MovesFixedPole { pole } => Some(pole),
            _ => None,
        },
    }
}

/// The wire form of one method's reachable set.
pub fn region_body(
    kind: SurfaceMethodKind,
    reachable: &SurfaceReachable,
) -> SurfaceMethodRegionBody {
    let mut body = SurfaceMethodRegionBody {
        method: kind.into(),
        everywhere: false,
        tetrahedra: None,
        knot_regions: None,
        reason: None,
    };
    match reachable {
        SurfaceReachable::Everywhere => body.everywhere = true,
        SurfaceReachable::Tetrahedra(regions) => {
            body.tetrahedra = Some(
                regions
                    .iter()
                    .map(|region| TetrahedronBody {
                        poles: region.poles,
                        tetrahedron: region.tetrahedron.map(wire),
                    })
                    .collect(),
            );
        }
        SurfaceReachable::KnotRegions(regions) => {
            body.knot_regions = Some(
                regions
                    .iter()
                    .filter(|region| {
                        region
                            .rings
                            .iter()
                            .flatten()
                            .flatten()
                            .all(|x| x.is_finite())
                    })
                    .map(|region| SurfaceKnotRegionBody {
                        family: region.family.name().to_string(),
                        region: region.region.clone(),
                        rings: region
                            .rings
                            .iter()
                            .map(|ring| ring.iter().map(|&p| wire(p)).collect())
                            .collect(),
                        folded: region.folded,
                    })
                    .collect(),
            );
        }
        SurfaceReachable::Nothing(reason) => body.reason = Some(reason.to_string()),
    }
    body
}

//! STEP (ISO 10303-21, "Part 21") B-spline curves and surfaces: `B_SPLINE_CURVE_WITH_KNOTS`
//! and its rational complex form `( BOUNDED_CURVE() B_SPLINE_CURVE(..)
//! B_SPLINE_CURVE_WITH_KNOTS(..) CURVE() GEOMETRIC_REPRESENTATION_ITEM()
//! RATIONAL_B_SPLINE_CURVE(..) REPRESENTATION_ITEM(..) )`, `B_SPLINE_SURFACE_WITH_KNOTS` and its
//! rational complex form likewise (`B_SPLINE_SURFACE`, `RATIONAL_B_SPLINE_SURFACE`), read from
//! any exchange file and written inside a shape representation that Open CASCADE's
//! `STEPControl_Reader` transfers (curves to edges, surfaces to faces).
//!
//! Hand-written, on purpose: the Rust STEP crates read whole application protocols (large
//! generated schemas) or do not bound their work on hostile input; these few entities need a
//! tokenizer and a parser of Part 21's instance syntax with limits (`step/syntax.rs`), and this
//! reader and writer of the entities, small enough to be fuzzed whole
//! (fuzz/fuzz_targets/step_import.rs). The reader and the writer of both entities stay in one
//! file (about 830 lines; the tests in `step/tests.rs`), over 600 on purpose: each is the
//! other's check, entity by entity, and the curve and surface forms share their parsing of
//! knots, weights and the complex instance.
//!
//! Reading: the syntax of the whole file is checked (header, data sections, every instance),
//! only `CARTESIAN_POINT`s and the B-spline curves and surfaces are kept, and every control
//! point reference is resolved to its point. Other curve and surface entities (`LINE`,
//! `CIRCLE`, `TRIMMED_CURVE`, `PLANE`, `CYLINDRICAL_SURFACE`, other B-spline forms, …) are
//! counted as skipped. Equal consecutive knots are merged (summing
//! their multiplicities), which some writers emit and the curve is the same with.

mod syntax;

use std::collections::HashMap;

use syntax::{Parser, Record, Token, Value, describe};

use super::numbers::real;
use super::{
    FileError, FileLimits, Imported, ImportedCurve, ImportedSurface, check_size, exportable_curve,
    exportable_knots, exportable_surface, malformed,
};
use crate::spline::{Curve, KnotForm, distinct_knots};
use crate::surface::{Direction, Surface};

/// The curve entity types that are counted as skipped (ISO 10303-42 curves other than the
/// B-spline curves with knots that are read).
const OTHER_CURVES: &[&str] = &[
    "BEZIER_CURVE",
    "BOUNDARY_CURVE",
    "B_SPLINE_CURVE",
    "CIRCLE",
    "CLOTHOID",
    "COMPOSITE_CURVE",
    "COMPOSITE_CURVE_ON_SURFACE",
    "CONIC",
    "CURVE_REPLICA",
    "DEGENERATE_PCURVE",
    "ELLIPSE",
    "EVALUATED_DEGENERATE_PCURVE",
    "HYPERBOLA",
    "INTERSECTION_CURVE",
    "LINE",
    "OFFSET_CURVE_2D",
    "OFFSET_CURVE_3D",
    "OUTER_BOUNDARY_CURVE",
    "PARABOLA",
    "PCURVE",
    "POLYLINE",
    "QUASI_UNIFORM_CURVE",
    "RATIONAL_B_SPLINE_CURVE",
    "SEAM_CURVE",
    "SURFACE_CURVE",
    "TRIMMED_CURVE",
    "UNIFORM_CURVE",
];

/// The surface entity types that are counted as skipped (ISO 10303-42 surfaces other than the
/// B-spline surfaces with knots that are read).
const OTHER_SURFACES: &[&str] = &[
    "BEZIER_SURFACE",
    "B_SPLINE_SURFACE",
    "CONICAL_SURFACE",
    "CURVE_BOUNDED_SURFACE",
    "CYLINDRICAL_SURFACE",
    "DEGENERATE_TOROIDAL_SURFACE",
    "OFFSET_SURFACE",
    "ORIENTED_SURFACE",
    "PLANE",
    "QUASI_UNIFORM_SURFACE",
    "RATIONAL_B_SPLINE_SURFACE",
    "RECTANGULAR_COMPOSITE_SURFACE",
    "RECTANGULAR_TRIMMED_SURFACE",
    "SPHERICAL_SURFACE",
    "SURFACE_OF_LINEAR_EXTRUSION",
    "SURFACE_OF_REVOLUTION",
    "SURFACE_REPLICA",
    "TOROIDAL_SURFACE",
    "UNIFORM_SURFACE",
];

/// A B-spline surface entity as read, before its points are resolved.
struct SurfaceEntity<'a> {
    id: u64,
    line: usize,
    degrees: [Value<'a>; 2],
    points: Value<'a>,
    multiplicities: [Value<'a>; 2],
    knots: [Value<'a>; 2],
    weights: Option<Value<'a>>,
}

/// A B-spline curve entity as read, before its points are resolved.
struct CurveEntity<'a> {
    id: u64,
    line: usize,
    degree: Value<'a>,
    points: Value<'a>,
    multiplicities: Value<'a>,
    knots: Value<'a>,
    weights: Option<Value<'a>>,
}

/// What the data section keeps while it is read.
#[derive(Default)]
struct Found<'a> {
    points: HashMap<u64, Vec<f64>>,
    /// Every instance name, with whether it is a point (for the error of a wrong reference).
    names: HashMap<u64, bool>,
    curves: Vec<CurveEntity<'a>>,
    surfaces: Vec<SurfaceEntity<'a>>,
    skipped: usize,
}

/// Reads every B-spline curve and surface of a STEP exchange file.
pub fn read(text: &str, limits: &FileLimits) -> Result<Imported, FileError> {
    check_size(text, limits)?;
    let mut parser = Parser::new(text);
    parser.expect(Token::Magic, "ISO-10303-21 at the start of the file")?;
    parser.expect(Token::Semicolon, "; after ISO-10303-21")?;
    parser.expect_keyword("HEADER")?;
    parser.expect(Token::Semicolon, "; after HEADER")?;
    let mut entities = 0usize;
    loop {
        match parser.required("a header entity or ENDSEC")? {
            Token::Keyword(k) if k.eq_ignore_ascii_case("ENDSEC") => break,
            Token::Keyword(keyword) => {
                count_entity(&mut entities, limits)?;
                parser.record(keyword)?;
                parser.expect(Token::Semicolon, "; after a header entity")?;
            }
            other => {
                return Err(malformed(
                    parser.line(),
                    format!("expected a header entity, found {}", describe(other)),
                ));
            }
        }
    }
    parser.expect(Token::Semicolon, "; after ENDSEC")?;
    let mut found = Found::default();
    let mut sections = 0;
    loop {
        match parser.required("DATA or END-ISO-10303-21")? {
            Token::EndMagic => break,
            Token::Keyword(k) if k.eq_ignore_ascii_case("DATA") => {
                sections += 1;
                if parser.peek()? == Some(Token::Open) {
                    parser.next()?;
                    parser.list(1)?;
                }
                parser.expect(Token::Semicolon, "; after DATA")?;
                data_section(&mut parser, &mut found, &mut entities, limits)?;
            }
            Token::Keyword(k)
                if k.eq_ignore_ascii_case("ANCHOR")
                    || k.eq_ignore_ascii_case("REFERENCE")
                    || k.eq_ignore_ascii_case("SIGNATURE") =>
            {
                return Err(malformed(
                    parser.line(),
                    format!("{k} sections are not supported"),
                ));
            }
            other => {
                return Err(malformed(
                    parser.line(),
                    format!("expected DATA, found {}", describe(other)),
                ));
            }
        }
    }
    if sections == 0 {
        return Err(malformed(parser.line(), "the file has no DATA section"));
    }
    parser.expect(Token::Semicolon, "; after END-ISO-10303-21")?;
    if let Some(token) = parser.next()? {
        return Err(malformed(
            parser.line(),
            format!("{} after the end of the file", describe(token)),
        ));
    }
    let curves = found
        .curves
        .iter()
        .map(|entity| build_curve(entity, &found, limits))
        .collect::<Result<_, _>>()?;
    let surfaces = found
        .surfaces
        .iter()
        .map(|entity| build_surface(entity, &found, limits))
        .collect::<Result<_, _>>()?;
    Ok(Imported {
        curves,
        surfaces,
        skipped: found.skipped,
    })
}

fn count_entity(entities: &mut usize, limits: &FileLimits) -> Result<(), FileError> {
    *entities += 1;
    if *entities > limits.max_entities {
        return Err(FileError::TooManyEntities {
            max: limits.max_entities,
        });
    }
    Ok(())
}

/// The instances of one data section, up to its `ENDSEC;`.
fn data_section<'a>(
    parser: &mut Parser<'a>,
    found: &mut Found<'a>,
    entities: &mut usize,
    limits: &FileLimits,
) -> Result<(), FileError> {
    loop {
        let id = match parser.required("an instance or ENDSEC")? {
            Token::Keyword(k) if k.eq_ignore_ascii_case("ENDSEC") => {
                return parser.expect(Token::Semicolon, "; after ENDSEC");
            }
            Token::Ref(id) => id,
            other => {
                return Err(malformed(
                    parser.line(),
                    format!("expected an instance #N = …, found {}", describe(other)),
                ));
            }
        };
        count_entity(entities, limits)?;
        let line = parser.line();
        parser.expect(Token::Equals, "= after an instance name")?;
        let records = match parser.required("an entity")? {
            Token::Keyword(keyword) => vec![parser.record(keyword)?],
            Token::Open => {
                let mut records = Vec::new();
                loop {
                    match parser.required("a record or )")? {
                        Token::Close if !records.is_empty() => break,
                        Token::Keyword(keyword) => records.push(parser.record(keyword)?),
                        other => {
                            return Err(malformed(
                                parser.line(),
                                format!(
                                    "expected a record of a complex entity, found {}",
                                    describe(other)
                                ),
                            ));
                        }
                    }
                }
                records
            }
            other => {
                return Err(malformed(
                    parser.line(),
                    format!("expected an entity, found {}", describe(other)),
                ));
            }
        };
        parser.expect(Token::Semicolon, "; after an instance")?;
        let is_point =
            records.len() == 1 && records[0].keyword.eq_ignore_ascii_case("CARTESIAN_POINT");
        if found.names.insert(id, is_point).is_some() {
            return Err(malformed(line, format!("#{id} is defined twice")));
        }
        keep(id, line, records, found)?;
    }
}

/// Keeps what an instance holds for the curves and surfaces: a point's coordinates, a
/// B-spline curve's or surface's parameters; counts the other curves and surfaces.
fn keep<'a>(
    id: u64,
    line: usize,
    records: Vec<Record<'a>>,
    found: &mut Found<'a>,
) -> Result<(), FileError> {
    let has = |name: &str| {
        records
            .iter()
            .position(|r| r.keyword.eq_ignore_ascii_case(name))
    };
    if let [record] = &records[..] {
        if record.keyword.eq_ignore_ascii_case("CARTESIAN_POINT") {
            let coordinates = match &record.parameters[..] {
                [_, Value::List(values)] => values.iter().map(number).collect::<Option<Vec<f64>>>(),
                _ => None,
            };
            let Some(coordinates) = coordinates else {
                return Err(malformed(
                    line,
                    format!("#{id}: a CARTESIAN_POINT is (name, (coordinates))"),
                ));
            };
            found.points.insert(id, coordinates);
            return Ok(());
        }
    }
    if let Some(with_knots) = has("B_SPLINE_CURVE_WITH_KNOTS") {
        let entity = if records.len() == 1 {
            match <[Value; 9]>::try_from(
                records
                    .into_iter()
                    .next()
                    .map(|r| r.parameters)
                    .unwrap_or_default(),
            ) {
                Ok([_, degree, points, _, _, _, multiplicities, knots, _]) => CurveEntity {
                    id,
                    line,
                    degree,
                    points,
                    multiplicities,
                    knots,
                    weights: None,
                },
                Err(_) => {
                    return Err(malformed(
                        line,
                        format!("#{id}: B_SPLINE_CURVE_WITH_KNOTS has 9 parameters"),
                    ));
                }
            }
        } else {
            let Some(base) = has("B_SPLINE_CURVE") else {
                return Err(malformed(
                    line,
                    format!(
                        "#{id}: a complex B_SPLINE_CURVE_WITH_KNOTS needs its B_SPLINE_CURVE record"
                    ),
                ));
            };
            let rational = has("RATIONAL_B_SPLINE_CURVE");
            let mut records: Vec<Option<Record>> = records.into_iter().map(Some).collect();
            let mut take = |index: usize, count: usize, name: &str| {
                let parameters = records[index]
                    .take()
                    .map(|r| r.parameters)
                    .unwrap_or_default();
                if parameters.len() == count {
                    Ok(parameters)
                } else {
                    Err(malformed(
                        line,
                        format!("#{id}: {name} has {count} parameters here"),
                    ))
                }
            };
            let [degree, points, _, _, _] =
                <[Value; 5]>::try_from(take(base, 5, "B_SPLINE_CURVE")?)
                    .map_err(|_| malformed(line, "B_SPLINE_CURVE"))?;
            let [multiplicities, knots, _] =
                <[Value; 3]>::try_from(take(with_knots, 3, "B_SPLINE_CURVE_WITH_KNOTS")?)
                    .map_err(|_| malformed(line, "B_SPLINE_CURVE_WITH_KNOTS"))?;
            let weights = match rational {
                Some(index) => take(index, 1, "RATIONAL_B_SPLINE_CURVE")?.pop(),
                None => None,
            };
            CurveEntity {
                id,
                line,
                degree,
                points,
                multiplicities,
                knots,
                weights,
            }
        };
        found.curves.push(entity);
        return Ok(());
    }
    if let Some(with_knots) = has("B_SPLINE_SURFACE_WITH_KNOTS") {
        found
            .surfaces
            .push(surface_entity(id, line, records, with_knots)?);
        return Ok(());
    }
    if records.iter().any(|r| {
        OTHER_CURVES
            .iter()
            .chain(OTHER_SURFACES)
            .any(|c| r.keyword.eq_ignore_ascii_case(c))
    }) {
        found.skipped += 1;
    }
    Ok(())
}

/// The parameters of a B-spline surface entity, simple (13 parameters) or complex
/// (`B_SPLINE_SURFACE` with 7, `B_SPLINE_SURFACE_WITH_KNOTS` with 5, optionally
/// `RATIONAL_B_SPLINE_SURFACE` with 1).
fn surface_entity<'a>(
    id: u64,
    line: usize,
    records: Vec<Record<'a>>,
    with_knots: usize,
) -> Result<SurfaceEntity<'a>, FileError> {
    if records.len() == 1 {
        let parameters = records
            .into_iter()
            .next()
            .map(|r| r.parameters)
            .unwrap_or_default();
        return match <[Value; 13]>::try_from(parameters) {
            Ok([_, du, dv, points, _, _, _, _, mu, mv, ku, kv, _]) => Ok(SurfaceEntity {
                id,
                line,
                degrees: [du, dv],
                points,
                multiplicities: [mu, mv],
                knots: [ku, kv],
                weights: None,
            }),
            Err(_) => Err(malformed(
                line,
                format!("#{id}: B_SPLINE_SURFACE_WITH_KNOTS has 13 parameters"),
            )),
        };
    }
    let position = |name: &str| {
        records
            .iter()
            .position(|r| r.keyword.eq_ignore_ascii_case(name))
    };
    let Some(base) = position("B_SPLINE_SURFACE") else {
        return Err(malformed(
            line,
            format!(
                "#{id}: a complex B_SPLINE_SURFACE_WITH_KNOTS needs its B_SPLINE_SURFACE record"
            ),
        ));
    };
    let rational = position("RATIONAL_B_SPLINE_SURFACE");
    let mut records: Vec<Option<Record>> = records.into_iter().map(Some).collect();
    let mut take = |index: usize, count: usize, name: &str| {
        let parameters = records[index]
            .take()
            .map(|r| r.parameters)
            .unwrap_or_default();
        if parameters.len() == count {
            Ok(parameters)
        } else {
            Err(malformed(
                line,
                format!("#{id}: {name} has {count} parameters here"),
            ))
        }
    };
    let [du, dv, points, _, _, _, _] = <[Value; 7]>::try_from(take(base, 7, "B_SPLINE_SURFACE")?)
        .map_err(|_| malformed(line, "B_SPLINE_SURFACE"))?;
    let [mu, mv, ku, kv, _] =
        <[Value; 5]>::try_from(take(with_knots, 5, "B_SPLINE_SURFACE_WITH_KNOTS")?)
            .map_err(|_| malformed(line, "B_SPLINE_SURFACE_WITH_KNOTS"))?;
    let weights = match rational {
        Some(index) => take(index, 1, "RATIONAL_B_SPLINE_SURFACE")?.pop(),
        None => None,
    };
    Ok(SurfaceEntity {
        id,
        line,
        degrees: [du, dv],
        points,
        multiplicities: [mu, mv],
        knots: [ku, kv],
        weights,
    })
}

/// A number parameter (integers are numbers too).
fn number(value: &Value<'_>) -> Option<f64> {
    match *value {
        Value::Real(v) => Some(v),
        Value::Integer(v) => Some(v as f64),
        _ => None,
    }
}

/// The curve of a B-spline entity, its points resolved.
fn build_curve<'v, 'a>(
    entity: &'v CurveEntity<'a>,
    found: &Found<'_>,
    limits: &FileLimits,
) -> Result<ImportedCurve, FileError> {
    let (id, line) = (entity.id, entity.line);
    let bad = |what: &str| malformed(line, format!("#{id}: {what}"));
    let degree = match entity.degree {
        Value::Integer(d) if d >= 0 => d as usize,
        _ => return Err(bad("the degree must be an integer >= 0")),
    };
    let Value::List(references) = &entity.points else {
        return Err(bad("the control points must be a list of references"));
    };
    let mut points: Vec<&[f64]> = Vec::with_capacity(references.len());
    for reference in references {
        let Value::Ref(point) = reference else {
            return Err(bad("the control points must be a list of references"));
        };
        match (found.points.get(point), found.names.get(point)) {
            (Some(coordinates), _) => points.push(coordinates),
            (None, Some(_)) => return Err(bad(&format!("#{point} is not a CARTESIAN_POINT"))),
            (None, None) => return Err(bad(&format!("#{point} is not defined in the file"))),
        }
    }
    let list_of = |value: &'v Value<'a>, what: &str| match value {
        Value::List(values) => Ok(values.as_slice()),
        _ => Err(bad(&format!("the {what} must be a list"))),
    };
    let mut multiplicities = Vec::new();
    for value in list_of(&entity.multiplicities, "knot multiplicities")? {
        match value {
            Value::Integer(m) if *m >= 0 => multiplicities.push(*m as usize),
            _ => return Err(bad("the knot multiplicities must be integers >= 0")),
        }
    }
    let knots = list_of(&entity.knots, "knots")?
        .iter()
        .map(number)
        .collect::<Option<Vec<f64>>>()
        .ok_or_else(|| bad("the knots must be numbers"))?;
    let weights = match &entity.weights {
        None => None,
        Some(value) => Some(
            list_of(value, "weights")?
                .iter()
                .map(number)
                .collect::<Option<Vec<f64>>>()
                .ok_or_else(|| bad("the weights must be numbers"))?,
        ),
    };
    let (knots, multiplicities) = merged(&knots, &multiplicities);
    let source = format!("#{id}");
    let curve = Curve::from_knot_form(
        degree,
        &points,
        KnotForm::Multiplicities {
            knots: &knots,
            multiplicities: &multiplicities,
        },
        weights.as_deref(),
        &limits.curve_limits,
    )
    .map_err(|error| FileError::InvalidCurve {
        entity: source.clone(),
        error,
    })?;
    Ok(ImportedCurve { curve, source })
}

/// The surface of a B-spline surface entity, its points resolved (3D points only: a surface
/// lives in space).
fn build_surface(
    entity: &SurfaceEntity<'_>,
    found: &Found<'_>,
    limits: &FileLimits,
) -> Result<ImportedSurface, FileError> {
    let (id, line) = (entity.id, entity.line);
    let bad = |what: &str| malformed(line, format!("#{id}: {what}"));
    let mut degrees = [0usize; 2];
    for (slot, value) in degrees.iter_mut().zip(&entity.degrees) {
        *slot = match *value {
            Value::Integer(d) if d >= 0 => d as usize,
            _ => return Err(bad("the degrees must be integers >= 0")),
        };
    }
    let Value::List(rows) = &entity.points else {
        return Err(bad(
            "the control points must be a list of lists of references",
        ));
    };
    // The point count is bounded by the file's entity count (each reference is a token).
    let mut points: Vec<Vec<&[f64]>> = Vec::with_capacity(rows.len());
    for row in rows {
        let Value::List(references) = row else {
            return Err(bad(
                "the control points must be a list of lists of references",
            ));
        };
        let mut out = Vec::with_capacity(references.len());
        for reference in references {
            let Value::Ref(point) = reference else {
                return Err(bad(
                    "the control points must be a list of lists of references",
                ));
            };
            match (found.points.get(point), found.names.get(point)) {
                (Some(coordinates), _) => out.push(coordinates.as_slice()),
                (None, Some(_)) => return Err(bad(&format!("#{point} is not a CARTESIAN_POINT"))),
                (None, None) => return Err(bad(&format!("#{point} is not defined in the file"))),
            }
        }
        points.push(out);
    }
    if points.is_empty() {
        return Err(bad("the control points must not be empty"));
    }
    let list_of = |value: &Value<'_>, what: &str| -> Result<Vec<f64>, FileError> {
        match value {
            Value::List(values) => values
                .iter()
                .map(number)
                .collect::<Option<Vec<f64>>>()
                .ok_or_else(|| bad(&format!("the {what} must be numbers"))),
            _ => Err(bad(&format!("the {what} must be a list"))),
        }
    };
    let mut directions = Vec::with_capacity(2);
    for k in 0..2 {
        let mut multiplicities = Vec::new();
        let Value::List(values) = &entity.multiplicities[k] else {
            return Err(bad("the knot multiplicities must be a list"));
        };
        for value in values {
            match value {
                Value::Integer(m) if *m >= 0 => multiplicities.push(*m as usize),
                _ => return Err(bad("the knot multiplicities must be integers >= 0")),
            }
        }
        let knots = list_of(&entity.knots[k], "knots")?;
        directions.push(merged(&knots, &multiplicities));
    }
    let weights = match &entity.weights {
        None => None,
        Some(Value::List(rows)) => Some(
            rows.iter()
                .map(|row| list_of(row, "weights"))
                .collect::<Result<Vec<Vec<f64>>, _>>()?,
        ),
        Some(_) => return Err(bad("the weights must be a list of lists")),
    };
    let source = format!("#{id}");
    let form = |k: usize| KnotForm::Multiplicities {
        knots: &directions[k].0,
        multiplicities: &directions[k].1,
    };
    let surface = Surface::from_knot_forms(
        (degrees[0], degrees[1]),
        &points,
        (form(0), form(1)),
        weights.as_deref(),
        &limits.surface_limits,
    )
    .map_err(|error| FileError::InvalidSurface {
        entity: source.clone(),
        error,
    })?;
    Ok(ImportedSurface { surface, source })
}

/// Equal consecutive knots merged into one, their multiplicities summed (a length mismatch is
/// left for the curve's validation to name).
fn merged(knots: &[f64], multiplicities: &[usize]) -> (Vec<f64>, Vec<usize>) {
    if knots.len() != multiplicities.len() {
        return (knots.to_vec(), multiplicities.to_vec());
    }
    let mut out_knots: Vec<f64> = Vec::with_capacity(knots.len());
    let mut out_multiplicities: Vec<usize> = Vec::with_capacity(knots.len());
    for (&u, &m) in knots.iter().zip(multiplicities) {
        match (out_knots.last(), out_multiplicities.last_mut()) {
            (Some(&last), Some(count)) if last == u => *count = count.saturating_add(m),
            _ => {
                out_knots.push(u);
                out_multiplicities.push(m);
            }
        }
    }
    (out_knots, out_multiplicities)
}

/// A STEP exchange file (AP214, `AUTOMOTIVE_DESIGN`) holding `curves` and `surfaces` as
/// Open CASCADE writes geometry: curves alone in one `GEOMETRIC_CURVE_SET` of a
/// `GEOMETRICALLY_BOUNDED_WIREFRAME_SHAPE_REPRESENTATION` of one product (each transferred to
/// an edge by `STEPControl_Reader`); with surfaces, curves and surfaces in one
/// `GEOMETRIC_SET` of a `GEOMETRICALLY_BOUNDED_SURFACE_SHAPE_REPRESENTATION` (each surface
/// transferred to a face over its whole domain). Numbers in full precision (the shortest
/// digits that read back exactly); 2D curves with `z = 0`; a periodic curve or surface
/// direction as the clamped one over its period (STEP has no periodic form); knots as
/// distinct values with multiplicities. Lengths in millimetres.
pub fn write(curves: &[Curve], surfaces: &[Surface]) -> String {
    let mut out = String::new();
    let (kind, representation, set) = if surfaces.is_empty() {
        (
            "curves",
            "GEOMETRICALLY_BOUNDED_WIREFRAME_SHAPE_REPRESENTATION",
            "GEOMETRIC_CURVE_SET",
        )
    } else {
        (
            "surfaces",
            "GEOMETRICALLY_BOUNDED_SURFACE_SHAPE_REPRESENTATION",
            "GEOMETRIC_SET",
        )
    };
    out.push_str("ISO-10303-21;\nHEADER;\n");
    if surfaces.is_empty() {
        out.push_str("FILE_DESCRIPTION(('knotshape B-spline curves'),'2;1');\n");
    } else {
        out.push_str("FILE_DESCRIPTION(('knotshape B-spline curves and surfaces'),'2;1');\n");
    }
    out.push_str(&format!(
        "FILE_NAME('{kind}.step','',(''),(''),'knotshape','knotshape','');\n"
    ));
    out.push_str("FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));\nENDSEC;\nDATA;\n");
    let preamble = [
        "#1=APPLICATION_PROTOCOL_DEFINITION('international standard','automotive_design',2000,#2);",
        "#2=APPLICATION_CONTEXT('core data for automotive mechanical design processes');",
        "#3=SHAPE_DEFINITION_REPRESENTATION(#4,#10);",
        "#4=PRODUCT_DEFINITION_SHAPE('','',#5);",
        "#5=PRODUCT_DEFINITION('design','',#6,#9);",
        "#6=PRODUCT_DEFINITION_FORMATION('','',#7);",
        "#7=PRODUCT('{kind}','{kind}','',(#8));",
        "#8=PRODUCT_CONTEXT('',#2,'mechanical');",
        "#9=PRODUCT_DEFINITION_CONTEXT('part definition',#2,'design');",
        "#10={representation}('{kind}',(#11,#15),#20);",
        "#11=AXIS2_PLACEMENT_3D('',#12,#13,#14);",
        "#12=CARTESIAN_POINT('',(0.,0.,0.));",
        "#13=DIRECTION('',(0.,0.,1.));",
        "#14=DIRECTION('',(1.,0.,0.));",
        "#16=PRODUCT_RELATED_PRODUCT_CATEGORY('part',$,(#7));",
        "#20=(GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#24)) GLOBAL_UNIT_ASSIGNED_CONTEXT((#21,#22,#23)) REPRESENTATION_CONTEXT('Context #1','3D Context with UNIT and UNCERTAINTY'));",
        "#21=(LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.));",
        "#22=(NAMED_UNIT(*) PLANE_ANGLE_UNIT() SI_UNIT($,.RADIAN.));",
        "#23=(NAMED_UNIT(*) SI_UNIT($,.STERADIAN.) SOLID_ANGLE_UNIT());",
        "#24=UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE(1.E-7),#21,'distance_accuracy_value','confusion accuracy');",
    ];
    for line in preamble {
        out.push_str(
            &line
                .replace("{kind}", kind)
                .replace("{representation}", representation),
        );
        out.push('\n');
    }
    let mut next_id = 100u64;
    let mut item_ids = Vec::with_capacity(curves.len() + surfaces.len());
    let mut fresh = || {
        next_id += 1;
        next_id - 1
    };
    let point = |out: &mut String, id: u64, point: &[f64]| {
        out.push_str(&format!(
            "#{id}=CARTESIAN_POINT('',({},{},{}));\n",
            real(point[0]),
            real(point[1]),
            real(point.get(2).copied().unwrap_or(0.0))
        ));
        id
    };
    for curve in curves.iter().map(exportable_curve) {
        let curve = &curve;
        let point_ids: Vec<u64> = curve
            .control_points()
            .iter()
            .map(|p| point(&mut out, fresh(), p))
            .collect();
        let id = fresh();
        item_ids.push(id);
        let (knots, multiplicities) = distinct_knots(&exportable_knots(curve));
        let points = joined(point_ids.iter().map(|id| format!("#{id}")));
        let multiplicities = joined(multiplicities.iter().map(usize::to_string));
        let knots = joined(knots.iter().map(|&u| real(u)));
        let degree = curve.degree();
        match curve.weights() {
            None => out.push_str(&format!(
                "#{id}=B_SPLINE_CURVE_WITH_KNOTS('',{degree},({points}),.UNSPECIFIED.,.F.,.F.,({multiplicities}),({knots}),.UNSPECIFIED.);\n"
            )),
            Some(weights) => {
                let weights = joined(weights.iter().map(|&w| real(w)));
                out.push_str(&format!(
                    "#{id}=(BOUNDED_CURVE() B_SPLINE_CURVE({degree},({points}),.UNSPECIFIED.,.F.,.F.) B_SPLINE_CURVE_WITH_KNOTS(({multiplicities}),({knots}),.UNSPECIFIED.) CURVE() GEOMETRIC_REPRESENTATION_ITEM() RATIONAL_B_SPLINE_CURVE(({weights})) REPRESENTATION_ITEM(''));\n"
                ));
            }
        }
    }
    for surface in surfaces.iter().map(exportable_surface) {
        let (n_u, n_v) = (surface.u().count(), surface.v().count());
        let rows: Vec<String> = (0..n_u)
            .map(|i| {
                let ids: Vec<u64> = (0..n_v)
                    .map(|j| point(&mut out, fresh(), &surface.control_point(i, j)))
                    .collect();
                format!("({})", joined(ids.iter().map(|id| format!("#{id}"))))
            })
            .collect();
        let id = fresh();
        item_ids.push(id);
        let points = rows.join(",");
        let direction = |direction: Direction| {
            let curve = match direction {
                Direction::U => surface.column(0),
                Direction::V => surface.row(0),
            };
            let (knots, multiplicities) = distinct_knots(&exportable_knots(&curve));
            (
                joined(multiplicities.iter().map(usize::to_string)),
                joined(knots.iter().map(|&u| real(u))),
            )
        };
        let ((mu, ku), (mv, kv)) = (direction(Direction::U), direction(Direction::V));
        let (du, dv) = (surface.u().degree(), surface.v().degree());
        if surface.is_rational() {
            let weights = (0..n_u)
                .map(|i| format!("({})", joined((0..n_v).map(|j| real(surface.weight(i, j))))))
                .collect::<Vec<_>>()
                .join(",");
            out.push_str(&format!(
                "#{id}=(BOUNDED_SURFACE() B_SPLINE_SURFACE({du},{dv},({points}),.UNSPECIFIED.,.F.,.F.,.F.) B_SPLINE_SURFACE_WITH_KNOTS(({mu}),({mv}),({ku}),({kv}),.UNSPECIFIED.) GEOMETRIC_REPRESENTATION_ITEM() RATIONAL_B_SPLINE_SURFACE(({weights})) REPRESENTATION_ITEM('') SURFACE());\n"
            ));
        } else {
            out.push_str(&format!(
                "#{id}=B_SPLINE_SURFACE_WITH_KNOTS('',{du},{dv},({points}),.UNSPECIFIED.,.F.,.F.,.F.,({mu}),({mv}),({ku}),({kv}),.UNSPECIFIED.);\n"
            ));
        }
    }
    let items = joined(item_ids.iter().map(|id| format!("#{id}")));
    out.push_str(&format!("#15={set}('{kind}',({items}));\n"));
    out.push_str("ENDSEC;\nEND-ISO-10303-21;\n");
    out
}

fn joined(items: impl Iterator<Item = String>) -> String {
    items.collect::<Vec<_>>().join(",")
}

#[cfg(test)]
mod tests;

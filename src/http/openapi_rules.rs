//! The rules the server enforces, written into the generated OpenAPI document where utoipa's
//! derive cannot state them: array lengths (points of 2 or 3 coordinates, pairs, triangles),
//! exclusive minimums, unique region lists, exactly one way of choosing parameters, problem
//! status codes, response headers, open operations, a `servers` entry; and the shape of
//! answers as they are sent: optional fields of answer-only schemas are left out, never
//! `null`, request fields carry no `default` (generators would make such fields required), and
//! candidates are unions told apart by `applicable`.

use serde_json::{Map, Value, json};

/// `(schema, property, levels of items below the property, min items, max items)`.
const ARRAY_LENGTHS: &[(&str, &str, usize, u64, u64)] = &[
    // Points: 2 (planar) or 3 (spatial) coordinates.
    ("BezierSegment", "control_points", 1, 2, 3),
    ("CandidateBody", "triangle", 1, 2, 3),
    ("ClosestPointRequest", "points", 1, 2, 3),
    ("ClosestPointResult", "point", 0, 2, 3),
    ("CurveBody", "control_points", 1, 2, 3),
    ("EvaluateResponse", "points", 1, 2, 3),
    ("EvaluateResponse", "derivatives", 2, 2, 3),
    ("NearestBody", "point", 0, 2, 3),
    ("RegionPolygonBody", "polygon", 1, 2, 3),
    ("RegionPolygonBody", "polygon_frame", 1, 2, 2),
    ("RegionsRequest", "target", 0, 2, 3),
    ("ShapeRequest", "target", 0, 2, 3),
    ("ConstraintBody", "value", 0, 2, 3),
    ("KnotSolutionBody", "point", 0, 2, 3),
    ("ControlPointSolutionBody", "point", 0, 2, 3),
    ("ControlPointSolutionBody", "control_points", 1, 2, 3),
    ("WeightSolutionBody", "point", 0, 2, 3),
    ("WeightRegionBody", "triangle", 1, 2, 3),
    ("WeightRegionBody", "polygon", 1, 2, 3),
    ("WeightRegionBody", "polygon_frame", 1, 2, 2),
    // Triangles: three points.
    ("CandidateBody", "triangle", 0, 3, 3),
    ("WeightRegionBody", "triangle", 0, 3, 3),
    // Pairs: `[lo, hi]` intervals and the two knots of a region.
    ("BezierSegment", "domain", 0, 2, 2),
    ("ClosestPointRequest", "range", 0, 2, 2),
    ("EnvelopeResponse", "range", 0, 2, 2),
    ("EvaluateResponse", "domain", 0, 2, 2),
    ("RegionMembershipBody", "knots", 0, 2, 2),
    ("RegionPolygonBody", "knots", 0, 2, 2),
    ("KnotSolutionBody", "affected_domain", 0, 2, 2),
    ("ControlPointSolutionBody", "affected_domain", 0, 2, 2),
    ("WeightSolutionBody", "affected_domain", 0, 2, 2),
    // The two poles of a weight pair.
    ("WeightSolutionBody", "poles", 0, 2, 2),
    ("WeightPairBody", "poles", 0, 2, 2),
    ("WeightRegionBody", "poles", 0, 2, 2),
    // At most `MAX_CONSTRAINTS` constraints.
    (
        "ShapeRequest",
        "constraints",
        0,
        0,
        crate::shape::MAX_CONSTRAINTS as u64,
    ),
    // The curve toolkit of the third release.
    ("InterpolateRequest", "points", 1, 2, 3),
    ("InterpolateRequest", "end_tangents", 0, 2, 2),
    ("InterpolateRequest", "end_tangents", 1, 2, 3),
    ("ApproximateRequest", "points", 1, 2, 3),
    ("LengthRequest", "range", 0, 2, 2),
    // Surfaces (fourth release): 3D points, pairs, ranges of two pairs.
    ("SurfaceBody", "control_points", 2, 3, 3),
    ("SurfaceClosestPointRequest", "points", 1, 3, 3),
    ("SurfaceClosestPointRequest", "range", 0, 2, 2),
    ("SurfaceClosestPointRequest", "range", 1, 2, 2),
];

/// `(schema, property)` of lists that need at least one entry, none repeated.
const UNIQUE_LISTS: &[(&str, &str)] = &[
    ("ShapeRequest", "regions"),
    ("RegionsRequest", "regions"),
    ("ShapeRequest", "methods"),
    ("RegionsRequest", "methods"),
];

/// `(schema, property)` of lists whose entries may not repeat (an empty list is allowed).
const NO_REPEATS: &[(&str, &str)] = &[
    ("ShapeRequest", "fixed_control_points"),
    ("RegionsRequest", "fixed_control_points"),
];

/// `(schema, property, levels of items)` of numbers that must be `> 0`.
const POSITIVE: &[(&str, &str, usize)] = &[
    ("CurveBody", "weights", 1),
    ("EvaluateRequest", "tolerance", 0),
    ("RegionsRequest", "tolerance", 0),
    ("EditableAt", "spacing", 0),
    ("ApproximateRequest", "tolerance", 0),
    ("SurfaceBody", "weights", 2),
    ("TessellateRequest", "tolerance", 0),
];

/// Writes the rules into `document` (an OpenAPI 3.1 document as JSON).
pub fn apply(document: &mut Value) {
    let response_schemas = reachable_schemas(document, "responses");
    let request_schemas = reachable_schemas(document, "requestBody");
    let Some(schemas) = document
        .pointer_mut("/components/schemas")
        .and_then(Value::as_object_mut)
    else {
        return;
    };
    for &(schema, property, levels, min, max) in ARRAY_LENGTHS {
        if let Some(array) = property_at(schemas, schema, property, levels) {
            array.insert("minItems".into(), json!(min));
            array.insert("maxItems".into(), json!(max));
        }
    }
    for &(schema, property) in UNIQUE_LISTS {
        if let Some(array) = property_at(schemas, schema, property, 0) {
            array.insert("minItems".into(), json!(1));
            array.insert("uniqueItems".into(), json!(true));
        }
    }
    for &(schema, property) in NO_REPEATS {
        if let Some(array) = property_at(schemas, schema, property, 0) {
            array.insert("uniqueItems".into(), json!(true));
        }
    }
    for &(schema, property, levels) in POSITIVE {
        if let Some(number) = property_at(schemas, schema, property, levels) {
            number.insert("exclusiveMinimum".into(), json!(0));
        }
    }
    // "Exactly one of `parameters`, `samples` and `tolerance`" stays in the descriptions and
    // is checked by the handler (a 422): a `oneOf` of `required` lists would make
    // openapi-python-client type the whole request body as `Any`.
    if let Some(status) = schemas
        .get_mut("Problem")
        .and_then(|p| p.pointer_mut("/properties/status"))
        .and_then(Value::as_object_mut)
    {
        status.insert("minimum".into(), json!(100));
        status.insert("maximum".into(), json!(599));
    }
    // Only schemas that are never sent in a request: a request may send `null` for an
    // optional field (it reads as absent), so shared schemas (the curve) keep it.
    for name in response_schemas
        .iter()
        .filter(|name| !request_schemas.contains(name))
    {
        if let Some(schema) = schemas.get_mut(name) {
            optional_fields_not_null(schema);
        }
    }
    for name in &request_schemas {
        if let Some(properties) = schemas
            .get_mut(name)
            .and_then(|s| s.get_mut("properties"))
            .and_then(Value::as_object_mut)
        {
            for property in properties.values_mut() {
                if let Some(property) = property.as_object_mut() {
                    property.remove("default");
                }
            }
        }
    }
    candidates_as_unions(schemas);
    document_headers_servers_and_open_operations(document);
}

/// The candidates of membership (and solve) and regions answers as unions told apart by
/// `applicable` (`true`: the side applies, and in membership and solve answers has the
/// target's `frame`; `false`: it does not, and says why in `reason`), so that typed clients
/// can narrow them: every field a variant always carries is required in it. Both carry the
/// `triangle` (a cubic's sides at a parameter of its domain always have one, degenerate or
/// not) and `regions`. Built from `CandidateBody`, which only serde's flattening used, and
/// which goes.
fn candidates_as_unions(schemas: &mut Map<String, Value>) {
    let Some(base) = schemas.remove("CandidateBody") else {
        return;
    };
    let base_required: Vec<Value> = base
        .get("required")
        .and_then(Value::as_array)
        .cloned()
        .unwrap_or_default();
    for (name, applicable_name, inapplicable_name) in [
        (
            "MembershipCandidate",
            "ApplicableMembershipCandidate",
            "InapplicableMembershipCandidate",
        ),
        (
            "RegionsCandidate",
            "ApplicableRegionsCandidate",
            "InapplicableRegionsCandidate",
        ),
    ] {
        let Some(schema) = schemas.get(name).cloned() else {
            continue;
        };
        let mut properties = base
            .get("properties")
            .and_then(Value::as_object)
            .cloned()
            .unwrap_or_default();
        if let Some(regions) = schema.pointer("/allOf/1/properties/regions") {
            properties.insert("regions".into(), regions.clone());
        }
        let example = schema.get("example").cloned().unwrap_or(Value::Null);
        // Membership and solve answers have a target: an applicable side always carries its
        // frame. Regions answers have none, so no side there has a frame.
        let with_target = name == "MembershipCandidate";
        let variant = |applicable: bool| {
            let mut properties = properties.clone();
            let mut needed = vec!["regions", "triangle"];
            if applicable {
                properties.remove("reason");
                if with_target {
                    needed.push("frame");
                }
            } else {
                needed.push("reason");
            }
            if !(applicable && with_target) {
                properties.remove("frame");
            }
            properties.insert(
                "applicable".into(),
                json!({"type": "boolean", "const": applicable,
                       "description": if applicable { "`true`: this side can move the point." }
                                      else { "`false`: this side cannot move the point (see `reason`)." }}),
            );
            let mut required = base_required.clone();
            required.extend(needed.into_iter().map(Value::from));
            let example = if applicable {
                example.clone()
            } else {
                json!({"side": "right", "applicable": false, "span": 2, "moved_knot": 3,
                       "reason": "the control triangle is degenerate (its points are collinear)",
                       "triangle": [[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]], "regions": []})
            };
            json!({
                "type": "object",
                "description": if applicable { "A side that applies, with its regions." }
                               else { "A side that does not apply (no region holds any target)." },
                "properties": properties,
                "required": required,
                "example": example,
            })
        };
        schemas.insert(applicable_name.into(), variant(true));
        schemas.insert(inapplicable_name.into(), variant(false));
        schemas.insert(
            name.into(),
            json!({
                "description": schema.get("description").cloned().unwrap_or(Value::Null),
                // The side that does not apply first: generators that try the variants in
                // order and ignore `const` (openapi-python-client) tell them apart by the
                // required `reason`, which an applicable side never has.
                "oneOf": [
                    {"$ref": format!("#/components/schemas/{inapplicable_name}")},
                    {"$ref": format!("#/components/schemas/{applicable_name}")},
                ],
                "example": example,
            }),
        );
    }
}

/// The array (or number) schema `levels` levels of `items` below `schema.property`, with a
/// nullable wrapper looked through.
fn property_at<'a>(
    schemas: &'a mut Map<String, Value>,
    schema: &str,
    property: &str,
    levels: usize,
) -> Option<&'a mut Map<String, Value>> {
    let mut at = schemas
        .get_mut(schema)?
        .get_mut("properties")?
        .get_mut(property)?;
    for _ in 0..levels {
        at = at.get_mut("items")?;
    }
    at.as_object_mut()
}

/// The names of the component schemas reachable from the operations' `key` (`responses` or
/// `requestBody`), following `$ref`s.
fn reachable_schemas(document: &Value, key: &str) -> Vec<String> {
    let mut found: Vec<String> = Vec::new();
    let mut pending: Vec<&Value> = Vec::new();
    if let Some(paths) = document.get("paths").and_then(Value::as_object) {
        for item in paths.values() {
            for operation in item.as_object().into_iter().flat_map(|o| o.values()) {
                if let Some(part) = operation.get(key) {
                    pending.push(part);
                }
            }
        }
    }
    let schemas = document.pointer("/components/schemas");
    while let Some(value) = pending.pop() {
        match value {
            Value::Object(map) => {
                if let Some(name) = map
                    .get("$ref")
                    .and_then(Value::as_str)
                    .and_then(|r| r.strip_prefix("#/components/schemas/"))
                {
                    if !found.iter().any(|f| f == name) {
                        found.push(name.to_owned());
                        if let Some(schema) = schemas.and_then(|s| s.get(name)) {
                            pending.push(schema);
                        }
                    }
                }
                pending.extend(map.values());
            }
            Value::Array(items) => pending.extend(items),
            _ => {}
        }
    }
    found
}

/// Optional properties of an answer are left out when empty (serde's
/// `skip_serializing_if`), never sent as `null`: drops the `null` alternative utoipa writes.
fn optional_fields_not_null(schema: &mut Value) {
    let required: Vec<String> = schema
        .get("required")
        .and_then(Value::as_array)
        .map(|r| {
            r.iter()
                .filter_map(Value::as_str)
                .map(str::to_owned)
                .collect()
        })
        .unwrap_or_default();
    let Some(properties) = schema.get_mut("properties").and_then(Value::as_object_mut) else {
        return;
    };
    for (name, property) in properties.iter_mut() {
        if required.contains(name) {
            continue;
        }
        let Some(map) = property.as_object_mut() else {
            continue;
        };
        if let Some(Value::Array(types)) = map.get_mut("type") {
            types.retain(|t| t != "null");
            if types.len() == 1 {
                let only = types[0].clone();
                map.insert("type".into(), only);
            }
        }
        if let Some(Value::Array(choices)) = map.get("oneOf").cloned() {
            let kept: Vec<Value> = choices
                .into_iter()
                .filter(|c| c.get("type").and_then(Value::as_str) != Some("null"))
                .collect();
            if kept.len() == 1 {
                map.remove("oneOf");
                if let Some(Value::Object(only)) = kept.into_iter().next() {
                    for (key, value) in only {
                        map.entry(key).or_insert(value);
                    }
                }
            } else {
                map.insert("oneOf".into(), Value::Array(kept));
            }
        }
    }
}

/// `Retry-After` on every 503, `WWW-Authenticate` on every 401, `security: []` on the
/// operations outside `/v1` (they never need the key), the optional key as the document's
/// own `security` (the `/v1` operations carry none of their own), and a `servers` entry.
fn document_headers_servers_and_open_operations(document: &mut Value) {
    if let Some(paths) = document.get_mut("paths").and_then(Value::as_object_mut) {
        for (path, item) in paths.iter_mut() {
            let Some(operations) = item.as_object_mut() else {
                continue;
            };
            for operation in operations.values_mut() {
                let Some(operation) = operation.as_object_mut() else {
                    continue;
                };
                if path.starts_with("/v1/") {
                    // The document-wide requirement below stands for these: a generator that
                    // reads an operation's `[{}, {api_key: []}]` as "key required" (as
                    // openapi-python-client 0.29 does) would make every call authenticated.
                    operation.remove("security");
                } else {
                    operation.insert("security".into(), json!([]));
                }
                let Some(responses) = operation
                    .get_mut("responses")
                    .and_then(Value::as_object_mut)
                else {
                    continue;
                };
                if let Some(response) = responses.get_mut("503").and_then(Value::as_object_mut) {
                    response.insert(
                        "headers".into(),
                        json!({"Retry-After": {
                            "description": "Seconds to wait before trying again",
                            "schema": {"type": "integer", "minimum": 0}
                        }}),
                    );
                }
                if let Some(response) = responses.get_mut("401").and_then(Value::as_object_mut) {
                    response.insert(
                        "headers".into(),
                        json!({"WWW-Authenticate": {
                            "description": "The scheme to authenticate with: `Bearer`",
                            "schema": {"type": "string"}
                        }}),
                    );
                }
            }
        }
    }
    if let Some(root) = document.as_object_mut() {
        // The key is optional: needed only when the service is configured with one.
        root.insert("security".into(), json!([{}, {"api_key": []}]));
        root.insert(
            "servers".into(),
            json!([{"url": "/", "description": "The service that serves this document"}]),
        );
    }
}

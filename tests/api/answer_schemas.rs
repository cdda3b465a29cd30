//! Every answer schema of the OpenAPI document is as precise as the answers. Real answers —
//! every request of `examples/`, the probes, and requests written here for the cases the
//! examples leave out (other methods, knot forms, conditions, errors) — are walked along the
//! schema their operation documents for their status, `oneOf` resolved to the one variant the
//! answer matches (JSON Schema 2020-12, the `jsonschema` crate). The walk fails on:
//!
//! * a field an answer carries that its schema does not document;
//! * an optional field that every answer object of its schema carried (it must be required,
//!   or the case without it must be among the requests: a typed client narrowed by the
//!   schema would otherwise see "possibly undefined" for a field that is always there);
//! * an optional field that no answer carried (a field that never comes, or a case missing
//!   here);
//! * an answer that breaks its schema, a status or content type the operation does not
//!   document, and an object schema of the answers that no answer reached.

use std::collections::{BTreeMap, BTreeSet, HashMap};

use serde_json::{Value, json};

use crate::helpers::{TestApp, spawn_app};

/// What the walk saw of one object schema (by its pointer in the document).
#[derive(Debug, Default)]
struct Seen {
    /// Answer objects walked with this schema.
    objects: usize,
    /// How many of them carried each field.
    present: BTreeMap<String, usize>,
}

/// The walk of answers along the document's schemas.
struct Walk {
    document: Value,
    validators: HashMap<String, jsonschema::Validator>,
    seen: BTreeMap<String, Seen>,
    visited: BTreeSet<String>,
    problems: Vec<String>,
    answers: usize,
}

/// `token` escaped for a JSON pointer.
fn escaped(token: &str) -> String {
    token.replace('~', "~0").replace('/', "~1")
}

/// A schema pointer as the failure messages name it: a component by its name.
fn named(pointer: &str) -> String {
    pointer
        .strip_prefix("/components/schemas/")
        .unwrap_or(pointer)
        .to_owned()
}

impl Walk {
    fn new(document: Value) -> Walk {
        Walk {
            document,
            validators: HashMap::new(),
            seen: BTreeMap::new(),
            visited: BTreeSet::new(),
            problems: Vec::new(),
            answers: 0,
        }
    }

    fn schema(&self, pointer: &str) -> Value {
        self.document
            .pointer(pointer)
            .unwrap_or_else(|| panic!("no schema at {pointer}"))
            .clone()
    }

    /// Whether `instance` is valid against the schema at `pointer` (the document is the root,
    /// so that `$ref`s into its components resolve).
    fn is_valid(&mut self, pointer: &str, instance: &Value) -> bool {
        self.errors(pointer, instance).is_empty()
    }

    fn errors(&mut self, pointer: &str, instance: &Value) -> Vec<String> {
        let document = &self.document;
        let validator = self
            .validators
            .entry(pointer.to_owned())
            .or_insert_with(|| {
                let mut root = document.clone();
                root["$ref"] = Value::String(format!("#{pointer}"));
                jsonschema::draft202012::new(&root)
                    .unwrap_or_else(|error| panic!("{pointer}: not a schema: {error}"))
            });
        validator
            .iter_errors(instance)
            .map(|error| format!("{error} at {}", error.instance_path()))
            .collect()
    }

    /// One answer of `method path` with `status` and `content_type`; JSON bodies are walked.
    fn answer(
        &mut self,
        what: &str,
        method: &str,
        path: &str,
        status: u16,
        content_type: &str,
        body: &Value,
    ) {
        self.answers += 1;
        let response = format!("/paths/{}/{method}/responses/{status}", escaped(path));
        if self.document.pointer(&response).is_none() {
            self.problems.push(format!(
                "{what}: status {status} of {method} {path} is not documented"
            ));
            return;
        }
        let media = content_type.split(';').next().unwrap_or("").trim();
        let pointer = format!("{response}/content/{}/schema", escaped(media));
        if self.document.pointer(&pointer).is_none() {
            self.problems.push(format!(
                "{what}: {status} of {method} {path} in {media} is not documented"
            ));
            return;
        }
        let errors = self.errors(&pointer, body);
        if !errors.is_empty() {
            self.problems
                .push(format!("{what}: the answer breaks its schema: {errors:?}"));
            return;
        }
        self.walk(&pointer, body, what, "");
    }

    fn walk(&mut self, pointer: &str, instance: &Value, what: &str, at: &str) {
        self.visited.insert(pointer.to_owned());
        let schema = self.schema(pointer);
        if let Some(reference) = schema.get("$ref").and_then(Value::as_str) {
            let target = reference.trim_start_matches('#').to_owned();
            self.walk(&target, instance, what, at);
            return;
        }
        if schema.get("allOf").is_some() || schema.get("anyOf").is_some() {
            self.problems.push(format!(
                "{what}{at}: {} uses allOf/anyOf, which this walk does not resolve",
                named(pointer)
            ));
            return;
        }
        if let Some(variants) = schema.get("oneOf").and_then(Value::as_array) {
            let matching: Vec<String> = (0..variants.len())
                .map(|i| format!("{pointer}/oneOf/{i}"))
                .filter(|variant| self.is_valid(variant, instance))
                .collect();
            match matching.as_slice() {
                [one] => self.walk(one, instance, what, at),
                _ => self.problems.push(format!(
                    "{what}{at}: {} variants of {} match, not one",
                    matching.len(),
                    named(pointer)
                )),
            }
            return;
        }
        match instance {
            Value::Object(fields) => {
                let properties = schema.get("properties").and_then(Value::as_object);
                let additional = schema
                    .get("additionalProperties")
                    .filter(|a| a.is_object())
                    .map(|_| format!("{pointer}/additionalProperties"));
                if properties.is_some() {
                    let seen = self.seen.entry(pointer.to_owned()).or_default();
                    seen.objects += 1;
                    for key in fields.keys() {
                        if properties.is_some_and(|p| p.contains_key(key)) {
                            *seen.present.entry(key.clone()).or_default() += 1;
                        }
                    }
                }
                for (key, value) in fields {
                    let here = format!("{at}/{key}");
                    if properties.is_some_and(|p| p.contains_key(key)) {
                        let property = format!("{pointer}/properties/{}", escaped(key));
                        self.walk(&property, value, what, &here);
                    } else if let Some(additional) = &additional {
                        self.walk(additional, value, what, &here);
                    } else {
                        self.problems.push(format!(
                            "{what}{here}: `{key}` is not documented in {}",
                            named(pointer)
                        ));
                    }
                }
            }
            Value::Array(items) if schema.get("items").is_some_and(Value::is_object) => {
                let item = format!("{pointer}/items");
                for (index, value) in items.iter().enumerate() {
                    self.walk(&item, value, what, &format!("{at}/{index}"));
                }
            }
            _ => {}
        }
    }

    /// The verdicts on everything walked (module docs).
    fn verdicts(&self) -> Vec<String> {
        let mut problems = self.problems.clone();
        for (pointer, seen) in &self.seen {
            let schema = self.schema(pointer);
            let required: BTreeSet<&str> = schema["required"]
                .as_array()
                .into_iter()
                .flatten()
                .filter_map(Value::as_str)
                .collect();
            let properties = schema["properties"]
                .as_object()
                .cloned()
                .unwrap_or_default();
            for name in properties.keys() {
                if required.contains(name.as_str()) {
                    continue;
                }
                let present = seen.present.get(name).copied().unwrap_or(0);
                if present == seen.objects {
                    problems.push(format!(
                        "{}.{name}: optional, but all {} answer objects carried it",
                        named(pointer),
                        seen.objects
                    ));
                } else if present == 0 {
                    problems.push(format!(
                        "{}.{name}: optional, and none of {} answer objects carried it",
                        named(pointer),
                        seen.objects
                    ));
                }
            }
        }
        for name in answer_components(&self.document) {
            let pointer = format!("/components/schemas/{}", escaped(&name));
            let schema = self.schema(&pointer);
            let walkable = schema.get("properties").is_some() || schema.get("oneOf").is_some();
            if walkable && !self.visited.contains(&pointer) {
                problems.push(format!("{name}: no answer reached this schema"));
            }
        }
        problems
    }
}

/// The component schemas reachable from the operations' responses, following `$ref`s.
fn answer_components(document: &Value) -> BTreeSet<String> {
    let mut found = BTreeSet::new();
    let mut pending: Vec<&Value> = document["paths"]
        .as_object()
        .into_iter()
        .flat_map(|paths| paths.values())
        .flat_map(|item| item.as_object().into_iter().flat_map(|o| o.values()))
        .filter_map(|operation| operation.get("responses"))
        .collect();
    while let Some(value) = pending.pop() {
        match value {
            Value::Object(map) => {
                if let Some(name) = map
                    .get("$ref")
                    .and_then(Value::as_str)
                    .and_then(|r| r.strip_prefix("#/components/schemas/"))
                {
                    if found.insert(name.to_owned()) {
                        pending.push(&document["components"]["schemas"][name]);
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

/// What a request sends.
enum Body {
    /// A POST with this JSON body.
    Json(Value),
    /// A POST with this text and content type (malformed on purpose).
    Raw(&'static str, &'static str),
    /// A GET.
    Get,
}

/// One request: what it shows, its path and body, and the status it must get.
struct Case {
    what: String,
    path: String,
    body: Body,
    status: u16,
}

fn post(what: &str, path: &str, body: Value, status: u16) -> Case {
    Case {
        what: what.to_owned(),
        path: path.to_owned(),
        body: Body::Json(body),
        status,
    }
}

/// Every file of `examples/`, posted to its route (as tests/api/examples.rs does).
fn example_cases(document: &Value) -> Vec<Case> {
    let directory = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let mut files: Vec<_> = std::fs::read_dir(&directory)
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.extension().is_some_and(|e| e == "json"))
        .collect();
    files.sort();
    let routes: Vec<&String> = document["paths"]
        .as_object()
        .unwrap()
        .keys()
        .filter(|path| path.starts_with("/v1/"))
        .collect();
    files
        .iter()
        .map(|file| {
            let name = file.file_stem().unwrap().to_str().unwrap();
            let path = routes
                .iter()
                .filter(|route| {
                    let stem = route.trim_start_matches("/v1/").replace('/', "-");
                    name == stem || name.starts_with(&format!("{stem}-"))
                })
                .max_by_key(|route| route.len())
                .unwrap_or_else(|| panic!("{name}: no route matches the file name"));
            let body: Value =
                serde_json::from_str(&std::fs::read_to_string(file).unwrap()).unwrap();
            post(&format!("examples/{name}.json"), path, body, 200)
        })
        .collect()
}

/// The worked example's cubic (the examples' curve).
fn cubic() -> Value {
    json!({"degree": 3,
           "control_points": [[0, 0], [1, 3], [3, 4], [5, 3.5], [6, 1], [8, 0], [9, 2], [10, 4]],
           "knots": [0, 0, 0, 0, 0.2, 0.35, 0.5, 0.75, 1, 1, 1, 1]})
}

/// The same cubic with its knots as distinct values and multiplicities.
fn cubic_with_multiplicities() -> Value {
    json!({"degree": 3,
           "control_points": [[0, 0], [1, 3], [3, 4], [5, 3.5], [6, 1], [8, 0], [9, 2], [10, 4]],
           "knots": [0, 0.2, 0.35, 0.5, 0.75, 1], "multiplicities": [4, 1, 1, 1, 1, 4]})
}

/// A rational 3D cubic.
fn rational_3d() -> Value {
    json!({"degree": 3,
           "control_points": [[0, 0, 0], [1, 2, 1], [3, 4, 0.5], [5, 3.5, 2], [6, 1, 1], [7, 0, -1], [9, 2, 0]],
           "knots": [0, 0, 0, 0, 0.25, 0.5, 0.5, 1, 1, 1, 1],
           "weights": [1, 0.5, 2, 1, 1.5, 0.8, 1]})
}

/// A periodic cubic in Open CASCADE's form (examples/curves-evaluate-periodic.json).
fn periodic() -> Value {
    json!({"degree": 3, "periodic": true,
           "control_points": [[2, 0], [1, 1.7], [-1, 1.7], [-2, 0], [-1, -1.7], [1, -1.7]],
           "knots": [0, 0.5, 1, 1.5, 2, 2.5, 3], "multiplicities": [1, 1, 1, 1, 1, 1, 1]})
}

/// A cubic whose first control points are collinear: both sides at `t = 0.1` have a
/// degenerate control triangle.
fn flat_start() -> Value {
    json!({"degree": 3,
           "control_points": [[0, 0], [1, 0], [2, 0], [3, 0], [4, 1], [5, 0], [6, 1], [7, 0]],
           "knots": [0, 0, 0, 0, 0.2, 0.35, 0.5, 0.75, 1, 1, 1, 1]})
}

/// The requests for what the examples leave out: the other side of every field that an
/// answer carries only sometimes, and the answers outside `/v1` and of errors.
fn more_cases() -> Vec<Case> {
    let solve = |curve: Value, extra: Value| {
        let mut body = json!({"curve": curve, "parameter": 0.42,
                              "target": [4.746666666666666, 3.3233333333333333]});
        body.as_object_mut()
            .unwrap()
            .extend(extra.as_object().unwrap().clone());
        body
    };
    vec![
        Case {
            what: "GET /healthz".into(),
            path: "/healthz".into(),
            body: Body::Get,
            status: 200,
        },
        Case {
            what: "GET /readyz".into(),
            path: "/readyz".into(),
            body: Body::Get,
            status: 200,
        },
        // Problems: with field errors (422, 400 for malformed JSON) and without (415).
        post(
            "a parameter outside the domain",
            "/v1/curves/evaluate",
            json!({"curve": cubic(), "parameters": [2]}),
            422,
        ),
        Case {
            what: "malformed JSON".into(),
            path: "/v1/curves/evaluate".into(),
            body: Body::Raw("application/json", "{\"curve\": "),
            status: 400,
        },
        Case {
            what: "not JSON".into(),
            path: "/v1/curves/evaluate".into(),
            body: Body::Raw("text/plain", "{}"),
            status: 415,
        },
        // Curves in answers: rational, with multiplicities, periodic.
        post(
            "insert-knots, rational 3D",
            "/v1/curves/insert-knots",
            json!({"curve": rational_3d(), "knots": [0.3]}),
            200,
        ),
        post(
            "insert-knots, multiplicities",
            "/v1/curves/insert-knots",
            json!({"curve": cubic_with_multiplicities(), "knots": [0.3]}),
            200,
        ),
        post(
            "insert-knots, periodic",
            "/v1/curves/insert-knots",
            json!({"curve": periodic(), "knots": [0.3]}),
            200,
        ),
        // Bézier pieces of a rational 3D curve: weights, no SVG path.
        post(
            "bezier, rational 3D",
            "/v1/curves/bezier",
            json!({"curve": rational_3d()}),
            200,
        ),
        // Curvature where the tangent vanishes (the first two control points coincide).
        post(
            "curvature at a vanishing tangent",
            "/v1/curves/evaluate",
            json!({"curve": {"degree": 3, "control_points": [[0, 0], [0, 0], [1, 1], [2, 0]],
                             "knots": [0, 0, 0, 0, 1, 1, 1, 1]},
                   "parameters": [0, 0.5], "curvature": true}),
            200,
        ),
        // Arc length without `at_lengths`.
        post(
            "length alone",
            "/v1/curves/length",
            json!({"curve": cubic()}),
            200,
        ),
        // Solutions with SVG paths, and with multiplicities.
        post(
            "solve with svg_paths",
            "/v1/shape/solve",
            solve(
                cubic(),
                json!({"methods": ["knots", "control_points"], "svg_paths": true}),
            ),
            200,
        ),
        post(
            "solve with multiplicities",
            "/v1/shape/solve",
            solve(cubic_with_multiplicities(), json!({})),
            200,
        ),
        // Weight pairs ruled out by fixed control points.
        post(
            "weights with fixed control points",
            "/v1/shape/solve",
            solve(
                cubic(),
                json!({"methods": ["weights"], "fixed_control_points": [3, 4, 5]}),
            ),
            200,
        ),
        // Sides that do not apply: degenerate triangles.
        post(
            "membership, degenerate triangles",
            "/v1/shape/membership",
            json!({"curve": flat_start(), "parameter": 0.1, "target": [1, 0.5]}),
            200,
        ),
        post(
            "regions, degenerate triangles",
            "/v1/shape/regions",
            json!({"curve": flat_start(), "parameter": 0.1}),
            200,
        ),
        // The surface edit with constraints that contradict each other: exclusions that
        // name a constraint.
        post(
            "surface solve, contradictory constraints",
            "/v1/surfaces/shape/solve",
            json!({"surface": {"degree_u": 2, "degree_v": 2,
                               "control_points": [[[0, 0, 0], [0, 1, 0], [0, 2, 0]],
                                                  [[1, 0, 0], [1, 1, 1], [1, 2, 0]],
                                                  [[2, 0, 0], [2, 1, 0], [2, 2, 0]]],
                               "knots_u": [0, 0, 0, 1, 1, 1], "knots_v": [0, 0, 0, 1, 1, 1]},
                   "parameter": [0.5, 0.5], "target": [1, 1, 0.8],
                   "constraints": [{"parameter": [0.2, 0.2], "order": 0},
                                   {"parameter": [0.2, 0.2], "order": 0, "value": [0, 0, 1]}]}),
            200,
        ),
        // Weight triples through a fixed pole: exclusions that name it.
        post(
            "surface solve, weights with a fixed pole",
            "/v1/surfaces/shape/solve",
            json!({"surface": {"degree_u": 2, "degree_v": 2,
                               "control_points": [[[0, 0, 0], [0, 1, 0], [0, 2, 0]],
                                                  [[1, 0, 0], [1, 1, 1], [1, 2, 0]],
                                                  [[2, 0, 0], [2, 1, 0], [2, 2, 0]]],
                               "knots_u": [0, 0, 0, 1, 1, 1], "knots_v": [0, 0, 0, 1, 1, 1]},
                   "parameter": [0.5, 0.5], "target": [1.02, 1.01, 0.3],
                   "methods": ["weights"], "fixed_control_points": [[1, 1]]}),
            200,
        ),
        // Knot moves in u and in v on a planar bicubic sent with multiplicities: solutions
        // with their family, region, new knots and multiplicities (targets planted by moving
        // u_5, then v_5, from 0.55 to 0.5).
        post(
            "surface solve, knots in u",
            "/v1/surfaces/shape/solve",
            json!({"surface": {"degree_u": 3, "degree_v": 3, "control_points": [[[0.0, 0.3, 0.0], [0.156665, 1.3, 0.0], [0.19477, 2.3, 0.0], [0.085476, 3.3, 0.0], [-0.088504, 4.3, 0.0], [-0.195506, 5.3, 0.0], [-0.154553, 6.3, 0.0]], [[1.0, 0.229453, 0.0], [1.156665, 1.229453, 0.0], [1.19477, 2.229453, 0.0], [1.085476, 3.229453, 0.0], [0.911496, 4.229453, 0.0], [0.804494, 5.229453, 0.0], [0.845447, 6.229453, 0.0]], [[2.0, 0.05099, 0.0], [2.156665, 1.05099, 0.0], [2.19477, 2.05099, 0.0], [2.085476, 3.05099, 0.0], [1.911496, 4.05099, 0.0], [1.804494, 5.05099, 0.0], [1.845447, 6.05099, 0.0]], [[3.0, -0.151454, 0.0], [3.156665, 0.848546, 0.0], [3.19477, 1.848546, 0.0], [3.085476, 2.848546, 0.0], [2.911496, 3.848546, 0.0], [2.804494, 4.848546, 0.0], [2.845447, 5.848546, 0.0]], [[4.0, -0.282667, 0.0], [4.156665, 0.717333, 0.0], [4.19477, 1.717333, 0.0], [4.085476, 2.717333, 0.0], [3.911496, 3.717333, 0.0], [3.804494, 4.717333, 0.0], [3.845447, 5.717333, 0.0]], [[5.0, -0.280937, 0.0], [5.156665, 0.719063, 0.0], [5.19477, 1.719063, 0.0], [5.085476, 2.719063, 0.0], [4.911496, 3.719063, 0.0], [4.804494, 4.719063, 0.0], [4.845447, 5.719063, 0.0]], [[6.0, -0.147078, 0.0], [6.156665, 0.852922, 0.0], [6.19477, 1.852922, 0.0], [6.085476, 2.852922, 0.0], [5.911496, 3.852922, 0.0], [5.804494, 4.852922, 0.0], [5.845447, 5.852922, 0.0]]],
                               "knots_u": [0, 0.3, 0.55, 0.8, 1], "multiplicities_u": [4, 1, 1, 1, 4],
                               "knots_v": [0, 0.3, 0.55, 0.8, 1], "multiplicities_v": [4, 1, 1, 1, 4]},
                   "parameter": [0.62, 0.45], "target": [3.5068959065562404, 2.430249237189757, 0.0],
                   "methods": ["knots"], "keep_domain": true}),
            200,
        ),
        post(
            "surface solve, knots in v",
            "/v1/surfaces/shape/solve",
            json!({"surface": {"degree_u": 3, "degree_v": 3, "control_points": [[[0.0, 0.3, 0.0], [0.156665, 1.3, 0.0], [0.19477, 2.3, 0.0], [0.085476, 3.3, 0.0], [-0.088504, 4.3, 0.0], [-0.195506, 5.3, 0.0], [-0.154553, 6.3, 0.0]], [[1.0, 0.229453, 0.0], [1.156665, 1.229453, 0.0], [1.19477, 2.229453, 0.0], [1.085476, 3.229453, 0.0], [0.911496, 4.229453, 0.0], [0.804494, 5.229453, 0.0], [0.845447, 6.229453, 0.0]], [[2.0, 0.05099, 0.0], [2.156665, 1.05099, 0.0], [2.19477, 2.05099, 0.0], [2.085476, 3.05099, 0.0], [1.911496, 4.05099, 0.0], [1.804494, 5.05099, 0.0], [1.845447, 6.05099, 0.0]], [[3.0, -0.151454, 0.0], [3.156665, 0.848546, 0.0], [3.19477, 1.848546, 0.0], [3.085476, 2.848546, 0.0], [2.911496, 3.848546, 0.0], [2.804494, 4.848546, 0.0], [2.845447, 5.848546, 0.0]], [[4.0, -0.282667, 0.0], [4.156665, 0.717333, 0.0], [4.19477, 1.717333, 0.0], [4.085476, 2.717333, 0.0], [3.911496, 3.717333, 0.0], [3.804494, 4.717333, 0.0], [3.845447, 5.717333, 0.0]], [[5.0, -0.280937, 0.0], [5.156665, 0.719063, 0.0], [5.19477, 1.719063, 0.0], [5.085476, 2.719063, 0.0], [4.911496, 3.719063, 0.0], [4.804494, 4.719063, 0.0], [4.845447, 5.719063, 0.0]], [[6.0, -0.147078, 0.0], [6.156665, 0.852922, 0.0], [6.19477, 1.852922, 0.0], [6.085476, 2.852922, 0.0], [5.911496, 3.852922, 0.0], [5.804494, 4.852922, 0.0], [5.845447, 5.852922, 0.0]]],
                               "knots_u": [0, 0.3, 0.55, 0.8, 1], "multiplicities_u": [4, 1, 1, 1, 4],
                               "knots_v": [0, 0.3, 0.55, 0.8, 1], "multiplicities_v": [4, 1, 1, 1, 4]},
                   "parameter": [0.62, 0.45], "target": [3.4263378576849366, 2.5054158245520557, 0.0],
                   "methods": ["knots"], "keep_domain": true}),
            200,
        ),
        // Regions of a method that reaches nothing: every pole fixed (the boundary kept, the
        // middle one fixed): the reason.
        post(
            "surface regions, every pole fixed",
            "/v1/surfaces/shape/regions",
            json!({"surface": {"degree_u": 2, "degree_v": 2,
                               "control_points": [[[0, 0, 0], [0, 1, 0], [0, 2, 0]],
                                                  [[1, 0, 0], [1, 1, 1], [1, 2, 0]],
                                                  [[2, 0, 0], [2, 1, 0], [2, 2, 0]]],
                               "knots_u": [0, 0, 0, 1, 1, 1], "knots_v": [0, 0, 0, 1, 1, 1]},
                   "parameter": [0.5, 0.5], "methods": ["control_points"],
                   "keep_boundary": true, "fixed_control_points": [[1, 1]]}),
            200,
        ),
    ]
}

async fn send(app: &TestApp, case: &Case) -> (u16, String, Value) {
    let url = format!("{}{}", app.address, case.path);
    let response = match &case.body {
        Body::Json(body) => app.post(&case.path, body).await,
        Body::Raw(content_type, text) => app
            .client
            .post(url)
            .header("content-type", *content_type)
            .body(*text)
            .send()
            .await
            .unwrap(),
        Body::Get => app.get(&case.path).await,
    };
    let status = response.status().as_u16();
    let content_type = response
        .headers()
        .get("content-type")
        .and_then(|v| v.to_str().ok())
        .unwrap_or("")
        .to_owned();
    let text = response.text().await.unwrap();
    let body = if content_type.contains("json") {
        serde_json::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}: {text}", case.what))
    } else {
        Value::Null
    };
    (status, content_type, body)
}

#[tokio::test]
async fn every_field_an_answer_always_carries_is_required_and_every_field_documented() {
    let document: Value = serde_json::from_str(&knotshape::openapi_json()).unwrap();
    let app = spawn_app().await;
    let mut cases = example_cases(&document);
    cases.extend(more_cases());
    let mut walk = Walk::new(document);
    for case in &cases {
        let (status, content_type, body) = send(&app, case).await;
        assert_eq!(status, case.status, "{}: {body}", case.what);
        let method = if matches!(case.body, Body::Get) {
            "get"
        } else {
            "post"
        };
        if content_type.contains("json") {
            walk.answer(&case.what, method, &case.path, status, &content_type, &body);
        }
    }
    let problems = walk.verdicts();
    assert!(
        problems.is_empty(),
        "{} answers walked; the schemas and the answers disagree:\n{}",
        walk.answers,
        problems.join("\n")
    );
}

/// The walk can fail: on a small document, an undocumented field, an optional field every
/// answer carried, one none carried, a `oneOf` resolved by `applicable`, and a schema no
/// answer reached are each reported; a precise schema passes.
#[test]
fn the_walk_finds_imprecise_schemas() {
    let document = |side_required: Value| {
        json!({
            "paths": {"/v1/x": {"post": {"responses": {"200": {"content": {"application/json":
                {"schema": {"$ref": "#/components/schemas/Answer"}}}}}}}},
            "components": {"schemas": {
                "Answer": {"type": "object", "required": ["sides"],
                           "properties": {"sides": {"type": "array", "items": {"$ref": "#/components/schemas/Side"}},
                                          "note": {"type": "string"},
                                          "unused": {"$ref": "#/components/schemas/Unused"}}},
                "Side": {"oneOf": [{"$ref": "#/components/schemas/Yes"}, {"$ref": "#/components/schemas/No"}]},
                "Yes": {"type": "object", "required": side_required,
                        "properties": {"applicable": {"const": true}, "frame": {"type": "number"}}},
                "No": {"type": "object", "required": ["applicable"],
                       "properties": {"applicable": {"const": false}}},
                "Unused": {"type": "object", "properties": {"a": {"type": "number"}}}
            }}
        })
    };
    let answers = [
        json!({"sides": [{"applicable": true, "frame": 1.0}, {"applicable": false}]}),
        json!({"sides": [{"applicable": true, "frame": 2.0}], "note": "n"}),
    ];
    let verdicts = |document: Value, extra: Option<Value>| {
        let mut walk = Walk::new(document);
        for answer in answers.iter().chain(extra.iter()) {
            walk.answer("case", "post", "/v1/x", 200, "application/json", answer);
        }
        walk.verdicts()
    };
    let imprecise = verdicts(
        document(json!(["applicable"])),
        Some(json!({"sides": [{"applicable": false, "extra": 1}]})),
    );
    assert_eq!(
        imprecise,
        [
            "case/sides/0/extra: `extra` is not documented in No",
            "Answer.unused: optional, and none of 3 answer objects carried it",
            "Yes.frame: optional, but all 2 answer objects carried it",
            "Unused: no answer reached this schema",
        ],
        "{imprecise:#?}"
    );
    let mut precise_document = document(json!(["applicable", "frame"]));
    let schemas = &mut precise_document["components"]["schemas"];
    schemas["Answer"]["properties"]
        .as_object_mut()
        .unwrap()
        .remove("unused");
    schemas.as_object_mut().unwrap().remove("Unused");
    assert_eq!(verdicts(precise_document, None), Vec::<String>::new());
}

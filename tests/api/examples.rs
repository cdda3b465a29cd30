//! Every request body in `examples/` (the curl examples of README.md and docs/api.md) posted
//! to the real server: a 200 with a sensible body. A file
//! `<group>-<endpoint>[-variant].json` goes to `/v1/<group>/<endpoint>` (the longest documented
//! route that the name starts with, so `curves-closest-point.json` goes to
//! `/v1/curves/closest-point`).

use serde_json::Value;

use crate::helpers::{numbers, points, spawn_app};

fn check_sensible(path: &str, request: &Value, body: &Value) {
    match path {
        "/v1/curves/evaluate" => {
            let parameters = numbers(&body["parameters"]);
            assert!(!parameters.is_empty());
            let found = points(&body["points"]);
            assert_eq!(found.len(), parameters.len());
            assert!(found.iter().flatten().all(|v| v.is_finite()));
            assert_eq!(numbers(&body["domain"]).len(), 2);
            if let Some(order) = request["derivatives"].as_u64().filter(|&d| d > 0) {
                assert_eq!(body["derivatives"].as_array().unwrap().len() as u64, order);
            }
            if request["curvature"] == true {
                assert_eq!(numbers(&body["curvature"]).len(), parameters.len());
            }
        }
        "/v1/curves/envelope" => {
            let multiplicity = body["multiplicity"].as_u64().unwrap();
            assert_eq!(
                body["envelope"]["degree"].as_u64().unwrap(),
                request["curve"]["degree"].as_u64().unwrap() - multiplicity
            );
        }
        "/v1/shape/membership" => {
            let any = body["candidates"]
                .as_array()
                .unwrap()
                .iter()
                .flat_map(|c| c["regions"].as_array().unwrap())
                .any(|r| r["contains"] == true)
                || body["families"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .flat_map(|f| f["pairs"].as_array().unwrap())
                    .any(|r| r["contains"] == true)
                || body["control_points"]["contains"] == true
                || body["weights"]["contains"] == true;
            assert_eq!(body["reachable"], any);
            assert_eq!(body["reachable"], true, "examples show reachable targets");
        }
        "/v1/shape/regions" => {
            let weight_regions = body["weight_regions"].as_array().unwrap();
            for region in body["candidates"]
                .as_array()
                .unwrap()
                .iter()
                .flat_map(|c| c["regions"].as_array().unwrap())
                .chain(weight_regions)
            {
                let polygon = points(&region["polygon"]);
                assert!(polygon.len() >= 4);
                assert_eq!(polygon.first(), polygon.last());
            }
            for region in body["families"]
                .as_array()
                .unwrap()
                .iter()
                .flat_map(|f| f["regions"].as_array().unwrap())
            {
                for ring in region["polygons"].as_array().unwrap() {
                    let ring = points(ring);
                    assert!(ring.len() >= 4);
                    assert_eq!(ring.first(), ring.last());
                }
            }
        }
        "/v1/shape/solve" if request["nearest"] == true => {
            assert_eq!(
                body["reachable"], false,
                "the nearest example's target is unreachable"
            );
            let nearest = &body["nearest"];
            assert!(nearest["distance"].as_f64().unwrap() > 0.0);
            assert!(!nearest["solutions"].as_array().unwrap().is_empty());
        }
        "/v1/shape/solve" => {
            let solutions = body["solutions"].as_array().unwrap();
            assert_eq!(body["reachable"], true, "examples show reachable targets");
            assert!(!solutions.is_empty());
            for solution in solutions {
                assert!(solution["residual"].as_f64().unwrap() < 1e-9, "{solution}");
            }
        }
        "/v1/curves/closest-point" => {
            let results = body["results"].as_array().unwrap();
            assert_eq!(results.len(), request["points"].as_array().unwrap().len());
            assert!(
                results
                    .iter()
                    .all(|r| r["distance"].as_f64().unwrap() >= 0.0)
            );
        }
        "/v1/curves/insert-knots" => {
            let before = request["curve"]["control_points"].as_array().unwrap().len();
            let after = body["curve"]["control_points"].as_array().unwrap().len();
            assert!(after > before, "knots were inserted");
        }
        "/v1/curves/import" => {
            let curves = body["curves"].as_array().unwrap();
            assert!(!curves.is_empty(), "the example files hold B-spline curves");
            assert!(curves.iter().all(|c| c["source"].is_string()));
            let surfaces = body["surfaces"].as_array().unwrap();
            assert!(surfaces.iter().all(|s| s["source"].is_string()));
        }
        // The surfaces of the fourth release.
        "/v1/surfaces/evaluate" => {
            let count = match request["parameters"].as_array() {
                Some(parameters) => parameters.len(),
                None => numbers(&request["samples"]).iter().product::<f64>() as usize,
            };
            let found = points(&body["points"]);
            assert_eq!(found.len(), count);
            assert!(found.iter().flatten().all(|v| v.is_finite()));
        }
        "/v1/surfaces/closest-point" => {
            let results = body["results"].as_array().unwrap();
            assert_eq!(results.len(), request["points"].as_array().unwrap().len());
            assert!(
                results
                    .iter()
                    .all(|r| r["distance"].as_f64().unwrap() >= 0.0)
            );
        }
        "/v1/surfaces/tessellate" => {
            let max_error = body["max_error"].as_f64().unwrap();
            assert!(max_error > 0.0 && max_error <= request["tolerance"].as_f64().unwrap());
            assert!(!body["triangles"].as_array().unwrap().is_empty());
            assert_eq!(
                points(&body["vertices"]).len(),
                points(&body["normals"]).len()
            );
        }
        "/v1/surfaces/iso-curve" => {
            assert!(body["curve"]["control_points"].as_array().unwrap().len() >= 2);
        }
        "/v1/surfaces/insert-knots" => {
            let rows = |v: &Value| v["control_points"].as_array().unwrap().len();
            let columns = |v: &Value| v["control_points"][0].as_array().unwrap().len();
            let (before, after) = (&request["surface"], &body["surface"]);
            assert!(rows(after) * columns(after) > rows(before) * columns(before));
        }
        "/v1/surfaces/split" => {
            let cuts = request["parameters"].as_array().unwrap().len();
            assert_eq!(body["surfaces"].as_array().unwrap().len(), cuts + 1);
        }
        "/v1/surfaces/shape/solve" => {
            if request["nearest"] == true {
                // Unreachable by the weights alone: the nearest point they reach instead.
                assert_eq!(body["reachable"], false);
                assert!(!body["nearest"]["solutions"].as_array().unwrap().is_empty());
                return;
            }
            assert_eq!(body["reachable"], true, "examples show reachable targets");
            let solutions = body["solutions"].as_array().unwrap();
            assert!(!solutions.is_empty());
            let deviations: Vec<f64> = solutions
                .iter()
                .map(|s| s["max_deviation"].as_f64().unwrap())
                .collect();
            assert!(deviations.windows(2).all(|d| d[0] <= d[1]), "ranked");
            let target = numbers(&request["target"]);
            for solution in solutions {
                let point = numbers(&solution["point"]);
                let gap: f64 = (0..3).map(|c| (point[c] - target[c]).powi(2)).sum();
                assert!(gap.sqrt() < 1e-9, "{solution}");
            }
        }
        "/v1/surfaces/shape/regions" => {
            let methods = body["methods"].as_array().unwrap();
            assert_eq!(methods.len(), request["methods"].as_array().unwrap().len());
            assert!(methods.iter().any(|m| m["everywhere"] == true
                || m["tetrahedra"].as_array().is_some_and(|t| !t.is_empty())));
        }
        "/v1/curves/bezier" => {
            assert!(!body["segments"].as_array().unwrap().is_empty());
            assert!(body["svg_path"].as_str().unwrap().starts_with('M'));
        }
        // The curve toolkit of the third release.
        "/v1/curves/interpolate" => {
            let given = request["points"].as_array().unwrap().len();
            assert_eq!(numbers(&body["parameters"]).len(), given);
            let poles = body["curve"]["control_points"].as_array().unwrap().len();
            assert!(poles >= given, "one pole per point at least");
        }
        "/v1/curves/approximate" => {
            let tolerance = request["tolerance"].as_f64().unwrap();
            assert!(body["max_error"].as_f64().unwrap() <= tolerance);
            let poles = body["curve"]["control_points"].as_array().unwrap().len();
            assert!(poles < request["points"].as_array().unwrap().len());
        }
        "/v1/curves/elevate-degree" => {
            assert_eq!(body["curve"]["degree"], request["degree"]);
        }
        "/v1/curves/remove-knots" => {
            assert!(!body["removed"].as_array().unwrap().is_empty());
            let tolerance = request["tolerance"].as_f64().unwrap();
            assert!(body["max_deviation"].as_f64().unwrap() <= tolerance);
        }
        "/v1/curves/split" => {
            let cuts = request["parameters"].as_array().unwrap().len();
            assert_eq!(body["curves"].as_array().unwrap().len(), cuts + 1);
        }
        "/v1/curves/length" => {
            assert!(body["length"].as_f64().unwrap() > 0.0);
            let asked = request["at_lengths"].as_array().map_or(0, Vec::len);
            assert_eq!(numbers(&body["parameters"]).len(), asked);
        }
        other => panic!("no check for {other}"),
    }
}

#[tokio::test]
async fn every_example_request_gets_a_sensible_200() {
    let app = spawn_app().await;
    let directory = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let mut files: Vec<_> = std::fs::read_dir(&directory)
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.extension().is_some_and(|e| e == "json"))
        .collect();
    files.sort();
    let document = knotshape::openapi();
    let routes: Vec<&String> = document
        .paths
        .paths
        .keys()
        .filter(|path| path.starts_with("/v1/"))
        .collect();
    let mut endpoints = std::collections::BTreeSet::new();
    for file in &files {
        let name = file.file_stem().unwrap().to_str().unwrap();
        let path = routes
            .iter()
            .filter(|route| {
                let stem = route.trim_start_matches("/v1/").replace('/', "-");
                name == stem || name.starts_with(&format!("{stem}-"))
            })
            .max_by_key(|route| route.len())
            .unwrap_or_else(|| panic!("{name}: no route matches the file name"))
            .to_string();
        let request: Value = serde_json::from_str(&std::fs::read_to_string(file).unwrap()).unwrap();
        if path == "/v1/curves/export" {
            // The answer is the file; it reads back to as many curves.
            let response = app.post(&path, &request).await;
            assert_eq!(response.status().as_u16(), 200, "{name}");
            let data = response.text().await.unwrap();
            let import = serde_json::json!({"format": request["format"], "data": data});
            let (status, back) = app.post_json("/v1/curves/import", &import).await;
            assert_eq!(status, 200, "{name}: {back}");
            let count = |v: &Value| v.as_array().map_or(0, Vec::len);
            assert_eq!(count(&back["curves"]), count(&request["curves"]), "{name}");
            assert_eq!(
                count(&back["surfaces"]),
                count(&request["surfaces"]),
                "{name}"
            );
            endpoints.insert(path);
            continue;
        }
        let (status, body) = app.post_json(&path, &request).await;
        assert_eq!(status, 200, "{name}: {body}");
        check_sensible(&path, &request, &body);
        endpoints.insert(path);
    }
    assert_eq!(
        endpoints.len(),
        10 + 6 + 6 + 2,
        "one example or more per endpoint: {endpoints:?}"
    );
}

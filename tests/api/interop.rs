//! Interoperability over HTTP: the multiplicities form and Open CASCADE's periodic form on the
//! endpoints that take a curve (answers in the caller's form, 422s with pointers), and
//! `/v1/curves/import` and `/export` with STEP and DXF files (every 4xx).

use serde_json::{Value, json};

use crate::helpers::{assert_problem, numbers, points, spawn_app, spawn_app_with};

/// A clamped cubic in the full form and the same in the multiplicities form.
fn cubic_forms() -> (Value, Value) {
    let points = json!([
        [0, 0],
        [1, 3],
        [3, 4],
        [5, 3.5],
        [6, 1],
        [8, 0],
        [9, 2],
        [10, 4]
    ]);
    let full = json!({"degree": 3, "control_points": points,
        "knots": [0, 0, 0, 0, 0.2, 0.35, 0.5, 0.75, 1, 1, 1, 1]});
    let multiplicities = json!({"degree": 3, "control_points": points,
        "knots": [0, 0.2, 0.35, 0.5, 0.75, 1], "multiplicities": [4, 1, 1, 1, 1, 4]});
    (full, multiplicities)
}

/// A periodic cubic in Open CASCADE's form: 6 poles, knots of one period [0, 3].
fn periodic_cubic() -> Value {
    json!({"degree": 3, "periodic": true,
        "control_points": [[2, 0], [1, 1.7], [-1, 1.7], [-2, 0], [-1, -1.7], [1, -1.7]],
        "knots": [0, 0.5, 1, 1.5, 2, 2.5, 3], "multiplicities": [1, 1, 1, 1, 1, 1, 1]})
}

/// The full vector of a multiplicities-form answer.
fn expanded(curve: &Value) -> Vec<f64> {
    numbers(&curve["knots"])
        .into_iter()
        .zip(curve["multiplicities"].as_array().unwrap())
        .flat_map(|(u, m)| std::iter::repeat_n(u, m.as_u64().unwrap() as usize))
        .collect()
}

#[tokio::test]
async fn the_multiplicities_form_evaluates_as_the_full_vector_and_answers_keep_it() {
    let app = spawn_app().await;
    let (full, with_multiplicities) = cubic_forms();
    let parameters: Vec<f64> = (0..=20).map(|i| i as f64 / 20.0).collect();
    let evaluate =
        |curve: &Value| json!({"curve": curve, "parameters": parameters, "derivatives": 1});
    let (status, flat) = app.post_json("/v1/curves/evaluate", &evaluate(&full)).await;
    assert_eq!(status, 200, "{flat}");
    let (status, distinct) = app
        .post_json("/v1/curves/evaluate", &evaluate(&with_multiplicities))
        .await;
    assert_eq!(status, 200, "{distinct}");
    assert_eq!(flat, distinct);

    // Insertion: the refined curve comes back with multiplicities.
    let insert = json!({"curve": with_multiplicities, "knots": [0.6, 0.6]});
    let (status, body) = app.post_json("/v1/curves/insert-knots", &insert).await;
    assert_eq!(status, 200, "{body}");
    assert_eq!(
        numbers(&body["curve"]["knots"]),
        [0.0, 0.2, 0.35, 0.5, 0.6, 0.75, 1.0]
    );
    assert_eq!(
        body["curve"]["multiplicities"],
        json!([4, 1, 1, 1, 2, 1, 4])
    );

    // Envelope: knot indices are the full vector's; the envelope keeps the form.
    let envelope = json!({"curve": with_multiplicities, "knot_index": 5});
    let (status, body) = app.post_json("/v1/curves/envelope", &envelope).await;
    assert_eq!(status, 200, "{body}");
    assert_eq!(body["moved_knots"], json!([5]));
    assert_eq!(
        expanded(&body["envelope"]),
        [0.0, 0.0, 0.0, 0.0, 0.2, 0.5, 0.75, 1.0, 1.0, 1.0, 1.0]
    );

    // Solutions carry knots with multiplicities: the flat answer's vector, run-length coded.
    let solve = |curve: &Value| json!({"curve": curve, "parameter": 0.42, "target": [4.746666666666666, 3.3233333333333333]});
    let (status, flat) = app.post_json("/v1/shape/solve", &solve(&full)).await;
    assert_eq!(status, 200, "{flat}");
    let (status, distinct) = app
        .post_json("/v1/shape/solve", &solve(&with_multiplicities))
        .await;
    assert_eq!(status, 200, "{distinct}");
    let flat_solutions = flat["solutions"].as_array().unwrap();
    let solutions = distinct["solutions"].as_array().unwrap();
    assert_eq!(flat_solutions.len(), solutions.len());
    let mut knot_solutions = 0;
    for (a, b) in flat_solutions.iter().zip(solutions) {
        assert_eq!(a["changed_knots"], b["changed_knots"]);
        assert_eq!(a["moved_knot"], b["moved_knot"]);
        if a["method"] == "knots" {
            knot_solutions += 1;
            assert!(a.get("multiplicities").is_none());
            assert_eq!(numbers(&a["knots"]), expanded(b));
        }
    }
    assert!(knot_solutions > 0, "{distinct}");
}

#[tokio::test]
async fn periodic_curves_evaluate_repeat_insert_and_split_into_pieces() {
    let app = spawn_app().await;
    let curve = periodic_cubic();
    // Any parameter: reduced into the period [0, 3].
    let request = json!({"curve": curve, "parameters": [0.4, 3.4, -2.6, 0, 3]});
    let (status, body) = app.post_json("/v1/curves/evaluate", &request).await;
    assert_eq!(status, 200, "{body}");
    assert_eq!(numbers(&body["domain"]), [0.0, 3.0]);
    let found = points(&body["points"]);
    let parameters = numbers(&body["parameters"]);
    assert!((parameters[1] - 0.4).abs() < 1e-12 && (parameters[2] - 0.4).abs() < 1e-12);
    for p in &found[1..3] {
        assert!((p[0] - found[0][0]).abs() < 1e-12 && (p[1] - found[0][1]).abs() < 1e-12);
    }
    // Closed: the two ends meet. A uniform cubic's point at a knot is (P_{i-1} + 4 P_i +
    // P_{i+1}) / 6; the span [k_0, k_1) uses P_0 … P_3 (Open CASCADE's numbering, checked
    // against Open CASCADE in tests/spline_core/periodic.rs), so at 0 it is (P_0 + 4 P_1 + P_2) / 6.
    assert!((found[3][0] - found[4][0]).abs() < 1e-12 && (found[3][1] - found[4][1]).abs() < 1e-12);
    assert!(
        (found[3][0] - (2.0 + 4.0 - 1.0) / 6.0).abs() < 1e-12,
        "{found:?}"
    );
    assert!(
        (found[3][1] - (0.0 + 6.8 + 1.7) / 6.0).abs() < 1e-12,
        "{found:?}"
    );

    // Insertion keeps the curve periodic, in the form.
    let insert = json!({"curve": curve, "knots": [0.75, 3.0]});
    let (status, body) = app.post_json("/v1/curves/insert-knots", &insert).await;
    assert_eq!(status, 200, "{body}");
    let refined = &body["curve"];
    assert_eq!(refined["periodic"], true);
    assert_eq!(refined["control_points"].as_array().unwrap().len(), 8);
    assert_eq!(refined["multiplicities"], json!([2, 1, 1, 1, 1, 1, 1, 2]));
    let probes: Vec<f64> = (0..=30).map(|i| i as f64 / 10.0).collect();
    let (_, before) = app
        .post_json(
            "/v1/curves/evaluate",
            &json!({"curve": curve, "parameters": probes}),
        )
        .await;
    let (_, after) = app
        .post_json(
            "/v1/curves/evaluate",
            &json!({"curve": refined, "parameters": probes}),
        )
        .await;
    for (a, b) in points(&before["points"])
        .iter()
        .zip(points(&after["points"]))
    {
        assert!((a[0] - b[0]).abs() < 1e-12 && (a[1] - b[1]).abs() < 1e-12);
    }

    // One Bézier piece per span of the period.
    let (status, body) = app
        .post_json("/v1/curves/bezier", &json!({"curve": curve}))
        .await;
    assert_eq!(status, 200, "{body}");
    assert_eq!(body["segments"].as_array().unwrap().len(), 6);

    // Closest point across the seam: a query near s(0) finds a parameter at either end.
    let (_, at_zero) = app
        .post_json(
            "/v1/curves/evaluate",
            &json!({"curve": curve, "parameters": [0.0]}),
        )
        .await;
    let seam = points(&at_zero["points"])[0].clone();
    let query = json!({"curve": curve, "points": [[seam[0] + 0.01, seam[1]]]});
    let (status, body) = app.post_json("/v1/curves/closest-point", &query).await;
    assert_eq!(status, 200, "{body}");
    let u = body["results"][0]["parameter"].as_f64().unwrap();
    assert!(!(0.01..=2.99).contains(&u), "{body}");
    assert!(body["results"][0]["distance"].as_f64().unwrap() < 0.0101);
}

#[tokio::test]
async fn bad_multiplicities_are_422s_or_400s_with_pointers() {
    let app = spawn_app().await;
    let (_, good) = cubic_forms();
    let with = |change: &dyn Fn(&mut Value)| {
        let mut curve = good.clone();
        change(&mut curve);
        json!({"curve": curve, "parameters": [0.5]})
    };
    let cases: Vec<(Value, u16, Option<&str>)> = vec![
        // A wrong sum.
        (
            with(&|c| c["multiplicities"] = json!([4, 1, 1, 1, 2, 4])),
            422,
            Some("/curve/multiplicities"),
        ),
        // An interior multiplicity above degree + 1.
        (
            with(&|c| {
                c["multiplicities"] = json!([4, 1, 5, 4]);
                c["knots"] = json!([0, 0.2, 0.5, 1]);
                c["control_points"] = json!([
                    [0, 0],
                    [1, 3],
                    [3, 4],
                    [5, 3.5],
                    [6, 1],
                    [8, 0],
                    [9, 2],
                    [10, 4],
                    [11, 0],
                    [12, 1]
                ]);
            }),
            422,
            Some("/curve/multiplicities/2"),
        ),
        (
            with(&|c| c["multiplicities"] = json!([4, 0, 1, 1, 2, 4])),
            422,
            Some("/curve/multiplicities/1"),
        ),
        (
            with(&|c| c["multiplicities"] = json!([4, 1, 1, 1, 4])),
            422,
            Some("/curve/multiplicities"),
        ),
        (
            with(&|c| c["knots"] = json!([0, 0.2, 0.2, 0.5, 0.75, 1])),
            422,
            Some("/curve/knots/2"),
        ),
        // Not integers >= 0: the body's types are wrong.
        (
            with(&|c| c["multiplicities"] = json!([4, 1.5, 1, 1, 1, 4])),
            400,
            None,
        ),
        (
            with(&|c| c["multiplicities"] = json!([4, -1, 1, 1, 1, 4])),
            400,
            None,
        ),
        (
            with(&|c| c["multiplicities"] = json!([4, 1e300, 1, 1, 1, 4])),
            400,
            None,
        ),
        (
            with(&|c| c["multiplicities"] = json!([4, u64::MAX, u64::MAX, 1, 1, 4])),
            422,
            Some("/curve/multiplicities/1"),
        ),
    ];
    for (request, status, pointer) in cases {
        let (got, body) = app.post_json("/v1/curves/evaluate", &request).await;
        assert_eq!(got, status, "{request}: {body}");
        assert_problem(status, &body, pointer);
    }
}

#[tokio::test]
async fn bad_periodic_curves_are_422s_and_editing_endpoints_refuse_periodic_ones() {
    let app = spawn_app().await;
    let good = periodic_cubic();
    let with = |change: &dyn Fn(&mut Value)| {
        let mut curve = good.clone();
        change(&mut curve);
        json!({"curve": curve, "parameters": [0.5]})
    };
    let cases = [
        (
            with(&|c| c["multiplicities"] = json!([1, 1, 1, 1, 1, 1, 2])),
            "/curve/multiplicities/6",
        ),
        (
            with(&|c| {
                c["multiplicities"] = json!([4, 1, 4]);
                c["knots"] = json!([0, 1, 3]);
            }),
            "/curve/multiplicities/0",
        ),
        (
            with(&|c| c["multiplicities"] = json!([1, 2, 1, 1, 1, 1, 1])),
            "/curve/multiplicities",
        ),
        (
            with(&|c| {
                c.as_object_mut()
                    .unwrap()
                    .remove("multiplicities")
                    .map(|_| ())
                    .unwrap()
            }),
            "/curve/multiplicities",
        ),
        (
            with(&|c| {
                c["knots"] = json!([0]);
                c["multiplicities"] = json!([1]);
            }),
            "/curve/knots",
        ),
    ];
    for (request, pointer) in cases {
        let (status, body) = app.post_json("/v1/curves/evaluate", &request).await;
        assert_eq!(status, 422, "{request}: {body}");
        assert_problem(422, &body, Some(pointer));
    }
    // The envelope and the editable-at insertion do not take periodic curves: a clear 422,
    // not a wrong answer (the editing methods do: tests/api/periodic_edit.rs).
    for (path, request) in [
        (
            "/v1/curves/envelope",
            json!({"curve": good, "knot_index": 3}),
        ),
        (
            "/v1/curves/insert-knots",
            json!({"curve": good, "editable_at": {"parameter": 0.7}}),
        ),
    ] {
        let (status, body) = app.post_json(path, &request).await;
        assert_eq!(status, 422, "{path}: {body}");
        let pointer = if path.ends_with("insert-knots") {
            "/editable_at"
        } else {
            "/curve/periodic"
        };
        assert_problem(422, &body, Some(pointer));
    }
}

/// A small STEP file Open CASCADE 8 wrote (a rational cubic edge), see examples/.
fn occt_step() -> String {
    let example: Value = serde_json::from_str(
        &std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/examples/curves-import-step.json"
        ))
        .unwrap(),
    )
    .unwrap();
    example["data"].as_str().unwrap().to_owned()
}

#[tokio::test]
async fn import_reads_step_and_dxf_and_export_writes_them_back() {
    let app = spawn_app().await;
    let (status, body) = app
        .post_json(
            "/v1/curves/import",
            &json!({"format": "step", "data": occt_step()}),
        )
        .await;
    assert_eq!(status, 200, "{body}");
    assert_eq!(body["skipped"], 1, "the trimmed curve around the B-spline");
    let curve = &body["curves"][0];
    assert_eq!(curve["source"], "#17");
    assert_eq!(curve["multiplicities"], json!([4, 4]));
    assert_eq!(curve["weights"], json!([1.0, 0.5, 2.0, 1.0]));

    // Export both formats; import what was written: the same curves.
    let (_, with_multiplicities) = cubic_forms();
    let curves = json!([with_multiplicities, periodic_cubic(), {"degree": 1,
        "control_points": [[0, 0, 1], [1, 1, 2]], "knots": [0, 0, 1, 1], "weights": [1, 3]}]);
    for (format, content_type) in [("step", "model/step"), ("dxf", "image/vnd.dxf")] {
        let response = app
            .post(
                "/v1/curves/export",
                &json!({"format": format, "curves": curves}),
            )
            .await;
        assert_eq!(response.status().as_u16(), 200);
        assert_eq!(response.headers()["content-type"], content_type);
        let text = response.text().await.unwrap();
        let (status, back) = app
            .post_json(
                "/v1/curves/import",
                &json!({"format": format, "data": text}),
            )
            .await;
        assert_eq!(status, 200, "{back}");
        assert_eq!(back["skipped"], 0);
        let back = back["curves"].as_array().unwrap();
        assert_eq!(back.len(), 3);
        // 2D curves come back with z = 0; the first one's numbers are the ones sent.
        let first = points(&back[0]["control_points"]);
        let sent = points(&with_multiplicities["control_points"]);
        for (a, b) in first.iter().zip(&sent) {
            assert_eq!(&a[..2], &b[..]);
            assert_eq!(a[2], 0.0);
        }
        assert_eq!(back[2]["weights"], json!([1.0, 3.0]));
        // The periodic curve comes back clamped over its period: the same points.
        let probes: Vec<f64> = (0..=12).map(|i| i as f64 / 4.0).collect();
        let mut periodic = back[1].clone();
        periodic.as_object_mut().unwrap().remove("source");
        let (_, a) = app
            .post_json(
                "/v1/curves/evaluate",
                &json!({"curve": periodic_cubic(), "parameters": probes}),
            )
            .await;
        let (_, b) = app
            .post_json(
                "/v1/curves/evaluate",
                &json!({"curve": periodic, "parameters": probes}),
            )
            .await;
        for (p, q) in points(&a["points"]).iter().zip(points(&b["points"])) {
            assert!((p[0] - q[0]).abs() < 1e-12 && (p[1] - q[1]).abs() < 1e-12 && q[2] == 0.0);
        }
    }
}

#[tokio::test]
async fn bad_files_and_exports_are_4xx_as_a_whole() {
    let app = spawn_app_with(|config| {
        config.max_file_bytes = 20_000;
        config.max_file_entities = 50;
    })
    .await;
    let step = occt_step();
    let truncated = &step[..step.len() / 2];
    let cases: Vec<(Value, u16, Option<&str>)> = vec![
        (
            json!({"format": "step", "data": truncated}),
            422,
            Some("/data"),
        ),
        (
            json!({"format": "step", "data": step.replace("(4,4)", "(4,3)")}),
            422,
            Some("/data"),
        ),
        (
            json!({"format": "step", "data": "x".repeat(20_001)}),
            422,
            Some("/data"),
        ),
        (
            json!({"format": "step", "data": step.replace("#29 =", "#29 = A((((((((((((((((((((((((((((((((((1)))))))))))))))))))))))))))))))))); #30 =")}),
            422,
            Some("/data"),
        ),
        (
            json!({"format": "dxf", "data": "0\nSECTION\n2\nENTITIES\n0\nSPLINE\n71\n3\n"}),
            422,
            Some("/data"),
        ),
        (
            json!({"format": "dxf", "data": "AutoCAD Binary DXF\r\n"}),
            422,
            Some("/data"),
        ),
        (json!({"format": "iges", "data": ""}), 422, Some("/format")),
        (json!({"format": "step"}), 400, None),
    ];
    for (request, status, pointer) in cases {
        let (got, body) = app.post_json("/v1/curves/import", &request).await;
        assert_eq!(got, status, "{body}");
        assert_problem(status, &body, pointer);
    }
    let many: String = (0..60)
        .map(|i| format!("#{}=CARTESIAN_POINT('',(0.,0.));\n", i + 100))
        .collect();
    let crowded = step.replace("ENDSEC;\nEND-ISO", &format!("{many}ENDSEC;\nEND-ISO"));
    let (status, body) = app
        .post_json(
            "/v1/curves/import",
            &json!({"format": "step", "data": crowded}),
        )
        .await;
    assert_eq!(status, 422, "{body}");
    assert!(
        body["detail"]
            .as_str()
            .unwrap()
            .contains("more than 50 entities"),
        "{body}"
    );

    let (_, good) = cubic_forms();
    let mut bad = good.clone();
    bad["multiplicities"] = json!([4, 1, 1, 1, 1, 3]);
    let exports: Vec<(Value, u16, Option<&str>)> = vec![
        (
            json!({"format": "step", "curves": []}),
            422,
            Some("/curves"),
        ),
        (
            json!({"format": "dxf", "curves": [good, bad]}),
            422,
            Some("/curves/1/multiplicities"),
        ),
        (
            json!({"format": "step", "curves": vec![good.clone(); 51]}),
            422,
            Some("/curves"),
        ),
        (
            json!({"format": "svg", "curves": [good]}),
            422,
            Some("/format"),
        ),
    ];
    for (request, status, pointer) in exports {
        let (got, body) = app.post_json("/v1/curves/export", &request).await;
        assert_eq!(got, status, "{body}");
        assert_problem(status, &body, pointer);
    }
}

#[tokio::test]
async fn healthz_answers_while_large_files_are_read() {
    let app = spawn_app().await;
    // A 900 kB STEP file of points: read on the blocking pool, the runtime stays free.
    let points: String = (0..20_000)
        .map(|i| format!("#{}=CARTESIAN_POINT('',({i}.,0.5,1.E-3));\n", i + 1))
        .collect();
    let data =
        format!("ISO-10303-21;\nHEADER;\nENDSEC;\nDATA;\n{points}ENDSEC;\nEND-ISO-10303-21;\n");
    let request = json!({"format": "step", "data": data});
    let imports: Vec<_> = (0..4)
        .map(|_| app.post("/v1/curves/import", &request))
        .collect();
    let health = app.get("/healthz");
    let (health, answers) = tokio::join!(health, futures_join(imports));
    assert_eq!(health.status().as_u16(), 200);
    for answer in answers {
        assert_eq!(answer.status().as_u16(), 200);
    }
}

async fn futures_join<F: std::future::Future>(futures: Vec<F>) -> Vec<F::Output> {
    let mut out = Vec::with_capacity(futures.len());
    for future in futures {
        out.push(future.await);
    }
    out
}

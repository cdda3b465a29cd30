//! `POST /v1/shape/regions` with `Accept: image/svg+xml`: the picture parses as XML, its
//! polygons are exactly the JSON answer's (same request), and it shows the control
//! triangles, the picked point, the target and a legend.

use serde_json::{Value, json};

use crate::helpers::{expect_problem, spawn_app};

fn request() -> Value {
    json!({
        "curve": {"degree": 3, "control_points": [[0, 0], [1, 3], [3, 4], [5, 3.5], [6, 1], [8, 0], [9, 2], [10, 4]],
                  "knots": [0, 0, 0, 0, 0.2, 0.35, 0.5, 0.75, 1, 1, 1, 1]},
        "parameter": 0.42,
        "target": [4.746666666666666, 3.3233333333333333]
    })
}

/// The `points` attribute as pairs.
fn parse_points(text: &str) -> Vec<[f64; 2]> {
    text.split_whitespace()
        .map(|pair| {
            let (x, y) = pair.split_once(',').expect("x,y");
            [x.parse().unwrap(), y.parse().unwrap()]
        })
        .collect()
}

async fn picture(body: &Value, accept: &str) -> (u16, String, String) {
    let app = spawn_app().await;
    let response = app
        .client
        .post(format!("{}/v1/shape/regions", app.address))
        .header("accept", accept)
        .json(body)
        .send()
        .await
        .unwrap();
    let status = response.status().as_u16();
    let content_type = response.headers()["content-type"]
        .to_str()
        .unwrap()
        .to_owned();
    (status, content_type, response.text().await.unwrap())
}

#[tokio::test]
async fn the_svg_polygons_are_the_json_polygons() {
    let app = spawn_app().await;
    let (status, json_answer) = app.post_json("/v1/shape/regions", &request()).await;
    assert_eq!(status, 200, "{json_answer}");
    let (status, content_type, svg) = picture(&request(), "image/svg+xml").await;
    assert_eq!(status, 200, "{svg}");
    assert_eq!(content_type, "image/svg+xml");
    let document = roxmltree::Document::parse(&svg).expect("the picture is well-formed XML");
    let root = document.root_element();
    assert_eq!(root.tag_name().name(), "svg");
    assert_eq!(
        root.tag_name().namespace(),
        Some("http://www.w3.org/2000/svg")
    );

    let mut compared = 0;
    for candidate in json_answer["candidates"].as_array().unwrap() {
        let side = candidate["side"].as_str().unwrap();
        for region in candidate["regions"].as_array().unwrap() {
            let name = region["region"].as_str().unwrap();
            let node = document
                .descendants()
                .find(|n| {
                    n.has_tag_name("polygon")
                        && n.attribute("data-side") == Some(side)
                        && n.attribute("data-region") == Some(name)
                })
                .unwrap_or_else(|| panic!("no polygon for {side} {name}"));
            let drawn = parse_points(node.attribute("points").unwrap());
            let expected: Vec<[f64; 2]> = region["polygon"]
                .as_array()
                .unwrap()
                .iter()
                .map(|p| [p[0].as_f64().unwrap(), p[1].as_f64().unwrap()])
                .collect();
            assert_eq!(drawn, expected, "{side} {name}");
            assert!(
                node.attribute("fill")
                    .is_some_and(|fill| fill.starts_with('#'))
            );
            compared += 1;
        }
        if candidate["applicable"] == json!(true) {
            let triangle = document
                .descendants()
                .find(|n| {
                    n.has_tag_name("polygon")
                        && n.attribute("class") == Some("triangle")
                        && n.attribute("data-side") == Some(side)
                })
                .unwrap_or_else(|| panic!("no control triangle for {side}"));
            let expected: Vec<[f64; 2]> = candidate["triangle"]
                .as_array()
                .unwrap()
                .iter()
                .map(|p| [p[0].as_f64().unwrap(), p[1].as_f64().unwrap()])
                .collect();
            assert_eq!(
                parse_points(triangle.attribute("points").unwrap()),
                expected
            );
        }
    }
    assert!(compared >= 6, "only {compared} polygons compared");
    let count = |class: &str| {
        document
            .descendants()
            .filter(|n| n.attribute("class") == Some(class))
            .count()
    };
    assert_eq!(
        count("picked"),
        json_answer["candidates"].as_array().unwrap().len()
    );
    assert_eq!(count("target"), count("picked"));
    assert_eq!(count("legend"), 1);
    let target = document
        .descendants()
        .find(|n| n.attribute("class") == Some("target"))
        .unwrap();
    assert_eq!(
        target.attribute("cx").unwrap().parse::<f64>().unwrap(),
        4.746666666666666
    );
    // The picked point is s(0.42) of the sample.
    let (_, evaluated) = app
        .post_json(
            "/v1/curves/evaluate",
            &json!({"curve": request()["curve"], "parameters": [0.42]}),
        )
        .await;
    let picked = document
        .descendants()
        .find(|n| n.attribute("class") == Some("picked"))
        .unwrap();
    assert_eq!(
        picked.attribute("cx").unwrap().parse::<f64>().unwrap(),
        evaluated["points"][0][0].as_f64().unwrap()
    );
}

#[tokio::test]
async fn json_stays_the_default_and_errors_stay_problems() {
    for accept in ["application/json", "*/*", "image/svg+xml, application/json"] {
        let (status, content_type, body) = picture(&request(), accept).await;
        assert_eq!(status, 200);
        assert_eq!(content_type, "application/json", "Accept: {accept}");
        assert!(body.starts_with('{'));
    }
    // Without a target the picture has none.
    let mut without = request();
    without.as_object_mut().unwrap().remove("target");
    let (_, _, svg) = picture(&without, "image/svg+xml").await;
    let document = roxmltree::Document::parse(&svg).unwrap();
    assert!(
        !document
            .descendants()
            .any(|n| n.attribute("class") == Some("target"))
    );
    // A bad target is a 422 naming it, for both media types.
    let mut bad = request();
    bad["target"] = json!([1, 2, 3]);
    let app = spawn_app().await;
    for accept in ["image/svg+xml", "application/json"] {
        let response = app
            .client
            .post(format!("{}/v1/shape/regions", app.address))
            .header("accept", accept)
            .json(&bad)
            .send()
            .await
            .unwrap();
        expect_problem(response, 422, Some("/target")).await;
    }
}

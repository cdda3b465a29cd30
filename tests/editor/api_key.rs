//! With an API key configured, the page itself loads (it is open like the probes) but its
//! `/v1` requests are refused until the designer types the key into its field; then it draws
//! and edits as usual.

use fantoccini::Locator;
use fantoccini::key::Key;
use serde_json::json;

use super::browser::Browser;
use super::page::Page;
use crate::helpers::spawn_app_with;

#[tokio::test]
async fn the_page_sends_the_key_typed_into_its_field() {
    let app = spawn_app_with(|config| config.api_key = Some("s3cret".parse().unwrap())).await;
    let browser = Browser::start().await;
    let page = Page::open(&browser.client, &app.address).await;
    let error = page.data("error").await;
    assert!(
        error.contains("Unauthorized"),
        "error without the key: {error}"
    );
    let curves = "return document.querySelectorAll('#scene .layer-curve > .curve').length;";
    assert_eq!(page.run(curves, vec![]).await, json!(0));

    let field = browser.client.find(Locator::Id("api-key")).await.unwrap();
    field
        .send_keys(&format!("s3cret{}", char::from(Key::Enter)))
        .await
        .unwrap();
    page.settle().await;
    assert_eq!(page.data("error").await, "", "{}", page.describe().await);
    assert_eq!(page.run(curves, vec![]).await, json!(1));
    let stored = page
        .run("return sessionStorage.getItem('knotshape.apiKey');", vec![])
        .await;
    assert_eq!(stored, json!("s3cret"));
    // The curve is drawn from the API's answer, across the canvas.
    let bounds = page
        .run(
            "const r = document.querySelector('#scene .layer-curve > .curve').getBoundingClientRect(); \
             return [r.width, r.height];",
            vec![],
        )
        .await;
    assert!(bounds[0].as_f64().unwrap() > 300.0, "{bounds}");
    // No script error, nothing on the console.
    assert_eq!(page.script_errors().await, Vec::<String>::new());
    browser.close().await;
}

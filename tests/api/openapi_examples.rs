//! Every `example` in the OpenAPI document is valid against the schema it illustrates
//! (checked by the `jsonschema` crate, JSON Schema 2020-12 as OpenAPI 3.1 uses it), so that
//! clients generated from the document, and readers, are never shown an impossible value.

use serde_json::Value;

/// Every `(JSON pointer of a schema, its example)` under `value` (at `pointer`).
fn examples(value: &Value, pointer: &str, found: &mut Vec<(String, Value)>) {
    match value {
        Value::Object(map) => {
            if let Some(example) = map.get("example") {
                found.push((pointer.to_owned(), example.clone()));
            }
            for (key, child) in map {
                if key == "example" {
                    continue;
                }
                let token = key.replace('~', "~0").replace('/', "~1");
                examples(child, &format!("{pointer}/{token}"), found);
            }
        }
        Value::Array(items) => {
            for (index, child) in items.iter().enumerate() {
                examples(child, &format!("{pointer}/{index}"), found);
            }
        }
        _ => {}
    }
}

#[test]
fn every_example_in_the_document_is_valid_against_its_schema() {
    let document: Value = serde_json::from_str(&knotshape::openapi_json()).unwrap();
    let mut found = Vec::new();
    examples(
        &document["components"]["schemas"],
        "#/components/schemas",
        &mut found,
    );
    assert!(found.len() > 60, "{} examples", found.len());
    let mut invalid = Vec::new();
    for (pointer, example) in &found {
        // The document itself is the root schema, so that `$ref`s into its components
        // resolve; its other members are keywords JSON Schema does not know (ignored).
        let mut schema = document.clone();
        schema["$ref"] = Value::String(pointer.clone());
        let validator = jsonschema::draft202012::new(&schema)
            .unwrap_or_else(|error| panic!("{pointer}: not a schema: {error}"));
        let errors: Vec<String> = validator
            .iter_errors(example)
            .map(|error| format!("{} at {}", error, error.instance_path()))
            .collect();
        if !errors.is_empty() {
            invalid.push(format!("{pointer}: {example}: {errors:?}"));
        }
    }
    assert!(
        invalid.is_empty(),
        "examples that break their schema:\n{}",
        invalid.join("\n")
    );
}

/// The test can fail: an example that breaks its schema is found.
#[test]
fn a_broken_example_is_caught() {
    let mut document: Value = serde_json::from_str(&knotshape::openapi_json()).unwrap();
    let example = &mut document["components"]["schemas"]["SolveResponse"]["example"];
    example["solutions"][0]
        .as_object_mut()
        .unwrap()
        .remove("method");
    let mut schema = document.clone();
    schema["$ref"] = Value::String("#/components/schemas/SolveResponse".into());
    let validator = jsonschema::draft202012::new(&schema).unwrap();
    assert!(!validator.is_valid(&document["components"]["schemas"]["SolveResponse"]["example"]));
}

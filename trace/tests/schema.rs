//! docs/trace-schema.json is generated from the types (`ilmr_trace::json_schema`);
//! `UPDATE_DOCS=1 cargo test -p ilmr-trace --test schema` rewrites it.

const DOC: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/trace-schema.json");

#[test]
fn the_published_schema_is_the_types_schema() {
    let schema = ilmr_trace::json_schema();
    if std::env::var_os("UPDATE_DOCS").is_some() {
        std::fs::write(DOC, &schema).expect("write docs/trace-schema.json");
    }
    let doc = std::fs::read_to_string(DOC).unwrap_or_default();
    assert!(
        doc == schema,
        "docs/trace-schema.json is stale: run `UPDATE_DOCS=1 cargo test -p ilmr-trace --test schema`"
    );
}

#[test]
fn docs_list_every_reader_code() {
    let run = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/run.md"))
        .expect("docs/run.md");
    let listed: Vec<&str> = run
        .lines()
        .filter_map(|l| l.strip_prefix("| `T")?.split('`').next())
        .collect();
    let codes: Vec<String> = ilmr_trace::Code::ALL
        .iter()
        .map(|c| c.code()[1..].to_string())
        .collect();
    assert_eq!(listed, codes, "docs/run.md's table of trace codes");
}

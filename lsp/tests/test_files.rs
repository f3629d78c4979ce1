//! Test files (`*.test.toml`) through the engine: diagnostics re-checked once after a
//! burst of edits, completion while an assertion's string is still open, hover.

use ilmr_lsp::{Engine, Settings};
use tower_lsp_server::ls_types::{
    CompletionTextEdit, HoverContents, Position, Range, TextDocumentContentChangeEvent, Uri,
};

fn folder(name: &str) -> std::path::PathBuf {
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("task.ilmr"),
        "speed(0.4)\ng=goahead(1.2)\nwait(g)\n",
    )
    .unwrap();
    dir
}

fn engine() -> Engine {
    Engine::new(
        Vec::new(),
        Settings {
            robot: Some("moro".into()),
            snippets: false,
            ilmrc: None,
        },
    )
}

fn codes(engine: &Engine, uri: &Uri) -> Vec<String> {
    engine
        .diagnostics(uri)
        .iter()
        .map(|d| match &d.code {
            Some(tower_lsp_server::ls_types::NumberOrString::String(c)) => c.clone(),
            _ => String::new(),
        })
        .collect()
}

#[test]
fn a_burst_of_edits_is_checked_once_after_it() {
    let dir = folder("burst");
    let uri: Uri = format!("file://{}/t.test.toml", dir.display())
        .parse()
        .unwrap();
    let text = "task = \"task.ilmr\"\n[[test]]\nname = \"t\"\nassert = [\"never: refused\"]\n";
    let mut e = engine();
    let opened = e.open(uri.clone(), 1, text.to_string());
    assert_eq!(opened.len(), 1);
    assert!(
        opened[0].diagnostics.is_empty(),
        "{:?}",
        opened[0].diagnostics
    );
    // `refused` becomes `refusd`, then `refusd` becomes `refusd2`: one check after both.
    let edit = |col: u32, len: u32, text: &str| TextDocumentContentChangeEvent {
        range: Some(Range::new(
            Position::new(3, col),
            Position::new(3, col + len),
        )),
        range_length: None,
        text: text.into(),
    };
    e.apply_change(&uri, 2, vec![edit(23, 1, "")]);
    e.apply_change(&uri, 3, vec![edit(24, 0, "2")]);
    let published = e.refresh().expect("the edits are checked");
    assert_eq!(published.len(), 1);
    assert_eq!(published[0].version, Some(3));
    assert_eq!(codes(&e, &uri), ["A0201"]);
    assert!(e.refresh().is_none(), "nothing is left to check");
    let closed = e.close(&uri);
    assert!(closed[0].diagnostics.is_empty());
    assert!(e.diagnostics(&uri).is_empty());
}

#[test]
fn an_open_string_is_completed_as_if_closed() {
    let dir = folder("open_string");
    let uri: Uri = format!("file://{}/t.test.toml", dir.display())
        .parse()
        .unwrap();
    // The string (and the array) are not closed yet: the file is no TOML.
    let text = "task = \"task.ilmr\"\n[[test]]\nname = \"t\"\nassert = [\"wait until: line ";
    let mut e = engine();
    e.open(uri.clone(), 1, text.to_string());
    let not_toml = codes(&e, &uri);
    assert!(
        !not_toml.is_empty() && not_toml.iter().all(|c| c == "A0101"),
        "{not_toml:?}"
    );
    let text = "task = \"task.ilmr\"\n[[test]]\nname = \"t\"\nassert = [\"before(line ";
    e.change(
        &uri,
        2,
        vec![TextDocumentContentChangeEvent {
            range: None,
            range_length: None,
            text: text.into(),
        }],
    );
    let at = Position::new(3, "assert = [\"before(line ".len() as u32);
    let list = e.completion_list(&uri, at);
    let got: Vec<(String, Option<String>)> = list
        .items
        .iter()
        .map(|i| (i.label.clone(), i.detail.clone()))
        .collect();
    assert_eq!(
        got,
        [
            ("1".to_string(), Some("speed(0.4)".to_string())),
            ("2".to_string(), Some("g=goahead(1.2)".to_string())),
            ("3".to_string(), Some("wait(g)".to_string())),
        ]
    );
    let Some(CompletionTextEdit::Edit(edit)) = &list.items[0].text_edit else {
        panic!("an edit");
    };
    assert_eq!(edit.range, Range::new(at, at));
}

#[test]
fn hover_on_a_line_reference_shows_its_statement() {
    let dir = folder("hover");
    let uri: Uri = format!("file://{}/t.test.toml", dir.display())
        .parse()
        .unwrap();
    let text =
        "task = \"task.ilmr\"\n[[test]]\nname = \"t\"\nassert = [\"eventually: line 2 ends\"]\n";
    let mut e = engine();
    e.open(uri.clone(), 1, text.to_string());
    assert!(e.diagnostics(&uri).is_empty());
    let at = Position::new(3, "assert = [\"eventually: line ".len() as u32);
    let hover = e.hover(&uri, at).expect("a hover");
    let HoverContents::Markup(m) = hover.contents else {
        panic!("markdown");
    };
    assert_eq!(m.value, "line 2 of the task: `g=goahead(1.2)`");
    assert_eq!(
        hover.range,
        Some(Range::new(at, Position::new(at.line, at.character + 1)))
    );
    // Off the assertions and keys, nothing.
    assert!(e.hover(&uri, Position::new(1, 3)).is_none());
}

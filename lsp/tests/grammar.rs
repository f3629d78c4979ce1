//! The VS Code extension's TextMate grammar names every command and keyword of the
//! catalogue, so that a command added to `ilmr-stdlib` cannot go unhighlighted.

use ilmr_stdlib::{CATALOGUE, Syntax};
use serde_json::Value;

/// The word list of a rule's regex: the parenthesised run of `a|b|c` with most words.
fn alternatives(grammar: &Value, rule: &str, key: &str) -> Vec<String> {
    let regex = grammar["repository"][rule][key]
        .as_str()
        .unwrap_or_else(|| panic!("rule `{rule}` has a `{key}`"));
    let list = regex
        .split(['(', ')'])
        .filter(|part| part.contains('|'))
        .filter(|part| part.chars().all(|c| c.is_ascii_lowercase() || c == '|'))
        .max_by_key(|part| part.matches('|').count())
        .unwrap_or_else(|| panic!("rule `{rule}` lists words"));
    list.split('|').map(str::to_string).collect()
}

#[test]
fn the_grammar_knows_every_command_and_keyword() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../vscode-extension/syntaxes/ilmr.tmLanguage.json"
    );
    let text = std::fs::read_to_string(path).expect("the grammar is in the repository");
    let grammar: Value = serde_json::from_str(&text).expect("the grammar is JSON");
    let commands = alternatives(&grammar, "call", "begin");
    for spec in CATALOGUE.iter().filter(|s| s.syntax == Syntax::Call) {
        assert!(
            commands.iter().any(|c| c == spec.name),
            "`{}` missing from the grammar",
            spec.name
        );
    }
    let keywords = alternatives(&grammar, "keyword", "match");
    // One-letter keywords (`x`, `w`) are left to semantic highlighting: as plain words
    // they are far more often variables.
    for word in ilmr_stdlib::all_keywords()
        .into_iter()
        .filter(|w| w.len() > 1)
    {
        assert!(
            keywords.iter().any(|k| k == word),
            "keyword `{word}` missing from the grammar"
        );
    }
}

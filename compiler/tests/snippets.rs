//! Every ILMR snippet of the README and the language docs (fenced as `ilmr` for a task,
//! `ilms` for a skill file) checks without a diagnostic on MoRo, so the examples a
//! newcomer copies are valid ILMR.

use ilmr_compiler::check::{Source, analyze};

const DOCS: &[&str] = &["README.md", "docs/language.md", "docs/commands.md"];

/// The fenced blocks of `text` whose info string is `ilmr` or `ilms`, with their kind.
fn snippets(text: &str) -> Vec<(&str, String)> {
    let mut out = Vec::new();
    let mut open: Option<(&str, String)> = None;
    for line in text.lines() {
        let fence = line.trim_start().strip_prefix("```");
        match (&mut open, fence) {
            (None, Some(info)) => {
                open = Some((info.trim(), String::new()));
            }
            (Some(_), Some(_)) => {
                let (info, body) = open.take().unwrap();
                if matches!(info, "ilmr" | "ilms") {
                    out.push((info, body));
                }
            }
            (Some((_, body)), None) => {
                body.push_str(line);
                body.push('\n');
            }
            (None, None) => {}
        }
    }
    assert!(open.is_none(), "a fenced block is not closed");
    out
}

#[test]
fn every_snippet_of_the_docs_checks_clean() {
    let model = ilmr_model::RobotModel::builtin("moro").unwrap();
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
    let mut checked = 0;
    for doc in DOCS {
        let text = std::fs::read_to_string(format!("{root}/{doc}")).unwrap();
        for (i, (kind, body)) in snippets(&text).into_iter().enumerate() {
            let name = format!("{doc} snippet {}.{kind}", i + 1);
            let sources = vec![Source::new(name.clone(), body.clone())];
            let analysis = analyze(&sources, &model);
            let found: Vec<String> = analysis
                .diagnostics
                .iter()
                .map(|d| format!("{} {}", d.code.as_str(), d.message))
                .collect();
            assert!(found.is_empty(), "{name}:\n{body}\n{found:#?}");
            checked += 1;
        }
    }
    // The README's language example is one of them.
    assert!(checked >= 2, "only {checked} snippets found");
}

#[test]
fn the_one_line_example_the_readme_used_to_show_is_not_ilmr() {
    let model = ilmr_model::RobotModel::builtin("moro").unwrap();
    let text = "door = sensor(scanner,door,left)\nif(door) gotoxy(door) endif\n";
    let sources = vec![Source::new("old.ilmr", text)];
    assert!(
        analyze(&sources, &model)
            .diagnostics
            .iter()
            .any(|d| d.is_error())
    );
}

#[test]
fn fences_are_read_by_their_info_string() {
    let text = "```ilmr\ngoahead(1)\n```\n```sh\nls\n```\n```ilms\nA:\nstop\n```\n";
    let found = snippets(text);
    assert_eq!(
        found,
        [
            ("ilmr", "goahead(1)\n".to_string()),
            ("ilms", "A:\nstop\n".to_string())
        ]
    );
}

//! The engine without the protocol: fixtures with a `$0` cursor, answers rendered as
//! text (completion one item per line, hovers as their markdown) and snapshotted.

use ilmr_lsp::{Engine, Settings};
use tower_lsp_server::ls_types::{
    CompletionItem, CompletionTextEdit, Position, Range, TextDocumentContentChangeEvent, Uri,
};

const TASK: &str = "file:///ws/task.ilmr";
const SKILLS: &str = "file:///ws/skills.ilms";

fn uri(s: &str) -> Uri {
    s.parse().expect("test URIs parse")
}

/// An engine holding `files` (URI, text); the one with `$0` gives the cursor.
fn setup(files: &[(&str, &str)]) -> (Engine, Uri, Position) {
    let mut engine = Engine::new(
        Vec::new(),
        Settings {
            robot: Some("moro".into()),
            snippets: true,
            ilmrc: None,
        },
    );
    let mut cursor = None;
    for (name, text) in files {
        let text = match text.find("$0") {
            Some(at) => {
                let before = &text[..at];
                let line = before.matches('\n').count() as u32;
                let col = before
                    .rsplit('\n')
                    .next()
                    .unwrap_or("")
                    .encode_utf16()
                    .count() as u32;
                cursor = Some((uri(name), Position::new(line, col)));
                text.replacen("$0", "", 1)
            }
            None => text.to_string(),
        };
        engine.open(uri(name), 1, text);
    }
    let (u, p) = cursor.expect("a fixture marks the cursor with $0");
    (engine, u, p)
}

fn completions(text: &str) -> String {
    let (engine, u, p) = setup(&[(TASK, text)]);
    render_items(&engine.completion(&u, p))
}

fn render_items(items: &[CompletionItem]) -> String {
    items
        .iter()
        .map(|i| {
            let insert = match &i.text_edit {
                Some(CompletionTextEdit::Edit(e)) if e.new_text != i.label => {
                    format!("  => {}", e.new_text.replace('\n', "\\n"))
                }
                _ => String::new(),
            };
            format!(
                "{:<14} {:?} | {}{insert}",
                i.label,
                i.kind.expect("every item has a kind"),
                i.detail.as_deref().unwrap_or("")
            )
        })
        .collect::<Vec<_>>()
        .join("\n")
}

fn labels(text: &str) -> Vec<String> {
    let (engine, u, p) = setup(&[(TASK, text)]);
    engine
        .completion(&u, p)
        .into_iter()
        .map(|i| i.label)
        .collect()
}

fn hover(files: &[(&str, &str)]) -> String {
    let (engine, u, p) = setup(files);
    let h = engine.hover(&u, p).expect("something to hover");
    let tower_lsp_server::ls_types::HoverContents::Markup(m) = h.contents else {
        panic!("hovers are markdown")
    };
    let r = h.range.expect("hovers name their range");
    format!(
        "range {}:{}-{}:{}\n{}",
        r.start.line, r.start.character, r.end.line, r.end.character, m.value
    )
}

#[test]
fn turn_offers_directions_settings_and_positions() {
    let text = "door = sensor(scanner,door)\nn = 3\nm = goahead(1)\nwait(door)\nt = turn($0";
    assert_eq!(
        labels(text),
        ["left", "right", "c=", "d=", "m", "door"],
        "`m` is a movement, whose end pose is a position, bound nearer than `door`; `t` \
         is bound only by this line"
    );
}

#[test]
fn followwall_offers_its_sides() {
    assert_eq!(labels("followwall($0"), ["left", "middle", "right"]);
}

#[test]
fn sensor_offers_sensors_then_objects_and_keywords() {
    insta::assert_snapshot!(completions("s = sensor($0"));
    assert_eq!(
        labels("s = sensor(scanner,$0"),
        ["forever", "left", "right", "box", "charger", "door"]
    );
}

#[test]
fn statements_offer_commands_with_snippets_skills_and_blocks() {
    let (engine, u, p) = setup(&[(TASK, "käännös = 1\n$0"), (SKILLS, "TURN1:\nspeed(-0.4)\n")]);
    let out = render_items(&engine.completion(&u, p));
    insta::assert_snapshot!(out);
}

#[test]
fn a_half_typed_line_keeps_the_rest_of_the_file() {
    let text = "ovi_ö = sensor(scanner,door)\nwait(ovi_ö)\ngotoxy($0\nspeed(0.3)\n";
    let got = labels(text);
    assert_eq!(got[0], "ovi_ö", "the position variable first: {got:?}");
    assert!(
        got.contains(&"max_speed".to_string()),
        "and for `gotoxy(x,y)`, numbers"
    );
    let (engine, u, _) = setup(&[(TASK, text)]);
    let codes: Vec<String> = engine
        .diagnostics(&u)
        .into_iter()
        .map(|d| {
            let code = match d.code {
                Some(tower_lsp_server::ls_types::NumberOrString::String(c)) => c,
                other => panic!("codes are strings: {other:?}"),
            };
            let r = d.range;
            format!(
                "{code} {}:{}-{}:{} {}",
                r.start.line,
                r.start.character,
                r.end.line,
                r.end.character,
                d.message.lines().next().unwrap_or("")
            )
        })
        .collect();
    insta::assert_snapshot!(codes.join("\n"));
}

#[test]
fn conditions_offer_variables_and_model_constants() {
    let got = labels("b = sensor(battery)\nif(b < $0");
    assert!(got.contains(&"b".to_string()), "{got:?}");
    assert!(got.contains(&"LowBattery".to_string()), "{got:?}");
    assert!(!got.contains(&"goahead".to_string()), "{got:?}");
    // Variables are filtered by what is typed (there may be thousands); the model's
    // names are few and left to the editor's filter.
    let got = labels("b = sensor(battery)\nlow = 1\nif(b < Lo$0");
    assert!(got.contains(&"low".to_string()), "{got:?}");
    assert!(!got.contains(&"b".to_string()), "{got:?}");
    assert!(got.contains(&"LowBattery".to_string()), "{got:?}");
}

fn variable_labels(list: &tower_lsp_server::ls_types::CompletionList) -> Vec<&str> {
    list.items
        .iter()
        .filter(|i| i.kind == Some(tower_lsp_server::ls_types::CompletionItemKind::VARIABLE))
        .map(|i| i.label.as_str())
        .collect()
}

/// A task that binds more variables than one list holds: the list is marked
/// incomplete, holds the nearest ones above the cursor first, and narrows to what is
/// typed, names that begin with it before names that contain it.
#[test]
fn a_long_list_of_variables_is_capped_ranked_and_incomplete() {
    let count = ilmr_lsp::completion::MAX_VARIABLE_ITEMS * 3;
    let mut text: String = (0..count).map(|i| format!("v{i} = {i}\n")).collect();
    text.push_str("x_v7 = 1\ngoahead($0");
    let (engine, u, p) = setup(&[(TASK, &text)]);
    let list = engine.completion_list(&u, p);
    assert!(list.is_incomplete);
    let vars = variable_labels(&list);
    assert_eq!(vars.len(), ilmr_lsp::completion::MAX_VARIABLE_ITEMS);
    assert_eq!(
        &vars[..3],
        [
            "x_v7",
            &format!("v{}", count - 1),
            &format!("v{}", count - 2)
        ]
    );
    let text = text.replace("goahead($0", "goahead(v7$0");
    let (engine, u, p) = setup(&[(TASK, &text)]);
    let list = engine.completion_list(&u, p);
    let vars = variable_labels(&list);
    // v7 and v70..v79 begin with it, the nearest (v79) first; x_v7 only contains it.
    assert!(!list.is_incomplete, "{}", vars.len());
    assert_eq!(vars.len(), 12, "{vars:?}");
    assert_eq!((vars[0], vars[10], vars[11]), ("v79", "v7", "x_v7"));
}

#[test]
fn skills_see_every_variable_of_the_program() {
    let (engine, u, p) = setup(&[
        (TASK, "target = sensor(scanner,door)\nwait(target)\nGO\n"),
        (SKILLS, "GO:\ngotoxy($0\n"),
    ]);
    let got: Vec<String> = engine
        .completion(&u, p)
        .into_iter()
        .map(|i| i.label)
        .collect();
    assert_eq!(got[0], "target", "{got:?}");
}

#[test]
fn hover_on_a_command_shows_grammar_units_and_the_robots_ranges() {
    insta::assert_snapshot!(hover(&[(TASK, "spe$0ed(0.3)\n")]));
}

#[test]
fn hover_on_a_variable_shows_its_kind_and_binding() {
    insta::assert_snapshot!(hover(&[(TASK, "käännös = turn(left)\nwait(kää$0nnös)\n")]));
}

#[test]
fn hover_on_a_model_name_shows_robo_ini() {
    insta::assert_snapshot!(hover(&[(TASK, "b = sensor(batt$0ery)\nwait(b)\n")]));
    insta::assert_snapshot!(hover(&[(TASK, "speed(max_sp$0eed)\n")]));
}

#[test]
fn hover_on_a_skill_shows_its_definition() {
    insta::assert_snapshot!(hover(&[
        (TASK, "TUR$0N1\n"),
        (
            SKILLS,
            "TURN1:\nspeed(-0.4)\nt1=turn(d=90,c=0.25)\nwait(t1)\n"
        ),
    ]));
}

#[test]
fn hover_on_a_keyword_shows_its_parameter() {
    insta::assert_snapshot!(hover(&[(TASK, "followwall(mid$0dle)\n")]));
}

#[test]
fn definition_and_references_cross_files() {
    let (engine, u, p) = setup(&[
        (TASK, "TURN1\nwait(t$01)\n"),
        (
            SKILLS,
            "TURN1:\nspeed(-0.4)\nt1=turn(d=90,c=0.25)\nwait(t1)\n",
        ),
    ]);
    let show = |locs: Vec<tower_lsp_server::ls_types::Location>| {
        locs.iter()
            .map(|l| {
                format!(
                    "{} {}:{}-{}",
                    l.uri.as_str().rsplit('/').next().unwrap_or(""),
                    l.range.start.line,
                    l.range.start.character,
                    l.range.end.character
                )
            })
            .collect::<Vec<_>>()
    };
    assert_eq!(show(engine.definition(&u, p)), ["skills.ilms 2:0-2"]);
    assert_eq!(
        show(engine.references(&u, p, true)),
        ["skills.ilms 2:0-2", "skills.ilms 3:5-7", "task.ilmr 1:5-7"]
    );
    assert_eq!(
        show(engine.references(&u, p, false)),
        ["skills.ilms 3:5-7", "task.ilmr 1:5-7"]
    );
    let skill = Position::new(0, 2);
    assert_eq!(show(engine.definition(&u, skill)), ["skills.ilms 0:0-5"]);
}

#[test]
fn rename_changes_every_spelling_and_refuses_taken_names() {
    let (engine, u, p) = setup(&[(
        TASK,
        "Käännös = 0\nkäännös = KÄÄNNÖS + 1$0\nif(käännös > 2)\nendif\n",
    )]);
    let at = Position::new(0, 2);
    let edit = engine.rename(&u, at, "kierros").expect("renames");
    let edits = &edit.changes.expect("edits by file")[&u];
    assert_eq!(edits.len(), 4);
    assert!(edits.iter().all(|e| e.new_text == "kierros"));
    assert_eq!(
        engine.rename(&u, at, "speed").unwrap_err().to_string(),
        "`speed` is a command"
    );
    assert_eq!(
        engine.rename(&u, at, "max_speed").unwrap_err().to_string(),
        "`max_speed` is a constant of robot `moro`"
    );
    assert!(engine.rename(&u, at, "2x").is_err());
    assert!(
        engine.prepare_rename(&u, p).is_none(),
        "a number is not renamed"
    );
}

#[test]
fn code_actions_apply_the_checkers_fixes() {
    let (engine, u, _) = setup(&[(TASK, "followwall(lft)\nif(1)\n    stop\n$0")]);
    let whole = tower_lsp_server::ls_types::Range::new(Position::new(0, 0), Position::new(9, 0));
    let actions: Vec<String> = engine
        .code_actions(&u, whole)
        .into_iter()
        .map(|a| match a {
            tower_lsp_server::ls_types::CodeActionOrCommand::CodeAction(a) => {
                let edits = &a.edit.expect("fixes edit").changes.expect("by file")[&u];
                format!(
                    "{} -> {:?} at {}:{}",
                    a.title,
                    edits[0].new_text,
                    edits[0].range.start.line,
                    edits[0].range.start.character
                )
            }
            other => panic!("{other:?}"),
        })
        .collect();
    insta::assert_snapshot!(actions.join("\n"));
}

#[test]
fn formatting_is_ilmrc_fmt() {
    let (engine, u, _) = setup(&[(TASK, "T=Turn(LEFT)\nIf(t)\nStop\nEndIf\n$0")]);
    let edits = engine.formatting(&u).expect("formats");
    assert_eq!(edits.len(), 1);
    assert_eq!(
        edits[0].new_text,
        "T = turn(left)\nif(T)\n    stop\nendif\n"
    );
    let (engine, u, _) = setup(&[(TASK, "goahead(1\n$0")]);
    assert_eq!(engine.formatting(&u), None, "syntax errors stop formatting");
}

#[test]
fn outline_and_folding_follow_the_blocks() {
    let text = "// one\n// two\nwhile(1)\n    if(1)\n        stop\n    endif\nendwhile\n$0";
    let (engine, u, _) = setup(&[(TASK, text)]);
    let symbols = engine.document_symbols(&u);
    assert_eq!(symbols.len(), 1);
    assert_eq!(symbols[0].name, "while(1)");
    let children = symbols[0].children.as_ref().expect("the if is nested");
    assert_eq!(children[0].name, "if(1)");
    let folds: Vec<(u32, u32)> = engine
        .folding_ranges(&u)
        .iter()
        .map(|f| (f.start_line, f.end_line))
        .collect();
    assert_eq!(folds, [(0, 1), (2, 5), (3, 4)]);
}

#[test]
fn partial_edits_recheck_the_program() {
    let (mut engine, u, _) = setup(&[(TASK, "followwall(lft)\n$0")]);
    assert_eq!(engine.diagnostics(&u).len(), 1);
    let fix = TextDocumentContentChangeEvent {
        range: Some(tower_lsp_server::ls_types::Range::new(
            Position::new(0, 11),
            Position::new(0, 14),
        )),
        range_length: None,
        text: "left".into(),
    };
    let published = engine.change(&u, 2, vec![fix]);
    assert_eq!(published.len(), 1);
    assert_eq!(published[0].version, Some(2));
    assert!(published[0].diagnostics.is_empty());
}

#[test]
fn semantic_tokens_tell_names_apart() {
    let (engine, u, _) = setup(&[(
        TASK,
        "ovi_ö = sensor(scanner,door) // find\nif(ovi_ö)\nendif\n$0",
    )]);
    let tokens = engine.semantic_tokens(&u);
    let kinds: Vec<(u32, u32, u32, u32)> = tokens
        .iter()
        .map(|t| (t.delta_line, t.delta_start, t.length, t.token_type))
        .collect();
    // variable, `=`, command, model name, model name, comment; `if`, variable; `endif`.
    assert_eq!(
        kinds,
        [
            (0, 0, 5, 3),
            (0, 6, 1, 9),
            (0, 2, 6, 1),
            (0, 7, 7, 5),
            (0, 8, 4, 5),
            (0, 6, 7, 8),
            (1, 0, 2, 0),
            (0, 3, 5, 3),
            (1, 0, 5, 0),
        ]
    );
    // The second line alone, as an editor asks for the lines it shows: the same
    // tokens, the first still counted from the file's start.
    let second = Range::new(Position::new(1, 0), Position::new(2, 0));
    let shown: Vec<(u32, u32, u32, u32)> = engine
        .semantic_tokens_in(&u, second)
        .iter()
        .map(|t| (t.delta_line, t.delta_start, t.length, t.token_type))
        .collect();
    assert_eq!(shown, [(1, 0, 2, 0), (0, 3, 5, 3)]);
}

/// The compiler's analysis, but for a program holding `CHECKER_BUG`, where it fails as a
/// bug in the checker would.
fn fragile<'s>(
    sources: &'s [ilmr_compiler::check::Source],
    model: &ilmr_model::RobotModel,
) -> ilmr_compiler::check::Analysis<'s> {
    if sources.iter().any(|s| s.text.contains(CHECKER_BUG)) {
        panic!("a bug in the checker");
    }
    if sources.iter().any(|s| s.text.contains(HALF_A_BUG))
        && sources.iter().any(|s| s.text.contains(OTHER_HALF))
    {
        panic!("a bug between two files");
    }
    ilmr_compiler::check::analyze(sources, model)
}

const CHECKER_BUG: &str = "// the checker fails here";
const HALF_A_BUG: &str = "// fails with the other half";
const OTHER_HALF: &str = "// the other half";

fn codes(engine: &Engine, u: &Uri) -> Vec<String> {
    engine
        .diagnostics(u)
        .iter()
        .map(|d| match &d.code {
            Some(tower_lsp_server::ls_types::NumberOrString::String(c)) => c.clone(),
            other => format!("{other:?}"),
        })
        .collect()
}

#[test]
fn a_panic_in_the_analysis_costs_its_file_only() {
    let mut engine = Engine::with_analyzer(
        Vec::new(),
        Settings {
            robot: Some("moro".into()),
            snippets: false,
            ilmrc: None,
        },
        fragile,
    );
    let good = uri(TASK);
    let bad = uri(SKILLS);
    engine.open(good.clone(), 1, "followwall(lft)\n".into());
    let published = engine.open(bad.clone(), 1, format!("TURNS:\n{CHECKER_BUG}\nwait(1)\n"));
    assert_eq!(
        codes(&engine, &good),
        ["E0304"],
        "the good file is still checked"
    );
    assert_eq!(
        codes(&engine, &bad),
        [ilmr_lsp::diagnostics::ANALYSIS_FAILED]
    );
    let failed = engine.diagnostics(&bad).remove(0);
    assert_eq!(
        failed.message,
        ilmr_lsp::diagnostics::ANALYSIS_FAILED_MESSAGE
    );
    assert!(
        published
            .iter()
            .any(|p| p.uri == bad && p.diagnostics == [failed.clone()])
    );
    let log = engine.take_log();
    assert_eq!(log.len(), 1, "{log:?}");
    assert!(
        log[0].contains(SKILLS) && log[0].contains("a bug in the checker"),
        "{log:?}"
    );

    // Every feature answers on the file the analysis failed on.
    let at = Position::new(1, 3);
    assert!(engine.completion(&bad, at).is_empty());
    assert!(engine.hover(&bad, at).is_none());
    assert!(engine.document_symbols(&bad).is_empty());
    assert!(engine.semantic_tokens(&bad).is_empty());
    assert!(engine.definition(&bad, at).is_empty());

    // Fixed, the file is checked again and the log stays quiet.
    let change = TextDocumentContentChangeEvent {
        range: None,
        range_length: None,
        text: "TURNS:\nwait(1)\n".into(),
    };
    engine.change(&bad, 2, vec![change]);
    assert_eq!(codes(&engine, &bad), Vec::<String>::new());
    assert!(engine.take_log().is_empty());
}

#[test]
fn a_panic_no_single_file_causes_costs_every_file() {
    let mut engine = Engine::with_analyzer(Vec::new(), Settings::default(), fragile);
    let (a, b, c) = (
        uri("file:///ws/a.ilmr"),
        uri("file:///ws/b.ilms"),
        uri("file:///ws/c.ilms"),
    );
    engine.open(a.clone(), 1, format!("{HALF_A_BUG}\nwait(1)\n"));
    engine.open(c.clone(), 1, "C:\nwait(1)\n".into());
    assert_eq!(codes(&engine, &a), Vec::<String>::new());
    engine.open(b.clone(), 1, format!("B:\n{OTHER_HALF}\nwait(1)\n"));
    for u in [&a, &b, &c] {
        assert_eq!(
            codes(&engine, u),
            [ilmr_lsp::diagnostics::ANALYSIS_FAILED],
            "{u:?}"
        );
    }
    assert_eq!(engine.take_log().len(), 3);
}

#[test]
fn a_document_larger_than_ilmrc_reads_is_not_analysed() {
    let (mut engine, good, _) = setup(&[(TASK, "followwall(lft)\n$0")]);
    let big = uri("file:///ws/big.ilmr");
    let text = "wait(1)\n".repeat(ilmr_files::MAX_SOURCE_BYTES as usize / 8 + 1);
    engine.open(big.clone(), 1, text);
    assert_eq!(codes(&engine, &big), [ilmr_lsp::diagnostics::TOO_LARGE]);
    let message = engine.diagnostics(&big).remove(0).message;
    assert!(message.contains("MAX_SOURCE_BYTES"), "{message}");
    assert_eq!(
        codes(&engine, &good),
        ["E0304"],
        "the other files are checked"
    );
    assert!(engine.semantic_tokens(&big).is_empty());
}

const CORNER: &str =
    "Corner(d, side=left/right):\nspeed(0.3)\nm = goahead(d)\nwait(m)\nturn(side)\n";

#[test]
fn a_skill_with_parameters_is_offered_with_a_snippet_of_them() {
    let (engine, u, p) = setup(&[(TASK, "Cor$0\n"), (SKILLS, CORNER)]);
    let items = engine.completion(&u, p);
    let corner = items
        .iter()
        .find(|i| i.label == "Corner")
        .expect("the skill is offered");
    let Some(CompletionTextEdit::Edit(edit)) = &corner.text_edit else {
        panic!("an edit")
    };
    assert_eq!(edit.new_text, "Corner(${1:d}, ${2|left,right|})");
    assert!(
        corner
            .detail
            .as_deref()
            .unwrap()
            .starts_with("Corner(d, side=left/right), skill in skills.ilms"),
        "{:?}",
        corner.detail
    );
}

#[test]
fn a_skill_argument_offers_what_its_parameter_takes() {
    let (engine, u, p) = setup(&[(TASK, "Corner(1.5, $0\n"), (SKILLS, CORNER)]);
    let words: Vec<String> = engine
        .completion(&u, p)
        .into_iter()
        .map(|i| i.label)
        .collect();
    assert_eq!(words, ["left", "right"]);
    let (engine, u, p) = setup(&[(TASK, "n = 2\nCorner($0\n"), (SKILLS, CORNER)]);
    let numbers: Vec<String> = engine
        .completion(&u, p)
        .into_iter()
        .map(|i| i.label)
        .collect();
    assert!(numbers.contains(&"n".to_string()), "{numbers:?}");
    assert!(!numbers.contains(&"left".to_string()), "{numbers:?}");
}

#[test]
fn hover_on_a_call_of_a_skill_with_parameters_names_them_and_what_it_runs() {
    let text = hover(&[(TASK, "Cor$0ner(1.5, left)\n"), (SKILLS, CORNER)]);
    assert!(
        text.contains(
            "Parameters, given in this order: `d`: a number; `side`: one of `left`, `right`."
        ),
        "{text}"
    );
    assert!(text.contains("This call runs `Corner(1.5,left)`"), "{text}");
}

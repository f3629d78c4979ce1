//! The concurrency lens and its neighbours: inlay hints (when each statement starts,
//! what ends it, units, the last run's times), the hover of `break(pattern)`, the run
//! lens, workspace symbols and document highlights. Hints are snapshotted inline in the
//! text they annotate, `[unit]` after a value and `⟨label⟩` at a line's end.

use ilmr_lsp::run::{LastRun, fingerprint, times};
use ilmr_lsp::{Engine, Settings};
use tower_lsp_server::ls_types::{
    DocumentHighlightKind, HoverContents, InlayHint, InlayHintKind, InlayHintLabel, Position,
    Range, Uri,
};

const TASK: &str = "file:///ws/task.ilmr";
const SKILLS: &str = "file:///ws/skills.ilms";

fn uri(s: &str) -> Uri {
    s.parse().expect("test URIs parse")
}

fn engine(files: &[(&str, &str)]) -> Engine {
    let mut engine = Engine::new(
        Vec::new(),
        Settings {
            robot: Some("moro".into()),
            snippets: false,
            ilmrc: None,
        },
    );
    for (name, text) in files {
        engine.open(uri(name), 1, text.to_string());
    }
    engine
}

fn whole() -> Range {
    Range::new(Position::new(0, 0), Position::new(u32::MAX, 0))
}

fn label(h: &InlayHint) -> &str {
    match &h.label {
        InlayHintLabel::String(s) => s,
        InlayHintLabel::LabelParts(_) => panic!("hints are plain strings"),
    }
}

/// The text with its hints written in (positions are ASCII columns in these fixtures).
fn annotated(text: &str, hints: &[InlayHint]) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let mut by_place: Vec<(usize, &InlayHint)> = hints.iter().enumerate().collect();
    // Right to left, and the last of one place first, so that each insertion keeps
    // the columns and the order of those before it.
    by_place.sort_by_key(|(i, h)| {
        (
            h.position.line,
            std::cmp::Reverse((h.position.character, *i)),
        )
    });
    for (_, h) in by_place {
        let line = &mut lines[h.position.line as usize];
        let at = h.position.character as usize;
        let shown = match h.kind {
            Some(InlayHintKind::TYPE) => format!(" [{}]", label(h)),
            _ => format!("  ⟨{}⟩", label(h)),
        };
        line.insert_str(at, &shown);
    }
    lines.join("\n")
}

fn hints(files: &[(&str, &str)]) -> String {
    let engine = engine(files);
    annotated(files[0].1, &engine.inlay_hints(&uri(files[0].0), whole()))
}

const FIGURE: &str = "\
m = goahead(2)
turn(d=90,c=0.5)
wait(m)
speed(0.4)
gotoxy(1,1)

d = sensor(battery)
if(d < 10)
stop
endif

n = 0
w = while(n < 3)
n = n + 1
wait(1.5)
endwhile

break(while(n)
";

#[test]
fn every_statement_says_when_it_starts_and_what_ends_it() {
    insta::assert_snapshot!(hints(&[(TASK, FIGURE)]));
}

const ENDERS: &str = "\
followwall(left)

d = sensor(battery)
if(d < 10)
priority = highest
speed(0)
endif

wait(30)
break
";

#[test]
fn a_bare_break_ends_everything_and_a_priority_block_what_stands_outside_it() {
    insta::assert_snapshot!(hints(&[(TASK, ENDERS)]));
}

const MANY_ENDERS: &str = "\
w = while(1 < 2)
goahead(1)
endwhile

break(goahead)

break(while)

break(goahead(1)

break(w)

priority = highest
speed(0)

priority = highest
speed(0.1)

priority = highest
speed(0.2)

priority = highest
speed(0.3)
";

#[test]
fn a_statement_names_three_breaks_and_three_priority_blocks_and_counts_the_rest() {
    // `goahead(1)` is ended by four pattern breaks, two of them through its loop, and
    // by four priority blocks.
    insta::assert_snapshot!(hints(&[(TASK, MANY_ENDERS)]));
}

#[test]
fn a_priority_block_ends_only_its_own_units_statements_and_breaks_in_check_end_nothing() {
    let task = "Patrol\nfollowwall(left)\n\ncheck\nbreak\ncheckend\n";
    let skills = "Patrol:\ngoahead()\n\npriority = highest\nspeed(0)\n";
    insta::assert_snapshot!(hints(&[(TASK, task), (SKILLS, skills)]));
    insta::assert_snapshot!(hints(&[(SKILLS, skills), (TASK, task)]));
}

#[test]
fn a_skills_statements_start_when_it_is_called_and_a_holding_call_holds() {
    let task = "Takeoff\ngoahead(1)\n";
    let skills = "Takeoff:\ninit()\nspeed(0.3)\n";
    insta::assert_snapshot!(hints(&[(TASK, task), (SKILLS, skills)]));
    insta::assert_snapshot!(hints(&[(SKILLS, skills), (TASK, task)]));
}

#[test]
fn only_the_range_asked_is_labelled() {
    let engine = engine(&[(TASK, FIGURE)]);
    // Lines 7-9 (0-based 6..=8): the second block's sensor, guard and its body.
    let range = Range::new(Position::new(6, 0), Position::new(8, 4));
    let got: Vec<u32> = engine
        .inlay_hints(&uri(TASK), range)
        .iter()
        .map(|h| h.position.line)
        .collect();
    assert_eq!(got, vec![6, 8], "a hint on `d = sensor`, one on `stop`");
    let all = engine.inlay_hints(&uri(TASK), whole());
    assert!(all.len() > got.len());
}

#[test]
fn units_come_from_the_catalogue_and_keywords_have_none() {
    let text = "speed(0.4)\nturn(left)\nturn(d=90,c=0.5)\nbodypose(r=10)\ngoahead(2)\n";
    let engine = engine(&[(TASK, text)]);
    let units: Vec<String> = engine
        .inlay_hints(&uri(TASK), whole())
        .iter()
        .filter(|h| h.kind == Some(InlayHintKind::TYPE))
        .map(|h| {
            format!(
                "{}:{} {}",
                h.position.line + 1,
                h.position.character,
                label(h)
            )
        })
        .collect();
    let want = |command: ilmr_stdlib::Command, param: &str| {
        let spec = command.spec();
        let p = spec
            .forms
            .iter()
            .flat_map(|f| f.params)
            .find(|p| p.name == param)
            .unwrap();
        match p.kind {
            ilmr_stdlib::ParamKind::Value { unit, .. }
            | ilmr_stdlib::ParamKind::Setting { unit, .. } => unit.symbol(),
            _ => panic!("{param} has a unit"),
        }
    };
    assert_eq!(
        units,
        vec![
            format!("1:9 {}", want(ilmr_stdlib::Command::Speed, "value")),
            format!("3:9 {}", want(ilmr_stdlib::Command::Turn, "d")),
            format!("3:15 {}", want(ilmr_stdlib::Command::Turn, "c")),
            format!("4:13 {}", want(ilmr_stdlib::Command::BodyPose, "r")),
            format!("5:9 {}", want(ilmr_stdlib::Command::Goahead, "distance")),
        ]
    );
    assert_eq!(units[0], "1:9 m/s");
}

#[test]
fn hover_on_a_pattern_break_lists_what_it_ends() {
    let text = "\
c = 0
while(c < 5)
c = c + 1
goahead(1)
endwhile

followwall(left,1)
break(while(c)
";
    let engine = engine(&[(TASK, text)]);
    let hover = engine
        .hover(&uri(TASK), Position::new(7, 8))
        .expect("a hover on the pattern");
    let HoverContents::Markup(m) = hover.contents else {
        panic!("markdown")
    };
    let list = &m.value[m.value.find("---").expect("a list after the command's doc")..];
    insta::assert_snapshot!(list);
    // A pattern nothing contains ends nothing, and says so.
    let engine = self::engine(&[(TASK, "goahead(1)\nbreak(followw)\n")]);
    let hover = engine.hover(&uri(TASK), Position::new(1, 8)).unwrap();
    let HoverContents::Markup(m) = hover.contents else {
        panic!("markdown")
    };
    assert!(
        m.value
            .contains("Ends nothing: no statement contains `followw`"),
        "{}",
        m.value
    );
}

#[test]
fn the_run_lens_is_on_task_files_and_the_last_runs_times_are_hints() {
    let text = "goahead(1)\nturn(left)\n";
    let mut engine = engine(&[(TASK, text), (SKILLS, "Taito:\nspeed(0.3)\n")]);
    let lenses = engine.code_lenses(&uri(TASK));
    assert_eq!(lenses.len(), 1);
    let command = lenses[0].command.as_ref().unwrap();
    assert_eq!(command.command, ilmr_lsp::run::RUN_COMMAND);
    assert_eq!(command.title, "▶ run in simulator");
    assert_eq!(
        command.arguments.as_ref().unwrap()[0],
        serde_json::json!(TASK)
    );
    assert!(
        engine.code_lenses(&uri(SKILLS)).is_empty(),
        "skills do not run alone"
    );

    let trace = "\
{\"t\":0,\"event\":\"trace\",\"version\":1}
{\"t\":0,\"event\":\"issue\",\"line\":1,\"text\":\"goahead(1)\"}
{\"t\":0,\"event\":\"issue\",\"line\":2,\"text\":\"turn(left)\"}
{\"t\":2.5,\"event\":\"end\",\"line\":1,\"text\":\"goahead(1)\",\"how\":\"completed\"}
{\"t\":2.5,\"event\":\"start\",\"line\":2,\"text\":\"turn(left)\"}
{\"t\":9.1,\"event\":\"end\",\"line\":2,\"text\":\"turn(left)\",\"how\":\"completed\"}
";
    engine.set_run(
        &uri(TASK),
        LastRun {
            text: fingerprint(text),
            summary: "task.ilmr: finished: no command left\n  exit 0".into(),
            exit: Some(0),
            times: times(trace, text).unwrap(),
        },
    );
    insta::assert_snapshot!(annotated(text, &engine.inlay_hints(&uri(TASK), whole())));
    let title = &engine.code_lenses(&uri(TASK))[0]
        .command
        .clone()
        .unwrap()
        .title;
    assert_eq!(
        title,
        "▶ run in simulator · last run: task.ilmr: finished: no command left"
    );

    // Once the text changes the times no longer fit it: they go, the lens says so.
    engine.open(uri(TASK), 2, format!("{text}stop\n"));
    let hints = engine.inlay_hints(&uri(TASK), whole());
    assert!(
        hints.iter().all(|h| !label(h).starts_with("ran ")),
        "{hints:?}"
    );
    let title = &engine.code_lenses(&uri(TASK))[0]
        .command
        .clone()
        .unwrap()
        .title;
    assert!(title.ends_with("(an earlier text)"), "{title}");
}

#[test]
fn workspace_symbols_find_skills_variables_and_paths_by_a_fuzzy_query() {
    let task = "record(Reitti)\nkäännös = turn(left)\nwait(käännös)\nrecord(close)\nfollowpath(Reitti)\nTaito\n";
    let engine = engine(&[(TASK, task), (SKILLS, "Taito:\nspeed(0.3)\n")]);
    let render = |query: &str| -> Vec<String> {
        engine
            .workspace_symbols(query)
            .iter()
            .map(|s| {
                format!(
                    "{} {:?} {} {}:{}",
                    s.name,
                    s.kind,
                    s.container_name.as_deref().unwrap_or(""),
                    s.location.uri.as_str().rsplit('/').next().unwrap(),
                    s.location.range.start.line + 1
                )
            })
            .collect()
    };
    assert_eq!(
        render(""),
        vec![
            "Taito Function skill skills.ilms:1",
            "käännös Variable variable task.ilmr:2",
            "Reitti Key path task.ilmr:1",
        ]
    );
    assert_eq!(render("KNS"), vec!["käännös Variable variable task.ilmr:2"]);
    assert_eq!(
        render("tt"),
        vec![
            "Taito Function skill skills.ilms:1",
            "Reitti Key path task.ilmr:1"
        ]
    );
    assert!(render("zz").is_empty());
}

#[test]
fn a_long_workspace_is_answered_a_capped_list() {
    let task: String = (0..2 * ilmr_lsp::symbols::MAX_WORKSPACE_SYMBOLS)
        .map(|i| format!("v{i} = {i}\n"))
        .collect();
    let engine = engine(&[(TASK, &task)]);
    assert_eq!(
        engine.workspace_symbols("v").len(),
        ilmr_lsp::symbols::MAX_WORKSPACE_SYMBOLS
    );
}

#[test]
fn highlights_tell_bindings_from_uses_in_one_document() {
    let task = "t = turn(left)\nwait(t)\nif(t == 1)\nstop\nendif\nt = goahead(1)\n";
    let engine = engine(&[(TASK, task), (SKILLS, "Taito:\nwait(t)\n")]);
    let got: Vec<(u32, u32, bool)> = engine
        .document_highlights(&uri(TASK), Position::new(1, 5))
        .iter()
        .map(|h| {
            (
                h.range.start.line + 1,
                h.range.start.character,
                h.kind == Some(DocumentHighlightKind::WRITE),
            )
        })
        .collect();
    // Only this document's: the skill's `wait(t)` is a reference, not a highlight here.
    assert_eq!(
        got,
        vec![(1, 0, true), (2, 5, false), (3, 3, false), (6, 0, true)]
    );
    assert!(
        engine
            .document_highlights(&uri(TASK), Position::new(3, 1))
            .is_empty()
    );
}

//! The corpus of broken programs: every diagnostic code fires at least once, and each
//! file's rendered and JSON output are snapshots.

mod support;

use std::collections::BTreeSet;

use ilmr_compiler::Code;
use ilmr_compiler::check::{Source, analyze};
use ilmr_compiler::limits::MAX_DIAGNOSTICS;
use ilmr_compiler::render;
use support::*;

fn corpus() -> Vec<std::path::PathBuf> {
    let mut files: Vec<_> = std::fs::read_dir(root().join("tests/check/broken"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    files.sort();
    files
}

fn load(path: &std::path::Path) -> Vec<Source> {
    let text = std::fs::read_to_string(path).unwrap();
    let display = path.strip_prefix(root()).unwrap().display().to_string();
    vec![Source::new(display, text)]
}

#[test]
fn broken_programs_render_for_people_and_tools() {
    for path in corpus() {
        let sources = load(&path);
        let robot = intended_robot(&sources[0].text).to_string();
        let (analysis, _) = check(&sources, &robot);
        let name = path
            .file_name()
            .unwrap()
            .to_string_lossy()
            .replace('.', "_");
        insta::assert_snapshot!(format!("human_{name}"), human(&analysis));
        let json = render::json(&analysis.diagnostics, &render_files(&analysis));
        insta::assert_snapshot!(
            format!("json_{name}"),
            serde_json::to_string_pretty(&json).unwrap()
        );
    }
}

#[test]
fn every_code_is_exercised_by_the_corpus() {
    let mut seen = BTreeSet::new();
    for path in corpus() {
        let sources = load(&path);
        let robot = intended_robot(&sources[0].text).to_string();
        let (analysis, _) = check(&sources, &robot);
        seen.extend(analysis.diagnostics.iter().map(|d| d.code));
    }
    for sources in past_the_limit() {
        let (analysis, _) = check(&sources, "moro");
        seen.extend(analysis.diagnostics.iter().map(|d| d.code));
    }
    // The robot model's own warnings come from loading a model file, and unreadable
    // files are said by `ilmrc check` itself (tests/cli.rs).
    seen.insert(Code::RobotModel);
    seen.insert(Code::UnreadableFile);
    seen.insert(Code::NotUtf8);
    let missing: Vec<&str> = Code::ALL
        .iter()
        .filter(|c| !seen.contains(c))
        .map(|c| c.as_str())
        .collect();
    assert!(missing.is_empty(), "no corpus file produces {missing:?}");
}

#[test]
fn several_independent_mistakes_give_one_diagnostic_each() {
    let path = root().join("tests/check/broken/syntax.ilmr");
    let sources = load(&path);
    let (analysis, _) = check(&sources, "moro");
    let lines: BTreeSet<usize> = analysis
        .diagnostics
        .iter()
        .filter(|d| d.is_error())
        .map(|d| {
            ilmr_compiler::LineIndex::new(&sources[0].text)
                .line_col(&sources[0].text, d.span.start as usize)
                .0
        })
        .collect();
    let errors = analysis.diagnostics.iter().filter(|d| d.is_error()).count();
    assert_eq!(lines.len(), errors, "one error per broken line");
    assert_eq!(errors, 6);
    // The last line is still read and checked.
    assert!(
        analysis.files[0].tree.blocks[0]
            .stmts
            .iter()
            .any(|s| s.span.slice(&sources[0].text) == "goahead(1)")
    );
}

/// Programs with more problems than a program is given diagnostics: 1,500 unknown
/// commands, and 1,500 variables nothing reads. Generated rather than in the corpus,
/// whose snapshots would hold a thousand diagnostics each.
fn past_the_limit() -> [Vec<Source>; 2] {
    let over = MAX_DIAGNOSTICS + MAX_DIAGNOSTICS / 2;
    [
        vec![Source::new("errors.ilmr", "nosuchcommand\n".repeat(over))],
        vec![Source::new(
            "warnings.ilmr",
            (0..over)
                .map(|i| format!("v{i} = {i}\n"))
                .collect::<String>(),
        )],
    ]
}

#[test]
fn past_the_limit_the_first_diagnostics_are_kept_and_the_rest_counted() {
    let [errors, warnings] = past_the_limit();
    let over = MAX_DIAGNOSTICS / 2;

    let (analysis, _) = check(&errors, "moro");
    let (last, kept) = analysis.diagnostics.split_last().unwrap();
    assert_eq!(kept.len(), MAX_DIAGNOSTICS);
    assert!(kept.iter().all(|d| d.code == Code::UnknownCommand));
    // The first ones in source order: lines 1 to 1,000.
    let index = ilmr_compiler::LineIndex::new(&errors[0].text);
    let line =
        |d: &ilmr_compiler::Diagnostic| index.line_col(&errors[0].text, d.span.start as usize).0;
    assert_eq!(line(&kept[0]), 1);
    assert_eq!(line(&kept[MAX_DIAGNOSTICS - 1]), MAX_DIAGNOSTICS);
    assert_eq!(last.code, Code::TooManyErrors);
    assert_eq!(last.span.start, kept[MAX_DIAGNOSTICS - 1].span.start);
    assert!(
        last.message.starts_with(&format!("{over} more problems")),
        "{}",
        last.message
    );

    // Only warnings past the limit: the program is not refused for them.
    let (analysis, m) = check(&warnings, "moro");
    assert_eq!(analysis.diagnostics.len(), MAX_DIAGNOSTICS + 1);
    let last = analysis.diagnostics.last().unwrap();
    assert_eq!(last.code, Code::TooManyWarnings);
    assert!(!analysis.has_errors());
    assert!(ilmr_compiler::lower::lower(&analysis, &m, ilmr_compiler::FileId(0)).is_ok());
}

#[test]
fn diagnostics_reference_is_fresh() {
    let path = root().join("docs/diagnostics.md");
    let expected = ilmr_compiler::diagnostic::reference_markdown();
    if std::env::var_os("UPDATE_DOCS").is_some() {
        std::fs::write(&path, &expected).unwrap();
    }
    let actual = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        actual == expected,
        "docs/diagnostics.md is stale: run `UPDATE_DOCS=1 cargo test --test diagnostics`"
    );
}

#[test]
fn checking_an_empty_program_is_clean() {
    let sources = vec![Source::new("empty.ilmr", "")];
    let m = model("moro");
    assert!(analyze(&sources, &m).diagnostics.is_empty());
}

/// A scratch directory of this test binary, emptied first and removed when the test
/// is done with it (its traces take some 60 MB).
struct Scratch(std::path::PathBuf);

impl std::ops::Deref for Scratch {
    type Target = std::path::Path;
    fn deref(&self) -> &std::path::Path {
        &self.0
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn scratch(name: &str) -> Scratch {
    let dir = std::env::temp_dir().join(format!("ilmr-diagnostics-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    Scratch(dir)
}

/// The trace of `task` run for `max_time` seconds on a simulated Workpartner in the
/// empty world.
fn traced(dir: &std::path::Path, name: &str, task: &str, max_time: &str) -> String {
    traced_with(dir, name, task, "", max_time)
}

/// `traced`, with a skill file beside the task when `skills` is not empty.
fn traced_with(
    dir: &std::path::Path,
    name: &str,
    task: &str,
    skills: &str,
    max_time: &str,
) -> String {
    let path = dir.join(format!("{name}.ilmr"));
    let trace = dir.join(format!("{name}.jsonl"));
    let library = dir.join(format!("{name}.ilms"));
    std::fs::write(&path, task).unwrap();
    let mut args = vec![
        "run".to_string(),
        "--robot".into(),
        "workpartner".into(),
        "--world".into(),
        "empty".into(),
        "--max-time".into(),
        max_time.into(),
        "--trace".into(),
        trace.to_str().unwrap().into(),
    ];
    if !skills.is_empty() {
        std::fs::write(&library, skills).unwrap();
        args.extend(["--skills".into(), library.to_str().unwrap().into()]);
    }
    args.push(path.to_str().unwrap().into());
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let (code, out, err) = ilmrc(&args);
    assert!(code == 0 || code == 5, "{task}\n{out}{err}");
    std::fs::read_to_string(&trace).unwrap()
}

/// The passes a `while` on line 2 made in the first tick that started it, from the
/// trace of `task` run on a simulated Workpartner in the empty world.
fn passes_in_first_tick(dir: &std::path::Path, name: &str, task: &str) -> u64 {
    let text = traced(dir, name, task, "0.03");
    let first = text
        .lines()
        .map(|l| serde_json::from_str::<serde_json::Value>(l).unwrap())
        .find(|e| e["event"] == "start" && e["line"] == 2)
        .unwrap_or_else(|| panic!("no start of the loop in\n{text}"));
    first["iteration"].as_u64().unwrap_or(1)
}

/// W0902 rests on the catalogue's `Ends::AtIssue`: every example of every command it
/// marks so, alone in a loop whose condition stays true, keeps the VM passing through
/// the loop until the first tick's budget is spent.
#[test]
fn commands_the_catalogue_says_end_at_issue_end_at_issue_in_the_vm() {
    use ilmr_stdlib::{CATALOGUE, Syntax};
    let dir = scratch("at_issue");
    let m = model("workpartner");
    let budget = u64::from(ilmr_vm::Config::default().budget_ops);
    for spec in CATALOGUE
        .iter()
        .filter(|s| s.syntax == Syntax::Call && s.ends.at_issue(std::iter::empty()))
    {
        let mut tried = 0;
        for (i, example) in spec.examples.iter().enumerate() {
            if !spec
                .ends
                .at_issue(example.split([',', '(', ')']).map(str::trim))
            {
                continue;
            }
            let task = format!("counter = 0\nwhile(1)\n{example}\nendwhile\n");
            let sources = vec![Source::new("t.ilmr", task.clone())];
            if analyze(&sources, &m).has_errors() {
                continue;
            }
            tried += 1;
            let passes = passes_in_first_tick(&dir, &format!("{}_{i}", spec.name), &task);
            assert!(
                passes > budget / 100,
                "`{example}` made {passes} passes in a tick: it does not end at issue"
            );
        }
        assert!(tried > 0, "no example of `{}` checks clean", spec.name);
    }
}

/// The passes a tick W0902 announces are the VM's, within a factor of two (the count
/// is a lower bound of each pass's operations).
#[test]
fn a_starving_loop_makes_about_the_passes_it_is_said_to() {
    let dir = scratch("passes");
    for (name, task) in [
        ("leg", "n = 5\nwhile(n > 1)\nactuator(leg1,90)\nendwhile\n"),
        (
            "arithmetic",
            "n = 5\nwhile(n * 2 > 1)\nk = n + 1\nspeed(0.1)\nendwhile\nm = k\n",
        ),
        ("empty", "n = 1\nwhile(n)\nendwhile\n"),
    ] {
        let sources = vec![Source::new("t.ilmr", task)];
        let analysis = analyze(&sources, &model("workpartner"));
        let d = analysis
            .diagnostics
            .iter()
            .find(|d| d.code == Code::StarvingLoop)
            .unwrap_or_else(|| panic!("no W0902 for {task}"));
        let said: u64 = d
            .label
            .split("up to ")
            .nth(1)
            .and_then(|rest| rest.split(' ').next())
            .map(|n| n.replace(',', "").parse().unwrap())
            .unwrap_or_else(|| panic!("{}", d.label));
        let passes = passes_in_first_tick(&dir, name, task);
        assert!(
            passes <= said && passes * 2 >= said,
            "{task}: said up to {said} passes a tick, the VM made {passes}"
        );
    }
}

/// W0902's reference text quotes the VM's budget and tick.
#[test]
fn the_starving_loop_reference_quotes_the_vm_budget() {
    let c = ilmr_vm::Config::default();
    let budget = c.budget_ops.to_string();
    let grouped = format!(
        "{},{}",
        &budget[..budget.len() - 3],
        &budget[budget.len() - 3..]
    );
    let doc = Code::StarvingLoop.doc();
    assert!(doc.contains(&format!("{grouped} operations")), "{doc}");
    assert!(
        doc.contains(&format!("every {} ms tick", c.period * 1000.0)),
        "{doc}"
    );
}

/// `approach(door)`: a model object that no variable above is named after is that
/// object (it was read as an unbound variable, E0501), and lowers; a variable of that
/// name bound above stays the variable.
#[test]
fn approach_takes_an_object_of_the_model() {
    let m = model("moro");
    for task in [
        "approach(door)\napproach(door,0.5)\n",
        "door = sensor(scanner,door)\nwait(door)\napproach(door)\n",
    ] {
        let sources = vec![Source::new("t.ilmr", task)];
        let analysis = analyze(&sources, &m);
        assert!(
            analysis.diagnostics.is_empty(),
            "{task}: {:?}",
            analysis.diagnostics
        );
        assert!(
            ilmr_compiler::lower::lower(&analysis, &m, ilmr_compiler::FileId(0)).is_ok(),
            "{task}"
        );
    }
    let sources = vec![Source::new("t.ilmr", "approach(dor)\n")];
    let analysis = analyze(&sources, &m);
    assert!(analysis.has_errors(), "an unknown name is still an error");
}

/// The time each of `lines` of `task` was first issued, from the trace of a run on a
/// simulated Workpartner in the empty world.
fn issued_at(
    dir: &std::path::Path,
    name: &str,
    task: &str,
    skills: &str,
    lines: &[u64],
) -> Vec<f64> {
    let text = traced_with(dir, name, task, skills, "20");
    let events: Vec<serde_json::Value> = text
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    lines
        .iter()
        .map(|line| {
            events
                .iter()
                // The task's own line: a skill's statements name their file.
                .find(|e| e["event"] == "issue" && e["line"] == *line && e["file"].is_null())
                .and_then(|e| e["t"].as_f64())
                .unwrap_or_else(|| panic!("line {line} never issued in\n{text}"))
        })
        .collect()
}

/// W0905 says two settings of concurrent blocks are issued in the same tick: the VM
/// issues them at one time where it warns, and at different times where statements
/// held by different waits are not compared.
#[test]
fn settings_said_to_meet_are_issued_in_one_tick() {
    let dir = scratch("settings");
    let m = model("workpartner");
    // (task, its skills, the two setting lines of the task, whether W0905 is said)
    let cases: [(&str, &str, [u64; 2], bool); 10] = [
        ("speed(0.4)\ngoahead(1)\n\nspeed(0.5)\n", "", [1, 4], true),
        // Guards of one condition issued at one moment fire in one tick.
        (
            "m = goahead(0.5)\nif(m)\nspeed(0.3)\nendif\n\nw = wait(3)\nif(w)\nspeed(0.5)\nendif\n",
            "",
            [3, 8],
            false,
        ),
        (
            "m = goahead(0.5)\nif(m)\nspeed(0.3)\nendif\n\nIF(M)\nspeed(0.5)\nendif\n",
            "",
            [3, 7],
            true,
        ),
        // A skill call that waits lets its caller go when the wait does.
        (
            "m = goahead(0.5)\nPause\nspeed(0.3)\n\nwait(m)\nspeed(0.5)\n",
            "Pause:\nwait(m)\n",
            [3, 6],
            true,
        ),
        (
            "speed(0.2)\nHold\nspeed(0.3)\n\nwait(1)\nwait(0.5)\nspeed(0.5)\n",
            "Hold:\nHalf\nwait(0.5)\n\nHalf:\nwait(1)\n",
            [3, 7],
            true,
        ),
        (
            "speed(0.2)\nHold\nspeed(0.3)\n\nwait(1)\nspeed(0.5)\n",
            "Hold:\nwait(1)\nwait(0.5)\n",
            [3, 6],
            false,
        ),
        (
            "m = goahead(0.5)\nwait(m)\nspeed(0.3)\n\nwait(m)\nspeed(0.5)\n",
            "",
            [3, 6],
            true,
        ),
        (
            "speed(0.2)\nwait(1)\nspeed(0.3)\n\nwait(1)\nspeed(0.5)\n",
            "",
            [3, 6],
            true,
        ),
        (
            "speed(0.4)\ngoahead(1)\n\nwait(0.5)\nspeed(0.5)\n",
            "",
            [1, 5],
            false,
        ),
        (
            "m = goahead(0.5)\nwait(m)\nspeed(0.3)\n\nwait(5)\nwait(m)\nspeed(0.5)\n",
            "",
            [3, 7],
            false,
        ),
    ];
    for (i, (task, skills, lines, warned)) in cases.iter().enumerate() {
        let mut sources = vec![Source::new("t.ilmr", task.to_string())];
        if !skills.is_empty() {
            sources.push(Source::library("t.ilms", skills.to_string()));
        }
        let analysis = analyze(&sources, &m);
        let said = analysis
            .diagnostics
            .iter()
            .any(|d| d.code == Code::SettingRace);
        assert_eq!(said, *warned, "{task}\n{:?}", analysis.diagnostics);
        let t = issued_at(&dir, &format!("case{i}"), task, skills, lines);
        assert_eq!(t[0] == t[1], *warned, "{task}: issued at {t:?}");
    }
}

//! `Detail::Diagnostics` (what `ilmrc check` asks for) keeps less than `Detail::Full`
//! but reports exactly the same diagnostics: on every program of the repository, with
//! the examples' skills as a library, on both robots; on the benchmark corpus with
//! damaged lines; and on mutated programs.

use ilmr_compiler::check::{Detail, Source, Target, analyze_with};
use ilmr_model::RobotModel;
use proptest::prelude::*;

#[path = "../benches/corpus.rs"]
mod corpus;
mod support {
    pub mod programs;
}
use support::programs::repository_programs as programs;

/// Both details of one program, compared; returns how many diagnostics there were.
fn assert_same(sources: &[Source], robot: &str) -> usize {
    let model = RobotModel::builtin(robot).unwrap();
    let full = analyze_with(sources, &model, Detail::Full);
    let lean = analyze_with(sources, &model, Detail::Diagnostics);
    assert_eq!(
        full.diagnostics,
        lean.diagnostics,
        "diagnostics differ on {robot} for {:?}",
        sources.iter().map(|s| &s.path).collect::<Vec<_>>()
    );
    for unit in &lean.units {
        assert!(unit.refs.is_empty());
        assert!(unit.targets.values().all(|t| matches!(t, Target::Skill(_))));
        assert!(
            unit.vars
                .iter()
                .all(|(_, v)| v.defs.len() <= 1 && v.uses.len() <= 1)
        );
    }
    full.diagnostics.len()
}

fn example_skills() -> Vec<Source> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/skills");
    let mut paths: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .collect();
    paths.sort();
    paths
        .iter()
        .map(|p| Source::library(p.display().to_string(), std::fs::read_to_string(p).unwrap()))
        .collect()
}

#[test]
fn every_program_of_the_repository() {
    let programs = programs();
    assert!(programs.len() > 20, "only {} programs", programs.len());
    let mut diagnostics = 0;
    for (path, text) in &programs {
        let mut sources = vec![Source::new(path.clone(), text.clone())];
        sources.extend(example_skills());
        for robot in ["moro", "workpartner"] {
            diagnostics += assert_same(&sources, robot);
        }
    }
    // The broken programs among them make sure the comparison covers diagnostics.
    assert!(diagnostics > 100, "{diagnostics} diagnostics");
}

#[test]
fn the_corpus_with_damaged_lines() {
    let corpus = corpus::generate(3_000);
    let damage = [
        "speeed(0.3)",
        "x = = 3",
        "break(turn(d=))",
        "break(while(c",
        "endif",
        "gotoxy(v99999)",
        "turn(lft)",
        "skill3",
        "q = nothing + 1",
        "käännös = 3",
        "KÄÄNNÖS = käännös + 1",
        "check",
        "priority = highest",
    ];
    let task: String = corpus
        .task
        .lines()
        .enumerate()
        .map(|(i, line)| match i % 37 {
            0 => damage[(i / 37) % damage.len()],
            _ => line,
        })
        .collect::<Vec<_>>()
        .join("\n");
    let sources = [
        Source::new("task.ilmr", task),
        Source::library("skills.ilms", corpus.skills),
    ];
    assert!(assert_same(&sources, "moro") > 50);
}

/// `ilmrc check` reads a task block by block where the diagnostics allow it
/// (`check/stream.rs`): then no tree of it is kept. The corpus with statements that
/// are wrong but parse (unknown names, frozen and starving loops, settings that
/// meet): streamed, with the whole tree's diagnostics, unless a starving loop makes
/// the check fall back to the whole tree.
#[test]
fn the_corpus_is_checked_block_by_block() {
    let corpus = corpus::generate(3_000);
    let damage = [
        "speeed(0.3)",
        "gotoxy(v99999)",
        "turn(lft)",
        "skill3",
        "q = nothing + 1",
        "käännös = 3",
        "KÄÄNNÖS = käännös + 1",
        "priority = highest",
        "speed(0.7)",
        "n7 = 1\nwhile(n7 < 2)\nspeed(0.2)\nwait(1)\nendwhile",
        "\nspeed(0.4)\n",
        // A library skill is checked only where called: the streamed check keeps
        // which skills the task calls, not every call.
        "faulty",
    ];
    let skills = format!("{}faulty:\nspeeed(0.1)\n\n", corpus.skills);
    let damaged = |starving: bool| -> String {
        let mut lines: Vec<String> = corpus
            .task
            .lines()
            .enumerate()
            .map(|(i, line)| match i % 41 {
                // Inserted, not in place of a line: an `endif` replaced would be a
                // diagnostic of the parser, which the streamed check leaves alone.
                // Each loop's own counter, set once before it: W0901.
                0 => format!("{}\n{line}", damage[(i / 41) % damage.len()])
                    .replace("n7", &format!("n7_{i}")),
                _ => line.to_string(),
            })
            .collect();
        if starving {
            lines.push("\nwhile(1)\nx9 = 1\nendwhile".to_string());
        }
        lines.join("\n")
    };
    let model = RobotModel::builtin("moro").unwrap();
    for starving in [false, true] {
        let sources = [
            Source::new("task.ilmr", damaged(starving)),
            Source::library("skills.ilms", skills.clone()),
        ];
        let n = assert_same(&sources, "moro");
        assert!(n > 30, "{n} diagnostics");
        let lean = analyze_with(&sources, &model, Detail::Diagnostics);
        assert_eq!(lean.files[0].tree.blocks.is_empty(), !starving);
        let codes: Vec<&str> = lean.diagnostics.iter().map(|d| d.code.as_str()).collect();
        for code in ["E0301", "W0901", "W0905"] {
            assert!(codes.contains(&code), "no {code} among {codes:?}");
        }
        assert_eq!(codes.contains(&"W0902"), starving);
        assert!(
            lean.diagnostics
                .iter()
                .any(|d| d.code.as_str() == "E0301" && d.file.0 == 1),
            "the called library skill was not checked"
        );
    }
}

const PIECES: &[&str] = &[
    "turn",
    "sensor",
    "wait",
    "if",
    "endif",
    "while(",
    "endwhile",
    "break(",
    "check",
    "checkend",
    "(",
    ")",
    ",",
    "=",
    "<",
    "+",
    "x",
    "1",
    "left",
    "door",
    "\n",
    "\n\n",
    " ",
    "käännös",
    "TURN1",
    "gestures",
];

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    #[test]
    fn mutated_programs(
        which in 0usize..1_000,
        cuts in proptest::collection::vec((0usize..10_000, 0usize..8, 0usize..64), 1..10),
    ) {
        let programs = programs();
        let (path, base) = &programs[which % programs.len()];
        let mut text: Vec<char> = base.chars().collect();
        for &(at, len, piece) in &cuts {
            if text.is_empty() {
                break;
            }
            let at = at % text.len();
            let end = (at + len).min(text.len());
            text.splice(at..end, PIECES[piece % PIECES.len()].chars());
        }
        let mut sources = vec![Source::new(path.clone(), text.into_iter().collect::<String>())];
        sources.extend(example_skills());
        assert_same(&sources, "moro");
    }
}

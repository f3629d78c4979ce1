//! Every program printed in the dissertation checks clean on the robot it was written
//! for; its tree and its diagnostics on both robot models are snapshots.

mod support;

use std::path::Path;

use ilmr_compiler::check::analyze;
use support::*;

fn fixtures() -> Vec<std::path::PathBuf> {
    let mut files = Vec::new();
    for dir in ["examples", "tests/check/dissertation"] {
        for entry in std::fs::read_dir(root().join(dir)).unwrap() {
            let p = entry.unwrap().path();
            if p.extension().is_some_and(|x| x == "ilmr") {
                files.push(p);
            }
        }
    }
    files.sort();
    assert!(
        files.len() >= 9,
        "the figures and the BNF examples are all there"
    );
    files
}

fn snapshot_name(path: &Path) -> String {
    path.strip_prefix(root())
        .unwrap()
        .display()
        .to_string()
        .replace(['/', '.'], "_")
}

#[test]
fn dissertation_programs_check_clean_on_their_robot() {
    for path in fixtures() {
        let sources = program(&path);
        let robot = intended_robot(&sources[0].text).to_string();
        let m = model(&robot);
        let analysis = analyze(&sources, &m);
        assert!(
            !analysis.has_errors(),
            "{} has errors on {robot}:\n{}",
            path.display(),
            human(&analysis)
        );
    }
}

#[test]
fn dissertation_program_trees() {
    for path in fixtures() {
        let text = std::fs::read_to_string(&path).unwrap();
        let parsed = ilmr_compiler::parser::parse(&text, ilmr_compiler::FileId(0));
        assert!(parsed.diagnostics.is_empty());
        insta::assert_snapshot!(
            format!("tree_{}", snapshot_name(&path)),
            ilmr_compiler::tree::render(&parsed.file)
        );
    }
}

#[test]
fn dissertation_program_diagnostics_on_both_robots() {
    for path in fixtures() {
        let sources = program(&path);
        for robot in ROBOTS {
            let (analysis, _) = check(&sources, robot);
            insta::assert_snapshot!(
                format!("diagnostics_{}_{robot}", snapshot_name(&path)),
                human(&analysis)
            );
        }
    }
}

#[test]
fn skill_files_parse_into_their_skills() {
    let text = std::fs::read_to_string(root().join("examples/skills/turns.ilms")).unwrap();
    let parsed = ilmr_compiler::parser::parse(&text, ilmr_compiler::FileId(0));
    assert!(parsed.diagnostics.is_empty());
    insta::assert_snapshot!(
        "tree_skills_turns",
        ilmr_compiler::tree::render(&parsed.file)
    );
}

#[test]
fn formatting_the_dissertation_programs_is_stable_and_keeps_their_meaning() {
    for path in fixtures() {
        let text = std::fs::read_to_string(&path).unwrap();
        let m = model(intended_robot(&text));
        let once = ilmr_compiler::format::format(&text, &m).unwrap();
        assert_eq!(
            ilmr_compiler::format::format(&once, &m).unwrap(),
            once,
            "{}",
            path.display()
        );
        let before = ilmr_compiler::parser::parse(&text, ilmr_compiler::FileId(0));
        let after = ilmr_compiler::parser::parse(&once, ilmr_compiler::FileId(0));
        assert_eq!(
            before.file.blocks.len(),
            after.file.blocks.len(),
            "{}",
            path.display()
        );
        if path.ends_with("fetch_boxes.ilmr") {
            insta::assert_snapshot!("fmt_fetch_boxes", once);
        }
    }
}

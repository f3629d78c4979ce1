//! `docs/experiments.md` is what the runs give today. With `ILMR_EXPERIMENTS=full`
//! (the report's own seeds) it is rendered again from fresh runs, keeping its
//! hand-written sections, and must be byte for byte the committed file. The fast
//! subset `cargo test` runs by default gives other numbers, so there the rendered
//! report must have the committed file's structure: the same headings and the same
//! table rows, numbers aside. Either way every picture it shows exists.

use ilmr_experiments::doc::{COMMAND, render};
use ilmr_experiments::{PICTURES, harness, run_all, seeds};

/// Headings and each table row's first cell, every run of digits read as `#`.
fn skeleton(text: &str) -> Vec<String> {
    text.lines()
        .filter(|l| l.starts_with('#') || l.starts_with('|'))
        .map(|l| {
            let l = if l.starts_with('|') {
                l.splitn(3, '|').take(2).collect::<Vec<_>>().join("|")
            } else {
                l.to_string()
            };
            let mut out = String::new();
            for c in l.chars() {
                if c.is_ascii_digit() {
                    if !out.ends_with('#') {
                        out.push('#');
                    }
                } else {
                    out.push(c);
                }
            }
            out
        })
        .collect()
}

fn first_difference(committed: &str, fresh: &str) -> (usize, String, String) {
    committed
        .lines()
        .zip(fresh.lines())
        .enumerate()
        .find(|(_, (a, b))| a != b)
        .map_or(
            (
                committed.lines().count().min(fresh.lines().count()),
                String::new(),
                String::new(),
            ),
            |(i, (a, b))| (i, a.to_string(), b.to_string()),
        )
}

#[test]
fn docs_experiments_md_matches_the_runs() {
    let docs = harness::repo().join("docs");
    let path = docs.join("experiments.md");
    let committed = std::fs::read_to_string(&path).expect("docs/experiments.md readable");
    let results = run_all(seeds::for_tests()).expect("the experiments run");
    let fresh = render(&results, &committed);
    if seeds::full() {
        if fresh != committed {
            let (line, was, now) = first_difference(&committed, &fresh);
            panic!(
                "docs/experiments.md is stale: regenerate it with `{COMMAND}`.\n\
                 First difference, line {}:\n  file: {was}\n  runs: {now}",
                line + 1
            );
        }
    } else {
        let (was, now) = (skeleton(&committed), skeleton(&fresh));
        if was != now {
            let (line, a, b) = first_difference(&was.join("\n"), &now.join("\n"));
            panic!(
                "docs/experiments.md's sections or rows are not the runs': regenerate it \
                 with `{COMMAND}`.\nFirst difference, heading or row {}:\n  file: {a}\n  runs: {b}",
                line + 1
            );
        }
    }
    for name in PICTURES {
        let svg = docs.join("experiments").join(name);
        assert!(
            svg.is_file(),
            "{} is missing: run `{COMMAND}`",
            svg.display()
        );
        assert!(
            committed.contains(&format!("(experiments/{name})")),
            "the report shows {name}"
        );
    }
}

#[test]
fn the_skeleton_keeps_headings_and_rows_and_reads_numbers_as_one_mark() {
    let text = "# Title\nprose 12\n## Over 20 seeds\n| row 3.5 m | 0.0412 | x |\n| --- | --- |\n";
    assert_eq!(
        skeleton(text),
        ["# Title", "## Over # seeds", "| row #.# m ", "| --- "]
    );
    assert_ne!(skeleton(text), skeleton(&text.replace("row", "line")));
}

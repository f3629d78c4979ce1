//! `docs/experiments.md` is what the runs give today: rendered again from fresh runs
//! (keeping its hand-written sections), it is byte for byte the committed file, and
//! every picture it shows exists.

use ilmr_experiments::doc::{COMMAND, render};
use ilmr_experiments::{PICTURES, harness, run_all};

#[test]
fn docs_experiments_md_matches_the_runs() {
    let docs = harness::repo().join("docs");
    let path = docs.join("experiments.md");
    let committed = std::fs::read_to_string(&path).expect("docs/experiments.md readable");
    let results = run_all().expect("the experiments run");
    let fresh = render(&results, &committed);
    if fresh != committed {
        let (line, (was, now)) = committed
            .lines()
            .zip(fresh.lines())
            .enumerate()
            .find(|(_, (a, b))| a != b)
            .map_or(
                (
                    committed.lines().count().min(fresh.lines().count()),
                    ("", ""),
                ),
                |(i, p)| (i, p),
            );
        panic!(
            "docs/experiments.md is stale: regenerate it with `{COMMAND}`.\n\
             First difference, line {}:\n  file: {was}\n  runs: {now}",
            line + 1
        );
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

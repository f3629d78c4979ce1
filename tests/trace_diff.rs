//! `ilmrc diff A.jsonl B.jsonl`: two traces of a task compared (`src/diff.rs`).

mod support;

use std::path::PathBuf;

use support::ilmrc;

fn scratch(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("ilmr-trace-diff-{}-{name}", std::process::id()))
}

/// The trace of `task` (a file of the repository, or text written to a scratch file).
fn traced(name: &str, task: &str, extra: &[&str]) -> PathBuf {
    let trace = scratch(&format!("{name}.jsonl"));
    let path = if task.ends_with(".ilmr") {
        task.to_string()
    } else {
        let p = scratch(&format!("{name}.ilmr"));
        std::fs::write(&p, task).unwrap();
        p.display().to_string()
    };
    let mut args = vec!["run", "--trace", trace.to_str().unwrap(), path.as_str()];
    args.extend_from_slice(extra);
    let (code, out, err) = ilmrc(&args);
    assert!(matches!(code, 0 | 5), "{out}{err}");
    trace
}

/// `ilmrc diff A B`, after which both traces are removed.
fn diff(a: &PathBuf, b: &PathBuf) -> (i32, String, String) {
    let said = ilmrc(&["diff", a.to_str().unwrap(), b.to_str().unwrap()]);
    for p in [a, b] {
        let _ = std::fs::remove_file(p);
    }
    said
}

#[test]
fn one_task_run_twice_with_one_seed_is_the_same_run() {
    let a = traced("same-a", "examples/short_task.ilmr", &["--seed", "3"]);
    let b = traced("same-b", "examples/short_task.ilmr", &["--seed", "3"]);
    let (code, out, err) = diff(&a, &b);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.contains("are the same run: "), "{out}");
    assert!(!out.contains("the runs differ"), "{out}");
}

#[test]
fn a_changed_task_shows_where_it_parts_ways_and_which_ends_moved() {
    // From (8, 5) in the office's lab, `goahead(1)` then `turn(left)` now ends held by
    // the supervisor beside the bench's end (issue 15 item 4's turn check lets the
    // turn begin where the old one did not; left open), so these runs go half a
    // metre further first. The ends' times quoted below are the `basic` profile's (a
    // test of the diff).
    let basic = ["--sim-profile", "basic"];
    let a = traced(
        "task-a",
        "goahead(1.5)
turn(left)
",
        &basic,
    );
    let b = traced(
        "task-b",
        "goahead(2)
turn(left)
",
        &basic,
    );
    let (code, out, err) = diff(&a, &b);
    assert_eq!(code, 1, "{out}{err}");
    assert!(out.contains("part ways at t=0 (event 1 of"), "{out}");
    assert!(
        out.contains(r#"  A: {"t":0,"event":"issue","line":1,"text":"goahead(1.5)"}"#)
            && out.contains(r#"  B: {"t":0,"event":"issue","line":1,"text":"goahead(2)"}"#),
        "{out}"
    );
    assert!(out.contains("  statement: line 1 `goahead(1.5)`"), "{out}");
    assert!(out.contains("commands whose end changed (3):"), "{out}");
    assert!(
        out.contains("  line 1 `goahead(1.5)`: A completed at t=3.65, B never ended"),
        "{out}"
    );
    // The turn starts half a metre later, so it ends later, from another place.
    let turn = out
        .lines()
        .find(|l| l.starts_with("  line 2 `turn(left)`: A completed at t="))
        .unwrap_or_else(|| panic!("{out}"));
    assert!(turn.contains(", B completed at t="), "{turn}");
    let largest = out
        .lines()
        .find(|l| l.starts_with("largest pose difference: "))
        .unwrap_or_else(|| panic!("{out}"));
    let metres: f64 = largest["largest pose difference: ".len()..]
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!((0.4..0.6).contains(&metres), "{largest}");
}

#[test]
fn plot_draws_both_trajectories_over_the_world() {
    let a = traced("plot-a", "goahead(1.5)\nturn(left)\n", &[]);
    let b = traced("plot-b", "goahead(2)\nturn(left)\n", &[]);
    let svg = scratch("both.svg");
    let (code, out, err) = ilmrc(&[
        "diff",
        a.to_str().unwrap(),
        b.to_str().unwrap(),
        "--plot",
        svg.to_str().unwrap(),
    ]);
    for p in [&a, &b] {
        let _ = std::fs::remove_file(p);
    }
    assert_eq!(code, 1, "{out}{err}");
    assert!(
        out.ends_with(&format!("drew both runs: {}\n", svg.display())),
        "{out}"
    );
    let text = std::fs::read_to_string(&svg).expect("an SVG");
    let _ = std::fs::remove_file(&svg);
    assert!(text.starts_with("<svg") && text.trim_end().ends_with("</svg>"));
    // Both tracks are named in the legend, each in its own colour of the palette.
    for (side, trace) in [("A", &a), ("B", &b)] {
        let label = format!("{side} {}", trace.display());
        assert!(text.contains(&label), "{label} not in the legend");
    }
    assert!(text.contains(r##"stroke="#0072B2""##), "A's colour");
    assert!(text.contains(r##"stroke="#D55E00""##), "B's colour");
}

#[test]
fn two_seeds_differ_in_their_headers_and_their_noise() {
    let a = traced("seed-a", "examples/short_task.ilmr", &["--seed", "1"]);
    let b = traced("seed-b", "examples/short_task.ilmr", &["--seed", "2"]);
    let (code, out, _) = diff(&a, &b);
    assert_eq!(code, 1);
    assert!(out.starts_with("the runs differ:\n"), "{out}");
    assert!(
        out.contains(r#""seed":1"#) && out.contains(r#""seed":2"#),
        "{out}"
    );
    // A scan's line runs to kilobytes: it is cut.
    for line in out.lines() {
        assert!(
            line.chars().count() < 400,
            "a line of {} characters",
            line.len()
        );
    }
    assert!(out.contains("more characters)"), "{out}");
}

#[test]
fn what_is_not_a_trace_is_refused_with_its_code() {
    let a = traced("bad-a", "goahead(1)\n", &[]);
    let not = scratch("not-a-trace.jsonl");
    std::fs::write(&not, "hello\n").unwrap();
    let (code, _, err) = ilmrc(&["diff", a.to_str().unwrap(), "/no/such/trace.jsonl"]);
    assert_eq!(code, 2);
    assert!(
        err.contains("cannot read trace `/no/such/trace.jsonl`"),
        "{err}"
    );
    let (code, out, err) = diff(&a, &not);
    assert_eq!(code, 2, "{out}{err}");
    assert!(
        err.contains("is not a trace of ilmrc run: line 1: T0101"),
        "{err}"
    );
}

//! The assertion language and its evaluation on small traces written by hand.

use super::assertion::{Context, Kind, Place, parse};
use super::codes::Code;
use super::eval::Run;
use super::file::{KEYS, MAX_SEEDS, MAX_TIME};

const STATEMENTS: [(u32, &str); 5] = [
    (3, "speed(0.4)"),
    (4, "goahead(1.2)"),
    (5, "turn(d=90,c=0.5)"),
    (6, "m=goahead(0.7)"),
    (7, "wait(m)"),
];

fn with<T>(robot: bool, f: impl FnOnce(&Context<'_>) -> T) -> T {
    let statements: Vec<(u32, String)> = STATEMENTS
        .iter()
        .map(|(l, t)| (*l, t.to_string()))
        .collect();
    let variables = vec!["m".to_string(), "cnt".to_string()];
    let objects = vec![Place::Object {
        name: "lab_door".into(),
        from: (5.0, 11.5),
        to: (5.0, 11.5),
    }];
    let ctx = Context {
        statements: &statements,
        variables: &variables,
        objects: robot.then_some(objects.as_slice()),
        poses: robot,
        scans: robot,
    };
    f(&ctx)
}

fn ok(text: &str) -> Kind {
    with(true, |ctx| parse(text, Some(100), 0..1, ctx))
        .unwrap_or_else(|p| panic!("{text}: {p:?}"))
        .kind
}

/// The problem's code and its span in the assertion (the text is at byte 100).
fn bad(text: &str) -> (Code, std::ops::Range<usize>, String) {
    let p = with(true, |ctx| parse(text, Some(100), 0..1, ctx)).expect_err(text);
    (p.code, p.span.start - 100..p.span.end - 100, p.message)
}

#[test]
fn keywords_are_in_any_case_and_units_optional() {
    assert_eq!(
        ok("EVENTUALLY Within 5 S: Line 4 ENDS Completed"),
        ok("eventually within 5 s: line 4 ends completed")
    );
    let Kind::Eventually { within, .. } = ok("eventually within 5: line 4 ends") else {
        panic!()
    };
    assert_eq!(within, Some(5.0));
    assert_eq!(ok("at end: M == -1.5"), ok("at end: m.value == -1.5"));
}

#[test]
fn a_command_is_found_by_line_or_by_text_with_or_without_its_variable() {
    let by_text = ok("before(`GoAhead( 0.7 )`, `m=goahead(0.7)`)");
    let Kind::Before(a, b) = by_text else {
        panic!("{by_text:?}")
    };
    let task = |line, text| stmt(line, text, None);
    assert!(a.is(&task(6, "m=goahead(0.7)")) && b.is(&task(6, "m = goahead(0.7)")));
    assert!(!a.is(&task(4, "goahead(1.2)")));
    // A reference by text finds the statement in a skill too.
    assert!(a.is(&stmt(2, "m=goahead(0.7)", Some("skills/s.ilms"))));
    // A line reference is the task's line and its text: a skill's statement on line 4
    // is another statement, even of the same text.
    let Kind::During(l, _) = ok("during(line 4, line 5)") else {
        panic!()
    };
    assert!(l.is(&task(4, "goahead(1.2)")));
    assert!(!l.is(&task(4, "near_box = approach(box_at,4.5)")));
    assert!(!l.is(&stmt(4, "goahead(1.2)", Some("skills/s.ilms"))));
}

fn stmt<'a>(line: u32, text: &'a str, file: Option<&'a str>) -> ilmr_trace::Stmt<'a> {
    ilmr_trace::Stmt {
        line,
        text: text.into(),
        file: file.map(Into::into),
    }
}

#[test]
fn mistakes_are_said_where_they_are_with_a_suggestion() {
    let (code, span, message) = bad("eventually: `goahed(1.2)` ends");
    assert_eq!((code, span), (Code::UnknownCommand, 12..25));
    assert!(message.contains("goahed(1.2)"), "{message}");
    assert_eq!(bad("before(line 9, line 4)").0, Code::UnknownLine);
    assert_eq!(bad("eventually: cnnt == 2").0, Code::UnknownVariable);
    assert_eq!(
        bad("eventually: robot within 1 of lab_dor").0,
        Code::UnknownObject
    );
    assert_eq!(bad("never: contact").0, Code::NotTraced);
    let (code, span, _) = bad("always: speed =< 1");
    assert_eq!((code, span), (Code::Syntax, 14..15));
    assert_eq!(bad("always: speed <= 1 now").1, 19..22);
    assert_eq!(bad("eventually within -1 s: m == 1").0, Code::Syntax);
    assert_eq!(bad("before(line 4 line 5)").1, 14..18);
    assert_eq!(bad("eventually: `goahead(1.2)").1, 12..25);
    assert_eq!(bad("").1, 0..0);
    let (code, span, message) = bad("always whle line 4: speed <= 1");
    assert_eq!((code, span), (Code::Syntax, 7..11));
    assert!(message.contains("found `whle`"), "{message}");
}

#[test]
fn robot_states_need_a_simulated_robot() {
    let p =
        with(false, |ctx| parse("always: speed <= 1", Some(0), 0..1, ctx)).expect_err("no robot");
    assert_eq!(p.code, Code::NeedsRobot);
    assert!(with(false, |ctx| parse("never: refused", Some(0), 0..1, ctx)).is_ok());
}

#[test]
fn a_scripted_robot_has_poses_but_no_scans_and_no_world() {
    let statements: Vec<(u32, String)> = vec![(1, "goahead(1)".into())];
    let ctx = Context {
        statements: &statements,
        variables: &[],
        objects: None,
        poses: true,
        scans: false,
    };
    let code = |text: &str| parse(text, Some(0), 0..1, &ctx).err().map(|p| p.code);
    assert_eq!(code("always: speed <= 1"), None);
    assert_eq!(code("at end: robot within 1 of (0, 0)"), None);
    assert_eq!(code("always: clearance > 1"), Some(Code::NeedsRobot));
    assert_eq!(
        code("eventually: robot within 1 of lab_door"),
        Some(Code::NeedsRobot)
    );
}

#[test]
fn a_string_with_escapes_points_at_itself() {
    let p = with(true, |ctx| parse("never: sped", None, 40..60, ctx)).expect_err("typo");
    assert_eq!(p.span, 40..60);
}

#[test]
fn no_text_makes_the_parser_panic() {
    let pieces = [
        "eventually",
        "within",
        "-",
        "1.5",
        "s",
        ":",
        "`",
        "goahead(1.2)",
        "ends",
        "(",
        ")",
        ",",
        "..",
        ".",
        "line",
        "4",
        "robot",
        "of",
        "at",
        "end",
        "==",
        "<",
        "é",
        "\"",
        "never",
        "fault",
        "m",
        "x",
        "speed",
        "inside",
        "before",
        "during",
        "always",
        " ",
    ];
    let mut seed = 7u64;
    for _ in 0..20_000 {
        let mut text = String::new();
        for _ in 0..(seed % 12) {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            text.push_str(pieces[(seed >> 33) as usize % pieces.len()]);
            if seed & 1 == 0 {
                text.push(' ');
            }
        }
        seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1);
        let _ = with(true, |ctx| parse(&text, Some(0), 0..text.len(), ctx));
    }
}

const TRACE: &str = r#"{"t":0,"event":"trace","version":1}
{"t":0,"event":"issue","line":4,"text":"goahead(1.2)"}
{"t":0,"event":"start","line":4,"text":"goahead(1.2)"}
{"t":0,"event":"issue","line":5,"text":"turn(d=90,c=0.5)"}
{"t":0,"event":"pose","x":8,"y":5,"h":0,"v":0,"c":0,"source":"true"}
{"t":1,"event":"pose","x":8.4,"y":5,"h":0,"v":-0.4,"c":0,"source":"true"}
{"t":1,"event":"scan","x":8.4,"y":5,"h":0,"hits":[[9.4,5],[8.4,5.5]]}
{"t":2.17,"event":"end","line":4,"text":"goahead(1.2)","how":"completed","linked":true}
{"t":2.17,"event":"start","line":5,"text":"turn(d=90,c=0.5)"}
{"t":3,"event":"var","line":6,"text":"m=goahead(0.7)","var":"m","status":0}
{"t":5,"event":"pose","x":9.2,"y":5.5,"h":1.5708,"v":0.3,"c":0,"source":"true"}
{"t":9,"event":"end","line":5,"text":"turn(d=90,c=0.5)","how":"broken"}
{"t":9,"event":"var","line":6,"text":"m=goahead(0.7)","var":"m","status":1,"value":2}
{"t":10,"event":"pose","x":9.2,"y":6,"h":3.1416,"v":0,"c":0,"source":"true"}
"#;

fn check(assertion: &str) -> Result<(), (f64, String)> {
    let records: Vec<_> = ilmr_trace::records(TRACE)
        .collect::<Result<_, _>>()
        .expect("trace");
    let a = with(true, |ctx| parse(assertion, Some(0), 0..1, ctx)).expect(assertion);
    Run::new(&records).check(&a).map_err(|f| (f.t, f.message))
}

#[test]
fn each_assertion_holds_or_fails_with_the_time_and_the_values() {
    let holds = [
        "eventually within 2.17 s: line 4 ends completed",
        "eventually: `turn(d=90,c=0.5)` ends broken",
        "eventually within 9 s: m == 2",
        "eventually: robot within 0.5 of (9.2, 6.4)",
        "always: speed <= 0.4",
        "never: speed > 0.4",
        "always: robot inside (8, 5)..(9.2, 6)",
        "never: clearance < 0.5",
        "before(line 4, line 5)",
        "never: refused",
        "eventually: broken",
        "at end: robot within 0.01 of (9.2, 6)",
        "at end: heading within 0.01 of -180",
        "at end: completed == 1",
        "at end: broken == 1",
        "at end: m.status == 1",
        "always while line 4: speed <= 0.4",
        "always from 4 s until 6 s: robot within 0.1 of (9.2, 5.5)",
        "never until 8: broken",
        "never from 9.5 s: speed > 0",
    ];
    for a in holds {
        assert_eq!(check(a), Ok(()), "{a}");
    }
    let fails = [
        (
            "eventually within 2 s: line 4 ends",
            2.0,
            "it ended completed at t=2.17",
        ),
        (
            "eventually: line 5 ends completed",
            10.0,
            "it ended broken at t=9",
        ),
        (
            "eventually within 8 s: m.status == 1",
            8.0,
            "it was 0 from t=3",
        ),
        ("always: speed < 0.4", 1.0, "speed 0.4 m/s"),
        (
            "always: clearance > 0.6",
            1.0,
            "nearest scanner hit 0.5 m away",
        ),
        (
            "always: robot within 0.5 of (8, 5)",
            5.0,
            "1.3 m from (8, 5)",
        ),
        (
            "before(line 5, line 4)",
            0.0,
            "started at t=0, before line 5",
        ),
        ("during(line 5, line 4)", 2.17, "ran t=2.17..9"),
        (
            "never: broken",
            9.0,
            "line 5 `turn(d=90,c=0.5)` ended broken",
        ),
        (
            "at end: heading within 10 of 90",
            10.0,
            "ended heading 180.0004 deg, 90.0004 deg from 90 deg",
        ),
        ("at end: cnt == 1", 10.0, "`cnt` was never set"),
        ("always while line 5: speed < 0.3", 5.0, "speed 0.3 m/s"),
        (
            "never while `wait(m)`: refused",
            10.0,
            "`wait(m)` never ran",
        ),
        (
            "always from 6 until 7: speed <= 1",
            6.0,
            "no pose line from t=6 to t=7",
        ),
        ("never from 8 s: broken", 9.0, "ended broken"),
    ];
    for (a, t, seen) in fails {
        let (at, message) = check(a).expect_err(a);
        assert_eq!(at, t, "{a}: {message}");
        assert!(message.contains(seen), "{a}: {message}");
    }
}

fn docs() -> String {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/testing.md");
    std::fs::read_to_string(path).expect("docs/testing.md")
}

#[test]
fn docs_list_every_code_and_key() {
    let docs = docs();
    for code in Code::ALL {
        let row = format!("| {} | {} |", code.as_str(), code.title());
        assert!(docs.contains(&row), "docs/testing.md lacks `{row}`");
    }
    let rows = docs.lines().filter(|l| l.starts_with("| A0")).count();
    assert_eq!(rows, Code::ALL.len(), "docs/testing.md lists other codes");
    for (key, what) in KEYS {
        let row = format!("| `{key}` | {what} |");
        assert!(docs.contains(&row), "docs/testing.md lacks `{row}`");
    }
    let seeds = MAX_SEEDS.to_string();
    let (thousands, rest) = seeds.split_at(seeds.len() - 3);
    assert!(docs.contains(&format!("at most {thousands},{rest} (`MAX_SEEDS`)")));
    assert!(docs.contains(&format!(
        "at most {MAX_TIME} s, a day of\nlogical time (`MAX_TIME`)"
    )));
}

#[test]
fn the_progress_line_fills_with_the_runs_done() {
    use super::progress::line;
    use std::time::Duration;
    let half = line(5, 10, Duration::from_millis(3400));
    assert_eq!(
        half,
        format!("[{}>{}] 5/10 runs, 3.4 s", "=".repeat(15), " ".repeat(14))
    );
    assert!(line(10, 10, Duration::ZERO).starts_with(&format!("[{}]", "=".repeat(30))));
    assert!(line(0, 0, Duration::ZERO).contains("0/0 runs"));
}

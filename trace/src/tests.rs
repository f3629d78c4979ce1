use super::*;

fn stmt(line: u32, text: &str) -> Option<Stmt<'_>> {
    Some(Stmt {
        line,
        text: text.into(),
    })
}

/// One record of every event, with every optional key present where that is rare.
fn every_event() -> Vec<Record<'static>> {
    let events = vec![
        Event::Trace(Version {
            version: SCHEMA_VERSION,
        }),
        Event::Run(Run {
            task: "t.ilmr".into(),
            robot: "moro".into(),
            world: "w.toml".into(),
            seed: 7,
            start: At {
                x: Num(1.5),
                y: Num(-2.0),
                h: Num(0.25),
            },
            world_toml: Some("[world]\nname = \"w\"\n".into()),
        }),
        Event::Failed(Failed {
            reason: "no \"robot\"".into(),
            exit: 2,
        }),
        Event::Truncated(Truncated {
            limit: 4096,
            message: "full".into(),
        }),
        Event::Line(Entered {
            text: "goahead(1)".into(),
            accepted: false,
            codes: vec!["E0201".into()],
        }),
        Event::Issue(Issue {
            stmt: stmt(3, "x=x+1"),
            count: 25000,
        }),
        Event::Start(Start {
            stmt: stmt(2, "while(x>-1)"),
            iteration: Some(50000),
            count: 3,
        }),
        Event::End(End {
            stmt: stmt(4, "goahead(speed=9)"),
            how: How::Refused,
            linked: true,
            code: Some("R0101".into()),
            reason: Some("too fast".into()),
            help: Some("slow down".into()),
        }),
        Event::Var(Var {
            stmt: stmt(5, "x=1e999"),
            var: "x".into(),
            status: Some(Num(1.0)),
            x: None,
            y: Some(Num(f64::NEG_INFINITY)),
            h: None,
            value: Some(Num(f64::INFINITY)),
            dist: Some(Num(f64::NAN)),
            how: Some(How::Completed),
            count: 1,
        }),
        Event::Pose(Pose {
            x: Num(1.0),
            y: Num(2.0),
            h: Num(-0.5),
            v: Num(0.3),
            c: Num(0.0),
            source: Source::Estimated,
        }),
        Event::Path(Path {
            stmt: stmt(6, "turn(d=90,c=0.5)"),
            points: vec![(1.0, 2.0), (3.25, -0.5)].into(),
        }),
        Event::Avoid(Avoid {
            stmt: stmt(6, "goahead(1)"),
            state: AvoidState::Returning,
        }),
        Event::Fault(Fault {
            stmt: None,
            fault: "obstacle_near".into(),
            code: "R0206".into(),
            reaction: "hold".into(),
            message: "an obstacle 0.25 m ahead".into(),
            help: "move it".into(),
        }),
        Event::Recovered(Recovered {
            stmt: None,
            fault: "obstacle_near".into(),
            code: "R0206".into(),
        }),
        Event::Overrun(Overrun {
            stmt: stmt(2, "while(x>-1)"),
            pending: 1,
        }),
        Event::Error(Error {
            stmt: None,
            message: "division by zero".into(),
        }),
        Event::Mark(Mark {
            line: 4,
            text: "goahead(1.2)".into(),
            at: Moment::End,
            x: Num(19.5),
            y: Num(5.5),
            h: Num(0.0),
            how: Some(How::Broken),
        }),
        Event::Scan(Scan {
            x: Num(20.2),
            y: Num(5.5),
            h: Num(0.0),
            hits: vec![(20.5, 4.08)].into(),
        }),
    ];
    events
        .into_iter()
        .enumerate()
        .map(|(i, e)| Record::new(i as f64 * 0.01, e))
        .collect()
}

#[test]
fn every_event_round_trips() {
    let mut text = String::new();
    for r in every_event() {
        text.push_str(&to_line(&r));
        text.push('\n');
    }
    let back: Vec<Record> = records(&text).collect::<Result<_, _>>().expect("reads");
    assert_eq!(back, every_event());
}

#[test]
fn keys_are_in_the_documented_order() {
    let lines: Vec<String> = every_event().iter().map(to_line).collect();
    assert_eq!(lines[0], r#"{"t":0,"event":"trace","version":1}"#);
    assert_eq!(
        lines[5],
        r#"{"t":0.05,"event":"issue","line":3,"text":"x=x+1","count":25000}"#
    );
    assert_eq!(
        lines[7],
        r#"{"t":0.07,"event":"end","line":4,"text":"goahead(speed=9)","how":"refused","linked":true,"code":"R0101","reason":"too fast","help":"slow down"}"#
    );
    assert_eq!(
        lines[8],
        r#"{"t":0.08,"event":"var","line":5,"text":"x=1e999","var":"x","status":1,"y":"-inf","value":"inf","dist":"nan","how":"completed"}"#
    );
    assert_eq!(
        lines[10],
        r#"{"t":0.1,"event":"path","line":6,"text":"turn(d=90,c=0.5)","points":[[1,2],[3.25,-0.5]]}"#
    );
}

#[test]
fn a_trace_without_its_version_line_is_refused_with_a_code() {
    let old = r#"{"t":0.01,"event":"issue","line":3,"text":"x=1"}"#;
    let err = records(old).next().unwrap().unwrap_err();
    assert_eq!((err.code, err.line), (Code::NoVersion, 1));
    assert!(
        err.to_string()
            .starts_with("line 1: T0102 the first line is not")
    );

    let newer = "\n{\"t\":0,\"event\":\"trace\",\"version\":2,\"units\":\"si\"}\n";
    let err = records(newer).next().unwrap().unwrap_err();
    assert_eq!((err.code, err.line), (Code::UnknownVersion, 2));
    assert!(
        err.message
            .starts_with("the trace has schema version 2; this ilmrc reads version 1"),
        "{}",
        err.message
    );

    let err = records("not json").next().unwrap().unwrap_err();
    assert_eq!(err.code, Code::NotALine);
}

#[test]
fn an_unknown_event_or_a_wrong_key_is_refused() {
    let header = to_line(&Record::header());
    for bad in [
        r#"{"t":1,"event":"teleport","x":1}"#,
        r#"{"t":1,"event":"pose","x":1,"y":2,"h":0,"v":0,"c":0}"#,
        r#"{"t":1,"event":"pose","x":"far","y":2,"h":0,"v":0,"c":0,"source":"true"}"#,
        r#"{"t":1,"event":"var","line":3,"text":"x=1","var":"x","value":1e999}"#,
    ] {
        let text = format!("{header}\n{bad}\n");
        let err = records(&text)
            .find_map(Result::err)
            .unwrap_or_else(|| panic!("{bad} was read"));
        assert_eq!((err.code, err.line), (Code::NotALine, 2), "{bad}");
    }
}

use super::*;

fn stmt(line: u32, text: &str) -> Option<Stmt<'_>> {
    Some(Stmt {
        line,
        text: text.into(),
        file: None,
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
            profile: Some("calibrated".into()),
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
        Event::Tape(tape()),
        Event::Input(Box::new(input(&[0.1 + 0.2, f64::INFINITY]))),
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

fn tape() -> Tape {
    Tape {
        format: INPUT_FORMAT,
        ilmrc: "0.1.0".into(),
        backend: "sim".into(),
        model: "moro".into(),
        body: Some("moro".into()),
        scanner_offset: None,
        pose_every: 10,
        scan_every: Num(1.0),
        max_time: Num(600.0),
        hold_limit: Num(f64::INFINITY),
        paths: vec![TaughtPath {
            name: "P".into(),
            points: vec![(0.0, 0.0), (10.0, 0.0)].into(),
        }],
    }
}

/// One tick's inputs whose numbers are `xs`, with one of every kind of call.
fn input(xs: &[f64]) -> Input {
    let n = |i: usize| Num(xs[i % xs.len()]);
    let at = |i: usize| At {
        x: n(i),
        y: n(i + 1),
        h: n(i + 2),
    };
    let refused = Some(Failure::Refused {
        message: "too fast".into(),
    });
    Input {
        calls: vec![
            Exchange::KnownMap {
                map: Some(Map {
                    bounds: Some((n(0), n(1), n(2), n(3))),
                    solids: vec![Solid {
                        a: (n(4), n(5)),
                        b: (n(6), n(7)),
                        radius: n(8),
                        name: Some("w1".into()),
                    }],
                }),
            },
            Exchange::ActuatorRange {
                id: "arm".into(),
                range: Some((n(9), n(10))),
            },
            Exchange::Update {
                t: n(11),
                error: None,
            },
            Exchange::Snapshot {
                snapshot: Box::new(Snapshot {
                    t: n(12),
                    pose: at(13),
                    true_pose: Some(at(16)),
                    speed: n(19),
                    curvature: n(20),
                    scan: Some(Ranges {
                        device: "scanner".into(),
                        t: n(21),
                        angle_min: n(22),
                        angle_step: n(23),
                        ranges: (0..xs.len()).map(n).collect(),
                    }),
                    scan_kept: false,
                    battery: Some(n(24)),
                    devices: vec![Reading {
                        name: "door".into(),
                        value: None,
                    }],
                    detections: vec![Sighting {
                        sensor: "camera".into(),
                        object: "ball".into(),
                        x: n(25),
                        y: n(26),
                        h: n(27),
                        side: "left".into(),
                    }],
                    odometry_t: Some(n(28)),
                    nav_t: None,
                }),
                error: None,
            },
            Exchange::SetMotion {
                speed: n(29),
                curvature: n(30),
                error: refused.clone(),
            },
            Exchange::Actuator {
                id: "arm".into(),
                value: n(31),
                error: None,
            },
            Exchange::Locmode {
                mode: "gps".into(),
                error: Some(Failure::Unsupported {
                    message: "no gps".into(),
                }),
            },
            Exchange::Bodypose {
                roll: Some(n(32)),
                pitch: None,
                clearance: Some(n(33)),
                error: None,
            },
            Exchange::Locate {
                pose: at(34),
                error: None,
            },
            Exchange::Start {
                op: Operation::Manipulate("take".into()),
                id: Some(3),
                error: None,
            },
            Exchange::Start {
                op: Operation::Init(vec!["a".into()]),
                id: None,
                error: Some(Failure::Timeout {
                    message: "init".into(),
                }),
            },
            Exchange::Poll {
                id: 3,
                status: Some(OpState::Failed("dropped".into())),
                error: None,
            },
            Exchange::Poll {
                id: 9,
                status: None,
                error: Some(Failure::UnknownOp { id: 9 }),
            },
            Exchange::Cancel {
                id: 3,
                error: Some(Failure::Link {
                    message: "lost".into(),
                }),
            },
        ],
        robot: Seen {
            at_rest: false,
            true_pose: Some(at(37)),
            motion: Some((n(40), n(41))),
            contacts: 2,
            scan: Some(PlacedScan {
                t: n(42),
                origin: at(43),
                angle_min: n(46),
                angle_step: n(47),
                max_range: n(48),
                ranges: None,
            }),
        },
    }
}

/// Every number of the recorded inputs reads back as the very `f64` written, bit for
/// bit: the replay feeds them to the VM.
#[test]
fn recorded_inputs_round_trip_exactly() {
    let awkward = [
        0.1 + 0.2,
        1.0 / 3.0,
        -0.0,
        5e-324,
        f64::MAX,
        f64::MIN_POSITIVE,
        19.512_345_678_901_234,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NAN,
        -1e300,
        std::f64::consts::PI,
    ];
    let written = input(&awkward);
    let line = to_line(&Record::new(
        0.1 + 0.2,
        Event::Input(Box::new(written.clone())),
    ));
    let text = format!("{}\n{line}\n", to_line(&Record::header()));
    let back: Vec<Record> = records(&text).collect::<Result<_, _>>().expect("reads");
    let Event::Input(read) = &back[1].event else {
        panic!("not an input: {line}");
    };
    assert_eq!(back[1].t.0.to_bits(), (0.1f64 + 0.2).to_bits());
    let bits = |i: &Input| {
        let json = serde_json::to_value(i).expect("serializes");
        format!("{json}")
    };
    assert_eq!(bits(read), bits(&written));
    let Exchange::Snapshot { snapshot, .. } = &read.calls[3] else {
        panic!("the fourth call is the snapshot");
    };
    let ranges = &snapshot.scan.as_ref().expect("a scan").ranges;
    for (got, want) in ranges.iter().zip(awkward) {
        assert!(
            got.0.to_bits() == want.to_bits() || (got.0.is_nan() && want.is_nan()),
            "{want:e} read back as {:e}",
            got.0
        );
    }
    assert!(line.contains("0.30000000000000004"), "{line}");
    assert!(line.contains("\"-inf\""), "{line}");
}

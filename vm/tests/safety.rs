//! Issue 7's guarantees on the scripted robot: each run-time refusal and its code,
//! every halt through the ramp (the speed setpoint never changes faster than the
//! model allows), and each supervisor reaction driven by what the HAL reports.

mod common;

use common::{A, Asm, X, config, ended, robot, trace, vm, when};
use ilmr_hal::{
    Call, HalError, KnownMap, ManipTask, OpMatch, OpOutcome, Pose, Scan, ScriptedRobot, Solid,
    Stream,
};
use ilmr_stdlib::Command;
use ilmr_vm::bytecode::{ExprOp, Op};
use ilmr_vm::runtime::safety::Fault;
use ilmr_vm::{Config, EventKind};

/// The VM's acceleration and deceleration in `config()`, m/s^2, and its tick.
const RATE: f64 = 0.5;
const DT: f64 = 0.01;

/// The largest change of the speed setpoint between two consecutive calls.
fn largest_step(setpoints: &[(f64, f64)]) -> f64 {
    setpoints
        .windows(2)
        .map(|w| (w[1].0 - w[0].0).abs())
        .fold(0.0, f64::max)
}

fn assert_ramped(vm: &common::TestVm) {
    let step = largest_step(vm.hal().setpoints());
    assert!(
        step <= RATE * DT + 1e-9,
        "the speed setpoint jumped by {step} m/s in one tick (at most {})",
        RATE * DT
    );
    let last = vm.hal().setpoints().last().copied().unwrap_or_default();
    assert_eq!(last, (0.0, 0.0), "it ends at rest");
}

/// The stable code of the `end` event of the statement with `text`.
fn code(vm: &common::TestVm, text: &str) -> Option<&'static str> {
    vm.events().iter().find_map(|e| {
        let s = e.stmt.and_then(|s| vm.module().stmt(s))?;
        match &e.kind {
            EventKind::End { code, .. } if s.text == text => code.map(|c| c.code()),
            _ => None,
        }
    })
}

/// The reason in the `end` event of the statement with `text`.
fn reason(vm: &common::TestVm, text: &str) -> Option<String> {
    vm.events().iter().find_map(|e| {
        let s = e.stmt.and_then(|s| vm.module().stmt(s))?;
        match &e.kind {
            EventKind::End { reason, .. } if s.text == text => reason.clone(),
            _ => None,
        }
    })
}

/// `(t, fault name)` of every `fault` and `recovered` event, in order.
fn faults(vm: &common::TestVm) -> Vec<(String, f64, &'static str)> {
    vm.events()
        .iter()
        .filter_map(|e| match &e.kind {
            EventKind::Fault { fault, .. } => Some(("fault".into(), round(e.t), fault.name())),
            EventKind::Recovered { fault } => Some(("recovered".into(), round(e.t), fault.name())),
            _ => None,
        })
        .collect()
}

/// Event times to the tick, for comparing.
fn round(t: f64) -> f64 {
    (t * 100.0).round() / 100.0
}

fn scan(t: f64, ahead: f64) -> Scan {
    let n = 181;
    let mut ranges = vec![30.0; n];
    ranges[n / 2] = ahead;
    Scan {
        device: "scanner".into(),
        t,
        angle_min: -std::f64::consts::FRAC_PI_2,
        angle_step: std::f64::consts::PI / (n - 1) as f64,
        ranges,
    }
}

/// Runs until everything has ended and the robot is at rest (a halt ramp may go
/// on after the last command).
fn settle(vm: &mut common::TestVm, seconds: f64) {
    for _ in 0..(seconds / DT) as usize {
        if vm.finished() && vm.activity().robot_at_rest {
            return;
        }
        vm.tick();
    }
}

#[test]
fn a_computed_speed_beyond_max_speed_is_refused_and_the_old_one_stays() {
    let mut a = Asm::new();
    let code_ = vec![
        a.assign("s=0.6*3", "s", &[X::N(0.6), X::N(3.0), X::Op(ExprOp::Mul)]),
        a.cmd("speed(s)", Command::Speed, &[A::V("s")], None),
        a.cmd("m=goahead(0.5)", Command::Goahead, &[A::N(0.5)], Some("m")),
    ];
    let b = a.block(code_);
    let cfg = Config {
        safety: ilmr_vm::runtime::safety::Safety {
            max_speed: 0.6,
            ..config().safety
        },
        ..config()
    };
    let mut vm = vm(a.task(&[b]), robot(), cfg);
    settle(&mut vm, 10.0);
    assert_eq!(ended(&vm, "speed(s)").as_deref(), Some("refused"));
    assert_eq!(code(&vm, "speed(s)"), Some("R0101"));
    let fastest = vm
        .hal()
        .setpoints()
        .iter()
        .map(|s| s.0.abs())
        .fold(0.0, f64::max);
    assert!(
        fastest <= 0.3 + 1e-9,
        "drove at the default speed: {fastest}"
    );
    assert_eq!(ended(&vm, "m=goahead(0.5)").as_deref(), Some("completed"));
    insta::assert_snapshot!(trace(&vm));
}

#[test]
fn actuator_values_and_body_poses_outside_their_limits_are_refused() {
    let mut a = Asm::new();
    let code_ = vec![
        a.assign(
            "deg=90+100",
            "deg",
            &[X::N(90.0), X::N(100.0), X::Op(ExprOp::Add)],
        ),
        a.cmd(
            "actuator(leg1,deg)",
            Command::Actuator,
            &[A::W("leg1"), A::V("deg")],
            None,
        ),
        a.cmd(
            "actuator(leg2,120)",
            Command::Actuator,
            &[A::W("leg2"), A::N(120.0)],
            None,
        ),
        a.cmd(
            "bodypose(r=45)",
            Command::BodyPose,
            &[A::S("r", 45.0)],
            None,
        ),
        a.cmd(
            "bodypose(rc=0.5)",
            Command::BodyPose,
            &[A::S("rc", 0.5)],
            None,
        ),
    ];
    let b = a.block(code_);
    let r = robot()
        .actuator_range("leg1", 0.0, 180.0)
        .actuator_range("leg2", 0.0, 180.0);
    let mut vm = vm(a.task(&[b]), r, config());
    settle(&mut vm, 1.0);
    assert_eq!(code(&vm, "actuator(leg1,deg)"), Some("R0102"));
    assert_eq!(
        ended(&vm, "actuator(leg2,120)"),
        None,
        "in range: instant, not refused"
    );
    assert_eq!(vm.hal().actuator_log(), &[("leg2".to_string(), 120.0)]);
    assert_eq!(code(&vm, "bodypose(r=45)"), Some("R0103"));
    assert_eq!(vm.hal().current_bodypose().clearance, Some(0.5));
    assert_eq!(
        vm.hal().current_bodypose().roll,
        None,
        "the refused pose never reached it"
    );
}

#[test]
fn a_body_pose_the_movement_mode_forbids_is_refused() {
    let mut a = Asm::new();
    let code_ = vec![
        a.cmd(
            "movemode(rolking)",
            Command::MoveMode,
            &[A::W("rolking")],
            None,
        ),
        a.wait("wait(0.1)", 0.1),
        a.cmd(
            "bodypose(r=10)",
            Command::BodyPose,
            &[A::S("r", 10.0)],
            None,
        ),
        a.cmd(
            "bodypose(rc=0.4)",
            Command::BodyPose,
            &[A::S("rc", 0.4)],
            None,
        ),
        a.cmd(
            "movemode(parking)",
            Command::MoveMode,
            &[A::W("parking")],
            None,
        ),
        a.wait("wait(0.2)", 0.2),
        a.cmd(
            "bodypose(rc=0.6)",
            Command::BodyPose,
            &[A::S("rc", 0.6)],
            None,
        ),
        a.cmd("goahead(1)", Command::Goahead, &[A::N(1.0)], None),
    ];
    let b = a.block(code_);
    let mut vm = vm(a.task(&[b]), robot(), config());
    settle(&mut vm, 2.0);
    assert_eq!(
        code(&vm, "bodypose(r=10)"),
        Some("R0104"),
        "rolking keeps the body level"
    );
    assert_eq!(ended(&vm, "bodypose(rc=0.4)"), None);
    assert_eq!(
        code(&vm, "bodypose(rc=0.6)"),
        Some("R0104"),
        "parking locks every joint"
    );
    assert_eq!(code(&vm, "goahead(1)"), Some("R0109"));
    assert_eq!(vm.hal().current_bodypose().clearance, Some(0.4));
    assert!(vm.hal().setpoints().is_empty(), "nothing moved");
}

#[test]
fn gotoxy_targets_in_walls_off_the_map_or_on_obstacles_are_refused() {
    let mut a = Asm::new();
    let code_ = vec![a.assign("x=1.5*2", "x", &[X::N(1.5), X::N(2.0), X::Op(ExprOp::Mul)])];
    let x = a.expr(&[X::V("x")]);
    let code_ = [
        code_,
        vec![
            a.cmd("gotoxy(x,1)", Command::GotoXY, &[A::E(x), A::N(1.0)], None),
            a.cmd(
                "gotoxy(1,9)",
                Command::GotoXY,
                &[A::N(1.0), A::N(9.0)],
                None,
            ),
            a.cmd(
                "gotorelxy(2.8,0)",
                Command::GotoRelXY,
                &[A::N(2.8), A::N(0.0)],
                None,
            ),
            a.cmd(
                "gotoxy(1.5,0)",
                Command::GotoXY,
                &[A::N(1.5), A::N(0.0)],
                None,
            ),
        ],
    ]
    .concat();
    let b = a.block(code_);
    let map = KnownMap {
        bounds: Some((-1.0, -4.0, 6.0, 4.0)),
        solids: vec![Solid {
            a: (2.5, 1.0),
            b: (3.5, 1.0),
            radius: 0.05,
            name: Some("desk_front".into()),
        }],
    };
    // One scanned point 2 m in front of the scanner, 0.85 m ahead of the robot.
    let r = robot().known_map(map).scan(scan(0.0, 2.0));
    let mut vm = vm(a.task(&[b]), r, config());
    vm.tick();
    let at_start: Vec<_> = vm.hal().setpoints().to_vec();
    settle(&mut vm, 20.0);
    assert_eq!(code(&vm, "gotoxy(x,1)"), Some("R0105"));
    let why = reason(&vm, "gotoxy(x,1)").unwrap();
    assert!(why.contains("from the wall `desk_front`"), "{why}");
    assert_eq!(code(&vm, "gotoxy(1,9)"), Some("R0106"));
    assert_eq!(code(&vm, "gotorelxy(2.8,0)"), Some("R0107"));
    assert!(
        at_start.is_empty(),
        "the refused targets never moved the robot"
    );
    assert_eq!(ended(&vm, "gotoxy(1.5,0)").as_deref(), Some("completed"));
    insta::assert_snapshot!(trace(&vm));
}

#[test]
fn a_target_the_robot_cannot_turn_to_is_refused_with_its_way_out() {
    let mut a = Asm::new();
    // 1 mm ahead and facing back: the direct curve bends far beyond max_curvature.
    let go = a.cmd(
        "gotoxy(0.001,0,180)",
        Command::GotoXY,
        &[A::N(0.001), A::N(0.0), A::N(180.0)],
        None,
    );
    let b = a.block(vec![go]);
    let mut vm = vm(a.task(&[b]), robot(), config());
    settle(&mut vm, 5.0);
    assert_eq!(code(&vm, "gotoxy(0.001,0,180)"), Some("R0110"));
    let why = reason(&vm, "gotoxy(0.001,0,180)").unwrap();
    assert!(why.contains("the robot turns at most"), "{why}");
    let line = trace(&vm);
    assert!(
        line.contains(r#""code":"R0110""#)
            && line.contains(r#""help":"give a heading the robot can reach"#),
        "{line}"
    );
}

/// `goahead(4)` at 0.5 m/s, and a second block that does `halt` after 1.5 s.
fn halted_by(halt: impl FnOnce(&mut Asm) -> Vec<ilmr_vm::bytecode::Instr>) -> common::TestVm {
    let mut a = Asm::new();
    let one = vec![
        a.cmd("speed(0.5)", Command::Speed, &[A::N(0.5)], None),
        a.cmd("m=goahead(4)", Command::Goahead, &[A::N(4.0)], Some("m")),
    ];
    let b1 = a.block(one);
    a.blank();
    let mut two = vec![a.wait("wait(1.5)", 1.5)];
    two.extend(halt(&mut a));
    let b2 = a.block(two);
    let mut vm = vm(a.task(&[b1, b2]), robot(), config());
    settle(&mut vm, 20.0);
    vm
}

#[test]
fn break_brakes_within_the_deceleration_and_a_new_movement_can_go_on() {
    let mut vm = halted_by(|a| vec![a.op("break", Op::BreakAll)]);
    assert_eq!(ended(&vm, "m=goahead(4)").as_deref(), Some("broken"));
    assert_ramped(&vm);
    // A new line after the break drives again.
    let mut a = Asm::extending(vm.module(), "line.ilmr");
    let line = vec![a.cmd(
        "again=goahead(-0.5)",
        Command::Goahead,
        &[A::N(-0.5)],
        Some("again"),
    )];
    let b = a.block(line);
    vm.add_block(&a.fragment(&[b])).expect("joins");
    settle(&mut vm, 10.0);
    assert_eq!(
        ended(&vm, "again=goahead(-0.5)").as_deref(),
        Some("completed")
    );
    assert_ramped(&vm);
}

#[test]
fn break_of_a_pattern_and_priority_brake_the_same_way() {
    let vm = halted_by(|a| vec![a.brk("break(goahead)", "goahead")]);
    assert_eq!(ended(&vm, "m=goahead(4)").as_deref(), Some("broken"));
    // 0.5 m/s braked at 0.5 m/s^2 goes 0.25 m on: the ramp, not a jump.
    let x = vm.hal().true_pose().x;
    let at_break = vm.var("m").map_or(0.0, |m| m.x);
    assert!(
        x - at_break > 0.2,
        "rolled {} m after the break",
        x - at_break
    );
    assert_ramped(&vm);

    let vm = halted_by(|a| {
        vec![a.if_(
            "if(1==1)",
            &[X::N(1.0), X::N(1.0), X::Op(ExprOp::Eq)],
            |a| vec![a.op("priority=highest", Op::Priority)],
        )]
    });
    assert_eq!(ended(&vm, "m=goahead(4)").as_deref(), Some("broken"));
    assert_ramped(&vm);
}

#[test]
fn stop_brakes_within_the_deceleration_and_cont_goes_on() {
    let vm = halted_by(|a| {
        vec![
            a.op("stop", Op::Stop),
            a.wait("wait(2)", 2.0),
            a.op("cont", Op::Cont),
        ]
    });
    assert_eq!(ended(&vm, "m=goahead(4)").as_deref(), Some("completed"));
    assert!(
        vm.hal().setpoints().iter().any(|s| s.0 == 0.0),
        "stood still"
    );
    assert_ramped(&vm);
}

#[test]
fn a_lost_scanner_holds_the_movement_until_scans_return() {
    let mut a = Asm::new();
    let code_ = vec![
        a.cmd("speed(0.5)", Command::Speed, &[A::N(0.5)], None),
        a.cmd("m=goahead(3)", Command::Goahead, &[A::N(3.0)], Some("m")),
    ];
    let b = a.block(code_);
    let r = robot()
        .scan_every(0.25, scan(0.0, 30.0))
        .dropout(Stream::Scanner, 2.0, 5.0);
    let mut vm = vm(a.task(&[b]), r, config());
    vm.run_for(4.5);
    assert!(vm.fault_active(Fault::ScannerLost));
    assert_eq!(vm.supervisor_reading(), 2.0);
    assert!(vm.hal().speed().abs() < 1e-9, "held at rest");
    settle(&mut vm, 20.0);
    assert_eq!(
        faults(&vm),
        [
            ("fault".into(), 3.26, "scanner_lost"),
            ("recovered".into(), 5.0, "scanner_lost")
        ]
    );
    assert_eq!(ended(&vm, "m=goahead(3)").as_deref(), Some("completed"));
    assert_ramped(&vm);
    insta::assert_snapshot!(trace(&vm));
}

#[test]
fn lost_odometry_ends_the_movement_and_refuses_movement_until_it_returns() {
    let mut a = Asm::new();
    let one = vec![a.cmd("m=goahead(3)", Command::Goahead, &[A::N(3.0)], Some("m"))];
    let b1 = a.block(one);
    a.blank();
    let two = vec![
        a.wait("wait(2)", 2.0),
        a.cmd("n=goahead(0.5)", Command::Goahead, &[A::N(0.5)], Some("n")),
        a.wait("wait(2)", 2.0),
        a.cmd("o=goahead(0.5)", Command::Goahead, &[A::N(0.5)], Some("o")),
    ];
    let b2 = a.block(two);
    let r = robot()
        .odometry_every(0.1)
        .dropout(Stream::Odometry, 1.0, 3.0);
    let mut vm = vm(a.task(&[b1, b2]), r, config());
    settle(&mut vm, 20.0);
    assert_eq!(code(&vm, "m=goahead(3)"), Some("R0203"));
    assert_eq!(code(&vm, "n=goahead(0.5)"), Some("R0108"));
    assert_eq!(ended(&vm, "o=goahead(0.5)").as_deref(), Some("completed"));
    assert_eq!(
        faults(&vm),
        [
            ("fault".into(), 1.4, "odometry_lost"),
            ("recovered".into(), 3.0, "odometry_lost")
        ]
    );
    assert_ramped(&vm);
    insta::assert_snapshot!(trace(&vm));
}

#[test]
fn a_missing_navigation_fix_slows_the_robot_down() {
    let mut a = Asm::new();
    let code_ = vec![
        a.cmd("speed(0.5)", Command::Speed, &[A::N(0.5)], None),
        a.cmd("m=goahead(3)", Command::Goahead, &[A::N(3.0)], Some("m")),
    ];
    let b = a.block(code_);
    let r = robot().nav_every(0.5).dropout(Stream::Nav, 1.5, 4.0);
    let cfg = Config {
        safety: ilmr_vm::runtime::safety::Safety {
            nav_timeout: Some(1.0),
            ..config().safety
        },
        ..config()
    };
    let mut vm = vm(a.task(&[b]), r, cfg);
    vm.run_for(3.5);
    assert!(vm.fault_active(Fault::NavLost));
    assert!(
        (vm.hal().speed() - 0.1).abs() < 1e-9,
        "degraded_speed: {}",
        vm.hal().speed()
    );
    settle(&mut vm, 20.0);
    assert_eq!(ended(&vm, "m=goahead(3)").as_deref(), Some("completed"));
    assert_eq!(
        faults(&vm),
        [
            ("fault".into(), 2.01, "nav_lost"),
            ("recovered".into(), 4.0, "nav_lost")
        ]
    );
    assert_ramped(&vm);
}

#[test]
fn a_task_watches_the_supervisor_through_a_sensor_reading() {
    let mut a = Asm::new();
    let code_ = vec![
        a.cmd(
            "F=sensor(supervisor)",
            Command::Sensor,
            &[A::W("supervisor")],
            Some("F"),
        ),
        a.if_(
            "if(F==1)",
            &[X::V("F"), X::N(1.0), X::Op(ExprOp::Eq)],
            |a| vec![a.assign("charge=1", "charge", &[X::N(1.0)])],
        ),
    ];
    let b = a.block(code_);
    let r = robot()
        .battery(0.0, 24.0)
        .battery(1.0, 22.8)
        .battery(2.0, 23.05);
    let mut vm = vm(a.task(&[b]), r, config());
    vm.run_for(3.0);
    assert_eq!(when(&vm, "start", "if(F==1)"), Some(1.0));
    assert_eq!(vm.var("charge").map(|v| v.value), Some(1.0));
    assert_eq!(
        faults(&vm),
        [("fault".into(), 1.0, "battery_low")],
        "23.05 V is within the hysteresis: still low"
    );
    insta::assert_snapshot!(trace(&vm));
}

#[test]
fn an_obstacle_inside_the_stopping_distance_stops_the_robot_short_of_it() {
    let mut a = Asm::new();
    let code_ = vec![
        a.cmd("speed(0.5)", Command::Speed, &[A::N(0.5)], None),
        a.cmd("m=goahead(5)", Command::Goahead, &[A::N(5.0)], Some("m")),
    ];
    let b = a.block(code_);
    // The obstacle is 2 m in front of the scanner at the start: at x = 2.85.
    let mut vm = vm(a.task(&[b]), robot().scan(scan(0.0, 2.0)), config());
    vm.run_for(8.0);
    let front = vm.hal().true_pose().x + config().front_offset;
    assert!(vm.hal().speed().abs() < 1e-9);
    assert!(
        // stop_margin, plus the 5 cm skin of the swept outline, plus a tick.
        (2.85 - 0.2 - 0.05 - 0.06..2.85).contains(&front),
        "stands about stop_margin short of the obstacle: front at {front}"
    );
    assert!(vm.fault_active(Fault::ObstacleNear));
    assert_eq!(vm.supervisor_reading(), 6.0);
    assert_ramped(&vm);
}

#[test]
fn a_localization_jump_ends_the_movement_and_clears_when_at_rest() {
    let mut a = Asm::new();
    let code_ = vec![
        a.cmd("speed(0.5)", Command::Speed, &[A::N(0.5)], None),
        a.cmd("m=goahead(3)", Command::Goahead, &[A::N(3.0)], Some("m")),
    ];
    let b = a.block(code_);
    let r = robot().jump(1.5, Pose::new(1.0, 0.5, 0.0));
    let mut vm = vm(a.task(&[b]), r, config());
    settle(&mut vm, 10.0);
    assert_eq!(code(&vm, "m=goahead(3)"), Some("R0205"));
    assert_eq!(when(&vm, "end", "m=goahead(3)"), Some(1.5));
    let seen = faults(&vm);
    assert_eq!(seen.len(), 2, "{seen:?}");
    assert_eq!(seen[0], ("fault".into(), 1.5, "localization_jump"));
    assert_eq!(seen[1].2, "localization_jump");
    assert_ramped(&vm);
}

#[test]
fn an_operation_that_never_answers_is_cancelled_and_refused() {
    let mut a = Asm::new();
    let code_ = vec![a.cmd(
        "ok=manipulate(take)",
        Command::Manipulate,
        &[A::W("take")],
        Some("ok"),
    )];
    let b = a.block(code_);
    let r = robot().op(
        OpMatch::Manipulate(ManipTask::Take),
        u32::MAX,
        OpOutcome::Done,
    );
    let cfg = Config {
        safety: ilmr_vm::runtime::safety::Safety {
            operation_timeout: Some(2.0),
            ..config().safety
        },
        ..config()
    };
    let mut vm = vm(a.task(&[b]), r, cfg);
    assert!(vm.run_for(5.0));
    assert_eq!(code(&vm, "ok=manipulate(take)"), Some("R0207"));
    assert_eq!(when(&vm, "end", "ok=manipulate(take)"), Some(2.0));
    assert_eq!(vm.hal().cancelled().len(), 1);
    insta::assert_snapshot!(trace(&vm));
}

#[test]
fn failing_robot_calls_are_recorded_and_the_tick_goes_on() {
    let mut a = Asm::new();
    let code_ = vec![
        a.cmd("speed(0.5)", Command::Speed, &[A::N(0.5)], None),
        a.cmd("m=goahead(2)", Command::Goahead, &[A::N(2.0)], Some("m")),
    ];
    let b = a.block(code_);
    let r = robot()
        .fail(Call::Snapshot, 1.0, 1.5, HalError::Link("cable".into()))
        .fail(Call::Update, 3.0, 3.05, HalError::Link("cable".into()));
    let mut vm = vm(a.task(&[b]), r, config());
    settle(&mut vm, 20.0);
    assert_eq!(ended(&vm, "m=goahead(2)").as_deref(), Some("completed"));
    let errors = vm
        .events()
        .iter()
        .filter(|e| matches!(e.kind, EventKind::Error { .. }))
        .count();
    assert_eq!(errors, 50 + 5, "every failed call is in the trace");
    assert_eq!(
        faults(&vm)
            .iter()
            .filter(|f| f.0 == "fault" && f.2 == "robot_link")
            .count(),
        2
    );
    assert_ramped(&vm);
}

#[test]
fn a_drive_that_comes_back_is_told_to_stand_still() {
    // The drive takes no setpoint while the robot brakes for the goal; the VM
    // comes to rest in its own books, and must still tell the drive 0 once it
    // answers again, or the drive goes on with the last speed it took.
    let mut a = Asm::new();
    let code_ = vec![
        a.cmd("speed(0.5)", Command::Speed, &[A::N(0.5)], None),
        a.cmd("m=goahead(1)", Command::Goahead, &[A::N(1.0)], Some("m")),
    ];
    let b = a.block(code_);
    let r = robot().fail(Call::SetMotion, 1.5, 4.0, HalError::Link("drive".into()));
    let mut vm = vm(a.task(&[b]), r, config());
    // Ticks on after the task has finished: the drive is what is watched.
    for _ in 0..800 {
        vm.tick();
    }
    assert!(
        vm.hal().speed().abs() < 1e-9,
        "the drive stands: {} m/s",
        vm.hal().speed()
    );
    assert_eq!(vm.hal().setpoints().last().map(|s| s.0), Some(0.0));
}

#[test]
fn refused_runs_leave_the_robot_where_it_stood() {
    // The scripted robot refuses nothing by itself: what is refused is the VM's.
    let r = ScriptedRobot::new(ilmr_hal::Limits::default());
    let mut a = Asm::new();
    let code_ = vec![a.cmd("speed(-5)", Command::Speed, &[A::N(-5.0)], None)];
    let b = a.block(code_);
    let mut vm = vm(a.task(&[b]), r, config());
    assert!(vm.run_for(1.0));
    assert_eq!(code(&vm, "speed(-5)"), Some("R0101"));
    assert_eq!(vm.hal().true_pose(), Pose::default());
}

/// A driver whose snapshot blocks forever from one second on.
struct Hangs {
    inner: ScriptedRobot,
    t: f64,
}

impl ilmr_hal::Hal for Hangs {
    fn update(&mut self, t: f64) -> Result<(), HalError> {
        self.t = t;
        self.inner.update(t)
    }
    fn snapshot(&mut self, out: &mut ilmr_hal::Snapshot) -> Result<(), HalError> {
        if self.t >= 1.0 {
            loop {
                std::thread::park();
            }
        }
        self.inner.snapshot(out)
    }
    fn set_motion(&mut self, v: f64, c: f64) -> Result<(), HalError> {
        self.inner.set_motion(v, c)
    }
    fn actuator(&mut self, id: &str, value: f64) -> Result<(), HalError> {
        self.inner.actuator(id, value)
    }
    fn locmode(&mut self, mode: &str) -> Result<(), HalError> {
        self.inner.locmode(mode)
    }
    fn bodypose(&mut self, pose: ilmr_hal::BodyPose) -> Result<(), HalError> {
        self.inner.bodypose(pose)
    }
    fn locate(&mut self, pose: Pose) -> Result<(), HalError> {
        self.inner.locate(pose)
    }
    fn start(&mut self, op: &ilmr_hal::AsyncOp) -> Result<ilmr_hal::OpId, HalError> {
        self.inner.start(op)
    }
    fn poll(&mut self, op: ilmr_hal::OpId) -> Result<ilmr_hal::OpStatus, HalError> {
        self.inner.poll(op)
    }
}

#[test]
fn a_driver_that_hangs_does_not_stop_the_tick() {
    let mut a = Asm::new();
    let code_ = vec![a.cmd("m=goahead(3)", Command::Goahead, &[A::N(3.0)], Some("m"))];
    let b = a.block(code_);
    let driver = Hangs {
        inner: robot(),
        t: 0.0,
    };
    let hal = ilmr_hal::Deadline::spawn(driver, std::time::Duration::from_millis(20));
    let mut vm = ilmr_vm::Vm::new(a.task(&[b]), hal, ilmr_vm::SimClock, config()).expect("valid");
    let started = std::time::Instant::now();
    for _ in 0..300 {
        vm.tick();
    }
    assert_eq!(vm.ticks(), 300);
    assert!(
        started.elapsed() < std::time::Duration::from_secs(5),
        "one deadline, then every call fails fast: {:?}",
        started.elapsed()
    );
    assert!(vm.fault_active(Fault::RobotLink));
    assert_eq!(vm.supervisor_reading(), 8.0);
    let errors = vm
        .events()
        .iter()
        .filter(
            |e| matches!(&e.kind, EventKind::Error { message } if message.contains("no answer")),
        )
        .count();
    assert!(errors >= 200, "each failed call is recorded: {errors}");
}

#[test]
fn every_code_and_fault_is_documented() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/reliability.md");
    let doc = std::fs::read_to_string(path).expect("docs/reliability.md");
    for c in ilmr_vm::runtime::safety::CODES {
        assert!(
            doc.contains(&format!("| {} |", c.code())),
            "{} is not in the table",
            c.code()
        );
    }
    for f in ilmr_vm::runtime::safety::FAULTS {
        assert!(
            doc.contains(&format!("| `{}` |", f.name())),
            "{} is not in the table",
            f.name()
        );
        assert!(doc.contains(f.reaction().name().split('_').next().unwrap_or("")));
    }
    assert!(doc.contains("## Fault injection and soak figures"));
}

#[test]
fn every_code_has_its_way_out_in_the_docs() {
    const START: &str = "<!-- ways out: generated from vm/src/runtime/safety/codes.rs -->\n";
    const END: &str = "<!-- end of ways out -->";
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/reliability.md");
    let doc = std::fs::read_to_string(path).expect("docs/reliability.md");
    let table = ilmr_vm::runtime::safety::ways_out_markdown();
    let (Some(a), Some(b)) = (doc.find(START), doc.find(END)) else {
        panic!("docs/reliability.md has no ways-out table");
    };
    let fresh = format!("{}{START}{table}{}", &doc[..a], &doc[b..]);
    let doc = if std::env::var_os("UPDATE_DOCS").is_some() {
        std::fs::write(path, &fresh).unwrap();
        fresh.clone()
    } else {
        doc
    };
    assert!(
        doc == fresh,
        "the ways-out table is stale: run `UPDATE_DOCS=1 cargo test -p ilmr-vm --test safety`"
    );
}

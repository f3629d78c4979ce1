//! One small hand-built program per rule of the execution model, run on the
//! ScriptedRobot, checked by plain assertions and by a snapshot of the trace.

mod common;

use common::{A, Asm, X, config, ended, robot, trace, vm, when};
use ilmr_hal::{Detection, OpMatch, OpOutcome, Side};
use ilmr_stdlib::{Command, Field, VarKind};
use ilmr_vm::bytecode::{ExprOp, Op};
use ilmr_vm::{Config, TraceLevel};

#[test]
fn movements_start_in_issue_order_and_other_statements_go_on() {
    let mut a = Asm::new();
    let code = vec![
        a.cmd("speed(0.5)", Command::Speed, &[A::N(0.5)], None),
        a.cmd(
            "first=goahead(1)",
            Command::Goahead,
            &[A::N(1.0)],
            Some("first"),
        ),
        a.cmd(
            "second=goahead(0.5)",
            Command::Goahead,
            &[A::N(0.5)],
            Some("second"),
        ),
        a.assign("after=1", "after", &[X::N(1.0)]),
    ];
    let b = a.block(code);
    let m = a.task(&[b]);
    let mut vm = vm(m, robot(), config());
    assert!(vm.run_for(10.0), "task ends");
    let first_end = when(&vm, "end", "first=goahead(1)").expect("first ends");
    let second_start = when(&vm, "start", "second=goahead(0.5)").expect("second starts");
    assert_eq!(
        when(&vm, "var", "after=1"),
        Some(0.0),
        "not held by the queue"
    );
    assert!(
        second_start >= first_end,
        "second waits for the reservation"
    );
    let first = vm.var("first").expect("bound");
    assert!(
        (first.dist - 1.0).abs() < 0.6,
        "first drove about 1 m: {first:?}"
    );
    insta::assert_snapshot!(trace(&vm));
}

#[test]
fn a_wait_holds_only_its_own_block() {
    let mut a = Asm::new();
    let one = vec![a.wait("wait(1)", 1.0), a.assign("x=1", "x", &[X::N(1.0)])];
    let b1 = a.block(one);
    a.blank();
    let two = vec![a.assign("y=1", "y", &[X::N(1.0)])];
    let b2 = a.block(two);
    let mut vm = vm(a.task(&[b1, b2]), robot(), config());
    assert!(vm.run_for(3.0));
    assert_eq!(when(&vm, "var", "y=1"), Some(0.0));
    assert_eq!(when(&vm, "var", "x=1"), Some(1.0));
    insta::assert_snapshot!(trace(&vm));
}

#[test]
fn a_guard_fires_once_when_its_reading_drops() {
    let mut a = Asm::new();
    let code = vec![
        a.cmd(
            "b=sensor(battery)",
            Command::Sensor,
            &[A::W("battery")],
            Some("b"),
        ),
        a.if_(
            "if(b<24)",
            &[X::V("b"), X::N(24.0), X::Op(ExprOp::Lt)],
            |a| {
                vec![
                    a.wait("wait(1)", 1.0),
                    a.assign(
                        "low=low+1",
                        "low",
                        &[X::V("low"), X::N(1.0), X::Op(ExprOp::Add)],
                    ),
                ]
            },
        ),
    ];
    let b = a.block(code);
    let r = robot()
        .battery(0.0, 25.0)
        .battery(1.5, 23.5)
        .battery(2.0, 23.0);
    let mut vm = vm(a.task(&[b]), r, config());
    assert!(vm.run_for(4.0), "the if ends when its body has");
    assert_eq!(when(&vm, "start", "if(b<24)"), Some(1.5));
    assert_eq!(vm.var("low").map(|v| v.value), Some(1.0), "body runs once");
    assert_eq!(
        vm.var("b").map(|v| v.value),
        Some(23.0),
        "b keeps following"
    );
    insta::assert_snapshot!(trace(&vm));
}

#[test]
fn a_while_counts_and_reevaluates_after_each_iteration() {
    let mut a = Asm::new();
    let code = vec![
        a.assign("cnt=0", "cnt", &[X::N(0.0)]),
        a.while_(
            "loop=while(cnt<3)",
            &[X::V("cnt"), X::N(3.0), X::Op(ExprOp::Lt)],
            Some("loop"),
            |a| {
                vec![
                    a.wait("wait(0.1)", 0.1),
                    a.assign(
                        "cnt=cnt+1",
                        "cnt",
                        &[X::V("cnt"), X::N(1.0), X::Op(ExprOp::Add)],
                    ),
                ]
            },
        ),
        a.wait_var("wait(loop)", "loop"),
        a.assign("done=cnt", "done", &[X::V("cnt")]),
    ];
    let b = a.block(code);
    let mut vm = vm(a.task(&[b]), robot(), config());
    assert!(vm.run_for(2.0));
    assert_eq!(vm.var("done").map(|v| v.value), Some(3.0));
    assert_eq!(when(&vm, "var", "done=cnt"), Some(0.3));
    insta::assert_snapshot!(trace(&vm));
}

#[test]
fn a_loop_steps_in_place_and_a_suspended_one_ends_cleanly() {
    // Each iteration reuses the loop's body block and the block sleeps in its own
    // wait: after the first iterations the run-time state neither grows nor shrinks.
    let counting = |a: &mut Asm| {
        let code = vec![
            a.assign("n=0", "n", &[X::N(0.0)]),
            count_to(a, "n", 50.0, 0.01),
        ];
        a.block(code)
    };
    let mut a = Asm::new();
    let b = counting(&mut a);
    let mut vm = vm(a.task(&[b]), robot(), config());
    vm.tick();
    vm.tick();
    let (live, bytes) = (vm.live(), vm.footprint());
    assert_eq!(live, 4, "the block, the while, its body and the wait");
    for _ in 0..40 {
        vm.tick();
        assert_eq!((vm.live(), vm.footprint()), (live, bytes));
    }
    assert!(vm.run_for(1.0));
    assert_eq!(vm.var("n").map(|v| v.value), Some(50.0));
    assert_eq!(vm.live(), 0);

    // Under a budget of 3 ops a tick the loop is suspended between statements; a
    // break ends it wherever it stands, and nothing of it is left (the first part
    // ended a while whose body was parked).
    let mut a = Asm::new();
    let b1 = counting(&mut a);
    a.blank();
    let two = vec![a.wait("wait(0.2)", 0.2), a.brk("break(while)", "while")];
    let b2 = a.block(two);
    let cfg = Config {
        budget_ops: 3,
        ..config()
    };
    let mut vm = common::vm(a.task(&[b1, b2]), robot(), cfg);
    assert!(vm.run_for(1.0), "the loop was broken");
    assert_eq!(ended(&vm, "while(n<50)").as_deref(), Some("broken"));
    let n = vm.var("n").map_or(0.0, |v| v.value);
    assert!(n > 1.0 && n < 50.0, "{n}");
    assert_eq!((vm.live(), vm.activity().ready), (0, 0));
    assert!(vm.events().iter().any(|e| e.kind.name() == "overrun"));
}

#[test]
fn break_ends_every_live_command_whose_text_matches() {
    let mut a = Asm::new();
    let one = vec![
        a.cmd("d=goahead()", Command::Goahead, &[], Some("d")),
        a.cmd(
            "door=sensor(scanner,door)",
            Command::Sensor,
            &[A::W("scanner"), A::W("door")],
            Some("door"),
        ),
    ];
    let b1 = a.block(one);
    a.blank();
    let two = vec![a.wait("wait(1)", 1.0), a.brk("break(GoAhead)", "GoAhead")];
    let b2 = a.block(two);
    let mut vm = vm(a.task(&[b1, b2]), robot(), config());
    vm.run_for(2.0);
    assert_eq!(ended(&vm, "d=goahead()").as_deref(), Some("broken"));
    assert_eq!(
        ended(&vm, "door=sensor(scanner,door)"),
        None,
        "the search goes on"
    );
    let d = vm.var("d").expect("bound");
    assert_eq!((d.status, d.how), (1.0, Some(ilmr_vm::How::Broken)));
    assert!(d.dist > 0.1);
    insta::assert_snapshot!(trace(&vm));
}

#[test]
fn breaking_a_wait_of_time_wakes_its_block_and_its_old_timer_stays_silent() {
    // A block sleeps in its own `wait(seconds)` (no node of its own): `break` must
    // still find it by its text, end it with its variable, and resume the block; the
    // broken wait's timer (due at 0.5 s) must not cut the next wait (due at 0.7 s).
    let mut a = Asm::new();
    let bound = a.wait_bound("w=wait(0.5)", 0.5, "w");
    let one = vec![
        bound,
        a.assign("x=1", "x", &[X::N(1.0)]),
        a.wait("wait(0.6)", 0.6),
        a.assign("y=1", "y", &[X::N(1.0)]),
    ];
    let b1 = a.block(one);
    a.blank();
    let two = vec![a.wait("wait(0.1)", 0.1), a.brk("break(w=wait)", "w=wait")];
    let b2 = a.block(two);
    let mut vm = vm(a.task(&[b1, b2]), robot(), config());
    vm.tick();
    assert_eq!(vm.activity().sleeping, 2, "both blocks sleep");
    assert_eq!(vm.live_statements().len(), 2, "both waits are live");
    assert!(vm.run_for(2.0), "task ends");
    assert_eq!(ended(&vm, "w=wait(0.5)").as_deref(), Some("broken"));
    let w = vm.var("w").expect("bound");
    assert_eq!((w.status, w.how), (1.0, Some(ilmr_vm::How::Broken)));
    let at = |text| when(&vm, "var", text).map(|t| (t * 100.0).round() as u32);
    assert_eq!(at("x=1"), Some(10), "resumed by the break at 0.1 s");
    assert_eq!(at("y=1"), Some(70), "the old timer (0.5 s) woke nothing");
    assert_eq!(ended(&vm, "wait(0.6)").as_deref(), Some("completed"));
    assert_eq!(vm.activity().sleeping, 0);
    assert_eq!(vm.live(), 0);
}

#[test]
fn breaking_a_while_ends_everything_inside_it() {
    let mut a = Asm::new();
    let one = vec![a.while_("while(1)", &[X::N(1.0)], None, |a| {
        vec![
            a.wait("wait(5)", 5.0),
            a.assign("never=1", "never", &[X::N(1.0)]),
        ]
    })];
    let b1 = a.block(one);
    a.blank();
    let two = vec![a.wait("wait(0.5)", 0.5), a.brk("break(while(1)", "while(1")];
    let b2 = a.block(two);
    let mut vm = vm(a.task(&[b1, b2]), robot(), config());
    assert!(vm.run_for(2.0));
    assert_eq!(ended(&vm, "wait(5)").as_deref(), Some("broken"));
    assert_eq!(ended(&vm, "while(1)").as_deref(), Some("broken"));
    assert_eq!(vm.var("never").map(|v| v.status), Some(0.0));
    insta::assert_snapshot!(trace(&vm));
}

#[test]
fn priority_highest_ends_every_other_command_and_runs_alone() {
    let mut a = Asm::new();
    let one = vec![
        a.cmd("speed(0.4)", Command::Speed, &[A::N(0.4)], None),
        a.cmd("goahead()", Command::Goahead, &[], None),
        a.cmd(
            "x=sensor(scanner,door)",
            Command::Sensor,
            &[A::W("scanner"), A::W("door")],
            Some("x"),
        ),
    ];
    let b1 = a.block(one);
    a.blank();
    let two = vec![
        a.cmd(
            "battery=sensor(battery)",
            Command::Sensor,
            &[A::W("battery")],
            Some("battery"),
        ),
        a.if_(
            "if(battery<24)",
            &[X::V("battery"), X::N(24.0), X::Op(ExprOp::Lt)],
            |a| {
                vec![
                    a.op("priority=highest", Op::Priority),
                    a.cmd(
                        "charge=goahead(-0.5)",
                        Command::Goahead,
                        &[A::N(-0.5)],
                        Some("charge"),
                    ),
                ]
            },
        ),
    ];
    let b2 = a.block(two);
    let r = robot().battery(0.0, 25.0).battery(1.0, 23.0);
    let mut vm = vm(a.task(&[b1, b2]), r, config());
    assert!(vm.run_for(10.0));
    assert_eq!(ended(&vm, "goahead()").as_deref(), Some("broken"));
    assert_eq!(
        ended(&vm, "x=sensor(scanner,door)").as_deref(),
        Some("broken")
    );
    assert_eq!(when(&vm, "end", "goahead()"), Some(1.0));
    assert_eq!(
        ended(&vm, "charge=goahead(-0.5)").as_deref(),
        Some("completed")
    );
    insta::assert_snapshot!(trace(&vm));
}

#[test]
fn a_budget_overrun_suspends_the_block_but_not_the_movement() {
    let mut a = Asm::new();
    let one = vec![
        a.cmd("speed(0.5)", Command::Speed, &[A::N(0.5)], None),
        a.cmd("m=goahead(1)", Command::Goahead, &[A::N(1.0)], Some("m")),
    ];
    let b1 = a.block(one);
    a.blank();
    let two = vec![a.while_(
        "while(n<1000000)",
        &[X::V("n"), X::N(1e6), X::Op(ExprOp::Lt)],
        None,
        |a| vec![a.assign("n=n+1", "n", &[X::V("n"), X::N(1.0), X::Op(ExprOp::Add)])],
    )];
    let b2 = a.block(two);
    let cfg = Config {
        budget_ops: 5_000,
        ..config()
    };
    let mut vm = vm(a.task(&[b1, b2]), robot(), cfg);
    vm.run_for(4.0);
    let overruns = vm
        .events()
        .iter()
        .filter(|e| e.kind.name() == "overrun")
        .count();
    assert!(overruns >= 300, "one overrun per tick: {overruns}");
    assert_eq!(ended(&vm, "m=goahead(1)").as_deref(), Some("completed"));
    let end = when(&vm, "end", "m=goahead(1)").expect("ends");
    assert!(end < 3.5, "the movement was not starved: ended at {end}");
    let n = vm.var("n").expect("n").value;
    assert!(
        n > 1000.0 && n < 1e6,
        "the loop made progress without finishing: {n}"
    );
    // The snapshot keeps the first second: the overruns repeat every tick after.
    let head: String = trace(&vm)
        .lines()
        .take(12)
        .map(|l| format!("{l}\n"))
        .collect();
    insta::assert_snapshot!(head);
}

/// A tight loop keeps one `issue`, `start` and `var` event per statement a tick, with
/// the last value and how many there were: the trace grows with the ticks, not with the
/// loop's iterations, and no write goes uncounted.
#[test]
fn a_tight_loop_keeps_one_event_per_statement_and_variable_a_tick() {
    let mut a = Asm::new();
    let body = vec![a.while_(
        "while(x>-1)",
        &[X::V("x"), X::N(-1.0), X::Op(ExprOp::Gt)],
        None,
        |a| vec![a.assign("x=x+1", "x", &[X::V("x"), X::N(1.0), X::Op(ExprOp::Add)])],
    )];
    let b = a.block(body);
    let mut vm = vm(a.task(&[b]), robot(), config());
    vm.run_for(2.0);
    let events = vm.events();
    let ticks = vm.ticks();
    assert!(
        events.len() as u64 <= 4 * ticks + 4,
        "{} events in {ticks} ticks",
        events.len()
    );
    let count = |name: &str| -> u64 {
        events
            .iter()
            .filter(|e| e.kind.name() == name)
            .map(|e| u64::from(e.count))
            .sum()
    };
    let x = vm.var("x").expect("x").value;
    assert!(
        x > 100.0 * ticks as f64,
        "the loop ran many times a tick: {x}"
    );
    assert_eq!(count("var") as f64, x, "every write of x is counted");
    assert_eq!(
        count("issue") as f64,
        x + 1.0,
        "the while once, and every issue of x=x+1"
    );
    assert_eq!(count("overrun"), ticks, "each tick's overrun is kept");
    let last_start = events.iter().rev().find(|e| e.kind.name() == "start");
    let Some(ilmr_vm::EventKind::Start { iteration }) = last_start.map(|e| &e.kind) else {
        panic!("no start event");
    };
    assert_eq!(
        iteration.map(f64::from),
        Some(x),
        "the last iteration is the one kept"
    );
    let last_var = trace(&vm)
        .lines()
        .rev()
        .find(|l| l.contains("\"event\":\"var\""))
        .map(str::to_string)
        .expect("a var line");
    assert!(
        last_var.starts_with(
            "{\"t\":1.99,\"event\":\"var\",\"line\":2,\"text\":\"x=x+1\",\"var\":\"x\""
        ) && last_var.contains(&format!(",\"value\":{x},\"count\":")),
        "the tick's last value and its count: {last_var}"
    );
}

#[test]
fn stop_halts_the_robot_and_cont_resumes_the_movement() {
    let mut a = Asm::new();
    let one = vec![
        a.cmd("speed(0.5)", Command::Speed, &[A::N(0.5)], None),
        a.cmd("m=goahead(2)", Command::Goahead, &[A::N(2.0)], Some("m")),
    ];
    let b1 = a.block(one);
    a.blank();
    let two = vec![
        a.wait("wait(1.5)", 1.5),
        a.op("stop", Op::Stop),
        a.wait("wait(2)", 2.0),
        a.op("cont", Op::Cont),
    ];
    let b2 = a.block(two);
    let mut vm = vm(a.task(&[b1, b2]), robot(), config());
    vm.run_for(3.0);
    assert!(vm.hal().speed().abs() < 1e-9, "halted during the stop");
    let x_stopped = vm.hal().true_pose().x;
    vm.run_for(0.4);
    assert!((vm.hal().true_pose().x - x_stopped).abs() < 1e-9);
    assert!(vm.run_for(10.0));
    assert_eq!(ended(&vm, "m=goahead(2)").as_deref(), Some("completed"));
    assert!((vm.hal().true_pose().x - 2.0).abs() < 0.05);
    insta::assert_snapshot!(trace(&vm));
}

#[test]
fn clear_resets_a_variable_so_waits_wait_anew() {
    let mut a = Asm::new();
    let one = vec![
        a.assign("x=5", "x", &[X::N(5.0)]),
        a.clear("clear(x)", "x"),
        a.wait_var("wait(x)", "x"),
        a.assign("seen=x", "seen", &[X::V("x")]),
    ];
    let b1 = a.block(one);
    a.blank();
    let two = vec![a.wait("wait(0.5)", 0.5), a.assign("x=7", "x", &[X::N(7.0)])];
    let b2 = a.block(two);
    let mut vm = vm(a.task(&[b1, b2]), robot(), config());
    assert!(vm.run_for(2.0));
    assert_eq!(when(&vm, "var", "seen=x"), Some(0.5));
    assert_eq!(vm.var("seen").map(|v| v.value), Some(7.0));
    insta::assert_snapshot!(trace(&vm));
}

#[test]
fn a_skill_call_binds_a_status_set_when_all_its_commands_ended() {
    let mut a = Asm::new();
    let skill = a.skill("Takebox");
    let s1 = vec![
        a.cmd(
            "manipulate(take)",
            Command::Manipulate,
            &[A::W("take")],
            None,
        ),
        a.wait("wait(0.3)", 0.3),
    ];
    let sb1 = a.block(s1);
    a.blank();
    let s2 = vec![a.cmd(
        "actuator(brake,on)",
        Command::Actuator,
        &[A::W("brake"), A::W("on")],
        None,
    )];
    let sb2 = a.block(s2);
    a.define(skill, &[sb1, sb2]);
    a.blank();
    let main = vec![
        a.call("Over=Takebox", skill, Some("Over")),
        a.wait_var("wait(Over)", "Over"),
        a.assign("done=1", "done", &[X::N(1.0)]),
    ];
    let mb = a.block(main);
    let r = robot().op(
        OpMatch::Manipulate(ilmr_hal::ManipTask::Take),
        50,
        OpOutcome::Done,
    );
    let mut vm = vm(a.task(&[mb]), r, config());
    assert!(vm.run_for(2.0));
    assert_eq!(
        when(&vm, "end", "Over=Takebox"),
        Some(0.5),
        "after the manipulation"
    );
    assert_eq!(when(&vm, "var", "done=1"), Some(0.5));
    assert_eq!(vm.hal().actuator_log(), &[("brake".to_string(), 1.0)]);
    insta::assert_snapshot!(trace(&vm));
}

/// Figure 56: `TURN1` then `speed(0.4)` and a movement. The skill's statements are
/// issued where the call stands, so its `speed(-0.4)` applies to its own movement and
/// its `wait` holds the caller; its second block starts at the call as a new strand.
#[test]
fn a_skill_call_runs_in_line_and_its_wait_holds_the_caller() {
    let mut a = Asm::new();
    let skill = a.skill("Back");
    let s1 = vec![
        a.cmd("speed(-0.4)", Command::Speed, &[A::N(-0.4)], None),
        a.cmd("t=goahead(0.5)", Command::Goahead, &[A::N(0.5)], Some("t")),
        a.wait_var("wait(t)", "t"),
    ];
    let sb1 = a.block(s1);
    a.blank();
    let s2 = vec![a.assign("side=1", "side", &[X::N(1.0)])];
    let sb2 = a.block(s2);
    a.define(skill, &[sb1, sb2]);
    a.blank();
    let main = vec![
        a.call("Back", skill, None),
        a.cmd("speed(0.4)", Command::Speed, &[A::N(0.4)], None),
        a.cmd("g=goahead(0.5)", Command::Goahead, &[A::N(0.5)], Some("g")),
    ];
    let mb = a.block(main);
    let mut vm = vm(a.task(&[mb]), robot(), config());
    assert!(vm.run_for(20.0), "task ends");
    let back_done = when(&vm, "end", "wait(t)").expect("the skill's wait ends");
    assert_eq!(
        when(&vm, "var", "side=1"),
        Some(0.0),
        "second block at the call"
    );
    assert_eq!(
        when(&vm, "issue", "speed(0.4)"),
        Some(back_done),
        "the caller goes on only when the skill's block has issued its last statement"
    );
    let order: Vec<&str> = vm
        .events()
        .iter()
        .filter(|e| e.kind.name() == "issue")
        .filter_map(|e| e.stmt.and_then(|s| vm.module().stmt(s)))
        .map(|s| s.text.as_str())
        .collect();
    assert_eq!(
        order,
        [
            "Back",
            "speed(-0.4)",
            "t=goahead(0.5)",
            "wait(t)",
            "side=1",
            "speed(0.4)",
            "g=goahead(0.5)"
        ]
    );
    // Backwards half a metre, then forwards again: the caller's speed drove its own
    // movement.
    let x = vm.hal().true_pose().x;
    assert!(x.abs() < 0.1, "back where it started: x = {x}");
    insta::assert_snapshot!(trace(&vm));
}

#[test]
fn a_skill_call_runs_in_line_even_when_it_issues_nothing_that_waits() {
    let mut a = Asm::new();
    let inner = a.skill("Inner");
    let i1 = vec![a.assign("x=1", "x", &[X::N(1.0)])];
    let ib = a.block(i1);
    a.define(inner, &[ib]);
    a.blank();
    let outer = a.skill("Outer");
    let o1 = vec![
        a.call("Inner", inner, None),
        a.assign("y=x+1", "y", &[X::V("x"), X::N(1.0), X::Op(ExprOp::Add)]),
    ];
    let ob = a.block(o1);
    a.define(outer, &[ob]);
    a.blank();
    let main = vec![
        a.call("o=Outer", outer, Some("o")),
        a.assign("z=y+1", "z", &[X::V("y"), X::N(1.0), X::Op(ExprOp::Add)]),
    ];
    let mb = a.block(main);
    let mut vm = vm(a.task(&[mb]), robot(), config());
    assert!(vm.run_for(1.0));
    assert_eq!(
        vm.var("z").map(|v| v.value),
        Some(3.0),
        "nested calls in line"
    );
    assert_eq!(vm.var("o").map(|v| v.status), Some(1.0));
    assert_eq!(when(&vm, "end", "o=Outer"), Some(0.0));
}

#[test]
fn consecutive_movements_link_without_a_stop() {
    let mut a = Asm::new();
    let code = vec![
        a.cmd("speed(0.5)", Command::Speed, &[A::N(0.5)], None),
        a.cmd("goahead(2)", Command::Goahead, &[A::N(2.0)], None),
        a.cmd(
            "turn(d=90,c=0.5)",
            Command::Turn,
            &[A::S("d", 90.0), A::S("c", 0.5)],
            None,
        ),
    ];
    let b = a.block(code);
    let mut vm = vm(a.task(&[b]), robot(), config());
    let mut slowest = f64::INFINITY;
    let mut linked_at = None;
    for _ in 0..2000 {
        vm.tick();
        if linked_at.is_none() {
            linked_at = when(&vm, "start", "turn(d=90,c=0.5)");
        }
        if vm.time() > 2.0 && !vm.finished() && linked_at.is_some_and(|t| vm.time() < t + 1.0) {
            slowest = slowest.min(vm.hal().speed());
        }
        if vm.finished() {
            break;
        }
    }
    assert!(vm.finished());
    let linked = vm
        .events()
        .iter()
        .any(|e| matches!(e.kind, ilmr_vm::EventKind::End { linked: true, .. }));
    assert!(linked, "the goahead was linked to the turn");
    assert!(
        slowest > 0.4,
        "no stop between the linked movements: {slowest}"
    );
    let p = vm.hal().true_pose();
    // 2 m ahead then a quarter circle of radius 2 to the left ends near (4, 2).
    assert!(
        (p.x - 4.0).abs() < 0.15 && (p.y - 2.0).abs() < 0.15,
        "{p:?}"
    );
    insta::assert_snapshot!(trace(&vm));
}

#[test]
fn a_wait_on_the_first_movement_prevents_linking() {
    let mut a = Asm::new();
    let code = vec![
        a.cmd("speed(0.5)", Command::Speed, &[A::N(0.5)], None),
        a.cmd("m=goahead(2)", Command::Goahead, &[A::N(2.0)], Some("m")),
        a.cmd("goahead(1)", Command::Goahead, &[A::N(1.0)], None),
        a.wait_var("wait(m)", "m"),
    ];
    let b = a.block(code);
    let mut vm = vm(a.task(&[b]), robot(), config());
    let mut slowest = f64::INFINITY;
    for _ in 0..2000 {
        vm.tick();
        if vm.time() > 2.0 && !vm.finished() {
            slowest = slowest.min(vm.hal().speed().abs());
        }
        if vm.finished() {
            break;
        }
    }
    assert!(vm.finished());
    let linked = vm
        .events()
        .iter()
        .any(|e| matches!(e.kind, ilmr_vm::EventKind::End { linked: true, .. }));
    assert!(!linked);
    assert!(
        slowest < 0.1,
        "the robot slowed to a stop between them: {slowest}"
    );
    assert!((vm.hal().true_pose().x - 3.0).abs() < 0.05);
}

#[test]
fn a_found_door_is_stored_and_compared_by_position() {
    let mut a = Asm::new();
    let code = vec![
        a.cmd(
            "MyDoor=sensor(scanner,door)",
            Command::Sensor,
            &[A::W("scanner"), A::W("door")],
            Some("MyDoor"),
        ),
        a.wait_var("wait(MyDoor)", "MyDoor"),
        a.cmd(
            "Door=sensor(scanner,door,left,forever)",
            Command::Sensor,
            &[A::W("scanner"), A::W("door"), A::W("left"), A::W("forever")],
            Some("Door"),
        ),
        a.if_("if(Door==MyDoor)", &[X::At("Door", "MyDoor")], |a| {
            vec![a.brk("break(sensor)", "sensor")]
        }),
    ];
    let b = a.block(code);
    let door = |x: f64, side: Side| Detection {
        sensor: "scanner".into(),
        object: "door".into(),
        x,
        y: 1.0,
        h: 0.0,
        side,
    };
    // The first door is seen on the right, so the left-only search misses it.
    let r = robot()
        .sighting(0.5, 0.6, door(3.0, Side::Right))
        .sighting(1.0, 1.2, door(8.0, Side::Left))
        .sighting(2.0, 2.2, door(3.1, Side::Left));
    let mut vm = vm(a.task(&[b]), r, config());
    assert!(vm.run_for(4.0));
    assert_eq!(when(&vm, "end", "MyDoor=sensor(scanner,door)"), Some(0.5));
    assert_eq!(when(&vm, "start", "if(Door==MyDoor)"), Some(2.0));
    assert_eq!(
        ended(&vm, "Door=sensor(scanner,door,left,forever)").as_deref(),
        Some("broken")
    );
    insta::assert_snapshot!(trace(&vm));
}

#[test]
fn a_forever_search_is_an_endless_reading_a_task_may_end_on() {
    let mut a = Asm::new();
    let code = vec![
        a.cmd(
            "Door=sensor(scanner,door,left,forever)",
            Command::Sensor,
            &[A::W("scanner"), A::W("door"), A::W("left"), A::W("forever")],
            Some("Door"),
        ),
        a.cmd(
            "MyDoor=sensor(scanner,door)",
            Command::Sensor,
            &[A::W("scanner"), A::W("door")],
            Some("MyDoor"),
        ),
    ];
    let b = a.block(code);
    let mut both = vm(a.task(&[b]), robot(), config());
    both.tick();
    let now = both.activity();
    assert_eq!((now.running_commands, now.endless_readings), (2, 1));
    assert!(
        !now.only_waiting(),
        "a search that ends by itself still runs"
    );
    let mut a = Asm::new();
    let code = vec![a.cmd(
        "Door=sensor(scanner,door,left,forever)",
        Command::Sensor,
        &[A::W("scanner"), A::W("door"), A::W("left"), A::W("forever")],
        Some("Door"),
    )];
    let b = a.block(code);
    let mut only = vm(a.task(&[b]), robot(), config());
    only.tick();
    only.tick();
    let now = only.activity();
    assert_eq!((now.running_commands, now.endless_readings), (1, 1));
    assert!(now.only_waiting() && !now.only_guards_waiting());
    assert!(!only.finished());
}

#[test]
fn refusals_and_missing_data_become_variable_states() {
    let mut a = Asm::new();
    let code = vec![
        a.cmd(
            "ok=manipulate(take)",
            Command::Manipulate,
            &[A::W("take")],
            Some("ok"),
        ),
        a.cmd(
            "v=sensor(sonar)",
            Command::Sensor,
            &[A::W("sonar")],
            Some("v"),
        ),
        a.cmd(
            "actuator(brake,on)",
            Command::Actuator,
            &[A::W("brake"), A::W("on")],
            None,
        ),
        a.cmd("gotoxy(nowhere)", Command::GotoXY, &[A::V("nowhere")], None),
    ];
    let b = a.block(code);
    let r = robot()
        .op(OpMatch::Any, 3, OpOutcome::Failed("gripper blocked".into()))
        .refuse_actuator("brake", "locked");
    let mut vm = vm(a.task(&[b]), r, config());
    assert!(vm.run_for(3.0));
    let ok = vm.var("ok").expect("ok");
    assert_eq!((ok.status, ok.how), (1.0, Some(ilmr_vm::How::Refused)));
    assert_eq!(
        vm.var("v").map(|v| v.how),
        Some(Some(ilmr_vm::How::Refused))
    );
    assert_eq!(ended(&vm, "actuator(brake,on)").as_deref(), Some("refused"));
    assert_eq!(ended(&vm, "gotoxy(nowhere)").as_deref(), Some("refused"));
    insta::assert_snapshot!(trace(&vm));
}

#[test]
fn init_holds_its_block_until_the_robot_is_ready() {
    let mut a = Asm::new();
    let one = vec![
        a.cmd("init()", Command::Init, &[], None),
        a.assign("ready=1", "ready", &[X::N(1.0)]),
    ];
    let b1 = a.block(one);
    a.blank();
    let two = vec![a.assign("meanwhile=1", "meanwhile", &[X::N(1.0)])];
    let b2 = a.block(two);
    let r = robot().op(OpMatch::Init, 30, OpOutcome::Done);
    let mut vm = vm(a.task(&[b1, b2]), r, config());
    assert!(vm.run_for(1.0));
    assert_eq!(when(&vm, "var", "meanwhile=1"), Some(0.0));
    assert_eq!(when(&vm, "var", "ready=1"), Some(0.3));
}

#[test]
fn an_exact_turn_follows_its_arc() {
    let mut a = Asm::new();
    let code = vec![
        a.cmd("speed(0.4)", Command::Speed, &[A::N(0.4)], None),
        a.cmd(
            "t=turn(d=90,c=0.6)",
            Command::Turn,
            &[A::S("d", 90.0), A::S("c", 0.6)],
            Some("t"),
        ),
    ];
    let b = a.block(code);
    let cfg = Config {
        trace: TraceLevel::Full,
        pose_every: 50,
        ..Config::default()
    };
    let mut vm = vm(a.task(&[b]), robot(), cfg);
    let r = 1.0 / 0.6;
    let mut worst: f64 = 0.0;
    while !vm.finished() && vm.time() < 20.0 {
        vm.tick();
        let p = vm.hal().true_pose();
        if p.x > 0.05 {
            // Distance from the circle about (0, r).
            worst = worst.max((p.x.hypot(p.y - r) - r).abs());
        }
    }
    assert!(vm.finished());
    let t = vm.var("t").expect("t");
    assert!(
        (t.dist - r * std::f64::consts::FRAC_PI_2).abs() < 0.05,
        "{t:?}"
    );
    assert!(worst < 0.08, "max deviation from the arc {worst}");
    let p = vm.hal().true_pose();
    assert!((p.h - std::f64::consts::FRAC_PI_2).abs() < 0.1, "{p:?}");
    insta::assert_snapshot!(trace(&vm));
}

#[test]
fn an_interactive_line_joins_the_running_task() {
    let mut a = Asm::new();
    a.var("count", VarKind::Number);
    let code = vec![a.while_(
        "while(count<100)",
        &[X::V("count"), X::N(100.0), X::Op(ExprOp::Lt)],
        None,
        |a| vec![a.wait("wait(0.1)", 0.1)],
    )];
    let b = a.block(code);
    let mut vm = vm(a.task(&[b]), robot(), config());
    vm.run_for(0.5);
    let mut line = Asm::extending(vm.module(), "<interactive>");
    let code = vec![line.assign("count=100", "count", &[X::N(100.0)])];
    let lb = line.block(code);
    let fragment = line.fragment(&[lb]);
    vm.add_block(&fragment)
        .expect("compiled against this module");
    assert!(vm.add_block(&fragment).is_err(), "a fragment applies once");
    assert!(vm.run_for(1.0), "the loop saw the new value");
    assert_eq!(when(&vm, "var", "count=100"), Some(0.5));
    assert_eq!(ended(&vm, "while(count<100)").as_deref(), Some("completed"));
}

#[test]
fn the_same_inputs_give_a_byte_identical_trace() {
    let run = || {
        let mut a = Asm::new();
        let one = vec![
            a.cmd("speed(0.6)", Command::Speed, &[A::N(0.6)], None),
            a.cmd(
                "gotoxy(3,1)",
                Command::GotoXY,
                &[A::N(3.0), A::N(1.0)],
                None,
            ),
            a.cmd(
                "turn(d=-90,c=1)",
                Command::Turn,
                &[A::S("d", -90.0), A::S("c", 1.0)],
                None,
            ),
        ];
        let b1 = a.block(one);
        a.blank();
        let two = vec![
            a.cmd(
                "b=sensor(battery)",
                Command::Sensor,
                &[A::W("battery")],
                Some("b"),
            ),
            a.if_(
                "if(b<24)",
                &[X::F("b", Field::Value), X::N(24.0), X::Op(ExprOp::Lt)],
                |a| vec![a.assign("low=1", "low", &[X::N(1.0)])],
            ),
        ];
        let b2 = a.block(two);
        let r = robot().battery(0.0, 25.0).battery(3.0, 23.0);
        let cfg = Config::default();
        let mut vm = vm(a.task(&[b1, b2]), r, cfg);
        vm.run_for(15.0);
        trace(&vm)
    };
    let (one, two) = (run(), run());
    assert!(one.lines().count() > 100);
    assert_eq!(one, two);
}

#[test]
fn runaway_skill_recursion_is_refused_not_fatal() {
    let mut a = Asm::new();
    let skill = a.skill("Again");
    let code = vec![
        a.assign(
            "depth=depth+1",
            "depth",
            &[X::V("depth"), X::N(1.0), X::Op(ExprOp::Add)],
        ),
        a.call("Again", skill, None),
    ];
    let sb = a.block(code);
    a.define(skill, &[sb]);
    a.blank();
    let main = vec![
        a.call("r=Again", skill, Some("r")),
        a.wait_var("wait(r)", "r"),
    ];
    let mb = a.block(main);
    let cfg = Config {
        budget_ops: 40,
        ..config()
    };
    let mut vm = vm(a.task(&[mb]), robot(), cfg);
    assert!(
        vm.run_for(5.0),
        "the refusal at the depth limit unwinds every call"
    );
    assert_eq!(vm.var("depth").map(|v| v.value), Some(64.0));
    assert!(vm.events().iter().any(|e| e.kind.name() == "overrun"));
    let refused = vm.events().iter().filter(|e| {
        matches!(
            &e.kind,
            ilmr_vm::EventKind::End {
                how: ilmr_vm::How::Refused,
                ..
            }
        )
    });
    assert_eq!(refused.count(), 1);
    assert_eq!(
        vm.var("r").map(|v| v.how),
        Some(Some(ilmr_vm::How::Completed))
    );
}

#[test]
fn speed_with_w_waits_for_the_running_movement() {
    let mut a = Asm::new();
    let code = vec![
        a.cmd("speed(0.5)", Command::Speed, &[A::N(0.5)], None),
        a.cmd("m=goahead(1)", Command::Goahead, &[A::N(1.0)], Some("m")),
        a.cmd(
            "speed(-0.3,w)",
            Command::Speed,
            &[A::N(-0.3), A::W("w")],
            None,
        ),
        a.wait_var("wait(m)", "m"),
        a.cmd("goahead(0.5)", Command::Goahead, &[A::N(0.5)], None),
    ];
    let b = a.block(code);
    let mut vm = vm(a.task(&[b]), robot(), config());
    assert!(vm.run_for(15.0));
    assert_eq!(
        when(&vm, "end", "speed(-0.3,w)"),
        when(&vm, "end", "m=goahead(1)"),
        "the new speed applies when the movement ends"
    );
    // 1 m ahead at 0.5 m/s, then 0.5 m reversing.
    assert!(
        (vm.hal().true_pose().x - 0.5).abs() < 0.05,
        "{:?}",
        vm.hal().true_pose()
    );
}

#[test]
fn activity_tells_when_only_waiting_guards_are_left() {
    let mut a = Asm::new();
    let one = vec![
        a.cmd("goahead(0.3)", Command::Goahead, &[A::N(0.3)], None),
        a.cmd("goahead(0.2)", Command::Goahead, &[A::N(0.2)], None),
        a.wait("wait(0.5)", 0.5),
        a.assign("x=1", "x", &[X::N(1.0)]),
    ];
    let b1 = a.block(one);
    a.blank();
    let two = vec![
        a.if_("if(x>5)", &[X::V("x"), X::N(5.0), X::Op(ExprOp::Gt)], |a| {
            vec![a.assign("y=1", "y", &[X::N(1.0)])]
        }),
    ];
    let b2 = a.block(two);
    let mut vm = vm(a.task(&[b1, b2]), robot(), config());
    vm.tick();
    let now = vm.activity();
    assert_eq!(
        now,
        ilmr_vm::Activity {
            running_commands: 1,
            endless_readings: 0,
            queued_movements: 1,
            waiting_guards: 1,
            sleeping: 1,
            issuing_blocks: 1,
            ready: 0,
            robot_at_rest: true,
        },
        "the first tick only commanded the speed"
    );
    assert!(!vm.only_guards_waiting());
    vm.tick();
    assert!(!vm.activity().robot_at_rest, "moving");
    let mut ticks = 0;
    while !vm.only_guards_waiting() && ticks < 2_000 {
        vm.tick();
        ticks += 1;
    }
    let end = vm.activity();
    assert!(end.only_guards_waiting(), "{end:?}");
    assert_eq!(end.waiting_guards, 1);
    assert!(!vm.finished(), "the guard still lives");
    assert_eq!(vm.var("x").map(|v| v.value), Some(1.0));
    assert!(
        vm.time() >= 0.5,
        "the movements and the wait are over: {}",
        vm.time()
    );
}

#[test]
fn break_with_an_empty_pattern_ends_nothing() {
    let mut a = Asm::new();
    let code = vec![a.wait("wait(0.5)", 0.5), a.assign("x=1", "x", &[X::N(1.0)])];
    let b1 = a.block(code);
    a.blank();
    let two = vec![a.brk("break()", ""), a.brk("break( )", " ")];
    let b2 = a.block(two);
    let mut vm = vm(a.task(&[b1, b2]), robot(), config());
    assert!(vm.run_for(2.0));
    assert_eq!(ended(&vm, "wait(0.5)").as_deref(), Some("completed"));
    assert_eq!(vm.var("x").map(|v| v.value), Some(1.0));
}

#[test]
fn copy_gives_a_variable_the_whole_record_of_another() {
    let mut a = Asm::new();
    let door = a.var("Door", VarKind::Position);
    let mine = a.var("MyDoor", VarKind::Position);
    let code = vec![
        a.cmd(
            "Door=sensor(camera,door)",
            Command::Sensor,
            &[A::W("camera"), A::W("door")],
            Some("Door"),
        ),
        a.wait_var("wait(Door)", "Door"),
        a.op(
            "MyDoor=Door",
            Op::Copy {
                to: mine,
                from: door,
            },
        ),
    ];
    let b = a.block(code);
    let detection = Detection {
        sensor: "camera".into(),
        object: "door".into(),
        x: 3.0,
        y: -1.5,
        h: 0.25,
        side: Side::Right,
    };
    let r = robot().sighting(0.1, 10.0, detection);
    let mut vm = vm(a.task(&[b]), r, config());
    assert!(vm.run_for(1.0));
    let (d, m) = (
        vm.var("Door").expect("door"),
        vm.var("MyDoor").expect("copy"),
    );
    assert_eq!(m, d, "every field and how it ended");
    assert_eq!((m.x, m.y, m.h, m.status), (3.0, -1.5, 0.25, 1.0));
    let line = trace(&vm)
        .lines()
        .find(|l| l.contains("\"var\":\"MyDoor\""))
        .map(str::to_string);
    assert_eq!(
        line.as_deref(),
        Some(
            "{\"t\":0.1,\"event\":\"var\",\"line\":3,\"text\":\"MyDoor=Door\",\"var\":\"MyDoor\",\"status\":1,\"x\":3,\"y\":-1.5,\"h\":0.25,\"how\":\"completed\"}"
        )
    );
}

#[test]
fn obstacle_avoidance_traces_its_state_changes() {
    let mut a = Asm::new();
    let code = vec![
        a.cmd("obsavoid(on)", Command::ObsAvoid, &[A::W("on")], None),
        a.cmd("goahead(6)", Command::Goahead, &[A::N(6.0)], None),
    ];
    let b = a.block(code);
    // One scan at the start: a post 2.5 m ahead of the scanner, nothing else in range.
    let n = 181;
    let step = std::f64::consts::PI / (n - 1) as f64;
    let ranges = (0..n)
        .map(|i| {
            let angle = -std::f64::consts::FRAC_PI_2 + i as f64 * step;
            if angle.abs() < 0.04 { 2.5 } else { 30.0 }
        })
        .collect();
    let scan = ilmr_hal::Scan {
        device: "scanner".into(),
        t: 0.0,
        angle_min: -std::f64::consts::FRAC_PI_2,
        angle_step: step,
        ranges,
    };
    let mut vm = vm(a.task(&[b]), robot().scan(scan), config());
    assert!(vm.run_for(60.0), "the movement ends");
    let states: Vec<String> = trace(&vm)
        .lines()
        .filter(|l| l.contains("\"event\":\"avoid\""))
        .map(|l| {
            let at = l.find("\"state\":\"").map_or(0, |i| i + 9);
            l[at..].trim_end_matches("\"}").to_string()
        })
        .collect();
    assert_eq!(
        states.first().map(String::as_str),
        Some("avoiding"),
        "{states:?}"
    );
    assert_eq!(
        states.last().map(String::as_str),
        Some("normal"),
        "{states:?}"
    );
    assert!(
        trace(&vm).contains("\"event\":\"avoid\",\"line\":2,\"text\":\"goahead(6)\""),
        "the event names the running movement"
    );
}

/// `while(v<to)` / `v=v+1` / `wait(nap)` / `endwhile`.
fn count_to(a: &mut Asm, v: &str, to: f64, nap: f64) -> ilmr_vm::bytecode::Instr {
    a.while_(
        &format!("while({v}<{to})"),
        &[X::V(v), X::N(to), X::Op(ExprOp::Lt)],
        None,
        |a| {
            vec![
                a.assign(
                    &format!("{v}={v}+1"),
                    v,
                    &[X::V(v), X::N(1.0), X::Op(ExprOp::Add)],
                ),
                a.wait(&format!("wait({nap})"), nap),
            ]
        },
    )
}

/// A counting loop in one block; in the other, after 0.1 s, `breaks`.
fn loop_and_breaks(breaks: &[(&str, &str)]) -> ilmr_vm::bytecode::Module {
    let mut a = Asm::new();
    a.var("n", VarKind::Number);
    let counting = vec![count_to(&mut a, "n", 50.0, 0.01)];
    let b1 = a.block(counting);
    a.blank();
    let mut code = vec![a.wait("wait(0.1)", 0.1)];
    for (text, pattern) in breaks {
        code.push(a.brk(text, pattern));
    }
    code.push(a.assign("later=1", "later", &[X::N(1.0)]));
    let b2 = a.block(code);
    a.task(&[b1, b2])
}

#[test]
fn breaks_whose_patterns_only_breaks_hold_look_at_no_node() {
    // Each pattern is found in its own `break(...)` and nowhere else: a break is never
    // live, so none of them can end anything, and none looks at the live nodes (each
    // read every live node's text, 9.5 s for 20,000 of them beside 20,000 loops).
    let texts: Vec<(String, String)> = (0..200)
        .map(|i| (format!("break(zz{i})"), format!("zz{i}")))
        .collect();
    let mut breaks: Vec<(&str, &str)> = (texts.iter())
        .map(|(t, p)| (t.as_str(), p.as_str()))
        .collect();
    breaks.push(("break( )", " "));
    let mut vm = vm(loop_and_breaks(&breaks), robot(), config());
    assert!(vm.run_for(2.0));
    assert_eq!(vm.break_looks(), 0);
    assert_eq!(
        vm.var("n").map(|v| v.value),
        Some(50.0),
        "nothing was broken"
    );
    assert_eq!(ended(&vm, "while(n<50)").as_deref(), Some("completed"));

    // A pattern found in a statement that runs looks, and ends what is live of it,
    // whatever its case, after breaks that found nothing.
    breaks.push(("break(WHILE(N)", "WHILE(N"));
    let mut vm = vm_of(loop_and_breaks(&breaks));
    assert!(vm.run_for(2.0));
    assert!(vm.break_looks() > 0);
    assert_eq!(ended(&vm, "while(n<50)").as_deref(), Some("broken"));
    let n = vm.var("n").map_or(0.0, |v| v.value);
    assert!(n > 5.0 && n < 15.0, "{n}");
}

fn vm_of(module: ilmr_vm::bytecode::Module) -> common::TestVm {
    vm(module, robot(), config())
}

#[test]
fn a_joined_line_breaks_with_a_pattern_the_task_never_had() {
    // The task's breaks found their statements before the line came; the line's
    // pattern and statements are new to them.
    let mut vm = vm_of(loop_and_breaks(&[("break(zz)", "zz")]));
    vm.run_for(0.2);
    let mut line = Asm::extending(vm.module(), "<interactive>");
    let code = vec![line.brk("break(n<5)", "n<5")];
    let lb = line.block(code);
    vm.add_block(&line.fragment(&[lb])).expect("joins");
    assert!(vm.run_for(1.0));
    assert_eq!(ended(&vm, "while(n<50)").as_deref(), Some("broken"));
    assert!(vm.var("n").map_or(0.0, |v| v.value) < 30.0);
}

#[test]
fn breaks_that_look_at_many_live_nodes_pay_from_the_tick_budget() {
    // 100 counting blocks, asleep for a second at a time, are live when twenty breaks
    // of a statement that runs but is not live come: each looks at every live node
    // and pays for them (about 40 ops here), so under a budget of 100 ops the breaks
    // spread over ticks, with overruns, instead of holding one tick (`later=1` ran at
    // 0.25 s; at 0.15 s when breaks did not pay, the blocks' start being slow too).
    let mut a = Asm::new();
    let mut blocks = Vec::new();
    for i in 0..100 {
        let v = format!("c{i}");
        a.var(&v, VarKind::Number);
        let code = vec![count_to(&mut a, &v, 3.0, 1.0)];
        blocks.push(a.block(code));
        a.blank();
    }
    let mut code = vec![a.wait("wait(0.1)", 0.1)];
    for _ in 0..20 {
        code.push(a.brk("break(later)", "later"));
    }
    code.push(a.assign("later=1", "later", &[X::N(1.0)]));
    blocks.push(a.block(code));
    let cfg = Config {
        budget_ops: 100,
        ..config()
    };
    let mut vm = vm(a.task(&blocks), robot(), cfg);
    assert!(vm.run_for(10.0));
    assert_eq!(vm.live(), 0);
    let later = when(&vm, "var", "later=1").expect("written");
    assert!(later >= 0.2, "the breaks took ticks of their own: {later}");
    assert!(vm.events().iter().any(|e| e.kind.name() == "overrun"));
    assert_eq!(
        vm.var("c0").map(|v| v.value),
        Some(3.0),
        "nothing was broken"
    );
}

//! Test 5 (section 5.6.4, Figures 52-55): the short task on MoRo in the
//! empty world. Linked commands do not stop between them; the robot comes
//! back to its start by `use(goalpos)` and reversed commands.

mod experiment;

use experiment::{A, Task, moro, run, shipped, speed, vm};
use ilmr_motion::path::{TurnSpec, straight, turn};
use ilmr_motion::{Direction, Path, Pose};
use ilmr_stdlib::Command;

pub const SEED: u64 = 5;

fn figure_52() -> ilmr_vm::Module {
    let t = speed(Task::new(), 0.4)
        .cmd("goahead(1.2)", Command::Goahead, &[A::N(1.2)], None)
        .cmd(
            "turn(d=90,c=0.5)",
            Command::Turn,
            &[A::S("d", 90.0), A::S("c", 0.5)],
            None,
        )
        .cmd("m=goahead(0.7)", Command::Goahead, &[A::N(0.7)], Some("m"))
        .wait_var("wait(m)", "m");
    speed(t, -0.4)
        .cmd("use(goalpos)", Command::Use, &[A::W("goalpos")], None)
        .cmd("goahead(-0.7)", Command::Goahead, &[A::N(-0.7)], None)
        .cmd(
            "turn(d=90,c=0.5) ",
            Command::Turn,
            &[A::S("d", 90.0), A::S("c", 0.5)],
            None,
        )
        .cmd("goahead(-1.2)", Command::Goahead, &[A::N(-1.2)], None)
        .finish()
}

/// The ideal route: out, and back over the same ground.
fn route() -> Path {
    let out = straight(Pose::new(0.0, 0.0, 0.0), 1.2, 0.01).expect("valid");
    let arc = turn(
        out.end_pose(),
        &TurnSpec::degrees(90.0, 0.5),
        Direction::Forward,
        0.01,
    )
    .expect("valid");
    let leg = straight(arc.end_pose(), 0.7, 0.01).expect("valid");
    out.concat(&arc, 1e-6)
        .and_then(|p| p.concat(&leg, 1e-6))
        .expect("commands meet")
}

#[test]
fn figure_52_links_without_stopping_and_returns_to_the_start() {
    let mut vm = vm(figure_52(), moro(shipped("empty"), SEED));
    let out = run(&mut vm, 60.0);
    assert!(out.finished, "the task finished");
    let ideal = route();
    let worst = out
        .trace
        .iter()
        .map(|p| ideal.distance_to(&nalgebra::Point2::new(p.x, p.y)))
        .fold(0.0, f64::max);
    let links = experiment::linked_ends(&vm);
    // Linking happens within one tick: the end of the first command and the
    // start of the next share a time stamp.
    let link_gap = link_gap(&vm);
    // Between reaching 0.4 m/s and the last braking on the way out, the
    // speed never dips (the forward half is three linked commands).
    let wait_at = vm
        .events()
        .iter()
        .find(|e| {
            e.stmt
                .and_then(|s| vm.module().stmt(s))
                .is_some_and(|s| s.text == "m=goahead(0.7)")
                && e.kind.name() == "end"
        })
        .map(|e| e.tick as usize)
        .expect("m ended");
    let forward = &out.speeds[..wait_at.min(out.speeds.len())];
    let cruise = forward.iter().position(|v| *v >= 0.39).expect("cruises");
    let braking = forward.iter().rposition(|v| *v >= 0.39).expect("cruises");
    let dip = forward[cruise..=braking]
        .iter()
        .cloned()
        .fold(f64::MAX, f64::min);
    let end = out.trace.last().expect("moved");
    let home = end.x.hypot(end.y);
    println!(
        "Figure 52: max position error {worst:.4} m, {links} links, longest link {link_gap:.2} s, \
         lowest speed between linked commands {dip:.3} m/s, back {home:.4} m from the start"
    );
    assert_eq!(links, 4, "two links out, two back");
    assert!(link_gap <= 0.1 + 1e-9, "linking took {link_gap} s");
    assert!(
        dip >= 0.38,
        "the speed dipped to {dip} between linked commands"
    );
    // Figure 53: 0.07 m.
    assert!(worst <= 0.07, "max position error {worst}");
    assert!(home <= 0.07, "ended {home} m from the start");
}

/// Longest time between a linked end and the next movement's start.
fn link_gap(vm: &experiment::SimVm) -> f64 {
    let mut worst: f64 = 0.0;
    let events = vm.events();
    for (i, e) in events.iter().enumerate() {
        if matches!(e.kind, ilmr_vm::EventKind::End { linked: true, .. })
            && let Some(next) = events[i..].iter().find(|n| n.kind.name() == "start")
        {
            worst = worst.max(next.t - e.t);
        }
    }
    worst
}

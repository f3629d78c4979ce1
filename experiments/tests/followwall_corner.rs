//! `followwall` at the corner at a corridor's end (issue 15 item 4): the leg
//! stops short of the wall ahead instead of leading the robot into the avoider's
//! area (where, finding no way round a wall, it stood blocked with the leg still
//! pointing into it), and the robot turns the corner away from the wall it
//! keeps as soon as the turn has room, then follows the wall ahead on.

use ilmr_experiments::harness::{self, moro, shipped};
use ilmr_hal::Pose;

/// In the office's 2 m main corridor heading west, the corridor's north wall on
/// the right; at its west end the corridor turns south (the west corridor, 2 m
/// wide too), which ends in the lobby's south wall.
#[test]
fn followwall_turns_the_corner_at_a_corridors_end() {
    let mut w = shipped("office").expect("the office");
    w.start = ilmr_sim::Pose {
        x: 8.0,
        y: 12.5,
        h: std::f64::consts::PI,
    };
    let robot = moro(w, 3).expect("MoRo starts");
    let text = "obsavoid(on)\nfollowwall(right)\n";
    let module = harness::compile("corner.ilmr", text, robot.model()).expect("compiles");
    let mut vm = harness::vm(module, robot).expect("the VM starts");
    let out = harness::run(&mut vm, 60.0);
    let end: Pose = *out.trace.last().expect("moved");
    let south = out
        .trace
        .iter()
        .filter(|p| p.y < 10.5 && (p.h + std::f64::consts::FRAC_PI_2).abs() < 0.2)
        .count();
    println!(
        "followwall(right) from (8, 12.5) west: end ({:.2}, {:.2}, {:.1} deg), {} poses heading south below y = 10.5, contacts {}",
        end.x,
        end.y,
        end.h.to_degrees(),
        south,
        vm.hal().sim().contact_count()
    );
    assert_eq!(vm.hal().sim().contact_count(), 0, "no contact");
    assert!(
        south > 0,
        "went round the corner and on south: ended at {end:?}"
    );
    // Down the west corridor, the outer wall on the right, and round its end
    // into the lobby (below y = 4), where the next corner turns it east.
    assert!(end.y < 4.0, "reached the lobby: {end:?}");
}

/// Runs `text` on MoRo in the office from beside the lab bench, (8, 5)
/// heading east, the bench 2.1 m to the left, the lab's south wall 1 m to
/// the right and its east wall 4.5 m ahead.
fn from_the_bench(text: &str, seconds: f64) -> ilmr_experiments::harness::SimVm {
    let mut w = shipped("office").expect("the office");
    w.start = ilmr_sim::Pose {
        x: 8.0,
        y: 5.0,
        h: 0.0,
    };
    // As `ilmrc run` has it: the calibrated errors, seed 0.
    let robot = harness::moro_with(w, 0, ilmr_sim::SimProfile::Calibrated).expect("MoRo starts");
    let module = harness::compile("bench.ilmr", text, robot.model()).expect("compiles");
    let mut vm = harness::vm(module, robot).expect("the VM starts");
    harness::run(&mut vm, seconds);
    vm
}

fn reason(vm: &ilmr_experiments::harness::SimVm, text: &str) -> Option<String> {
    vm.events().iter().find_map(|e| {
        let s = e.stmt.and_then(|s| vm.module().stmt(s))?;
        match &e.kind {
            ilmr_vm::EventKind::End { reason, .. } if s.text == text => reason.clone(),
            _ => None,
        }
    })
}

fn held(vm: &ilmr_experiments::harness::SimVm) -> usize {
    vm.events()
        .iter()
        .filter(|e| matches!(e.kind, ilmr_vm::EventKind::Fault { .. }))
        .count()
}

/// The bench ends 1.5 m on and the lab's east wall stands ahead: the leg stops
/// short of it, where neither wall following nor a right turn round the
/// corner (the lab's south wall 2 m off) can go on. Standing there until
/// the run's time is up said nothing; the command is refused, with why.
#[test]
fn followwall_at_the_end_of_its_wall_with_no_room_to_turn_is_refused_with_why() {
    let vm = from_the_bench("followwall(left)\n", 60.0);
    let why = reason(&vm, "followwall(left)");
    println!(
        "followwall(left) from (8, 5): {:?} at {:.2} s, {why:?}",
        harness::ended(&vm, "followwall(left)"),
        vm.time()
    );
    assert_eq!(
        harness::ended(&vm, "followwall(left)").as_deref(),
        Some("refused")
    );
    let why = why.expect("a reason");
    assert!(
        why.contains("wall ahead") && why.contains("no room to turn right"),
        "{why}"
    );
    assert!(
        vm.time() < 30.0,
        "refused once it stands: {:.2} s",
        vm.time()
    );
    assert_eq!(vm.hal().sim().contact_count(), 0);
}

/// A metre on from (8, 5) the quarter circle left ends facing north just
/// past the bench's end: the turn completes there, and the supervisor does
/// not hold the robot for the bench it has turned past.
#[test]
fn turn_left_past_the_end_of_the_bench_completes_unheld() {
    let vm = from_the_bench("goahead(1)\nturn(left)\n", 40.0);
    let end = vm.hal().sim().true_pose();
    println!(
        "goahead(1), turn(left) from (8, 5): {:?}, end ({:.2}, {:.2}, {:.1} deg), faults {}",
        harness::ended(&vm, "turn(left)"),
        end.x,
        end.y,
        end.h.to_degrees(),
        held(&vm)
    );
    assert_eq!(
        harness::ended(&vm, "turn(left)").as_deref(),
        Some("completed")
    );
    assert_eq!(held(&vm), 0, "never held");
    assert!(
        (end.h.to_degrees() - 90.0).abs() < 5.0,
        "facing north: {end:?}"
    );
    assert_eq!(vm.hal().sim().contact_count(), 0);
}

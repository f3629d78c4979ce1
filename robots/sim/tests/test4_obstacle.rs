//! Test 4 (section 5.6.3): `obsavoid(on)` then `goahead(5)` on MoRo at
//! 0.3 m/s with a box on the path (tests/worlds/obstacle.toml); and the
//! `stop` and `off` modes of the same run (with `off` the avoider ignores the
//! box and the VM's supervisor holds the robot before it).

mod experiment;

use experiment::{A, Task, moro, run, speed, vm, world};
use ilmr_stdlib::Command;

pub const SEED: u64 = 4;
const BOX: (f64, f64, f64) = (3.0, 0.05, 0.2);

fn task(mode: &str) -> ilmr_vm::Module {
    let t = Task::new().cmd(
        &format!("obsavoid({mode})"),
        Command::ObsAvoid,
        &[A::W(mode)],
        None,
    );
    speed(t, 0.3)
        .cmd("goahead(5)", Command::Goahead, &[A::N(5.0)], None)
        .finish()
}

/// Smallest distance from the robot's footprint to the box over the run.
fn clearance(robot: &ilmr_sim::SimRobot, trace: &[ilmr_hal::Pose]) -> f64 {
    let (bx, by, half) = BOX;
    trace
        .iter()
        .map(|p| {
            let fp = robot.sim().footprint(ilmr_sim::Pose::new(p.x, p.y, p.h));
            fp.corners()
                .iter()
                .map(|c| ((c.x - bx).abs() - half).max((c.y - by).abs() - half))
                .fold(f64::MAX, f64::min)
        })
        .fold(f64::MAX, f64::min)
}

#[test]
fn obsavoid_on_passes_the_obstacle_and_returns_to_the_path() {
    let mut vm = vm(task("on"), moro(world("obstacle.toml"), SEED));
    let out = run(&mut vm, 60.0);
    assert!(out.finished, "goahead(5) finished");
    assert_eq!(vm.hal().sim().contact_count(), 0, "touched the box");
    let aside = out.trace.iter().map(|p| p.y.abs()).fold(0.0, f64::max);
    let end = out.trace.last().expect("moved");
    let c = clearance(vm.hal(), &out.trace);
    println!(
        "obstacle test: widest {aside:.3} m off the path, corner clearance {c:.3} m, \
         end ({:.3}, {:.3}), {:.1} s",
        end.x,
        end.y,
        vm.time()
    );
    assert!(aside > 0.4, "went round the box: {aside}");
    assert!(c > 0.0, "the footprint never reached the box");
    assert!((end.x - 5.0).abs() < 0.1, "ended at {end:?}");
    assert!(end.y.abs() < 0.15, "back on the path: {end:?}");
}

#[test]
fn obsavoid_stop_halts_before_the_obstacle() {
    let mut vm = vm(task("stop"), moro(world("obstacle.toml"), SEED));
    let out = run(&mut vm, 30.0);
    assert!(!out.finished, "blocked: goahead(5) does not finish");
    assert_eq!(vm.hal().sim().contact_count(), 0);
    let end = out.trace.last().expect("moved");
    let front = end.x + vm.config().front_offset;
    println!(
        "obsavoid(stop): front stopped at x = {front:.3} m, box at {}",
        BOX.0 - BOX.2
    );
    assert!(front < BOX.0 - BOX.2, "front {front}");
    assert!(vm.hal().sim().true_speed().abs() < 1e-3);
}

#[test]
fn obsavoid_off_ignores_the_obstacle_until_the_supervisor_holds() {
    // The avoider ignores the box; the VM's supervisor (issue 7) still
    // holds the robot when the box comes inside its stopping distance.
    let mut vm = vm(task("off"), moro(world("obstacle.toml"), SEED));
    let out = run(&mut vm, 30.0);
    assert!(!out.finished);
    let held = vm
        .events()
        .iter()
        .any(|e| ilmr_vm::render_event(vm.module(), e).contains("\"obstacle_near\""));
    let end = out.trace.last().expect("moved");
    let front = end.x + vm.config().front_offset;
    println!("obsavoid(off): held by the supervisor, front at x = {front:.3} m");
    assert!(held, "an obstacle_near fault");
    assert_eq!(vm.hal().sim().contact_count(), 0);
    assert!(vm.hal().sim().true_speed().abs() < 1e-3);
}

//! Test 2 (section 5.6.1, Table 11): `turn(left)` in a corridor on MoRo at
//! 0.3 m/s. There is no room to turn at the start, so the robot follows the
//! left wall at its current distance until the corner, then turns; a linked
//! `goahead(1.5)` takes it up the side corridor.

mod experiment;

use experiment::{A, Task, moro, run, speed, vm, world};
use ilmr_stdlib::Command;

pub const SEED: u64 = 2;
/// The corner of the corridor (tests/worlds/corridor.toml).
const CORNER_X: f64 = 10.0;

#[test]
fn turn_left_follows_the_wall_to_the_corner_then_turns() {
    let task = speed(Task::new(), 0.3)
        .cmd("t=turn(left)", Command::Turn, &[A::W("left")], Some("t"))
        .cmd("goahead(1.5)", Command::Goahead, &[A::N(1.5)], None)
        .finish();
    let mut vm = vm(task, moro(world("corridor.toml"), SEED));
    let out = run(&mut vm, 80.0);
    assert!(out.finished, "turn(left) and goahead(1.5) finished");
    assert_eq!(
        experiment::ended(&vm, "t=turn(left)").as_deref(),
        Some("completed")
    );
    assert_eq!(vm.hal().sim().contact_count(), 0, "touched a wall");
    let y0 = out.trace[0].y;
    // Before the corner the robot keeps its distance to the left wall.
    let before: Vec<_> = out.trace.iter().filter(|p| p.x < CORNER_X - 1.0).collect();
    let y_dev = before.iter().map(|p| (p.y - y0).abs()).fold(0.0, f64::max);
    let turned_early = before.iter().any(|p| p.h.abs() > 5f64.to_radians());
    // After the turn it heads north in a straight line.
    let north: Vec<_> = out
        .trace
        .iter()
        .filter(|p| (p.h - std::f64::consts::FRAC_PI_2).abs() < 3f64.to_radians())
        .collect();
    let (lo, hi) = north.iter().fold((f64::MAX, f64::MIN), |(lo, hi), p| {
        (lo.min(p.x), hi.max(p.x))
    });
    let x_dev = (hi - lo) / 2.0;
    let end = out.trace.last().expect("moved");
    println!(
        "turn(left) in the corridor: y deviation before the corner {y_dev:.4} m, \
         x deviation heading north {x_dev:.4} m, end ({:.3}, {:.3}, {:.1} deg)",
        end.x,
        end.y,
        end.h.to_degrees()
    );
    assert!(!turned_early, "the turn began before the corner");
    assert!(!north.is_empty(), "never headed north");
    // Table 11: 0.04 m on x, 0.01 m on y.
    assert!(y_dev <= 0.04, "y deviation {y_dev}");
    assert!(x_dev <= 0.06, "x deviation {x_dev}");
    assert!(
        (CORNER_X..12.4).contains(&end.x),
        "ended in the side corridor: {end:?}"
    );
    assert!(end.y > 3.0, "went up the side corridor: {end:?}");
}

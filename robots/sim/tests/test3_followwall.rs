//! Test 3 (section 5.6.2, Table 12): `followwall(left,1.0)` on MoRo at
//! 0.3 m/s from 0.4, 1.0 and 1.2 m off the goal distance, past a door
//! opening (tests/worlds/wall_*.toml).

mod experiment;

use experiment::{A, Task, moro, speed, vm, world};
use ilmr_stdlib::Command;

pub const SEED: u64 = 3;
const WALL_HALF_THICKNESS: f64 = 0.075;

/// (overshoot past the distance, |error| after 3 m of travel, |error| at the end).
fn follow(off: f64) -> (f64, f64, f64) {
    // The distance is to the wall's face: its line is 0.15 m thick.
    let wall_y = 1.0 + off - WALL_HALF_THICKNESS;
    let task = speed(Task::new(), 0.3)
        .cmd(
            "followwall(left,1.0)",
            Command::FollowWall,
            &[A::W("left"), A::N(1.0)],
            None,
        )
        .finish();
    let mut vm = vm(task, moro(world(&format!("wall_{off:.1}.toml")), SEED));
    let mut travelled = 0.0;
    let mut last = vm.hal().true_pose();
    let (mut overshoot, mut at3) = (0.0f64, f64::NAN);
    while travelled < 14.0 && vm.time() < 80.0 {
        vm.tick();
        let p = vm.hal().true_pose();
        travelled += (p.x - last.x).hypot(p.y - last.y);
        last = p;
        let distance = wall_y - p.y;
        overshoot = overshoot.max(1.0 - distance);
        if at3.is_nan() && travelled >= 3.0 {
            at3 = (distance - 1.0).abs();
        }
    }
    assert_eq!(vm.hal().sim().contact_count(), 0);
    assert!(!vm.finished(), "followwall runs until it is broken");
    (overshoot, at3, (wall_y - last.y - 1.0).abs())
}

#[test]
fn followwall_reaches_the_distance_within_three_metres() {
    for (off, table) in [(0.4, 0.02), (1.0, 0.05), (1.2, 0.03)] {
        let (overshoot, at3, end) = follow(off);
        println!(
            "followwall(left,1.0) from {off} m off: overshoot {overshoot:.4} m \
             (Table 12: {table} m), error after 3 m {at3:.4} m, at the end {end:.4} m"
        );
        assert!(overshoot <= table + 0.05, "overshoot {overshoot}");
        assert!(at3 <= 0.1, "error after 3 m {at3}");
        assert!(end <= 0.03, "error at the end {end}");
    }
}

//! Test 3 of section 5.6.2: `followwall(left,1.0)` from 0.4, 1.0 and 1.2 m
//! off the goal distance, at 0.3 m/s: fit the wall, put a goal 3 m on at
//! the distance, plan a Bezier to it, and re-plan every 2 m.

mod common;

use common::{MORO, Sim};
use ilmr_motion::bezier::plan_to_pose;
use ilmr_motion::controller::stop_in;
use ilmr_motion::wall::{FOLLOWWALL_REPLAN, WallParams, fit_wall, followwall_goal};
use ilmr_motion::{Pose, Side};
use nalgebra::Point2;

/// A wall along y = `y` from x = -3 to 20 with a 1 m door opening at x = 6.
fn wall(y: f64) -> Vec<Point2<f64>> {
    (0..=230)
        .map(|i| -3.0 + i as f64 * 0.1)
        .filter(|x| !(6.0..7.0).contains(x))
        .map(|x| Point2::new(x, y))
        .collect()
}

/// Returns (closest approach below the goal distance, |error| after 3 m,
/// |error| at the end).
fn follow(initial_distance: f64) -> (f64, f64, f64) {
    let d = 1.0;
    let map = wall(initial_distance);
    let mut sim = Sim::new(MORO, Pose::new(0.0, 0.0, 0.0));
    let mut travelled = 0.0;
    let mut overshoot = 0.0f64;
    let mut error_at_3m = f64::NAN;
    while travelled < 12.0 {
        let line =
            fit_wall(&sim.pose, &map, Side::Left, &WallParams::default()).expect("wall seen");
        let goal = followwall_goal(&sim.pose, &line, Side::Left, d);
        let plan = plan_to_pose(sim.pose, goal, MORO.max_curvature, false).expect("goal reachable");
        let path = plan.path().expect("one segment");
        let mut k = 0;
        let mut leg = 0.0;
        while leg < FOLLOWWALL_REPLAN {
            let before = sim.pose.position();
            // The next goal is always queued: drive through the end.
            let stop = stop_in(&path, k, &sim.pose, 0.0, true);
            let (nk, _) = sim.tick(&path, k, 0.3, stop);
            k = nk;
            let step = (sim.pose.position() - before).norm();
            leg += step;
            travelled += step;
            let distance = initial_distance - sim.pose.y;
            overshoot = overshoot.max(d - distance);
            if error_at_3m.is_nan() && travelled >= 3.0 {
                error_at_3m = (distance - d).abs();
            }
        }
    }
    (
        overshoot,
        error_at_3m,
        (initial_distance - sim.pose.y - d).abs(),
    )
}

#[test]
fn followwall_reaches_the_distance_without_overshoot() {
    for off in [0.4, 1.0, 1.2] {
        let (overshoot, at3, end) = follow(1.0 + off);
        println!(
            "followwall(left,1.0) from {off} m off: overshoot {overshoot:.3} m, \
             error after 3 m {at3:.3} m, at the end {end:.4} m"
        );
        // Table 12: overshoot 0.02-0.05 m, distance reached within 3 m.
        // The kinematic loop lands within 0.01 m of those figures.
        assert!(overshoot <= 0.07, "overshoot {overshoot}");
        assert!(at3 <= 0.05, "error after 3 m {at3}");
        assert!(end <= 0.01, "final error {end}");
    }
}

//! One controller cycle and one Bezier plan: the two computations a
//! movement command repeats (every 10 ms, and at each (re)plan).

use ilmr_motion::controller::{self, ControlInput, ControllerParams};
use ilmr_motion::path::{TurnSpec, turn};
use ilmr_motion::{Direction, Pose, plan_to_pose};

fn main() {
    divan::main();
}

#[divan::bench(args = [0.2, 0.8])]
fn controller_step(bencher: divan::Bencher, speed: f64) {
    let spec = TurnSpec {
        lead_out: 1.0,
        ..TurnSpec::degrees(90.0, 0.6)
    };
    let path = turn(Pose::new(0.0, 0.0, 0.0), &spec, Direction::Forward, 0.05).expect("valid turn");
    let params = ControllerParams::new(1.0 / 0.75, 1.0, 0.01);
    let input = ControlInput {
        path: &path,
        k: 20,
        pose: Pose::new(0.95, 0.05, 0.3),
        curvature: 0.4,
        speed,
    };
    bencher.bench(|| controller::step(&params, divan::black_box(&input)));
}

#[divan::bench]
fn bezier_plan_direct() {
    let goal = Pose::from_degrees(3.0, 4.0, 90.0);
    divan::black_box(plan_to_pose(
        Pose::new(0.0, 0.0, 0.0),
        divan::black_box(goal),
        0.6,
        false,
    ))
    .ok();
}

#[divan::bench]
fn bezier_plan_reverse_fallback() {
    let goal = Pose::from_degrees(0.0, 3.0, 90.0);
    divan::black_box(plan_to_pose(
        Pose::new(0.0, 0.0, 0.0),
        divan::black_box(goal),
        0.5,
        true,
    ))
    .ok();
}

//! Exact turns driven backwards (Figure 56's TURN1 and TURN2): the sign of `d`
//! is the steering side, so after `speed(-0.4)` the robot retraces the arc a
//! forward `turn(d=..)` draws and its heading changes by `-d`.

mod common;

use std::f64::consts::{FRAC_PI_2, PI};

use common::{A, Asm, config, robot, vm};
use ilmr_hal::Pose;
use ilmr_stdlib::Command;

const C: f64 = 0.25;

/// Runs `speed(-0.4)` then `t=turn(d=deg,c=0.25)` from `start` and checks the
/// robot never drives forwards, stays on the circle of the forward arc, ends
/// with its heading changed by `-deg` in the time the arc takes, and `t` holds
/// the arc length.
fn reverse_turn(start: Pose, deg: f64) {
    let mut a = Asm::new();
    let text = format!("t=turn(d={deg},c={C})");
    let code = vec![
        a.cmd("speed(-0.4)", Command::Speed, &[A::N(-0.4)], None),
        a.cmd(
            &text,
            Command::Turn,
            &[A::S("d", deg), A::S("c", C)],
            Some("t"),
        ),
    ];
    let b = a.block(code);
    let mut vm = vm(a.task(&[b]), robot().at(start), config());

    let r = 1.0 / C;
    let side = deg.signum();
    // The forward turn's centre: r to the steering side of the start.
    let centre = (
        start.x - side * r * start.h.sin(),
        start.y + side * r * start.h.cos(),
    );
    let arc = deg.abs().to_radians() * r;
    // The arc at 0.4 m/s plus acceleration and braking.
    let limit = arc / 0.4 + 5.0;
    let mut worst: f64 = 0.0;
    let mut fastest_forward: f64 = 0.0;
    while !vm.finished() && vm.time() < limit {
        vm.tick();
        let p = vm.hal().true_pose();
        fastest_forward = fastest_forward.max(vm.hal().speed());
        worst = worst.max(((p.x - centre.0).hypot(p.y - centre.1) - r).abs());
    }
    assert!(
        vm.finished(),
        "{text} from {start:?}: not done after {limit:.1} s"
    );
    assert!(
        fastest_forward <= 1e-9,
        "{text} from {start:?} drove forwards at {fastest_forward} m/s"
    );
    assert!(worst < 0.08, "{text}: max deviation from the arc {worst}");
    let p = vm.hal().true_pose();
    let turned = ilmr_geometry::angle_diff(p.h, start.h);
    assert!(
        (turned + deg.to_radians()).abs() < 0.05,
        "{text} from {start:?} turned {} deg",
        turned.to_degrees()
    );
    // The end of the forward arc's circle, reached backwards: the radius to
    // the robot has swung by -deg as well.
    let swing = -deg.to_radians();
    let (sx, sy) = (start.x - centre.0, start.y - centre.1);
    let end = (
        centre.0 + sx * swing.cos() - sy * swing.sin(),
        centre.1 + sx * swing.sin() + sy * swing.cos(),
    );
    assert!(
        (p.x - end.0).hypot(p.y - end.1) < 0.1,
        "{text} from {start:?} ended at {p:?}, not {end:?}"
    );
    let t = vm.var("t").expect("t");
    assert!((t.dist - arc).abs() < 0.05, "{t:?}");
}

#[test]
fn a_reversing_turn_with_negative_d_steers_right_and_swings_the_nose_left() {
    // TURN2 of Figure 56 where the loop leaves it: facing -y after TURN1.
    reverse_turn(Pose::new(2.0, 4.0, -FRAC_PI_2), -90.0);
    reverse_turn(Pose::new(0.0, 0.0, 0.0), -90.0);
    // Across the +-pi seam of the heading.
    reverse_turn(Pose::new(1.0, -2.0, PI), -90.0);
    reverse_turn(Pose::new(0.0, 0.0, FRAC_PI_2), -45.0);
}

#[test]
fn a_reversing_turn_with_positive_d_steers_left_and_swings_the_nose_right() {
    // TURN1 of Figure 56 at the end of the taught path.
    reverse_turn(Pose::new(6.0, 0.0, 0.0), 90.0);
    reverse_turn(Pose::new(0.0, 0.0, -PI + 0.1), 90.0);
}

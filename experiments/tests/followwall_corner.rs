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

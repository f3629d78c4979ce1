//! Test 4: `obsavoid(on)` passes the box and returns to the path; `stop` halts before
//! it; with `off` the avoider ignores it and the VM's supervisor holds the robot.

use ilmr_experiments::test4_obstacle::{ASIDE, BACK_WITHIN, BOX, END_WITHIN, Mode, STANDS, avoid};

#[test]
fn obsavoid_on_passes_the_obstacle_and_returns_to_the_path() {
    let on = avoid(Mode::On).expect("obsavoid(on) runs");
    println!(
        "obstacle test: widest {:.3} m off the path, corner clearance {:.3} m, \
         end ({:.3}, {:.3}), {:.1} s",
        on.aside, on.clearance, on.end.x, on.end.y, on.time
    );
    assert!(on.finished, "goahead(5) finished");
    assert_eq!(on.contacts, 0, "touched the box");
    assert!(on.aside > ASIDE, "went round the box: {}", on.aside);
    assert!(on.clearance > 0.0, "the footprint never reached the box");
    assert!((on.end.x - 5.0).abs() < END_WITHIN, "ended at {:?}", on.end);
    assert!(
        on.end.y.abs() < BACK_WITHIN,
        "back on the path: {:?}",
        on.end
    );
}

#[test]
fn obsavoid_stop_halts_before_the_obstacle() {
    let stop = avoid(Mode::Stop).expect("obsavoid(stop) runs");
    println!(
        "obsavoid(stop): front stopped at x = {:.3} m, box at {}",
        stop.front,
        BOX.0 - BOX.2
    );
    assert!(!stop.finished, "blocked: goahead(5) does not finish");
    assert_eq!(stop.contacts, 0);
    assert!(stop.front < BOX.0 - BOX.2, "front {}", stop.front);
    assert!(stop.speed.abs() < STANDS);
}

#[test]
fn obsavoid_off_ignores_the_obstacle_until_the_supervisor_holds() {
    // The avoider ignores the box; the VM's supervisor (issue 7) still holds the
    // robot when the box comes inside its stopping distance.
    let off = avoid(Mode::Off).expect("obsavoid(off) runs");
    println!(
        "obsavoid(off): held by the supervisor, front at x = {:.3} m",
        off.front
    );
    assert!(!off.finished);
    assert!(off.held, "an obstacle_near fault");
    assert_eq!(off.contacts, 0);
    assert!(off.speed.abs() < STANDS);
}

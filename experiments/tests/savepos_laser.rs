//! `savepos(name,laser)` on Workpartner (section 4.5.1): the position stored
//! is where the laser pointer on the pan-tilt head hits, not the robot's.

mod experiment;

use experiment::{compile, ended, run, shipped, vm, workpartner};

/// The yard's start is (15, 15) facing east; the building's south wall
/// (0.4 m thick) has its face at y = 19.8 from x = 25 on.
const WALL_FACE: f64 = 20.0 - 0.2;

fn saved(pan_deg: f64) -> experiment::SimVm {
    let mut robot = workpartner(shipped("yard"), 3);
    robot
        .sim_mut()
        .set_pan_tilt(pan_deg.to_radians(), 0.0)
        .expect("the head pans");
    let task = compile(
        "savepos.ilmr",
        // The guards only make the names variables of the task.
        "wait(1)\nsavepos(spot,laser)\nsavepos(here)\nif(spot)\n  speed(0.2)\nendif\nif(here)\n  speed(0.2)\nendif\n",
        robot.model(),
    );
    let mut vm = vm(task, robot);
    run(&mut vm, 3.0);
    vm
}

#[test]
fn the_laser_spot_on_the_building_is_saved() {
    let vm = saved(20.0);
    let spot = vm.var("spot").expect("bound");
    let here = vm.var("here").expect("bound");
    assert_eq!(ended(&vm, "savepos(spot,laser)"), None, "not refused");
    assert_eq!(spot.status, 1.0);
    // The beam leaves the head at 20 degrees left and meets the wall face.
    let head = vm
        .hal()
        .sim()
        .config()
        .camera
        .as_ref()
        .expect("a head")
        .head;
    let eye = (15.0 + head.x, 15.0 + head.y);
    let expect_x = eye.0 + (WALL_FACE - eye.1) / 20f64.to_radians().tan();
    assert!((spot.y - WALL_FACE).abs() < 0.05, "{spot:?}");
    assert!((spot.x - expect_x).abs() < 0.1, "{spot:?} vs x {expect_x}");
    // Heading along the beam, from the robot's estimated heading.
    assert!((spot.h - 20f64.to_radians()).abs() < 1f64.to_radians());
    // Without a device it is the robot's own position.
    assert!((here.x - 15.0).abs() < 0.05 && (here.y - 15.0).abs() < 0.05);
}

#[test]
fn a_beam_that_meets_nothing_saves_nothing() {
    // Panned right over open ground to the south: no return within 30 m.
    let vm = saved(-90.0);
    assert_eq!(
        ended(&vm, "savepos(spot,laser)").as_deref(),
        Some("refused")
    );
    assert_eq!(vm.var("spot").map(|v| v.status), Some(0.0), "nothing saved");
    let here = vm.var("here").expect("bound");
    assert!((here.x - 15.0).abs() < 0.05);
}

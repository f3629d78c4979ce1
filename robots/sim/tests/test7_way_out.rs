//! Test 7 (section 5.6.6, Figures 58-59): MoRo learns the way out of the
//! laboratory from an abstract description (`examples/way_out.ilmr`, compiled
//! as `ilmrc run` compiles it) in `tests/worlds/lab.toml` (the office's lab
//! with 3 m corridors): two left turns round the bench, the lab door found on
//! the right by the scanner, through it, two left turns, 5 m along the lab
//! wall, left into the lobby and 1 m on. The path recorded on the way
//! (`record(path_1)`) is then driven again from the start with
//! `followpath(path_1)`.
//!
//! `if` is a guard that does not hold its block back (ilmr-guide), so
//! `record(close)` is issued with it, when the door has been found: path_1
//! is the way round the bench to where the door was seen.

mod experiment;

use experiment::{
    A, Task, compile_example, distance_to_polyline, ended, length, moro, run, vm, world,
};
use ilmr_stdlib::Command;

pub const SEED: u64 = 7;

/// The lab door's middle (corridor_south at y = 11.5, x = 5.0).
const DOOR: (f64, f64) = (5.0, 11.5);

#[test]
fn figure_58_finds_the_door_completes_and_its_path_drives_again() {
    let robot = moro(world("lab.toml"), SEED);
    let module = compile_example("way_out.ilmr", robot.model());
    let mut vm = vm(module, robot);
    let out = run(&mut vm, 240.0);
    let path: Vec<(f64, f64)> = vm.paths().get("path_1").cloned().unwrap_or_default();
    let door = vm.var("door").expect("door is a variable");
    let end = *out.trace.last().expect("moved");
    let driven = length(&out.trace);
    println!(
        "test 7: {} in {:.1} s, {driven:.1} m driven, door seen at ({:.3}, {:.3}) heading {:.1} deg, \
         end ({:.2}, {:.2}, {:.1} deg), path_1 {} points, contacts {}",
        if out.finished {
            "completed"
        } else {
            "NOT completed"
        },
        vm.time(),
        door.x,
        door.y,
        door.h.to_degrees(),
        end.x,
        end.y,
        end.h.to_degrees(),
        path.len(),
        vm.hal().sim().contact_count()
    );
    for text in [
        "turn(left)",
        "t=turn(left)",
        "door=sensor(scanner,door,right)",
        "gotoxy(door)",
        "dist=followwall(left)",
        "if(dist>5)",
        "goahead(1)",
    ] {
        println!("  {text}: {:?}", ended(&vm, text));
    }
    assert!(out.finished, "the task completes");
    assert_eq!(vm.hal().sim().contact_count(), 0, "no contact on the way");
    assert!(
        (door.x - DOOR.0).abs() < 0.15 && (door.y - DOOR.1).abs() < 0.15,
        "the lab door: {door:?}"
    );
    assert_eq!(ended(&vm, "gotoxy(door)").as_deref(), Some("completed"));
    assert_eq!(ended(&vm, "goahead(1)").as_deref(), Some("completed"));
    // Out of the lab, down the west corridor and into the lobby.
    assert!(end.y < 4.0 && end.x > 2.5, "in the lobby: {end:?}");
    assert!(path.len() > 50, "path_1 recorded");

    // Driven again from the start, as the dissertation did.
    let again = Task::new()
        .cmd(
            "f=followpath(path_1)",
            Command::FollowPath,
            &[A::W("path_1")],
            Some("f"),
        )
        .wait_var("wait(f)", "f")
        .finish();
    let mut vm2 = experiment::vm(again, moro(world("lab.toml"), SEED + 1));
    vm2.add_path("path_1", path.clone());
    let out2 = run(&mut vm2, 240.0);
    let last = *out2.trace.last().expect("moved");
    let off = out2
        .trace
        .iter()
        .map(|p| distance_to_polyline(&path, (p.x, p.y)))
        .fold(0.0, f64::max);
    let goal = *path.last().expect("points");
    let miss = (last.x - goal.0).hypot(last.y - goal.1);
    println!(
        "followpath(path_1): {} in {:.1} s, at most {off:.3} m off the recorded path, \
         ends {miss:.3} m from its end, contacts {}",
        ended(&vm2, "f=followpath(path_1)").unwrap_or_default(),
        vm2.time(),
        vm2.hal().sim().contact_count()
    );
    assert_eq!(
        ended(&vm2, "f=followpath(path_1)").as_deref(),
        Some("completed")
    );
    assert_eq!(vm2.hal().sim().contact_count(), 0);
    assert!(off < 0.3, "stays on the recorded path: {off}");
    assert!(miss < 0.1, "ends where it was taught: {miss}");
}

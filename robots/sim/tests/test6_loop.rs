//! Test 6 (section 5.6.5, Figures 56-57): Workpartner drives a taught path
//! back and forth twice (`examples/loop.ilmr` with TURN1 and TURN2 from
//! `examples/skills/turns.ilms`, compiled as `ilmrc run` compiles them) in
//! `tests/worlds/field.toml`. The path is taught first, as the dissertation's
//! was: recorded while the robot drives 25 m, bends 10 degrees left and
//! drives 27 m more.
//!
//! After each end the skill reverses a quarter circle on full lock, so the
//! robot stands across the path 4 m beside it; `followpath` then joins the
//! path a turning diameter along instead of its first point (a three-point
//! turn, as a driver would make it).

mod experiment;

use experiment::{
    compile, compile_example, distance_to_polyline, ended, length, run, vm, workpartner, world,
};

pub const SEED: u64 = 6;

/// Teaches PATH: `record` while driving it, in the frame `locate(0,0,0)`
/// sets at the start, the frame Figure 56 also starts in.
const TEACH: &str = "locate(0,0,0)
wait(1)
record(PATH)
speed(0.4)
goahead(25)
turn(d=10,c=0.1)
g=goahead(27)
wait(g)
record(close)
";

fn teach() -> Vec<(f64, f64)> {
    let robot = workpartner(world("field.toml"), SEED);
    let task = compile("teach.ilmr", TEACH, robot.model());
    let mut vm = vm(task, robot);
    let out = run(&mut vm, 200.0);
    assert!(out.finished, "teaching run ends");
    vm.paths().get("path").cloned().expect("PATH recorded")
}

#[test]
fn figure_56_drives_the_taught_path_back_and_forth_twice() {
    let taught = teach();
    let robot = workpartner(world("field.toml"), SEED);
    let start = robot.true_pose();
    let module = compile_example("loop.ilmr", robot.model());
    let mut vm = vm(module, robot);
    vm.add_path("PATH", taught.clone());
    let out = run(&mut vm, 1200.0);
    let driven = length(&out.trace);
    let followpaths = vm
        .events()
        .iter()
        .filter(|e| {
            matches!(&e.kind, ilmr_vm::EventKind::End { how, .. } if how.name() == "completed")
                && e.stmt
                    .and_then(|s| vm.module().stmt(s))
                    .is_some_and(|s| s.text.starts_with("f=followpath"))
        })
        .count();
    // Off the taught path on its middle part, away from the turns at the
    // ends (the path's frame is the start pose's).
    let (x0, x1) = (10.0, 40.0);
    let off = out
        .trace
        .iter()
        .map(|p| (p.x - start.x, p.y - start.y))
        .filter(|p| (x0..x1).contains(&p.0))
        .map(|p| distance_to_polyline(&taught, p))
        .fold(0.0, f64::max);
    let cnt = vm.var("cnt").map_or(f64::NAN, |v| v.value);
    println!(
        "test 6: {} in {:.1} s, {driven:.1} m driven, {followpaths} followpaths completed, \
         cnt = {cnt}, at most {off:.3} m off the taught path between x = {x0} and {x1} m, \
         taught path {} points, contacts {}",
        if out.finished {
            "completed"
        } else {
            "NOT completed"
        },
        vm.time(),
        taught.len(),
        vm.hal().sim().contact_count()
    );
    assert!(out.finished, "the loop ends");
    assert_eq!(cnt, 2.0);
    assert_eq!(followpaths, 4, "forwards and backwards, twice");
    assert_eq!(ended(&vm, "TURN2").as_deref(), Some("completed"));
    assert!(driven > 200.0, "more than 200 m: {driven}");
    assert_eq!(vm.hal().sim().contact_count(), 0);
    assert!(off < 0.25, "on the taught path: {off}");
}

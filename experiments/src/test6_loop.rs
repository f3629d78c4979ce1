//! Test 6 (section 5.6.5, Figures 56-57): Workpartner drives a taught path back and
//! forth twice (`examples/loop.ilmr` with TURN1 and TURN2 from
//! `examples/skills/turns.ilms`, compiled as `ilmrc run` compiles them) in
//! `field.toml`. The path is taught first, as the dissertation's was: recorded while
//! the robot drives 25 m, bends 10 degrees left and drives 27 m more.
//!
//! After each end the skill reverses a quarter circle on full lock, so the robot
//! stands across the path 4 m beside it; `followpath` then joins the path a turning
//! diameter along instead of its first point (a three-point turn, as a driver would
//! make it).

use ilmr_plot::{Colour, Corner, Figure, Reference, Sample, Scenery, Track};
use ilmr_sim::World;

use crate::harness::{
    self, compile, compile_example, distance_to_polyline, length, workpartner, world,
};
use crate::picture;

pub const SEED: u64 = 6;
pub const WORLD: &str = "field.toml";
/// More than this is driven, metres (the dissertation: more than 200 m).
pub const DRIVEN_BAR: f64 = 200.0;
/// The loop's count at the end, and the followpaths completed (forwards and
/// backwards, twice).
pub const LOOPS: f64 = 2.0;
pub const FOLLOWPATHS: usize = 4;
/// The stretch of the taught path, along x in its frame, on which the robot is
/// measured against it (away from the turns at the ends), and the bar, metres.
pub const MEASURED_X: (f64, f64) = (10.0, 40.0);
pub const OFF_BAR: f64 = 0.25;

/// Teaches PATH: `record` while driving it, in the frame `locate(0,0,0)` sets at the
/// start, the frame Figure 56 also starts in.
pub const TEACH: &str = "locate(0,0,0)
wait(1)
record(PATH)
speed(0.4)
goahead(25)
turn(d=10,c=0.1)
g=goahead(27)
wait(g)
record(close)
";

#[derive(Debug, Clone)]
pub struct Test6 {
    /// Whether the teaching run ended.
    pub taught_finished: bool,
    /// PATH as recorded, in its own frame (the start pose's).
    pub taught: Vec<(f64, f64)>,
    pub finished: bool,
    /// Simulated seconds the loop took.
    pub time: f64,
    /// Metres driven.
    pub driven: f64,
    /// `f=followpath(..)` statements that completed.
    pub followpaths: usize,
    /// The loop counter `cnt` at the end.
    pub cnt: f64,
    /// How TURN2 ended.
    pub turn2_how: Option<String>,
    pub contacts: u64,
    /// Farthest from the taught path within `MEASURED_X`, metres.
    pub off: f64,
    /// The start, where PATH's frame is.
    pub start: ilmr_hal::Pose,
    pub world: World,
    pub track: Vec<Sample>,
}

fn teach(robot: ilmr_sim::SimRobot) -> Result<(bool, Vec<(f64, f64)>), String> {
    let task = compile("teach.ilmr", TEACH, robot.model())?;
    let mut vm = harness::vm(task, robot)?;
    let out = harness::run(&mut vm, 200.0);
    let path = vm
        .paths()
        .get("path")
        .cloned()
        .ok_or("PATH was not recorded")?;
    Ok((out.finished, path))
}

pub fn run() -> Result<Test6, String> {
    let w = world(WORLD)?;
    loop_on(
        workpartner(w.clone(), SEED)?,
        workpartner(w.clone(), SEED)?,
        w,
    )
}

/// Test 6 on robots with `profile`'s errors: PATH taught with `seed`, the loop
/// driven with the next seed (a run of its own, as the dissertation's was).
pub fn run_with(profile: ilmr_sim::SimProfile, seed: u64) -> Result<Test6, String> {
    let w = world(WORLD)?;
    let robot = |seed| harness::workpartner_with(w.clone(), seed, profile);
    loop_on(robot(seed)?, robot(seed.wrapping_add(1))?, w.clone())
}

/// PATH taught on `teacher`, then the loop on `robot`.
fn loop_on(
    teacher: ilmr_sim::SimRobot,
    robot: ilmr_sim::SimRobot,
    w: World,
) -> Result<Test6, String> {
    let (taught_finished, taught) = teach(teacher)?;
    let start = robot.true_pose();
    let module = compile_example("loop.ilmr", robot.model())?;
    let mut vm = harness::vm(module, robot)?;
    vm.add_path("PATH", taught.clone());
    let out = harness::run(&mut vm, 1200.0);
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
    let (x0, x1) = MEASURED_X;
    let off = out
        .trace
        .iter()
        .map(|p| (p.x - start.x, p.y - start.y))
        .filter(|p| (x0..x1).contains(&p.0))
        .map(|p| distance_to_polyline(&taught, p))
        .fold(0.0, f64::max);
    Ok(Test6 {
        taught_finished,
        taught,
        finished: out.finished,
        time: vm.time(),
        driven: length(&out.trace),
        followpaths,
        cnt: vm.var("cnt").map_or(f64::NAN, |v| v.value),
        turn2_how: harness::ended(&vm, "TURN2"),
        contacts: vm.hal().sim().contact_count(),
        off,
        start,
        world: w,
        track: picture::track(&out, vm.config().period),
    })
}

impl Test6 {
    /// Figure 57: the taught path, in the world, and the loops driven over it.
    pub fn figure(&self) -> Figure {
        let mut f = Figure::new(format!(
            "Test 6 (Figure 57): examples/loop.ilmr in {WORLD}, Workpartner, seed {SEED}"
        ));
        f.legend = Corner::UpperRight;
        f.scenery.push(Scenery {
            world: self.world.clone(),
            tint: None,
        });
        let s = self.start.wrapped();
        f.references.push(Reference {
            label: Some("taught PATH".into()),
            colour: Colour::REFERENCE,
            points: self
                .taught
                .iter()
                .map(|&(x, y)| {
                    let p = s.to_world(&ilmr_geometry::Point2::new(x, y));
                    (p.x, p.y)
                })
                .collect(),
        });
        f.tracks.push(Track {
            label: Some("true trajectory, back and forth twice".into()),
            colour: Colour::TRUE_PATH,
            samples: self.track.clone(),
        });
        f
    }
}

//! Test 7 (section 5.6.6, Figures 58-59): MoRo learns the way out of the laboratory
//! from an abstract description (`examples/way_out.ilmr`, compiled as `ilmrc run`
//! compiles it) in the shipped `office` world, whose corridors are 2 m wide as the
//! dissertation's laboratory's: two left turns round the bench, the lab door found on
//! the right by the scanner, through it, two left turns (into the corridor straight
//! from the door, then into the west corridor at its end), 5 m along the lab wall,
//! left into the lobby and 1 m on. Each `turn(left)` is a quarter circle at 1 m
//! radius (three quarters of MoRo's full lock), begun where the robot's outline and
//! the avoider's band have room along it (section 4.5.3). The path
//! recorded on the way (`record(path_1)`) is then driven again from the start with
//! `followpath(path_1)`.
//!
//! `if` is a guard that does not hold its block back (ilmr-guide), so `record(close)`
//! is issued with it, when the door has been found: path_1 is the way round the bench
//! to where the door was seen.

use ilmr_plot::{Colour, Corner, Figure, Mark, Reference, Sample, Scenery, Track};
use ilmr_sim::World;
use ilmr_stdlib::Command;

use crate::harness::{self, A, Task, compile_example, distance_to_polyline, length, moro};
use crate::picture::{self, Hits, Marks};

pub const SEED: u64 = 7;
/// The shipped world (`robots/worlds/office.toml`).
pub const WORLD: &str = "office";
/// The lab door's middle (corridor_south at y = 11.5, x = 5.0), and how near the
/// door variable must be to it, metres.
pub const DOOR: (f64, f64) = (5.0, 11.5);
pub const DOOR_WITHIN: f64 = 0.15;
/// Out of the lab into the lobby: the end is below this y and beyond this x.
pub const LOBBY: (f64, f64) = (2.5, 4.0);
/// path_1 holds more points than this.
pub const PATH_POINTS: usize = 50;
/// The replay stays within `REPLAY_OFF` of the recording and ends within
/// `REPLAY_MISS` of its end, metres.
pub const REPLAY_OFF: f64 = 0.3;
pub const REPLAY_MISS: f64 = 0.1;
/// Seconds between the scans drawn.
const SCAN_EVERY: f64 = 1.0;

/// The statements whose ends the report lists.
pub const STATEMENTS: [&str; 7] = [
    "turn(left)",
    "t=turn(left)",
    "door=sensor(scanner,door,right)",
    "gotoxy(door)",
    "dist=followwall(left)",
    "if(dist>5)",
    "goahead(1)",
];

#[derive(Debug, Clone)]
pub struct WayOut {
    pub finished: bool,
    pub time: f64,
    pub driven: f64,
    pub contacts: u64,
    /// The `door` variable: where the door was seen, and the heading through it.
    pub door: (f64, f64, f64),
    pub end: ilmr_hal::Pose,
    /// How each of `STATEMENTS` ended.
    pub ends: Vec<(&'static str, Option<String>)>,
    pub path_1: Vec<(f64, f64)>,
    pub track: Vec<Sample>,
    pub marks: Vec<Mark>,
    pub hits: Vec<(f64, f64)>,
}

impl WayOut {
    pub fn how(&self, text: &str) -> Option<&str> {
        self.ends
            .iter()
            .find(|(t, _)| *t == text)
            .and_then(|(_, how)| how.as_deref())
    }
}

/// `followpath(path_1)` from the start on a fresh robot.
#[derive(Debug, Clone)]
pub struct Replay {
    pub seed: u64,
    pub how: Option<String>,
    pub time: f64,
    pub contacts: u64,
    /// Farthest from the recording, metres.
    pub off: f64,
    /// From the recording's end at the end, metres.
    pub miss: f64,
    pub track: Vec<Sample>,
}

#[derive(Debug, Clone)]
pub struct Test7 {
    pub way_out: WayOut,
    pub replay: Replay,
    pub world: World,
}

fn way_out(robot: ilmr_sim::SimRobot) -> Result<WayOut, String> {
    let module = compile_example("way_out.ilmr", robot.model())?;
    let mut vm = harness::vm(module, robot)?;
    let (mut marks, mut hits) = (Marks::new(&vm), Hits::new(SCAN_EVERY));
    let out = harness::run_watched(&mut vm, 240.0, |vm| {
        marks.watch(vm);
        hits.watch(vm);
    });
    let door = vm.var("door").ok_or("`door` is not a variable")?;
    Ok(WayOut {
        finished: out.finished,
        time: vm.time(),
        driven: length(&out.trace),
        contacts: vm.hal().sim().contact_count(),
        door: (door.x, door.y, door.h),
        end: *out.trace.last().ok_or("the robot did not move")?,
        ends: STATEMENTS
            .iter()
            .map(|&t| (t, harness::ended(&vm, t)))
            .collect(),
        path_1: vm.paths().get("path_1").cloned().unwrap_or_default(),
        track: picture::track(&out, vm.config().period),
        marks: marks.marks,
        hits: hits.points(),
    })
}

fn replay(robot: ilmr_sim::SimRobot, seed: u64, path: &[(f64, f64)]) -> Result<Replay, String> {
    let again = Task::new()
        .cmd(
            "f=followpath(path_1)",
            Command::FollowPath,
            &[A::W("path_1")],
            Some("f"),
        )
        .wait_var("wait(f)", "f")
        .finish();
    let mut vm = harness::vm(again, robot)?;
    vm.add_path("path_1", path.to_vec());
    let out = harness::run(&mut vm, 240.0);
    let last = *out.trace.last().ok_or("the robot did not move")?;
    let off = out
        .trace
        .iter()
        .map(|p| distance_to_polyline(path, (p.x, p.y)))
        .fold(0.0, f64::max);
    let goal = *path.last().ok_or("path_1 is empty")?;
    Ok(Replay {
        seed,
        how: harness::ended(&vm, "f=followpath(path_1)"),
        time: vm.time(),
        contacts: vm.hal().sim().contact_count(),
        off,
        miss: (last.x - goal.0).hypot(last.y - goal.1),
        track: picture::track(&out, vm.config().period),
    })
}

pub fn run() -> Result<Test7, String> {
    let w = harness::shipped(WORLD)?;
    let way_out = way_out(moro(w.clone(), SEED)?)?;
    let replay = replay(moro(w.clone(), SEED + 1)?, SEED + 1, &way_out.path_1)?;
    Ok(Test7 {
        way_out,
        replay,
        world: w,
    })
}

/// Test 7 on robots with `profile`'s errors: the way out with `seed`, the replay
/// with the next.
pub fn run_with(profile: ilmr_sim::SimProfile, seed: u64) -> Result<Test7, String> {
    let w = harness::shipped(WORLD)?;
    let robot = |seed| harness::moro_with(w.clone(), seed, profile);
    let way_out = way_out(robot(seed)?)?;
    let again = seed.wrapping_add(1);
    let replay = replay(robot(again)?, again, &way_out.path_1)?;
    Ok(Test7 {
        way_out,
        replay,
        world: w,
    })
}

impl Test7 {
    /// Figure 59: the lab, the scanner's hits, the way out, path_1 as recorded and
    /// its replay.
    pub fn figure(&self) -> Figure {
        let mut f = Figure::new(format!(
            "Test 7 (Figure 59): examples/way_out.ilmr in {WORLD}, MoRo, seed {SEED}; followpath(path_1), seed {}",
            self.replay.seed
        ));
        f.legend = Corner::LowerRight;
        f.scenery.push(Scenery {
            world: self.world.clone(),
            tint: None,
        });
        f.hits = self.way_out.hits.clone();
        f.references.push(Reference {
            label: Some("path_1 as recorded".into()),
            colour: Colour::REFERENCE,
            points: self.way_out.path_1.clone(),
        });
        f.tracks.push(Track {
            label: Some("the way out".into()),
            colour: Colour::palette(0),
            samples: self.way_out.track.clone(),
        });
        f.tracks.push(Track {
            label: Some("followpath(path_1)".into()),
            colour: Colour::palette(1),
            samples: self.replay.track.clone(),
        });
        f.marks = self.way_out.marks.clone();
        f
    }
}

//! Test 2 (section 5.6.1, Table 11, Figure 47): `turn(left)` in a corridor on MoRo at
//! 0.3 m/s. There is no room to turn at the start, so the robot follows the left wall
//! at its current distance until the corner, then turns; a linked `goahead(1.5)` takes
//! it up the side corridor.

use ilmr_plot::{Colour, Corner, Figure, Mark, Sample, Scenery, Track};
use ilmr_sim::World;
use ilmr_stdlib::Command;

use crate::harness::{self, A, Task, speed, world};
use crate::picture::{self, Marks};

pub const SEED: u64 = 2;
pub const WORLD: &str = "corridor.toml";
/// The corner of the corridor: the side corridor runs north between x = 10 and 12.4.
pub const CORNER_X: f64 = 10.0;
pub const SIDE_EAST_X: f64 = 12.4;
/// Table 11's deviations, metres.
pub const TABLE_11_X: f64 = 0.04;
pub const TABLE_11_Y: f64 = 0.01;
/// The bars: largest |y - y0| before the corner, and half the spread of x heading
/// north, metres.
pub const BAR_Y: f64 = 0.04;
pub const BAR_X: f64 = 0.06;
/// The end is up the side corridor: beyond this y.
pub const END_Y: f64 = 3.0;
/// Before this x the heading stays within `EARLY_DEG` of east.
pub const BEFORE_X: f64 = CORNER_X - 1.0;
pub const EARLY_DEG: f64 = 5.0;
/// Poses within this of north count as heading north.
pub const NORTH_DEG: f64 = 3.0;

#[derive(Debug, Clone)]
pub struct Test2 {
    pub finished: bool,
    /// How `t=turn(left)` ended.
    pub turn_how: Option<String>,
    pub contacts: u64,
    /// Largest |y - y0| before `BEFORE_X`, metres.
    pub y_deviation: f64,
    /// Half the spread of x while heading north, metres.
    pub x_deviation: f64,
    /// Whether the heading left east by `EARLY_DEG` before `BEFORE_X`.
    pub turned_early: bool,
    /// Poses heading north.
    pub north: usize,
    /// Where the heading first left east by `EARLY_DEG`.
    pub turn_start_x: Option<f64>,
    pub end: ilmr_hal::Pose,
    pub world: World,
    pub track: Vec<Sample>,
    pub marks: Vec<Mark>,
}

pub fn run() -> Result<Test2, String> {
    run_with(ilmr_sim::SimProfile::Basic, SEED)
}

/// Test 2 on a robot with `profile`'s errors and `seed`.
pub fn run_with(profile: ilmr_sim::SimProfile, seed: u64) -> Result<Test2, String> {
    let task = speed(Task::new(), 0.3)
        .cmd("t=turn(left)", Command::Turn, &[A::W("left")], Some("t"))
        .cmd("goahead(1.5)", Command::Goahead, &[A::N(1.5)], None)
        .finish();
    let w = world(WORLD)?;
    let mut vm = harness::vm(task, harness::moro_with(w.clone(), seed, profile)?)?;
    let mut marks = Marks::new(&vm);
    let out = harness::run_watched(&mut vm, 80.0, |vm| marks.watch(vm));
    let y0 = out.trace.first().ok_or("the robot did not move")?.y;
    let early = EARLY_DEG.to_radians();
    let before: Vec<_> = out.trace.iter().filter(|p| p.x < BEFORE_X).collect();
    let y_deviation = before.iter().map(|p| (p.y - y0).abs()).fold(0.0, f64::max);
    let turned_early = before.iter().any(|p| p.h.abs() > early);
    let north: Vec<_> = out
        .trace
        .iter()
        .filter(|p| (p.h - std::f64::consts::FRAC_PI_2).abs() < NORTH_DEG.to_radians())
        .collect();
    let (lo, hi) = north.iter().fold((f64::MAX, f64::MIN), |(lo, hi), p| {
        (lo.min(p.x), hi.max(p.x))
    });
    Ok(Test2 {
        finished: out.finished,
        turn_how: harness::ended(&vm, "t=turn(left)"),
        contacts: vm.hal().sim().contact_count(),
        y_deviation,
        x_deviation: (hi - lo) / 2.0,
        turned_early,
        north: north.len(),
        turn_start_x: out.trace.iter().find(|p| p.h.abs() > early).map(|p| p.x),
        end: *out.trace.last().ok_or("the robot did not move")?,
        world: w,
        track: picture::track(&out, vm.config().period),
        marks: marks.marks,
    })
}

impl Test2 {
    /// Figure 47: the corridor and the path round its corner.
    pub fn figure(&self) -> Figure {
        let mut f = Figure::new(format!(
            "Test 2 (Figure 47): turn(left), goahead(1.5) in {WORLD}, MoRo, seed {SEED}"
        ));
        f.legend = Corner::UpperLeft;
        f.scenery.push(Scenery {
            world: self.world.clone(),
            tint: None,
        });
        f.tracks.push(Track {
            label: Some("true trajectory".into()),
            colour: Colour::TRUE_PATH,
            samples: self.track.clone(),
        });
        f.marks = self.marks.clone();
        f
    }
}

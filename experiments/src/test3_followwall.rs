//! Test 3 (section 5.6.2, Table 12, Figure 49): `followwall(left,1.0)` on MoRo at
//! 0.3 m/s from 0.4, 1.0 and 1.2 m off the goal distance, past a door opening
//! (`wall_*.toml`), 14 m driven.

use ilmr_plot::{Colour, Corner, Figure, Reference, Sample, Scenery, Track};
use ilmr_sim::World;
use ilmr_stdlib::Command;

use crate::harness::{self, A, Task, speed, world};
use crate::picture;

pub const SEED: u64 = 3;
const WALL_HALF_THICKNESS: f64 = 0.075;
pub const GOAL: f64 = 1.0;
/// How far each run travels, metres (or 80 s).
pub const TRAVEL: f64 = 14.0;

/// How far the start is off the goal distance, and Table 12's overshoot from there,
/// metres.
pub const OFFSETS: [(f64, f64); 3] = [(0.4, 0.02), (1.0, 0.05), (1.2, 0.03)];
/// The bars: overshoot at most Table 12's plus this, the error after 3 m and at the
/// end at most these, metres.
pub const OVERSHOOT_SLACK: f64 = 0.05;
pub const BAR_AT_3M: f64 = 0.1;
pub const BAR_END: f64 = 0.03;

#[derive(Debug, Clone)]
pub struct Follow {
    pub off: f64,
    /// Table 12's overshoot, metres.
    pub table: f64,
    /// How much closer than the goal distance the robot came to the wall face, metres.
    pub overshoot: f64,
    /// |distance - goal| after 3 m of travel, and at the end, metres.
    pub at_3m: f64,
    pub at_end: f64,
    pub contacts: u64,
    /// Whether `followwall` ended (it should run until it is broken).
    pub finished: bool,
    pub world: World,
    pub track: Vec<Sample>,
}

fn follow(
    off: f64,
    table: f64,
    profile: ilmr_sim::SimProfile,
    seed: u64,
) -> Result<Follow, String> {
    // The distance is to the wall's face: its line is 0.15 m thick.
    let wall_y = GOAL + off - WALL_HALF_THICKNESS;
    let task = speed(Task::new(), 0.3)
        .cmd(
            "followwall(left,1.0)",
            Command::FollowWall,
            &[A::W("left"), A::N(GOAL)],
            None,
        )
        .finish();
    let w = world(&format!("wall_{off:.1}.toml"))?;
    let mut vm = harness::vm(task, harness::moro_with(w.clone(), seed, profile)?)?;
    let mut travelled = 0.0;
    let mut last = vm.hal().true_pose();
    let (mut overshoot, mut at_3m) = (0.0f64, f64::NAN);
    let (mut trace, mut speeds, mut curvatures) = (Vec::new(), Vec::new(), Vec::new());
    while travelled < TRAVEL && vm.time() < 80.0 {
        harness::tick(&mut vm);
        let p = vm.hal().true_pose();
        travelled += (p.x - last.x).hypot(p.y - last.y);
        last = p;
        let distance = wall_y - p.y;
        overshoot = overshoot.max(GOAL - distance);
        if at_3m.is_nan() && travelled >= 3.0 {
            at_3m = (distance - GOAL).abs();
        }
        trace.push(p);
        speeds.push(vm.hal().sim().true_speed());
        curvatures.push(vm.hal().sim().true_curvature());
    }
    Ok(Follow {
        off,
        table,
        overshoot,
        at_3m,
        at_end: (wall_y - last.y - GOAL).abs(),
        contacts: vm.hal().sim().contact_count(),
        finished: vm.finished(),
        world: w,
        track: picture::thin(&trace, &speeds, &curvatures, vm.config().period),
    })
}

#[derive(Debug, Clone)]
pub struct Test3 {
    pub follows: Vec<Follow>,
}

pub fn run() -> Result<Test3, String> {
    run_with(ilmr_sim::SimProfile::Basic, SEED)
}

/// Test 3 on robots with `profile`'s errors and `seed`.
pub fn run_with(profile: ilmr_sim::SimProfile, seed: u64) -> Result<Test3, String> {
    let follows = OFFSETS
        .iter()
        .map(|&(off, table)| follow(off, table, profile, seed))
        .collect::<Result<_, _>>()?;
    Ok(Test3 { follows })
}

impl Test3 {
    /// Figure 49: the three walls, each in the colour of its run, and the goal
    /// distance from each dashed.
    pub fn figure(&self) -> Figure {
        let mut f = Figure::new(format!(
            "Test 3 (Figure 49): followwall(left,1.0) from 0.4, 1.0 and 1.2 m off, MoRo, seed {SEED}"
        ));
        f.legend = Corner::LowerRight;
        for (i, r) in self.follows.iter().enumerate() {
            let colour = Colour::palette(i);
            f.scenery.push(Scenery {
                world: r.world.clone(),
                tint: Some(colour),
            });
            let goal_y = GOAL + r.off - WALL_HALF_THICKNESS - GOAL;
            let (x0, x1) = r
                .track
                .iter()
                .fold((f64::MAX, f64::MIN), |(a, b), s| (a.min(s.x), b.max(s.x)));
            f.references.push(Reference {
                label: Some("1.0 m from the wall".into()),
                colour: Colour::REFERENCE,
                points: vec![(x0, goal_y), (x1, goal_y)],
            });
            f.tracks.push(Track {
                label: Some(format!("from {:.1} m off the distance", r.off)),
                colour,
                samples: r.track.clone(),
            });
        }
        f
    }
}

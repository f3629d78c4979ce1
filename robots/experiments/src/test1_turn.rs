//! Test 1 (section 5.6.1, Table 10, Figure 46): `turn(d=90,c=0.6)` and `c=0.4` on MoRo
//! at 0.2-0.8 m/s, `c=0.25` on Workpartner at 0.2-0.4 m/s, in the empty world; the
//! maximum deviation of the true trace from the reference arc.

use ilmr_motion::path::{TurnSpec, turn};
use ilmr_motion::{Direction, Pose};
use ilmr_plot::{Colour, Corner, Figure, Reference, Sample, Track};
use ilmr_stdlib::Command;

use crate::harness::{self, A, Task, mean_std, shipped, speed};
use crate::picture;

/// The first trial's seed; trial `i` of a sweep runs with `SEED + i`.
pub const SEED: u64 = 1;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Robot {
    Moro,
    Workpartner,
}

impl Robot {
    pub fn name(self) -> &'static str {
        match self {
            Robot::Moro => "MoRo",
            Robot::Workpartner => "Workpartner",
        }
    }
}

/// A row of Table 10: the largest of the trials' maximum deviations, their mean and
/// standard deviation, metres.
#[derive(Debug, Clone, Copy)]
pub struct Table10 {
    pub max: f64,
    pub mean: f64,
    pub std: f64,
}

/// A sweep of trials over speeds, and the bar its worst trial must meet.
#[derive(Debug)]
pub struct Spec {
    pub robot: Robot,
    pub c: f64,
    pub speeds: &'static [f64],
    pub dissertation: Table10,
    /// The largest maximum deviation allowed, metres.
    pub bar: f64,
}

/// Eight trials as in Table 10; issue 4's bar is half the dissertation's worst 0.08 m.
pub const MORO_C06: Spec = Spec {
    robot: Robot::Moro,
    c: 0.6,
    speeds: &[0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.75, 0.8],
    dissertation: Table10 {
        max: 0.08,
        mean: 0.0225,
        std: 0.0242,
    },
    bar: 0.04,
};

/// Seven trials as in Table 10, which measured 0.04 m; MoRo's overall 0.08 m allowed
/// for the noise.
pub const MORO_C04: Spec = Spec {
    robot: Robot::Moro,
    c: 0.4,
    speeds: &[0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8],
    dissertation: Table10 {
        max: 0.04,
        mean: 0.025,
        std: 0.0115,
    },
    bar: 0.08,
};

/// Three trials as in Table 10; issue 4's bar is half the dissertation's 0.22 m. The arc
/// is at Workpartner's maximum curvature, so heading given away to pose noise is never
/// made up; the controller's look-ahead of half the turning radius keeps it.
pub const WORKPARTNER_C025: Spec = Spec {
    robot: Robot::Workpartner,
    c: 0.25,
    speeds: &[0.2, 0.3, 0.4],
    dissertation: Table10 {
        max: 0.22,
        mean: 0.183,
        std: 0.0635,
    },
    bar: 0.11,
};

pub const SPECS: [&Spec; 3] = [&MORO_C06, &MORO_C04, &WORKPARTNER_C025];

/// One `turn(d=90,c=..)` at one speed.
#[derive(Debug, Clone)]
pub struct Trial {
    pub v: f64,
    pub seed: u64,
    pub finished: bool,
    /// How `t=turn(..)` ended.
    pub how: Option<String>,
    /// The largest distance of the true trace from the reference arc, metres.
    pub max_deviation: f64,
    pub end: ilmr_hal::Pose,
    pub track: Vec<Sample>,
}

#[derive(Debug, Clone)]
pub struct Sweep {
    pub spec: &'static Spec,
    pub trials: Vec<Trial>,
    /// The reference arc every trial is measured against.
    pub arc: Vec<(f64, f64)>,
}

impl Sweep {
    pub fn label(&self) -> String {
        format!("{} c={}", self.spec.robot.name(), self.spec.c)
    }

    pub fn deviations(&self) -> Vec<f64> {
        self.trials.iter().map(|t| t.max_deviation).collect()
    }

    /// The largest of the trials' maximum deviations.
    pub fn worst(&self) -> f64 {
        self.deviations().into_iter().fold(0.0, f64::max)
    }

    /// Mean and sample standard deviation of the trials' maximum deviations.
    pub fn mean_std(&self) -> (f64, f64) {
        mean_std(&self.deviations())
    }
}

#[derive(Debug, Clone)]
pub struct Test1 {
    pub sweeps: Vec<Sweep>,
}

fn robot(r: Robot, seed: u64) -> Result<ilmr_sim::SimRobot, String> {
    let world = shipped("empty")?;
    match r {
        Robot::Moro => harness::moro(world, seed),
        Robot::Workpartner => harness::workpartner(world, seed),
    }
}

fn arc(c: f64) -> Result<ilmr_motion::Path, String> {
    turn(
        Pose::new(0.0, 0.0, 0.0),
        &TurnSpec::degrees(90.0, c),
        Direction::Forward,
        0.01,
    )
    .map_err(|e| format!("the reference arc c={c}: {e:?}"))
}

fn trial(spec: &Spec, v: f64, seed: u64) -> Result<Trial, String> {
    let c = spec.c;
    let text = format!("t=turn(d=90,c={c})");
    let task = speed(Task::new(), v)
        .cmd(
            &text,
            Command::Turn,
            &[A::S("d", 90.0), A::S("c", c)],
            Some("t"),
        )
        .finish();
    let mut vm = harness::vm(task, robot(spec.robot, seed)?)?;
    let out = harness::run(&mut vm, 60.0);
    let reference = arc(c)?;
    let max_deviation = out
        .trace
        .iter()
        .map(|p| reference.distance_to(&nalgebra::Point2::new(p.x, p.y)))
        .fold(0.0, f64::max);
    Ok(Trial {
        v,
        seed,
        finished: out.finished,
        how: harness::ended(&vm, &text),
        max_deviation,
        end: *out.trace.last().ok_or("the robot did not move")?,
        track: picture::track(&out, vm.config().period),
    })
}

/// The trials of one row of Table 10, seeds `SEED`, `SEED + 1`, ...
pub fn sweep(spec: &'static Spec) -> Result<Sweep, String> {
    let trials = spec
        .speeds
        .iter()
        .enumerate()
        .map(|(i, &v)| trial(spec, v, SEED + i as u64))
        .collect::<Result<Vec<_>, _>>()?;
    let arc = arc(spec.c)?
        .points()
        .iter()
        .map(|p| (p.position().x, p.position().y))
        .collect();
    Ok(Sweep { spec, trials, arc })
}

/// All three rows of Table 10.
pub fn run() -> Result<Test1, String> {
    let sweeps = SPECS.iter().map(|s| sweep(s)).collect::<Result<_, _>>()?;
    Ok(Test1 { sweeps })
}

impl Test1 {
    /// Figure 46: every trial's true path over its ideal arc.
    pub fn figure(&self) -> Figure {
        let mut f = Figure::new("Test 1 (Figure 46): turn(d=90,c=..) from (0, 0, 0) in empty");
        f.legend = Corner::UpperLeft;
        for (i, s) in self.sweeps.iter().enumerate() {
            f.references.push(Reference {
                label: Some("ideal arcs".into()),
                colour: Colour::REFERENCE,
                points: s.arc.clone(),
            });
            let speeds = s.spec.speeds;
            let label = format!(
                "{}, {} trials at {}-{} m/s",
                s.label(),
                s.trials.len(),
                speeds.first().copied().unwrap_or_default(),
                speeds.last().copied().unwrap_or_default()
            );
            for t in &s.trials {
                f.tracks.push(Track {
                    label: Some(label.clone()),
                    colour: Colour::palette(i),
                    samples: t.track.clone(),
                });
            }
        }
        f
    }
}

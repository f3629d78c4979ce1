//! Test 5 (section 5.6.4, Figures 52-55): the short task on MoRo in the empty world.
//! Linked commands do not stop between them; the robot comes back to its start by
//! `use(goalpos)` and reversed commands.

use ilmr_motion::path::{TurnSpec, straight, turn};
use ilmr_motion::{Direction, Path, Pose};
use ilmr_plot::{Colour, Corner, Figure, Mark, Reference, Sample, Track};
use ilmr_stdlib::Command;

use crate::harness::{self, A, SimVm, Task, shipped, speed};
use crate::picture::{self, Marks};

pub const SEED: u64 = 5;
/// Figure 53's maximum position error, metres; the bar for the error and for how far
/// from the start the robot ends.
pub const FIGURE_53: f64 = 0.07;
/// The links expected: two out, two back.
pub const LINKS: usize = 4;
/// The longest a link may take, seconds (the dissertation: about 0.1 s).
pub const LINK_BAR: f64 = 0.1;
/// The cruising speed, and the lowest allowed between linked commands, m/s.
pub const CRUISE: f64 = 0.39;
pub const DIP_BAR: f64 = 0.38;

/// Figure 52, assembled statement by statement.
fn figure_52() -> ilmr_vm::Module {
    let t = speed(Task::new(), 0.4)
        .cmd("goahead(1.2)", Command::Goahead, &[A::N(1.2)], None)
        .cmd(
            "turn(d=90,c=0.5)",
            Command::Turn,
            &[A::S("d", 90.0), A::S("c", 0.5)],
            None,
        )
        .cmd("m=goahead(0.7)", Command::Goahead, &[A::N(0.7)], Some("m"))
        .wait_var("wait(m)", "m");
    speed(t, -0.4)
        .cmd("use(goalpos)", Command::Use, &[A::W("goalpos")], None)
        .cmd("goahead(-0.7)", Command::Goahead, &[A::N(-0.7)], None)
        .cmd(
            "turn(d=90,c=0.5) ",
            Command::Turn,
            &[A::S("d", 90.0), A::S("c", 0.5)],
            None,
        )
        .cmd("goahead(-1.2)", Command::Goahead, &[A::N(-1.2)], None)
        .finish()
}

/// The ideal route: out, and back over the same ground.
fn route() -> Result<Path, String> {
    let e = |e| format!("the ideal route: {e:?}");
    let out = straight(Pose::new(0.0, 0.0, 0.0), 1.2, 0.01).map_err(e)?;
    let arc = turn(
        out.end_pose(),
        &TurnSpec::degrees(90.0, 0.5),
        Direction::Forward,
        0.01,
    )
    .map_err(e)?;
    let leg = straight(arc.end_pose(), 0.7, 0.01).map_err(e)?;
    out.concat(&arc, 1e-6)
        .and_then(|p| p.concat(&leg, 1e-6))
        .map_err(e)
}

#[derive(Debug, Clone)]
pub struct Test5 {
    pub finished: bool,
    /// The largest distance of the true trace from the ideal route, metres.
    pub max_error: f64,
    /// Linked ends.
    pub links: usize,
    /// The longest time from a linked end to the next movement's start, seconds.
    pub link_gap: f64,
    /// The lowest speed between reaching `CRUISE` and the last braking on the way out.
    pub dip: f64,
    /// How far from the start the robot ends, metres.
    pub home: f64,
    pub route: Vec<(f64, f64)>,
    pub track: Vec<Sample>,
    pub marks: Vec<Mark>,
}

pub fn run() -> Result<Test5, String> {
    run_with(ilmr_sim::SimProfile::Basic, SEED)
}

/// Test 5 on a robot with `profile`'s errors and `seed`.
pub fn run_with(profile: ilmr_sim::SimProfile, seed: u64) -> Result<Test5, String> {
    run_controlled(profile, seed, ilmr_vm::Controller::PROJECT)
}

/// As [`run_with`], with the position controller's `controller` variant.
pub fn run_controlled(
    profile: ilmr_sim::SimProfile,
    seed: u64,
    controller: ilmr_vm::Controller,
) -> Result<Test5, String> {
    let mut vm = harness::vm_with(
        figure_52(),
        harness::moro_with(shipped("empty")?, seed, profile)?,
        controller,
    )?;
    let mut marks = Marks::new(&vm);
    let out = harness::run_watched(&mut vm, 60.0, |vm| marks.watch(vm));
    let ideal = route()?;
    let max_error = out
        .trace
        .iter()
        .map(|p| ideal.distance_to(&nalgebra::Point2::new(p.x, p.y)))
        .fold(0.0, f64::max);
    // Between reaching the cruising speed and the last braking on the way out (three
    // linked commands) the speed never dips.
    let wait_at = vm
        .events()
        .iter()
        .find(|e| {
            e.stmt
                .and_then(|s| vm.module().stmt(s))
                .is_some_and(|s| s.text == "m=goahead(0.7)")
                && e.kind.name() == "end"
        })
        .map(|e| e.tick as usize)
        .ok_or("m=goahead(0.7) never ended")?;
    let forward = &out.speeds[..wait_at.min(out.speeds.len())];
    let cruise = forward.iter().position(|v| *v >= CRUISE);
    let braking = forward.iter().rposition(|v| *v >= CRUISE);
    let (Some(cruise), Some(braking)) = (cruise, braking) else {
        return Err(format!("never cruised at {CRUISE} m/s on the way out"));
    };
    let dip = forward[cruise..=braking]
        .iter()
        .cloned()
        .fold(f64::MAX, f64::min);
    let end = out.trace.last().ok_or("the robot did not move")?;
    Ok(Test5 {
        finished: out.finished,
        max_error,
        links: harness::linked_ends(&vm),
        link_gap: link_gap(&vm),
        dip,
        home: end.x.hypot(end.y),
        route: ideal
            .points()
            .iter()
            .map(|p| (p.position().x, p.position().y))
            .collect(),
        track: picture::track(&out, vm.config().period),
        marks: marks.marks,
    })
}

/// Longest time between a linked end and the next movement's start.
fn link_gap(vm: &SimVm) -> f64 {
    let mut worst: f64 = 0.0;
    let events = vm.events();
    for (i, e) in events.iter().enumerate() {
        if matches!(e.kind, ilmr_vm::EventKind::End { linked: true, .. })
            && let Some(next) = events[i..].iter().find(|n| n.kind.name() == "start")
        {
            worst = worst.max(next.t - e.t);
        }
    }
    worst
}

impl Test5 {
    /// Figures 53 and 54: the route out and back over the ideal one, and the speed
    /// and curvature over time.
    pub fn figure(&self) -> Figure {
        let mut f = Figure::new(format!(
            "Test 5 (Figures 53-54): the short task of Figure 52 in empty, MoRo, seed {SEED}"
        ));
        f.legend = Corner::UpperLeft;
        f.time_series = true;
        f.references.push(Reference {
            label: Some("ideal route".into()),
            colour: Colour::REFERENCE,
            points: self.route.clone(),
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

//! Test 4 (section 5.6.3, Figure 50): `obsavoid(on)` then `goahead(5)` on MoRo at
//! 0.3 m/s with a box on the path (`obstacle.toml`); and the `stop` and `off` modes of
//! the same run (with `off` the avoider ignores the box and the VM's supervisor holds
//! the robot before it).

use ilmr_plot::{Colour, Corner, Figure, Reference, Sample, Scenery, Track};
use ilmr_sim::World;
use ilmr_stdlib::Command;

use crate::harness::{self, A, Task, moro, speed, world};
use crate::picture;

pub const SEED: u64 = 4;
pub const WORLD: &str = "obstacle.toml";
/// The box: centre x, y and half side, metres.
pub const BOX: (f64, f64, f64) = (3.0, 0.05, 0.2);
/// `on` goes round: wider off the line than this, and ends within `END_WITHIN` of
/// x = 5 and `BACK_WITHIN` of the line, metres.
pub const ASIDE: f64 = 0.4;
pub const END_WITHIN: f64 = 0.1;
pub const BACK_WITHIN: f64 = 0.15;
/// `stop` and `off` end standing: slower than this, m/s.
pub const STANDS: f64 = 1e-3;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    On,
    Stop,
    Off,
}

impl Mode {
    pub const ALL: [Mode; 3] = [Mode::On, Mode::Stop, Mode::Off];

    pub fn name(self) -> &'static str {
        match self {
            Mode::On => "on",
            Mode::Stop => "stop",
            Mode::Off => "off",
        }
    }

    /// How long the run is given: `on` finishes; the others stand before the box.
    fn seconds(self) -> f64 {
        match self {
            Mode::On => 60.0,
            Mode::Stop | Mode::Off => 30.0,
        }
    }
}

#[derive(Debug, Clone)]
pub struct Avoid {
    pub mode: Mode,
    pub finished: bool,
    pub contacts: u64,
    /// Widest |y| off the line, metres.
    pub aside: f64,
    /// Smallest distance from the footprint's corners to the box, metres.
    pub clearance: f64,
    pub end: ilmr_hal::Pose,
    /// Where the robot's front stands at the end (x), metres.
    pub front: f64,
    /// Speed at the end, m/s.
    pub speed: f64,
    /// Whether the VM's supervisor reported `obstacle_near`.
    pub held: bool,
    /// Simulated seconds at the end.
    pub time: f64,
    pub track: Vec<Sample>,
}

#[derive(Debug, Clone)]
pub struct Test4 {
    pub modes: Vec<Avoid>,
    pub world: World,
}

fn task(mode: Mode) -> ilmr_vm::Module {
    let t = Task::new().cmd(
        &format!("obsavoid({})", mode.name()),
        Command::ObsAvoid,
        &[A::W(mode.name())],
        None,
    );
    speed(t, 0.3)
        .cmd("goahead(5)", Command::Goahead, &[A::N(5.0)], None)
        .finish()
}

/// Smallest distance from the robot's footprint to the box over the run.
fn clearance(robot: &ilmr_sim::SimRobot, trace: &[ilmr_hal::Pose]) -> f64 {
    let (bx, by, half) = BOX;
    trace
        .iter()
        .map(|p| {
            let fp = robot.sim().footprint(ilmr_sim::Pose::new(p.x, p.y, p.h));
            fp.corners()
                .iter()
                .map(|c| ((c.x - bx).abs() - half).max((c.y - by).abs() - half))
                .fold(f64::MAX, f64::min)
        })
        .fold(f64::MAX, f64::min)
}

/// One mode's run.
pub fn avoid(mode: Mode) -> Result<Avoid, String> {
    avoid_in(mode, world(WORLD)?)
}

fn avoid_in(mode: Mode, w: World) -> Result<Avoid, String> {
    let robot = moro(w, SEED)?;
    avoid_on(mode, robot)
}

/// `obsavoid(on)`, the mode the dissertation tested, on a robot with `profile`'s
/// errors and `seed`.
pub fn run_with(profile: ilmr_sim::SimProfile, seed: u64) -> Result<Avoid, String> {
    avoid_on(Mode::On, harness::moro_with(world(WORLD)?, seed, profile)?)
}

fn avoid_on(mode: Mode, robot: ilmr_sim::SimRobot) -> Result<Avoid, String> {
    let mut vm = harness::vm(task(mode), robot)?;
    let out = harness::run(&mut vm, mode.seconds());
    let end = *out.trace.last().ok_or("the robot did not move")?;
    let held = vm
        .events()
        .iter()
        .any(|e| ilmr_vm::render_event(vm.module(), e).contains("\"obstacle_near\""));
    Ok(Avoid {
        mode,
        finished: out.finished,
        contacts: vm.hal().sim().contact_count(),
        aside: out.trace.iter().map(|p| p.y.abs()).fold(0.0, f64::max),
        clearance: clearance(vm.hal(), &out.trace),
        end,
        front: end.x + vm.config().front_offset,
        speed: vm.hal().sim().true_speed(),
        held,
        time: vm.time(),
        track: picture::track(&out, vm.config().period),
    })
}

pub fn run() -> Result<Test4, String> {
    let w = world(WORLD)?;
    let modes = Mode::ALL
        .iter()
        .map(|&m| avoid_in(m, w.clone()))
        .collect::<Result<_, _>>()?;
    Ok(Test4 { modes, world: w })
}

impl Test4 {
    pub fn mode(&self, mode: Mode) -> Option<&Avoid> {
        self.modes.iter().find(|a| a.mode == mode)
    }

    /// Figure 50: the box and the three modes' paths along the line of `goahead(5)`.
    pub fn figure(&self) -> Figure {
        let mut f = Figure::new(format!(
            "Test 4 (Figure 50): obsavoid(on|stop|off), goahead(5) in {WORLD}, MoRo, seed {SEED}"
        ));
        f.legend = Corner::UpperRight;
        f.scenery.push(Scenery {
            world: self.world.clone(),
            tint: None,
        });
        f.references.push(Reference {
            label: Some("goahead(5)".into()),
            colour: Colour::REFERENCE,
            points: vec![(0.0, 0.0), (5.0, 0.0)],
        });
        // The longest path first: `stop`'s is the start of `off`'s, and stays visible
        // on top of it.
        for (i, a) in self.modes.iter().enumerate().rev() {
            f.tracks.push(Track {
                label: Some(format!("obsavoid({})", a.mode.name())),
                colour: Colour::palette(i),
                samples: a.track.clone(),
            });
        }
        f
    }
}

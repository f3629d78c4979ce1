//! What `--robot`, `--model`, `--world` and `--start` name: the backend, the robot model
//! the task is checked against, and for a simulated robot its world and start pose.

use ilmr_model::RobotModel;
use ilmr_sim::{RobotKind, SimProfile, SimRobot};

use super::backend::{AnyRobot, NoRobot, Ros2, Simulated};
use super::scenario::{Scenario, scripted_limits};
use crate::ros2::Ros2Args;

pub use ilmr_testfile::place::{Backend, LoadedWorld};

pub struct Setup {
    pub backend: Backend,
    /// A simulated robot's errors (`--sim-profile`); `basic` for the others.
    pub profile: SimProfile,
    /// What `check` is given: `moro`, `workpartner` or a ROBO.INI path.
    pub model_spec: String,
    pub model: RobotModel,
    /// Simulated robots only; its `start` is where the robot starts.
    pub world: Option<LoadedWorld>,
    /// `--robot ros2` only: where the robot is on DDS.
    pub ros2: Option<ilmr_ros2::Ros2Config>,
}

pub struct Choice<'a> {
    pub robot: &'a str,
    /// `--sim-profile`, when given.
    pub profile: Option<SimProfile>,
    pub model: Option<&'a str>,
    pub world: Option<&'a str>,
    pub start: Option<&'a str>,
    pub ros2: &'a Ros2Args,
}

/// The robot, world and start as `ilmr_testfile::place` places them (a test file's are
/// checked there too), with a ROS 2 robot's settings.
pub fn choose(c: &Choice<'_>) -> Result<Setup, String> {
    let backend = Backend::of(c.robot);
    if backend != Backend::Ros2
        && let Some(flag) = c.ros2.given()
    {
        return Err(format!(
            "{flag} is for --robot ros2; --robot {} is not a ROS 2 robot",
            c.robot
        ));
    }
    let placed = ilmr_testfile::place::place(
        &ilmr_testfile::place::Choice {
            robot: c.robot,
            profile: c.profile,
            model: c.model,
            world: c.world,
            start: c.start,
        },
        &mut crate::inputs::warn_about,
    )?;
    let ros2 = match placed.backend {
        Backend::Ros2 => Some(c.ros2.config(&placed.model)?),
        _ => None,
    };
    Ok(Setup {
        backend: placed.backend,
        profile: placed.profile,
        model_spec: placed.model_spec,
        model: placed.model,
        world: placed.world,
        ros2,
    })
}

/// Checks each fault of `world` against the robot (`model` on the body `kind`) and the
/// run's end: a fault for a part the robot lacks, or one that starts after the end,
/// would do nothing. The last `flags` faults came from `--fault`, the others from the
/// world's `[[fault]]` entries; the message says which.
pub fn check_faults(
    world: &LoadedWorld,
    model: &RobotModel,
    kind: RobotKind,
    max_time: Option<f64>,
    flags: usize,
) -> Result<(), String> {
    let body = ilmr_sim::config_from_model(model, kind);
    let from_world = world.world.faults.len().saturating_sub(flags);
    for (i, spec) in world.world.faults.iter().enumerate() {
        ilmr_sim::faults::check_fits(spec, &body, model, max_time).map_err(|e| {
            if i < from_world {
                format!("fault `{spec}` of world `{}`: {e}", world.name)
            } else {
                format!("--fault `{spec}`: {e}")
            }
        })?;
    }
    Ok(())
}

/// Opens the robot of a run. `seed` seeds every noise source of a simulated robot; the
/// scripted robot has none and replays its scenario exactly.
pub fn open(setup: &Setup, scenario: &Scenario, seed: u64) -> Result<AnyRobot, String> {
    match setup.backend {
        Backend::None => {
            if scenario.drives_a_robot() {
                return Err(
                    "the scenario scripts a robot, but the task runs with --robot none".into(),
                );
            }
            Ok(AnyRobot::new(NoRobot))
        }
        Backend::Scripted => Ok(AnyRobot::new(
            scenario.robot(scripted_limits(&setup.model))?,
        )),
        Backend::Ros2 => {
            if scenario.scripts_the_world() {
                return Err(
                    "the scenario scripts what a robot senses, but --robot ros2 senses the \
                     real world (a scenario's paths and lines are fine)"
                        .into(),
                );
            }
            let Some(config) = &setup.ros2 else {
                return Err("--robot ros2 without its DDS settings".into());
            };
            let robot = ilmr_ros2::Ros2Robot::connect(config).map_err(|e| e.to_string())?;
            Ok(AnyRobot::new(Ros2::new(robot)))
        }
        Backend::Sim(kind) => {
            if scenario.scripts_the_world() {
                return Err(
                    "the scenario scripts readings, sightings, operations or a start \
                     pose, which only the scripted robot replays; a simulated robot senses \
                     its world (a scenario's paths and lines are fine)"
                        .into(),
                );
            }
            let Some(world) = &setup.world else {
                return Err("a simulated robot needs a world".into());
            };
            let start = world.world.start;
            let robot = SimRobot::with_profile(
                setup.model.clone(),
                kind,
                setup.profile,
                world.world.clone(),
                seed,
            )
            .map_err(|e| {
                format!(
                    "the robot cannot start at ({:.2}, {:.2}, {:.0} deg) in `{}`: {e}",
                    start.x,
                    start.y,
                    start.h.to_degrees(),
                    world.name
                )
            })?;
            Ok(AnyRobot::new(Simulated::new(robot)))
        }
    }
}

/// The VM's settings for `model`, with a simulated `body`'s offsets where there is one.
pub fn vm_config(
    model: &ilmr_model::RobotModel,
    body: Option<&ilmr_sim::RobotConfig>,
) -> ilmr_vm::Config {
    ilmr_vm::Config::for_robot(model, body.map(ilmr_sim::RobotConfig::offsets))
}

/// The VM's `scanner_offset` for a ROS 2 robot: where `tf` puts its scanner ahead of
/// the body frame. Without a transform the scan is read as taken at the robot's origin,
/// and the operator is told.
pub fn ros2_scanner_offset(robot: &AnyRobot) -> f64 {
    use super::backend::Robot;
    match robot.scanner_mount() {
        Some(m) => m.x,
        None => {
            eprintln!(
                "warning: no transform places the robot's scanner on its body frame (tf, \
                 tf_static): its scans are read as taken at the robot's origin"
            );
            0.0
        }
    }
}

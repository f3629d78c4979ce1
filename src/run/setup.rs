//! What `--robot`, `--model`, `--world` and `--start` name: the backend, the robot model
//! the task is checked against, and for a simulated robot its world and start pose.

use ilmr_hal::Limits;
use ilmr_model::RobotModel;
use ilmr_sim::{RobotKind, SimProfile, SimRobot, World};

/// A simulated robot's errors when `--sim-profile` is not given: the dissertation's
/// robots were imperfect, and the `calibrated` profile has their errors (fitted to its
/// Table 10, docs/experiments.md). A trace names every profile but `basic`, whose
/// traces were recorded before profiles existed.
pub const DEFAULT_PROFILE: SimProfile = SimProfile::Calibrated;

use super::backend::{AnyRobot, NoRobot, Ros2, Simulated};
use super::scenario::Scenario;
use crate::ros2::Ros2Args;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Backend {
    /// No robot: only control flow, arithmetic, waits and skills.
    None,
    /// The deterministic scripted robot of `ilmr-hal`, driven by `--scenario`.
    Scripted,
    /// `ilmr-sim`'s robot with this body, in a world.
    Sim(RobotKind),
    /// A ROS 2 robot over DDS (`ilmr-ros2`), bounded by the model's limits.
    Ros2,
}

/// A world and the text it was read from (the trace carries the text, so that
/// `ilmrc replay` draws the same world).
#[derive(Debug, Clone)]
pub struct LoadedWorld {
    pub world: World,
    /// `office`, or the file's path.
    pub name: String,
    pub text: String,
}

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

/// Starts used instead of a shipped world's own `start`: the office's is beside the lab
/// bench, where the Figure 52 task's left turn (radius 2 m) runs into the bench; south
/// of the bench there is room for it. `--start` overrides both; Figure 20 starts in the
/// office's north wing, in the robot's room facing its door (`--start 8,21,90`).
const RUN_STARTS: [(&str, f64, f64, f64); 1] = [("office", 8.0, 5.0, 0.0)];

/// The names `--robot` takes besides a ROBO.INI path.
pub const ROBOT_NAMES: &str = "moro, workpartner, ros2, none, scripted";

pub struct Choice<'a> {
    pub robot: &'a str,
    /// `--sim-profile`, when given.
    pub profile: Option<SimProfile>,
    pub model: Option<&'a str>,
    pub world: Option<&'a str>,
    pub start: Option<&'a str>,
    pub ros2: &'a Ros2Args,
}

pub fn choose(c: &Choice<'_>) -> Result<Setup, String> {
    let backend = match c.robot.to_ascii_lowercase().as_str() {
        "none" => Backend::None,
        "scripted" => Backend::Scripted,
        crate::ros2::ROBOT_NAME => Backend::Ros2,
        _ => Backend::Sim(RobotKind::Moro),
    };
    if backend != Backend::Ros2
        && let Some(flag) = c.ros2.given()
    {
        return Err(format!(
            "{flag} is for --robot ros2; --robot {} is not a ROS 2 robot",
            c.robot
        ));
    }
    if let Backend::Sim(_) = backend {
        if c.model.is_some() {
            return Err(format!(
                "--model is for --robot ros2|none|scripted; the simulated robot `{}` is its own model",
                c.robot
            ));
        }
        let builtin = RobotModel::builtin(c.robot).is_some();
        // A missing file is an error here, where `check` warns and uses the defaults:
        // a run drives the body the file describes. Anything else wrong with the path
        // (a directory, a device) is said as `check` says it.
        if !builtin && c.robot.contains(['/', '\\', '.']) && !std::path::Path::new(c.robot).exists()
        {
            return Err(format!(
                "cannot read robot model `{}`: no such file",
                c.robot
            ));
        }
        let loaded = crate::inputs::load_robot(c.robot).map_err(|e| {
            if e.starts_with("unknown robot") {
                format!(
                    "unknown robot `{}`: use {ROBOT_NAMES} or a path to a ROBO.INI file",
                    c.robot
                )
            } else {
                e
            }
        })?;
        crate::inputs::warn_about(c.robot, &loaded.warnings);
        let kind = body_of(c.robot, &loaded.model);
        let mut world = load_world(c.world.unwrap_or(default_world(kind)))?;
        if let Some(text) = c.start {
            world.world.start = parse_start(text, &world.world)?;
        } else if let Some(&(_, x, y, h)) = RUN_STARTS.iter().find(|(n, ..)| *n == world.name) {
            world.world.start = ilmr_sim::Pose::new(x, y, f64::to_radians(h));
        }
        return Ok(Setup {
            backend: Backend::Sim(kind),
            profile: c.profile.unwrap_or(DEFAULT_PROFILE),
            model_spec: c.robot.to_string(),
            model: loaded.model,
            world: Some(world),
            ros2: None,
        });
    }
    if let Some(p) = c.profile {
        return Err(format!(
            "--sim-profile {p} sets a simulated robot's errors; --robot {} is not simulated",
            c.robot
        ));
    }
    for (flag, given) in [("--world", c.world), ("--start", c.start)] {
        if given.is_some() {
            return Err(format!(
                "{flag} places a simulated robot; --robot {} has no world",
                c.robot
            ));
        }
    }
    let model_spec = c.model.unwrap_or("moro").to_string();
    let model = crate::inputs::load_robot_model(&model_spec)?;
    let ros2 = match backend {
        Backend::Ros2 => Some(c.ros2.config(&model)?),
        _ => None,
    };
    Ok(Setup {
        backend,
        profile: SimProfile::Basic,
        model_spec,
        model,
        world: None,
        ros2,
    })
}

/// The simulated body of a model: the shipped models name theirs; a ROBO.INI file gets
/// Workpartner's when it describes a navigation subsystem (`nav_rate`), as Workpartner's
/// model does, and MoRo's otherwise.
pub fn body_of(spec: &str, model: &RobotModel) -> RobotKind {
    if spec.eq_ignore_ascii_case("workpartner") || model.nav_rate().is_some() {
        RobotKind::Workpartner
    } else {
        RobotKind::Moro
    }
}

/// Where each robot feels at home: MoRo in the office (its test site at VTT), Workpartner
/// in the yard (its test site outdoors).
pub fn default_world(kind: RobotKind) -> &'static str {
    match kind {
        RobotKind::Moro => "office",
        RobotKind::Workpartner => "yard",
    }
}

/// A shipped world by name, or a world file.
pub fn load_world(spec: &str) -> Result<LoadedWorld, String> {
    if let Some((name, text)) = ilmr_sim::world::SHIPPED
        .iter()
        .find(|(n, _)| n.eq_ignore_ascii_case(spec))
    {
        let world = World::from_toml(text, &format!("<{name}>")).map_err(|e| e.to_string())?;
        return Ok(LoadedWorld {
            world,
            name: (*name).to_string(),
            text: (*text).to_string(),
        });
    }
    let path = std::path::Path::new(spec);
    if !spec.contains(['/', '\\', '.']) {
        let names: Vec<&str> = ilmr_sim::world::SHIPPED.iter().map(|(n, _)| *n).collect();
        return Err(format!(
            "unknown world `{spec}`: use {} or a path to a world file (.toml)",
            names.join(", ")
        ));
    }
    let text = ilmr_files::read_text(path, ilmr_files::Kind::World)
        .map_err(|e| format!("cannot read world `{spec}`: {e}"))?;
    let world = World::from_toml(&text, spec).map_err(|e| format!("bad world file: {e}"))?;
    Ok(LoadedWorld {
        world,
        name: spec.to_string(),
        text,
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

/// `X,Y,H`: metres and degrees in the world frame, inside the world's bounds.
fn parse_start(text: &str, world: &World) -> Result<ilmr_sim::Pose, String> {
    let bad =
        || format!("--start `{text}`: expected X,Y,HEADING (metres, degrees), e.g. 19.5,5.5,0");
    let parts: Vec<f64> = text
        .split(',')
        .map(|p| p.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|_| bad())?;
    let [x, y, h] = parts[..] else {
        return Err(bad());
    };
    if !(x.is_finite() && y.is_finite() && h.is_finite()) {
        return Err(bad());
    }
    let at = ilmr_sim::Vec2::new(x, y);
    if !world.bounds.contains(at) {
        let b = world.bounds;
        return Err(format!(
            "--start ({x}, {y}) is outside the world `{}`, which spans ({}, {})..({}, {})",
            world.name, b.min.x, b.min.y, b.max.x, b.max.y
        ));
    }
    Ok(ilmr_sim::Pose::new(x, y, h.to_radians()))
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
        Backend::Scripted => Ok(AnyRobot::new(scenario.robot(limits(&setup.model))?)),
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

/// The scripted robot moves within the model's limits.
fn limits(model: &RobotModel) -> Limits {
    Limits {
        acceleration: model.max_acceleration(),
        deceleration: model.max_deceleration(),
        curvature_rate: model.curinc(),
        max_curvature: model.max_curvature(),
        max_speed: model.max_speed(),
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

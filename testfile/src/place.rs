//! What `--robot`, `--model`, `--world`, `--start` and `--sim-profile` name, as far as
//! it is known without a robot: the backend, the model the task is checked against, and
//! for a simulated robot its world and start pose. `ilmrc run` adds the ROS 2 side
//! (src/run/setup.rs); a test file's `robot`, `world` and `start` are checked here, so
//! that `ilmrc test` and the language server say the same of them.

use ilmr_compiler::check::Source;
use ilmr_model::{ModelWarning, RobotModel};
use ilmr_sim::{RobotKind, SimProfile, World};

/// A simulated robot's errors when `--sim-profile` is not given: the dissertation's
/// robots were imperfect, and the `calibrated` profile has their errors (fitted to its
/// Table 10, docs/experiments.md). A trace names every profile but `basic`, whose
/// traces were recorded before profiles existed.
pub const DEFAULT_PROFILE: SimProfile = SimProfile::Calibrated;

/// `--robot ros2`: a real robot over DDS, which only `ilmrc run` drives.
pub const ROS2_ROBOT: &str = "ros2";

/// The names `--robot` takes besides a ROBO.INI path.
pub const ROBOT_NAMES: &str = "moro, workpartner, ros2, none, scripted";

/// Starts used instead of a shipped world's own `start`: the office's is beside the lab
/// bench, where the Figure 52 task's left turn (radius 2 m) runs into the bench; south
/// of the bench there is room for it. `--start` overrides both; Figure 20 starts in the
/// office's north wing, in the robot's room facing its door (`--start 8,21,90`).
const RUN_STARTS: [(&str, f64, f64, f64); 1] = [("office", 8.0, 5.0, 0.0)];

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

impl Backend {
    /// The backend `--robot` names (anything else is a simulated robot's model).
    pub fn of(robot: &str) -> Backend {
        match robot.to_ascii_lowercase().as_str() {
            "none" => Backend::None,
            "scripted" => Backend::Scripted,
            ROS2_ROBOT => Backend::Ros2,
            _ => Backend::Sim(RobotKind::Moro),
        }
    }
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

pub struct Choice<'a> {
    pub robot: &'a str,
    /// `--sim-profile`, when given.
    pub profile: Option<SimProfile>,
    pub model: Option<&'a str>,
    pub world: Option<&'a str>,
    pub start: Option<&'a str>,
}

/// Where a run's robot is, without its ROS 2 settings.
pub struct Placed {
    pub backend: Backend,
    /// A simulated robot's errors (`--sim-profile`); `basic` for the others.
    pub profile: SimProfile,
    /// What `check` is given: `moro`, `workpartner` or a ROBO.INI path.
    pub model_spec: String,
    pub model: RobotModel,
    /// Simulated robots only; its `start` is where the robot starts.
    pub world: Option<LoadedWorld>,
}

/// Places the robot `c` names. A model file's warnings go to `warn` as soon as it is
/// read (before a later problem ends the choice), so that a run on a model `check`
/// warns about is not silently a run on other values.
pub fn place(
    c: &Choice<'_>,
    warn: &mut dyn FnMut(&str, &[ModelWarning]),
) -> Result<Placed, String> {
    let backend = Backend::of(c.robot);
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
        let loaded = load_robot(c.robot).map_err(|e| {
            if e.starts_with("unknown robot") {
                format!(
                    "unknown robot `{}`: use {ROBOT_NAMES} or a path to a ROBO.INI file",
                    c.robot
                )
            } else {
                e
            }
        })?;
        warn(c.robot, &loaded.warnings);
        let kind = body_of(c.robot, &loaded.model);
        let mut world = load_world(c.world.unwrap_or(default_world(kind)))?;
        if let Some(text) = c.start {
            world.world.start = parse_start(text, &world.world)?;
        } else if let Some(&(_, x, y, h)) = RUN_STARTS.iter().find(|(n, ..)| *n == world.name) {
            world.world.start = ilmr_sim::Pose::new(x, y, f64::to_radians(h));
        }
        return Ok(Placed {
            backend: Backend::Sim(kind),
            profile: c.profile.unwrap_or(DEFAULT_PROFILE),
            model_spec: c.robot.to_string(),
            model: loaded.model,
            world: Some(world),
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
    let robot = load_robot(&model_spec)?;
    warn(&model_spec, &robot.warnings);
    Ok(Placed {
        backend,
        profile: SimProfile::Basic,
        model_spec,
        model: robot.model,
        world: None,
    })
}

/// A loaded robot model, with where it came from so that its warnings can point there.
pub struct Robot {
    pub model: RobotModel,
    pub warnings: Vec<ModelWarning>,
    /// The model file's path and text, when it came from a file.
    pub file: Option<Source>,
}

/// `moro`, `workpartner`, or a path to a ROBO.INI file.
pub fn load_robot(spec: &str) -> Result<Robot, String> {
    if let Some(model) = RobotModel::builtin(spec) {
        return Ok(Robot {
            model,
            warnings: Vec::new(),
            file: None,
        });
    }
    let path = std::path::Path::new(spec);
    let looks_like_path = spec.contains(['/', '\\', '.']);
    if !looks_like_path {
        return Err(format!(
            "unknown robot `{spec}`: use {} or a path to a ROBO.INI file",
            RobotModel::builtin_names().join(", ")
        ));
    }
    let (model, warnings) =
        RobotModel::load(path).map_err(|e| format!("cannot read robot model `{spec}`: {e}"))?;
    // The model was read a moment ago; its text only places its warnings.
    let text = ilmr_files::read(path, ilmr_files::Kind::RobotModel)
        .map(|bytes| String::from_utf8_lossy(&bytes).into_owned())
        .unwrap_or_default();
    Ok(Robot {
        model,
        warnings,
        file: Some(Source::new(spec, text)),
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
    let at = ilmr_sim::Point2::new(x, y);
    if !world.bounds.contains(at) {
        let b = world.bounds;
        return Err(format!(
            "--start ({x}, {y}) is outside the world `{}`, which spans ({}, {})..({}, {})",
            world.name, b.min.x, b.min.y, b.max.x, b.max.y
        ));
    }
    Ok(ilmr_sim::Pose::new(x, y, h.to_radians()))
}

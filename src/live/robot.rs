//! The robot `ilmrc serve` and `ilmrc shell` drive, chosen as `ilmrc run` chooses it
//! (`run`'s own setup: the same robots, models, worlds, start poses and `--start`): a
//! simulated robot in its world, or a ROS 2 robot over DDS. Both run in real time.

use ilmr_model::RobotModel;
use ilmr_vm::{Config, TraceLevel};

use super::RobotArgs;
use crate::run::backend::AnyRobot;
use crate::run::scenario::Scenario;
use crate::run::setup::{self, Backend, Choice, check_faults, vm_config};

/// Ticks between pose samples in the event stream: 10 Hz.
const POSE_EVERY: u32 = 10;

pub struct Opened {
    /// `moro`, `workpartner` or the ROBO.INI path: what the task is checked against.
    pub spec: String,
    pub model: RobotModel,
    pub robot: AnyRobot,
    pub config: Config,
    /// Where the robot is: the world's name or file, or its ROS 2 namespace.
    pub world: String,
    /// The simulated robot's world, for a viewer.
    pub scene: Option<ilmr_sim::World>,
}

pub fn open(args: &RobotArgs) -> Result<Opened, String> {
    let spec = args.robot.as_str();
    if ["none", "scripted"]
        .iter()
        .any(|n| n.eq_ignore_ascii_case(spec))
    {
        return Err(format!(
            "--robot {spec}: a live robot is a simulated one or a ROS 2 one; use moro, \
             workpartner, ros2 or a path to a ROBO.INI file"
        ));
    }
    let setup = setup::choose(&Choice {
        robot: spec,
        profile: None,
        model: args.model.as_deref(),
        world: args.world.as_deref(),
        start: args.start.as_deref(),
        ros2: &args.ros2,
    })?;
    let (world, body) = match (setup.backend, &setup.world, &setup.ros2) {
        (Backend::Sim(kind), Some(loaded), _) => {
            check_faults(loaded, &setup.model, kind, None, 0)?;
            let body = ilmr_sim::config_from_model(&setup.model, kind);
            (loaded.name.clone(), Some(body))
        }
        (Backend::Ros2, _, Some(ros)) => (
            format!(
                "ROS 2 namespace {}, DDS domain {}",
                ros.namespace, ros.domain_id
            ),
            None,
        ),
        _ => return Err(format!("--robot {spec} is not a live robot")),
    };
    let robot = setup::open(&setup, &Scenario::default(), args.seed)?;
    let mut config = Config {
        trace: TraceLevel::Full,
        pose_every: POSE_EVERY,
        ..vm_config(&setup.model, body.as_ref())
    };
    if setup.backend == Backend::Ros2 {
        config.scanner_offset = setup::ros2_scanner_offset(&robot);
    }
    let scene = setup.world.map(|w| w.world);
    Ok(Opened {
        spec: setup.model_spec,
        model: setup.model,
        robot,
        config,
        world,
        scene,
    })
}

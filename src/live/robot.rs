//! The simulated robot `ilmrc serve` and `ilmrc shell` drive: `--robot`, `--world` and
//! `--seed` to a model, a `SimRobot` in its world, and the VM's `Config`, by `run`'s
//! own setup.

use ilmr_model::RobotModel;
use ilmr_sim::SimRobot;
use ilmr_vm::{Config, TraceLevel};

use crate::run::setup::{body_of, check_faults, default_world, load_world, vm_config};

/// Ticks between pose samples in the event stream: 10 Hz.
const POSE_EVERY: u32 = 10;

pub struct Opened {
    /// `moro`, `workpartner` or the ROBO.INI path: what the task is checked against.
    pub spec: String,
    pub model: RobotModel,
    pub robot: SimRobot,
    pub config: Config,
    /// The world's name or file.
    pub world: String,
}

pub fn open(spec: &str, world: Option<&str>, seed: u64) -> Result<Opened, String> {
    if ["none", "scripted"]
        .iter()
        .any(|n| n.eq_ignore_ascii_case(spec))
    {
        return Err(format!(
            "--robot {spec}: a live robot is a simulated one; use moro, workpartner or a \
             path to a ROBO.INI file"
        ));
    }
    let model = crate::inputs::load_robot(spec)?.model;
    let kind = body_of(spec, &model);
    let world_spec = world.unwrap_or(default_world(kind));
    let loaded = load_world(world_spec)?;
    check_faults(&loaded, &model, kind, None, 0)?;
    let loaded = loaded.world;
    let body = ilmr_sim::config_from_model(&model, kind);
    let start = loaded.start;
    let robot = SimRobot::new(model.clone(), kind, loaded, seed).map_err(|e| {
        format!(
            "the robot cannot start at ({:.2}, {:.2}, {:.0} deg) in `{world_spec}`: {e}",
            start.x,
            start.y,
            start.h.to_degrees()
        )
    })?;
    let config = Config {
        trace: TraceLevel::Full,
        pose_every: POSE_EVERY,
        ..vm_config(&model, Some(&body))
    };
    Ok(Opened {
        spec: spec.to_string(),
        model,
        robot,
        config,
        world: world_spec.to_string(),
    })
}

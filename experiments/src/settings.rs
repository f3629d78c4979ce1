//! The VM's physical settings for each simulated robot, as `ilmrc run` and every
//! experiment use them (`ilmr_vm::Config::for_robot` from the shipped ROBO.INI models).

use crate::harness::{moro, shipped, vm_config, workpartner};

#[derive(Debug, Clone, PartialEq)]
pub struct RobotSettings {
    pub name: &'static str,
    /// 1/m.
    pub max_curvature: f64,
    /// 1/(m s).
    pub curinc: f64,
    /// m/s².
    pub acceleration: f64,
    pub deceleration: f64,
    /// The curvature of `turn(left|right)`, 1/m.
    pub turn_curvature: f64,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Settings {
    pub moro: RobotSettings,
    pub workpartner: RobotSettings,
}

fn of(name: &'static str, robot: &ilmr_sim::SimRobot) -> RobotSettings {
    let c = vm_config(robot.model(), robot.sim().config());
    RobotSettings {
        name,
        max_curvature: c.max_curvature,
        curinc: c.curinc,
        acceleration: c.acceleration,
        deceleration: c.deceleration,
        turn_curvature: c.turn_curvature,
    }
}

impl Settings {
    pub fn of_both() -> Result<Settings, String> {
        Ok(Settings {
            moro: of("MoRo", &moro(shipped("empty")?, 0)?),
            workpartner: of("Workpartner", &workpartner(shipped("empty")?, 0)?),
        })
    }
}

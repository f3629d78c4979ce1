//! Whether a fault fits the robot it is injected into: a fault for a part the robot
//! lacks, or one that starts after the run ends, would do nothing, silently. Checked
//! like a command: the message names what the robot has.

use ilmr_model::RobotModel;

use super::{DRIVE, FaultKind, FaultSpec, KIND_NAMES};
use crate::config::{RobotConfig, RobotKind};

/// The devices the simulated robot measures (`SimRobot`'s device readings); any other
/// device of the model is an actuator, whose value `actuator(..)` sets and holds.
pub const SENSOR_DEVICES: [&str; 10] = [
    "battery",
    "camera",
    "frontwheel",
    "gyro",
    "inclinometer",
    "laser",
    "odometry",
    "plates",
    "scanner",
    "ultrasonic",
];

/// The part of the robot `kind` needs that a body may lack: `None` when every body
/// has it.
pub fn missing_part(kind: &FaultKind, cfg: &RobotConfig) -> Option<&'static str> {
    match kind {
        FaultKind::NavFrozen if cfg.nav.is_none() => Some("navigation fix"),
        FaultKind::ManipulatorSilent if cfg.kind == RobotKind::Moro => Some("manipulator"),
        _ => None,
    }
}

/// What `actuator_dead` may name on this robot: `drive`, then the model's actuators in
/// file order.
pub fn actuators(model: &RobotModel) -> Vec<String> {
    std::iter::once(DRIVE.to_string())
        .chain(
            model
                .devices
                .iter()
                .filter(|d| {
                    !SENSOR_DEVICES
                        .iter()
                        .any(|s| s.eq_ignore_ascii_case(&d.name))
                })
                .map(|d| d.name.clone()),
        )
        .collect()
}

/// The fault kinds this body can suffer, in [`KIND_NAMES`] order.
pub fn kinds_for(cfg: &RobotConfig) -> Vec<&'static str> {
    KIND_NAMES
        .iter()
        .copied()
        .filter(|name| {
            FaultKind::named(name).is_some_and(|kind| missing_part(&kind, cfg).is_none())
        })
        .collect()
}

/// Checks `spec` against the robot (its body `cfg` and its `model`) and the run's
/// length (`max_time`, s; `None` for a run without an end). The message names what
/// the robot has.
pub fn check_fits(
    spec: &FaultSpec,
    cfg: &RobotConfig,
    model: &RobotModel,
    max_time: Option<f64>,
) -> Result<(), String> {
    if let Some(what) = missing_part(&spec.kind, cfg) {
        return Err(format!(
            "{:?} has no {what}; the faults it can take are {}",
            cfg.kind,
            kinds_for(cfg).join(", ")
        ));
    }
    if let FaultKind::ActuatorDead { actuator } = &spec.kind {
        let names = actuators(model);
        if !names.iter().any(|n| n.eq_ignore_ascii_case(actuator)) {
            let what = if SENSOR_DEVICES
                .iter()
                .any(|s| s.eq_ignore_ascii_case(actuator))
                && model.device(actuator).is_some()
            {
                format!(
                    "`{actuator}` is a sensor of {}, not an actuator",
                    model.name
                )
            } else {
                format!("{} has no actuator `{actuator}`", model.name)
            };
            return Err(format!("{what}; its actuators are {}", names.join(", ")));
        }
    }
    if let Some(end) = max_time
        && spec.start > end
    {
        return Err(format!(
            "it starts at {} s, after the run ends (--max-time {end})",
            spec.start
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::faults::flag;

    fn fits(text: &str, cfg: &RobotConfig, robot: &str) -> Result<(), String> {
        let spec = flag::parse(text)?;
        let model = RobotModel::builtin(robot).unwrap_or_else(|| panic!("{robot}"));
        check_fits(&spec, cfg, &model, Some(600.0))
    }

    #[test]
    fn every_fault_moro_can_take_fits_it() {
        let moro = RobotConfig::moro();
        for text in [
            "scanner_dropout",
            "actuator_dead",
            "actuator_dead:horn",
            "actuator_dead:HORN",
            "obstacle_appears@600",
        ] {
            assert_eq!(fits(text, &moro, "moro"), Ok(()), "{text}");
        }
        let wp = RobotConfig::workpartner();
        for text in ["nav_frozen", "manipulator_silent", "actuator_dead:leg3"] {
            assert_eq!(fits(text, &wp, "workpartner"), Ok(()), "{text}");
        }
    }

    #[test]
    fn a_part_the_robot_lacks_is_named_with_what_it_has() {
        let moro = RobotConfig::moro();
        assert_eq!(
            fits("actuator_dead:nonexistent", &moro, "moro"),
            Err("moro has no actuator `nonexistent`; its actuators are drive, horn".into())
        );
        assert_eq!(
            fits("actuator_dead@0:scanner", &moro, "moro"),
            Err(
                "`scanner` is a sensor of moro, not an actuator; its actuators are drive, horn"
                    .into()
            )
        );
        assert_eq!(
            fits("nav_frozen", &moro, "moro"),
            Err(
                "Moro has no navigation fix; the faults it can take are scanner_dropout, \
                 odometry_slip, odometry_bias, odometry_dropout, dead_battery, actuator_dead, \
                 obstacle_appears"
                    .into()
            )
        );
        assert!(
            fits("manipulator_silent", &moro, "moro")
                .is_err_and(|e| e.starts_with("Moro has no manipulator;"))
        );
    }

    #[test]
    fn a_fault_after_the_end_of_the_run_is_refused() {
        assert_eq!(
            fits("dead_battery@600.5", &RobotConfig::moro(), "moro"),
            Err("it starts at 600.5 s, after the run ends (--max-time 600)".into())
        );
        let spec = flag::parse("dead_battery@1e9").unwrap_or_else(|e| panic!("{e}"));
        let model = RobotModel::builtin("moro").unwrap_or_else(|| panic!("moro"));
        assert_eq!(
            check_fits(&spec, &RobotConfig::moro(), &model, None),
            Ok(())
        );
    }

    /// The world docs list the sensors `actuator_dead` may not name.
    #[test]
    fn the_worlds_readme_lists_the_sensors() {
        let readme = include_str!("../../../worlds/README.md");
        for s in SENSOR_DEVICES {
            assert!(readme.contains(&format!("`{s}`")), "{s}");
        }
    }

    /// `random_plan` draws from the kinds a body can take; this is that list.
    #[test]
    fn the_kinds_a_body_takes_match_the_soak_plans() {
        for kind in [RobotKind::Moro, RobotKind::Workpartner] {
            let cfg = RobotConfig::for_kind(kind);
            let plan = super::super::random_plan(7, 100.0, 400, kind);
            let mut drawn: Vec<&str> = plan.iter().map(|s| s.kind.name()).collect();
            drawn.sort_unstable();
            drawn.dedup();
            let mut allowed = kinds_for(&cfg);
            allowed.sort_unstable();
            assert_eq!(drawn, allowed, "{kind:?}");
        }
    }
}

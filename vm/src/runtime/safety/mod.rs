//! Issue 7's guarantees inside the VM: refusing harmful computed commands
//! ([`refuse`]), the supervisor checked every tick ([`supervisor`]), and their stable
//! codes ([`codes`]). The halt ramp every stop goes through is the movement's
//! (`motion/halt.rs`). Thresholds come from the robot model through [`Safety`].

pub mod codes;
pub(crate) mod frame;
pub(crate) mod known;
mod refuse;
pub(crate) mod supervisor;
mod sweep;

use ilmr_model::RobotModel;

pub use codes::{CODES, Code, FAULTS, Fault, Reaction, ways_out_markdown};
pub(crate) use refuse::Refusal;

/// Limits of `bodypose(r=,p=,rc=)`: degrees, degrees, metres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyLimits {
    pub max_roll: f64,
    pub max_pitch: f64,
    pub max_clearance: f64,
}

/// The thresholds of the refusals and of the supervisor. Each field names the
/// ROBO.INI parameter it comes from; `None` switches a check off.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Safety {
    /// A computed `speed(v)` beyond this is refused, m/s (`max_speed`).
    pub max_speed: f64,
    /// `None`: the robot has no body pose, and `bodypose` is refused
    /// (`max_roll`, `max_pitch`, `max_clearance`).
    pub body: Option<BodyLimits>,
    /// `battery_low` below this, V (`LowBattery`).
    pub low_battery: Option<f64>,
    /// `scanner_lost` when the latest scan is older, s (`scanner_timeout`).
    pub scanner_timeout: Option<f64>,
    /// `odometry_lost` when the latest odometry sample is older, s
    /// (`odometry_timeout`).
    pub odometry_timeout: Option<f64>,
    /// `nav_lost` when the latest navigation fix is older, s (`nav_timeout`).
    pub nav_timeout: Option<f64>,
    /// With obstacle avoidance off, `obstacle_near` when an obstacle is nearer than
    /// the braking distance plus this, m (`stop_margin`).
    pub stop_margin: Option<f64>,
    /// A pose estimate moving this much more than the robot can drive in a tick is a
    /// `localization_jump`, m (`localization_jump`).
    pub localization_jump: f64,
    /// The same for the heading, radians (`localization_jump_h`, in degrees there).
    pub localization_jump_h: f64,
    /// An operation pending this long is given up, s (`operation_timeout`).
    pub operation_timeout: Option<f64>,
    /// The speed limit while `nav_lost`, m/s (`degraded_speed`).
    pub degraded_speed: f64,
}

impl Default for Safety {
    /// The defaults model's values, with the dissertation's body pose limits
    /// (roll and pitch +/-30 degrees, clearance 0-1 m) and the scripted robot's
    /// 1 m/s top speed.
    fn default() -> Safety {
        Safety {
            max_speed: 1.0,
            body: Some(BodyLimits {
                max_roll: 30.0,
                max_pitch: 30.0,
                max_clearance: 1.0,
            }),
            low_battery: Some(23.0),
            scanner_timeout: Some(1.5),
            odometry_timeout: Some(0.5),
            nav_timeout: None,
            stop_margin: Some(0.2),
            localization_jump: 0.5,
            localization_jump_h: 20f64.to_radians(),
            operation_timeout: Some(60.0),
            degraded_speed: 0.1,
        }
    }
}

impl Safety {
    /// The thresholds a robot model gives (its defaults where it is silent).
    pub fn from_model(model: &RobotModel) -> Safety {
        let body = match (model.max_roll(), model.max_pitch(), model.max_clearance()) {
            (Some(max_roll), Some(max_pitch), Some(max_clearance)) => Some(BodyLimits {
                max_roll,
                max_pitch,
                max_clearance,
            }),
            _ => None,
        };
        Safety {
            max_speed: model.max_speed(),
            body,
            low_battery: Some(model.low_battery()),
            scanner_timeout: Some(model.scanner_timeout()),
            odometry_timeout: Some(model.odometry_timeout()),
            nav_timeout: model.nav_timeout(),
            stop_margin: Some(model.stop_margin()),
            localization_jump: model.localization_jump(),
            localization_jump_h: model.localization_jump_h().to_radians(),
            operation_timeout: Some(model.operation_timeout()),
            degraded_speed: model.degraded_speed(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_models_set_the_thresholds() {
        let wp = RobotModel::builtin("workpartner").expect("shipped");
        let s = Safety::from_model(&wp);
        assert_eq!(s.max_speed, 0.6);
        assert_eq!(s.nav_timeout, Some(1.5));
        assert_eq!(s.body.map(|b| b.max_roll), Some(30.0));
        assert_eq!(s.stop_margin, Some(0.3));
        let moro = Safety::from_model(&RobotModel::builtin("moro").expect("shipped"));
        assert_eq!(moro.body, None, "MoRo has no body pose");
        assert_eq!(moro.nav_timeout, None, "nor a navigation subsystem");
        assert_eq!(moro.odometry_timeout, Some(0.25));
    }
}

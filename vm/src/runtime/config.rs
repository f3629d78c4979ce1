//! Tunables of the VM. The defaults are MoRo-like; a robot model overrides the
//! physical ones (each field names the ROBO.INI parameter it comes from).

use super::safety::Safety;
use ilmr_hal::BodyOffsets;
use ilmr_model::RobotModel;

/// `turn(left|right)` on a known body: three quarters of full lock, so the
/// controller keeps steering in reserve. At full lock it cannot catch up with
/// the arc's start, and at its end it takes the time of a full curinc ramp to
/// straighten: MoRo came out of test 2's corner 8 degrees past north, its
/// commanded arc into the side corridor's wall, and stood held (the clipping
/// of Figure 48 that "requires some modification to the code of ILMR"). The
/// room the turn needs is checked with the robot's outline on this arc
/// (`ilmr_motion::wall::turn_space_free`, section 4.5.3).
pub const TURN_SHARE: f64 = 0.75;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TraceLevel {
    /// No events (benchmarks).
    Off,
    /// Everything except pose samples.
    Commands,
    /// Everything.
    Full,
}

/// Which of this project's changes to the position controller of section 4.5.2.2
/// (eqs. 4-8) are on. [`Controller::PROJECT`] is the default; [`Controller::DISSERTATION`]
/// is the controller as the dissertation describes it, kept so that the two can be
/// compared on the same seeds (docs/experiments.md, "What the controller adds").
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Controller {
    /// The look-ahead never shorter than half a turning radius
    /// (`ilmr_motion::controller::ControllerParams::min_lookahead_radii`); off, only
    /// the speed, Δc and the curvature gap set it, as in the dissertation.
    pub lookahead_floor: bool,
    /// c_now of eq. (4) is the curvature commanded last cycle; off, it is the robot's
    /// measured curvature ("the current curvature of the robot"), which lags the
    /// command by the steering's dead time.
    pub commanded_curvature: bool,
}

impl Controller {
    pub const PROJECT: Controller = Controller {
        lookahead_floor: true,
        commanded_curvature: true,
    };
    pub const DISSERTATION: Controller = Controller {
        lookahead_floor: false,
        commanded_curvature: false,
    };
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Config {
    /// Seconds per tick (100 Hz).
    pub period: f64,
    /// Instructions and expression ops a tick may run before blocks are suspended.
    pub budget_ops: u32,
    /// Two positions compare equal within this distance, metres.
    pub position_tolerance: f64,
    /// A running movement links to the queued next one this far before its end, metres.
    pub link_distance: f64,
    /// Speed before any `speed(..)`, m/s.
    pub default_speed: f64,
    /// The robot's largest curvature, 1/m: the controller never asks for more
    /// (`max_curvature`).
    pub max_curvature: f64,
    /// Fastest change of curvature, 1/m per s: Δc of the controller (`curinc`).
    pub curinc: f64,
    /// Curvature of `turn(left)` and `turn(right)`, 1/m.
    pub turn_curvature: f64,
    /// Shortest look-ahead of the position controller, metres.
    pub lookahead: f64,
    /// Planned acceleration, m/s^2 (`max_acceleration`).
    pub acceleration: f64,
    /// Planned deceleration towards a goal, m/s^2 (`max_deceleration`).
    pub deceleration: f64,
    /// Width of the robot, metres: the checked area of equation (12) and the
    /// room `turn(left|right)` needs (`robot_width`).
    pub robot_width: f64,
    /// Length of the robot, metres (`robot_length`).
    pub robot_length: f64,
    /// From the reference point (whose pose the robot reports) to the front, metres.
    pub front_offset: f64,
    /// The laser scanner sits this far ahead of the reference point, metres.
    pub scanner_offset: f64,
    /// Distance of `followwall` when none is given, metres (`followwall_d`).
    pub followwall_d: f64,
    /// Largest curvature of paths round obstacles, 1/m (`omax_curvature`).
    pub obstacle_curvature: f64,
    /// Seconds an obstacle must stay away before the avoider returns to normal
    /// (`bs_security`).
    pub security_wait: f64,
    /// A movement has arrived when this close to its end, metres.
    pub goal_tolerance: f64,
    /// Ticks between pose samples.
    pub pose_every: u32,
    /// A reading that gives no data for this long is refused, seconds.
    pub sensor_timeout: f64,
    /// Nested skill calls beyond this are refused.
    pub max_call_depth: u16,
    /// `record(..)` stores a point every this many metres.
    pub record_spacing: f64,
    pub trace: TraceLevel,
    /// Run blocks that only compute and sleep as compact frames (`docs/bytecode.md`);
    /// `false` runs every block on the tree of nodes. Both give the same trace.
    pub frames: bool,
    /// Thresholds of the run-time refusals and the supervisor.
    pub safety: Safety,
    /// The position controller's variant.
    pub controller: Controller,
}

impl Config {
    /// The one place that turns a ROBO.INI model, and a body's offsets where the
    /// body is known (a simulated one), into the VM's settings; `ilmrc run` and the
    /// experiments alike. Each field names the model parameter it stands for. Without
    /// a body (a scripted robot, or none) the defaults stand for what the model does
    /// not say, as they did for every scripted trace recorded so far.
    pub fn for_robot(model: &RobotModel, body: Option<BodyOffsets>) -> Config {
        let base = Config::default();
        let mut config = Config {
            default_speed: model.default_speed(),
            max_curvature: model.max_curvature(),
            curinc: model.curinc(),
            turn_curvature: base.turn_curvature.min(model.max_curvature()),
            acceleration: model.max_acceleration(),
            deceleration: model.max_deceleration(),
            robot_width: model.robot_width(),
            robot_length: model.robot_length(),
            followwall_d: model.followwall_d(),
            obstacle_curvature: model.omax_curvature(),
            safety: Safety::from_model(model),
            ..base
        };
        if let Some(body) = body {
            config.turn_curvature = TURN_SHARE * model.max_curvature();
            config.front_offset = body.front;
            config.scanner_offset = body.scanner;
            config.security_wait = model.bs_security();
        }
        config
    }
}

impl Default for Config {
    fn default() -> Config {
        Config {
            period: 0.01,
            budget_ops: 200_000,
            position_tolerance: 0.3,
            link_distance: 0.5,
            default_speed: 0.3,
            max_curvature: 1.4,
            curinc: 2.0,
            turn_curvature: 0.5,
            lookahead: 0.6,
            acceleration: 0.5,
            deceleration: 0.5,
            robot_width: 0.6,
            robot_length: 1.2,
            front_offset: 0.95,
            scanner_offset: 0.85,
            followwall_d: 1.0,
            obstacle_curvature: 1.0,
            security_wait: 0.5,
            goal_tolerance: 0.02,
            pose_every: 10,
            sensor_timeout: 1.0,
            max_call_depth: 64,
            record_spacing: 0.1,
            trace: TraceLevel::Full,
            frames: true,
            safety: Safety::default(),
            controller: Controller::PROJECT,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_known_body_sets_its_offsets_and_the_turn_share() {
        let model = RobotModel::builtin("workpartner").unwrap_or_else(|| unreachable!());
        let body = BodyOffsets {
            front: 2.1,
            scanner: 1.7,
        };
        let c = Config::for_robot(&model, Some(body));
        assert_eq!(c.max_curvature, 0.25);
        assert!((c.turn_curvature - 0.1875).abs() < 1e-12);
        assert_eq!((c.front_offset, c.scanner_offset), (2.1, 1.7));
        assert_eq!(c.security_wait, model.bs_security());
        assert_eq!(c.safety.max_speed, model.max_speed());
        let bare = Config::for_robot(&model, None);
        assert_eq!(bare.front_offset, Config::default().front_offset);
        assert!(bare.turn_curvature <= 0.25);
    }
}

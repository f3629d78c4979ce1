//! The parameters the ILMR algorithms read: one table with unit, default,
//! admissible range, meaning and readers, and a typed accessor for each.
//!
//! The table is the single source: the parser validates against it, the
//! accessors fall back to it, and `docs/robot-model.md` carries a table
//! generated from it (a test keeps the two equal).

use crate::model::RobotModel;

/// What a parameter is worth when the model does not define it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ParamDefault {
    /// A fixed value (Figure 39's where Figure 39 has one).
    Value(f64),
    /// The value of another parameter (dead reckoning runs at the odometry
    /// rate unless told otherwise).
    SameAs(&'static ParamSpec),
    /// No default: the robot lacks the feature (MoRo has no body pose), and
    /// the accessor returns `None`.
    Absent,
}

/// Which values a parameter admits. A value outside is a corrupt line.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Valid {
    /// `> 0` and `<= max`.
    PositiveAtMost(f64),
    /// `min ..= max`.
    Between(f64, f64),
}

impl Valid {
    pub fn admits(self, v: f64) -> bool {
        match self {
            Valid::PositiveAtMost(max) => v > 0.0 && v <= max,
            Valid::Between(min, max) => (min..=max).contains(&v),
        }
    }

    /// The range as the docs and warnings write it.
    pub fn describe(self) -> String {
        match self {
            Valid::PositiveAtMost(max) => format!("> 0 and <= {max}"),
            Valid::Between(min, max) => format!("{min} to {max}"),
        }
    }
}

/// One known parameter.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParamSpec {
    /// Spelling used in the files and the docs (lookups ignore case).
    pub name: &'static str,
    /// SI unit (`m`, `m/s`, `1/m`, `Hz`, `s`, `V`, `deg`).
    pub unit: &'static str,
    pub default: ParamDefault,
    pub valid: Valid,
    /// What the value means, one sentence.
    pub meaning: &'static str,
    /// Which ILMR components read it.
    pub readers: &'static str,
}

// Ranges: wide enough for any wheeled robot a developer would describe (the
// dissertation's MoRo and Workpartner sit well inside), narrow enough that no
// value makes the tools allocate or loop in proportion to it (issue 12).
// Rates are capped at the VM's 100 Hz tick, since a faster source cannot be
// observed, and floored where a period would outlast any supervision timeout;
// angles of the body pose at 90 degrees.
const TICK_HZ: f64 = 100.0;
const MIN_RATE_HZ: f64 = 0.1;
/// m/s: 36 km/h, well past any mobile robot of the dissertation's kind.
const SPEED: f64 = 10.0;
/// 1/m: a 1 cm turning radius.
const CURVATURE: f64 = 100.0;
/// V: past any traction battery.
const VOLTAGE: f64 = 1000.0;
/// s: ten minutes without a sample is no supervision at all.
const SUPERVISION_TIMEOUT: f64 = 600.0;

pub const MAX_TIME_TO_SEARCH: ParamSpec = ParamSpec {
    name: "max_time_to_search",
    unit: "s",
    default: ParamDefault::Value(10.0),
    valid: Valid::PositiveAtMost(3600.0),
    meaning: "How long a search (`sensor(scanner,door)`, `findtarget`) should look before it ends without a find (Figure 39). Loaded and range-checked; the VM does not yet end searches by it: a search runs until it finds.",
    readers: "none yet",
};
pub const DEFAULT_SPEED: ParamSpec = ParamSpec {
    name: "default_speed",
    unit: "m/s",
    default: ParamDefault::Value(0.2),
    valid: Valid::PositiveAtMost(SPEED),
    meaning: "Speed of movement commands until the task gives `speed(...)`; must not exceed `max_speed`.",
    readers: "vm, motion",
};
pub const MAX_SPEED: ParamSpec = ParamSpec {
    name: "max_speed",
    unit: "m/s",
    default: ParamDefault::Value(0.6),
    valid: Valid::PositiveAtMost(SPEED),
    meaning: "Largest speed magnitude: `speed(v)` admits -max_speed..max_speed (the VM refuses a computed speed beyond it).",
    readers: "compiler (range check), vm, motion, sim",
};
pub const POS_INTERVAL: ParamSpec = ParamSpec {
    name: "pos_interval",
    unit: "m",
    default: ParamDefault::Value(0.5),
    valid: Valid::Between(0.01, 100.0),
    meaning: "Distance travelled between two positions stored by `record(file)`; `followpath` reads them back as its reference points.",
    readers: "vm (record), motion (followpath)",
};
pub const OMAX_CURVATURE: ParamSpec = ParamSpec {
    name: "omax_curvature",
    unit: "1/m",
    default: ParamDefault::Value(0.4),
    valid: Valid::PositiveAtMost(CURVATURE),
    meaning: "Largest curvature of the path around an obstacle (section 4.5.7); the path planner uses min(omax_curvature, max_curvature) so the robot can drive it.",
    readers: "motion (obstacle avoidance)",
};
pub const CURINC: ParamSpec = ParamSpec {
    name: "curinc",
    unit: "1/(m s)",
    default: ParamDefault::Value(0.8),
    valid: Valid::PositiveAtMost(100.0),
    meaning: "Largest rate of change of curvature, the Δc of equations (4)-(8) of the position controller.",
    readers: "motion (position controller), sim (steering rate)",
};
pub const ROBOT_LENGTH: ParamSpec = ParamSpec {
    name: "robot_length",
    unit: "m",
    default: ParamDefault::Value(2.2),
    valid: Valid::Between(0.05, 20.0),
    meaning: "Length of the robot's footprint; obstacle avoidance returns to the path only when the rear has passed the obstacle (Figure 34 H).",
    readers: "motion, sim",
};
pub const ROBOT_WIDTH: ParamSpec = ParamSpec {
    name: "robot_width",
    unit: "m",
    default: ParamDefault::Value(1.0),
    valid: Valid::Between(0.05, 10.0),
    meaning: "Width of the robot's footprint; the obstacle check area is 1.2 x robot_width wide (equation (12)).",
    readers: "motion, sim",
};
pub const FOLLOWWALL_D: ParamSpec = ParamSpec {
    name: "followwall_d",
    unit: "m",
    default: ParamDefault::Value(1.0),
    valid: Valid::PositiveAtMost(50.0),
    meaning: "Distance kept to the wall by `followwall(left)` and `followwall(right)` when no distance is given.",
    readers: "compiler (default argument), motion",
};
pub const BS_SECURITY: ParamSpec = ParamSpec {
    name: "bs_security",
    unit: "m",
    default: ParamDefault::Value(1.0),
    valid: Valid::PositiveAtMost(10.0),
    meaning: "Security distance of the scanner used as a safety switch: an obstacle nearer than this in the direction of travel stops the robot, whatever `obsavoid` is set to.",
    readers: "motion, sim",
};
pub const MAX_CURVATURE: ParamSpec = ParamSpec {
    name: "max_curvature",
    unit: "1/m",
    default: ParamDefault::Value(0.25),
    valid: Valid::PositiveAtMost(CURVATURE),
    meaning: "Largest curvature the robot can drive (1 / smallest turning radius): `turn(left)` drives an arc below it to keep steering in reserve (the VM's `TURN_SHARE`), the admissibility test of a Bezier path (section 4.5.2.1), R_max of equation (11).",
    readers: "compiler (range of `turn(c=)`), motion, sim",
};
pub const MAX_ACCELERATION: ParamSpec = ParamSpec {
    name: "max_acceleration",
    unit: "m/s^2",
    default: ParamDefault::Value(0.3),
    valid: Valid::Between(0.01, 20.0),
    meaning: "Largest rate at which the speed is raised.",
    readers: "motion, sim",
};
pub const MAX_DECELERATION: ParamSpec = ParamSpec {
    name: "max_deceleration",
    unit: "m/s^2",
    default: ParamDefault::Value(0.5),
    valid: Valid::Between(0.01, 20.0),
    meaning: "Largest rate at which the speed is lowered: `stop`, `advancestop` and the ends of paths brake with it.",
    readers: "motion, sim",
};
pub const WHEELBASE: ParamSpec = ParamSpec {
    name: "wheelbase",
    unit: "m",
    default: ParamDefault::Value(1.3),
    valid: Valid::Between(0.05, 20.0),
    meaning: "Distance from the steering axle to the fixed axle; turns a curvature into a steering angle (Workpartner's articulation joint, MoRo's front wheel).",
    readers: "hal, sim",
};
pub const LOW_BATTERY: ParamSpec = ParamSpec {
    name: "LowBattery",
    unit: "V",
    default: ParamDefault::Value(23.0),
    valid: Valid::PositiveAtMost(VOLTAGE),
    meaning: "Battery voltage below which the task should go and charge (Figure 20: `if(Battery<LowBattery)`); below battery_full. The supervisor raises `battery_low` below it.",
    readers: "compiler (model constant), vm (supervision), sim",
};
pub const BATTERY_FULL: ParamSpec = ParamSpec {
    name: "battery_full",
    unit: "V",
    default: ParamDefault::Value(25.6),
    valid: Valid::PositiveAtMost(VOLTAGE),
    meaning: "Voltage of a fully charged battery; the simulator starts a run there.",
    readers: "sim, hal",
};
pub const SCANNER_RANGE: ParamSpec = ParamSpec {
    name: "scanner_range",
    unit: "m",
    default: ParamDefault::Value(30.0),
    valid: Valid::PositiveAtMost(250.0),
    meaning: "Furthest scanner reading that counts as a hit (Figure 39's scanner reads 0..30000 mm).",
    readers: "sim, motion (environment map)",
};
pub const SCANNER_RATE: ParamSpec = ParamSpec {
    name: "scanner_rate",
    unit: "Hz",
    default: ParamDefault::Value(2.0),
    valid: Valid::Between(MIN_RATE_HZ, TICK_HZ),
    meaning: "Rate of new scans, so of environment-map updates and obstacle checks (2-4 Hz in the dissertation).",
    readers: "sim, hal, motion",
};
pub const ODOMETRY_RATE: ParamSpec = ParamSpec {
    name: "odometry_rate",
    unit: "Hz",
    default: ParamDefault::Value(10.0),
    valid: Valid::Between(MIN_RATE_HZ, TICK_HZ),
    meaning: "Rate of wheel odometry samples.",
    readers: "sim, hal",
};
pub const SCANNER_TIMEOUT: ParamSpec = ParamSpec {
    name: "scanner_timeout",
    unit: "s",
    default: ParamDefault::Value(1.5),
    valid: Valid::PositiveAtMost(SUPERVISION_TIMEOUT),
    meaning: "Supervision: no scan for this long is a scanner fault and the robot stops; should exceed 1/scanner_rate.",
    readers: "vm (supervision), hal",
};
pub const ODOMETRY_TIMEOUT: ParamSpec = ParamSpec {
    name: "odometry_timeout",
    unit: "s",
    default: ParamDefault::Value(0.5),
    valid: Valid::PositiveAtMost(SUPERVISION_TIMEOUT),
    meaning: "Supervision: no odometry sample for this long is a fault and the robot stops; should exceed 1/odometry_rate.",
    readers: "vm (supervision), hal",
};
pub const NAV_RATE: ParamSpec = ParamSpec {
    name: "nav_rate",
    unit: "Hz",
    default: ParamDefault::Absent,
    valid: Valid::Between(MIN_RATE_HZ, TICK_HZ),
    meaning: "Rate of position fixes from a separate navigation subsystem (Workpartner: 2 Hz); absent when the robot has none.",
    readers: "sim, hal",
};
pub const NAV_TIMEOUT: ParamSpec = ParamSpec {
    name: "nav_timeout",
    unit: "s",
    default: ParamDefault::Absent,
    valid: Valid::PositiveAtMost(SUPERVISION_TIMEOUT),
    meaning: "Supervision: no navigation fix for this long is a fault; should exceed 1/nav_rate.",
    readers: "vm (supervision), hal",
};
pub const DEADRECKONING_RATE: ParamSpec = ParamSpec {
    name: "deadreckoning_rate",
    unit: "Hz",
    default: ParamDefault::SameAs(&ODOMETRY_RATE),
    valid: Valid::Between(MIN_RATE_HZ, TICK_HZ),
    meaning: "Rate of dead-reckoning updates between navigation fixes (equation (1); Workpartner: 10 Hz); defaults to odometry_rate.",
    readers: "hal, sim",
};
pub const MAX_ROLL: ParamSpec = ParamSpec {
    name: "max_roll",
    unit: "deg",
    default: ParamDefault::Absent,
    valid: Valid::Between(0.0, 90.0),
    meaning: "`bodypose(r=)` admits -max_roll..max_roll; absent when the robot has no body pose.",
    readers: "compiler (range check), vm (refusal), hal, sim",
};
pub const MAX_PITCH: ParamSpec = ParamSpec {
    name: "max_pitch",
    unit: "deg",
    default: ParamDefault::Absent,
    valid: Valid::Between(0.0, 90.0),
    meaning: "`bodypose(p=)` admits -max_pitch..max_pitch; absent when the robot has no body pose.",
    readers: "compiler (range check), vm (refusal), hal, sim",
};
pub const MAX_CLEARANCE: ParamSpec = ParamSpec {
    name: "max_clearance",
    unit: "m",
    default: ParamDefault::Absent,
    valid: Valid::PositiveAtMost(1.0),
    meaning: "`bodypose(rc=)` admits 0..max_clearance; absent when the robot has no body pose.",
    readers: "compiler (range check), vm (refusal), hal, sim",
};

pub const STOP_MARGIN: ParamSpec = ParamSpec {
    name: "stop_margin",
    unit: "m",
    default: ParamDefault::Value(0.2),
    valid: Valid::PositiveAtMost(10.0),
    meaning: "Supervision: with obstacle avoidance off, an obstacle in the checked area nearer than the braking distance plus this stops the robot, which then stands this far from it.",
    readers: "vm (supervision)",
};
pub const LOCALIZATION_JUMP: ParamSpec = ParamSpec {
    name: "localization_jump",
    unit: "m",
    default: ParamDefault::Value(0.5),
    valid: Valid::PositiveAtMost(100.0),
    meaning: "Supervision: the pose estimate moving this much further in one tick than the robot can drive is a localization jump.",
    readers: "vm (supervision)",
};
pub const LOCALIZATION_JUMP_H: ParamSpec = ParamSpec {
    name: "localization_jump_h",
    unit: "deg",
    default: ParamDefault::Value(20.0),
    valid: Valid::Between(0.0, 180.0),
    meaning: "Supervision: the heading estimate turning this much further in one tick than the robot can turn is a localization jump.",
    readers: "vm (supervision)",
};
pub const OPERATION_TIMEOUT: ParamSpec = ParamSpec {
    name: "operation_timeout",
    unit: "s",
    default: ParamDefault::Value(60.0),
    valid: Valid::PositiveAtMost(3600.0),
    meaning: "Supervision: an asynchronous operation (`init`, `manipulate`, `movemode`) that has not answered after this long is cancelled and refused.",
    readers: "vm (supervision)",
};
pub const DEGRADED_SPEED: ParamSpec = ParamSpec {
    name: "degraded_speed",
    unit: "m/s",
    default: ParamDefault::Value(0.1),
    valid: Valid::PositiveAtMost(SPEED),
    meaning: "Supervision: the speed limit while the navigation fix is missing and the robot drives on dead reckoning alone.",
    readers: "vm (supervision)",
};

/// Every known parameter: Figure 39's ten in its order, then the additions.
pub const PARAMETER_SPECS: &[ParamSpec] = &[
    MAX_TIME_TO_SEARCH,
    DEFAULT_SPEED,
    MAX_SPEED,
    POS_INTERVAL,
    OMAX_CURVATURE,
    CURINC,
    ROBOT_LENGTH,
    ROBOT_WIDTH,
    FOLLOWWALL_D,
    BS_SECURITY,
    MAX_CURVATURE,
    MAX_ACCELERATION,
    MAX_DECELERATION,
    WHEELBASE,
    LOW_BATTERY,
    BATTERY_FULL,
    SCANNER_RANGE,
    SCANNER_RATE,
    ODOMETRY_RATE,
    SCANNER_TIMEOUT,
    ODOMETRY_TIMEOUT,
    NAV_RATE,
    NAV_TIMEOUT,
    DEADRECKONING_RATE,
    MAX_ROLL,
    MAX_PITCH,
    MAX_CLEARANCE,
    STOP_MARGIN,
    LOCALIZATION_JUMP,
    LOCALIZATION_JUMP_H,
    OPERATION_TIMEOUT,
    DEGRADED_SPEED,
];

/// The spec of a known parameter, by case-insensitive name.
pub fn parameter_spec(name: &str) -> Option<&'static ParamSpec> {
    PARAMETER_SPECS
        .iter()
        .find(|s| crate::names::same_name(s.name, name))
}

impl RobotModel {
    /// The model's value of a parameter, or for a known parameter its
    /// documented default. `None` for an unknown name the model lacks and
    /// for a feature the robot does not have (`max_roll` on MoRo).
    pub fn parameter_or_default(&self, name: &str) -> Option<f64> {
        match parameter_spec(name) {
            Some(spec) => self.spec_value(spec),
            None => self.parameter(name),
        }
    }

    fn spec_value(&self, spec: &ParamSpec) -> Option<f64> {
        self.parameter(spec.name).or_else(|| match spec.default {
            ParamDefault::Value(v) => Some(v),
            ParamDefault::SameAs(other) => self.spec_value(other),
            ParamDefault::Absent => None,
        })
    }

    /// Only called with specs whose default is not `Absent` (a unit test
    /// checks each accessor against its spec), so the 0.0 is never seen.
    fn always(&self, spec: &ParamSpec) -> f64 {
        self.spec_value(spec).unwrap_or(0.0)
    }

    /// s; default 10.
    pub fn max_time_to_search(&self) -> f64 {
        self.always(&MAX_TIME_TO_SEARCH)
    }
    /// m/s; default 0.2.
    pub fn default_speed(&self) -> f64 {
        self.always(&DEFAULT_SPEED)
    }
    /// m/s; default 0.6.
    pub fn max_speed(&self) -> f64 {
        self.always(&MAX_SPEED)
    }
    /// m; default 0.5.
    pub fn pos_interval(&self) -> f64 {
        self.always(&POS_INTERVAL)
    }
    /// 1/m; default 0.4. The curvature obstacle avoidance may use; drive
    /// with `min(omax_curvature, max_curvature)`.
    pub fn omax_curvature(&self) -> f64 {
        self.always(&OMAX_CURVATURE)
    }
    /// 1/(m s); default 0.8. The Δc of the position controller.
    pub fn curinc(&self) -> f64 {
        self.always(&CURINC)
    }
    /// m; default 2.2.
    pub fn robot_length(&self) -> f64 {
        self.always(&ROBOT_LENGTH)
    }
    /// m; default 1.0.
    pub fn robot_width(&self) -> f64 {
        self.always(&ROBOT_WIDTH)
    }
    /// m; default 1.0.
    pub fn followwall_d(&self) -> f64 {
        self.always(&FOLLOWWALL_D)
    }
    /// m; default 1.0.
    pub fn bs_security(&self) -> f64 {
        self.always(&BS_SECURITY)
    }
    /// 1/m; default 0.25 (Workpartner).
    pub fn max_curvature(&self) -> f64 {
        self.always(&MAX_CURVATURE)
    }
    /// m/s^2; default 0.3.
    pub fn max_acceleration(&self) -> f64 {
        self.always(&MAX_ACCELERATION)
    }
    /// m/s^2; default 0.5.
    pub fn max_deceleration(&self) -> f64 {
        self.always(&MAX_DECELERATION)
    }
    /// m; default 1.3.
    pub fn wheelbase(&self) -> f64 {
        self.always(&WHEELBASE)
    }
    /// V; default 23.0. The `LowBattery` of Figure 20.
    pub fn low_battery(&self) -> f64 {
        self.always(&LOW_BATTERY)
    }
    /// V; default 25.6.
    pub fn battery_full(&self) -> f64 {
        self.always(&BATTERY_FULL)
    }
    /// m; default 30.
    pub fn scanner_range(&self) -> f64 {
        self.always(&SCANNER_RANGE)
    }
    /// Hz; default 2.
    pub fn scanner_rate(&self) -> f64 {
        self.always(&SCANNER_RATE)
    }
    /// Hz; default 10.
    pub fn odometry_rate(&self) -> f64 {
        self.always(&ODOMETRY_RATE)
    }
    /// s; default 1.5.
    pub fn scanner_timeout(&self) -> f64 {
        self.always(&SCANNER_TIMEOUT)
    }
    /// s; default 0.5.
    pub fn odometry_timeout(&self) -> f64 {
        self.always(&ODOMETRY_TIMEOUT)
    }
    /// Hz; defaults to `odometry_rate()`.
    pub fn deadreckoning_rate(&self) -> f64 {
        self.always(&DEADRECKONING_RATE)
    }
    /// Hz; `None` when the robot has no separate navigation subsystem.
    pub fn nav_rate(&self) -> Option<f64> {
        self.spec_value(&NAV_RATE)
    }
    /// s; `None` when the robot has no separate navigation subsystem.
    pub fn nav_timeout(&self) -> Option<f64> {
        self.spec_value(&NAV_TIMEOUT)
    }
    /// deg; `None` when the robot has no body pose.
    pub fn max_roll(&self) -> Option<f64> {
        self.spec_value(&MAX_ROLL)
    }
    /// deg; `None` when the robot has no body pose.
    pub fn max_pitch(&self) -> Option<f64> {
        self.spec_value(&MAX_PITCH)
    }
    /// m; `None` when the robot has no body pose.
    pub fn max_clearance(&self) -> Option<f64> {
        self.spec_value(&MAX_CLEARANCE)
    }
    /// m; default 0.2.
    pub fn stop_margin(&self) -> f64 {
        self.always(&STOP_MARGIN)
    }
    /// m; default 0.5.
    pub fn localization_jump(&self) -> f64 {
        self.always(&LOCALIZATION_JUMP)
    }
    /// deg; default 20.
    pub fn localization_jump_h(&self) -> f64 {
        self.always(&LOCALIZATION_JUMP_H)
    }
    /// s; default 60.
    pub fn operation_timeout(&self) -> f64 {
        self.always(&OPERATION_TIMEOUT)
    }
    /// m/s; default 0.1.
    pub fn degraded_speed(&self) -> f64 {
        self.always(&DEGRADED_SPEED)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn empty() -> RobotModel {
        RobotModel {
            name: "empty".into(),
            devices: vec![],
            objects: vec![],
            colors: vec![],
            identifiers: vec![],
            parameters: vec![],
            ros2: vec![],
            source: None,
        }
    }

    fn with(name: &str, value: f64) -> RobotModel {
        let mut m = empty();
        m.parameters.push(crate::NamedValue {
            name: name.to_string(),
            value,
            line: 1,
        });
        m
    }

    type Always = fn(&RobotModel) -> f64;
    type Maybe = fn(&RobotModel) -> Option<f64>;

    fn always_accessors() -> Vec<(&'static ParamSpec, Always)> {
        vec![
            (&MAX_TIME_TO_SEARCH, RobotModel::max_time_to_search),
            (&DEFAULT_SPEED, RobotModel::default_speed),
            (&MAX_SPEED, RobotModel::max_speed),
            (&POS_INTERVAL, RobotModel::pos_interval),
            (&OMAX_CURVATURE, RobotModel::omax_curvature),
            (&CURINC, RobotModel::curinc),
            (&ROBOT_LENGTH, RobotModel::robot_length),
            (&ROBOT_WIDTH, RobotModel::robot_width),
            (&FOLLOWWALL_D, RobotModel::followwall_d),
            (&BS_SECURITY, RobotModel::bs_security),
            (&MAX_CURVATURE, RobotModel::max_curvature),
            (&MAX_ACCELERATION, RobotModel::max_acceleration),
            (&MAX_DECELERATION, RobotModel::max_deceleration),
            (&WHEELBASE, RobotModel::wheelbase),
            (&LOW_BATTERY, RobotModel::low_battery),
            (&BATTERY_FULL, RobotModel::battery_full),
            (&SCANNER_RANGE, RobotModel::scanner_range),
            (&SCANNER_RATE, RobotModel::scanner_rate),
            (&ODOMETRY_RATE, RobotModel::odometry_rate),
            (&SCANNER_TIMEOUT, RobotModel::scanner_timeout),
            (&ODOMETRY_TIMEOUT, RobotModel::odometry_timeout),
            (&DEADRECKONING_RATE, RobotModel::deadreckoning_rate),
            (&STOP_MARGIN, RobotModel::stop_margin),
            (&LOCALIZATION_JUMP, RobotModel::localization_jump),
            (&LOCALIZATION_JUMP_H, RobotModel::localization_jump_h),
            (&OPERATION_TIMEOUT, RobotModel::operation_timeout),
            (&DEGRADED_SPEED, RobotModel::degraded_speed),
        ]
    }

    fn maybe_accessors() -> Vec<(&'static ParamSpec, Maybe)> {
        vec![
            (&NAV_RATE, RobotModel::nav_rate),
            (&NAV_TIMEOUT, RobotModel::nav_timeout),
            (&MAX_ROLL, RobotModel::max_roll),
            (&MAX_PITCH, RobotModel::max_pitch),
            (&MAX_CLEARANCE, RobotModel::max_clearance),
        ]
    }

    #[test]
    fn every_spec_has_exactly_one_accessor() {
        let mut covered: Vec<&str> = always_accessors().iter().map(|(s, _)| s.name).collect();
        covered.extend(maybe_accessors().iter().map(|(s, _)| s.name));
        covered.sort_unstable();
        let mut specs: Vec<&str> = PARAMETER_SPECS.iter().map(|s| s.name).collect();
        specs.sort_unstable();
        assert_eq!(covered, specs);
    }

    #[test]
    fn always_accessors_fall_back_to_a_real_default_and_read_the_model() {
        for (spec, get) in always_accessors() {
            let fallback = get(&empty());
            let expected = match spec.default {
                ParamDefault::Value(v) => v,
                ParamDefault::SameAs(other) => match other.default {
                    ParamDefault::Value(v) => v,
                    other => panic!("{}: chained default {other:?}", spec.name),
                },
                ParamDefault::Absent => panic!("{} has no default", spec.name),
            };
            assert_eq!(fallback, expected, "{}", spec.name);
            assert!(spec.valid.admits(expected), "{} default invalid", spec.name);
            // Case-insensitive: the file may write `lowbattery`.
            let set = with(&spec.name.to_uppercase(), 7.25);
            assert_eq!(get(&set), 7.25, "{}", spec.name);
        }
    }

    #[test]
    fn feature_accessors_are_none_unless_defined() {
        for (spec, get) in maybe_accessors() {
            assert_eq!(spec.default, ParamDefault::Absent, "{}", spec.name);
            assert_eq!(get(&empty()), None, "{}", spec.name);
            assert_eq!(get(&with(spec.name, 3.5)), Some(3.5), "{}", spec.name);
        }
    }

    #[test]
    fn deadreckoning_follows_odometry_rate_unless_set() {
        assert_eq!(with("odometry_rate", 20.0).deadreckoning_rate(), 20.0);
        let mut m = with("odometry_rate", 20.0);
        m.parameters.push(crate::NamedValue {
            name: "deadreckoning_rate".into(),
            value: 10.0,
            line: 2,
        });
        assert_eq!(m.deadreckoning_rate(), 10.0);
    }

    #[test]
    fn parameter_or_default_covers_known_and_user_parameters() {
        let m = with("my_gain", 2.0);
        assert_eq!(m.parameter_or_default("MY_GAIN"), Some(2.0));
        assert_eq!(m.parameter_or_default("max_speed"), Some(0.6));
        assert_eq!(m.parameter("max_speed"), None);
        assert_eq!(m.parameter_or_default("max_roll"), None);
        assert_eq!(m.parameter_or_default("nonsense"), None);
    }

    #[test]
    fn ranges_admit_and_reject() {
        assert!(Valid::PositiveAtMost(1.0).admits(0.1) && !Valid::PositiveAtMost(1.0).admits(0.0));
        for v in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert!(!Valid::PositiveAtMost(1.0).admits(v) && !Valid::Between(0.0, 1.0).admits(v));
        }
        assert!(Valid::PositiveAtMost(100.0).admits(100.0));
        assert!(!Valid::PositiveAtMost(100.0).admits(100.5));
        assert!(Valid::Between(0.0, 90.0).admits(0.0) && !Valid::Between(0.0, 90.0).admits(-1.0));
    }
}

//! Tunables of the VM. The defaults are MoRo-like; a robot model overrides the
//! physical ones.

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TraceLevel {
    /// No events (benchmarks).
    Off,
    /// Everything except pose samples.
    Commands,
    /// Everything.
    Full,
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
    /// The robot's largest curvature, 1/m: the controller never asks for more.
    pub max_curvature: f64,
    /// Curvature of `turn(left)` and `turn(right)`, 1/m.
    pub turn_curvature: f64,
    /// Look-ahead of the path tracker, metres.
    pub lookahead: f64,
    /// Planned deceleration towards a goal, m/s^2.
    pub deceleration: f64,
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
            turn_curvature: 0.5,
            lookahead: 0.5,
            deceleration: 0.5,
            goal_tolerance: 0.02,
            pose_every: 10,
            sensor_timeout: 1.0,
            max_call_depth: 64,
            record_spacing: 0.1,
            trace: TraceLevel::Full,
        }
    }
}

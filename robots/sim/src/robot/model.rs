//! Building a simulator configuration from a ROBO.INI robot model: the
//! physical defaults of `RobotConfig::moro()` / `workpartner()` overridden by
//! every figure the model gives (speeds, accelerations, curvature, curinc,
//! dimensions, wheelbase, sensor rates and ranges).

use crate::config::{RobotConfig, RobotKind, Steering};
use ilmr_model::RobotModel;

/// The simulated robot for `model`: `kind` picks the body and sensors the
/// model cannot describe (steering geometry, noise, battery chemistry).
pub fn config_from_model(model: &RobotModel, kind: RobotKind) -> RobotConfig {
    let mut cfg = RobotConfig::for_kind(kind);
    let l = &mut cfg.limits;
    l.max_speed = model.max_speed();
    l.max_accel = model.max_acceleration();
    l.max_decel = model.max_deceleration();
    l.max_curvature = model.max_curvature();
    l.curinc = model.curinc();
    let b = &mut cfg.body;
    // The reference point keeps its place relative to the front.
    let front = b.length - b.rear_overhang;
    b.length = model.robot_length();
    b.width = model.robot_width();
    b.rear_overhang = (b.length - front).max(0.0);
    match &mut cfg.steering {
        Steering::FrontWheel { wheelbase, .. } => *wheelbase = model.wheelbase(),
        Steering::Articulated { half_length, .. } => *half_length = model.wheelbase() / 2.0,
    }
    // The model owns the voltages the task compares against `LowBattery`; the
    // simulated chemistry keeps its discharge depth (empty over full).
    let bat = &mut cfg.battery;
    let depth = bat.v_empty / bat.v_full;
    bat.v_full = model.battery_full();
    bat.v_empty = bat.v_full * depth;
    cfg.scanner.rate_hz = model.scanner_rate();
    cfg.scanner.max_range = model.scanner_range();
    if let Some(scanner) = model.device("scanner") {
        cfg.scanner.readings = scanner.readings as usize;
    }
    if let Some(nav) = &mut cfg.nav {
        if let Some(rate) = model.nav_rate() {
            nav.fix_rate_hz = rate;
        }
        nav.dead_reckoning_hz = model.deadreckoning_rate();
    }
    cfg
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_empty_battery_is_below_low_battery_on_both_robots() {
        for (name, kind) in [
            ("moro", RobotKind::Moro),
            ("workpartner", RobotKind::Workpartner),
        ] {
            let model = RobotModel::builtin(name).unwrap_or_else(|| unreachable!("{name} ships"));
            let cfg = config_from_model(&model, kind);
            assert_eq!(cfg.battery.v_full, model.battery_full());
            assert!(cfg.battery.v_empty < model.low_battery(), "{name}");
        }
    }
}

//! Battery: charge drains with an idle load, rolling resistance and
//! acceleration; voltage falls linearly from full to empty with the charge.

use crate::config::BatteryConfig;
use serde::Serialize;

const G: f64 = 9.81;

#[derive(Debug, Clone, PartialEq)]
pub struct Battery {
    /// State of charge, 0..1.
    pub charge: f64,
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BatteryReading {
    pub voltage: f64,
    /// State of charge, 0..1.
    pub charge: f64,
    pub charging: bool,
}

/// What the drive did over one step, for the power it drew.
pub struct Load {
    pub speed: f64,
    pub accel: f64,
    pub mass: f64,
    pub rolling_factor: f64,
    pub charging: bool,
}

impl Battery {
    pub fn full() -> Self {
        Battery { charge: 1.0 }
    }

    /// Power drawn, W: idle + rolling resistance + the kinetic energy put in
    /// (braking returns nothing).
    pub fn power(cfg: &BatteryConfig, l: &Load) -> f64 {
        let rolling = l.mass * G * cfg.rolling_resistance * l.rolling_factor * l.speed.abs();
        let kinetic = (l.mass * l.accel * l.speed).max(0.0);
        let charging = if l.charging { cfg.charge_w } else { 0.0 };
        cfg.idle_w + rolling + kinetic - charging
    }

    pub fn update(&mut self, cfg: &BatteryConfig, l: &Load, dt: f64) {
        let used_wh = Self::power(cfg, l) * dt / 3600.0;
        self.charge = (self.charge - used_wh / cfg.capacity_wh).clamp(0.0, 1.0);
    }

    pub fn voltage(&self, cfg: &BatteryConfig) -> f64 {
        cfg.v_empty + (cfg.v_full - cfg.v_empty) * self.charge
    }
}

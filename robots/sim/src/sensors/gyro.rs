//! MoRo's fibre-optic gyro: the true turn plus a slowly wandering bias and
//! white rate noise, integrated into a heading.

use crate::config::GyroConfig;
use crate::geometry::wrap_angle;
use crate::rng::Rng;
use serde::Serialize;

#[derive(Debug, Clone, PartialEq)]
pub struct Gyro {
    bias: f64,
    /// Unwrapped integrated angle, rad.
    angle: f64,
    rate: f64,
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct GyroReading {
    /// Integrated heading since start, rad in (-pi, pi].
    pub heading: f64,
    /// Measured turn rate, rad/s.
    pub rate: f64,
}

impl Gyro {
    /// A gyro switched on with `turn_on_bias` added to its configured bias.
    pub fn new(cfg: &GyroConfig, turn_on_bias: f64) -> Self {
        Gyro {
            bias: cfg.bias + turn_on_bias,
            angle: 0.0,
            rate: 0.0,
        }
    }

    /// Integrates one step in which the robot truly turned `dh`; returns the
    /// measured turn.
    pub fn update(&mut self, cfg: &GyroConfig, dh: f64, dt: f64, rng: &mut Rng) -> f64 {
        self.bias += rng.gauss(cfg.bias_walk * dt.sqrt());
        let measured = dh + self.bias * dt + rng.gauss(cfg.noise * dt.sqrt());
        self.angle += measured;
        self.rate = measured / dt;
        measured
    }

    pub fn reading(&self) -> GyroReading {
        GyroReading {
            heading: wrap_angle(self.angle),
            rate: self.rate,
        }
    }
}

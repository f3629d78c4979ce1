//! Wheel pulse counters. Counts are cumulative integers, so quantisation never
//! accumulates; only slip and scale errors make the estimate drift.

use crate::config::OdometryConfig;
use crate::kinematics::WheelTravel;
use serde::Serialize;

#[derive(Debug, Clone, PartialEq, Default)]
pub struct Odometry {
    /// Metres each wheel's counter has seen, scale errors included.
    seen: [f64; 4],
    pulses: [i64; 4],
    count: usize,
    side: [i8; 4],
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct OdometryReading {
    /// Cumulative signed pulse counts per wheel (MoRo: front, rear left,
    /// rear right; Workpartner: legs 0-3).
    pub pulses: Vec<i64>,
    pub metres_per_pulse: f64,
    /// Distance travelled by the reference point as the wheels count it, m.
    pub distance: f64,
}

impl Odometry {
    /// Counts the wheels' rolling; `extra_scale` is a fault added to both sides.
    pub fn update(&mut self, t: &WheelTravel, cfg: &OdometryConfig, extra_scale: f64) {
        self.count = t.count;
        self.side = t.side;
        for i in 0..t.count {
            let err = match t.side[i] {
                -1 => cfg.left_scale_error,
                1 => cfg.right_scale_error,
                _ => (cfg.left_scale_error + cfg.right_scale_error) / 2.0,
            };
            self.seen[i] += t.wheels[i] * (1.0 + err + extra_scale);
            self.pulses[i] = (self.seen[i] / cfg.metres_per_pulse).floor() as i64;
        }
    }

    pub fn pulses(&self) -> [i64; 4] {
        self.pulses
    }

    /// Mean pulse count of the side wheels, whose average is the reference
    /// point's travel (the steered front wheel runs a longer circle).
    pub fn side_mean(pulses: &[i64; 4], side: &[i8; 4], count: usize) -> f64 {
        let picked: Vec<f64> = (0..count)
            .filter(|&i| side[i] != 0)
            .map(|i| pulses[i] as f64)
            .collect();
        picked.iter().sum::<f64>() / picked.len().max(1) as f64
    }

    pub fn side(&self) -> [i8; 4] {
        self.side
    }

    pub fn count(&self) -> usize {
        self.count
    }

    pub fn reading(&self, cfg: &OdometryConfig) -> OdometryReading {
        OdometryReading {
            pulses: self.pulses[..self.count].to_vec(),
            metres_per_pulse: cfg.metres_per_pulse,
            distance: Self::side_mean(&self.pulses, &self.side, self.count) * cfg.metres_per_pulse,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::Steering;
    use crate::kinematics::wheel_travel;

    #[test]
    fn pulses_count_travel_with_scale_error() {
        let cfg = OdometryConfig {
            metres_per_pulse: 0.001,
            left_scale_error: 0.02,
            right_scale_error: 0.0,
            scale_sigma: 0.0,
            track_sigma: 0.0,
        };
        let s = Steering::Articulated {
            half_length: 0.6,
            track: 1.0,
        };
        let mut o = Odometry::default();
        for _ in 0..1000 {
            o.update(&wheel_travel(&s, 0.001, 0.0), &cfg, 0.0);
        }
        let p = o.pulses();
        assert!((p[0] - 1020).abs() <= 1, "{p:?}");
        assert!((p[1] - 1000).abs() <= 1, "{p:?}");
        let r = o.reading(&cfg);
        assert_eq!(r.pulses.len(), 4);
        assert!((r.distance - 1.01).abs() < 0.002);
    }
}

//! The robots' sensors. Each takes the true state and returns what the robot
//! would read, with noise from its own seeded stream.

mod battery;
mod camera;
mod gyro;
mod nav;
mod odometry;
mod plates;
mod scanner;
mod ultrasonic;

pub use battery::{Battery, BatteryReading, Load};
pub use camera::{CameraFrame, Detection, Head, Visible, observe};
pub use gyro::{Gyro, GyroReading};
pub use nav::{DeadReckoning, NavFix};
pub use odometry::{Odometry, OdometryReading};
pub use plates::{PlateEvent, crossings, quantise};
pub use scanner::{SKEW_PARTS, Scan, ScanNoise, ScanPose, add_artefacts, cast_scan, cast_skewed};
pub use ultrasonic::{UltrasonicReading, measure_ultrasonic};

/// Fires every `period_us` of simulated time, first at time 0.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Periodic {
    period_us: u64,
    next_us: u64,
}

impl Periodic {
    pub fn from_hz(hz: f64) -> Self {
        Periodic {
            period_us: ((1.0e6 / hz).round() as u64).max(1),
            next_us: 0,
        }
    }

    /// Whether a reading is due at `now_us`; a caller stepping slower than the
    /// rate gets one reading per step, not a burst of stale ones.
    pub fn due(&mut self, now_us: u64) -> bool {
        if now_us < self.next_us {
            return false;
        }
        self.next_us += self.period_us;
        if self.next_us <= now_us {
            self.next_us = now_us + self.period_us;
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn periodic_fires_on_schedule() {
        let mut p = Periodic::from_hz(4.0);
        let fired: Vec<u64> = (0..=100u64)
            .map(|k| k * 10_000)
            .filter(|&t| p.due(t))
            .collect();
        assert_eq!(fired, vec![0, 250_000, 500_000, 750_000, 1_000_000]);
        // A slow caller gets one reading per call.
        let mut p = Periodic::from_hz(10.0);
        assert!(p.due(0));
        assert!(p.due(1_000_000));
        assert!(!p.due(1_050_000));
        assert!(p.due(1_100_000));
    }
}

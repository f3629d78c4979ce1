//! Workpartner's body pose: roll, pitch and road clearance chase their
//! setpoints at limited rates (`bodypose(r=..,p=..,rc=..)`).

use serde::{Deserialize, Serialize};

/// Roll and pitch in radians within +/-30 degrees; clearance in metres, 0-1.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct BodyPose {
    pub roll: f64,
    pub pitch: f64,
    pub clearance: f64,
}

impl BodyPose {
    pub const MAX_ANGLE: f64 = 30.0 * std::f64::consts::PI / 180.0;
    pub const MAX_CLEARANCE: f64 = 1.0;

    /// An error naming the first setting out of range.
    pub fn check(&self) -> Result<(), String> {
        let a = Self::MAX_ANGLE;
        if !(self.roll.is_finite() && self.roll.abs() <= a + 1e-12) {
            return Err(format!(
                "roll {:.1} deg is outside -30..30 deg",
                self.roll.to_degrees()
            ));
        }
        if !(self.pitch.is_finite() && self.pitch.abs() <= a + 1e-12) {
            return Err(format!(
                "pitch {:.1} deg is outside -30..30 deg",
                self.pitch.to_degrees()
            ));
        }
        if !(self.clearance.is_finite() && (0.0..=Self::MAX_CLEARANCE).contains(&self.clearance)) {
            return Err(format!(
                "road clearance {} m is outside 0..1 m",
                self.clearance
            ));
        }
        Ok(())
    }

    /// One step toward `target` at `angle_rate` rad/s and `clearance_rate` m/s.
    pub fn toward(
        self,
        target: BodyPose,
        angle_rate: f64,
        clearance_rate: f64,
        dt: f64,
    ) -> BodyPose {
        fn go(from: f64, to: f64, step: f64) -> f64 {
            if to > from {
                (from + step).min(to)
            } else {
                (from - step).max(to)
            }
        }
        BodyPose {
            roll: go(self.roll, target.roll, angle_rate * dt),
            pitch: go(self.pitch, target.pitch, angle_rate * dt),
            clearance: go(self.clearance, target.clearance, clearance_rate * dt),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn moves_at_limited_rate_and_checks_ranges() {
        let target = BodyPose {
            roll: 0.2,
            pitch: -0.1,
            clearance: 0.8,
        };
        let p = BodyPose {
            roll: 0.0,
            pitch: 0.0,
            clearance: 0.5,
        }
        .toward(target, 0.1, 0.1, 0.5);
        assert!((p.roll - 0.05).abs() < 1e-12);
        assert!((p.pitch + 0.05).abs() < 1e-12);
        assert!((p.clearance - 0.55).abs() < 1e-12);
        assert!(target.check().is_ok());
        assert!(
            BodyPose {
                roll: 0.6,
                ..target
            }
            .check()
            .is_err()
        );
        assert!(
            BodyPose {
                clearance: 1.2,
                ..target
            }
            .check()
            .is_err()
        );
    }
}

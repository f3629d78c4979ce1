//! Steering geometry of the two robots: the steer or articulation angle behind
//! a curvature, the distance each wheel rolls, and Workpartner's movement modes.

use crate::config::Steering;
use serde::{Deserialize, Serialize};

/// Workpartner's movement modes (section 5.1, `movemode`).
///
/// - `Wheels`: legs locked, an ordinary wheeled vehicle; normal slip.
/// - `Rolking`: the legs slide along the ground. The top speed drops to
///   `rolking.speed_factor` of `max_speed`, slip is drawn from `rolking.slip`
///   (mean 8 % by default, against 1 % on wheels) so dead reckoning overshoots
///   and heading wanders, and rolling power rises by `rolking.power_factor`.
/// - `Parking`: all joints locked. The robot brakes to a standstill at
///   `max_decel` and then ignores speed setpoints until the mode changes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum MovementMode {
    #[default]
    Wheels,
    Rolking,
    Parking,
}

/// Signed distance each wheel rolled. MoRo: front, rear left, rear right.
/// Workpartner: legs 0-3 = front left, front right, rear left, rear right,
/// the numbering under which equation (1) turns left when leg 1 outruns leg 0.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct WheelTravel {
    pub wheels: [f64; 4],
    pub count: usize,
    /// Which wheels are on the left (-1), right (+1), or the middle (0).
    pub side: [i8; 4],
}

/// MoRo's front-wheel steer angle, or Workpartner's articulation angle, in
/// radians, for the reference point's curvature `c`.
pub fn steering_angle(steering: &Steering, c: f64) -> f64 {
    match *steering {
        Steering::FrontWheel { wheelbase, .. } => (c * wheelbase).atan(),
        // Equal halves: both axles lie on one circle about the turn centre,
        // each at half the joint angle from the radius through the joint.
        Steering::Articulated { half_length, .. } => 2.0 * (c * half_length).atan(),
    }
}

/// The curvature of the reference point behind a steer (articulation) angle:
/// the inverse of [`steering_angle`].
pub fn curvature_for_angle(steering: &Steering, angle: f64) -> f64 {
    match *steering {
        Steering::FrontWheel { wheelbase, .. } => angle.tan() / wheelbase,
        Steering::Articulated { half_length, .. } => (angle / 2.0).tan() / half_length,
    }
}

/// Distances rolled by each wheel when the reference point rolls `ds` on
/// curvature `c`.
pub fn wheel_travel(steering: &Steering, ds: f64, c: f64) -> WheelTravel {
    match *steering {
        Steering::FrontWheel {
            wheelbase,
            rear_track,
        } => {
            let half = rear_track / 2.0;
            WheelTravel {
                // The front wheel runs on the circle through the front axle,
                // of radius hypot(R, wheelbase).
                wheels: [
                    ds * (1.0 + (c * wheelbase).powi(2)).sqrt(),
                    ds * (1.0 - c * half),
                    ds * (1.0 + c * half),
                    0.0,
                ],
                count: 3,
                side: [0, -1, 1, 0],
            }
        }
        Steering::Articulated { track, .. } => {
            let left = ds * (1.0 - c * track / 2.0);
            let right = ds * (1.0 + c * track / 2.0);
            WheelTravel {
                wheels: [left, right, left, right],
                count: 4,
                side: [-1, 1, -1, 1],
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn moro_full_lock_angle_and_wheels() {
        let s = Steering::FrontWheel {
            wheelbase: 0.8,
            rear_track: 0.5,
        };
        let c = 1.0 / 0.75;
        assert!((steering_angle(&s, c).to_degrees() - 46.85).abs() < 0.01);
        let w = wheel_travel(&s, 1.0, c);
        // Inner rear wheel on radius 0.5, outer on 1.0, front on hypot(0.75, 0.8).
        assert!((w.wheels[1] - 0.5 / 0.75).abs() < 1e-12);
        assert!((w.wheels[2] - 1.0 / 0.75).abs() < 1e-12);
        assert!((w.wheels[0] - 0.75_f64.hypot(0.8) / 0.75).abs() < 1e-12);
    }

    #[test]
    fn articulated_wheels_differ_by_track_times_turn() {
        let s = Steering::Articulated {
            half_length: 0.6,
            track: 1.0,
        };
        let w = wheel_travel(&s, 2.0, 0.25);
        assert!((w.wheels[1] - w.wheels[0] - 2.0 * 0.25).abs() < 1e-12);
        assert_eq!(w.wheels[0], w.wheels[2]);
        assert!((steering_angle(&s, 0.25).to_degrees() - 17.06).abs() < 0.01);
    }

    #[test]
    fn curvature_for_angle_inverts_steering_angle() {
        for s in [
            Steering::FrontWheel {
                wheelbase: 0.8,
                rear_track: 0.5,
            },
            Steering::Articulated {
                half_length: 0.6,
                track: 1.0,
            },
        ] {
            for c in [-1.2, -0.25, 0.0, 0.4, 1.0] {
                let back = curvature_for_angle(&s, steering_angle(&s, c));
                assert!((back - c).abs() < 1e-12, "{s:?} {c} {back}");
            }
        }
    }
}

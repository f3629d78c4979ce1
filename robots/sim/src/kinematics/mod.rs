//! Vehicle motion: actuator lag (speed and curvature chase their setpoints
//! within the limits), exact arc integration, and per-robot steering geometry.

mod body_pose;
mod delay;
mod steering;

pub use body_pose::BodyPose;
pub use delay::{SetpointHistory, backlash};
pub use steering::{MovementMode, WheelTravel, curvature_for_angle, steering_angle, wheel_travel};

use crate::config::DriveLimits;
use crate::geometry::Pose;

/// One step of the speed actuator. Speeding up is limited by `max_accel`,
/// slowing down by `max_decel`; a reversal first brakes to a standstill, so
/// the speed never jumps across zero in one step.
pub fn next_speed(v: f64, v_set: f64, limits: &DriveLimits, dt: f64) -> f64 {
    let target = v_set.clamp(-limits.max_speed, limits.max_speed);
    let reversing = v != 0.0 && target != 0.0 && v.signum() != target.signum();
    if reversing {
        let braked = v.abs() - limits.max_decel * dt;
        return if braked > 0.0 {
            braked * v.signum()
        } else {
            0.0
        };
    }
    if target.abs() > v.abs() {
        let up = limits.max_accel * dt;
        if target > v {
            (v + up).min(target)
        } else {
            (v - up).max(target)
        }
    } else {
        let down = limits.max_decel * dt;
        if target > v {
            (v + down).min(target)
        } else {
            (v - down).max(target)
        }
    }
}

/// One step of the steering actuator, limited by `curinc`.
pub fn next_curvature(c: f64, c_set: f64, limits: &DriveLimits, dt: f64) -> f64 {
    let target = c_set.clamp(-limits.max_curvature, limits.max_curvature);
    let step = limits.curinc * dt;
    if target > c {
        (c + step).min(target)
    } else {
        (c - step).max(target)
    }
}

/// sin(x)/x, exact at 0.
fn sinc(x: f64) -> f64 {
    if x.abs() < 1e-4 {
        1.0 - x * x / 6.0
    } else {
        x.sin() / x
    }
}

/// Moves a pose `ds` metres along an arc that turns it by `dh` radians. Exact
/// for a constant curvature over the step, so step size does not bend paths.
pub fn advance(p: Pose, ds: f64, dh: f64) -> Pose {
    let chord = ds * sinc(dh / 2.0);
    let mid = p.h + dh / 2.0;
    Pose::new(p.x + chord * mid.cos(), p.y + chord * mid.sin(), p.h + dh)
}

/// `p` moved `lateral` metres to its left (negative: right), the side slip of a
/// step whose heading changed by `dh`, taken across the step's mean heading.
pub fn slide(p: Pose, lateral: f64, dh: f64) -> Pose {
    if lateral == 0.0 {
        return p;
    }
    let across = p.h - dh / 2.0 + std::f64::consts::FRAC_PI_2;
    Pose::new(
        p.x + lateral * across.cos(),
        p.y + lateral * across.sin(),
        p.h,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn limits() -> DriveLimits {
        DriveLimits {
            max_speed: 1.0,
            max_accel: 0.5,
            max_decel: 1.0,
            max_curvature: 1.0,
            curinc: 0.8,
        }
    }

    #[test]
    fn speed_respects_acceleration_deceleration_and_stops_before_reversing() {
        let l = limits();
        let dt = 0.01;
        let mut v = 0.0;
        for _ in 0..10 {
            let n = next_speed(v, 1.0, &l, dt);
            assert!((n - v - 0.005).abs() < 1e-12);
            v = n;
        }
        v = 0.5;
        let n = next_speed(v, 0.0, &l, dt);
        assert!((v - n - 0.01).abs() < 1e-12);
        // Reversal: brakes to exactly zero, never past it in one step.
        assert_eq!(next_speed(0.005, -1.0, &l, dt), 0.0);
        assert!((next_speed(0.0, -1.0, &l, dt) + 0.005).abs() < 1e-12);
        // Setpoints beyond the top speed saturate.
        assert_eq!(next_speed(0.999, 5.0, &l, dt), 1.0);
    }

    #[test]
    fn curvature_rate_and_saturation() {
        let l = limits();
        assert!((next_curvature(0.0, 1.0, &l, 0.01) - 0.008).abs() < 1e-12);
        assert!((next_curvature(0.995, 3.0, &l, 0.01) - 1.0).abs() < 1e-12);
        assert!((next_curvature(0.0, -0.004, &l, 0.01) + 0.004).abs() < 1e-12);
    }

    #[test]
    fn advance_follows_the_arc_exactly() {
        // A quarter circle of radius 2 in one step lands at (2, 2) facing +y.
        let p = advance(Pose::new(0.0, 0.0, 0.0), PI, PI / 2.0);
        assert!((p.x - 2.0).abs() < 1e-12 && (p.y - 2.0).abs() < 1e-12);
        assert!((p.h - PI / 2.0).abs() < 1e-12);
        let s = advance(Pose::new(1.0, 1.0, PI), 2.0, 0.0);
        assert!((s.x + 1.0).abs() < 1e-12 && (s.y - 1.0).abs() < 1e-12);
    }
}

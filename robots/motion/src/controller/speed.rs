//! Speed profile: accelerate and brake within the robot's limits so that it
//! stands still where the path ends, at a cusp, or `advancestop(d)` metres
//! early, and drives straight on when the next command is linked.

use crate::path::{LINK_REMAINING, Path};
use crate::pose::Pose;
use serde::{Deserialize, Serialize};

#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct SpeedLimits {
    /// m/s^2, positive.
    pub max_accel: f64,
    /// m/s^2, positive.
    pub max_decel: f64,
}

/// Distance needed to stop from `speed` at `decel`.
pub fn braking_distance(speed: f64, decel: f64) -> f64 {
    if decel > 0.0 {
        speed * speed / (2.0 * decel)
    } else {
        f64::INFINITY
    }
}

/// Remaining length at which a queued command must be linked: the
/// dissertation's 0.5 m, or more when the robot is fast enough that braking
/// for the end would already have begun (which would dip the speed).
pub fn link_distance(speed: f64, limits: &SpeedLimits, dt: f64) -> f64 {
    LINK_REMAINING.max(braking_distance(speed.abs(), limits.max_decel) + speed.abs() * dt.max(0.0))
}

/// Where, from reference point `k`, the robot has to stand still, or None
/// when it drives on. A cusp always stops the robot; the path's end does
/// unless the next command is `linked`, and `advance_stop` moves it closer.
pub fn stop_in(path: &Path, k: usize, pose: &Pose, advance_stop: f64, linked: bool) -> Option<f64> {
    let p = pose.position();
    let to_stop = path.distance_to_stop_from(k, Some(&p));
    let to_end = path.remaining_from(k, &p);
    if to_stop < to_end - 1e-9 {
        Some(to_stop)
    } else if linked {
        None
    } else {
        Some((to_end - advance_stop.max(0.0)).max(0.0))
    }
}

/// True when a movement command following `path` has done its job: the
/// robot is past the end, or within `advance_stop` (plus `tolerance`) of it.
/// "Past the end" counts only on the path's last `PASSED_WINDOW` metres: a
/// path that comes back (a taught loop round a bench) starts beyond the
/// line through its own end.
pub fn has_arrived(path: &Path, k: usize, pose: &Pose, advance_stop: f64, tolerance: f64) -> bool {
    let k = path.clamp_index(k);
    let p = pose.position();
    let last_leg = path.distance_to_stop(k) >= path.remaining(k) - 1e-9;
    let near_end = path.remaining(k) <= PASSED_WINDOW;
    last_leg
        && (path.remaining_from(k, &p) <= advance_stop.max(0.0) + tolerance
            || (advance_stop <= 0.0 && near_end && path.passed_end(&p)))
}

/// See `has_arrived`, m: more than the robot's reference index lags behind
/// its position in a cycle, less than any loop a robot can drive.
pub const PASSED_WINDOW: f64 = 0.5;

/// Next speed magnitude after `dt`: towards `target` within the limits, and
/// never faster than lets the robot stop in `stop_in` metres.
pub fn next_speed(
    current: f64,
    target: f64,
    stop_in: Option<f64>,
    limits: &SpeedLimits,
    dt: f64,
) -> f64 {
    let current = current.abs();
    let dt = dt.max(0.0);
    let up = current + limits.max_accel.max(0.0) * dt;
    let down = (current - limits.max_decel.max(0.0) * dt).max(0.0);
    let mut v = target.abs().clamp(down, up.max(down));
    if let Some(d) = stop_in {
        let d = d.max(0.0);
        // sqrt(2 a d) is the braking curve; d/dt stops the last step from
        // driving past the stop point. When the stop point moves closer than
        // the braking distance (a late advancestop) stopping there wins over
        // the deceleration limit.
        let cap = (2.0 * limits.max_decel.max(0.0) * d).sqrt();
        let cap = if dt > 0.0 { cap.min(d / dt) } else { cap };
        v = v.min(cap);
    }
    if v.is_finite() { v } else { 0.0 }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::path::straight;

    const LIM: SpeedLimits = SpeedLimits {
        max_accel: 0.5,
        max_decel: 0.5,
    };

    #[test]
    fn a_path_that_comes_back_has_not_arrived_at_its_start() {
        // Out 4 m, round and 2 m back: the start lies beyond the end's line.
        let wp = [
            nalgebra::Point2::new(0.0, 0.0),
            nalgebra::Point2::new(4.0, 0.0),
            nalgebra::Point2::new(4.0, 3.0),
            nalgebra::Point2::new(2.0, 3.0),
        ];
        let path = crate::path::polyline(&wp, 1.33, crate::path::Direction::Forward, 0.05)
            .expect("drivable");
        let start = Pose::new(0.0, 0.0, 0.0);
        assert!(path.passed_end(&start.position()));
        assert!(!has_arrived(&path, 0, &start, 0.0, 0.02));
        let last = path.points().len() - 1;
        let beyond = Pose::new(1.9, 3.0, std::f64::consts::PI);
        assert!(has_arrived(&path, last, &beyond, 0.0, 0.02));
    }

    /// Drives a point mass along a straight with the profile.
    fn run(length: f64, target: f64, advance: f64, linked: bool) -> (f64, f64, Vec<f64>) {
        let path = straight(Pose::new(0.0, 0.0, 0.0), length, 0.01).expect("valid");
        let dt = 0.01;
        let (mut x, mut v) = (0.0f64, 0.0f64);
        let mut speeds = vec![];
        for _ in 0..10_000 {
            let k = path.closest_index(&nalgebra::Point2::new(x, 0.0), 0, 10.0);
            if has_arrived(&path, k, &Pose::new(x, 0.0, 0.0), advance, 0.005) {
                break;
            }
            let here = Pose::new(x, 0.0, 0.0);
            v = next_speed(
                v,
                target,
                stop_in(&path, k, &here, advance, linked),
                &LIM,
                dt,
            );
            x += v * dt;
            speeds.push(v);
        }
        (x, v, speeds)
    }

    #[test]
    fn accelerates_cruises_and_stops_at_the_end() {
        let (x, v, speeds) = run(2.0, 0.4, 0.0, false);
        assert!((x - 2.0).abs() < 0.02, "stopped at {x}");
        // Arrival is declared within 5 mm; the last speed was set one step
        // earlier, up to v * dt further out, where the braking curve allows
        // sqrt(2 * 0.5 * (0.005 + 0.08 * 0.01)) m/s.
        assert!(v <= (2.0f64 * 0.5 * 0.0058).sqrt(), "arrived at {v} m/s");
        let peak = speeds.iter().cloned().fold(0.0, f64::max);
        assert!((peak - 0.4).abs() < 1e-9);
        let jumps = speeds
            .windows(2)
            .map(|w| (w[1] - w[0]).abs())
            .fold(0.0, f64::max);
        assert!(jumps <= 0.5 * 0.01 + 0.01, "speed jump {jumps}");
    }

    #[test]
    fn advancestop_stops_early() {
        let (x, _, _) = run(3.0, 0.4, 1.0, false);
        assert!((x - 2.0).abs() < 0.02, "stopped at {x}");
    }

    #[test]
    fn linked_end_is_driven_through_at_speed() {
        let path = straight(Pose::new(0.0, 0.0, 0.0), 1.0, 0.05).expect("valid");
        let at = Pose::new(0.5, 0.0, 0.0);
        assert_eq!(stop_in(&path, 10, &at, 0.0, true), None);
        assert!((stop_in(&path, 10, &at, 0.0, false).expect("stops") - 0.5).abs() < 1e-9);
        assert!((next_speed(0.4, 0.4, None, &LIM, 0.01) - 0.4).abs() < 1e-12);
    }

    #[test]
    fn link_distance_covers_braking() {
        assert_eq!(link_distance(0.4, &LIM, 0.01), LINK_REMAINING);
        assert!(link_distance(1.0, &LIM, 0.01) > braking_distance(1.0, 0.5));
    }
}

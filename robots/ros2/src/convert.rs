//! ROS 2's conventions to the HAL's and back: REP 103 units (metres, radians, counter-
//! clockwise, x forward) are the HAL's too, so what changes is the shape of things
//! (a twist for a speed and a curvature, a quaternion for a heading) and what a scan
//! says about beams that found nothing (REP 117).

use ilmr_hal::{Pose, Scan};
use ilmr_model::RobotModel;

use crate::msg::{LaserScan, Odometry, Twist, Vector3};

/// What `cmd_vel` may ask of the robot: the model's limits, the one source of them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits {
    /// m/s, either way.
    pub max_speed: f64,
    /// 1/m, either way.
    pub max_curvature: f64,
}

impl Limits {
    pub fn of(model: &RobotModel) -> Limits {
        Limits {
            max_speed: model.max_speed(),
            max_curvature: model.max_curvature(),
        }
    }
}

/// The `cmd_vel` for a speed setpoint (m/s, negative reversing) and a curvature (1/m,
/// positive turning left): `linear.x` is the speed and `angular.z` the speed times the
/// curvature, each within the model's limits. A value that is not a number asks the
/// robot to stand still: a driver must never get NaN.
pub fn cmd_vel(speed: f64, curvature: f64, limits: Limits) -> Twist {
    if !speed.is_finite() || !curvature.is_finite() {
        return Twist::default();
    }
    let v = speed.clamp(-limits.max_speed, limits.max_speed);
    let k = curvature.clamp(-limits.max_curvature, limits.max_curvature);
    Twist {
        linear: Vector3 {
            x: v,
            ..Vector3::default()
        },
        angular: Vector3 {
            z: v * k,
            ..Vector3::default()
        },
    }
}

/// What odometry tells the HAL: the pose in the odometry frame, the speed along x and
/// the curvature driven (0 at rest, where a turn on the spot has none), and the time of
/// the sample, seconds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Motion {
    pub pose: Pose,
    pub speed: f64,
    pub curvature: f64,
    pub t: f64,
}

/// Below this speed, m/s, the curvature of a twist is not taken as meaningful.
const AT_REST: f64 = 1e-3;

/// The motion in an odometry sample, or `None` for one that holds a value that is not
/// a number (a driver's glitch must not become the robot's pose).
pub fn motion(odometry: &Odometry) -> Option<Motion> {
    let p = &odometry.pose.pose;
    let twist = &odometry.twist.twist;
    let pose = Pose {
        x: p.position.x,
        y: p.position.y,
        h: p.orientation.yaw(),
    };
    let speed = twist.linear.x;
    let curvature = if speed.abs() < AT_REST {
        0.0
    } else {
        twist.angular.z / speed
    };
    let all = [pose.x, pose.y, pose.h, speed, curvature];
    all.iter().all(|v| v.is_finite()).then_some(Motion {
        pose,
        speed,
        curvature,
        t: odometry.header.stamp.as_secs(),
    })
}

/// A ROS scan as the HAL's, for the model's scanner `device`. Per REP 117, `+inf`, NaN
/// and ranges beyond `range_max` found nothing and read `range_max`, as a simulated
/// beam that found nothing reads its maximum range; `-inf` and ranges below
/// `range_min` saw something too close to measure and read `range_min`, so that the
/// supervisor holds the robot rather than drive it into what it could not range.
pub fn scan(message: &LaserScan, device: &str) -> Scan {
    let (near, far) = (
        f64::from(message.range_min).max(0.0),
        f64::from(message.range_max).max(0.0),
    );
    let ranges = message
        .ranges
        .iter()
        .map(|&r| {
            let r = f64::from(r);
            if r.is_nan() || r > far {
                far
            } else if r < near {
                near
            } else {
                r
            }
        })
        .collect();
    Scan {
        device: device.to_string(),
        t: message.header.stamp.as_secs(),
        angle_min: f64::from(message.angle_min),
        angle_step: f64::from(message.angle_increment),
        ranges,
    }
}

/// A battery's voltage, `None` where the message says it was not measured (NaN).
pub fn battery_voltage(voltage: f32) -> Option<f64> {
    let v = f64::from(voltage);
    v.is_finite().then_some(v)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::msg::{Header, Point, Pose as RosPose, PoseWithCovariance, Quaternion, Time};

    fn moro() -> Limits {
        Limits::of(&RobotModel::builtin("moro").unwrap())
    }

    #[test]
    fn cmd_vel_never_exceeds_the_model() {
        let limits = moro();
        let values = [
            -1e308,
            -10.0,
            -0.6,
            -0.1,
            0.0,
            0.1,
            0.6,
            5.0,
            1e308,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
        ];
        for v in values {
            for k in values {
                let t = cmd_vel(v, k, limits);
                let (lin, ang) = (t.linear.x, t.angular.z);
                assert!(lin.is_finite() && ang.is_finite(), "{v} {k}");
                assert!(lin.abs() <= limits.max_speed, "{v} {k}: {lin}");
                assert!(
                    ang.abs() <= limits.max_speed * limits.max_curvature + 1e-12,
                    "{v} {k}: {ang}"
                );
                let rest = [t.linear.y, t.linear.z, t.angular.x, t.angular.y];
                assert!(rest.iter().all(|x| *x == 0.0));
            }
        }
    }

    #[test]
    fn a_setpoint_within_the_limits_is_sent_as_it_is() {
        let t = cmd_vel(0.4, -0.5, moro());
        assert_eq!((t.linear.x, t.angular.z), (0.4, -0.2));
        let back = cmd_vel(-0.2, 1.0, moro());
        // Reversing along a left-hand arc turns the body clockwise.
        assert_eq!((back.linear.x, back.angular.z), (-0.2, -0.2));
    }

    fn odometry(x: f64, yaw: f64, v: f64, w: f64) -> Odometry {
        let mut o = Odometry {
            header: Header {
                stamp: Time {
                    sec: 5,
                    nanosec: 500_000_000,
                },
                frame_id: "odom".into(),
            },
            child_frame_id: "base_link".into(),
            pose: PoseWithCovariance {
                pose: RosPose {
                    position: Point { x, y: 2.0, z: 0.0 },
                    orientation: Quaternion::from_yaw(yaw),
                },
                ..PoseWithCovariance::default()
            },
            ..Odometry::default()
        };
        o.twist.twist.linear.x = v;
        o.twist.twist.angular.z = w;
        o
    }

    #[test]
    fn odometry_gives_the_pose_speed_and_curvature() {
        let m = motion(&odometry(1.0, 0.5, 0.4, 0.2)).unwrap();
        assert_eq!((m.pose.x, m.pose.y), (1.0, 2.0));
        assert!((m.pose.h - 0.5).abs() < 1e-12);
        assert_eq!((m.speed, m.curvature, m.t), (0.4, 0.5, 5.5));
        // Turning on the spot: no curvature to speak of.
        assert_eq!(
            motion(&odometry(0.0, 0.0, 0.0, 0.7)).unwrap().curvature,
            0.0
        );
        assert!(motion(&odometry(f64::NAN, 0.0, 0.0, 0.0)).is_none());
        assert!(motion(&odometry(0.0, 0.0, f64::INFINITY, 0.0)).is_none());
    }

    #[test]
    fn beams_that_found_nothing_read_the_maximum_and_too_close_the_minimum() {
        let message = LaserScan {
            angle_min: -1.0,
            angle_increment: 0.5,
            range_min: 0.1,
            range_max: 30.0,
            ranges: vec![
                2.0,
                f32::INFINITY,
                f32::NAN,
                45.0,
                f32::NEG_INFINITY,
                0.02,
                30.0,
            ],
            ..LaserScan::default()
        };
        let s = scan(&message, "scanner");
        let near = f64::from(0.1f32);
        assert_eq!(s.ranges, [2.0, 30.0, 30.0, 30.0, near, near, 30.0]);
        assert_eq!((s.angle_min, s.angle_step), (-1.0, 0.5));
        assert_eq!(s.device, "scanner");
        assert_eq!(battery_voltage(f32::NAN), None);
        assert_eq!(battery_voltage(24.5), Some(24.5));
    }
}

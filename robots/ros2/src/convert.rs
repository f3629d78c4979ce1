//! ROS 2's conventions to the HAL's and back: REP 103 units (metres, radians, counter-
//! clockwise, x forward) are the HAL's too, so what changes is the shape of things
//! (a twist for a speed and a curvature, a quaternion for a heading) and what a scan
//! says about beams that found nothing (REP 117).

use ilmr_hal::{Pose, Scan};
use ilmr_model::RobotModel;

use crate::msg::{
    BatteryState, Header, LaserScan, Odometry, Point, Pose as RosPose, Quaternion, Time, Transform,
    TransformStamped, Twist, Vector3,
};

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

/// What a robot driver makes of a `cmd_vel`: the speed setpoint (`linear.x`) and the
/// curvature (`angular.z / linear.x`), within its model's limits. A twist that turns
/// on the spot (no `linear.x`) has no curvature a car-like robot can drive: it stands.
/// A value that is not a number stops the robot.
pub fn setpoint(twist: &Twist, limits: Limits) -> (f64, f64) {
    let (v, w) = (twist.linear.x, twist.angular.z);
    if !v.is_finite() || !w.is_finite() {
        return (0.0, 0.0);
    }
    let v = v.clamp(-limits.max_speed, limits.max_speed);
    if v.abs() < AT_REST {
        return (v, 0.0);
    }
    (
        v,
        (w / v).clamp(-limits.max_curvature, limits.max_curvature),
    )
}

/// A robot's state as `nav_msgs/Odometry`: the pose in `frame` (`odom`), the speed and
/// turn rate in `child` (`base_link`).
pub fn odometry(
    pose: Pose,
    speed: f64,
    curvature: f64,
    stamp: Time,
    frame: &str,
    child: &str,
) -> Odometry {
    let mut o = Odometry {
        header: Header {
            stamp,
            frame_id: frame.to_string(),
        },
        child_frame_id: child.to_string(),
        ..Odometry::default()
    };
    o.pose.pose = RosPose {
        position: Point {
            x: pose.x,
            y: pose.y,
            z: 0.0,
        },
        orientation: Quaternion::from_yaw(pose.h),
    };
    o.twist.twist.linear.x = speed;
    o.twist.twist.angular.z = speed * curvature;
    o
}

/// `child` at `pose` in `parent`, for `tf`.
pub fn transform(pose: Pose, stamp: Time, parent: &str, child: &str) -> TransformStamped {
    TransformStamped {
        header: Header {
            stamp,
            frame_id: parent.to_string(),
        },
        child_frame_id: child.to_string(),
        transform: Transform {
            translation: Vector3 {
                x: pose.x,
                y: pose.y,
                z: 0.0,
            },
            rotation: Quaternion::from_yaw(pose.h),
        },
    }
}

/// A HAL-style scan (a beam that found nothing reads `max_range`) as REP 117 says it:
/// such a beam is `+inf`.
pub fn laser_scan(scan: &Scan, max_range: f64, period: f64, stamp: Time, frame: &str) -> LaserScan {
    let n = scan.ranges.len();
    LaserScan {
        header: Header {
            stamp,
            frame_id: frame.to_string(),
        },
        angle_min: scan.angle_min as f32,
        angle_max: (scan.angle_min + n.saturating_sub(1) as f64 * scan.angle_step) as f32,
        angle_increment: scan.angle_step as f32,
        time_increment: 0.0,
        scan_time: period as f32,
        range_min: 0.0,
        range_max: max_range as f32,
        ranges: scan
            .ranges
            .iter()
            .map(|&r| {
                if r >= max_range {
                    f32::INFINITY
                } else {
                    r as f32
                }
            })
            .collect(),
        intensities: Vec::new(),
    }
}

/// A battery of `voltage` volts, the rest not measured (NaN, as the message defines).
pub fn battery_state(voltage: f64, percentage: f64, stamp: Time, frame: &str) -> BatteryState {
    let nan = f32::NAN;
    BatteryState {
        header: Header {
            stamp,
            frame_id: frame.to_string(),
        },
        voltage: voltage as f32,
        temperature: nan,
        current: nan,
        charge: nan,
        capacity: nan,
        design_capacity: nan,
        percentage: percentage.clamp(0.0, 1.0) as f32,
        // POWER_SUPPLY_STATUS_DISCHARGING, _HEALTH_UNKNOWN, _TECHNOLOGY_UNKNOWN
        power_supply_status: 2,
        power_supply_health: 0,
        power_supply_technology: 0,
        present: true,
        ..BatteryState::default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::msg::PoseWithCovariance;

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

    #[test]
    fn a_driver_reads_back_the_setpoint_it_was_sent() {
        let limits = moro();
        for (v, k) in [(0.4, -0.5), (-0.2, 1.0), (0.8, 1.333333), (0.0, 0.0)] {
            let (v2, k2) = setpoint(&cmd_vel(v, k, limits), limits);
            assert!(
                (v2 - v).abs() < 1e-12 && (k2 - k).abs() < 1e-9,
                "{v} {k}: {v2} {k2}"
            );
        }
        let spin = Twist {
            angular: Vector3 {
                z: 1.0,
                ..Vector3::default()
            },
            ..Twist::default()
        };
        assert_eq!(
            setpoint(&spin, limits),
            (0.0, 0.0),
            "a car cannot spin in place"
        );
        let mut wild = spin;
        wild.linear.x = f64::NAN;
        assert_eq!(setpoint(&wild, limits), (0.0, 0.0));
        wild.linear.x = 9.0;
        wild.angular.z = 900.0;
        let (v, k) = setpoint(&wild, limits);
        assert_eq!((v, k), (limits.max_speed, limits.max_curvature));
    }

    #[test]
    fn what_a_robot_publishes_reads_back_as_what_it_is() {
        let pose = Pose::new(1.5, -2.0, 2.5);
        let o = super::odometry(pose, 0.4, -0.5, Time::from_secs(3.25), "odom", "base_link");
        let m = motion(&o).unwrap();
        assert!((m.pose.x - 1.5).abs() < 1e-12 && (m.pose.h - 2.5).abs() < 1e-12);
        assert!((m.speed - 0.4).abs() < 1e-12 && (m.curvature + 0.5).abs() < 1e-12);
        assert_eq!(m.t, 3.25);
        let hal = Scan {
            device: "scanner".into(),
            t: 0.0,
            angle_min: -1.0,
            angle_step: 0.5,
            ranges: vec![1.0, 30.0, 2.5, 30.0, 0.25],
        };
        let ros = laser_scan(&hal, 30.0, 0.25, Time::default(), "laser");
        assert_eq!(ros.ranges[1], f32::INFINITY, "REP 117: no return is +inf");
        assert_eq!(ros.angle_max, 1.0);
        let back = scan(&ros, "scanner");
        assert_eq!(back.ranges, hal.ranges);
    }
}

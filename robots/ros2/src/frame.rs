//! The task's frame over the robot's odometry frame: `locate(x,y,h)` says where the
//! robot is now, and every later odometry pose is moved and turned by the same amount.

use ilmr_geometry::wrap_angle;
use ilmr_hal::Pose;

/// A planar rigid transform: turn by `dh`, then move by `(dx, dy)`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Frame {
    dx: f64,
    dy: f64,
    dh: f64,
}

impl Frame {
    /// The frame in which the odometry pose `raw` is `placed`.
    pub fn placing(raw: Pose, placed: Pose) -> Frame {
        let dh = placed.h - raw.h;
        let (s, c) = dh.sin_cos();
        Frame {
            dx: placed.x - (c * raw.x - s * raw.y),
            dy: placed.y - (s * raw.x + c * raw.y),
            dh,
        }
    }

    pub fn apply(&self, raw: Pose) -> Pose {
        let (s, c) = self.dh.sin_cos();
        Pose {
            x: c * raw.x - s * raw.y + self.dx,
            y: s * raw.x + c * raw.y + self.dy,
            h: wrap_angle(raw.h + self.dh),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::FRAC_PI_2;

    fn close(a: Pose, b: Pose) -> bool {
        (a.x - b.x).abs() < 1e-12 && (a.y - b.y).abs() < 1e-12 && (a.h - b.h).abs() < 1e-12
    }

    #[test]
    fn the_located_pose_is_where_the_robot_is_and_later_motion_turns_with_it() {
        let raw = Pose::new(2.0, 1.0, FRAC_PI_2);
        let frame = Frame::placing(raw, Pose::new(10.0, 5.0, 0.0));
        assert!(close(frame.apply(raw), Pose::new(10.0, 5.0, 0.0)));
        // One metre ahead in odometry (+y, the robot faced +y) is one metre ahead in
        // the task's frame (+x, where it faces now).
        let ahead = frame.apply(Pose::new(2.0, 2.0, FRAC_PI_2));
        assert!(close(ahead, Pose::new(11.0, 5.0, 0.0)), "{ahead:?}");
    }

    #[test]
    fn no_locate_is_the_odometry_frame() {
        let p = Pose::new(-3.0, 4.0, 3.0);
        assert!(close(Frame::default().apply(p), p));
    }
}

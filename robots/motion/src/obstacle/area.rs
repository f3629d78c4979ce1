//! The area checked for obstacles: length by equation (11), width by
//! equation (12), bent along the robot's current curvature.

use crate::arc::Arc;
use crate::path::Direction;
use crate::pose::Pose;
use nalgebra::Point2;
use serde::{Deserialize, Serialize};

#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct AreaParams {
    /// R_max of equation (11): the robot's maximum curvature, 1/m.
    pub max_curvature: f64,
    /// robot_width of equation (12), m.
    pub robot_width: f64,
    /// From the pose's reference point to the front (in the direction of
    /// travel), m: the area starts there.
    pub front_offset: f64,
}

/// Equation (11): the turning radius plus two seconds of travel, at least
/// half a metre.
pub fn check_length(max_curvature: f64, speed: f64) -> f64 {
    let radius = if max_curvature > 0.0 {
        1.0 / max_curvature
    } else {
        0.0
    };
    (radius + 2.0 * speed.abs()).max(0.5)
}

/// Equation (12).
pub fn check_width(robot_width: f64) -> f64 {
    1.2 * robot_width
}

/// A map point inside the area, in the area's own coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    pub index: usize,
    /// Distance along the area from its start (the robot's front).
    pub s: f64,
    /// Offset to the left of the area's centre line.
    pub n: f64,
}

/// The checked area: a band of `width` around an arc of the robot's
/// current curvature, a rectangle only when the robot drives straight.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CheckArea {
    pub arc: Arc,
    pub width: f64,
}

impl CheckArea {
    /// The area in front of a robot at `pose` that moves in `direction`
    /// with steering `curvature` at `speed`.
    pub fn new(
        pose: &Pose,
        direction: Direction,
        curvature: f64,
        speed: f64,
        params: &AreaParams,
    ) -> CheckArea {
        let travel = match direction {
            Direction::Forward => *pose,
            Direction::Backward => pose.flipped(),
        };
        let geometric = direction.sign() * curvature;
        CheckArea {
            arc: Arc {
                start: travel.advance(params.front_offset, geometric),
                curvature: geometric,
                length: check_length(params.max_curvature, speed),
            },
            width: check_width(params.robot_width),
        }
    }

    pub fn hit(&self, index: usize, p: &Point2<f64>) -> Option<Hit> {
        let (s, n) = self.arc.coords(p);
        (s >= 0.0 && s <= self.arc.length && n.abs() <= 0.5 * self.width).then_some(Hit {
            index,
            s,
            n,
        })
    }

    /// Every map point inside the area, nearest first (ties by index).
    pub fn hits(&self, points: &[Point2<f64>]) -> Vec<Hit> {
        let mut hits: Vec<Hit> = points
            .iter()
            .enumerate()
            .filter_map(|(i, p)| self.hit(i, p))
            .collect();
        hits.sort_by(|a, b| a.s.total_cmp(&b.s).then(a.index.cmp(&b.index)));
        hits
    }

    /// "If one or more of them is inside the defined area, an obstacle is
    /// found": the nearest such point.
    pub fn first_hit(&self, points: &[Point2<f64>]) -> Option<Hit> {
        self.hits(points).into_iter().next()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MORO: AreaParams = AreaParams {
        max_curvature: 1.0 / 0.75,
        robot_width: 0.6,
        front_offset: 0.9,
    };

    #[test]
    fn dimensions_follow_equations_11_and_12() {
        assert!((check_length(1.0 / 0.75, 0.4) - (0.75 + 0.8)).abs() < 1e-12);
        assert!((check_length(0.25, 0.0) - 4.0).abs() < 1e-12);
        // Equation (11) has a floor of half a metre.
        assert_eq!(check_length(10.0, 0.1), 0.5);
        assert!((check_width(0.6) - 0.72).abs() < 1e-12);
        let a = CheckArea::new(
            &Pose::new(0.0, 0.0, 0.0),
            Direction::Forward,
            0.0,
            0.4,
            &MORO,
        );
        assert!((a.arc.length - 1.55).abs() < 1e-12 && (a.width - 0.72).abs() < 1e-12);
    }

    #[test]
    fn straight_area_is_a_rectangle_ahead_of_the_front() {
        let a = CheckArea::new(
            &Pose::new(0.0, 0.0, 0.0),
            Direction::Forward,
            0.0,
            0.4,
            &MORO,
        );
        assert!(a.hit(0, &Point2::new(1.0, 0.35)).is_some());
        assert!(a.hit(0, &Point2::new(1.0, 0.37)).is_none());
        assert!(
            a.hit(0, &Point2::new(0.8, 0.0)).is_none(),
            "behind the front"
        );
        assert!(a.hit(0, &Point2::new(2.44, 0.0)).is_some());
        assert!(a.hit(0, &Point2::new(2.46, 0.0)).is_none(), "beyond l_obs");
    }

    #[test]
    fn curving_area_follows_the_turn() {
        let a = CheckArea::new(
            &Pose::new(0.0, 0.0, 0.0),
            Direction::Forward,
            1.0,
            0.4,
            &MORO,
        );
        // Straight ahead at the far end lies outside the bent band, a point
        // on the arc there inside it.
        let on_arc = a.arc.point_at(1.4);
        assert!(a.hit(0, &on_arc).is_some());
        assert!(a.hit(0, &Point2::new(0.9 + 1.4, 0.0)).is_none());
    }

    #[test]
    fn reversing_checks_behind() {
        let a = CheckArea::new(
            &Pose::new(0.0, 0.0, 0.0),
            Direction::Backward,
            0.0,
            0.3,
            &MORO,
        );
        assert!(a.hit(0, &Point2::new(-1.2, 0.0)).is_some());
        assert!(a.hit(0, &Point2::new(1.2, 0.0)).is_none());
    }

    #[test]
    fn first_hit_is_the_nearest() {
        let a = CheckArea::new(
            &Pose::new(0.0, 0.0, 0.0),
            Direction::Forward,
            0.0,
            0.4,
            &MORO,
        );
        let pts = [
            Point2::new(2.0, 0.1),
            Point2::new(5.0, 0.0),
            Point2::new(1.2, -0.2),
        ];
        assert_eq!(a.first_hit(&pts).map(|h| h.index), Some(2));
        assert_eq!(a.hits(&pts).len(), 2);
    }
}

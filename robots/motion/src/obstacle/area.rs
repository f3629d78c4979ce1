//! The area checked for obstacles: length by equation (11), width by
//! equation (12), bent along the robot's current curvature, but no further
//! than the route turns: past that the area goes straight on.

use crate::arc::Arc;
use crate::path::{Direction, Path};
use crate::pose::{Pose, angle_diff};
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

/// How far, in radians, the route turns towards the side of `curvature`
/// from the robot's heading, over the `reach` metres of `reference` from
/// index `k` on (0 when it turns the other way or not at all).
///
/// The robot steers along its route: once its heading has caught up with
/// the route's it straightens, so the area need bend no further. Bent the
/// whole length of equation (11) at a tight curvature, it would sweep round
/// through the wall the robot is turning past (the end of the lab bench in
/// Figure 58).
pub fn route_turn(reference: &Path, k: usize, travel: &Pose, curvature: f64, reach: f64) -> f64 {
    let pts = reference.points();
    let k = reference.clamp_index(k);
    let side = curvature.signum();
    let s_end = pts[k].s + reach.max(0.0);
    let mut heading = travel.h;
    let mut turned: f64 = 0.0;
    let mut most: f64 = 0.0;
    for p in pts[k..].iter().take_while(|p| p.s <= s_end) {
        let h = p.travel_heading();
        turned += angle_diff(h, heading);
        heading = h;
        most = most.max(side * turned);
    }
    most
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
/// current curvature, continued by a straight band of length `straight`
/// where the route stops turning; a rectangle when the robot drives
/// straight.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CheckArea {
    pub arc: Arc,
    pub straight: f64,
    pub width: f64,
}

impl CheckArea {
    /// The area in front of a robot at `pose` that moves in `direction`
    /// with steering `curvature` at `speed`, bent along the whole length.
    pub fn new(
        pose: &Pose,
        direction: Direction,
        curvature: f64,
        speed: f64,
        params: &AreaParams,
    ) -> CheckArea {
        Self::turning_at_most(pose, direction, curvature, speed, params, f64::INFINITY)
    }

    /// As `new`, but the area turns through at most `max_turn` radians
    /// (measured from the robot's heading, the stretch to the front
    /// included) and goes straight on after that.
    pub fn turning_at_most(
        pose: &Pose,
        direction: Direction,
        curvature: f64,
        speed: f64,
        params: &AreaParams,
        max_turn: f64,
    ) -> CheckArea {
        let travel = match direction {
            Direction::Forward => *pose,
            Direction::Backward => pose.flipped(),
        };
        let geometric = direction.sign() * curvature;
        let bend = if geometric == 0.0 || max_turn.is_nan() {
            f64::INFINITY
        } else {
            max_turn.max(0.0) / geometric.abs()
        };
        let length = check_length(params.max_curvature, speed);
        // The front: along the arc as far as the bend goes, then straight.
        let to_front = params.front_offset.min(bend);
        let start = travel
            .advance(to_front, geometric)
            .advance(params.front_offset - to_front, 0.0);
        let arc_length = length.min((bend - to_front).max(0.0));
        let arc_curvature = if arc_length > 0.0 { geometric } else { 0.0 };
        CheckArea {
            arc: Arc {
                start,
                curvature: arc_curvature,
                length: arc_length,
            },
            straight: length - arc_length,
            width: check_width(params.robot_width),
        }
    }

    /// Total length of the area, m.
    pub fn length(&self) -> f64 {
        self.arc.length + self.straight
    }

    pub fn hit(&self, index: usize, p: &Point2<f64>) -> Option<Hit> {
        let half = 0.5 * self.width;
        // Every point of the area lies within its length along the path plus
        // half its width of the start: most mapped points are rejected here,
        // before the trigonometry of the arc's coordinates.
        let reach = self.arc.length.max(0.0) + self.straight.max(0.0) + half;
        let (dx, dy) = (p.x - self.arc.start.x, p.y - self.arc.start.y);
        if dx * dx + dy * dy > reach * reach {
            return None;
        }
        let (s, n) = self.arc.coords(p);
        if s >= 0.0 && s <= self.arc.length && n.abs() <= half {
            return Some(Hit { index, s, n });
        }
        if self.straight <= 0.0 {
            return None;
        }
        let l = self.arc.end().to_local(p);
        (l.x >= 0.0 && l.x <= self.straight && l.y.abs() <= half).then_some(Hit {
            index,
            s: self.arc.length + l.x,
            n: l.y,
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

    #[test]
    fn the_area_bends_no_further_than_the_route_turns() {
        // A quarter circle of radius 1 to the left, then straight north.
        let spec = crate::path::TurnSpec {
            lead_out: 3.0,
            ..crate::path::TurnSpec::degrees(90.0, 1.0)
        };
        let route = crate::path::turn(Pose::new(0.0, 0.0, 0.0), &spec, Direction::Forward, 0.05)
            .expect("valid");
        let at = Pose::new(0.0, 0.0, 0.0);
        let turn = route_turn(&route, 0, &at, 1.0, 4.0);
        assert!((turn - std::f64::consts::FRAC_PI_2).abs() < 1e-9, "{turn}");
        // Steering right against a left route: nothing to bend for.
        assert_eq!(route_turn(&route, 0, &at, -1.0, 4.0), 0.0);

        let full = CheckArea::new(&at, Direction::Forward, 1.0, 0.4, &MORO);
        let limited = CheckArea::turning_at_most(&at, Direction::Forward, 1.0, 0.4, &MORO, turn);
        assert!((limited.length() - full.length()).abs() < 1e-12);
        assert!(limited.straight > 0.0 && full.straight == 0.0);
        // Inside the circle past the quarter, where the full bend sweeps
        // (the wall the robot turns round); the limited area goes north.
        let inside = Point2::new(0.55, 1.45);
        assert!(full.hit(0, &inside).is_some());
        assert!(limited.hit(0, &inside).is_none());
        let ahead = Point2::new(1.0, 1.6);
        let h = limited.hit(0, &ahead).expect("on the route after the turn");
        assert!(h.n.abs() < 1e-9 && h.s > limited.arc.length);
    }
}

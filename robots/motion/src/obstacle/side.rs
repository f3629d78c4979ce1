//! "The path around the obstacle is calculated in a simple way to search
//! enough space on either side of the obstacle" (section 4.5.7).

use crate::bezier::{CubicBezier, PlanError};
use crate::path::{Direction, JOIN_TOLERANCE, Path, segment_distance, straight};
use crate::pose::{Pose, Side};
use nalgebra::Point2;
use serde::{Deserialize, Serialize};

#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct SideParams {
    pub robot_width: f64,
    pub robot_length: f64,
    /// From the pose's reference point to the front, m.
    pub front_offset: f64,
    /// Extra clearance on top of the check width, m.
    pub margin: f64,
    /// Farthest sideways the robot may leave its route, m.
    pub max_offset: f64,
}

impl SideParams {
    fn half_width(&self) -> f64 {
        0.5 * super::check_width(self.robot_width) + self.margin
    }
}

/// A way past an obstacle, in the frame of motion of the robot when it was
/// planned (`origin`): drive over to the lateral `offset` by `start` (where
/// the front reaches the obstacle), at the latest by `latest` (where the
/// reference point does), and keep it until `end`, where the rear has
/// passed the obstacle.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Detour {
    pub side: Side,
    pub origin: Pose,
    /// Signed, positive to the left of the motion, m.
    pub offset: f64,
    pub start: f64,
    pub latest: f64,
    pub end: f64,
}

/// Searches both sides of `obstacle` (its points in world coordinates) for
/// a lane as wide as the checked area (plus a margin) right beside it that
/// no map point blocks, within `max_offset` of the robot's line, seen from a
/// robot at the travel-frame pose `travel`. The smaller sideways move wins;
/// left wins a tie, so the choice is deterministic.
pub fn find_free_side(
    travel: &Pose,
    obstacle: &[Point2<f64>],
    points: &[Point2<f64>],
    params: &SideParams,
) -> Option<Detour> {
    let local: Vec<Point2<f64>> = obstacle.iter().map(|p| travel.to_local(p)).collect();
    let (first, rest) = local.split_first()?;
    let (mut x0, mut x1, mut y0, mut y1) = (first.x, first.x, first.y, first.y);
    for p in rest {
        x0 = x0.min(p.x);
        x1 = x1.max(p.x);
        y0 = y0.min(p.y);
        y1 = y1.max(p.y);
    }
    let start = x0 - params.front_offset - params.margin;
    let end = x1 + params.robot_length + params.margin;
    let half = params.half_width();
    let map: Vec<Point2<f64>> = points
        .iter()
        .map(|p| travel.to_local(p))
        .filter(|p| p.x >= start.min(0.0) && p.x <= end)
        .collect();
    // The lane hugs the obstacle. It is not pushed further out past other
    // points: those may be a wall, and a lane behind a wall is no way round.
    let lane = |side: Side| -> Option<f64> {
        let centre = if side == Side::Left {
            y1 + half
        } else {
            y0 - half
        };
        // The obstacle's own edge lies exactly half a lane away; rounding must
        // not count it as inside.
        let blocked = map.iter().any(|p| (p.y - centre).abs() < half - 1e-9);
        (!blocked && centre.abs() <= params.max_offset).then_some(centre)
    };
    let left = lane(Side::Left);
    let right = lane(Side::Right);
    let (side, offset) = match (left, right) {
        (Some(l), Some(r)) if r.abs() < l.abs() => (Side::Right, r),
        (Some(l), _) => (Side::Left, l),
        (None, Some(r)) => (Side::Right, r),
        (None, None) => return None,
    };
    Some(Detour {
        side,
        origin: *travel,
        offset,
        start,
        latest: x0 - params.margin,
        end,
    })
}

/// The path of a detour from the robot's current `pose`: a Bezier over to
/// the lane, then along it to the detour's end, driven in `direction`.
pub fn detour_path(
    pose: &Pose,
    direction: Direction,
    detour: &Detour,
    max_curvature: f64,
    spacing: f64,
) -> Result<Path, PlanError> {
    let travel = match direction {
        Direction::Forward => *pose,
        Direction::Backward => pose.flipped(),
    };
    let o = &detour.origin;
    let here = o.to_local(&travel.position()).x;
    // Reach the lane as early as planned if the robot can bend that hard,
    // else a little later each try, up to the latest point.
    let mut entry_x = detour.start.max(here);
    let mut best = f64::INFINITY;
    let (bend, entry_pose, entry_x) = loop {
        let entry = o.to_world(&Point2::new(entry_x, detour.offset));
        let entry_pose = Pose::new(entry.x, entry.y, o.h);
        let bend = CubicBezier::from_poses(&travel, &entry_pose);
        let needed = bend.max_abs_curvature();
        if needed <= max_curvature * (1.0 + 1e-9) {
            break (bend, entry_pose, entry_x);
        }
        best = best.min(needed);
        entry_x += 0.1;
        if entry_x > detour.latest.max(detour.start) + 1e-9 {
            return Err(PlanError::NoAdmissiblePath {
                needed: best,
                max_curvature,
            });
        }
    };
    let bend = bend.sample(spacing, Direction::Forward)?;
    let along = straight(entry_pose, (detour.end - entry_x).max(0.0), spacing)?;
    let joined = bend.concat(&along, JOIN_TOLERANCE)?;
    Ok(joined.with_direction(direction))
}

/// True when no map point lies within `half_width` of the segment `a`-`b`:
/// the check that "the way back to the reference path is free".
pub fn corridor_is_free(
    a: &Point2<f64>,
    b: &Point2<f64>,
    points: &[Point2<f64>],
    half_width: f64,
) -> bool {
    points
        .iter()
        .all(|p| segment_distance(p, a, b) > half_width)
}

#[cfg(test)]
mod tests {
    use super::*;

    const P: SideParams = SideParams {
        robot_width: 0.6,
        robot_length: 1.2,
        front_offset: 0.9,
        margin: 0.1,
        max_offset: 3.0,
    };

    fn boxed(cx: f64, cy: f64, half: f64) -> Vec<Point2<f64>> {
        let mut v = vec![];
        for i in 0..=10 {
            let t = -half + 2.0 * half * i as f64 / 10.0;
            v.push(Point2::new(cx + t, cy - half));
            v.push(Point2::new(cx + t, cy + half));
            v.push(Point2::new(cx - half, cy + t));
            v.push(Point2::new(cx + half, cy + t));
        }
        v
    }

    #[test]
    fn open_floor_picks_the_nearer_side() {
        let me = Pose::new(0.0, 0.0, 0.0);
        // Box centred a little to the left: passing it on the right is the
        // smaller move (lane half width 0.36 + 0.1).
        let obstacle = boxed(3.0, 0.1, 0.2);
        let d = find_free_side(&me, &obstacle, &obstacle, &P).expect("open floor");
        assert_eq!(d.side, Side::Right);
        assert!((d.offset - (-0.1 - 0.46)).abs() < 1e-9);
        assert!((d.end - (3.2 + 1.2 + 0.1)).abs() < 1e-9);
    }

    #[test]
    fn a_wall_on_one_side_sends_the_robot_round_the_other() {
        let me = Pose::new(0.0, 0.0, 0.0);
        let obstacle = boxed(3.0, 0.0, 0.2);
        let mut map = obstacle.clone();
        map.extend((0..60).map(|i| Point2::new(i as f64 * 0.1, 0.9)));
        let d = find_free_side(&me, &obstacle, &map, &P).expect("right is free");
        assert_eq!(d.side, Side::Right);
        map.extend((0..60).map(|i| Point2::new(i as f64 * 0.1, -0.9)));
        assert_eq!(find_free_side(&me, &obstacle, &map, &P), None);
    }

    #[test]
    fn detour_path_reaches_the_lane_and_passes_the_obstacle() {
        let me = Pose::new(0.0, 0.0, 0.0);
        let obstacle = boxed(4.0, 0.0, 0.2);
        let d = find_free_side(&me, &obstacle, &obstacle, &P).expect("free");
        let path = detour_path(&me, Direction::Forward, &d, 1.33, 0.05).expect("admissible");
        assert!((path.end_pose().y - d.offset).abs() < 1e-9);
        assert!((path.end_pose().x - d.end).abs() < 1e-6);
        assert!(path.max_abs_curvature() <= 1.33 + 1e-6);
        // Every point of the path clears the obstacle by half the lane.
        for p in path.points() {
            if p.x > 3.8 - 0.9 {
                assert!(
                    obstacle
                        .iter()
                        .all(|o| (o - p.position()).norm() >= 0.46 - 1e-6)
                );
            }
        }
    }

    #[test]
    fn too_close_an_obstacle_has_no_admissible_detour() {
        let me = Pose::new(0.0, 0.0, 0.0);
        let obstacle = boxed(1.3, 0.0, 0.2);
        let d = find_free_side(&me, &obstacle, &obstacle, &P).expect("free side");
        assert!(detour_path(&me, Direction::Forward, &d, 0.25, 0.05).is_err());
    }

    #[test]
    fn corridor_check() {
        let pts = [Point2::new(1.0, 0.5)];
        assert!(corridor_is_free(
            &Point2::new(0.0, 0.0),
            &Point2::new(2.0, 0.0),
            &pts,
            0.4
        ));
        assert!(!corridor_is_free(
            &Point2::new(0.0, 0.0),
            &Point2::new(2.0, 0.0),
            &pts,
            0.6
        ));
    }
}

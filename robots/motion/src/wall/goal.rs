//! Goals of `followwall`: "The position of the robot is projected to the
//! wall. From this point three meters ahead a new point is calculated, and
//! this point is used to calculate the goal position for the robot at
//! desired distance from the wall ... this is repeated after each two
//! meters" (section 4.5.3).

use super::WallLine;
use crate::pose::{Pose, Side};
use nalgebra::Vector2;

/// How far along the wall the goal lies, m.
pub const FOLLOWWALL_AHEAD: f64 = 3.0;
/// How often the goal is recomputed, in metres driven.
pub const FOLLOWWALL_REPLAN: f64 = 2.0;

/// `followwall(side, distance)`: the goal `distance` metres off the wall on
/// `side`, `FOLLOWWALL_AHEAD` metres on from the robot's projection onto it,
/// heading along the wall.
pub fn followwall_goal(pose: &Pose, wall: &WallLine, side: Side, distance: f64) -> Pose {
    let dir = wall.direction.into_inner();
    let ahead = wall.project(&pose.position()) + dir * FOLLOWWALL_AHEAD;
    // The robot keeps to the side of the wall facing it: away from a wall
    // on its left means towards the right of the wall's direction.
    let left_normal = Vector2::new(-dir.y, dir.x);
    let goal = ahead - left_normal * (side.sign() * distance);
    Pose::new(goal.x, goal.y, wall.heading())
}

/// `followwall(middle)`: halfway between the two walls' points ahead,
/// heading along their mean direction.
pub fn middle_goal(pose: &Pose, left: &WallLine, right: &WallLine) -> Pose {
    let p = pose.position();
    let a = left.project(&p) + left.direction.into_inner() * FOLLOWWALL_AHEAD;
    let b = right.project(&p) + right.direction.into_inner() * FOLLOWWALL_AHEAD;
    let mid = nalgebra::center(&a, &b);
    let dir = left.direction.into_inner() + right.direction.into_inner();
    let heading = if dir.norm() > 1e-9 {
        dir.y.atan2(dir.x)
    } else {
        pose.h
    };
    Pose::new(mid.x, mid.y, heading)
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Point2, Unit};

    fn wall(y: f64) -> WallLine {
        WallLine {
            point: Point2::new(0.0, y),
            direction: Unit::new_normalize(Vector2::new(1.0, 0.0)),
            inliers: 50,
            rms: 0.0,
        }
    }

    #[test]
    fn left_wall_goal_is_three_metres_on_at_the_distance() {
        let g = followwall_goal(&Pose::new(2.0, 0.6, 0.2), &wall(2.0), Side::Left, 1.0);
        assert!((g.x - 5.0).abs() < 1e-12 && (g.y - 1.0).abs() < 1e-12 && g.h == 0.0);
        let g = followwall_goal(&Pose::new(2.0, 0.6, 0.2), &wall(-1.0), Side::Right, 0.5);
        assert!((g.x - 5.0).abs() < 1e-12 && (g.y + 0.5).abs() < 1e-12);
    }

    #[test]
    fn middle_goal_is_between_the_walls() {
        let g = middle_goal(&Pose::new(1.0, 0.3, 0.0), &wall(1.5), &wall(-0.5));
        assert!((g.x - 4.0).abs() < 1e-12 && (g.y - 0.5).abs() < 1e-12 && g.h == 0.0);
    }
}

//! Obstacle avoidance of section 4.5.7: the checked area (equations (11)
//! and (12)), the search for a free side, and the state machine of Figure 35.
//! Everything works on a point cloud in world coordinates (the environmental
//! map); keeping that map is the caller's job.

mod area;
mod bounds;
mod grid;
mod side;
mod state;

pub use area::{
    AreaParams, AreaTester, CheckArea, Hit, check_length, check_width, on_the_way, route_turn,
};
pub use bounds::Bounds;
pub use grid::{PointGrid, grid_of};
pub use side::{Detour, SideParams, corridor_is_free, detour_path, find_free_side};
pub use state::{AvoidMode, AvoidParams, AvoidState, Avoider, Decision, Observation};

use crate::pose::Pose;
use nalgebra::Point2;

/// How far behind the robot map points are kept (section 4.5.7).
pub const MAP_KEEP_BEHIND: f64 = 3.0;

/// Drops the map points that lie more than `MAP_KEEP_BEHIND` metres behind
/// the robot, keeping the order of the rest.
pub fn prune_map(points: &[Point2<f64>], pose: &Pose) -> Vec<Point2<f64>> {
    // `pose.to_local(p).x`, with the heading's sine and cosine once.
    let (s, c) = pose.h.sin_cos();
    let o = pose.position();
    points
        .iter()
        .filter(|p| {
            let d = *p - o;
            c * d.x + s * d.y >= -MAP_KEEP_BEHIND
        })
        .copied()
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pruning_keeps_points_up_to_three_metres_behind() {
        let pose = Pose::new(5.0, 0.0, 0.0);
        let pts = [
            Point2::new(1.0, 0.0),
            Point2::new(2.5, 1.0),
            Point2::new(9.0, 0.0),
        ];
        assert_eq!(prune_map(&pts, &pose), vec![pts[1], pts[2]]);
    }
}

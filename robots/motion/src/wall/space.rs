//! "When turn(left) or turn(right) is given, the space for turning is first
//! checked" (section 4.5.3).

use crate::arc::Arc;
use crate::obstacle::{Bounds, check_width};
use crate::path::{Path, segment_distance};
use crate::pose::{Pose, Side};
use nalgebra::Point2;
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4};

/// True when no map point lies within `half_width` of the path.
pub fn path_is_free(path: &Path, points: &[Point2<f64>], half_width: f64) -> bool {
    points.iter().all(|p| path.distance_to(p) > half_width)
}

/// True when a quarter turn to `side` at `curvature` from `pose`, and the
/// `lead_out` metres the robot then drives straight on, keep every map
/// point further than half the checked width (equation (12)) plus `margin`
/// from the robot's centre line.
///
/// The straight after the arc matters at the end of a wall the robot turns
/// round: the arc alone clears the corner as soon as the corner lies beyond
/// the arc's end, but the robot goes on past it with the avoider's area
/// ahead, and that area would then find the corner.
pub fn turn_space_free(
    pose: &Pose,
    side: Side,
    curvature: f64,
    robot_width: f64,
    margin: f64,
    lead_out: f64,
    points: &[Point2<f64>],
) -> bool {
    if !(curvature.is_finite() && curvature > 0.0 && lead_out.is_finite()) {
        return false;
    }
    let arc = Arc {
        start: *pose,
        curvature: side.sign() * curvature,
        length: FRAC_PI_2 / curvature,
    };
    let end = arc.end();
    let beyond = end.advance(lead_out.max(0.0), 0.0).position();
    let clearance = 0.5 * check_width(robot_width) + margin;
    // Every point of a quarter circle lies within its sagitta of the chord:
    // a point outside this box is further than the clearance from both, and
    // is passed over without the arc's trigonometry.
    let sagitta = (1.0 - FRAC_PI_4.cos()) / curvature;
    let near = Bounds::around(
        &[(pose.x, pose.y), (end.x, end.y), (beyond.x, beyond.y)],
        clearance + sagitta,
    );
    points.iter().all(|p| {
        near.excludes((p.x, p.y))
            || (arc.distance_to(p) > clearance
                && segment_distance(p, &end.position(), &beyond) > clearance)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn passing_over_far_points_changes_no_answer() {
        // The check over every point with the arc's own distances, as it was
        // before far points were passed over.
        let every_point = |pose: &Pose, side: Side, c: f64, lead_out: f64, pts: &[Point2<f64>]| {
            let arc = Arc {
                start: *pose,
                curvature: side.sign() * c,
                length: FRAC_PI_2 / c,
            };
            let end = arc.end();
            let beyond = end.advance(lead_out, 0.0).position();
            let clearance = 0.5 * check_width(0.6) + 0.1;
            pts.iter().all(|p| {
                arc.distance_to(p) > clearance
                    && segment_distance(p, &end.position(), &beyond) > clearance
            })
        };
        let mut state = 5u64;
        let mut next = move || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let (mut free, mut blocked) = (0, 0);
        for round in 0..3000 {
            let pose = Pose::new(4.0 * next() - 2.0, 4.0 * next() - 2.0, 7.0 * next() - 3.5);
            let side = if round % 2 == 0 {
                Side::Left
            } else {
                Side::Right
            };
            let c = [1.0, 0.25, 1.0 / 0.75][round % 3];
            let lead_out = [0.0, 1.5][round % 2];
            // A few points, most a little way off the arc's band.
            let pts: Vec<Point2<f64>> = (0..6)
                .map(|_| Point2::new(pose.x + 10.0 * next() - 5.0, pose.y + 10.0 * next() - 5.0))
                .collect();
            let want = every_point(&pose, side, c, lead_out, &pts);
            assert_eq!(
                turn_space_free(&pose, side, c, 0.6, 0.1, lead_out, &pts),
                want,
                "round {round}"
            );
            if want { free += 1 } else { blocked += 1 }
        }
        assert!(
            free > 300 && blocked > 300,
            "{free} free, {blocked} blocked"
        );
    }

    /// A corridor 2 m wide along x with its left wall ending at x = 4 (a
    /// corner to the left).
    fn corridor() -> Vec<Point2<f64>> {
        let mut pts = vec![];
        for i in 0..=100 {
            let x = i as f64 * 0.1;
            if x < 4.0 {
                pts.push(Point2::new(x, 1.0));
            }
            pts.push(Point2::new(x, -1.0));
        }
        pts
    }

    #[test]
    fn left_turn_is_free_only_past_the_corner() {
        let pts = corridor();
        assert!(!turn_space_free(
            &Pose::new(2.0, 0.0, 0.0),
            Side::Left,
            1.0,
            0.6,
            0.1,
            0.0,
            &pts
        ));
        assert!(turn_space_free(
            &Pose::new(4.3, 0.0, 0.0),
            Side::Left,
            1.0,
            0.6,
            0.1,
            0.0,
            &pts
        ));
        // The right side is a wall all along.
        assert!(!turn_space_free(
            &Pose::new(4.3, 0.0, 0.0),
            Side::Right,
            1.0,
            0.6,
            0.1,
            0.0,
            &pts
        ));
        assert!(!turn_space_free(
            &Pose::new(4.3, 0.0, 0.0),
            Side::Left,
            0.0,
            0.6,
            0.1,
            0.0,
            &pts
        ));
    }

    #[test]
    fn the_straight_after_the_turn_must_clear_the_corner_too() {
        // The end of a bench on the left (Figure 58): its corner lies just
        // beyond the arc's end, closer than the clearance to the line the
        // robot drives on after the turn.
        let bench: Vec<Point2<f64>> = (0..=20)
            .map(|i| Point2::new(4.5 + 0.25 * f64::from(i), 7.1))
            .chain((0..=8).map(|i| Point2::new(9.5, 7.1 + 0.1 * f64::from(i))))
            .collect();
        let at = Pose::new(8.955, 6.0, 0.0);
        assert!(turn_space_free(&at, Side::Left, 1.0, 0.6, 0.1, 0.0, &bench));
        assert!(!turn_space_free(
            &at,
            Side::Left,
            1.0,
            0.6,
            0.1,
            1.4,
            &bench
        ));
        let later = Pose::new(9.1, 6.0, 0.0);
        assert!(turn_space_free(
            &later,
            Side::Left,
            1.0,
            0.6,
            0.1,
            1.4,
            &bench
        ));
    }
}

//! Cutting, joining and re-traversing paths: linking of consecutive movement
//! commands (Test 5) and `followpath(..,reverse,backwards)`.

use super::{Direction, Path, PathError, PathPoint};
use std::f64::consts::PI;

/// The remaining length at which a running movement command hands over to a
/// queued one (section 5.6.4: "0.5 m left").
pub const LINK_REMAINING: f64 = 0.5;

/// Gap up to which two paths count as meeting when they are joined.
pub const JOIN_TOLERANCE: f64 = 1e-3;

impl Path {
    /// The part of the path from point `k` on, with arc length restarting at 0.
    pub fn tail_from(&self, k: usize) -> Path {
        let k = self.clamp_index(k);
        let s0 = self.points[k].s;
        let points = self.points[k..]
            .iter()
            .map(|p| PathPoint { s: p.s - s0, ..*p })
            .collect();
        Path { points }
    }

    /// Splits where `remaining` metres are left: the part already driven up
    /// to there, and the rest (which shares the cut point).
    pub fn split_at_remaining(&self, remaining: f64) -> (Path, Path) {
        let j = self.index_at_remaining(remaining);
        let head = Path {
            points: self.points[..=j].to_vec(),
        };
        (head, self.tail_from(j))
    }

    /// Appends `next`, which must start within `tolerance` metres of this
    /// path's end. Arc length continues across the joint. A joint point
    /// shared by both paths is kept twice only when the driving direction
    /// changes there, so the cusp stays visible to `distance_to_stop`.
    pub fn concat(&self, next: &Path, tolerance: f64) -> Result<Path, PathError> {
        let end = self.last();
        let start = next.first();
        let gap = (start.position() - end.position()).norm();
        if !gap.is_finite() || gap > tolerance {
            return Err(PathError::Discontinuous { gap });
        }
        let skip_first = gap <= 1e-9 && start.direction == end.direction;
        let offset = end.s + gap - start.s;
        let mut points = self.points.clone();
        points.extend(
            next.points
                .iter()
                .skip(usize::from(skip_first))
                .map(|p| PathPoint {
                    s: p.s + offset,
                    ..*p
                }),
        );
        Path::new(points)
    }

    /// Linking: the rest of this path from point `k` joined to the start of
    /// `next`. `next` is planned from this path's end pose (the previous goal),
    /// so the robot drives on without stopping at the joint.
    pub fn link(&self, k: usize, next: &Path) -> Result<Path, PathError> {
        self.tail_from(k).concat(next, JOIN_TOLERANCE)
    }

    /// The same trace driven from its end to its start
    /// (`followpath(name,backwards)`); each point keeps whether the robot
    /// drives forwards or reverses there.
    pub fn backwards(&self) -> Path {
        let total = self.last().s;
        let points = self
            .points
            .iter()
            .rev()
            .map(|p| {
                PathPoint::from_travel(
                    total - p.s,
                    p.position(),
                    p.travel_heading() + PI,
                    -p.geometric_curvature(),
                    p.direction,
                )
            })
            .collect();
        Path { points }
    }

    /// The same trace in the same order with the robot driving it in
    /// `direction` (`followpath(name,reverse)` drives it backwards).
    pub fn with_direction(&self, direction: Direction) -> Path {
        let points = self
            .points
            .iter()
            .map(|p| {
                PathPoint::from_travel(
                    p.s,
                    p.position(),
                    p.travel_heading(),
                    p.geometric_curvature(),
                    direction,
                )
            })
            .collect();
        Path { points }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::path::{TurnSpec, straight, turn};
    use crate::pose::{Pose, angle_diff};

    const SP: f64 = 0.05;

    #[test]
    fn linking_keeps_the_rest_and_continues_arc_length() {
        let a = straight(Pose::new(0.0, 0.0, 0.0), 1.2, SP).expect("valid");
        let b = turn(
            a.end_pose(),
            &TurnSpec::degrees(90.0, 0.5),
            Direction::Forward,
            SP,
        )
        .expect("valid");
        let k = a.index_at_remaining(LINK_REMAINING);
        let linked = a.link(k, &b).expect("paths meet");
        assert!((linked.length() - (0.5 + b.length())).abs() < 1e-9);
        assert!((linked.first().x - 0.7).abs() < 1e-9);
        let ss: Vec<f64> = linked.points().iter().map(|p| p.s).collect();
        assert!(ss.windows(2).all(|w| w[1] - w[0] > 1e-6));
        assert!(angle_diff(linked.end_pose().h, b.end_pose().h).abs() < 1e-12);
    }

    #[test]
    fn split_shares_the_cut_point() {
        let a = straight(Pose::new(0.0, 0.0, 0.0), 1.2, SP).expect("valid");
        let (head, rest) = a.split_at_remaining(LINK_REMAINING);
        assert_eq!(head.last().position(), rest.first().position());
        assert!((head.length() + rest.length() - 1.2).abs() < 1e-9);
    }

    #[test]
    fn joining_distant_paths_is_an_error() {
        let a = straight(Pose::new(0.0, 0.0, 0.0), 1.0, SP).expect("valid");
        let b = straight(Pose::new(2.0, 0.0, 0.0), 1.0, SP).expect("valid");
        assert!(matches!(
            a.concat(&b, JOIN_TOLERANCE),
            Err(PathError::Discontinuous { .. })
        ));
    }

    #[test]
    fn backwards_traversal_mirrors_a_left_turn_into_a_right_turn() {
        let a = turn(
            Pose::new(0.0, 0.0, 0.0),
            &TurnSpec::degrees(90.0, 0.5),
            Direction::Forward,
            SP,
        )
        .expect("valid");
        let b = a.backwards();
        assert_eq!(b.first().position(), a.last().position());
        assert!(angle_diff(b.first().h, a.last().h + PI).abs() < 1e-12);
        assert!(b.points().iter().all(|p| (p.curvature + 0.5).abs() < 1e-12));
        assert!((b.length() - a.length()).abs() < 1e-12);
    }

    #[test]
    fn reverse_driving_faces_away_and_flips_steering() {
        let a = turn(
            Pose::new(0.0, 0.0, 0.0),
            &TurnSpec::degrees(90.0, 0.5),
            Direction::Forward,
            SP,
        )
        .expect("valid");
        let r = a.with_direction(Direction::Backward);
        assert!(angle_diff(r.first().h, PI).abs() < 1e-12);
        assert!(r.points().iter().all(|p| (p.curvature + 0.5).abs() < 1e-12));
        let again = r.with_direction(Direction::Forward);
        for (p, q) in again.points().iter().zip(a.points()) {
            assert!((p.position() - q.position()).norm() < 1e-12);
            assert!(angle_diff(p.h, q.h).abs() < 1e-12);
            assert!((p.curvature - q.curvature).abs() < 1e-12 && p.direction == q.direction);
        }
    }
}

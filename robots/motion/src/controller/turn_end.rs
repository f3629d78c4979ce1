//! `turn(d=..,c=..)` ends on its heading, not on its arc's length.
//!
//! The controller follows the arc by position: every centimetre of position
//! error (a navigation fix, wheel slip, a curvature the steering's play falls
//! short of) is corrected over its look-ahead, and the robot reaches the
//! arc's end point at whatever angle that correction leaves. On Workpartner
//! (look-ahead 2 m, radius 4 m) that angle was up to 5 degrees either way on
//! the calibrated profile (seeds 1-20), with the robot's own heading estimate
//! saying so. A turn is asked for an angle: over its last stretch the heading
//! says how far is left, and the arc goes on past its planned end when the
//! robot is still short. The VM ends reversing turns this way (why not
//! forward ones: `ilmr_vm`'s `plan_movement`).

use std::f64::consts::PI;

use crate::path::{Direction, JOIN_TOLERANCE, Path, PathError, TurnSpec, turn};
use crate::pose::{Pose, angle_diff};

/// How far before the arc's planned end (in turning angle) the heading
/// decides, rad. Well beyond any heading error a position controller leaves
/// (5 degrees above), and well below half a circle, so that the wrapped
/// difference to the planned heading is never one turn off.
pub const HEADING_WINDOW: f64 = PI / 3.0;

/// How far the arc goes on past its planned end for a robot still short of
/// the heading there, rad. Three times the largest shortfall measured; a
/// robot that still falls short stops at the overrun's end.
pub const OVERRUN: f64 = PI / 12.0;

/// The heading a turn ends on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HeadingEnd {
    /// The planned body heading at the arc's end, rad.
    pub heading: f64,
    /// +1 when the body heading grows through the turn, -1 when it falls.
    pub sign: f64,
    /// The arc's curvature, 1/m, positive.
    pub curvature: f64,
    /// Arc length along the movement's reference at which the arc ends as
    /// planned, m.
    pub at: f64,
    /// The turn's geometry and direction, for continuing the arc.
    spec: TurnSpec,
    direction: Direction,
}

impl HeadingEnd {
    /// The end of the turn `spec` driven in `direction` from `start` (body
    /// pose), whose arc ends `at` metres along the reference. `None` for a
    /// turn without an arc (zero angle).
    pub fn of_turn(start: Pose, spec: &TurnSpec, direction: Direction, at: f64) -> Option<Self> {
        // Reversing retraces a forward turn's arc: the heading changes by -angle.
        let turned = direction.sign() * spec.angle;
        let usable = turned.is_finite() && turned != 0.0 && spec.curvature > 0.0;
        usable.then(|| HeadingEnd {
            heading: start.h + turned,
            sign: turned.signum(),
            curvature: spec.curvature,
            at,
            spec: TurnSpec {
                lead_in: 0.0,
                lead_out: 0.0,
                ..*spec
            },
            direction,
        })
    }

    /// The same end, `by` metres further along a reference that grew at its
    /// start (a linked predecessor's remainder joined before the turn).
    pub fn shifted(self, by: f64) -> Self {
        HeadingEnd {
            at: self.at + by,
            ..self
        }
    }

    /// What the body still has to turn, rad (negative: turned too far), for
    /// a robot at `pose` that has come `along` metres of the reference; `None`
    /// before the last [`HEADING_WINDOW`] of the arc, where the position alone
    /// says how far is left.
    pub fn to_turn(&self, pose: &Pose, along: f64) -> Option<f64> {
        let before_end = (self.at - along) * self.curvature;
        (before_end <= HEADING_WINDOW).then(|| self.sign * angle_diff(self.heading, pose.h))
    }

    /// The arc still to drive by the heading, m: where to stop.
    pub fn to_drive(&self, pose: &Pose, along: f64) -> Option<f64> {
        self.to_turn(pose, along)
            .map(|left| left.max(0.0) / self.curvature)
    }

    /// The turn is done: within `tolerance` metres of arc of its heading, or
    /// past it.
    pub fn reached(&self, pose: &Pose, along: f64, tolerance: f64) -> bool {
        self.to_turn(pose, along)
            .is_some_and(|left| left <= tolerance * self.curvature)
    }

    /// `path` (whose arc ends where it does) with the arc continued by
    /// [`OVERRUN`], for the controller to follow while the robot is short of
    /// the heading.
    pub fn overrun(&self, path: &Path, spacing: f64) -> Result<Path, PathError> {
        let more = TurnSpec {
            angle: OVERRUN.copysign(self.spec.angle),
            ..self.spec
        };
        let tail = turn(path.end_pose(), &more, self.direction, spacing)?;
        path.concat(&tail, JOIN_TOLERANCE)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn reversing_turn() -> (Path, HeadingEnd) {
        let start = Pose::new(0.0, 0.0, 0.0);
        let spec = TurnSpec::degrees(-135.0, 0.5);
        let path = turn(start, &spec, Direction::Backward, 0.05).expect("an arc");
        let end = HeadingEnd::of_turn(start, &spec, Direction::Backward, path.length());
        (path, end.expect("a turn"))
    }

    #[test]
    fn reversing_the_heading_changes_by_minus_the_angle() {
        let (path, end) = reversing_turn();
        assert!((end.heading - 135f64.to_radians()).abs() < 1e-12);
        assert_eq!(end.sign, 1.0);
        assert!(angle_diff(path.end_pose().h, end.heading).abs() < 1e-9);
    }

    #[test]
    fn the_heading_decides_only_over_the_last_stretch() {
        let (path, end) = reversing_turn();
        let at = |s: f64| path.points()[path.index_at_remaining(path.length() - s)].pose();
        // Half way the wrapped difference could be a turn off: not asked.
        let half = path.length() / 2.0;
        assert_eq!(end.to_turn(&at(half), half), None);
        // 20 degrees before the end, 20 degrees are left.
        let s = path.length() - 20f64.to_radians() / 0.5;
        let left = end.to_turn(&at(s), s).expect("in the window");
        assert!((left - 20f64.to_radians()).abs() < 0.02);
        assert!((end.to_drive(&at(s), s).expect("in the window") - left / 0.5).abs() < 1e-12);
    }

    #[test]
    fn a_robot_short_of_the_heading_at_the_end_point_drives_on() {
        let (path, end) = reversing_turn();
        let mut short = path.end_pose();
        short.h -= 4f64.to_radians();
        let s = path.length();
        let drive = end.to_drive(&short, s).expect("at the end");
        assert!((drive - 4f64.to_radians() / 0.5).abs() < 1e-9);
        assert!(!end.reached(&short, s, 0.02));
        // Turned too far: nothing left to drive, done.
        let mut long = path.end_pose();
        long.h += 1f64.to_radians();
        assert_eq!(end.to_drive(&long, s), Some(0.0));
        assert!(end.reached(&long, s, 0.02));
    }

    #[test]
    fn the_overrun_continues_the_arc() {
        let (path, end) = reversing_turn();
        let longer = end.overrun(&path, 0.05).expect("joins");
        assert!((longer.length() - path.length() - OVERRUN / 0.5).abs() < 1e-9);
        let past = angle_diff(longer.end_pose().h, end.heading);
        assert!((past - OVERRUN).abs() < 1e-9);
        assert!(
            longer
                .points()
                .iter()
                .all(|p| p.direction == Direction::Backward)
        );
    }

    #[test]
    fn a_turn_through_no_angle_has_no_heading_end() {
        let spec = TurnSpec::degrees(0.0, 0.5);
        assert_eq!(
            HeadingEnd::of_turn(Pose::default(), &spec, Direction::Forward, 0.0),
            None
        );
    }
}

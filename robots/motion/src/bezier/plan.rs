//! Planning a movement to a goal pose (section 4.5.2.1): the Bezier path if
//! the robot can follow it, else, when the user allows it (`gotoxy(..,r)`),
//! a reversing turn first, extended until a path from there is admissible;
//! and where no reversing turn is enough (a U-turn narrower than the turning
//! circle), a three-point turn: forwards on full lock, reversing, then the
//! Bezier.

use super::CubicBezier;
use crate::path::{Direction, JOIN_TOLERANCE, Path, PathError};
use crate::pose::{Pose, angle_diff};
use std::f64::consts::PI;
use std::fmt;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlanParams {
    /// The robot's maximum curvature, 1/m.
    pub max_curvature: f64,
    /// The `r` parameter of gotoxy: may reverse and turn first.
    pub allow_reverse: bool,
    /// How the robot drives to the goal (a negative speed reverses).
    pub direction: Direction,
    /// Arc length between path samples, m.
    pub spacing: f64,
    /// How far the reversing turn grows between two admissibility checks, m.
    pub reverse_step: f64,
    /// Curvature of the reversing turn as a fraction of the maximum, so the
    /// controller keeps some steering in reserve to correct errors on it.
    pub reverse_fraction: f64,
}

impl PlanParams {
    pub fn new(max_curvature: f64) -> Self {
        PlanParams {
            max_curvature,
            allow_reverse: false,
            direction: Direction::Forward,
            spacing: 0.05,
            // A fiftieth of the turning radius, at least 5 cm: the search
            // then takes as many steps for Workpartner as for MoRo.
            reverse_step: (0.02 / max_curvature).max(0.05),
            reverse_fraction: 0.8,
        }
    }
}

/// The planned movement: segments in the order they are driven, each in a
/// single direction. The reverse-and-turn fallback has two (reversing, then
/// the Bezier), the three-point turn three.
#[derive(Clone, Debug, PartialEq)]
pub struct Plan {
    pub segments: Vec<Path>,
}

impl Plan {
    /// True when the plan starts with the reverse-and-turn manoeuvre.
    pub fn reverses_first(&self) -> bool {
        self.segments.len() == 2
    }

    /// How many cusps the plan has: 0 for the direct Bezier, 1 for the
    /// reverse-and-turn, 2 for the three-point turn.
    pub fn cusps(&self) -> usize {
        self.segments.len().saturating_sub(1)
    }

    /// All segments as one path; the joints between them are cusps.
    pub fn path(&self) -> Result<Path, PathError> {
        let (first, rest) = self.segments.split_first().ok_or(PathError::TooFewPoints)?;
        rest.iter()
            .try_fold(first.clone(), |acc, seg| acc.concat(seg, JOIN_TOLERANCE))
    }

    pub fn length(&self) -> f64 {
        self.segments.iter().map(Path::length).sum()
    }
}

#[derive(Clone, Debug, PartialEq)]
pub enum PlanError {
    Path(PathError),
    /// The maximum curvature is not a positive finite number.
    BadMaxCurvature(f64),
    /// The direct path bends more than the robot can (and reversing is not
    /// allowed or did not help); `needed` is the direct path's peak curvature.
    NoAdmissiblePath {
        needed: f64,
        max_curvature: f64,
    },
}

impl fmt::Display for PlanError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PlanError::Path(e) => write!(f, "{e}"),
            PlanError::BadMaxCurvature(c) => write!(f, "maximum curvature {c} is not usable"),
            PlanError::NoAdmissiblePath {
                needed,
                max_curvature,
            } => write!(
                f,
                "the path needs curvature {needed:.3} 1/m but the robot turns at most {max_curvature:.3} 1/m"
            ),
        }
    }
}

impl std::error::Error for PlanError {}

impl From<PathError> for PlanError {
    fn from(e: PathError) -> Self {
        PlanError::Path(e)
    }
}

/// Plans with the default spacing, driving forwards.
pub fn plan_to_pose(
    start: Pose,
    goal: Pose,
    max_curvature: f64,
    allow_reverse: bool,
) -> Result<Plan, PlanError> {
    plan_with(
        start,
        goal,
        &PlanParams {
            allow_reverse,
            ..PlanParams::new(max_curvature)
        },
    )
}

pub fn plan_with(start: Pose, goal: Pose, params: &PlanParams) -> Result<Plan, PlanError> {
    let kmax = params.max_curvature;
    if !(kmax.is_finite() && kmax > 0.0) {
        return Err(PlanError::BadMaxCurvature(kmax));
    }
    if ![start.x, start.y, start.h, goal.x, goal.y, goal.h]
        .iter()
        .all(|v| v.is_finite())
    {
        return Err(PathError::NonFinite.into());
    }
    let dir = params.direction;
    let travel = |p: Pose| match dir {
        Direction::Forward => p,
        Direction::Backward => p.flipped(),
    };
    let admissible = |k: f64| k <= kmax * (1.0 + 1e-9);
    let goal_t = travel(goal);

    let dist = (goal.position() - start.position()).norm();
    if dist < 1e-6 && angle_diff(goal.h, start.h).abs() < 1e-6 {
        let here = CubicBezier::from_poses(&travel(start), &goal_t).sample(params.spacing, dir)?;
        return Ok(Plan {
            segments: vec![here],
        });
    }

    let direct = CubicBezier::from_poses(&travel(start), &goal_t);
    let direct_k = direct.max_abs_curvature();
    if admissible(direct_k) {
        return Ok(Plan {
            segments: vec![direct.sample(params.spacing, dir)?],
        });
    }
    if !params.allow_reverse {
        return Err(PlanError::NoAdmissiblePath {
            needed: direct_k,
            max_curvature: kmax,
        });
    }
    // A millimetre is finer than any robot steers; smaller steps would only
    // make the search run for a very long time.
    if !(params.reverse_step.is_finite() && params.reverse_step >= 1e-3) {
        return Err(PathError::BadSpacing(params.reverse_step).into());
    }
    let k_rev = kmax * params.reverse_fraction.clamp(0.05, 1.0);
    // The text's manoeuvre: reverse while turning, then the Bezier.
    if let Some(plan) = reverse_then_bezier(start, goal, params, k_rev)? {
        return Ok(plan);
    }
    // A goal to the side and facing back (a U-turn narrower than the
    // turning circle) needs one more leg, as a driver's three-point turn:
    // forwards on full lock first, then the manoeuvre above from there.
    // Legs grow in coarser steps: each is a whole search of its own.
    let lead_step = (params.reverse_step * LEAD_STEPS).max(params.reverse_step);
    let max_lead = PI / k_rev;
    let leads = (max_lead / lead_step).ceil() as usize;
    for i in 1..=leads {
        let len = (i as f64 * lead_step).min(max_lead);
        for side in [1.0, -1.0] {
            let steer = side * k_rev;
            let lead = arc(start, steer * len, k_rev, dir, params.spacing)?;
            let from = lead.end_pose();
            if let Some(rest) = reverse_then_bezier(from, goal, params, k_rev)? {
                let mut segments = vec![lead];
                segments.extend(rest.segments);
                return Ok(Plan { segments });
            }
        }
    }
    Err(PlanError::NoAdmissiblePath {
        needed: direct_k,
        max_curvature: kmax,
    })
}

/// How many reverse steps one forward leg of the three-point turn grows by.
const LEAD_STEPS: f64 = 5.0;

/// An arc from `start` turning the body by `angle` at `curvature`, driven in
/// `direction`; a zero angle is a straight of no length.
fn arc(
    start: Pose,
    angle: f64,
    curvature: f64,
    direction: Direction,
    spacing: f64,
) -> Result<Path, PathError> {
    crate::path::turn(
        start,
        &crate::path::TurnSpec {
            angle,
            curvature,
            lead_in: 0.0,
            lead_out: 0.0,
        },
        direction,
        spacing,
    )
}

/// One reversing leg from `start`, as short as will do, then the Bezier to
/// `goal` in the plan's direction; `None` when no leg up to half a circle
/// (or that and the goal's distance, straight) makes the Bezier admissible.
fn reverse_then_bezier(
    start: Pose,
    goal: Pose,
    params: &PlanParams,
    k_rev: f64,
) -> Result<Option<Plan>, PlanError> {
    let dir = params.direction;
    let travel = |p: Pose| match dir {
        Direction::Forward => p,
        Direction::Backward => p.flipped(),
    };
    let kmax = params.max_curvature;
    let goal_t = travel(goal);
    // The manoeuvre drives the other way. The text has the robot turn while
    // it reverses; which way is not said, so the shortest manoeuvre wins:
    // each length is tried swinging the travel heading towards the goal's
    // bearing, then away from it, then reversing straight (the last two make
    // room for goals the first cannot reach, such as a U-turn to one side).
    let back = dir.opposite();
    let dist = (goal.position() - start.position()).norm();
    let local = travel(start).to_local(&goal.position());
    let bearing = if dist < 1e-6 {
        angle_diff(goal_t.h, travel(start).h)
    } else {
        local.y.atan2(local.x)
    };
    let towards = if bearing >= 0.0 { 1.0 } else { -1.0 };
    // Half a circle of reversing covers every heading the goal can need;
    // reversing straight may go on as far again as the goal is away, which
    // a goal beside and behind the robot needs to make room for an S-bend.
    let max_turning = PI / k_rev;
    let max_len = max_turning + dist;
    let steps = (max_len / params.reverse_step).ceil() as usize;
    for i in 1..=steps {
        let len = (i as f64 * params.reverse_step).min(max_len);
        for side in [towards, -towards, 0.0] {
            if side != 0.0 && len > max_turning {
                continue;
            }
            // Body heading change = steering * signed distance; choose the
            // steering so the heading turns towards `side`.
            let steer = side * back.sign() * k_rev;
            let turned = start.advance(back.sign() * len, steer);
            let candidate = CubicBezier::from_poses(&travel(turned), &goal_t);
            if !candidate.fits(kmax) {
                continue;
            }
            let manoeuvre = if side == 0.0 {
                crate::path::straight(start, back.sign() * len, params.spacing)?
            } else {
                arc(start, steer * len, k_rev, back, params.spacing)?
            };
            let main = candidate.sample(params.spacing, dir)?;
            return Ok(Some(Plan {
                segments: vec![manoeuvre, main],
            }));
        }
    }
    Ok(None)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reachable_goal_gives_one_forward_segment() {
        let plan = plan_to_pose(
            Pose::new(0.0, 0.0, 0.0),
            Pose::from_degrees(3.0, 4.0, 90.0),
            0.6,
            false,
        )
        .expect("admissible");
        assert_eq!(plan.segments.len(), 1);
        assert!(plan.segments[0].max_abs_curvature() <= 0.6);
    }

    #[test]
    fn too_tight_goal_without_r_is_an_error() {
        let err = plan_to_pose(
            Pose::new(0.0, 0.0, 0.0),
            Pose::from_degrees(1.0, 1.0, 180.0),
            0.25,
            false,
        )
        .expect_err("inadmissible");
        match err {
            PlanError::NoAdmissiblePath {
                needed,
                max_curvature,
            } => assert!(needed > max_curvature),
            other => panic!("unexpected {other:?}"),
        }
    }

    #[test]
    fn goal_behind_with_r_reverses_then_drives_forward() {
        let start = Pose::new(0.0, 0.0, 0.0);
        let goal = Pose::from_degrees(0.0, 3.0, 90.0);
        assert!(plan_to_pose(start, goal, 0.5, false).is_err());
        let plan = plan_to_pose(start, goal, 0.5, true).expect("fallback works");
        assert!(plan.reverses_first());
        let (manoeuvre, main) = (&plan.segments[0], &plan.segments[1]);
        assert!(
            manoeuvre
                .points()
                .iter()
                .all(|p| p.direction == Direction::Backward)
        );
        assert!(
            main.points()
                .iter()
                .all(|p| p.direction == Direction::Forward)
        );
        assert!(main.max_abs_curvature() <= 0.5 + 1e-6);
        assert!((manoeuvre.end_pose().position() - main.start_pose().position()).norm() < 1e-6);
        // The goal lies to the left, so reversing swings the nose left.
        assert!(manoeuvre.end_pose().h > 0.0);
        let joined = plan.path().expect("segments meet");
        assert!((joined.end_pose().position() - goal.position()).norm() < 1e-9);
        assert!((joined.distance_to_stop(0) - manoeuvre.length()).abs() < 1e-9);
    }

    #[test]
    fn goal_behind_the_robot_is_reached_by_reversing_first() {
        let start = Pose::new(0.0, 0.0, 0.0);
        let goal = Pose::from_degrees(-2.0, 0.0, 90.0);
        let plan = plan_to_pose(start, goal, 0.5, true).expect("reverse then forward");
        assert!(plan.reverses_first());
        assert!(plan.segments[1].max_abs_curvature() <= 0.5 + 1e-6);
    }

    #[test]
    fn a_u_turn_tighter_than_the_robot_takes_a_three_point_turn() {
        // Every pose one reversing arc reaches makes the Bezier to this goal
        // tighter still; forwards, back and forwards again it fits.
        let (start, goal) = (
            Pose::new(0.0, 0.0, 0.0),
            Pose::from_degrees(0.0, 3.0, 180.0),
        );
        let params = PlanParams {
            allow_reverse: true,
            ..PlanParams::new(0.6)
        };
        let plan = plan_with(start, goal, &params).expect("a three-point turn");
        assert_eq!(plan.cusps(), 2);
        let dirs: Vec<Direction> = plan.segments.iter().map(|s| s.first().direction).collect();
        assert_eq!(
            dirs,
            [Direction::Forward, Direction::Backward, Direction::Forward]
        );
        check_plan(&plan, start, goal, 0.6);
    }

    /// Segments meet, each keeps one direction and the curvature limit, and
    /// the whole ends on the goal pose.
    fn check_plan(plan: &Plan, start: Pose, goal: Pose, kmax: f64) {
        let path = plan.path().expect("segments meet");
        assert!((path.start_pose().position() - start.position()).norm() < 1e-9);
        assert!((path.end_pose().position() - goal.position()).norm() < 1e-6);
        assert!(angle_diff(path.end_pose().h, goal.h).abs() < 1e-3);
        for seg in &plan.segments {
            assert!(seg.max_abs_curvature() <= kmax * (1.0 + 1e-6));
            let d = seg.first().direction;
            assert!(seg.points().iter().all(|p| p.direction == d));
        }
    }

    #[test]
    fn with_r_every_goal_around_the_robot_is_reached() {
        // Goals on a grid of turning radii round the robot, facing every
        // 45 degrees. The search scales with the turning radius (its steps
        // are a fraction of it), so one curvature stands for both robots.
        // One reversing leg of at most half a circle (the fallback before
        // the three-point turn) reached 95 of these 200 goals; now 16 reverse
        // straight further and 89 take the three-point turn.
        let kmax = 0.25;
        let radius = 1.0 / kmax;
        let params = PlanParams {
            allow_reverse: true,
            reverse_step: 0.05 * radius,
            ..PlanParams::new(kmax)
        };
        let start = Pose::new(0.0, 0.0, 0.0);
        for gx in -2..=2 {
            for gy in -2..=2 {
                for gh in 0..8 {
                    let goal = Pose::new(
                        f64::from(gx) * radius,
                        f64::from(gy) * radius,
                        f64::from(gh) * std::f64::consts::FRAC_PI_4,
                    );
                    let plan = plan_with(start, goal, &params)
                        .unwrap_or_else(|e| panic!("goal {goal:?}: {e}"));
                    check_plan(&plan, start, goal, kmax);
                }
            }
        }
    }

    #[test]
    fn a_goal_straight_behind_is_a_cusp_not_a_straight_line() {
        // Collinear control points: the curve runs out and back along one
        // line; its cross product is zero but it is not drivable.
        let bz = CubicBezier::from_poses(
            &Pose::new(0.0, 0.0, 0.0),
            &Pose::from_degrees(3.0, 0.0, 180.0),
        );
        assert!(bz.max_abs_curvature() > 10.0);
    }

    #[test]
    fn same_pose_is_an_empty_movement() {
        let p = Pose::new(1.0, 2.0, 0.3);
        let plan = plan_to_pose(p, p, 0.5, false).expect("trivial");
        assert_eq!(plan.length(), 0.0);
    }

    #[test]
    fn reversing_plan_faces_the_start_heading() {
        let mut params = PlanParams::new(0.6);
        params.direction = Direction::Backward;
        let plan = plan_with(
            Pose::new(0.0, 0.0, 0.0),
            Pose::new(-3.0, -1.0, 0.0),
            &params,
        )
        .expect("admissible");
        let path = &plan.segments[0];
        assert!(
            path.points()
                .iter()
                .all(|p| p.direction == Direction::Backward)
        );
        assert!(path.start_pose().h.abs() < 1e-12);
    }

    #[test]
    fn bad_inputs_are_errors() {
        let o = Pose::new(0.0, 0.0, 0.0);
        assert_eq!(
            plan_to_pose(o, Pose::new(1.0, 0.0, 0.0), 0.0, false),
            Err(PlanError::BadMaxCurvature(0.0))
        );
        assert_eq!(
            plan_to_pose(o, Pose::new(f64::NAN, 0.0, 0.0), 0.5, false),
            Err(PlanError::Path(PathError::NonFinite))
        );
    }
}

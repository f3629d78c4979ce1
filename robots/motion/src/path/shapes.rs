//! Paths made of straight and constant-curvature pieces: `goahead(d)` and
//! `turn(d=..,c=..)`.

use super::{Direction, Path, PathError, PathPoint};
use crate::pose::Pose;

/// One piece of a trace, in the travel frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Piece {
    pub length: f64,
    /// Geometric curvature of the trace; 0 for a straight.
    pub curvature: f64,
}

/// Samples consecutive pieces starting at `start` (a travel-frame pose:
/// heading along the motion) every `spacing` metres, always including the
/// final point, for a robot moving along them in `direction`.
pub(crate) fn trace(
    start: Pose,
    pieces: &[Piece],
    direction: Direction,
    spacing: f64,
) -> Result<Path, PathError> {
    check_spacing(spacing)?;
    if !(start.x.is_finite() && start.y.is_finite() && start.h.is_finite())
        || pieces
            .iter()
            .any(|p| !p.length.is_finite() || !p.curvature.is_finite() || p.length < 0.0)
    {
        return Err(PathError::NonFinite);
    }
    // Starting pose of each piece, and where in s it begins.
    let mut starts = Vec::with_capacity(pieces.len());
    let mut pose = start;
    let mut s0 = 0.0;
    // Zero-length pieces would claim the boundary samples of their
    // neighbours (a turn without lead-out would end with curvature 0).
    let pieces: Vec<Piece> = pieces.iter().copied().filter(|p| p.length > 0.0).collect();
    for piece in &pieces {
        starts.push((s0, pose));
        pose = pose.advance(piece.length, piece.curvature);
        s0 += piece.length;
    }
    let total = s0;
    let n = (total / spacing).ceil();
    if n >= super::MAX_SAMPLES as f64 {
        return Err(PathError::BadSpacing(spacing));
    }
    let n = n as usize;
    let mut points = Vec::with_capacity(n + 1);
    let mut piece_ix = 0;
    for i in 0..=n {
        let s = (i as f64 * spacing).min(total);
        while piece_ix + 1 < pieces.len() && s >= starts[piece_ix + 1].0 {
            piece_ix += 1;
        }
        let (p, kappa) = match (pieces.get(piece_ix), starts.get(piece_ix)) {
            (Some(piece), Some(&(ps, pp))) => {
                (pp.advance(s - ps, piece.curvature), piece.curvature)
            }
            _ => (start, 0.0),
        };
        points.push(PathPoint::from_travel(
            s,
            p.position(),
            p.h,
            kappa,
            direction,
        ));
        if s >= total {
            break;
        }
    }
    Path::new(points)
}

pub(crate) fn check_spacing(spacing: f64) -> Result<(), PathError> {
    if spacing.is_finite() && spacing > 0.0 {
        Ok(())
    } else {
        Err(PathError::BadSpacing(spacing))
    }
}

/// `goahead(d)`: a straight from `start` along its heading; negative `d`
/// reverses with the body keeping its heading.
pub fn straight(start: Pose, d: f64, spacing: f64) -> Result<Path, PathError> {
    let direction = Direction::of(d);
    let travel = travel_pose(start, direction);
    trace(
        travel,
        &[Piece {
            length: d.abs(),
            curvature: 0.0,
        }],
        direction,
        spacing,
    )
}

/// The geometry of `turn(d=..,c=..)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TurnSpec {
    /// Turning angle in radians as `turn(d=..)` gives it: its sign is the
    /// steering side (positive steers left). Driving forwards the body
    /// heading changes by `angle`; reversing it changes by `-angle`, so the
    /// robot retraces the arc a forward turn would draw. Figure 52 needs
    /// this: after `goahead(1.2) turn(d=90,c=0.5) goahead(0.7)` the robot
    /// returns to its start with `speed(-0.4) goahead(-0.7)
    /// turn(d=90,c=0.5) goahead(-1.2)`.
    pub angle: f64,
    /// Magnitude of the arc's curvature, 1/m; must be positive.
    pub curvature: f64,
    /// Straight driven before the arc begins.
    pub lead_in: f64,
    /// Straight after the arc, so the controller sees where the turn leads
    /// and straightens its steering before the path ends.
    pub lead_out: f64,
}

impl TurnSpec {
    /// `turn(d=deg,c=curv)` with no straights around the arc.
    pub fn degrees(deg: f64, curvature: f64) -> Self {
        TurnSpec {
            angle: deg.to_radians(),
            curvature,
            lead_in: 0.0,
            lead_out: 0.0,
        }
    }
}

/// `turn(d=..,c=..)`: a constant-curvature arc of steering curvature
/// `±spec.curvature` (the sign of `spec.angle`) and turning angle
/// `|spec.angle|`, with optional straights before and after.
pub fn turn(
    start: Pose,
    spec: &TurnSpec,
    direction: Direction,
    spacing: f64,
) -> Result<Path, PathError> {
    if !(spec.curvature.is_finite() && spec.curvature > 0.0) {
        return Err(PathError::BadCurvature(spec.curvature));
    }
    if !spec.angle.is_finite() || spec.lead_in < 0.0 || spec.lead_out < 0.0 {
        return Err(PathError::NonFinite);
    }
    let steering = spec.curvature.copysign(spec.angle);
    let kappa = direction.sign() * steering;
    let pieces = [
        Piece {
            length: spec.lead_in,
            curvature: 0.0,
        },
        Piece {
            length: spec.angle.abs() / spec.curvature,
            curvature: kappa,
        },
        Piece {
            length: spec.lead_out,
            curvature: 0.0,
        },
    ];
    trace(travel_pose(start, direction), &pieces, direction, spacing)
}

pub(crate) fn travel_pose(body: Pose, direction: Direction) -> Pose {
    match direction {
        Direction::Forward => body,
        Direction::Backward => body.flipped(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::FRAC_PI_2;

    #[test]
    fn straight_backwards_keeps_the_body_heading() {
        let p = straight(Pose::new(1.0, 0.0, FRAC_PI_2), -0.7, 0.05).expect("valid");
        assert_eq!(p.first().direction, Direction::Backward);
        assert!((p.end_pose().y + 0.7).abs() < 1e-9);
        assert!((p.end_pose().h - FRAC_PI_2).abs() < 1e-9);
        assert!((p.length() - 0.7).abs() < 1e-9);
    }

    #[test]
    fn quarter_turn_has_the_arc_geometry() {
        let spec = TurnSpec::degrees(90.0, 0.5);
        let p = turn(Pose::new(0.0, 0.0, 0.0), &spec, Direction::Forward, 0.05).expect("valid");
        let end = p.end_pose();
        assert!((end.x - 2.0).abs() < 1e-9 && (end.y - 2.0).abs() < 1e-9);
        assert!((end.h - FRAC_PI_2).abs() < 1e-9);
        assert!((p.length() - FRAC_PI_2 / 0.5).abs() < 1e-9);
        assert!(p.points().iter().all(|q| (q.curvature - 0.5).abs() < 1e-12));
    }

    #[test]
    fn reversing_turn_steers_the_given_side_and_turns_the_other_way() {
        // TURN2 of Figure 56: speed(-0.4) turn(d=-90,c=0.25): steering
        // right while reversing swings the nose left.
        let spec = TurnSpec::degrees(-90.0, 0.25);
        let p = turn(Pose::new(0.0, 0.0, 0.0), &spec, Direction::Backward, 0.05).expect("valid");
        let end = p.end_pose();
        assert!((end.h - FRAC_PI_2).abs() < 1e-9);
        assert!((end.x + 4.0).abs() < 1e-9 && (end.y + 4.0).abs() < 1e-9);
        assert!(
            p.points()
                .iter()
                .all(|q| (q.curvature + 0.25).abs() < 1e-12)
        );
    }

    #[test]
    fn reversing_the_same_turn_retraces_the_forward_one() {
        let spec = TurnSpec::degrees(90.0, 0.5);
        let fwd = turn(Pose::new(0.0, 0.0, 0.0), &spec, Direction::Forward, 0.05).expect("valid");
        let back = turn(fwd.end_pose(), &spec, Direction::Backward, 0.05).expect("valid");
        assert!(back.end_pose().position().coords.norm() < 1e-9);
        assert!(back.end_pose().h.abs() < 1e-9);
    }

    #[test]
    fn leads_add_straights() {
        let spec = TurnSpec {
            lead_in: 0.5,
            lead_out: 1.0,
            ..TurnSpec::degrees(90.0, 0.6)
        };
        let p = turn(Pose::new(0.0, 0.0, 0.0), &spec, Direction::Forward, 0.05).expect("valid");
        assert!((p.length() - (1.5 + FRAC_PI_2 / 0.6)).abs() < 1e-9);
        assert_eq!(p.first().curvature, 0.0);
        assert_eq!(p.last().curvature, 0.0);
    }

    #[test]
    fn bad_parameters_are_errors() {
        let o = Pose::new(0.0, 0.0, 0.0);
        assert_eq!(straight(o, 1.0, 0.0), Err(PathError::BadSpacing(0.0)));
        assert_eq!(
            turn(o, &TurnSpec::degrees(90.0, 0.0), Direction::Forward, 0.05),
            Err(PathError::BadCurvature(0.0))
        );
        assert_eq!(straight(o, f64::NAN, 0.05), Err(PathError::NonFinite));
        assert_eq!(straight(o, 10.0, 1e-9), Err(PathError::BadSpacing(1e-9)));
    }
}

//! `createpath`/`followpath`: a path through waypoints whose corners are
//! rounded with circular fillets, so its curvature never exceeds the robot's.

use super::shapes::{Piece, check_spacing, trace};
use super::{Direction, Path, PathError};
use crate::pose::{Pose, angle_diff};
use nalgebra::{Point2, Vector2};

/// Waypoints closer than this are one waypoint.
const SAME_POINT: f64 = 1e-6;

/// A path through `waypoints` (straight between them), each interior corner
/// replaced by the widest fillet of radius at most `1 / max_curvature` that
/// fits: a fillet may take the whole of an end segment but only half of a
/// segment it shares with another corner. The path starts on the first
/// waypoint heading to the second and ends on the last.
///
/// Fails with `CornerTooSharp` when the segments around a corner are too
/// short for a fillet within `max_curvature`: the caller must then bring the
/// waypoints further apart or accept a larger curvature.
pub fn polyline(
    waypoints: &[Point2<f64>],
    max_curvature: f64,
    direction: Direction,
    spacing: f64,
) -> Result<Path, PathError> {
    check_spacing(spacing)?;
    if !(max_curvature.is_finite() && max_curvature > 0.0) {
        return Err(PathError::BadCurvature(max_curvature));
    }
    if waypoints
        .iter()
        .any(|p| !(p.x.is_finite() && p.y.is_finite()))
    {
        return Err(PathError::NonFinite);
    }
    // Original indices survive deduplication so errors name the user's waypoint.
    let mut pts: Vec<(usize, Point2<f64>)> = Vec::with_capacity(waypoints.len());
    for (i, p) in waypoints.iter().enumerate() {
        if pts.last().is_none_or(|(_, q)| (p - q).norm() > SAME_POINT) {
            pts.push((i, *p));
        }
    }
    if pts.len() < 2 {
        return Err(PathError::TooFewPoints);
    }
    let segs: Vec<Vector2<f64>> = pts.windows(2).map(|w| w[1].1 - w[0].1).collect();
    let lens: Vec<f64> = segs.iter().map(|v| v.norm()).collect();
    let heads: Vec<f64> = segs.iter().map(|v| v.y.atan2(v.x)).collect();
    let last_seg = segs.len() - 1;

    // For each interior vertex: signed turn angle and tangent length.
    let mut fillets = vec![(0.0, 0.0); pts.len()];
    for v in 1..pts.len() - 1 {
        let theta = angle_diff(heads[v], heads[v - 1]);
        let half = 0.5 * theta.abs();
        let tan_half = half.tan();
        if tan_half <= 1e-12 {
            continue;
        }
        let share = |seg: usize| {
            if seg == 0 || seg == last_seg {
                lens[seg]
            } else {
                0.5 * lens[seg]
            }
        };
        let t = (tan_half / max_curvature).min(share(v - 1)).min(share(v));
        let needed = tan_half / t;
        if !needed.is_finite() || needed > max_curvature * (1.0 + 1e-9) {
            return Err(PathError::CornerTooSharp {
                index: pts[v].0,
                curvature: needed,
            });
        }
        fillets[v] = (theta, t);
    }

    let mut pieces = Vec::with_capacity(2 * segs.len());
    for (i, &len) in lens.iter().enumerate() {
        let straight = (len - fillets[i].1 - fillets[i + 1].1).max(0.0);
        pieces.push(Piece {
            length: straight,
            curvature: 0.0,
        });
        let (theta, t) = fillets[i + 1];
        if t > 0.0 {
            let kappa = (0.5 * theta.abs()).tan() / t;
            pieces.push(Piece {
                length: theta.abs() / kappa,
                curvature: kappa.copysign(theta),
            });
        }
    }
    let start = Pose::new(pts[0].1.x, pts[0].1.y, heads[0]);
    trace(start, &pieces, direction, spacing)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn createpath_example_is_smooth_and_bounded() {
        // createpath(path1,0.0,0.0,5.0,1.0,6.0,5.0) from section 4.5.1.
        let wp = [
            Point2::new(0.0, 0.0),
            Point2::new(5.0, 1.0),
            Point2::new(6.0, 5.0),
        ];
        let p = polyline(&wp, 0.6, Direction::Forward, 0.05).expect("corner fits");
        assert!(p.max_abs_curvature() <= 0.6 + 1e-9);
        assert!((p.last().position() - wp[2]).norm() < 1e-9);
        // Consecutive samples never jump: the fillet is tangent to both legs.
        let pts = p.points();
        assert!(
            pts.windows(2)
                .all(|w| (w[1].position() - w[0].position()).norm() <= 0.05 + 1e-9)
        );
        let hs: Vec<f64> = pts.iter().map(|q| q.h).collect();
        assert!(
            hs.windows(2)
                .all(|w| angle_diff(w[1], w[0]).abs() <= 0.05 * 0.6 + 1e-9)
        );
    }

    #[test]
    fn a_corner_too_tight_for_the_robot_is_reported() {
        let wp = [
            Point2::new(0.0, 0.0),
            Point2::new(1.0, 0.0),
            Point2::new(1.0, 0.5),
            Point2::new(2.0, 0.5),
        ];
        match polyline(&wp, 0.25, Direction::Forward, 0.05) {
            Err(PathError::CornerTooSharp { index, curvature }) => {
                assert_eq!(index, 1);
                assert!(curvature > 0.25);
            }
            other => panic!("expected CornerTooSharp, got {other:?}"),
        }
    }

    #[test]
    fn duplicates_collapse_and_single_points_fail() {
        let same = [Point2::new(1.0, 1.0), Point2::new(1.0, 1.0)];
        assert_eq!(
            polyline(&same, 0.5, Direction::Forward, 0.05),
            Err(PathError::TooFewPoints)
        );
        let line = [
            Point2::new(0.0, 0.0),
            Point2::new(1.0, 0.0),
            Point2::new(1.0, 0.0),
            Point2::new(2.0, 0.0),
        ];
        let p = polyline(&line, 0.5, Direction::Forward, 0.05).expect("straight");
        assert!((p.length() - 2.0).abs() < 1e-9);
        assert_eq!(p.max_abs_curvature(), 0.0);
    }
}

//! Paths taught by driving (`record`) made drivable for `followpath`.
//!
//! A recorded path is the robot's own pose estimate every few centimetres:
//! dense, jittery (Workpartner's estimate jumps at each 2 Hz navigation fix)
//! and, where it was taught on full lock, bending exactly as much as the
//! robot can. A filleted polyline through every point cannot be driven: each
//! 5 cm chord of a full-lock arc needs a fillet of `tan(θ/2)/κ`, which is
//! always a little more than the half chord it may use, and the jitter makes
//! some corners far sharper. So the points are first simplified to within
//! `SIMPLIFY_TOLERANCE` of the record (Douglas-Peucker, which drops jitter
//! smaller than that), and then every corner that still cannot be rounded
//! is merged with the neighbour that crowds it, until all fit.

use super::polyline::polyline;
use super::{Direction, Path, PathError};
use crate::pose::angle_diff;
use nalgebra::Point2;

/// How far the simplified outline may leave the recorded points, m: about the
/// noise of a navigation fix, well inside the dissertation's deviations.
pub const SIMPLIFY_TOLERANCE: f64 = 0.05;

/// A recorded corner turning more than this reverses the path (the robot
/// backed up while recording); no fillet can drive it forwards.
const CUSP: f64 = 150.0 * std::f64::consts::PI / 180.0;

/// Waypoints closer than this are one waypoint (as `polyline` takes them).
const SAME_POINT: f64 = 1e-6;

/// The drivable path through a recorded outline: simplified, then with the
/// corners merged that are too crowded for a fillet within `max_curvature`.
///
/// Fails on non-finite or too few points, bad parameters, a cusp
/// (`CornerTooSharp` naming the recorded point where the path reverses), or
/// when the merged corners leave a recorded point further than a turning
/// radius away (`StraysFromRecord`): such a path was not taught by driving.
pub fn taught(
    recorded: &[Point2<f64>],
    max_curvature: f64,
    direction: Direction,
    spacing: f64,
) -> Result<Path, PathError> {
    if recorded
        .iter()
        .any(|p| !(p.x.is_finite() && p.y.is_finite()))
    {
        return Err(PathError::NonFinite);
    }
    let mut points: Vec<Point2<f64>> = Vec::with_capacity(recorded.len());
    let mut origin: Vec<usize> = Vec::with_capacity(recorded.len());
    for (i, p) in recorded.iter().enumerate() {
        if points.last().is_none_or(|q| (p - q).norm() > SAME_POINT) {
            points.push(*p);
            origin.push(i);
        }
    }
    let keep = simplify(&points, SIMPLIFY_TOLERANCE);
    let mut outline: Vec<Point2<f64>> = keep.iter().map(|&i| points[i]).collect();
    let mut names: Vec<usize> = keep.iter().map(|&i| origin[i]).collect();
    // Every merge removes a waypoint, so this ends; two points are a line.
    loop {
        match polyline(&outline, max_curvature, direction, spacing) {
            Err(PathError::CornerTooSharp { index, curvature }) => {
                if turn_at(&outline, index).abs() > CUSP {
                    return Err(PathError::CornerTooSharp {
                        index: names[index],
                        curvature,
                    });
                }
                merge(&mut outline, &mut names, index);
            }
            Ok(path) => return within_reach(path, recorded, 1.0 / max_curvature),
            Err(e) => return Err(e),
        }
    }
}

/// `path` if every recorded point lies within `reach` of it.
fn within_reach(path: Path, recorded: &[Point2<f64>], reach: f64) -> Result<Path, PathError> {
    let worst = recorded
        .iter()
        .enumerate()
        .map(|(i, p)| (i, path.distance_to(p)))
        .fold((0, 0.0), |a, b| if b.1 > a.1 { b } else { a });
    if worst.1 > reach {
        return Err(PathError::StraysFromRecord {
            index: worst.0,
            distance: worst.1,
        });
    }
    Ok(path)
}

/// Signed turn of the outline at interior vertex `v`, radians.
fn turn_at(pts: &[Point2<f64>], v: usize) -> f64 {
    if v == 0 || v + 1 >= pts.len() {
        return 0.0;
    }
    let a = pts[v] - pts[v - 1];
    let b = pts[v + 1] - pts[v];
    angle_diff(b.y.atan2(b.x), a.y.atan2(a.x))
}

/// Merges the crowded corner `v` with the vertex across its shorter side.
/// Two corners turning the same way become one at the crossing of their
/// outer legs, which keeps the total turn and the legs; an S-bend, or a
/// corner beside an end point, is straightened instead.
fn merge(pts: &mut Vec<Point2<f64>>, names: &mut Vec<usize>, v: usize) {
    let last = pts.len() - 1;
    if v == 0 || v >= last {
        return;
    }
    let before = (pts[v] - pts[v - 1]).norm();
    let after = (pts[v + 1] - pts[v]).norm();
    let u = if before <= after { v - 1 } else { v + 1 };
    if u == 0 || u == last {
        pts.remove(v);
        names.remove(v);
        return;
    }
    let (first, second) = (v.min(u), v.max(u));
    let same_way = turn_at(pts, first) * turn_at(pts, second) > 0.0;
    let joined = same_way
        .then(|| crossing(pts[first - 1], pts[first], pts[second], pts[second + 1]))
        .flatten()
        .unwrap_or_else(|| Point2::from((pts[first].coords + pts[second].coords) * 0.5));
    pts[first] = joined;
    pts.remove(second);
    names.remove(second);
}

/// Where the line a→b, continued past b, meets the line d→c continued
/// past c; `None` when they are parallel or meet behind either leg.
fn crossing(a: Point2<f64>, b: Point2<f64>, c: Point2<f64>, d: Point2<f64>) -> Option<Point2<f64>> {
    let r = b - a;
    let s = c - d;
    let denom = r.x * s.y - r.y * s.x;
    if denom.abs() < 1e-12 {
        return None;
    }
    let w = d - a;
    let t = (w.x * s.y - w.y * s.x) / denom;
    let q = (w.x * r.y - w.y * r.x) / denom;
    (t >= 1.0 && q >= 1.0).then(|| a + r * t)
}

/// Douglas-Peucker: indices of the points to keep so that every dropped
/// point lies within `tolerance` of the kept outline. Iterative, so a
/// recording of any length cannot overflow the stack.
fn simplify(pts: &[Point2<f64>], tolerance: f64) -> Vec<usize> {
    if pts.len() <= 2 {
        return (0..pts.len()).collect();
    }
    let mut keep = vec![false; pts.len()];
    keep[0] = true;
    keep[pts.len() - 1] = true;
    let mut stack = vec![(0, pts.len() - 1)];
    while let Some((i, j)) = stack.pop() {
        let mut worst = (0.0, i);
        for k in i + 1..j {
            let d = segment_distance(pts[k], pts[i], pts[j]);
            if d > worst.0 {
                worst = (d, k);
            }
        }
        if worst.0 > tolerance {
            keep[worst.1] = true;
            stack.push((i, worst.1));
            stack.push((worst.1, j));
        }
    }
    (0..pts.len()).filter(|&i| keep[i]).collect()
}

fn segment_distance(p: Point2<f64>, a: Point2<f64>, b: Point2<f64>) -> f64 {
    let ab = b - a;
    let len2 = ab.norm_squared();
    if len2 < 1e-18 {
        return (p - a).norm();
    }
    let t = ((p - a).dot(&ab) / len2).clamp(0.0, 1.0);
    (p - (a + ab * t)).norm()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::path::PathError;

    use ilmr_geometry::SplitMix64;

    /// Uniform noise in [-1, 1).
    fn noise(rng: &mut SplitMix64) -> f64 {
        2.0 * rng.uniform() - 1.0
    }

    /// What `record` keeps while a robot drives 10 m, a left quarter circle
    /// at `radius`, and 10 m: a point every 5 cm, each off by up to `jitter`.
    fn recorded(radius: f64, jitter: f64) -> Vec<Point2<f64>> {
        let mut rng = SplitMix64::new(7);
        let mut pts = Vec::new();
        let mut s = 0.0;
        let arc = radius * std::f64::consts::FRAC_PI_2;
        while s <= 20.0 + arc {
            let p = if s <= 10.0 {
                Point2::new(s, 0.0)
            } else if s <= 10.0 + arc {
                let a = (s - 10.0) / radius;
                Point2::new(10.0 + radius * a.sin(), radius * (1.0 - a.cos()))
            } else {
                Point2::new(10.0 + radius, radius + s - 10.0 - arc)
            };
            pts.push(p + nalgebra::Vector2::new(noise(&mut rng), noise(&mut rng)) * jitter);
            s += 0.05;
        }
        pts
    }

    fn farthest_from(path: &Path, pts: &[Point2<f64>]) -> f64 {
        pts.iter().map(|p| path.distance_to(p)).fold(0.0, f64::max)
    }

    #[test]
    fn a_full_lock_recording_is_drivable_and_stays_on_it() {
        // Workpartner taught a corner on full lock (radius 4 m): no fillet
        // through the raw points fits, the taught path does.
        let pts = recorded(4.0, 0.0);
        assert!(matches!(
            polyline(&pts, 0.25, Direction::Forward, 0.05),
            Err(PathError::CornerTooSharp { .. })
        ));
        let path = taught(&pts, 0.25, Direction::Forward, 0.05).expect("drivable");
        assert!(path.max_abs_curvature() <= 0.25 + 1e-9);
        let off = farthest_from(&path, &pts);
        assert!(off < 0.15, "{off}");
        assert!((path.last().position() - pts[pts.len() - 1]).norm() < 1e-9);
        assert!((path.first().position() - pts[0]).norm() < 1e-9);
    }

    #[test]
    fn navigation_jitter_is_smoothed_away() {
        let pts = recorded(6.0, 0.03);
        let path = taught(&pts, 0.25, Direction::Forward, 0.05).expect("drivable");
        assert!(path.max_abs_curvature() <= 0.25 + 1e-9);
        let off = farthest_from(&path, &pts);
        assert!(off < 0.2, "{off}");
        // The first straight stays straight: the jitter leaves kinks of a
        // degree or two at most, not a wander.
        let wander = path
            .points()
            .iter()
            .filter(|p| p.x < 8.0)
            .map(|p| p.h.abs())
            .fold(0.0, f64::max);
        assert!(wander < 3f64.to_radians(), "{}", wander.to_degrees());
    }

    #[test]
    fn a_tight_s_bend_is_straightened_within_the_robot() {
        let pts: Vec<_> = [(0.0, 0.0), (3.0, 0.0), (3.3, 0.4), (3.6, 0.0), (7.0, 0.0)]
            .iter()
            .map(|&(x, y)| Point2::new(x, y))
            .collect();
        let path = taught(&pts, 0.25, Direction::Backward, 0.05).expect("drivable");
        assert!(path.max_abs_curvature() <= 0.25 + 1e-9);
        assert!(
            path.points()
                .iter()
                .all(|p| p.direction == Direction::Backward)
        );
    }

    #[test]
    fn a_recording_that_backs_up_is_refused_at_the_cusp() {
        let pts: Vec<_> = [(0.0, 0.0), (5.0, 0.0), (2.0, 0.1)]
            .iter()
            .map(|&(x, y)| Point2::new(x, y))
            .collect();
        match taught(&pts, 0.25, Direction::Forward, 0.05) {
            Err(PathError::CornerTooSharp { index, .. }) => assert_eq!(index, 1),
            other => panic!("expected a cusp, got {other:?}"),
        }
    }

    #[test]
    fn a_spike_no_robot_could_have_driven_is_refused() {
        // A 1 m spike 0.6 m wide on MoRo (0.75 m turning radius): the
        // only drivable path cuts it and leaves its tip far away.
        let pts: Vec<_> = [(0.0, 0.0), (3.0, 0.0), (3.3, 1.0), (3.6, 0.0), (7.0, 0.0)]
            .iter()
            .map(|&(x, y)| Point2::new(x, y))
            .collect();
        match taught(&pts, 1.33, Direction::Forward, 0.05) {
            Err(PathError::StraysFromRecord { index, distance }) => {
                assert_eq!(index, 2);
                assert!(distance > 0.75, "{distance}");
            }
            other => panic!("expected StraysFromRecord, got {other:?}"),
        }
    }

    #[test]
    fn bad_input_is_an_error() {
        assert_eq!(
            taught(&[Point2::new(0.0, 0.0)], 0.25, Direction::Forward, 0.05),
            Err(PathError::TooFewPoints)
        );
        assert_eq!(
            taught(
                &[Point2::new(0.0, 0.0), Point2::new(f64::NAN, 1.0)],
                0.25,
                Direction::Forward,
                0.05
            ),
            Err(PathError::NonFinite)
        );
    }

    #[test]
    fn simplify_keeps_ends_and_corners() {
        let pts: Vec<_> = (0..=20)
            .map(|i| {
                let i = f64::from(i);
                // Along x to (5, 0), then up to (5, 5).
                Point2::new(0.5 * i.min(10.0), 0.5 * (i - 10.0).max(0.0))
            })
            .collect();
        assert_eq!(simplify(&pts, 0.01), vec![0, 10, 20]);
    }
}

//! The reference path: sampled points with arc length, body heading, steering
//! curvature and driving direction, and the queries the controller needs.
//!
//! Conventions used by every path in this crate:
//! - `h` is the heading of the robot's body (its nose), not of its motion:
//!   a robot reversing along a path faces away from where it travels.
//! - `curvature` is the steering curvature, dh/dsigma with sigma the signed
//!   odometer (positive forwards). It is what the robot's steering is set to,
//!   so it compares directly with the controller's `c_now`. A forward path
//!   bending left and a backward path whose rear swings left both have the
//!   geometric curvature of their trace equal to `direction.sign() * curvature`.
//! - `s` is the unsigned arc length from the path's first point, increasing.

mod link;
pub use link::{JOIN_TOLERANCE, LINK_REMAINING};
mod polyline;
mod shapes;
mod taught;

pub use polyline::polyline;
pub use shapes::{TurnSpec, straight, turn};
pub use taught::{SIMPLIFY_TOLERANCE, taught};

use crate::pose::{Pose, wrap_angle};
use nalgebra::Point2;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;
use std::fmt;

/// Most samples one path may have; a spacing that asks for more is refused
/// rather than exhausting memory.
pub const MAX_SAMPLES: usize = 1_000_000;

/// Which way the robot's body moves along a path.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Direction {
    Forward,
    Backward,
}

impl Direction {
    pub fn sign(self) -> f64 {
        match self {
            Direction::Forward => 1.0,
            Direction::Backward => -1.0,
        }
    }

    pub fn opposite(self) -> Direction {
        match self {
            Direction::Forward => Direction::Backward,
            Direction::Backward => Direction::Forward,
        }
    }

    /// Direction of a signed speed or distance; zero counts as forward.
    pub fn of(value: f64) -> Direction {
        if value < 0.0 {
            Direction::Backward
        } else {
            Direction::Forward
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct PathPoint {
    pub s: f64,
    pub x: f64,
    pub y: f64,
    pub h: f64,
    pub curvature: f64,
    pub direction: Direction,
}

impl PathPoint {
    /// Builds a point from its trace: where the robot travels (`travel_h`)
    /// and how that trace bends (`geometric_curvature`), for a robot that
    /// moves along it in `direction`.
    pub fn from_travel(
        s: f64,
        p: Point2<f64>,
        travel_h: f64,
        geometric_curvature: f64,
        direction: Direction,
    ) -> Self {
        let h = match direction {
            Direction::Forward => travel_h,
            Direction::Backward => travel_h + PI,
        };
        PathPoint {
            s,
            x: p.x,
            y: p.y,
            h: wrap_angle(h),
            curvature: direction.sign() * geometric_curvature,
            direction,
        }
    }

    pub fn position(&self) -> Point2<f64> {
        Point2::new(self.x, self.y)
    }

    /// Body pose of the robot standing on this point.
    pub fn pose(&self) -> Pose {
        Pose::new(self.x, self.y, self.h)
    }

    /// Heading of the motion along the path at this point.
    pub fn travel_heading(&self) -> f64 {
        match self.direction {
            Direction::Forward => self.h,
            Direction::Backward => wrap_angle(self.h + PI),
        }
    }

    /// Signed curvature of the trace with respect to the travel direction.
    pub fn geometric_curvature(&self) -> f64 {
        self.direction.sign() * self.curvature
    }
}

/// Why a path could not be built or joined.
#[derive(Clone, Debug, PartialEq)]
pub enum PathError {
    /// A path needs at least one point; a polyline at least two distinct ones.
    TooFewPoints,
    /// A coordinate, heading or parameter was NaN or infinite.
    NonFinite,
    /// Sample spacing must be positive and finite.
    BadSpacing(f64),
    /// Arc lengths must not decrease along the path.
    DecreasingArcLength { index: usize },
    /// Two paths to join do not meet: the gap between them in metres.
    Discontinuous { gap: f64 },
    /// A turn needs a positive, finite curvature.
    BadCurvature(f64),
    /// A polyline corner cannot be rounded within the robot's curvature:
    /// the corner's waypoint index and the curvature it would need.
    CornerTooSharp { index: usize, curvature: f64 },
    /// A taught path could only be made drivable by leaving its recorded
    /// point `index` this many metres away.
    StraysFromRecord { index: usize, distance: f64 },
}

impl fmt::Display for PathError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PathError::TooFewPoints => write!(f, "a path needs more points"),
            PathError::NonFinite => write!(f, "a path value is not a finite number"),
            PathError::BadSpacing(s) => write!(f, "sample spacing {s} m is not positive"),
            PathError::DecreasingArcLength { index } => {
                write!(f, "arc length decreases at point {index}")
            }
            PathError::Discontinuous { gap } => {
                write!(f, "paths to join are {gap:.3} m apart")
            }
            PathError::BadCurvature(c) => write!(f, "curvature {c} 1/m is not usable"),
            PathError::CornerTooSharp { index, curvature } => write!(
                f,
                "corner at waypoint {index} needs curvature {curvature:.3} 1/m"
            ),
            PathError::StraysFromRecord { index, distance } => write!(
                f,
                "a drivable path passes {distance:.2} m from waypoint {index}"
            ),
        }
    }
}

impl std::error::Error for PathError {}

/// A sampled reference path; never empty.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Path {
    points: Vec<PathPoint>,
}

impl Path {
    /// Validates and wraps points; arc lengths are taken as given.
    pub fn new(points: Vec<PathPoint>) -> Result<Path, PathError> {
        if points.is_empty() {
            return Err(PathError::TooFewPoints);
        }
        for (i, p) in points.iter().enumerate() {
            if ![p.s, p.x, p.y, p.h, p.curvature]
                .iter()
                .all(|v| v.is_finite())
            {
                return Err(PathError::NonFinite);
            }
            if i > 0 && p.s < points[i - 1].s {
                return Err(PathError::DecreasingArcLength { index: i });
            }
        }
        Ok(Path { points })
    }

    pub fn points(&self) -> &[PathPoint] {
        &self.points
    }

    pub fn first(&self) -> &PathPoint {
        &self.points[0]
    }

    pub fn last(&self) -> &PathPoint {
        &self.points[self.points.len() - 1]
    }

    pub fn start_pose(&self) -> Pose {
        self.first().pose()
    }

    pub fn end_pose(&self) -> Pose {
        self.last().pose()
    }

    /// Total arc length in metres.
    pub fn length(&self) -> f64 {
        self.last().s - self.first().s
    }

    pub fn max_abs_curvature(&self) -> f64 {
        self.points
            .iter()
            .map(|p| p.curvature.abs())
            .fold(0.0, f64::max)
    }

    /// Clamps an index into the path.
    pub fn clamp_index(&self, k: usize) -> usize {
        k.min(self.points.len() - 1)
    }

    /// Arc length left from point `k` to the end.
    pub fn remaining(&self, k: usize) -> f64 {
        self.last().s - self.points[self.clamp_index(k)].s
    }

    /// Arc length left from `p`, standing near point `k`: `remaining(k)`
    /// corrected by how far `p` is ahead of (or behind) point `k` along the
    /// path, so braking does not see the steps of the sampling.
    pub fn remaining_from(&self, k: usize, p: &Point2<f64>) -> f64 {
        let k = self.clamp_index(k);
        let q = &self.points[k];
        let t = q.travel_heading();
        let ahead = (p - q.position()).dot(&nalgebra::Vector2::new(t.cos(), t.sin()));
        (self.remaining(k) - ahead).max(0.0)
    }

    /// Arc length from point `k` to where the robot has to stand still: the
    /// next change of driving direction, or the end.
    pub fn distance_to_stop(&self, k: usize) -> f64 {
        self.distance_to_stop_from(k, None)
    }

    /// [`Path::distance_to_stop`] refined by the robot's position `p` near
    /// point `k`, as [`Path::remaining_from`] refines `remaining`.
    pub fn distance_to_stop_from(&self, k: usize, p: Option<&Point2<f64>>) -> f64 {
        let k = self.clamp_index(k);
        let dir = self.points[k].direction;
        let stop = self.points[k..]
            .iter()
            .find(|p| p.direction != dir)
            .map_or(self.last().s, |p| p.s);
        let ahead = match p {
            Some(p) => self.remaining(k) - self.remaining_from(k, p),
            None => 0.0,
        };
        (stop - self.points[k].s - ahead).max(0.0)
    }

    /// Closest point to `p`, searched only forwards from `k` and only within
    /// `window` metres of arc length, so the index never runs backwards and
    /// never jumps to a later pass of a path that crosses itself.
    pub fn closest_index(&self, p: &Point2<f64>, k: usize, window: f64) -> usize {
        let k = self.clamp_index(k);
        let s_limit = self.points[k].s + window.max(0.0);
        let mut best = k;
        let mut best_d = f64::INFINITY;
        for (j, q) in self.points.iter().enumerate().skip(k) {
            if q.s > s_limit {
                break;
            }
            let d = (q.position() - p).norm_squared();
            if d < best_d {
                best_d = d;
                best = j;
            }
        }
        best
    }

    /// Shortest distance from `p` to the path's polyline.
    pub fn distance_to(&self, p: &Point2<f64>) -> f64 {
        if self.points.len() == 1 {
            return (self.first().position() - p).norm();
        }
        self.points
            .windows(2)
            .map(|w| segment_distance(p, &w[0].position(), &w[1].position()))
            .fold(f64::INFINITY, f64::min)
    }

    /// Shortest distance from `p` to the stretch of the path from index `k`
    /// to `reach` metres on (to the end if that comes first).
    pub fn distance_to_stretch(&self, p: &Point2<f64>, k: usize, reach: f64) -> f64 {
        let k = self.clamp_index(k);
        let s_end = self.points[k].s + reach.max(0.0);
        let stretch = &self.points[k..];
        let n = stretch.iter().take_while(|q| q.s <= s_end).count().max(1);
        // One point past the reach closes the last segment.
        let stretch = &stretch[..(n + 1).min(stretch.len())];
        if stretch.len() == 1 {
            return (stretch[0].position() - p).norm();
        }
        stretch
            .windows(2)
            .map(|w| segment_distance(p, &w[0].position(), &w[1].position()))
            .fold(f64::INFINITY, f64::min)
    }

    /// True once `p` lies at or beyond the end, measured along the final
    /// travel direction: the test that ends a movement command even when
    /// the robot passes beside the last point rather than over it.
    pub fn passed_end(&self, p: &Point2<f64>) -> bool {
        let end = self.last();
        let t = end.travel_heading();
        let d = p - end.position();
        d.x * t.cos() + d.y * t.sin() >= 0.0
    }

    /// First index from which at most `remaining` metres are left.
    pub fn index_at_remaining(&self, remaining: f64) -> usize {
        let s_cut = self.last().s - remaining.max(0.0);
        self.points
            .iter()
            .position(|p| p.s >= s_cut)
            .unwrap_or(self.points.len() - 1)
    }
}

/// Distance from `p` to the segment `a`-`b`.
pub(crate) fn segment_distance(p: &Point2<f64>, a: &Point2<f64>, b: &Point2<f64>) -> f64 {
    let ab = b - a;
    let len2 = ab.norm_squared();
    if len2 <= f64::EPSILON {
        return (p - a).norm();
    }
    let t = ((p - a).dot(&ab) / len2).clamp(0.0, 1.0);
    (p - (a + ab * t)).norm()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line(n: usize, spacing: f64) -> Path {
        straight(Pose::new(0.0, 0.0, 0.0), spacing * n as f64, spacing).expect("valid line")
    }

    #[test]
    fn empty_or_non_finite_paths_are_rejected() {
        assert_eq!(Path::new(vec![]), Err(PathError::TooFewPoints));
        let mut p = PathPoint::from_travel(0.0, Point2::origin(), 0.0, 0.0, Direction::Forward);
        p.x = f64::NAN;
        assert_eq!(Path::new(vec![p]), Err(PathError::NonFinite));
    }

    #[test]
    fn closest_index_is_monotone_and_windowed() {
        let path = line(100, 0.05);
        let k = path.closest_index(&Point2::new(1.0, 0.3), 0, 3.0);
        assert_eq!(k, 20);
        // A point behind the current index does not pull k back.
        assert_eq!(path.closest_index(&Point2::new(0.2, 0.0), k, 3.0), k);
        // The window stops the search from jumping far ahead.
        assert_eq!(path.closest_index(&Point2::new(4.0, 0.0), 0, 1.0), 20);
    }

    #[test]
    fn remaining_and_index_at_remaining_agree() {
        let path = line(40, 0.05);
        let j = path.index_at_remaining(0.5);
        assert!((path.remaining(j) - 0.5).abs() < 1e-9);
    }

    #[test]
    fn passed_end_uses_the_travel_direction() {
        let fwd = line(20, 0.05);
        assert!(!fwd.passed_end(&Point2::new(0.9, 0.2)));
        assert!(fwd.passed_end(&Point2::new(1.01, 0.2)));
        let back = straight(Pose::new(0.0, 0.0, 0.0), -1.0, 0.05).expect("valid");
        assert!(!back.passed_end(&Point2::new(-0.9, 0.0)));
        assert!(back.passed_end(&Point2::new(-1.05, 0.0)));
    }

    #[test]
    fn distance_to_stop_ends_at_a_cusp() {
        let fwd = line(20, 0.05);
        let back = straight(fwd.end_pose(), -0.5, 0.05).expect("valid");
        let joined = fwd.concat(&back, 1e-6).expect("touching paths");
        assert!((joined.distance_to_stop(0) - 1.0).abs() < 1e-9);
        assert!((joined.length() - 1.5).abs() < 1e-9);
    }
}

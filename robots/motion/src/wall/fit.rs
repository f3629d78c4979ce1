//! Fitting the wall on one side of the robot: a Hough-like vote over
//! directions near the robot's heading and offsets from it, refined by total
//! least squares on the winning line's inliers. Door openings only remove
//! votes, and points seen through them lie on other offsets, so neither
//! moves the line.

use crate::pose::{Pose, Side};
use nalgebra::{Matrix2, Point2, SymmetricEigen, Unit, Vector2};
use serde::{Deserialize, Serialize};
use std::fmt;

#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct WallParams {
    /// Points considered: from `behind` metres behind to `ahead` metres in
    /// front of the robot, `min_offset` to `max_offset` metres to the side.
    pub behind: f64,
    pub ahead: f64,
    pub min_offset: f64,
    pub max_offset: f64,
    /// Directions tried: within ± this of the robot's heading, radians.
    pub max_angle: f64,
    pub angle_step: f64,
    /// Width of an offset bin in the vote, m.
    pub bin: f64,
    /// Distance within which a point belongs to the line, m.
    pub inlier_tolerance: f64,
    /// Fewer inliers than this is no wall.
    pub min_inliers: usize,
}

impl Default for WallParams {
    fn default() -> Self {
        WallParams {
            behind: 2.0,
            ahead: 4.0,
            min_offset: 0.2,
            max_offset: 4.0,
            max_angle: 40f64.to_radians(),
            angle_step: 1f64.to_radians(),
            bin: 0.05,
            inlier_tolerance: 0.08,
            min_inliers: 8,
        }
    }
}

/// A wall as an infinite line in world coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WallLine {
    /// A point on the line (the inliers' centroid).
    pub point: Point2<f64>,
    /// Unit direction, pointing the way the robot faced when it was fitted.
    pub direction: Unit<Vector2<f64>>,
    pub inliers: usize,
    /// Root mean square distance of the inliers from the line, m.
    pub rms: f64,
}

impl WallLine {
    /// Foot of the perpendicular from `p`.
    pub fn project(&self, p: &Point2<f64>) -> Point2<f64> {
        self.point + self.direction.into_inner() * (p - self.point).dot(&self.direction)
    }

    /// Signed distance, positive when `p` is to the left of the direction.
    pub fn signed_distance(&self, p: &Point2<f64>) -> f64 {
        self.direction.perp(&(p - self.point))
    }

    pub fn heading(&self) -> f64 {
        self.direction.y.atan2(self.direction.x)
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WallError {
    /// Too few points on that side to call anything a wall.
    NoWall {
        points: usize,
    },
    BadParams,
}

impl fmt::Display for WallError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            WallError::NoWall { points } => write!(f, "no wall: {points} points on that side"),
            WallError::BadParams => write!(f, "wall fitting parameters are not usable"),
        }
    }
}

impl std::error::Error for WallError {}

/// The wall on `side` of a robot at `pose`, from map points in world
/// coordinates.
pub fn fit_wall(
    pose: &Pose,
    points: &[Point2<f64>],
    side: Side,
    params: &WallParams,
) -> Result<WallLine, WallError> {
    let angles = params.max_angle / params.angle_step;
    if !(params.bin > 0.0
        && params.angle_step > 0.0
        && params.max_angle >= 0.0
        && params.inlier_tolerance > 0.0
        && angles <= 10_000.0)
    {
        return Err(WallError::BadParams);
    }
    let sign = side.sign();
    let local: Vec<Point2<f64>> = points
        .iter()
        .map(|p| pose.to_local(p))
        .filter(|p| {
            p.x >= -params.behind
                && p.x <= params.ahead
                && sign * p.y >= params.min_offset
                && sign * p.y <= params.max_offset
        })
        .collect();
    if local.len() < params.min_inliers.max(2) {
        return Err(WallError::NoWall {
            points: local.len(),
        });
    }

    // Vote: for each direction, count points per offset bin (two adjacent
    // bins together, so a wall straddling a bin edge is not split). Best
    // count wins; ties go to the nearer wall, then the smaller angle.
    let steps = angles.floor() as i64;
    let mut best: Option<Vote> = None;
    let mut bins: Vec<(i64, usize)> = Vec::new();
    for i in -steps..=steps {
        let angle = i as f64 * params.angle_step;
        let normal = Vector2::new(-angle.sin(), angle.cos());
        bins.clear();
        let mut keys: Vec<i64> = local
            .iter()
            .map(|p| (p.coords.dot(&normal) / params.bin).floor() as i64)
            .collect();
        keys.sort_unstable();
        for key in keys {
            match bins.last_mut() {
                Some((k, n)) if *k == key => *n += 1,
                _ => bins.push((key, 1)),
            }
        }
        for (j, &(key, n)) in bins.iter().enumerate() {
            let pair = n + bins
                .get(j + 1)
                .filter(|(k, _)| *k == key + 1)
                .map_or(0, |(_, m)| *m);
            let offset = (key as f64 + 1.0) * params.bin;
            let candidate = Vote {
                count: pair,
                offset,
                angle,
            };
            if best.is_none_or(|b| candidate.beats(&b)) {
                best = Some(candidate);
            }
        }
    }
    let Some(Vote { offset, angle, .. }) = best else {
        return Err(WallError::NoWall {
            points: local.len(),
        });
    };
    let normal = Vector2::new(-angle.sin(), angle.cos());
    let coarse: Vec<Point2<f64>> = local
        .iter()
        .filter(|p| (p.coords.dot(&normal) - offset).abs() <= params.bin + params.inlier_tolerance)
        .copied()
        .collect();
    let (c, d) = total_least_squares(&coarse).ok_or(WallError::NoWall {
        points: coarse.len(),
    })?;
    // One more pass with the exact line and the real tolerance.
    let inliers: Vec<Point2<f64>> = local
        .iter()
        .filter(|p| d.perp(&(*p - c)).abs() <= params.inlier_tolerance)
        .copied()
        .collect();
    if inliers.len() < params.min_inliers.max(2) {
        return Err(WallError::NoWall {
            points: inliers.len(),
        });
    }
    let (c, mut d) = total_least_squares(&inliers).ok_or(WallError::NoWall {
        points: inliers.len(),
    })?;
    if d.x < 0.0 {
        d = -d;
    }
    let rms = (inliers
        .iter()
        .map(|p| d.perp(&(p - c)).powi(2))
        .sum::<f64>()
        / inliers.len() as f64)
        .sqrt();
    let world_dir = {
        let (s, co) = pose.h.sin_cos();
        Vector2::new(co * d.x - s * d.y, s * d.x + co * d.y)
    };
    Ok(WallLine {
        point: pose.to_world(&c),
        direction: Unit::new_normalize(world_dir),
        inliers: inliers.len(),
        rms,
    })
}

/// One line in the vote: how many points lie near it, and where it is.
#[derive(Clone, Copy, Debug)]
struct Vote {
    count: usize,
    offset: f64,
    angle: f64,
}

impl Vote {
    /// More points wins; then the nearer wall; then the smaller angle.
    fn beats(&self, other: &Vote) -> bool {
        let (o, p) = (self.offset.abs(), other.offset.abs());
        self.count > other.count
            || (self.count == other.count
                && (o < p - 1e-12 || (o <= p + 1e-12 && self.angle.abs() < other.angle.abs())))
    }
}

/// Centroid and unit direction of the best-fitting line (principal axis).
fn total_least_squares(points: &[Point2<f64>]) -> Option<(Point2<f64>, Unit<Vector2<f64>>)> {
    if points.len() < 2 {
        return None;
    }
    let n = points.len() as f64;
    let c = points
        .iter()
        .fold(Vector2::zeros(), |acc, p| acc + p.coords)
        / n;
    let mut m = Matrix2::zeros();
    for p in points {
        let d = p.coords - c;
        m += d * d.transpose();
    }
    let eig = SymmetricEigen::new(m);
    let i = if eig.eigenvalues[0] >= eig.eigenvalues[1] {
        0
    } else {
        1
    };
    let v: Vector2<f64> = eig.eigenvectors.column(i).into_owned();
    (v.norm() > 0.0).then(|| (Point2::from(c), Unit::new_normalize(v)))
}

#[cfg(test)]
mod tests {
    use super::*;

    use ilmr_geometry::SplitMix64;

    fn noise(rng: &mut SplitMix64, amp: f64) -> f64 {
        amp * (2.0 * rng.uniform() - 1.0)
    }

    /// A wall at y = 1.2 tilted by 5 degrees, 2 cm noise, a 1 m door
    /// opening, and the room behind the door seen through it.
    fn corridor() -> Vec<Point2<f64>> {
        let mut rng = SplitMix64::new(7);
        let tilt = 5f64.to_radians().tan();
        let mut pts = vec![];
        for i in 0..120 {
            let x = -2.0 + i as f64 * 0.05;
            if (0.5..1.5).contains(&x) {
                // Through the door: the far wall of the room, 3 m further.
                pts.push(Point2::new(x, 4.2 + noise(&mut rng, 0.02)));
                continue;
            }
            pts.push(Point2::new(x, 1.2 + x * tilt + noise(&mut rng, 0.02)));
        }
        pts
    }

    #[test]
    fn fits_a_noisy_wall_with_a_door_opening() {
        let pose = Pose::new(0.0, 0.0, 0.0);
        let wall = fit_wall(&pose, &corridor(), Side::Left, &WallParams::default()).expect("wall");
        assert!(
            (wall.heading() - 5f64.to_radians()).abs() < 0.01,
            "heading {}",
            wall.heading()
        );
        let d = -wall.signed_distance(&pose.position());
        assert!(
            (d - 1.2 * 5f64.to_radians().cos()).abs() < 0.01,
            "distance {d}"
        );
        assert!(wall.rms < 0.02);
        assert!(wall.inliers >= 90);
    }

    #[test]
    fn the_other_side_has_no_wall() {
        let pose = Pose::new(0.0, 0.0, 0.0);
        assert!(matches!(
            fit_wall(&pose, &corridor(), Side::Right, &WallParams::default()),
            Err(WallError::NoWall { points: 0 })
        ));
    }

    #[test]
    fn fitting_works_in_any_robot_frame() {
        let pose = Pose::from_degrees(3.0, -2.0, 130.0);
        let pts: Vec<Point2<f64>> = corridor().iter().map(|p| pose.to_world(p)).collect();
        let wall = fit_wall(&pose, &pts, Side::Left, &WallParams::default()).expect("wall");
        let expected = 130f64.to_radians() + 5f64.to_radians();
        assert!(crate::pose::angle_diff(wall.heading(), expected).abs() < 0.01);
    }
}

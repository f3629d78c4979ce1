//! Planar pose of a robot and the angle helpers every other module relies on.

use nalgebra::{Point2, Vector2};
use serde::{Deserialize, Serialize};
use std::f64::consts::{PI, TAU};

/// Position in metres and heading in radians, counter-clockwise from the x axis.
///
/// The heading is always kept in (-pi, pi] so that poses compare and print the
/// same way whichever computation produced them.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Pose {
    pub x: f64,
    pub y: f64,
    pub h: f64,
}

impl Pose {
    pub fn new(x: f64, y: f64, h: f64) -> Self {
        Pose {
            x,
            y,
            h: normalize_angle(h),
        }
    }

    /// Heading given in degrees, as ILMR commands write it (`gotoxy(3,4,180)`).
    pub fn from_degrees(x: f64, y: f64, h_deg: f64) -> Self {
        Pose::new(x, y, h_deg.to_radians())
    }

    pub fn position(&self) -> Point2<f64> {
        Point2::new(self.x, self.y)
    }

    /// Unit vector the robot's nose points along.
    pub fn heading_vector(&self) -> Vector2<f64> {
        Vector2::new(self.h.cos(), self.h.sin())
    }

    pub fn distance_to(&self, p: &Point2<f64>) -> f64 {
        (p - self.position()).norm()
    }

    /// Expresses a world point in the robot frame: x forward, y to the left.
    pub fn to_local(&self, p: &Point2<f64>) -> Point2<f64> {
        let d = p - self.position();
        let (s, c) = self.h.sin_cos();
        Point2::new(c * d.x + s * d.y, -s * d.x + c * d.y)
    }

    /// Inverse of [`Pose::to_local`].
    pub fn to_world(&self, p: &Point2<f64>) -> Point2<f64> {
        let (s, c) = self.h.sin_cos();
        Point2::new(self.x + c * p.x - s * p.y, self.y + s * p.x + c * p.y)
    }

    /// The same place with the nose turned around: a robot driving backwards
    /// travels along this pose's heading.
    pub fn flipped(&self) -> Pose {
        Pose::new(self.x, self.y, self.h + PI)
    }

    /// Moves along a circular arc of signed `curvature` (1/m, positive turns
    /// left) for the signed distance `ds` (negative drives backwards).
    ///
    /// Exact for constant curvature, so integrators and predictors built on
    /// it do not accumulate the drift of an Euler step.
    pub fn advance(&self, ds: f64, curvature: f64) -> Pose {
        let dh = ds * curvature;
        let (dx, dy) = if dh.abs() < 1e-9 {
            // Second-order series of the arc chord; avoids 0/0 on straights.
            let mid = self.h + 0.5 * dh;
            (ds * mid.cos(), ds * mid.sin())
        } else {
            let r = 1.0 / curvature;
            (
                r * ((self.h + dh).sin() - self.h.sin()),
                -r * ((self.h + dh).cos() - self.h.cos()),
            )
        };
        Pose::new(self.x + dx, self.y + dy, self.h + dh)
    }
}

/// A side of the robot, as `followwall(left)` or `turn(right)` name it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Side {
    Left,
    Right,
}

impl Side {
    /// +1 for left (the positive y of the robot frame), -1 for right.
    pub fn sign(self) -> f64 {
        match self {
            Side::Left => 1.0,
            Side::Right => -1.0,
        }
    }

    pub fn opposite(self) -> Side {
        match self {
            Side::Left => Side::Right,
            Side::Right => Side::Left,
        }
    }
}

/// Wraps an angle into (-pi, pi].
pub fn normalize_angle(a: f64) -> f64 {
    if !a.is_finite() {
        return a;
    }
    let mut r = a.rem_euclid(TAU);
    if r > PI {
        r -= TAU;
    }
    r
}

/// Signed smallest rotation that takes heading `from` to heading `to`.
pub fn angle_diff(to: f64, from: f64) -> f64 {
    normalize_angle(to - from)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normalisation_keeps_pi_and_maps_minus_pi_to_pi() {
        assert_eq!(normalize_angle(PI), PI);
        assert!((normalize_angle(-PI) - PI).abs() < 1e-12);
        assert!((normalize_angle(3.0 * PI) - PI).abs() < 1e-12);
        assert!((normalize_angle(-0.5 * PI) + 0.5 * PI).abs() < 1e-12);
        assert!((normalize_angle(7.0) - (7.0 - TAU)).abs() < 1e-12);
    }

    #[test]
    fn angle_diff_takes_the_short_way_round() {
        let d = angle_diff((-170.0f64).to_radians(), 170.0f64.to_radians());
        assert!((d - 20.0f64.to_radians()).abs() < 1e-12);
    }

    #[test]
    fn local_and_world_frames_are_inverse() {
        let p = Pose::from_degrees(1.0, 2.0, 30.0);
        let w = Point2::new(-0.3, 4.5);
        let back = p.to_world(&p.to_local(&w));
        assert!((back - w).norm() < 1e-12);
        let ahead = p.to_local(&(p.position() + p.heading_vector()));
        assert!((ahead - Point2::new(1.0, 0.0)).norm() < 1e-12);
    }

    #[test]
    fn quarter_circle_advance_lands_on_the_circle() {
        let p = Pose::new(0.0, 0.0, 0.0);
        let c = 0.5;
        let q = p.advance(PI / 2.0 / c, c);
        assert!((q.x - 2.0).abs() < 1e-12 && (q.y - 2.0).abs() < 1e-12);
        assert!((q.h - PI / 2.0).abs() < 1e-12);
        let back = q.advance(-PI / 2.0 / c, c);
        assert!(back.x.abs() < 1e-12 && back.y.abs() < 1e-12 && back.h.abs() < 1e-12);
    }

    #[test]
    fn straight_advance_backwards() {
        let q = Pose::new(1.0, 1.0, PI / 2.0).advance(-0.5, 0.0);
        assert!((q.x - 1.0).abs() < 1e-12 && (q.y - 0.5).abs() < 1e-12);
    }
}

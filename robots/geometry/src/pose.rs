//! The planar pose of a robot, a goal or a frame, as every layer speaks of it.

use nalgebra::{Point2, Vector2};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

use crate::angle::wrap_angle;

/// Position in metres and heading in radians, counter-clockwise from the x axis.
///
/// [`Pose::new`] keeps the heading in (-pi, pi] so that poses compare and print
/// the same way whichever computation produced them. A pose written field by
/// field keeps the heading it is given: a heading read from outside (a trace's
/// rounded number, a frame's sum of two headings) may lie beyond a half turn,
/// and [`Pose::wrapped`] folds it where an algorithm needs it folded.
#[derive(Clone, Copy, Debug, PartialEq, Default, Serialize, Deserialize)]
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
            h: wrap_angle(h),
        }
    }

    /// Heading given in degrees, as ILMR commands write it (`gotoxy(3,4,180)`).
    pub fn from_degrees(x: f64, y: f64, h_deg: f64) -> Self {
        Pose::new(x, y, h_deg.to_radians())
    }

    /// The same pose with its heading folded into (-pi, pi]; bit for bit the same
    /// pose when it already is.
    pub fn wrapped(self) -> Pose {
        Pose::new(self.x, self.y, self.h)
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

    /// `self` followed by `other` expressed in `self`'s frame.
    pub fn compose(&self, other: Pose) -> Pose {
        let p = self.to_world(&other.position());
        Pose::new(p.x, p.y, self.h + other.h)
    }

    /// The pose that maps `self` back to the origin.
    pub fn inverse(&self) -> Pose {
        let (s, c) = self.h.sin_cos();
        Pose::new(-(c * self.x + s * self.y), s * self.x - c * self.y, -self.h)
    }

    pub fn is_finite(&self) -> bool {
        self.x.is_finite() && self.y.is_finite() && self.h.is_finite()
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn new_folds_the_heading_and_a_literal_keeps_it() {
        assert_eq!(Pose::new(0.0, 0.0, -PI).h, PI);
        assert!((Pose::new(0.0, 0.0, 1.5 * PI).h + 0.5 * PI).abs() < 1e-12);
        let outside = Pose {
            x: 1.0,
            y: 2.0,
            h: 3.2,
        };
        assert_eq!(outside.h, 3.2);
        assert!((outside.wrapped().h - (3.2 - std::f64::consts::TAU)).abs() < 1e-12);
        let inside = Pose::new(1.0, 2.0, -0.3);
        assert_eq!(inside.wrapped(), inside);
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
    fn compose_with_inverse_is_identity() {
        let p = Pose::new(1.5, -2.0, 0.7);
        let id = p.compose(p.inverse());
        assert!(id.x.abs() < 1e-12 && id.y.abs() < 1e-12 && id.h.abs() < 1e-12);
        let q = Pose::new(0.5, 0.25, -2.0);
        let there = p.compose(q);
        assert!((there.position() - p.to_world(&q.position())).norm() < 1e-15);
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

    #[test]
    fn non_finite_parts_are_seen() {
        assert!(Pose::new(1.0, 2.0, 3.0).is_finite());
        assert!(!Pose::new(f64::NAN, 2.0, 3.0).is_finite());
        assert!(!Pose::new(1.0, 2.0, f64::INFINITY).is_finite());
    }
}

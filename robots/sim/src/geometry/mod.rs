//! Plane geometry: vectors and poses, the two solid shapes (circles and oriented
//! boxes), exact ray casting and overlap tests, and the scene that holds every
//! solid of a world.

mod fan;
mod index;
mod scene;
mod shapes;

pub use fan::Fan;
pub use scene::{Hit, Scene, Solid, SolidRef};
pub use shapes::{Circle, Obb, Shape};

use serde::{Deserialize, Serialize};
use std::f64::consts::{PI, TAU};

/// A point or direction in the world plane, metres.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Vec2 {
    pub x: f64,
    pub y: f64,
}

impl Vec2 {
    pub const ZERO: Vec2 = Vec2 { x: 0.0, y: 0.0 };

    pub const fn new(x: f64, y: f64) -> Self {
        Vec2 { x, y }
    }

    /// Unit vector at angle `a` (radians, counter-clockwise from +x).
    pub fn from_angle(a: f64) -> Self {
        let (s, c) = a.sin_cos();
        Vec2 { x: c, y: s }
    }

    pub fn dot(self, o: Vec2) -> f64 {
        self.x * o.x + self.y * o.y
    }

    /// z component of the 3D cross product: positive when `o` is to the left.
    pub fn cross(self, o: Vec2) -> f64 {
        self.x * o.y - self.y * o.x
    }

    pub fn length(self) -> f64 {
        self.x.hypot(self.y)
    }

    pub fn length_sq(self) -> f64 {
        self.dot(self)
    }

    pub fn distance(self, o: Vec2) -> f64 {
        (self - o).length()
    }

    pub fn scale(self, k: f64) -> Vec2 {
        Vec2::new(self.x * k, self.y * k)
    }

    /// Rotated counter-clockwise by 90 degrees.
    pub fn perp(self) -> Vec2 {
        Vec2::new(-self.y, self.x)
    }

    pub fn angle(self) -> f64 {
        self.y.atan2(self.x)
    }

    pub fn is_finite(self) -> bool {
        self.x.is_finite() && self.y.is_finite()
    }
}

impl std::ops::Add for Vec2 {
    type Output = Vec2;
    fn add(self, o: Vec2) -> Vec2 {
        Vec2::new(self.x + o.x, self.y + o.y)
    }
}

impl std::ops::Sub for Vec2 {
    type Output = Vec2;
    fn sub(self, o: Vec2) -> Vec2 {
        Vec2::new(self.x - o.x, self.y - o.y)
    }
}

impl std::ops::Neg for Vec2 {
    type Output = Vec2;
    fn neg(self) -> Vec2 {
        Vec2::new(-self.x, -self.y)
    }
}

/// A robot posture (x, y, h): position in metres and heading in radians,
/// counter-clockwise from +x, kept in (-pi, pi].
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
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

    pub fn position(self) -> Vec2 {
        Vec2::new(self.x, self.y)
    }

    pub fn heading(self) -> Vec2 {
        Vec2::from_angle(self.h)
    }

    /// A point given in this pose's frame (x forward, y left), in world coordinates.
    pub fn transform(self, local: Vec2) -> Vec2 {
        let (s, c) = self.h.sin_cos();
        Vec2::new(
            self.x + c * local.x - s * local.y,
            self.y + s * local.x + c * local.y,
        )
    }

    /// A world point in this pose's frame (x forward, y left).
    pub fn inverse_transform(self, world: Vec2) -> Vec2 {
        let (s, c) = self.h.sin_cos();
        let d = world - self.position();
        Vec2::new(c * d.x + s * d.y, -s * d.x + c * d.y)
    }

    /// `self` followed by `other` expressed in `self`'s frame.
    pub fn compose(self, other: Pose) -> Pose {
        let p = self.transform(other.position());
        Pose::new(p.x, p.y, self.h + other.h)
    }

    /// The pose that maps `self` back to the origin.
    pub fn inverse(self) -> Pose {
        let (s, c) = self.h.sin_cos();
        Pose::new(-(c * self.x + s * self.y), s * self.x - c * self.y, -self.h)
    }

    pub fn is_finite(self) -> bool {
        self.x.is_finite() && self.y.is_finite() && self.h.is_finite()
    }
}

/// An angle folded into (-pi, pi].
pub fn wrap_angle(a: f64) -> f64 {
    if a > -PI && a <= PI {
        return a;
    }
    let r = a.rem_euclid(TAU);
    if r > PI { r - TAU } else { r }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrap_angle_folds_into_half_open_range() {
        assert_eq!(wrap_angle(PI), PI);
        assert!((wrap_angle(-PI) - PI).abs() < 1e-12);
        assert!((wrap_angle(3.0 * PI / 2.0) + PI / 2.0).abs() < 1e-12);
        assert!((wrap_angle(-5.0 * TAU + 0.25) - 0.25).abs() < 1e-9);
    }

    #[test]
    fn compose_with_inverse_is_identity() {
        let p = Pose::new(1.5, -2.0, 0.7);
        let id = p.compose(p.inverse());
        assert!(id.x.abs() < 1e-12 && id.y.abs() < 1e-12 && id.h.abs() < 1e-12);
        let w = Vec2::new(3.0, 4.0);
        let back = p.transform(p.inverse_transform(w));
        assert!(back.distance(w) < 1e-12);
    }
}

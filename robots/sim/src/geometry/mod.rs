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

pub use ilmr_geometry::wrap_angle;
use serde::{Deserialize, Serialize};

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

/// The pose the simulator shares with the HAL and the motion code (ilmr-geometry's).
pub use ilmr_geometry::Pose;

/// A pose as a frame of the simulator's plane, in its [`Vec2`]: the simulator's
/// shapes and sensors still compute in `Vec2`, where the other layers use
/// nalgebra's points and vectors. Each is the same arithmetic as
/// [`Pose::to_world`] and [`Pose::to_local`].
pub trait Frame {
    fn origin(self) -> Vec2;
    /// Unit vector along the heading.
    fn heading(self) -> Vec2;
    /// A point given in this pose's frame (x forward, y left), in world coordinates.
    fn transform(self, local: Vec2) -> Vec2;
    /// A world point in this pose's frame (x forward, y left).
    fn inverse_transform(self, world: Vec2) -> Vec2;
}

impl Frame for Pose {
    fn origin(self) -> Vec2 {
        Vec2::new(self.x, self.y)
    }

    fn heading(self) -> Vec2 {
        Vec2::from_angle(self.h)
    }

    fn transform(self, local: Vec2) -> Vec2 {
        let (s, c) = self.h.sin_cos();
        Vec2::new(
            self.x + c * local.x - s * local.y,
            self.y + s * local.x + c * local.y,
        )
    }

    fn inverse_transform(self, world: Vec2) -> Vec2 {
        let (s, c) = self.h.sin_cos();
        let d = world - self.origin();
        Vec2::new(c * d.x + s * d.y, -s * d.x + c * d.y)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_frame_is_the_poses_own() {
        let p = Pose::new(1.5, -2.0, 0.7);
        let w = Vec2::new(3.0, 4.0);
        let there = p.to_world(&ilmr_geometry::Point2::new(w.x, w.y));
        assert_eq!(p.transform(w), Vec2::new(there.x, there.y));
        let here = p.to_local(&ilmr_geometry::Point2::new(w.x, w.y));
        assert_eq!(p.inverse_transform(w), Vec2::new(here.x, here.y));
        let back = p.transform(p.inverse_transform(w));
        assert!(back.distance(w) < 1e-12);
    }
}

//! Plane geometry: the two solid shapes (circles and oriented
//! boxes), exact ray casting and overlap tests, and the scene that holds every
//! solid of a world.

mod fan;
mod index;
mod scene;
mod shapes;

pub use fan::Fan;
pub use scene::{Hit, Scene, Solid, SolidRef};
pub use shapes::{Circle, Obb, Shape};

pub use ilmr_geometry::{PlaneVector, Point2, Pose, Vector2, wrap_angle, xy};

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

/// The mean of `pts` (the origin for none): the middle of a run of scan returns.
pub fn centroid(pts: &[Point2<f64>]) -> Point2<f64> {
    let n = pts.len().max(1) as f64;
    Point2::from(pts.iter().fold(Vector2::zeros(), |acc, p| acc + p.coords) * (1.0 / n))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_centroid_is_the_mean_and_the_origin_for_none() {
        let pts = [
            Point2::new(1.0, 2.0),
            Point2::new(3.0, -2.0),
            Point2::new(2.0, 3.0),
        ];
        assert_eq!(centroid(&pts), Point2::new(2.0, 1.0));
        assert_eq!(centroid(&[]), Point2::origin());
    }
}

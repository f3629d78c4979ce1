//! Workpartner's pan-tilt head: a colour camera that reports coloured objects
//! in its field of view by bearing and apparent size, and a laser pointer that
//! measures the distance along the head's direction.

use crate::config::CameraConfig;
use crate::geometry::{PlaneVector, Point2, Pose, Scene, SolidRef, Vector2};
use crate::rng::Rng;
use crate::world::Colour;
use serde::Serialize;

/// Something coloured the camera may see.
#[derive(Debug, Clone, PartialEq)]
pub struct Visible {
    pub name: String,
    pub colour: Colour,
    pub position: Point2<f64>,
    pub radius: f64,
    /// The solid standing for it, which may block its own sight line.
    pub solid: Option<SolidRef>,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Detection {
    pub name: String,
    pub colour: Colour,
    /// Relative to the robot's heading, radians, left positive.
    pub bearing: f64,
    /// Angle the object spans, radians.
    pub angular_size: f64,
    /// The same in image pixels.
    pub size_px: f64,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CameraFrame {
    pub seq: u64,
    pub time: f64,
    /// Head direction relative to the robot, radians.
    pub pan: f64,
    pub tilt: f64,
    /// In order of bearing, right to left.
    pub detections: Vec<Detection>,
    /// Laser pointer distance along the head's direction, m; `None` when
    /// the beam finds nothing within range.
    pub laser: Option<f64>,
}

pub struct Head {
    pub pan: f64,
    pub tilt: f64,
}

pub fn observe(
    cfg: &CameraConfig,
    scene: &Scene,
    things: &[Visible],
    robot: Pose,
    head: &Head,
    rng: &mut Rng,
) -> (Vec<Detection>, Option<f64>) {
    let eye = robot.to_world(&cfg.head);
    let axis = robot.h + head.pan;
    let half_fov = cfg.fov_deg.to_radians() / 2.0;
    let mut detections: Vec<Detection> = things
        .iter()
        .filter_map(|t| {
            let to = t.position - eye;
            let dist = to.hypot();
            if dist <= t.radius || dist > cfg.max_range {
                return None;
            }
            let off_axis = crate::geometry::wrap_angle(to.polar_angle() - axis);
            if off_axis.abs() > half_fov {
                return None;
            }
            let dir = to * (1.0 / dist);
            let blocked = scene
                .ray(eye, dir, dist)
                .is_some_and(|h| Some(h.what) != t.solid && h.distance < dist - t.radius);
            if blocked {
                return None;
            }
            let angular_size = 2.0 * (t.radius / dist).asin();
            Some(Detection {
                name: t.name.clone(),
                colour: t.colour,
                bearing: crate::geometry::wrap_angle(to.polar_angle() - robot.h),
                angular_size,
                size_px: angular_size / (2.0 * half_fov) * cfg.image_width_px,
            })
        })
        .collect();
    detections.sort_by(|a, b| a.bearing.total_cmp(&b.bearing));
    (
        detections,
        laser_pointer(cfg, scene, eye, axis, head.tilt, rng),
    )
}

/// Slant distance to the first wall, object or floor point along the beam.
/// Solids are taken as taller than the head, so a rising beam still meets them.
fn laser_pointer(
    cfg: &CameraConfig,
    scene: &Scene,
    eye: Point2<f64>,
    axis: f64,
    tilt: f64,
    rng: &mut Rng,
) -> Option<f64> {
    let cos_t = tilt.cos();
    let horizontal_limit = cfg.laser_max_range * cos_t;
    let wall = scene
        .ray(eye, Vector2::from_angle(axis), horizontal_limit)
        .map(|h| h.distance / cos_t);
    let floor = (tilt < 0.0).then(|| cfg.head_height / (-tilt).sin());
    let d = match (wall, floor) {
        (Some(w), Some(f)) => w.min(f),
        (w, f) => w.or(f)?,
    };
    (d <= cfg.laser_max_range).then(|| (d + rng.gauss(cfg.laser_sigma)).max(0.0))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{Circle, Obb, Shape, Solid};

    fn cfg() -> CameraConfig {
        crate::config::RobotConfig::workpartner()
            .camera
            .unwrap_or_else(|| unreachable!())
    }

    #[test]
    fn sees_target_in_view_with_bearing_and_size_but_not_behind_a_wall() {
        let c = cfg();
        let user = Visible {
            name: "user".into(),
            colour: Colour::Yellow,
            position: Point2::new(10.3, 1.0),
            radius: 0.3,
            solid: Some(SolidRef::Target(0)),
        };
        let scene = Scene::new(vec![Solid::new(
            Shape::Circle(Circle::new(user.position, 0.3)),
            SolidRef::Target(0),
        )]);
        let head = Head {
            pan: 0.0,
            tilt: 0.0,
        };
        let mut rng = Rng::new(1);
        let (d, _) = observe(
            &c,
            &scene,
            std::slice::from_ref(&user),
            Pose::new(0.0, 0.0, 0.0),
            &head,
            &mut rng,
        );
        assert_eq!(d.len(), 1);
        assert!((d[0].bearing - (0.1_f64).atan()).abs() < 1e-9);
        assert!((d[0].angular_size - 2.0 * (0.3 / 10.0_f64.hypot(1.0)).asin()).abs() < 1e-9);
        // Panned away: out of the field of view.
        let (d, _) = observe(
            &c,
            &scene,
            std::slice::from_ref(&user),
            Pose::new(0.0, 0.0, 0.0),
            &Head {
                pan: 1.0,
                tilt: 0.0,
            },
            &mut rng,
        );
        assert!(d.is_empty());
        // A wall between: hidden.
        let mut solids = scene.solids().to_vec();
        solids.push(Solid::new(
            Shape::Box(Obb::from_segment(
                Point2::new(5.0, -3.0),
                Point2::new(5.0, 3.0),
                0.2,
            )),
            SolidRef::Wall(0),
        ));
        let walled = Scene::new(solids);
        let (d, laser) = observe(
            &c,
            &walled,
            &[user],
            Pose::new(0.0, 0.0, 0.0),
            &head,
            &mut rng,
        );
        assert!(d.is_empty());
        // The laser meets the wall face 0.3 m from the eye's 4.6 m.
        assert!((laser.unwrap_or(0.0) - 4.6).abs() < 0.06);
    }

    #[test]
    fn laser_pointed_down_meets_the_floor() {
        let c = cfg();
        let mut rng = Rng::new(3);
        let head = Head {
            pan: 0.0,
            tilt: -30f64.to_radians(),
        };
        let (_, laser) = observe(
            &c,
            &Scene::default(),
            &[],
            Pose::new(0.0, 0.0, 0.0),
            &head,
            &mut rng,
        );
        // 1.6 m high, 30 degrees down: 3.2 m slant.
        assert!((laser.unwrap_or(0.0) - 3.2).abs() < 0.06);
        let (_, level) = observe(
            &c,
            &Scene::default(),
            &[],
            Pose::new(0.0, 0.0, 0.0),
            &Head {
                pan: 0.0,
                tilt: 0.0,
            },
            &mut rng,
        );
        assert_eq!(level, None);
    }
}

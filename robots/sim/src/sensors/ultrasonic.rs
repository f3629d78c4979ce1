//! Workpartner's four rear ultrasonic sensors: each reads the nearest echo
//! within its cone, facing backwards from the rear edge.

use crate::config::UltrasonicConfig;
use crate::geometry::{PlaneVector, Point2, Pose, Scene, Vector2};
use crate::rng::Rng;
use serde::Serialize;

/// Beams per cone; enough that a 0.08 m pole at 3 m falls between none.
const RAYS_PER_CONE: usize = 9;

#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct UltrasonicReading {
    pub time: f64,
    /// Metres, leftmost sensor first; `max_range` when nothing echoes.
    pub ranges: [f64; 4],
}

pub fn measure_ultrasonic(
    cfg: &UltrasonicConfig,
    scene: &Scene,
    robot: Pose,
    rear: f64,
    rng: &mut Rng,
) -> [f64; 4] {
    let cone = cfg.cone_deg.to_radians();
    let mut out = [cfg.max_range; 4];
    for (k, &lat) in cfg.lateral.iter().enumerate() {
        let origin = robot.to_world(&Point2::new(-rear, lat));
        let nearest = (0..RAYS_PER_CONE)
            .filter_map(|j| {
                let a = robot.h + std::f64::consts::PI - cone / 2.0
                    + cone * j as f64 / (RAYS_PER_CONE - 1) as f64;
                scene
                    .ray(origin, Vector2::from_angle(a), cfg.max_range)
                    .map(|h| h.distance)
            })
            .fold(f64::INFINITY, f64::min);
        if nearest.is_finite() {
            out[k] = (nearest.max(cfg.min_range) + rng.gauss(cfg.noise_sigma))
                .clamp(cfg.min_range, cfg.max_range);
        }
    }
    out
}

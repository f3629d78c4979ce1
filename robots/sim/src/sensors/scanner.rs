//! SICK LMS 291: a fan of beams over `fov_deg`, reading 0 on the right
//! (-90 degrees for 180) and the last on the left, ranges in metres.

use crate::config::ScannerConfig;
use crate::geometry::{Pose, Scene};
use crate::rng::Rng;
use serde::Serialize;

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Scan {
    /// Counts scans from 0; a new number means a new scan.
    pub seq: u64,
    /// Simulated time the scan was taken, s.
    pub time: f64,
    /// The robot's estimated pose when the scan was taken (the beams were cast
    /// from the true pose, as a real scanner's are).
    pub pose: Pose,
    /// Bearing of reading 0 relative to the robot's heading, radians.
    pub angle_min: f64,
    pub angle_increment: f64,
    pub max_range: f64,
    /// Scanner origin in the robot frame.
    pub mount: crate::geometry::Vec2,
    /// Metres; exactly `max_range` where a beam found nothing.
    pub ranges: Vec<f64>,
}

impl Scan {
    pub fn bearing(&self, index: usize) -> f64 {
        self.angle_min + index as f64 * self.angle_increment
    }
}

/// Noise-free ranges from the scanner on a robot at `robot`.
pub fn cast_scan(scene: &Scene, cfg: &ScannerConfig, robot: Pose) -> Vec<f64> {
    let origin = robot.transform(cfg.mount);
    let fov = cfg.fov_deg.to_radians();
    let inc = fov / (cfg.readings - 1) as f64;
    let first = robot.h - fov / 2.0;
    let fan = scene.fan(origin, first, inc, cfg.readings, cfg.max_range);
    (0..cfg.readings)
        .map(|i| {
            let dir = crate::geometry::Vec2::from_angle(first + i as f64 * inc);
            fan.ray(scene, i, origin, dir, cfg.max_range)
                .map_or(cfg.max_range, |h| h.distance)
        })
        .collect()
}

/// Adds range noise to the beams that hit something.
pub fn add_noise(ranges: &mut [f64], cfg: &ScannerConfig, rng: &mut Rng) {
    for r in ranges.iter_mut() {
        if *r < cfg.max_range {
            *r = (*r + rng.gauss(cfg.noise_sigma)).clamp(0.0, cfg.max_range);
        }
    }
}

impl Scan {
    pub fn take(
        scene: &Scene,
        cfg: &ScannerConfig,
        truth: Pose,
        estimate: Pose,
        time: f64,
        seq: u64,
        rng: &mut Rng,
    ) -> Scan {
        let mut ranges = cast_scan(scene, cfg, truth);
        add_noise(&mut ranges, cfg, rng);
        let fov = cfg.fov_deg.to_radians();
        Scan {
            seq,
            time,
            pose: estimate,
            angle_min: -fov / 2.0,
            angle_increment: fov / (cfg.readings - 1) as f64,
            max_range: cfg.max_range,
            mount: cfg.mount,
            ranges,
        }
    }
}

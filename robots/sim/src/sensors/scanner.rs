//! SICK LMS 291: a fan of beams over `fov_deg`, reading 0 on the right
//! (-90 degrees for 180) and the last on the left, ranges in metres.

use crate::config::{MIXED_PIXEL_JUMP, ScannerConfig};
use crate::geometry::{Hit, PlaneVector, Point2, Pose, Scene, Vector2, xy};
use crate::kinematics::advance;
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
    #[serde(with = "xy")]
    pub mount: Point2<f64>,
    /// Metres; exactly `max_range` where a beam found nothing.
    pub ranges: Vec<f64>,
}

impl Scan {
    pub fn bearing(&self, index: usize) -> f64 {
        self.angle_min + index as f64 * self.angle_increment
    }

    /// Whether reading `index` came back: a finite range short of `max_range`.
    pub fn returned(&self, index: usize) -> bool {
        let r = self.ranges[index];
        r.is_finite() && r < self.max_range
    }

    /// Where reading `index` lies in the robot frame: the mount, then its range
    /// along its bearing.
    pub fn local_point(&self, index: usize) -> Point2<f64> {
        self.mount + Vector2::from_angle(self.bearing(index)) * self.ranges[index]
    }

    /// The points the beams hit, in the world frame, for a robot that stood at
    /// `robot` when the scan was taken (its true pose: the beams were cast from it).
    /// A range of 0 is the scanner's own housing, not a point of the world.
    pub fn world_hits(&self, robot: Pose) -> impl Iterator<Item = Point2<f64>> + '_ {
        (0..self.ranges.len())
            .filter(|&i| self.returned(i) && self.ranges[i] > 0.0)
            .map(move |i| robot.to_world(&self.local_point(i)))
    }
}

/// Noise-free ranges from the scanner on a robot at `robot`.
pub fn cast_scan(scene: &Scene, cfg: &ScannerConfig, robot: Pose) -> Vec<f64> {
    ranges(&cast_hits(scene, cfg, robot), cfg)
}

/// What each beam meets from a robot standing at `robot`.
fn cast_hits(scene: &Scene, cfg: &ScannerConfig, robot: Pose) -> Vec<Option<Hit>> {
    let origin = robot.to_world(&cfg.mount);
    let fov = cfg.fov_deg.to_radians();
    let inc = fov / (cfg.readings - 1) as f64;
    let first = robot.h - fov / 2.0;
    let fan = scene.fan(origin, first, inc, cfg.readings, cfg.max_range);
    (0..cfg.readings)
        .map(|i| {
            let dir = Vector2::from_angle(first + i as f64 * inc);
            fan.ray(scene, i, origin, dir, cfg.max_range)
        })
        .collect()
}

fn ranges(hits: &[Option<Hit>], cfg: &ScannerConfig) -> Vec<f64> {
    hits.iter()
        .map(|h| h.map_or(cfg.max_range, |h| h.distance))
        .collect()
}

/// What each beam of a scan swept while the robot moved meets: beam `i` is
/// taken `sweep_time * (1 - i / (n - 1))` before the scan's end, and cast from
/// where the robot was then (back along its arc at `speed`, m/s, and
/// `turn_rate`, rad/s), to within a [`SKEW_PARTS`]th of the sweep.
pub fn cast_skewed(
    scene: &Scene,
    cfg: &ScannerConfig,
    end: Pose,
    speed: f64,
    turn_rate: f64,
) -> Vec<f64> {
    ranges(&cast_skewed_hits(scene, cfg, end, speed, turn_rate), cfg)
}

fn cast_skewed_hits(
    scene: &Scene,
    cfg: &ScannerConfig,
    end: Pose,
    speed: f64,
    turn_rate: f64,
) -> Vec<Option<Hit>> {
    let fov = cfg.fov_deg.to_radians();
    let inc = fov / (cfg.readings - 1) as f64;
    let last = (cfg.readings - 1) as f64;
    let per_part = cfg.readings.div_ceil(SKEW_PARTS);
    let mut hits = Vec::with_capacity(cfg.readings);
    for start in (0..cfg.readings).step_by(per_part) {
        let count = per_part.min(cfg.readings - start);
        let middle = start as f64 + (count - 1) as f64 / 2.0;
        let ago = cfg.sweep_time * (1.0 - middle / last);
        let at = advance(end, -speed * ago, -turn_rate * ago);
        let origin = at.to_world(&cfg.mount);
        let first = at.h - fov / 2.0 + start as f64 * inc;
        let fan = scene.fan(origin, first, inc, count, cfg.max_range);
        hits.extend((0..count).map(|i| {
            let dir = Vector2::from_angle(first + i as f64 * inc);
            fan.ray(scene, i, origin, dir, cfg.max_range)
        }));
    }
    hits
}

/// A swept scan is cast in this many parts, each from the pose at its middle
/// beam's time: within a part the robot moves an eighth of the sweep (3 mm at
/// 1 m/s over 26.6 ms), and each part goes through a fan of its own.
pub const SKEW_PARTS: usize = 8;

/// Mixed pixels and dropouts on noise-free ranges. A beam beside an edge (its
/// neighbour met another solid more than [`MIXED_PIXEL_JUMP`] further away)
/// may read anywhere between its own surface and its neighbour's; a beam that
/// met something may return nothing.
pub fn add_artefacts(ranges: &mut [f64], hits: &[Option<Hit>], cfg: &ScannerConfig, rng: &mut Rng) {
    if cfg.mixed_pixel > 0.0 {
        let clean = ranges.to_vec();
        for (i, r) in ranges.iter_mut().enumerate() {
            let Some(own) = hits.get(i).copied().flatten() else {
                continue;
            };
            let far = [i.wrapping_sub(1), i + 1]
                .into_iter()
                .filter_map(|j| Some((hits.get(j).copied().flatten()?, clean[j])))
                .filter(|(h, n)| h.what != own.what && n - *r > MIXED_PIXEL_JUMP)
                .map(|(_, n)| n)
                .fold(None, |m: Option<f64>, n| Some(m.map_or(n, |m| m.max(n))));
            if let Some(far) = far
                && rng.uniform() < cfg.mixed_pixel
            {
                *r += (far - *r) * rng.uniform();
            }
        }
    }
    if cfg.dropout > 0.0 {
        for r in ranges.iter_mut() {
            if *r < cfg.max_range && rng.uniform() < cfg.dropout {
                *r = cfg.max_range;
            }
        }
    }
}

/// Adds range noise to the beams that hit something.
pub fn add_noise(ranges: &mut [f64], cfg: &ScannerConfig, rng: &mut Rng) {
    for r in ranges.iter_mut() {
        if *r < cfg.max_range {
            *r = (*r + rng.gauss(cfg.noise_sigma)).clamp(0.0, cfg.max_range);
        }
    }
}

/// Where the robot is as a scan ends, and how it moves.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScanPose {
    pub truth: Pose,
    /// What the robot believes; the scan is stamped with it.
    pub estimate: Pose,
    /// m/s and rad/s of the true motion, for the skew of a sweep.
    pub speed: f64,
    pub turn_rate: f64,
}

/// The scanner's two noise streams: range noise, and dropouts with mixed pixels.
pub struct ScanNoise<'a> {
    pub range: &'a mut Rng,
    pub artefacts: &'a mut Rng,
}

impl Scan {
    pub fn take(
        scene: &Scene,
        cfg: &ScannerConfig,
        at: ScanPose,
        time: f64,
        seq: u64,
        noise: ScanNoise<'_>,
    ) -> Scan {
        let ScanPose {
            truth, estimate, ..
        } = at;
        let moving = at.speed != 0.0 || at.turn_rate != 0.0;
        let hits = if cfg.sweep_time > 0.0 && moving {
            cast_skewed_hits(scene, cfg, truth, at.speed, at.turn_rate)
        } else {
            cast_hits(scene, cfg, truth)
        };
        let mut ranges = ranges(&hits, cfg);
        add_artefacts(&mut ranges, &hits, cfg, noise.artefacts);
        add_noise(&mut ranges, cfg, noise.range);
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

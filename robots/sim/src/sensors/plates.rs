//! MoRo's inductive sensor array: a line across the body that fires when it
//! passes over a floor plate and tells how far off-centre the plate was.

use crate::config::PlateSensorConfig;
use crate::geometry::Pose;
use crate::world::Plate;
use serde::Serialize;

#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PlateEvent {
    /// Counts detections from 0.
    pub seq: u64,
    pub time: f64,
    /// Index into the world's plates (the simulator's ground truth; a real
    /// robot knows only which plate it expected).
    pub plate: usize,
    /// Plate's offset across the body, left positive, rounded to the
    /// sensor's resolution (1 cm).
    pub lateral: f64,
}

/// Plates whose centre the array line crossed while the robot moved from
/// `before` to `after`, with the true lateral offset at the crossing.
pub fn crossings(
    cfg: &PlateSensorConfig,
    plates: &[Plate],
    before: Pose,
    after: Pose,
) -> Vec<(usize, f64)> {
    plates
        .iter()
        .enumerate()
        .filter_map(|(i, p)| {
            let l0 = before.to_local(&p.position);
            let l1 = after.to_local(&p.position);
            let a0 = l0.x - cfg.offset;
            let a1 = l1.x - cfg.offset;
            if (a0 > 0.0) == (a1 > 0.0) {
                return None;
            }
            let f = a0 / (a0 - a1);
            let lateral = l0.y + (l1.y - l0.y) * f;
            (lateral.abs() <= cfg.half_width + p.radius).then_some((i, lateral))
        })
        .collect()
}

pub fn quantise(value: f64, resolution: f64) -> f64 {
    (value / resolution).round() * resolution
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Point2;

    #[test]
    fn crossing_reports_lateral_offset_and_misses_far_plates() {
        let cfg = PlateSensorConfig {
            offset: 0.45,
            half_width: 0.3,
            noise_sigma: 0.0,
            resolution: 0.01,
        };
        let plates = [
            Plate {
                position: Point2::new(1.0, 0.12),
                radius: 0.05,
            },
            Plate {
                position: Point2::new(1.0, 0.5),
                radius: 0.05,
            },
        ];
        let before = Pose::new(0.5, 0.0, 0.0);
        let after = Pose::new(0.6, 0.0, 0.0);
        let hits = crossings(&cfg, &plates, before, after);
        assert_eq!(hits.len(), 1);
        assert_eq!(hits[0].0, 0);
        assert!((hits[0].1 - 0.12).abs() < 1e-12);
        // Not yet reached, and already passed: no crossing.
        assert!(
            crossings(
                &cfg,
                &plates,
                Pose::new(0.4, 0.0, 0.0),
                Pose::new(0.5, 0.0, 0.0)
            )
            .is_empty()
        );
        assert!(
            crossings(
                &cfg,
                &plates,
                Pose::new(0.6, 0.0, 0.0),
                Pose::new(0.7, 0.0, 0.0)
            )
            .is_empty()
        );
        assert!((quantise(0.1234, 0.01) - 0.12).abs() < 1e-12);
    }
}

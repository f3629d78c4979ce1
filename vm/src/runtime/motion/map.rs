//! The environmental map of section 4.5.7: scanner points in world
//! coordinates, added when a new scan arrives and kept until they are more
//! than 3 m behind the robot (`prune_map`). One point per 5 cm cell, so a
//! robot standing in front of a wall does not pile up a point per beam per
//! scan.

use std::collections::BTreeMap;

use ilmr_hal::Scan;
use ilmr_motion::Pose;
use ilmr_motion::obstacle::prune_map;
use nalgebra::Point2;

/// Returns further away than this are not mapped: the checked area, the wall
/// fit and the turn check all look within a few metres.
pub(crate) const MAP_RANGE: f64 = 8.0;
/// Closer than this is the scanner's own housing.
const MIN_RANGE: f64 = 0.05;
const CELL: f64 = 0.05;

#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct EnvMap {
    points: Vec<Point2<f64>>,
    cells: BTreeMap<(i64, i64), usize>,
    /// Time stamp of the last scan taken in.
    last_scan: Option<f64>,
}

fn cell(p: &Point2<f64>) -> (i64, i64) {
    ((p.x / CELL).floor() as i64, (p.y / CELL).floor() as i64)
}

impl EnvMap {
    pub fn points(&self) -> &[Point2<f64>] {
        &self.points
    }

    pub fn clear(&mut self) {
        self.points.clear();
        self.cells.clear();
    }

    /// Takes in `scan` if it is new: `pose` is where the robot was when it
    /// was taken, `mount` how far ahead of that point the scanner sits.
    /// Returns whether the map changed.
    pub fn update(&mut self, scan: Option<&Scan>, pose: &Pose, mount: f64) -> bool {
        let Some(scan) = scan else {
            return false;
        };
        if self.last_scan == Some(scan.t) {
            return false;
        }
        self.last_scan = Some(scan.t);
        let origin = pose.to_world(&Point2::new(mount, 0.0));
        for (i, &r) in scan.ranges.iter().enumerate() {
            if !(r.is_finite() && (MIN_RANGE..MAP_RANGE).contains(&r)) {
                continue;
            }
            let a = pose.h + scan.angle_min + i as f64 * scan.angle_step;
            let p = Point2::new(origin.x + r * a.cos(), origin.y + r * a.sin());
            if !(p.x.is_finite() && p.y.is_finite()) {
                continue;
            }
            match self.cells.get(&cell(&p)) {
                Some(&j) => self.points[j] = p,
                None => {
                    self.cells.insert(cell(&p), self.points.len());
                    self.points.push(p);
                }
            }
        }
        let kept = prune_map(&self.points, pose);
        if kept.len() != self.points.len() {
            self.points = kept;
            self.cells.clear();
            for (i, p) in self.points.iter().enumerate() {
                self.cells.insert(cell(p), i);
            }
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scan(t: f64, ranges: Vec<f64>) -> Scan {
        Scan {
            device: "scanner".into(),
            t,
            angle_min: -std::f64::consts::FRAC_PI_2,
            angle_step: std::f64::consts::PI / (ranges.len() - 1) as f64,
            ranges,
        }
    }

    #[test]
    fn a_scan_is_mapped_once_and_far_points_are_dropped_behind() {
        let mut m = EnvMap::default();
        let s = scan(0.0, vec![1.0, 2.0, 30.0]);
        assert!(m.update(Some(&s), &Pose::new(0.0, 0.0, 0.0), 0.5));
        // Right, ahead; the 30 m return is beyond the map.
        assert_eq!(m.points().len(), 2);
        let right = m.points()[0];
        assert!((right.x - 0.5).abs() < 1e-9 && (right.y + 1.0).abs() < 1e-9);
        assert!(!m.update(Some(&s), &Pose::new(0.0, 0.0, 0.0), 0.5));
        // Drive on 4 m: the point beside the start is 3.5 m behind.
        let s2 = scan(1.0, vec![30.0, 30.0, 30.0]);
        assert!(m.update(Some(&s2), &Pose::new(4.0, 0.0, 0.0), 0.5));
        assert_eq!(m.points().len(), 1);
    }

    #[test]
    fn repeated_scans_of_one_wall_do_not_grow_the_map() {
        let mut m = EnvMap::default();
        for t in 0..10 {
            let s = scan(f64::from(t), vec![1.0; 181]);
            m.update(Some(&s), &Pose::new(0.0, 0.0, 0.0), 0.0);
        }
        let n = m.points().len();
        assert!(n <= 181, "{n}");
    }
}

//! The environmental map of section 4.5.7: scanner points in world
//! coordinates, added when a new scan arrives and kept until they are more
//! than 3 m behind the robot (`prune_map`). One point per 5 cm cell, so a
//! robot standing in front of a wall does not pile up a point per beam per
//! scan.

use ilmr_hal::Scan;
use ilmr_motion::Pose;
use ilmr_motion::obstacle::{Bounds, PointGrid, prune_map};
use nalgebra::Point2;

use super::cells::Cells;
use super::forget::SeenThrough;

/// Returns further away than this are not mapped: the checked area, the wall
/// fit and the turn check all look within a few metres.
pub(crate) const MAP_RANGE: f64 = 8.0;
/// Closer than this is the scanner's own housing.
pub(crate) const MIN_RANGE: f64 = 0.05;

/// Side of the index's cells, m: a checked area a few metres long covers a
/// few hundred of them, and a cell holds a handful of points.
pub(crate) const GRID_CELL: f64 = 0.25;

#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct EnvMap {
    points: Vec<Point2<f64>>,
    cells: Cells,
    /// `points` by place, rebuilt whenever a scan is taken in.
    grid: PointGrid,

    /// Time stamp of the last scan taken in.
    last_scan: Option<f64>,
}

impl EnvMap {
    pub fn points(&self) -> &[Point2<f64>] {
        &self.points
    }

    /// An index of `points()`.
    pub fn grid(&self) -> &PointGrid {
        &self.grid
    }

    /// Into `out` (cleared first), each once and in no set order: the index of
    /// every point inside `b`, and some near it.
    pub fn near(&self, b: &Bounds, out: &mut Vec<usize>) {
        if self.grid.len() == self.points.len() {
            self.grid.within(b, out);
        } else {
            out.clear();
            out.extend(0..self.points.len());
        }
    }

    pub fn clear(&mut self) {
        self.points.clear();
        self.cells.clear();
        self.grid = PointGrid::default();
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
        self.forget_seen_through(scan, &origin, pose.h);
        for (i, &r) in scan.ranges.iter().enumerate() {
            if !(r.is_finite() && (MIN_RANGE..MAP_RANGE).contains(&r)) {
                continue;
            }
            let a = pose.h + scan.angle_min + i as f64 * scan.angle_step;
            let p = Point2::new(origin.x + r * a.cos(), origin.y + r * a.sin());
            if !(p.x.is_finite() && p.y.is_finite()) {
                continue;
            }
            match self.cells.get(&p) {
                Some(j) => self.points[j] = p,
                None => {
                    self.cells.insert(&p, self.points.len());
                    self.points.push(p);
                }
            }
        }
        let kept = prune_map(&self.points, pose);
        if kept.len() != self.points.len() {
            self.points = kept;
            self.cells.rebuild(&self.points);
        }
        self.grid.rebuild(GRID_CELL, &self.points, |p| (p.x, p.y));
        true
    }

    /// Drops the points that the beams of `scan` pass through: an obstacle that
    /// has gone (a person who walked on, a box taken away) must stop holding the
    /// robot (the rule is in `forget.rs`).
    fn forget_seen_through(&mut self, scan: &Scan, origin: &Point2<f64>, heading: f64) {
        let Some(rule) = SeenThrough::new(scan, *origin, heading) else {
            return;
        };
        let before = self.points.len();
        self.points.retain(|p| rule.keeps(p));
        if self.points.len() != before {
            self.cells.rebuild(&self.points);
        }
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
    fn a_thing_that_has_gone_is_forgotten_and_a_wall_is_not() {
        let mut m = EnvMap::default();
        // Something 1 m ahead, a wall 3 m ahead behind it.
        let mut ranges = vec![3.0; 181];
        for r in &mut ranges[85..96] {
            *r = 1.0;
        }
        m.update(Some(&scan(0.0, ranges)), &Pose::new(0.0, 0.0, 0.0), 0.0);
        let near = |m: &EnvMap| m.points().iter().filter(|p| p.x.hypot(p.y) < 1.5).count();
        assert!(near(&m) >= 3, "{}", near(&m));
        // It has gone: the beams reach the wall.
        m.update(
            Some(&scan(1.0, vec![3.0; 181])),
            &Pose::new(0.0, 0.0, 0.0),
            0.0,
        );
        assert_eq!(near(&m), 0);
        assert!(
            m.points().len() > 100,
            "the wall stays: {}",
            m.points().len()
        );
        // Seen again from 1 m nearer, the wall is still there.
        let n = m.points().len();
        m.update(
            Some(&scan(2.0, vec![2.0; 181])),
            &Pose::new(1.0, 0.0, 0.0),
            0.0,
        );
        assert!(m.points().len() >= n / 2);
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

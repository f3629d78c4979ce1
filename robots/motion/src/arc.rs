//! Constant-curvature arcs: the controller's predicted trajectories and the
//! obstacle check area are both measured in an arc's own coordinates.

use crate::path::segment_distance;
use crate::pose::Pose;
use nalgebra::Point2;
use std::f64::consts::TAU;

/// Curvatures below this are straight lines for the formulas here.
const STRAIGHT: f64 = 1e-9;

/// An arc leaving `start` along its heading (the direction of motion) with
/// signed `curvature` (positive bends left) for `length` metres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Arc {
    pub start: Pose,
    pub curvature: f64,
    pub length: f64,
}

impl Arc {
    pub fn end(&self) -> Pose {
        self.start.advance(self.length, self.curvature)
    }

    pub fn point_at(&self, s: f64) -> Point2<f64> {
        self.start.advance(s, self.curvature).position()
    }

    /// Coordinates of `p` relative to the arc's full circle: `s` is the arc
    /// length from the start to `p`'s radial projection (within half a circle
    /// either way), `n` the signed offset to the left of the motion.
    ///
    /// Written so that nothing cancels as the curvature goes to zero: the
    /// formulas turn smoothly into the straight-line ones.
    pub fn coords(&self, p: &Point2<f64>) -> (f64, f64) {
        let l = self.start.to_local(p);
        let k = self.curvature;
        if k.abs() < STRAIGHT {
            return (l.x, l.y);
        }
        let (kx, ky) = (k * l.x, 1.0 - k * l.y);
        let s = (k.abs() * l.x).atan2(ky) / k.abs();
        let q = (kx * kx + ky * ky).sqrt();
        let n = (2.0 * l.y - k * (l.x * l.x + l.y * l.y)) / (1.0 + q);
        (s, n)
    }

    /// Shortest distance from `p` to the arc.
    pub fn distance_to(&self, p: &Point2<f64>) -> f64 {
        let k = self.curvature;
        if k.abs() < STRAIGHT {
            return segment_distance(p, &self.start.position(), &self.end().position());
        }
        let (s, n) = self.coords(p);
        let circumference = TAU / k.abs();
        let along = if s < 0.0 { s + circumference } else { s };
        if self.length >= circumference || along <= self.length {
            n.abs()
        } else {
            let a = (p - self.start.position()).norm();
            let b = (p - self.end().position()).norm();
            a.min(b)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn coords_of_points_on_and_off_a_left_arc() {
        let arc = Arc {
            start: Pose::new(0.0, 0.0, 0.0),
            curvature: 0.5,
            length: PI,
        };
        // Quarter circle of radius 2 ends at (2, 2); a point 0.3 m inside it.
        let (s, n) = arc.coords(&Point2::new(2.0 - 0.3, 2.0));
        assert!((s - PI).abs() < 1e-12 && (n - 0.3).abs() < 1e-12);
        assert!((arc.distance_to(&Point2::new(2.0 - 0.3, 2.0)) - 0.3).abs() < 1e-12);
        // Beyond the end of the arc the end point is nearest.
        let beyond = Point2::new(0.0, 4.5);
        assert!((arc.distance_to(&beyond) - (beyond - Point2::new(2.0, 2.0)).norm()).abs() < 1e-9);
    }

    #[test]
    fn right_arc_offsets_are_to_the_left_of_motion() {
        let arc = Arc {
            start: Pose::new(1.0, 1.0, PI / 2.0),
            curvature: -1.0,
            length: 1.0,
        };
        let on = arc.point_at(0.5);
        let (s, n) = arc.coords(&on);
        assert!((s - 0.5).abs() < 1e-12 && n.abs() < 1e-12);
    }

    #[test]
    fn tiny_curvature_matches_the_straight_line() {
        let p = Point2::new(1.5, -0.4);
        let bent = Arc {
            start: Pose::new(0.0, 0.0, 0.0),
            curvature: 1e-7,
            length: 2.0,
        };
        let (s, n) = bent.coords(&p);
        assert!((s - 1.5).abs() < 1e-6 && (n + 0.4).abs() < 1e-6);
    }

    #[test]
    fn distance_behind_the_start_is_to_the_start() {
        let arc = Arc {
            start: Pose::new(0.0, 0.0, 0.0),
            curvature: 0.8,
            length: 1.0,
        };
        assert!((arc.distance_to(&Point2::new(-0.5, 0.0)) - 0.5).abs() < 1e-12);
    }
}

//! The reference path of equations (2)-(3): a cubic Bezier curve between a
//! start and an end pose, sampled at a fixed arc-length spacing.

mod plan;

pub use plan::{Plan, PlanError, PlanParams, plan_to_pose, plan_with};

use crate::path::{Direction, Path, PathError, PathPoint};
use crate::pose::Pose;
use nalgebra::{Point2, Vector2};

/// Fraction of the start-end distance at which equations (3) place the inner
/// control points along the two headings.
pub const CONTROL_FRACTION: f64 = 0.4;

/// Intervals of the parameter t used for arc length and curvature scans;
/// fine enough that a scan misses no curvature peak of an admissible path.
const TABLE: usize = 256;
/// Intervals of the quick rejection scan of `fits`.
const COARSE: usize = 32;

/// Gauss-Legendre nodes and weights on [-1, 1]: exact for the degree-5
/// speed polynomial's square root to well below a millimetre per interval.
const GAUSS: [(f64, f64); 3] = [
    (-0.774_596_669_241_483_4, 5.0 / 9.0),
    (0.0, 8.0 / 9.0),
    (0.774_596_669_241_483_4, 5.0 / 9.0),
];

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CubicBezier {
    pub p: [Point2<f64>; 4],
}

impl CubicBezier {
    /// Equations (3). Both poses are in the frame of motion: for a robot
    /// reversing to its goal pass the poses with their headings flipped.
    pub fn from_poses(start: &Pose, end: &Pose) -> Self {
        let d = (end.position() - start.position()).norm() * CONTROL_FRACTION;
        let p0 = start.position();
        let p3 = end.position();
        CubicBezier {
            p: [
                p0,
                p0 + start.heading_vector() * d,
                p3 - end.heading_vector() * d,
                p3,
            ],
        }
    }

    /// Equation (2).
    pub fn point(&self, t: f64) -> Point2<f64> {
        let u = 1.0 - t;
        let [a, b, c, d] = self.p.map(|q| q.coords);
        Point2::from(
            a * (u * u * u) + b * (3.0 * t * u * u) + c * (3.0 * t * t * u) + d * (t * t * t),
        )
    }

    pub fn derivative(&self, t: f64) -> Vector2<f64> {
        let u = 1.0 - t;
        let [a, b, c, d] = self.p;
        (b - a) * (3.0 * u * u) + (c - b) * (6.0 * u * t) + (d - c) * (3.0 * t * t)
    }

    pub fn second_derivative(&self, t: f64) -> Vector2<f64> {
        let [a, b, c, d] = self.p.map(|q| q.coords);
        (c - b * 2.0 + a) * (6.0 * (1.0 - t)) + (d - c * 2.0 + b) * (6.0 * t)
    }

    /// Signed curvature at parameter t; infinite where the curve stops (a
    /// cusp), because no robot can follow it there.
    pub fn curvature(&self, t: f64) -> f64 {
        let d1 = self.derivative(t);
        let speed = d1.norm();
        if speed < 1e-9 {
            return f64::INFINITY;
        }
        d1.perp(&self.second_derivative(t)) / (speed * speed * speed)
    }

    /// Whether the curve bends at most `kmax` anywhere. A coarse look first:
    /// the curvature at a few parameters is a lower bound of the maximum, so
    /// most curves a planner tries and rejects cost an eighth of a full scan.
    pub fn fits(&self, kmax: f64) -> bool {
        let limit = kmax * (1.0 + 1e-9);
        (0..=COARSE).all(|i| self.curvature(i as f64 / COARSE as f64).abs() <= limit)
            && self.max_abs_curvature() <= limit
    }

    /// Largest |curvature| over the curve, scanned on a fine parameter grid.
    ///
    /// Besides the pointwise formula this takes the turn of the tangent
    /// between neighbouring grid points over their chord: a curve whose
    /// control points are collinear (a goal straight behind the robot)
    /// reverses on itself with a zero cross product everywhere, and only the
    /// tangent flipping between two samples shows that cusp.
    pub fn max_abs_curvature(&self) -> f64 {
        let mut max = 0.0f64;
        let mut prev: Option<(Point2<f64>, f64)> = None;
        for i in 0..=TABLE {
            let t = i as f64 / TABLE as f64;
            let k = self.curvature(t);
            if !k.is_finite() {
                return f64::INFINITY;
            }
            max = max.max(k.abs());
            let d1 = self.derivative(t);
            let here = (self.point(t), d1.y.atan2(d1.x));
            if let Some((p, h)) = prev {
                let chord = (here.0 - p).norm();
                let turn = crate::pose::angle_diff(here.1, h).abs();
                if chord > 1e-12 {
                    // Smooth bends turn by about k * chord; only a cusp
                    // turns by much more over a short chord.
                    if turn > 0.5 {
                        max = max.max(turn / chord);
                    }
                } else if turn > 1e-6 {
                    return f64::INFINITY;
                }
            }
            prev = Some(here);
        }
        max
    }

    fn length_between(&self, t0: f64, t1: f64) -> f64 {
        let half = 0.5 * (t1 - t0);
        let mid = 0.5 * (t0 + t1);
        GAUSS
            .iter()
            .map(|&(x, w)| w * self.derivative(mid + half * x).norm())
            .sum::<f64>()
            * half
    }

    /// Cumulative arc length at t = i / TABLE.
    fn length_table(&self) -> Vec<f64> {
        let mut table = Vec::with_capacity(TABLE + 1);
        table.push(0.0);
        let mut acc = 0.0;
        for i in 0..TABLE {
            acc += self.length_between(i as f64 / TABLE as f64, (i + 1) as f64 / TABLE as f64);
            table.push(acc);
        }
        table
    }

    pub fn length(&self) -> f64 {
        self.length_table()[TABLE]
    }

    /// Samples the curve every `spacing` metres of arc length (and at its
    /// end) into a path driven in `direction`.
    pub fn sample(&self, spacing: f64, direction: Direction) -> Result<Path, PathError> {
        if !(spacing.is_finite() && spacing > 0.0) {
            return Err(PathError::BadSpacing(spacing));
        }
        if self.p.iter().any(|q| !(q.x.is_finite() && q.y.is_finite())) {
            return Err(PathError::NonFinite);
        }
        let table = self.length_table();
        let total = table[TABLE];
        let n = (total / spacing).ceil();
        if n >= crate::path::MAX_SAMPLES as f64 {
            return Err(PathError::BadSpacing(spacing));
        }
        let n = n as usize;
        let mut points = Vec::with_capacity(n + 1);
        let mut interval = 0;
        for i in 0..=n {
            let s = (i as f64 * spacing).min(total);
            while interval + 1 < TABLE && table[interval + 1] < s {
                interval += 1;
            }
            let t = self.parameter_at(s, interval, &table);
            let d1 = self.derivative(t);
            let heading = if d1.norm() > 1e-12 {
                d1.y.atan2(d1.x)
            } else {
                // Only a zero-length curve stops at its ends; its heading
                // is the start control direction.
                let v = self.p[1] - self.p[0];
                v.y.atan2(v.x)
            };
            let kappa = if total > 0.0 { self.curvature(t) } else { 0.0 };
            let kappa = if kappa.is_finite() { kappa } else { 0.0 };
            points.push(PathPoint::from_travel(
                s,
                self.point(t),
                heading,
                kappa,
                direction,
            ));
            if s >= total {
                break;
            }
        }
        Path::new(points)
    }

    /// Parameter t at arc length `s` inside table interval `i`: linear
    /// interpolation, then one Newton step on the exact length.
    fn parameter_at(&self, s: f64, i: usize, table: &[f64]) -> f64 {
        let (s0, s1) = (table[i], table[i + 1]);
        let t0 = i as f64 / TABLE as f64;
        let dt = 1.0 / TABLE as f64;
        if s1 - s0 <= 1e-15 {
            return t0;
        }
        let mut t = t0 + dt * ((s - s0) / (s1 - s0)).clamp(0.0, 1.0);
        let speed = self.derivative(t).norm();
        if speed > 1e-9 {
            let err = s0 + self.length_between(t0, t) - s;
            t = (t - err / speed).clamp(t0, t0 + dt);
        }
        t
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pose::angle_diff;
    use std::f64::consts::FRAC_PI_2;

    #[test]
    fn endpoints_and_tangents_match_the_poses() {
        let a = Pose::from_degrees(0.0, 0.0, 0.0);
        let b = Pose::from_degrees(3.0, 4.0, 90.0);
        let bz = CubicBezier::from_poses(&a, &b);
        assert_eq!(bz.point(0.0), a.position());
        assert!((bz.point(1.0) - b.position()).norm() < 1e-12);
        let t0 = bz.derivative(0.0);
        let t1 = bz.derivative(1.0);
        assert!(angle_diff(t0.y.atan2(t0.x), a.h).abs() < 1e-12);
        assert!(angle_diff(t1.y.atan2(t1.x), b.h).abs() < 1e-12);
        // Equations (3): inner control points 0.4 * trajdist along the headings.
        assert!((bz.p[1] - Point2::new(2.0, 0.0)).norm() < 1e-12);
        assert!((bz.p[2] - Point2::new(3.0, 2.0)).norm() < 1e-12);
    }

    #[test]
    fn sampled_path_is_evenly_spaced_and_ends_on_the_goal() {
        let a = Pose::from_degrees(1.0, 1.0, 30.0);
        let b = Pose::from_degrees(5.0, 2.0, -20.0);
        let path = CubicBezier::from_poses(&a, &b)
            .sample(0.05, Direction::Forward)
            .expect("valid");
        let pts = path.points();
        for w in pts.windows(2).take(pts.len() - 2) {
            let chord = (w[1].position() - w[0].position()).norm();
            assert!((chord - 0.05).abs() < 1e-4, "chord {chord}");
        }
        assert!((path.last().position() - b.position()).norm() < 1e-9);
        assert!(angle_diff(path.end_pose().h, b.h).abs() < 1e-9);
    }

    #[test]
    fn straight_curve_has_zero_curvature() {
        let bz = CubicBezier::from_poses(&Pose::new(0.0, 0.0, 0.0), &Pose::new(2.0, 0.0, 0.0));
        assert!(bz.max_abs_curvature() < 1e-12);
        assert!((bz.length() - 2.0).abs() < 1e-12);
    }

    #[test]
    fn curvature_of_a_quarter_turn_is_near_the_circle() {
        // The Bezier approximation of a quarter circle of radius 2 (control
        // fraction 0.4 of the chord is ~0.566 r, close to the ideal 0.552 r)
        // bends with a curvature near 1/2 all the way.
        let bz =
            CubicBezier::from_poses(&Pose::new(0.0, 0.0, 0.0), &Pose::new(2.0, 2.0, FRAC_PI_2));
        for i in 0..=20 {
            let k = bz.curvature(i as f64 / 20.0);
            assert!((k - 0.5).abs() < 0.05, "curvature {k}");
        }
        assert!((bz.length() - std::f64::consts::PI).abs() < 0.02);
    }

    #[test]
    fn reversing_path_keeps_the_body_facing_the_start_heading() {
        let start = Pose::new(0.0, 0.0, 0.0);
        let goal = Pose::new(-2.0, -0.5, 0.0);
        let bz = CubicBezier::from_poses(&start.flipped(), &goal.flipped());
        let path = bz.sample(0.05, Direction::Backward).expect("valid");
        assert!(angle_diff(path.start_pose().h, 0.0).abs() < 1e-12);
        assert!(angle_diff(path.end_pose().h, 0.0).abs() < 1e-9);
    }
}

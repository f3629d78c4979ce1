//! The rule that drops map points a new scan sees through (see
//! `EnvMap::update`): a point goes only when the beam nearest its bearing and
//! both neighbours reach past it by `SEEN_THROUGH`, so that the edge of a
//! thing and a wall seen at a grazing angle stay.
//!
//! The rule needs each point's beam, an `atan2` and a remainder per point per
//! scan. Most points lie on what the scan sees again, and keep: a rough
//! bearing (no library call) places the beam within two, and when none of
//! those five beams could pass the point, it keeps without the exact bearing.
//! Every other point gets the exact rule, so the answers are the same.

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use ilmr_hal::Scan;
use nalgebra::Point2;

use super::map::{MAP_RANGE, MIN_RANGE};

/// A beam must reach this far past a mapped point to clear it: well above the
/// scanner's noise.
const SEEN_THROUGH: f64 = 0.15;
/// Largest error of `rough_atan2`, radians (the test checks it).
const ROUGH_ERROR: f64 = 2e-5;
/// Beams either side of the rough beam that the exact one may be.
const WINDOW: usize = 2;

/// `y.atan2(x)` within `ROUGH_ERROR`: a polynomial for the arctangent on
/// [0, 1] and the octants' symmetry.
fn rough_atan2(y: f64, x: f64) -> f64 {
    let (ax, ay) = (x.abs(), y.abs());
    let (small, big) = if ax < ay { (ax, ay) } else { (ay, ax) };
    if big == 0.0 {
        return 0.0;
    }
    let t = small / big;
    let s = t * t;
    // Abramowitz and Stegun 4.4.49: within 1e-5 on [0, 1].
    let mut a =
        t * (0.999_866 + s * (-0.330_299_5 + s * (0.180_141 + s * (-0.085_133 + s * 0.020_835_1))));
    if ay > ax {
        a = FRAC_PI_2 - a;
    }
    if x < 0.0 {
        a = PI - a;
    }
    if y < 0.0 { -a } else { a }
}

/// One scan's rule, with what its shortcut needs worked out once.
pub(crate) struct SeenThrough<'a> {
    scan: &'a Scan,
    origin: Point2<f64>,
    heading: f64,
    /// For each rough beam `b`: the farthest that the nearest of three beams
    /// round any beam within `WINDOW` of `b` reaches (-inf when none of them
    /// is a beam the rule looks at). Empty when the beams are too close
    /// together for the rough bearing.
    farthest: Vec<f64>,
}

impl<'a> SeenThrough<'a> {
    /// `None` when the scan can clear nothing (too few beams, no usable
    /// step). `origin` and `heading` are the scanner's.
    pub fn new(scan: &'a Scan, origin: Point2<f64>, heading: f64) -> Option<SeenThrough<'a>> {
        let n = scan.ranges.len();
        let step = scan.angle_step;
        if n < 3 || !(step.is_finite() && step > 0.0) {
            return None;
        }
        let mut rule = SeenThrough {
            scan,
            origin,
            heading,
            farthest: Vec::new(),
        };
        if step > 50.0 * ROUGH_ERROR && step < 1.0 {
            let nearest: Vec<f64> = (1..n - 1)
                .map(|i| rule.reach(i - 1).min(rule.reach(i)).min(rule.reach(i + 1)))
                .collect();
            rule.farthest = (0..n + WINDOW + 1)
                .map(|b| {
                    let lo = b.saturating_sub(WINDOW).max(1);
                    let hi = (b + WINDOW).min(n - 2);
                    (lo..=hi)
                        .map(|j| nearest[j - 1])
                        .fold(f64::NEG_INFINITY, f64::max)
                })
                .collect();
        }
        Some(rule)
    }

    /// How far beam `i` shows free space: no return within range means free
    /// space as far as the map looks.
    fn reach(&self, i: usize) -> f64 {
        let r = self.scan.ranges[i];
        if r.is_nan() || r < MIN_RANGE {
            0.0
        } else {
            r.min(MAP_RANGE)
        }
    }

    /// Whether `p` stays in the map.
    pub fn keeps(&self, p: &Point2<f64>) -> bool {
        self.surely_kept(p) || self.keeps_exactly(p)
    }

    fn keeps_exactly(&self, p: &Point2<f64>) -> bool {
        let n = self.scan.ranges.len();
        let (dx, dy) = (p.x - self.origin.x, p.y - self.origin.y);
        let d = dx.hypot(dy);
        if d >= MAP_RANGE {
            return true;
        }
        let bearing = (dy.atan2(dx) - self.heading - self.scan.angle_min).rem_euclid(TAU);
        let beam = (bearing / self.scan.angle_step).round();
        if !(1.0..(n - 1) as f64).contains(&beam) {
            return true;
        }
        let i = beam as usize;
        let nearest = self.reach(i - 1).min(self.reach(i)).min(self.reach(i + 1));
        nearest < d + SEEN_THROUGH
    }

    /// True only where `keeps_exactly` is: the exact beam is within `WINDOW`
    /// of the rough one, and either it is not a beam the rule looks at or
    /// it and its neighbours stop short of the point.
    fn surely_kept(&self, p: &Point2<f64>) -> bool {
        if self.farthest.is_empty() {
            return false;
        }
        let step = self.scan.angle_step;
        let (dx, dy) = (p.x - self.origin.x, p.y - self.origin.y);
        let mut bearing = rough_atan2(dy, dx) - self.heading - self.scan.angle_min;
        for _ in 0..4 {
            if bearing < 0.0 {
                bearing += TAU;
            } else if bearing >= TAU {
                bearing -= TAU;
            }
        }
        // Near the wrap the exact remainder may land a whole turn away.
        if !(bearing >= 3.0 * step && bearing <= TAU - 3.0 * step) {
            return false;
        }
        // Rounded half up, truncating a positive value: within one of the
        // exact rounding, which the rough bearing is within one of.
        let b = (bearing / step + 0.5) as usize;
        let Some(&farthest) = self.farthest.get(b) else {
            // Every beam within the window is past the last.
            return true;
        };
        // `d` is the exact distance; its square root form differs from
        // `hypot` by a few units in the last place.
        let d = (dx * dx + dy * dy).sqrt();
        farthest < d + SEEN_THROUGH - 1e-9
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Uniform in [0, 1).
    fn rng(seed: u64) -> impl FnMut() -> f64 {
        let mut g = ilmr_geometry::SplitMix64::new(seed);
        move || g.uniform()
    }

    #[test]
    fn the_rough_bearing_is_within_its_error() {
        let mut worst: f64 = 0.0;
        for i in 0..200_000 {
            let a = f64::from(i) / 200_000.0 * TAU - PI;
            for r in [1e-3, 1.0, 7.9] {
                let (y, x) = (r * a.sin(), r * a.cos());
                let e = (rough_atan2(y, x) - y.atan2(x)).abs();
                worst = worst.max(e.min(TAU - e));
            }
        }
        assert!(worst < ROUGH_ERROR, "{worst}");
        assert!(
            worst > ROUGH_ERROR / 10.0,
            "the bound is not loose: {worst}"
        );
        assert_eq!(rough_atan2(0.0, 0.0), 0.0);
        assert_eq!(rough_atan2(0.0, -1.0), PI);
    }

    #[test]
    fn the_shortcut_keeps_only_what_the_rule_keeps() {
        let mut next = rng(9);
        let mut shortcut = 0;
        let mut dropped = 0;
        let mut total = 0;
        for round in 0..400 {
            let n = [361, 181, 541, 3, 721][round % 5];
            let fov = [PI, PI, 1.5 * PI, PI, TAU - 1e-3][round % 5];
            let step = fov / (n - 1) as f64;
            let ranges: Vec<f64> = (0..n)
                .map(|i| match (i / 7 + round) % 9 {
                    0 => f64::INFINITY,
                    1 => f64::NAN,
                    2 => 0.01,
                    3 => 30.0,
                    _ => 0.5 + 6.0 * next(),
                })
                .collect();
            let scan = Scan {
                device: "scanner".into(),
                t: 0.0,
                angle_min: -fov / 2.0 + 0.3 * next() - 0.15,
                angle_step: step,
                ranges,
            };
            let origin = Point2::new(10.0 * next() - 5.0, 10.0 * next() - 5.0);
            let heading = 8.0 * next() - 4.0;
            let Some(rule) = SeenThrough::new(&scan, origin, heading) else {
                panic!("{n} beams can clear points");
            };
            for k in 0..300 {
                // Points on the beams (where walls are), between them, at
                // the ends of their returns, and anywhere.
                let i = (k * 7 + round) % n;
                let bearing =
                    heading + scan.angle_min + step * (i as f64 + [0.0, 0.5, -0.49, 0.2][k % 4]);
                let r = match k % 3 {
                    0 => scan.ranges[i].min(9.0),
                    1 => scan.ranges[i].min(9.0) - SEEN_THROUGH + [1e-12, -1e-12, 0.0][k % 3],
                    _ => 9.0 * next(),
                };
                let r = if r.is_finite() { r } else { 3.0 };
                let p = Point2::new(origin.x + r * bearing.cos(), origin.y + r * bearing.sin());
                let want = rule.keeps_exactly(&p);
                assert_eq!(rule.keeps(&p), want, "round {round}, point {k}");
                shortcut += usize::from(rule.surely_kept(&p));
                dropped += usize::from(!want);
                total += 1;
            }
        }
        assert!(
            shortcut > total / 3,
            "the shortcut is taken: {shortcut} of {total}"
        );
        assert!(
            dropped > total / 20,
            "points are dropped: {dropped} of {total}"
        );
    }
}

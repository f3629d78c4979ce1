//! The last line of defence against touching anything: the robot's rectangle
//! swept along the arc it is commanded to drive. The checked area of equations
//! (11)-(12) is a band as wide as the robot round the path of its front; a
//! turning robot's outer front corner and inner flank leave that band, which is
//! how a sharp `turn` brushed the lab bench in the soak test. The supervisor
//! holds the robot when a point would enter the swept rectangle within its
//! braking distance plus the margin, whatever obstacle avoidance is doing.

use ilmr_motion::obstacle::Bounds;
use nalgebra::Point2;

/// The robot's outline around its reference point, metres.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Footprint {
    /// Reference point to the front.
    pub front: f64,
    /// Reference point to the rear.
    pub rear: f64,
    pub half_width: f64,
}

/// Steps of the sweep along the arc, metres.
const STEP: f64 = 0.05;
/// Points this close outside the outline already count as touching, metres.
const SKIN: f64 = 0.05;
/// Rounding allowance of the distance bounds that skip poses, metres.
const SLACK: f64 = 1e-6;
/// Most poses one sweep holds. The distance comes from the braking distance
/// plus `stop_margin`, which a robot model bounds; this bound holds whatever
/// a HAL or model reports, so memory never follows an unchecked number.
const MAX_POSES: usize = 4000;
/// Farthest a sweep looks, metres: `MAX_POSES` steps. No robot brakes over
/// that, and a point further off cannot matter to this tick's stop.
const MAX_DISTANCE: f64 = MAX_POSES as f64 * STEP;

/// One sweep of a footprint along an arc, its poses worked out once: the box
/// that holds every point it can meet, and the first contact.
pub(crate) struct Sweep {
    footprint: Footprint,
    pose: (f64, f64, f64),
    reach: f64,
    /// (travel, x, y, sin h, cos h): the trigonometry once per pose, not
    /// once per pose and point.
    poses: Vec<(f64, f64, f64, f64, f64)>,
    /// How far a point of the outline moves from one pose to the next, and
    /// whether poses may be skipped by it.
    drift: f64,
    skips: bool,
}

impl Footprint {
    fn holds(&self, local: (f64, f64)) -> bool {
        local.0 >= -self.rear - SKIN
            && local.0 <= self.front + SKIN
            && local.1.abs() <= self.half_width + SKIN
    }

    /// The outline, skin included, in the robot's frame: (lo, hi).
    fn outline(&self) -> ((f64, f64), (f64, f64)) {
        let y = self.half_width + SKIN;
        ((-self.rear - SKIN, -y), (self.front + SKIN, y))
    }

    /// How far from the start pose, along either axis, a sweep over
    /// `distance` metres looks: points further off are skipped.
    pub fn reach(&self, distance: f64) -> f64 {
        distance + self.front.max(self.rear).hypot(self.half_width) + SKIN
    }

    /// The robot at `(x, y, h)` driving `distance` metres along curvature `c`
    /// (1/m) in direction `sign` (+1 forwards, -1 backwards).
    pub fn sweep(&self, pose: (f64, f64, f64), sign: f64, c: f64, distance: f64) -> Sweep {
        // NaN stays NaN (clamp keeps it), which sweeps nothing, as before.
        let distance = distance.clamp(-MAX_DISTANCE, MAX_DISTANCE);
        let steps = (distance / STEP).ceil().max(1.0).min(MAX_POSES as f64) as usize;
        let poses = (0..=steps)
            .map(|i| {
                let d = distance * i as f64 / steps as f64;
                let (x, y, h) = along(pose, sign * d, c);
                let (s, co) = h.sin_cos();
                (d, x, y, s, co)
            })
            .collect();
        // From one pose to the next the outline moves no point of itself
        // further than the step along the arc plus the turn at its farthest
        // corner. Poses are skipped only along a positive distance, where
        // travel grows with the pose and skipping cannot pass over the stop
        // at the first contact found so far.
        let (lo, hi) = self.outline();
        let corner = lo.0.abs().max(hi.0.abs()).hypot(hi.1);
        let step = distance / steps as f64;
        let drift = step * (1.0 + c.abs() * corner);
        Sweep {
            footprint: *self,
            pose,
            reach: self.reach(distance),
            poses,
            drift,
            skips: step > 0.0 && drift.is_finite(),
        }
    }

    /// `sweep(..).first_contact(points)`.
    #[cfg(test)]
    pub fn first_contact(
        &self,
        pose: (f64, f64, f64),
        sign: f64,
        c: f64,
        distance: f64,
        points: impl Iterator<Item = Point2<f64>>,
    ) -> f64 {
        self.sweep(pose, sign, c, distance).first_contact(points)
    }
}

impl Sweep {
    /// A box that holds every point the sweep can meet: the outline at every
    /// pose, within the reach.
    pub fn bounds(&self) -> Bounds {
        let (x, y, _) = self.pose;
        let reach = Bounds::square((x, y), self.reach);
        let outline = self.footprint.outline();
        let swept = self
            .poses
            .iter()
            .map(|&(_, x, y, s, c)| Bounds::turned((x, y), (s, c), outline.0, outline.1))
            .reduce(|a, b| a.or(&b));
        swept.map_or(reach, |b| b.and(&reach))
    }

    /// The travel, metres, after which the first of `points` would be inside
    /// the outline; infinity when none is. Points inside the outline already
    /// are skipped: holding the robot cannot keep it off them, and it must be
    /// free to drive away.
    pub fn first_contact(&self, points: impl Iterator<Item = Point2<f64>>) -> f64 {
        let (x0, y0, _) = self.pose;
        let (lo, hi) = self.footprint.outline();
        let mut first = f64::INFINITY;
        for p in points {
            if (p.x - x0).abs() > self.reach || (p.y - y0).abs() > self.reach {
                continue;
            }
            let mut inside_now = true;
            let mut i = 0;
            while let Some(&(d, x, y, s, co)) = self.poses.get(i) {
                if d >= first {
                    break;
                }
                let (dx, dy) = (p.x - x, p.y - y);
                let local = (co * dx + s * dy, -s * dx + co * dy);
                let hit = self.footprint.holds(local);
                if d == 0.0 {
                    inside_now = hit;
                    if hit {
                        // Inside already, it never counts: only another pose
                        // at travel 0 could say otherwise, and that one
                        // records nothing either.
                        break;
                    }
                } else if hit && !inside_now {
                    first = d;
                    break;
                }
                i += 1;
                if self.skips && !hit {
                    // `gap` outside the outline now: not inside it for
                    // `gap / drift` poses. Truncation rounds the count down,
                    // never past a pose the point could be inside.
                    let ex = (lo.0 - local.0).max(local.0 - hi.0).max(0.0);
                    let ey = (local.1.abs() - hi.1).max(0.0);
                    let gap = (ex * ex + ey * ey).sqrt() - SLACK;
                    let more = (gap / self.drift) as usize;
                    i += more.saturating_sub(1);
                }
            }
        }
        first
    }
}

/// The pose after `u` metres of signed travel along curvature `c` from `pose`.
fn along(pose: (f64, f64, f64), u: f64, c: f64) -> (f64, f64, f64) {
    let p = ilmr_motion::Pose::new(pose.0, pose.1, pose.2).advance(u, c);
    (p.x, p.y, p.h)
}

#[cfg(test)]
mod tests {
    use super::*;

    const MORO: Footprint = Footprint {
        front: 0.95,
        rear: 0.25,
        half_width: 0.3,
    };

    #[test]
    fn along_an_arc_the_pose_stays_on_the_circle() {
        let (x, y, h) = along((0.0, 0.0, 0.0), std::f64::consts::FRAC_PI_2, 1.0);
        assert!((x - 1.0).abs() < 1e-9 && (y - 1.0).abs() < 1e-9);
        assert!((h - std::f64::consts::FRAC_PI_2).abs() < 1e-9);
        let (x, _, _) = along((0.0, 0.0, 0.0), -0.5, 0.0);
        assert!((x + 0.5).abs() < 1e-12);
    }

    #[test]
    fn a_point_ahead_is_met_after_the_gap() {
        let d = MORO.first_contact(
            (0.0, 0.0, 0.0),
            1.0,
            0.0,
            1.0,
            [Point2::new(1.5, 0.0)].into_iter(),
        );
        assert!((d - 0.5).abs() <= STEP + 1e-9, "{d}");
        // Behind a reversing robot.
        let d = MORO.first_contact(
            (0.0, 0.0, 0.0),
            -1.0,
            0.0,
            1.0,
            [Point2::new(-0.7, 0.1)].into_iter(),
        );
        assert!((d - 0.4).abs() <= STEP + 1e-9, "{d}");
    }

    #[test]
    fn the_outer_front_corner_of_a_turn_is_swept() {
        // Turning right on a 1.33 m radius: the bench corner beside the front
        // point's path but inside the corner's sweep is met.
        let c = -0.75;
        let corner = Point2::new(1.45, -0.35);
        let band_miss = {
            // The front point's own path never comes within half a width of it.
            (0..=40)
                .map(|i| {
                    let (x, y, h) = along((0.0, 0.0, 0.0), 0.05 * f64::from(i), c);
                    let f = (x + 0.95 * h.cos(), y + 0.95 * h.sin());
                    (f.0 - corner.x).hypot(f.1 - corner.y)
                })
                .fold(f64::INFINITY, f64::min)
        };
        assert!(band_miss > 0.0);
        let d = MORO.first_contact((0.0, 0.0, 0.0), 1.0, c, 2.0, [corner].into_iter());
        assert!(d.is_finite(), "the sweep meets the corner");
    }

    /// The sweep as it was before poses were skipped: every pose of every
    /// point within reach.
    fn every_pose(
        f: &Footprint,
        pose: (f64, f64, f64),
        sign: f64,
        c: f64,
        distance: f64,
        points: &[Point2<f64>],
    ) -> f64 {
        let reach = f.reach(distance);
        let steps = (distance / STEP).ceil().max(1.0) as usize;
        let mut first = f64::INFINITY;
        for p in points {
            if (p.x - pose.0).abs() > reach || (p.y - pose.1).abs() > reach {
                continue;
            }
            let mut inside_now = true;
            for i in 0..=steps {
                let d = distance * i as f64 / steps as f64;
                if d >= first {
                    break;
                }
                let (x, y, h) = along(pose, sign * d, c);
                let (s, co) = h.sin_cos();
                let (dx, dy) = (p.x - x, p.y - y);
                let hit = f.holds((co * dx + s * dy, -s * dx + co * dy));
                if d == 0.0 {
                    inside_now = hit;
                    continue;
                }
                if hit && !inside_now {
                    first = d;
                    break;
                }
            }
        }
        first
    }

    #[test]
    fn skipping_poses_meets_the_same_first_contact() {
        let mut rng = ilmr_geometry::SplitMix64::new(17);
        let mut next = move || rng.uniform();
        let mut met = 0;
        for round in 0..2000 {
            let f = Footprint {
                front: 0.2 + 1.2 * next(),
                rear: 0.6 * next(),
                half_width: 0.15 + 0.5 * next(),
            };
            let pose = (4.0 * next() - 2.0, 4.0 * next() - 2.0, 7.0 * next() - 3.5);
            let sign = if next() < 0.3 { -1.0 } else { 1.0 };
            let c = if next() < 0.3 {
                0.0
            } else {
                3.0 * next() - 1.5
            };
            let distance = match round % 5 {
                0 => 0.0,
                1 => -0.4 * next(),
                _ => 2.5 * next(),
            };
            // Half of them close round the robot, where poses are skipped
            // by a few at a time.
            let points: Vec<Point2<f64>> = (0..40)
                .map(|i| {
                    let r = if i % 2 == 0 { 4.0 } else { 1.5 };
                    Point2::new(
                        pose.0 + r * (2.0 * next() - 1.0),
                        pose.1 + r * (2.0 * next() - 1.0),
                    )
                })
                .collect();
            let want = every_pose(&f, pose, sign, c, distance, &points);
            let sweep = f.sweep(pose, sign, c, distance);
            let got = sweep.first_contact(points.iter().copied());
            assert_eq!(got.to_bits(), want.to_bits(), "round {round}");
            // Only the points in the box: the same contact.
            let b = sweep.bounds();
            let inside = points.iter().copied().filter(|p| b.contains((p.x, p.y)));
            assert_eq!(
                sweep.first_contact(inside).to_bits(),
                want.to_bits(),
                "round {round}"
            );
            met += usize::from(want.is_finite());
        }
        assert!(met > 300, "contacts met: {met}");
    }

    #[test]
    fn a_huge_or_infinite_distance_sweeps_a_bounded_number_of_poses() {
        for distance in [1e6, 1e308, f64::INFINITY, f64::MAX, -1e308, f64::NAN] {
            let sweep = MORO.sweep((0.0, 0.0, 0.0), 1.0, 0.3, distance);
            assert!(sweep.poses.len() <= MAX_POSES + 1, "{distance}");
            assert!(sweep.reach.is_finite() || distance.is_nan(), "{distance}");
            let _ = sweep.bounds();
        }
        // A point ahead is still met on a sweep of any length.
        let d = MORO.first_contact(
            (0.0, 0.0, 0.0),
            1.0,
            0.0,
            1e308,
            [Point2::new(10.0, 0.0)].into_iter(),
        );
        assert!((d - 9.0).abs() <= STEP + 1e-9, "{d}");
    }

    #[test]
    fn a_point_already_inside_does_not_hold_the_robot() {
        let d = MORO.first_contact(
            (0.0, 0.0, 0.0),
            1.0,
            0.0,
            1.0,
            [Point2::new(0.5, 0.0)].into_iter(),
        );
        assert!(d.is_infinite());
    }
}

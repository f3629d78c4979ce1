//! The last line of defence against touching anything: the robot's rectangle
//! swept along the arc it is commanded to drive. The checked area of equations
//! (11)-(12) is a band as wide as the robot round the path of its front; a
//! turning robot's outer front corner and inner flank leave that band, which is
//! how a sharp `turn` brushed the lab bench in the soak test. The supervisor
//! holds the robot when a point would enter the swept rectangle within its
//! braking distance plus the margin, whatever obstacle avoidance is doing.

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

impl Footprint {
    fn holds(&self, local: (f64, f64)) -> bool {
        local.0 >= -self.rear - SKIN
            && local.0 <= self.front + SKIN
            && local.1.abs() <= self.half_width + SKIN
    }

    /// The travel, metres, after which the first of `points` would be inside
    /// the outline of a robot at `(x, y, h)` driving `distance` metres along
    /// curvature `c` (1/m) in direction `sign` (+1 forwards, -1 backwards);
    /// infinity when none is. Points inside the outline already are skipped:
    /// holding the robot cannot keep it off them, and it must be free to drive
    /// away.
    pub fn first_contact(
        &self,
        pose: (f64, f64, f64),
        sign: f64,
        c: f64,
        distance: f64,
        points: impl Iterator<Item = Point2<f64>>,
    ) -> f64 {
        let reach = distance + self.front.max(self.rear).hypot(self.half_width) + SKIN;
        let steps = (distance / STEP).ceil().max(1.0) as usize;
        // (travel, x, y, sin h, cos h): the trigonometry once per pose, not
        // once per pose and point.
        let poses: Vec<(f64, f64, f64, f64, f64)> = (0..=steps)
            .map(|i| {
                let d = distance * i as f64 / steps as f64;
                let (x, y, h) = along(pose, sign * d, c);
                let (s, co) = h.sin_cos();
                (d, x, y, s, co)
            })
            .collect();
        let mut first = f64::INFINITY;
        for p in points {
            if (p.x - pose.0).abs() > reach || (p.y - pose.1).abs() > reach {
                continue;
            }
            let mut inside_now = true;
            for &(d, x, y, s, co) in &poses {
                if d >= first {
                    break;
                }
                let (dx, dy) = (p.x - x, p.y - y);
                let local = (co * dx + s * dy, -s * dx + co * dy);
                let hit = self.holds(local);
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

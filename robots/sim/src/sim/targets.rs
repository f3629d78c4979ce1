//! Moving targets walk their waypoints at constant speed.

use crate::geometry::{PlaneVector, Point2};
use crate::world::{PathMode, Target};

#[derive(Debug, Clone, PartialEq)]
pub struct Walker {
    /// Start followed by the waypoints.
    points: Vec<Point2<f64>>,
    pub position: Point2<f64>,
    next: usize,
    forward: bool,
    speed: f64,
    mode: PathMode,
    standing: bool,
    /// Metres after which a `loop` or `back_and_forth` walk is where it was,
    /// going the same way; 0 for `once`.
    cycle: f64,
}

impl Walker {
    pub fn new(t: &Target) -> Self {
        let mut points = vec![t.start];
        points.extend(t.waypoints.iter().copied());
        let length: f64 = points.windows(2).map(|w| (w[0] - w[1]).hypot()).sum();
        let cycle = match t.path {
            PathMode::Once => 0.0,
            PathMode::Loop => length + (points[points.len() - 1] - points[0]).hypot(),
            PathMode::BackAndForth => 2.0 * length,
        };
        Walker {
            cycle,
            position: t.start,
            next: 1,
            forward: true,
            speed: t.speed,
            mode: t.path,
            // A path of zero length would spin the walking loop forever.
            standing: t.speed <= 0.0 || length <= 1e-9,
            points,
        }
    }

    pub fn step(&mut self, dt: f64) {
        let mut left = self.speed * dt;
        // Whole rounds leave the walker where it is, so only the rest is
        // walked: a step never visits more than one round of waypoints,
        // however fast the target (issue 12: 1e12 m/s on a loop never ended).
        if self.cycle > 0.0 && left >= self.cycle {
            left %= self.cycle;
        }
        if !left.is_finite() {
            return;
        }
        while left > 0.0 && !self.standing {
            let goal = self.points[self.next];
            let d = (self.position - goal).hypot();
            if d > left {
                self.position = self.position + (goal - self.position) * (left / d);
                return;
            }
            self.position = goal;
            left -= d;
            self.advance();
        }
    }

    fn advance(&mut self) {
        let n = self.points.len();
        match self.mode {
            PathMode::Once => {
                if self.next + 1 >= n {
                    self.standing = true;
                } else {
                    self.next += 1;
                }
            }
            PathMode::Loop => self.next = (self.next + 1) % n,
            PathMode::BackAndForth => {
                if self.forward && self.next + 1 >= n {
                    self.forward = false;
                    self.next = n - 2;
                } else if !self.forward && self.next == 0 {
                    self.forward = true;
                    self.next = 1;
                } else if self.forward {
                    self.next += 1;
                } else {
                    self.next -= 1;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::world::Colour;

    fn target(path: PathMode) -> Target {
        Target {
            name: "user".into(),
            colour: Colour::Yellow,
            start: Point2::new(0.0, 0.0),
            radius: 0.25,
            speed: 1.0,
            waypoints: vec![Point2::new(2.0, 0.0), Point2::new(2.0, 1.0)],
            path,
        }
    }

    #[test]
    fn walks_once_loops_and_turns_back() {
        let mut w = Walker::new(&target(PathMode::Once));
        w.step(2.5);
        assert!((w.position - Point2::new(2.0, 0.5)).hypot() < 1e-12);
        w.step(10.0);
        assert!((w.position - Point2::new(2.0, 1.0)).hypot() < 1e-12);

        let mut w = Walker::new(&target(PathMode::Loop));
        // 2 + 1 + sqrt(5) round; 0.5 m past the start.
        w.step(3.0 + 5f64.sqrt() + 0.5);
        assert!((w.position - Point2::new(0.5, 0.0)).hypot() < 1e-9);

        let mut w = Walker::new(&target(PathMode::BackAndForth));
        w.step(3.5);
        assert!((w.position - Point2::new(2.0, 0.5)).hypot() < 1e-12);
        w.step(2.5);
        assert!((w.position - Point2::new(0.0, 0.0)).hypot() < 1e-12);
        w.step(1.0);
        assert!((w.position - Point2::new(1.0, 0.0)).hypot() < 1e-12);
    }

    #[test]
    fn a_very_fast_target_steps_in_bounded_time_and_stays_on_its_path() {
        for path in [PathMode::Once, PathMode::Loop, PathMode::BackAndForth] {
            let mut t = target(path);
            t.speed = 1e12;
            let mut w = Walker::new(&t);
            for _ in 0..100 {
                w.step(0.01);
            }
            assert!(w.position.coords.is_finite(), "{path:?}");
            assert!(
                (0.0..=2.0).contains(&w.position.x) && (0.0..=1.0).contains(&w.position.y),
                "{path:?}: {:?}",
                w.position
            );
            t.speed = f64::MAX;
            let mut w = Walker::new(&t);
            w.step(1.0);
            assert!(w.position.coords.is_finite(), "{path:?}");
        }
        // Whole rounds: back where it started.
        let mut w = Walker::new(&target(PathMode::Loop));
        w.step(10.0 * (3.0 + 5f64.sqrt()));
        assert!(
            (w.position - Point2::new(0.0, 0.0)).hypot() < 1e-6,
            "{:?}",
            w.position
        );
    }
}

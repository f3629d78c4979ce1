//! Which solids each beam of a fan can meet. A scan casts hundreds of beams
//! from one origin; working out once per scan which directions each solid
//! covers, seen from there, lets every beam test only the solids that lie its
//! way. A beam meets exactly what [`Scene::ray`] over every solid meets: the
//! solids left out of its list are ones its exact test misses (the beam points
//! at least a beam's width past their outline, or they lie beyond the range),
//! and the rest are tested in scene order, so ties go as they did.

use super::{PlaneVector, Point2, Scene, Shape, Vector2};
use std::cmp::Ordering;
use std::f64::consts::{PI, TAU};

/// The beams `first + i * step`, `i < count`, each with its candidate solids.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Fan {
    /// `items[starts[i]..starts[i + 1]]`: beam `i`'s solids, ascending.
    starts: Vec<usize>,
    items: Vec<usize>,
}

/// An origin this close to a solid's outline (m) sees it in every direction:
/// corners seen from nearer would turn the angle bounds into rounding.
const NEAR: f64 = 1e-3;
/// Added to every angular bound, radians, on top of a whole beam each side.
const SLACK: f64 = 1e-6;

/// The directions a solid covers, as angles relative to the direction of its
/// centre from `origin`, or `None` when it covers them all.
fn span(shape: &Shape, origin: Point2<f64>) -> Option<(f64, f64)> {
    let to_centre = shape.center() - origin;
    match shape {
        Shape::Circle(c) => {
            let d = to_centre.hypot();
            if d.partial_cmp(&(c.radius + NEAR)) != Some(Ordering::Greater) {
                return None;
            }
            let a = (c.radius / d).asin();
            Some((-a, a))
        }
        Shape::Box(b) => {
            let l = Vector2::new(
                -to_centre.dot(&b.axis),
                -to_centre.dot(&b.axis.rotated_left()),
            );
            if l.x.abs() <= b.half.x + NEAR && l.y.abs() <= b.half.y + NEAR {
                return None;
            }
            // Seen from outside, a box lies within half a turn round the
            // direction of its centre: each corner's angle from it is in
            // (-pi, pi) without wrapping.
            let (mut lo, mut hi) = (0.0_f64, 0.0_f64);
            for corner in b.corners() {
                let v = corner - origin;
                let a = to_centre.perp(&v).atan2(to_centre.dot(&v));
                lo = lo.min(a);
                hi = hi.max(a);
            }
            Some((lo, hi))
        }
    }
}

impl Scene {
    /// The fan of `count` beams from `origin` at angles `first + i * step`
    /// reaching `max_range`, for [`Fan::ray`].
    pub fn fan(
        &self,
        origin: Point2<f64>,
        first: f64,
        step: f64,
        count: usize,
        max_range: f64,
    ) -> Fan {
        if count == 0 {
            return Fan {
                starts: vec![0],
                items: Vec::new(),
            };
        }
        // Runs of beams (solid, first, last) in scene order: a solid's span,
        // and that span a turn either way, which never overlap.
        let mut runs: Vec<(usize, usize, usize)> = Vec::new();
        let usable =
            step > 0.0 && step.is_finite() && first.is_finite() && origin.coords.is_finite();
        // Only the solids whose shape may lie within range: the rest would
        // be left out below anyway, or could not be met within the range.
        let near = if origin.coords.is_finite() && max_range.is_finite() {
            self.within_reach(origin, max_range + NEAR)
        } else {
            (0..self.solids().len()).collect()
        };
        for j in near {
            let s = &self.solids()[j];
            if !s.active {
                continue;
            }
            let centre = s.shape.center();
            let far = (centre - origin).hypot() - s.shape.bounding_radius();
            if far > max_range + NEAR {
                continue;
            }
            let span = span(&s.shape, origin).filter(|_| usable);
            let Some((lo, hi)) = span.filter(|(lo, hi)| hi - lo + 4.0 * step < PI) else {
                runs.push((j, 0, count - 1));
                continue;
            };
            let base = ((centre - origin).polar_angle() - first).rem_euclid(TAU);
            for turn in [-TAU, 0.0, TAU] {
                let a = (base + lo - SLACK + turn) / step - 1.0;
                let b = (base + hi + SLACK + turn) / step + 1.0;
                if !(b >= 0.0 && a <= (count - 1) as f64) {
                    continue;
                }
                let first_beam = if a > 0.0 { a.floor() as usize } else { 0 };
                let last_beam = (b.ceil() as usize).min(count - 1);
                runs.push((j, first_beam, last_beam));
            }
        }
        // Counted per beam, then filled in scene order.
        let mut starts = vec![0usize; count + 1];
        for &(_, a, b) in &runs {
            for beam in a..=b {
                starts[beam + 1] += 1;
            }
        }
        for i in 1..starts.len() {
            starts[i] += starts[i - 1];
        }
        let mut items = vec![0usize; starts[count]];
        let mut next = starts.clone();
        for &(j, a, b) in &runs {
            for beam in a..=b {
                items[next[beam]] = j;
                next[beam] += 1;
            }
        }
        Fan { starts, items }
    }
}

impl Fan {
    /// What beam `beam` (direction `dir`, from the fan's origin) meets within
    /// `max_range`: exactly `scene.ray(origin, dir, max_range)`.
    pub fn ray(
        &self,
        scene: &Scene,
        beam: usize,
        origin: Point2<f64>,
        dir: Vector2<f64>,
        max_range: f64,
    ) -> Option<super::Hit> {
        match (self.starts.get(beam), self.starts.get(beam + 1)) {
            (Some(&a), Some(&b)) => {
                scene.ray_among(origin, dir, max_range, self.items[a..b].iter().copied())
            }
            _ => scene.ray(origin, dir, max_range),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{Circle, Obb, Solid, SolidRef};

    /// Uniform in [0, 1), from the simulator's own seeded generator.
    fn rng(seed: u64) -> impl FnMut() -> f64 {
        let mut rng = crate::rng::Rng::new(seed);
        move || rng.uniform()
    }

    #[test]
    fn every_beam_meets_what_a_ray_over_every_solid_meets() {
        let mut next = rng(3);
        let mut hits = 0;
        for round in 0..300 {
            let mut solids: Vec<Solid> = (0..30)
                .map(|i| {
                    let c = Point2::new(20.0 * next() - 10.0, 20.0 * next() - 10.0);
                    let shape = if i % 4 == 0 {
                        Shape::Circle(Circle::new(c, 0.05 + next()))
                    } else {
                        // Walls long and short, some meeting at the same
                        // place, so that beams tie.
                        let (len, w) = (0.2 + 12.0 * next(), 0.05 + 0.3 * next());
                        Shape::Box(Obb::new(c, 7.0 * next(), len, w))
                    };
                    Solid::new(shape, SolidRef::Wall(i))
                })
                .collect();
            solids.push(solids[3].clone());
            solids[5].active = round % 2 == 0;
            let scene = Scene::new(solids);
            let origin = match round % 5 {
                // On a solid's outline or inside it.
                0 => scene.solids()[1].shape.center(),
                _ => Point2::new(16.0 * next() - 8.0, 16.0 * next() - 8.0),
            };
            let (count, fov) = match round % 3 {
                0 => (361, PI),
                1 => (181, 1.5 * PI),
                _ => (721, TAU),
            };
            let first = 7.0 * next() - 3.5;
            let step = fov / (count - 1) as f64;
            let range = [30.0, 4.0][round % 2];
            let fan = scene.fan(origin, first, step, count, range);
            for i in 0..count {
                let dir = Vector2::from_angle(first + i as f64 * step);
                let want = scene.ray(origin, dir, range);
                let got = fan.ray(&scene, i, origin, dir, range);
                assert_eq!(
                    got.map(|h| (h.distance.to_bits(), h.what)),
                    want.map(|h| (h.distance.to_bits(), h.what)),
                    "round {round}, beam {i}"
                );
                hits += usize::from(want.is_some());
            }
            // The fan is smaller than every solid for every beam.
            if round % 5 != 0 {
                assert!(
                    fan.items.len() < count * scene.solids().len() / 2,
                    "round {round}"
                );
            }
        }
        assert!(hits > 50_000, "{hits}");
    }

    #[test]
    fn a_beam_outside_the_fan_falls_back_to_every_solid() {
        let scene = Scene::new(vec![Solid::new(
            Shape::Circle(Circle::new(Point2::new(3.0, 0.0), 0.5)),
            SolidRef::Obstacle(0),
        )]);
        let fan = scene.fan(Point2::origin(), 0.0, f64::NAN, 3, 10.0);
        let dir = Vector2::new(1.0, 0.0);
        assert_eq!(
            fan.ray(&scene, 0, Point2::origin(), dir, 10.0),
            scene.ray(Point2::origin(), dir, 10.0)
        );
        assert_eq!(
            fan.ray(&scene, 7, Point2::origin(), dir, 10.0),
            scene.ray(Point2::origin(), dir, 10.0)
        );
    }
}

//! The two solid shapes and their exact ray and overlap tests. Walls are thick
//! segments, which are oriented boxes, so two shapes cover every solid.

use super::{PlaneVector, Point2, Vector2, xy};
use serde::{Deserialize, Serialize};

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Circle {
    #[serde(with = "xy")]
    pub center: Point2<f64>,
    pub radius: f64,
}

/// An oriented box: centre, heading of its local x axis, and half extents
/// along its local axes.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Obb {
    #[serde(with = "xy")]
    pub center: Point2<f64>,
    /// Unit vector of the local x axis.
    #[serde(with = "xy")]
    pub axis: Vector2<f64>,
    #[serde(with = "xy")]
    pub half: Vector2<f64>,
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum Shape {
    Circle(Circle),
    Box(Obb),
}

impl Obb {
    /// A box `length` x `width` centred at `center` with its length along `heading`.
    pub fn new(center: Point2<f64>, heading: f64, length: f64, width: f64) -> Self {
        Obb {
            center,
            axis: Vector2::from_angle(heading),
            half: Vector2::new(length / 2.0, width / 2.0),
        }
    }

    /// The thick segment from `a` to `b`: its thickness straddles the centre line.
    pub fn from_segment(a: Point2<f64>, b: Point2<f64>, thickness: f64) -> Self {
        let d = b - a;
        Obb::new(
            nalgebra::center(&a, &b),
            d.polar_angle(),
            d.hypot(),
            thickness,
        )
    }

    fn local_point(&self, p: Point2<f64>) -> Vector2<f64> {
        self.local_dir(p - self.center)
    }

    fn local_dir(&self, v: Vector2<f64>) -> Vector2<f64> {
        Vector2::new(v.dot(&self.axis), v.dot(&self.axis.rotated_left()))
    }

    pub fn corners(&self) -> [Point2<f64>; 4] {
        let ex = self.axis * self.half.x;
        let ey = self.axis.rotated_left() * self.half.y;
        [
            self.center + ex + ey,
            self.center - ex + ey,
            self.center - ex - ey,
            self.center + ex - ey,
        ]
    }

    pub fn contains(&self, p: Point2<f64>) -> bool {
        let l = self.local_point(p);
        l.x.abs() <= self.half.x && l.y.abs() <= self.half.y
    }

    /// Radius of the circle around the centre that holds the whole box.
    pub fn bounding_radius(&self) -> f64 {
        self.half.hypot()
    }

    /// Distance along the ray to the first boundary crossing (slab test in
    /// the box frame). A ray starting inside hits at 0.
    pub fn ray(&self, origin: Point2<f64>, dir: Vector2<f64>) -> Option<f64> {
        let o = self.local_point(origin);
        let d = self.local_dir(dir);
        let mut t_min = 0.0_f64;
        let mut t_max = f64::INFINITY;
        for (o, d, h) in [(o.x, d.x, self.half.x), (o.y, d.y, self.half.y)] {
            if d.abs() < 1e-15 {
                if o.abs() > h {
                    return None;
                }
            } else {
                let inv = 1.0 / d;
                let (t1, t2) = ((-h - o) * inv, (h - o) * inv);
                let (near, far) = if t1 < t2 { (t1, t2) } else { (t2, t1) };
                t_min = t_min.max(near);
                t_max = t_max.min(far);
                if t_min > t_max {
                    return None;
                }
            }
        }
        Some(t_min)
    }

    /// Separating-axis test between two oriented boxes.
    pub fn overlaps_box(&self, o: &Obb) -> bool {
        let axes = [
            self.axis,
            self.axis.rotated_left(),
            o.axis,
            o.axis.rotated_left(),
        ];
        let d = o.center - self.center;
        axes.iter().all(|ax| {
            let ra = self.half.x * self.axis.dot(ax).abs()
                + self.half.y * self.axis.rotated_left().dot(ax).abs();
            let rb =
                o.half.x * o.axis.dot(ax).abs() + o.half.y * o.axis.rotated_left().dot(ax).abs();
            d.dot(ax).abs() <= ra + rb
        })
    }

    pub fn overlaps_circle(&self, c: &Circle) -> bool {
        let l = self.local_point(c.center);
        let q = Vector2::new(
            l.x.clamp(-self.half.x, self.half.x),
            l.y.clamp(-self.half.y, self.half.y),
        );
        (l - q).norm_squared() <= c.radius * c.radius
    }
}

impl Circle {
    pub fn new(center: Point2<f64>, radius: f64) -> Self {
        Circle { center, radius }
    }

    /// Distance along the unit-direction ray to the circle; 0 from inside.
    pub fn ray(&self, origin: Point2<f64>, dir: Vector2<f64>) -> Option<f64> {
        let oc = self.center - origin;
        let proj = oc.dot(&dir);
        let perp_sq = oc.norm_squared() - proj * proj;
        let r_sq = self.radius * self.radius;
        if perp_sq > r_sq {
            return None;
        }
        let half_chord = (r_sq - perp_sq).max(0.0).sqrt();
        let t_in = proj - half_chord;
        let t_out = proj + half_chord;
        if t_out < 0.0 {
            None
        } else {
            Some(t_in.max(0.0))
        }
    }
}

impl Shape {
    pub fn center(&self) -> Point2<f64> {
        match self {
            Shape::Circle(c) => c.center,
            Shape::Box(b) => b.center,
        }
    }

    pub fn bounding_radius(&self) -> f64 {
        match self {
            Shape::Circle(c) => c.radius,
            Shape::Box(b) => b.bounding_radius(),
        }
    }

    /// `dir` must be a unit vector.
    pub fn ray(&self, origin: Point2<f64>, dir: Vector2<f64>) -> Option<f64> {
        match self {
            Shape::Circle(c) => c.ray(origin, dir),
            Shape::Box(b) => b.ray(origin, dir),
        }
    }

    pub fn overlaps_box(&self, footprint: &Obb) -> bool {
        match self {
            Shape::Circle(c) => footprint.overlaps_circle(c),
            Shape::Box(b) => footprint.overlaps_box(b),
        }
    }

    pub fn contains(&self, p: Point2<f64>) -> bool {
        match self {
            Shape::Circle(c) => (p - c.center).norm_squared() <= c.radius * c.radius,
            Shape::Box(b) => b.contains(p),
        }
    }

    pub fn translate_to(&mut self, center: Point2<f64>) {
        match self {
            Shape::Circle(c) => c.center = center,
            Shape::Box(b) => b.center = center,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 1e-9
    }

    #[test]
    fn ray_hits_axis_aligned_box_face() {
        let b = Obb::new(Point2::new(5.0, 0.0), 0.0, 2.0, 1.0);
        let t = b.ray(Point2::origin(), Vector2::new(1.0, 0.0));
        assert!(close(t.unwrap_or(-1.0), 4.0));
        // Grazing above the box misses.
        assert_eq!(b.ray(Point2::new(0.0, 0.6), Vector2::new(1.0, 0.0)), None);
        // Pointing away misses.
        assert_eq!(b.ray(Point2::origin(), Vector2::new(-1.0, 0.0)), None);
    }

    #[test]
    fn ray_hits_rotated_box_at_its_corner_distance() {
        // A unit square turned 45 degrees: its near corner is sqrt(2)/2 before the centre.
        let b = Obb::new(Point2::new(3.0, 0.0), std::f64::consts::FRAC_PI_4, 1.0, 1.0);
        let t = b
            .ray(Point2::origin(), Vector2::new(1.0, 0.0))
            .unwrap_or(-1.0);
        assert!(close(t, 3.0 - 0.5_f64.sqrt()), "{t}");
    }

    #[test]
    fn ray_hits_circle_and_starts_inside() {
        let c = Circle::new(Point2::new(0.0, 10.0), 1.0);
        let t = c
            .ray(Point2::origin(), Vector2::new(0.0, 1.0))
            .unwrap_or(-1.0);
        assert!(close(t, 9.0));
        // Offset by 0.6 of the radius: the chord enters at 10 - 0.8.
        let t = c
            .ray(Point2::new(0.6, 0.0), Vector2::new(0.0, 1.0))
            .unwrap_or(-1.0);
        assert!(close(t, 9.2), "{t}");
        assert_eq!(
            c.ray(Point2::new(0.0, 10.0), Vector2::new(1.0, 0.0)),
            Some(0.0)
        );
        assert_eq!(c.ray(Point2::new(1.5, 0.0), Vector2::new(0.0, 1.0)), None);
    }

    #[test]
    fn thick_segment_covers_its_thickness() {
        let w = Obb::from_segment(Point2::new(0.0, 0.0), Point2::new(0.0, 4.0), 0.2);
        assert!(w.contains(Point2::new(0.09, 2.0)));
        assert!(!w.contains(Point2::new(0.11, 2.0)));
        let t = w
            .ray(Point2::new(-3.0, 1.0), Vector2::new(1.0, 0.0))
            .unwrap_or(-1.0);
        assert!(close(t, 2.9));
    }

    #[test]
    fn box_overlap_by_separating_axes() {
        let a = Obb::new(Point2::origin(), 0.0, 2.0, 1.0);
        let near = Obb::new(Point2::new(1.4, 0.0), 0.3, 1.0, 0.2);
        let far = Obb::new(Point2::new(1.6, 1.2), 0.0, 1.0, 1.0);
        // Rotated so only the diagonal axis separates them.
        let diag = Obb::new(Point2::new(1.4, 0.9), std::f64::consts::FRAC_PI_4, 1.0, 0.2);
        assert!(a.overlaps_box(&near));
        assert!(!a.overlaps_box(&far));
        assert!(!a.overlaps_box(&diag));
        assert!(a.overlaps_circle(&Circle::new(Point2::new(1.3, 0.0), 0.31)));
        assert!(!a.overlaps_circle(&Circle::new(Point2::new(1.3, 0.8), 0.4)));
    }
}

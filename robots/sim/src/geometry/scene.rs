//! Every solid of a world in one flat list, for ray casting and collision.
//! The list is small (tens of solids), so a bounding-circle reject in front of
//! the exact test serves a single ray; a scan's fan of beams first sorts the
//! solids by direction (`fan.rs`).

use super::{Obb, Shape, Vec2};
use serde::{Deserialize, Serialize};

/// What a solid is in the world, by index into the world's lists.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
pub enum SolidRef {
    /// A solid piece of a wall (walls are split at their doors).
    Wall(usize),
    Obstacle(usize),
    PickupBox(usize),
    Target(usize),
    /// An obstacle that a fault made appear, by the fault's index in the world.
    Fault(usize),
}

#[derive(Debug, Clone, PartialEq)]
pub struct Solid {
    pub shape: Shape,
    pub what: SolidRef,
    /// Inactive solids (a box being carried) are ignored by every query.
    pub active: bool,
    bound: f64,
}

impl Solid {
    pub fn new(shape: Shape, what: SolidRef) -> Self {
        Solid {
            bound: shape.bounding_radius(),
            shape,
            what,
            active: true,
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit {
    pub distance: f64,
    pub what: SolidRef,
}

#[derive(Debug, Clone, Default, PartialEq)]
pub struct Scene {
    solids: Vec<Solid>,
}

impl Scene {
    pub fn new(solids: Vec<Solid>) -> Self {
        Scene { solids }
    }

    pub fn solids(&self) -> &[Solid] {
        &self.solids
    }

    /// The solid standing for `what`, if the scene has one.
    pub fn find_mut(&mut self, what: SolidRef) -> Option<&mut Solid> {
        self.solids.iter_mut().find(|s| s.what == what)
    }

    /// The nearest solid along a ray with unit direction `dir`, within `max_range`.
    /// Ties go to the solid listed first, so results never depend on anything
    /// but the scene's order.
    pub fn ray(&self, origin: Vec2, dir: Vec2, max_range: f64) -> Option<Hit> {
        self.ray_among(origin, dir, max_range, 0..self.solids.len())
    }

    /// As `ray`, over the solids `among` (indices into `solids()`, ascending)
    /// only.
    pub fn ray_among(
        &self,
        origin: Vec2,
        dir: Vec2,
        max_range: f64,
        among: impl Iterator<Item = usize>,
    ) -> Option<Hit> {
        let mut best: Option<Hit> = None;
        let mut limit = max_range;
        for s in among.filter_map(|j| self.solids.get(j)) {
            if !s.active {
                continue;
            }
            let oc = s.shape.center() - origin;
            let proj = oc.dot(dir);
            if proj + s.bound < 0.0 || proj - s.bound > limit {
                continue;
            }
            let perp = oc.cross(dir);
            if perp.abs() > s.bound {
                continue;
            }
            if let Some(t) = s.shape.ray(origin, dir)
                && t <= limit
                && best.is_none_or(|b| t < b.distance)
            {
                limit = t;
                best = Some(Hit {
                    distance: t,
                    what: s.what,
                });
            }
        }
        best
    }

    /// The first solid (in scene order) that the footprint overlaps.
    pub fn overlapping(&self, footprint: &Obb) -> Option<SolidRef> {
        let fr = footprint.bounding_radius();
        self.solids
            .iter()
            .filter(|s| s.active)
            .filter(|s| (s.shape.center() - footprint.center).length() <= s.bound + fr)
            .find(|s| s.shape.overlaps_box(footprint))
            .map(|s| s.what)
    }

    /// Whether a point lies inside any active solid.
    pub fn contains(&self, p: Vec2) -> bool {
        self.solids.iter().any(|s| s.active && s.shape.contains(p))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Circle;

    fn scene() -> Scene {
        Scene::new(vec![
            Solid::new(
                Shape::Box(Obb::from_segment(
                    Vec2::new(4.0, -5.0),
                    Vec2::new(4.0, 5.0),
                    0.2,
                )),
                SolidRef::Wall(0),
            ),
            Solid::new(
                Shape::Circle(Circle::new(Vec2::new(2.0, 0.0), 0.5)),
                SolidRef::Obstacle(0),
            ),
        ])
    }

    #[test]
    fn nearest_solid_wins() {
        let s = scene();
        let h = s.ray(Vec2::ZERO, Vec2::new(1.0, 0.0), 30.0);
        assert_eq!(h.map(|h| h.what), Some(SolidRef::Obstacle(0)));
        assert!((h.map_or(0.0, |h| h.distance) - 1.5).abs() < 1e-12);
        // Past the circle's side the wall face is at 3.9.
        let h = s.ray(Vec2::new(0.0, 1.0), Vec2::new(1.0, 0.0), 30.0);
        assert_eq!(h.map(|h| h.what), Some(SolidRef::Wall(0)));
        assert!((h.map_or(0.0, |h| h.distance) - 3.9).abs() < 1e-12);
    }

    #[test]
    fn range_limit_and_inactive_solids() {
        let mut s = scene();
        assert_eq!(s.ray(Vec2::ZERO, Vec2::new(1.0, 0.0), 1.0), None);
        if let Some(c) = s.find_mut(SolidRef::Obstacle(0)) {
            c.active = false;
        }
        let h = s.ray(Vec2::ZERO, Vec2::new(1.0, 0.0), 30.0);
        assert_eq!(h.map(|h| h.what), Some(SolidRef::Wall(0)));
    }

    #[test]
    fn footprint_overlap() {
        let s = scene();
        let fp = Obb::new(Vec2::new(3.5, 3.0), 0.0, 1.2, 0.6);
        assert_eq!(s.overlapping(&fp), Some(SolidRef::Wall(0)));
        let fp = Obb::new(Vec2::new(0.0, 3.0), 0.0, 1.2, 0.6);
        assert_eq!(s.overlapping(&fp), None);
    }
}

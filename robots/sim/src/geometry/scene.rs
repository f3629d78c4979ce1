//! Every solid of a world in one flat list, for ray casting and collision.
//! The fixed solids (walls, obstacles) are also in a uniform grid
//! (`index.rs`), so that a query looks only at the cells it crosses; the
//! few solids that move or come and go (targets, pickup boxes, appearing
//! obstacles) are tested one by one. Every query answers exactly what a test
//! of every solid in list order would: the nearest hit, ties to the solid
//! listed first. A scan's fan of beams first sorts the solids near it by
//! direction (`fan.rs`).

use super::index::SolidGrid;
use super::{Obb, PlaneVector, Point2, Shape, Vector2};
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
    /// The fixed solids: walls and obstacles.
    grid: SolidGrid,
    /// Every other solid, ascending.
    loose: Vec<usize>,
}

/// Solids that never move once the scene is built: they may be switched
/// off (`active`), but not moved, since the grid places them once.
fn fixed(what: SolidRef) -> bool {
    matches!(what, SolidRef::Wall(_) | SolidRef::Obstacle(_))
}

impl Scene {
    pub fn new(solids: Vec<Solid>) -> Self {
        let (members, loose): (Vec<usize>, Vec<usize>) =
            (0..solids.len()).partition(|&i| fixed(solids[i].what));
        Scene {
            grid: SolidGrid::new(&solids, &members),
            loose,
            solids,
        }
    }

    pub fn solids(&self) -> &[Solid] {
        &self.solids
    }

    /// The solid standing for `what`, if the scene has one.
    pub fn find(&self, what: SolidRef) -> Option<&Solid> {
        self.index_of(what).map(|i| &self.solids[i])
    }

    /// The solid standing for `what`, if the scene has one. A wall or
    /// obstacle may be switched off through it, not moved.
    pub fn find_mut(&mut self, what: SolidRef) -> Option<&mut Solid> {
        self.index_of(what).map(|i| &mut self.solids[i])
    }

    fn index_of(&self, what: SolidRef) -> Option<usize> {
        if fixed(what) {
            return self.solids.iter().position(|s| s.what == what);
        }
        self.loose
            .iter()
            .copied()
            .find(|&i| self.solids[i].what == what)
    }

    /// Ascending, without repeats: the loose solids and the fixed ones
    /// listed in the grid's cells that meet the box `lo..hi`.
    fn near(&self, lo: Point2<f64>, hi: Point2<f64>) -> Vec<usize> {
        let mut out = self.loose.clone();
        if lo.coords.is_finite() && hi.coords.is_finite() {
            self.grid.within(lo, hi, &mut out);
        } else {
            out.extend((0..self.solids.len()).filter(|&i| fixed(self.solids[i].what)));
        }
        out.sort_unstable();
        out.dedup();
        out
    }

    /// Ascending: every solid whose shape may come within `reach` of `origin`.
    pub(crate) fn within_reach(&self, origin: Point2<f64>, reach: f64) -> Vec<usize> {
        let r = Vector2::new(reach, reach);
        self.near(origin - r, origin + r)
    }

    /// The nearest solid along a ray with unit direction `dir`, within `max_range`.
    /// Ties go to the solid listed first, so results never depend on anything
    /// but the scene's order.
    pub fn ray(&self, origin: Point2<f64>, dir: Vector2<f64>, max_range: f64) -> Option<Hit> {
        if !(origin.coords.is_finite() && dir.is_finite() && max_range.is_finite()) {
            return self.ray_among(origin, dir, max_range, 0..self.solids.len());
        }
        // The nearest so far and its index: ties go to the lower index, as
        // in a test of every solid in order.
        let mut best: Option<(Hit, usize)> = None;
        let test = |i: usize, best: &mut Option<(Hit, usize)>| {
            let limit = best.map_or(max_range, |(h, _)| h.distance);
            if let Some(h) = self.ray_among(origin, dir, limit, std::iter::once(i))
                && best.is_none_or(|(b, j)| (h.distance, i) < (b.distance, j))
            {
                *best = Some((h, i));
            }
        };
        for &i in &self.loose {
            test(i, &mut best);
        }
        // A solid met before the ray enters a cell is listed in a cell
        // already crossed, so no later cell can hold a nearer one.
        self.grid.along(origin, dir, max_range, |cell, enter| {
            if best.is_some_and(|(h, _)| h.distance < enter) {
                return false;
            }
            for &i in cell {
                test(i, &mut best);
            }
            true
        });
        best.map(|(h, _)| h)
    }

    /// As `ray`, over the solids `among` (indices into `solids()`, ascending)
    /// only.
    pub fn ray_among(
        &self,
        origin: Point2<f64>,
        dir: Vector2<f64>,
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
            let proj = oc.dot(&dir);
            if proj + s.bound < 0.0 || proj - s.bound > limit {
                continue;
            }
            let perp = oc.perp(&dir);
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
        self.within_reach(footprint.center, fr)
            .into_iter()
            .map(|i| &self.solids[i])
            .filter(|s| s.active)
            .filter(|s| (s.shape.center() - footprint.center).hypot() <= s.bound + fr)
            .find(|s| s.shape.overlaps_box(footprint))
            .map(|s| s.what)
    }

    /// Whether a point lies inside any active solid.
    pub fn contains(&self, p: Point2<f64>) -> bool {
        self.near(p, p)
            .into_iter()
            .any(|i| self.solids[i].active && self.solids[i].shape.contains(p))
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
                    Point2::new(4.0, -5.0),
                    Point2::new(4.0, 5.0),
                    0.2,
                )),
                SolidRef::Wall(0),
            ),
            Solid::new(
                Shape::Circle(Circle::new(Point2::new(2.0, 0.0), 0.5)),
                SolidRef::Obstacle(0),
            ),
        ])
    }

    #[test]
    fn nearest_solid_wins() {
        let s = scene();
        let h = s.ray(Point2::origin(), Vector2::new(1.0, 0.0), 30.0);
        assert_eq!(h.map(|h| h.what), Some(SolidRef::Obstacle(0)));
        assert!((h.map_or(0.0, |h| h.distance) - 1.5).abs() < 1e-12);
        // Past the circle's side the wall face is at 3.9.
        let h = s.ray(Point2::new(0.0, 1.0), Vector2::new(1.0, 0.0), 30.0);
        assert_eq!(h.map(|h| h.what), Some(SolidRef::Wall(0)));
        assert!((h.map_or(0.0, |h| h.distance) - 3.9).abs() < 1e-12);
    }

    #[test]
    fn range_limit_and_inactive_solids() {
        let mut s = scene();
        assert_eq!(s.ray(Point2::origin(), Vector2::new(1.0, 0.0), 1.0), None);
        if let Some(c) = s.find_mut(SolidRef::Obstacle(0)) {
            c.active = false;
        }
        let h = s.ray(Point2::origin(), Vector2::new(1.0, 0.0), 30.0);
        assert_eq!(h.map(|h| h.what), Some(SolidRef::Wall(0)));
    }

    #[test]
    fn footprint_overlap() {
        let s = scene();
        let fp = Obb::new(Point2::new(3.5, 3.0), 0.0, 1.2, 0.6);
        assert_eq!(s.overlapping(&fp), Some(SolidRef::Wall(0)));
        let fp = Obb::new(Point2::new(0.0, 3.0), 0.0, 1.2, 0.6);
        assert_eq!(s.overlapping(&fp), None);
    }
}

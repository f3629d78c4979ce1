//! The known map's surfaces as points (`frame::surface_points`), indexed once:
//! the site plan does not change after the VM starts, and a check near the
//! robot should carry over only the part of it that lies there.
//! The index is in the map's frame; a `locate` moves the estimate's frame, so
//! the query region is carried into the map's frame instead of every point
//! into the estimate's.

use ilmr_hal::{KnownMap, Pose};
use ilmr_motion::obstacle::{Bounds, PointGrid};
use nalgebra::Point2;

use super::frame::{self, Rigid};

/// Side of the index's cells, m.
const CELL: f64 = 0.25;

#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct KnownSurface {
    /// Map frame.
    points: Vec<(f64, f64)>,
    grid: PointGrid,
}

impl KnownSurface {
    pub fn new(map: Option<&KnownMap>) -> KnownSurface {
        let points = map.map(frame::surface_points).unwrap_or_default();
        let grid = PointGrid::new(CELL, &points, |p| *p);
        KnownSurface { points, grid }
    }

    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// Into `out` (cleared first), each once with its index in the map and
    /// in the estimate's frame, in no set order: the points closer than
    /// `reach` to `here` (the map's frame), except some outside `region` (the
    /// estimate's frame). A caller whose own test accepts nothing outside
    /// `region` sees exactly the points it would over every point near
    /// `here`. `scratch` holds candidate indices between calls.
    #[allow(clippy::too_many_arguments)]
    pub fn near(
        &self,
        map_from_estimate: Pose,
        here: (f64, f64),
        reach: f64,
        region: &Bounds,
        scratch: &mut Vec<usize>,
        out: &mut Vec<(usize, Point2<f64>)>,
    ) {
        out.clear();
        // The region turned into the map's frame, and the box round that.
        let to_map = Rigid::to_map(map_from_estimate);
        let (s, c) = to_map.sin_cos();
        let turned = Bounds::turned(to_map.apply((0.0, 0.0)), (s, c), region.lo, region.hi);
        let query = Bounds::square(here, reach).and(&turned);
        self.grid.within(&query, scratch);
        let back = Rigid::from_map(map_from_estimate);
        for &i in scratch.iter() {
            let q = self.points[i];
            if (q.0 - here.0).powi(2) + (q.1 - here.1).powi(2) < reach * reach {
                let e = back.apply(q);
                out.push((i, Point2::new(e.0, e.1)));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small office: walls round a 12 x 9 m room, an inner wall with a door
    /// gap, a pillar.
    fn office() -> KnownMap {
        let wall = |a: (f64, f64), b: (f64, f64)| ilmr_hal::Solid {
            a,
            b,
            radius: 0.1,
            name: None,
        };
        KnownMap {
            bounds: None,
            solids: vec![
                wall((0.0, 0.0), (12.0, 0.0)),
                wall((12.0, 0.0), (12.0, 9.0)),
                wall((12.0, 9.0), (0.0, 9.0)),
                wall((0.0, 9.0), (0.0, 0.0)),
                wall((6.0, 0.0), (6.0, 4.0)),
                wall((6.0, 5.0), (6.0, 9.0)),
                ilmr_hal::Solid {
                    a: (3.0, 6.0),
                    b: (3.0, 6.0),
                    radius: 0.3,
                    name: None,
                },
            ],
        }
    }

    /// What the supervisor did before the index: filter every point, carry
    /// the rest over; then a check that accepts only the square round
    /// `centre`.
    fn brute(
        map: &KnownMap,
        t: Pose,
        here: (f64, f64),
        reach: f64,
        centre: (f64, f64),
        radius: f64,
    ) -> Vec<Point2<f64>> {
        frame::surface_points(map)
            .into_iter()
            .filter(|q| (q.0 - here.0).powi(2) + (q.1 - here.1).powi(2) < reach * reach)
            .map(|q| Rigid::from_map(t).apply(q))
            .map(|e| Point2::new(e.0, e.1))
            .filter(|p| (p.x - centre.0).abs() <= radius && (p.y - centre.1).abs() <= radius)
            .collect()
    }

    #[test]
    fn near_keeps_every_point_a_check_in_the_region_could_accept() {
        let map = office();
        let known = KnownSurface::new(Some(&map));
        let (mut scratch, mut out) = (Vec::new(), Vec::new());
        let mut seen = 0;
        // Frames as `locate` leaves them: none, shifted, turned.
        let frames = [
            Pose::default(),
            Pose::new(8.0, 5.0, std::f64::consts::FRAC_PI_2),
            Pose::new(-2.5, 1.0, -2.4),
        ];
        for t in frames {
            for i in 0..60 {
                let f = f64::from(i);
                let here_est = (0.3 * f - 3.0, 0.17 * f - 2.0);
                let here = frame::to_map(t, here_est);
                let reach = 2.0 + 0.05 * f;
                let centre = (here_est.0 + (0.3 * f).cos(), here_est.1 + (0.3 * f).sin());
                let radius = 0.5 + 0.04 * f;
                let region = Bounds::square(centre, radius);
                known.near(t, here, reach, &region, &mut scratch, &mut out);
                let want = brute(&map, t, here, reach, centre, radius);
                out.sort_by_key(|(i, _)| *i);
                let kept: Vec<Point2<f64>> = out
                    .iter()
                    .map(|(_, p)| *p)
                    .filter(|p| {
                        (p.x - centre.0).abs() <= radius && (p.y - centre.1).abs() <= radius
                    })
                    .collect();
                assert_eq!(kept, want, "frame {t:?}, step {i}");
                seen += want.len();
            }
        }
        assert!(seen > 500, "the queries found walls: {seen}");
    }

    #[test]
    fn without_a_site_plan_nothing_is_near() {
        let known = KnownSurface::new(None);
        assert!(known.is_empty());
        let (mut scratch, mut out) = (Vec::new(), vec![(0, Point2::new(1.0, 1.0))]);
        known.near(
            Pose::default(),
            (0.0, 0.0),
            5.0,
            &Bounds::ALL,
            &mut scratch,
            &mut out,
        );
        assert!(out.is_empty());
    }
}

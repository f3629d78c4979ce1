//! What a simulated robot knows before it looks: the site plan a real robot's
//! operator would give it. Walls and fixed furniture (the world's obstacles:
//! a bench, a cabinet, a pillar) are on the plan; boxes to pick up, walking
//! targets and faults that put obstacles in the way are what the scanner has
//! to find, so they are left out.

use crate::geometry::{PlaneVector, Point2, Shape};
use crate::world::World;
use ilmr_hal::{KnownMap, Solid};

/// The world's bounds, wall pieces and fixed obstacles, in the world frame (the
/// frame the simulated estimate starts in).
pub(crate) fn known_map(world: &World) -> KnownMap {
    let b = world.bounds;
    let mut solids: Vec<Solid> = world
        .walls
        .iter()
        .flat_map(|w| {
            w.pieces.iter().map(|&(a, b)| Solid {
                a: (a.x, a.y),
                b: (b.x, b.y),
                radius: 0.5 * w.thickness,
                name: Some(w.id.clone()),
            })
        })
        .collect();
    for shape in &world.obstacles {
        furniture(shape, &mut solids);
    }
    KnownMap {
        bounds: Some((b.min.x, b.min.y, b.max.x, b.max.y)),
        solids,
    }
}

/// A round obstacle is one solid; a box is its four edges (so that its surface
/// is exact) and a core along its long axis (so that a point inside it is
/// inside a solid).
fn furniture(shape: &Shape, out: &mut Vec<Solid>) {
    let p = |v: Point2<f64>| (v.x, v.y);
    match shape {
        Shape::Circle(c) => out.push(Solid {
            a: p(c.center),
            b: p(c.center),
            radius: c.radius,
            name: None,
        }),
        Shape::Box(obb) => {
            let k = obb.corners();
            for i in 0..4 {
                out.push(Solid {
                    a: p(k[i]),
                    b: p(k[(i + 1) % 4]),
                    radius: 0.0,
                    name: None,
                });
            }
            let (long, short, axis) = if obb.half.x >= obb.half.y {
                (obb.half.x, obb.half.y, obb.axis)
            } else {
                (obb.half.y, obb.half.x, obb.axis.rotated_left())
            };
            let reach = axis * (long - short);
            out.push(Solid {
                a: p(obb.center - reach),
                b: p(obb.center + reach),
                radius: short,
                name: None,
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_office_plan_has_its_walls_and_bounds() {
        let world = crate::world::shipped("office")
            .and_then(Result::ok)
            .unwrap_or_else(|| unreachable!("the office world ships"));
        let map = known_map(&world);
        let pieces: usize = world.walls.iter().map(|w| w.pieces.len()).sum();
        assert!(map.solids.len() > pieces, "walls and furniture");
        assert!(map.contains((world.start.x, world.start.y)));
        // The start is clear of every wall; the middle of a wall piece is not.
        let (_, d) = map
            .nearest((world.start.x, world.start.y))
            .unwrap_or_default();
        assert!(d > 0.3, "start {d} m from a wall");
        let (a, b) = world.walls[0].pieces[0];
        let mid = (0.5 * (a.x + b.x), 0.5 * (a.y + b.y));
        assert!(map.nearest(mid).is_some_and(|(_, d)| d < 0.0));
        // The lab bench (7, 7.5), 5 x 0.8 m: its middle is inside a solid, its
        // west end at x = 4.5 is on the plan to the centimetre.
        assert!(map.nearest((7.0, 7.5)).is_some_and(|(_, d)| d < 0.0));
        assert!(
            map.nearest((4.4, 7.5))
                .is_some_and(|(_, d)| (d - 0.1).abs() < 1e-9)
        );
    }
}

//! From TOML text to a [`World`]: parse with serde, then check every entry and
//! report the first fault with its line and field.

use std::collections::{BTreeMap, BTreeSet};

use super::error::{field_line, line_of};
use super::format::{Point, WorldFile};
use super::limits::*;
use super::{Bounds, Charger, Door, PickupBox, Plate, Target, Wall, World, WorldError};
use crate::geometry::{Circle, Obb, PlaneVector, Point2, Pose, Shape};
use toml::Spanned;

const DEFAULT_WALL_THICKNESS: f64 = 0.15;
const DEFAULT_TARGET_RADIUS: f64 = 0.25;
const DEFAULT_CHARGER_RADIUS: f64 = 0.5;
const DEFAULT_PLATE_RADIUS: f64 = 0.05;

pub(super) fn parse(text: &str, source: &str) -> Result<World, WorldError> {
    let file: WorldFile = toml::from_str(text).map_err(|e| WorldError {
        source: source.to_string(),
        line: e.span().map_or(1, |s| line_of(text, s.start)),
        field: None,
        message: e.message().trim().to_string(),
    })?;
    Checker { text, source }.world(file)
}

struct Checker<'a> {
    text: &'a str,
    source: &'a str,
}

/// Where an entry starts in the text, and how errors name it.
#[derive(Clone, Copy)]
struct Entry<'e> {
    at: usize,
    label: &'e str,
}

impl Checker<'_> {
    fn err(&self, entry: Entry<'_>, key: &str, message: impl Into<String>) -> WorldError {
        WorldError {
            source: self.source.to_string(),
            line: field_line(self.text, entry.at, key),
            field: Some(format!("{} {key}", entry.label)),
            message: message.into(),
        }
    }

    fn point(&self, e: Entry<'_>, key: &str, p: Point) -> Result<Point2<f64>, WorldError> {
        let max = MAX_COORDINATE;
        let expected = format!("-{max:e} to {max:e} m");
        for v in p {
            self.range(e, key, v, v.abs() <= max, &expected)?;
        }
        Ok(Point2::new(p[0], p[1]))
    }

    fn inside(
        &self,
        e: Entry<'_>,
        key: &str,
        b: &Bounds,
        p: Point,
    ) -> Result<Point2<f64>, WorldError> {
        let v = self.point(e, key, p)?;
        if b.contains(v) {
            Ok(v)
        } else {
            Err(self.err(
                e,
                key,
                format!(
                    "({}, {}) lies outside the bounds ({}, {})..({}, {})",
                    v.x, v.y, b.min.x, b.min.y, b.max.x, b.max.y
                ),
            ))
        }
    }

    /// A size: finite, above 0 and at most `max` metres.
    fn size(&self, e: Entry<'_>, key: &str, v: f64, max: f64) -> Result<f64, WorldError> {
        self.range(
            e,
            key,
            v,
            v > 0.0 && v <= max,
            &format!("> 0 and <= {max} m"),
        )
    }

    fn range(
        &self,
        e: Entry<'_>,
        key: &str,
        v: f64,
        admitted: bool,
        expected: &str,
    ) -> Result<f64, WorldError> {
        if v.is_finite() && admitted {
            Ok(v)
        } else if v.is_finite() {
            Err(self.err(
                e,
                key,
                format!("{} out of range (expected {expected})", shown(v)),
            ))
        } else {
            Err(self.err(e, key, format!("{v} is not a number (expected {expected})")))
        }
    }

    fn degrees(&self, e: Entry<'_>, key: &str, v: f64) -> Result<f64, WorldError> {
        let max = MAX_HEADING_DEG;
        self.range(e, key, v, v.abs() <= max, &format!("-{max} to {max} deg"))
            .map(f64::to_radians)
    }

    fn unique(
        &self,
        e: Entry<'_>,
        key: &str,
        id: &str,
        seen: &mut BTreeSet<String>,
    ) -> Result<(), WorldError> {
        if id.is_empty() {
            return Err(self.err(e, key, "must not be empty"));
        }
        if !seen.insert(id.to_string()) {
            return Err(self.err(e, key, format!("`{id}` is used twice")));
        }
        Ok(())
    }

    /// The first entry past `max` of a list, as an error at its header.
    fn count<T>(&self, list: &[Spanned<T>], what: &str, max: usize) -> Result<(), WorldError> {
        let Some(extra) = list.get(max) else {
            return Ok(());
        };
        Err(WorldError {
            source: self.source.to_string(),
            line: line_of(self.text, extra.span().start),
            field: Some(format!("{what} #{}", max + 1)),
            message: format!(
                "{} [[{what}]] entries out of range (expected at most {max})",
                list.len()
            ),
        })
    }

    /// Walls and obstacles add their outline to the site plan the VM keeps.
    fn outline(
        &self,
        e: Entry<'_>,
        key: &str,
        total: &mut f64,
        add: f64,
    ) -> Result<(), WorldError> {
        *total += add;
        if *total <= MAX_OUTLINE_LENGTH {
            return Ok(());
        }
        Err(self.err(
            e,
            key,
            format!(
                "the walls and obstacles so far measure {:.0} m, out of range (expected at most {MAX_OUTLINE_LENGTH} m in all)",
                *total
            ),
        ))
    }

    fn world(&self, f: WorldFile) -> Result<World, WorldError> {
        self.count(&f.wall, "wall", MAX_WALLS)?;
        self.count(&f.door, "door", MAX_DOORS)?;
        self.count(&f.obstacle, "obstacle", MAX_OBSTACLES)?;
        self.count(&f.pickup_box, "pickup_box", MAX_PICKUP_BOXES)?;
        self.count(&f.target, "target", MAX_TARGETS)?;
        self.count(&f.plate, "plate", MAX_PLATES)?;
        self.count(&f.fault, "fault", MAX_FAULTS)?;
        let be = Entry {
            at: f.bounds.span().start,
            label: "bounds",
        };
        let min = self.point(be, "min", f.bounds.get_ref().min)?;
        let max = self.point(be, "max", f.bounds.get_ref().max)?;
        if max.x <= min.x || max.y <= min.y {
            return Err(self.err(be, "max", "must be above and to the right of `min`"));
        }
        let side = (max.x - min.x).max(max.y - min.y);
        if side > MAX_WORLD_SIDE {
            return Err(self.err(
                be,
                "max",
                format!(
                    "a side of {} m out of range (expected at most {MAX_WORLD_SIDE} m)",
                    shown(side)
                ),
            ));
        }
        let bounds = Bounds { min, max };

        let se = Entry {
            at: f.start.span().start,
            label: "start",
        };
        let s = f.start.get_ref();
        let p = self.inside(se, "x", &bounds, [s.x, s.y])?;
        let start = Pose::new(p.x, p.y, self.degrees(se, "heading", s.heading)?);

        let mut walls = Vec::new();
        let mut wall_ids = BTreeSet::new();
        let mut outline = 0.0;
        for (i, w) in f.wall.iter().enumerate() {
            let label = format!("wall #{}", i + 1);
            let e = Entry {
                at: w.span().start,
                label: &label,
            };
            let d = w.get_ref();
            let from = self.inside(e, "from", &bounds, d.from)?;
            let to = self.inside(e, "to", &bounds, d.to)?;
            if (from - to).hypot() < 1e-6 {
                return Err(self.err(e, "to", "a wall needs two distinct ends"));
            }
            let thickness = self.size(
                e,
                "thickness",
                d.thickness.unwrap_or(DEFAULT_WALL_THICKNESS),
                MAX_WALL_THICKNESS,
            )?;
            self.outline(e, "to", &mut outline, (from - to).hypot())?;
            let id = d.id.clone().unwrap_or_else(|| format!("wall{}", i + 1));
            self.unique(e, "id", &id, &mut wall_ids)?;
            walls.push(Wall {
                id,
                from,
                to,
                thickness,
                pieces: vec![(from, to)],
            });
        }

        let doors = self.doors(&f, &mut walls)?;

        let mut obstacles = Vec::new();
        for (i, o) in f.obstacle.iter().enumerate() {
            let label = format!("obstacle #{}", i + 1);
            let e = Entry {
                at: o.span().start,
                label: &label,
            };
            let d = o.get_ref();
            let center = self.inside(e, "center", &bounds, d.center)?;
            let shape = match d.shape.as_str() {
                "circle" => {
                    if d.size.is_some() || d.heading.is_some() {
                        return Err(self.err(
                            e,
                            "shape",
                            "a circle takes `radius` only, not `size` or `heading`",
                        ));
                    }
                    let r = d
                        .radius
                        .ok_or_else(|| self.err(e, "radius", "a circle needs `radius`"))?;
                    let r = self.size(e, "radius", r, MAX_OBSTACLE_SIZE)?;
                    self.outline(e, "radius", &mut outline, std::f64::consts::TAU * r)?;
                    Shape::Circle(Circle::new(center, r))
                }
                "box" => {
                    if d.radius.is_some() {
                        return Err(self.err(
                            e,
                            "shape",
                            "a box takes `size` and `heading`, not `radius`",
                        ));
                    }
                    let size = d.size.ok_or_else(|| {
                        self.err(e, "size", "a box needs `size = [length, width]`")
                    })?;
                    let l = self.size(e, "size", size[0], MAX_OBSTACLE_SIZE)?;
                    let w = self.size(e, "size", size[1], MAX_OBSTACLE_SIZE)?;
                    let h = self.degrees(e, "heading", d.heading.unwrap_or(0.0))?;
                    self.outline(e, "size", &mut outline, 2.0 * (l + w))?;
                    Shape::Box(Obb::new(center, h, l, w))
                }
                other => {
                    return Err(self.err(
                        e,
                        "shape",
                        format!("unknown shape `{other}`, expected `circle` or `box`"),
                    ));
                }
            };
            obstacles.push(shape);
        }

        let mut pickup_boxes: Vec<PickupBox> = Vec::new();
        let mut box_ids = BTreeSet::new();
        for (i, b) in f.pickup_box.iter().enumerate() {
            let label = format!("pickup_box #{}", i + 1);
            let e = Entry {
                at: b.span().start,
                label: &label,
            };
            let d = b.get_ref();
            self.unique(e, "id", &d.id, &mut box_ids)?;
            let center = self.inside(e, "center", &bounds, d.center)?;
            let l = self.size(e, "size", d.size[0], MAX_PICKUP_BOX_SIZE)?;
            let w = self.size(e, "size", d.size[1], MAX_PICKUP_BOX_SIZE)?;
            let h = self.degrees(e, "heading", d.heading)?;
            pickup_boxes.push(PickupBox {
                id: d.id.clone(),
                shape: Obb::new(center, h, l, w),
                colour: d.colour,
            });
        }

        let mut targets: Vec<Target> = Vec::new();
        let mut target_names = BTreeSet::new();
        for (i, t) in f.target.iter().enumerate() {
            let label = format!("target #{}", i + 1);
            let e = Entry {
                at: t.span().start,
                label: &label,
            };
            let d = t.get_ref();
            self.unique(e, "name", &d.name, &mut target_names)?;
            let start = self.inside(e, "position", &bounds, d.position)?;
            let radius = self.size(
                e,
                "radius",
                d.radius.unwrap_or(DEFAULT_TARGET_RADIUS),
                MAX_TARGET_RADIUS,
            )?;
            let speed = self.range(
                e,
                "speed",
                d.speed,
                (0.0..=MAX_TARGET_SPEED).contains(&d.speed),
                &format!("0 to {MAX_TARGET_SPEED} m/s"),
            )?;
            if d.waypoints.len() > MAX_WAYPOINTS {
                return Err(self.err(
                    e,
                    "waypoints",
                    format!(
                        "{} waypoints out of range (expected at most {MAX_WAYPOINTS})",
                        d.waypoints.len()
                    ),
                ));
            }
            let waypoints = d
                .waypoints
                .iter()
                .map(|&w| self.inside(e, "waypoints", &bounds, w))
                .collect::<Result<Vec<_>, _>>()?;
            if speed > 0.0 && waypoints.is_empty() {
                return Err(self.err(
                    e,
                    "waypoints",
                    "a target with a speed needs waypoints to walk",
                ));
            }
            targets.push(Target {
                name: d.name.clone(),
                colour: d.colour,
                start,
                radius,
                speed,
                waypoints,
                path: d.path,
            });
        }

        let charger = match &f.charger {
            None => None,
            Some(c) => {
                let e = Entry {
                    at: c.span().start,
                    label: "charger",
                };
                let d = c.get_ref();
                Some(Charger {
                    position: self.inside(e, "position", &bounds, d.position)?,
                    heading: self.degrees(e, "heading", d.heading)?,
                    radius: self.size(
                        e,
                        "radius",
                        d.radius.unwrap_or(DEFAULT_CHARGER_RADIUS),
                        MAX_CHARGER_RADIUS,
                    )?,
                    colour: d.colour,
                })
            }
        };

        let mut plates = Vec::new();
        for (i, p) in f.plate.iter().enumerate() {
            let label = format!("plate #{}", i + 1);
            let e = Entry {
                at: p.span().start,
                label: &label,
            };
            let d = p.get_ref();
            plates.push(Plate {
                position: self.inside(e, "position", &bounds, d.position)?,
                radius: self.size(
                    e,
                    "radius",
                    d.radius.unwrap_or(DEFAULT_PLATE_RADIUS),
                    MAX_PLATE_RADIUS,
                )?,
            });
        }

        let mut faults = Vec::new();
        for (i, d) in f.fault.iter().enumerate() {
            let label = format!("fault #{}", i + 1);
            let e = Entry {
                at: d.span().start,
                label: &label,
            };
            let spec = crate::faults::world::spec(d.get_ref())
                .map_err(|(key, message)| self.err(e, key, message))?;
            faults.push(spec);
        }

        Ok(World {
            name: f.name,
            description: f.description,
            bounds,
            start,
            walls,
            doors,
            obstacles,
            pickup_boxes,
            targets,
            charger,
            plates,
            faults,
        })
    }

    /// Checks the doors and cuts their openings out of the walls.
    fn doors(&self, f: &WorldFile, walls: &mut [Wall]) -> Result<Vec<Door>, WorldError> {
        let mut doors: Vec<Door> = Vec::new();
        let mut door_ids = BTreeSet::new();
        let wall_index: BTreeMap<&str, usize> = walls
            .iter()
            .enumerate()
            .map(|(i, w)| (w.id.as_str(), i))
            .collect();
        // Per wall: (start, end) of each opening along the wall, with its door index.
        let mut cuts: Vec<Vec<(f64, f64, usize)>> = vec![Vec::new(); walls.len()];
        for (i, d) in f.door.iter().enumerate() {
            let label = format!("door #{}", i + 1);
            let e = Entry {
                at: d.span().start,
                label: &label,
            };
            let def = d.get_ref();
            let id = def.id.clone().unwrap_or_else(|| format!("door{}", i + 1));
            self.unique(e, "id", &id, &mut door_ids)?;
            let wi = *wall_index
                .get(def.wall.as_str())
                .ok_or_else(|| self.err(e, "wall", format!("no wall has the id `{}`", def.wall)))?;
            let wall = &walls[wi];
            let len = (wall.from - wall.to).hypot();
            let width = self.range(
                e,
                "width",
                def.width,
                def.width > 0.0 && def.width <= len,
                &format!("> 0 and <= {len:.3} m, the length of wall `{}`", wall.id),
            )?;
            if !def.at.is_finite() {
                return Err(self.err(e, "at", "must be a finite distance"));
            }
            let (a, b) = (def.at - width / 2.0, def.at + width / 2.0);
            if a < 0.0 || b > len {
                return Err(self.err(
                    e,
                    "at",
                    format!("the opening {a:.3}..{b:.3} m does not fit on wall `{}`, which is {len:.3} m long", wall.id),
                ));
            }
            if let Some(&(_, _, other)) = cuts[wi].iter().find(|&&(s, t, _)| a < t && s < b) {
                return Err(self.err(
                    e,
                    "at",
                    format!("overlaps door `{}` on the same wall", doors[other].id),
                ));
            }
            cuts[wi].push((a, b, i));
            let dir = (wall.to - wall.from) * (1.0 / len);
            doors.push(Door {
                id,
                wall: wi,
                width,
                center: wall.from + dir * def.at,
                jambs: (wall.from + dir * a, wall.from + dir * b),
            });
        }
        for (w, c) in walls.iter_mut().zip(cuts.iter_mut()) {
            c.sort_by(|x, y| x.0.total_cmp(&y.0));
            let len = (w.from - w.to).hypot();
            let dir = (w.to - w.from) * (1.0 / len);
            let mut pieces = Vec::new();
            let mut s = 0.0;
            for &(a, b, _) in c.iter() {
                if a > s + 1e-9 {
                    pieces.push((w.from + dir * s, w.from + dir * a));
                }
                s = b;
            }
            if len > s + 1e-9 {
                pieces.push((w.from + dir * s, w.to));
            }
            w.pieces = pieces;
        }
        Ok(doors)
    }
}

//! Objects of the robot model that the laser scanner recognises by their width,
//! for `findtarget(scanner,box)` and `findtarget(scanner,charger)`: "Object name
//! will be replaced by parameters" (section 5.1.2), and for these the parameters
//! are the smallest and largest width the scanner should see (`box 0.3 0.5`).
//! Workpartner found its boxes this way in the summer 2002 test (section 5.6.7).
//!
//! In a scan such an object is a short run of returns standing clear of what is
//! behind it: the beams beside it on both sides reach further. Its outline must
//! be one flat face, or two faces meeting at about a right angle (a box seen at
//! a corner), so that pillars and people of the same width are not taken for
//! boxes. A beam that returns nothing (a dropout) neither ends an object nor
//! shows space beside it: a stretch of wall between two dropouts is as flat and
//! as narrow as a box's face, and a search that runs while the robot drives
//! along a hall sees hundreds of scans. Doors are found by `doors.rs`.

use crate::geometry::{PlaneVector, Point2, Pose, Vector2, centroid};
use crate::sensors::Scan;
use ilmr_hal::{Detection, Side};
use ilmr_model::RobotModel;

/// The beams beside an object reach at least this much further, m: a box stands
/// free of the wall behind it.
const SEPARATION: f64 = 0.3;
/// Neighbouring returns on one object differ by less than this, m. Seen
/// edge-on, a face 0.5 m long spans about this much range.
const SAME_OBJECT: f64 = 0.25;
/// Fewer returns than this are too few to tell a flat face from a round one
/// through the noise, or a piece of a wall seen edge-on. At the scanner's half
/// degree a 0.3 m face shows eight returns up to 4.3 m off.
const MIN_RETURNS: usize = 8;
/// Objects further than this from the scanner are not recognised, m: a person
/// 6 m off shows nine returns on an arc that fits two faces at a corner as
/// well as a box does.
const MAX_RANGE: f64 = 5.0;
/// How far returns may lie off a face fitted to them, m: three and a half times
/// the scanner's 1 cm noise.
const FLAT: f64 = 0.035;
/// Returns on each face of a corner, the corner's own counted on both.
const FACE_RETURNS: usize = 3;
/// A face within this angle of the beam is seen edge-on, rad.
const EDGE_ON: f64 = 0.35;
/// A return this near the line of a face seen edge-on is the face going on, m.
const GOES_ON: f64 = 0.06;
/// Two faces of a box meet at a right angle; seen through noise, within this, rad.
const CORNER_SLACK: f64 = 0.25;
/// The faces' lines of a box meet on its outline, within this plus a beam's
/// spacing, m. Lines fitted to the two halves of a pillar's outline meet some
/// centimetres in front of it: a pillar of 0.44 m, 6 cm.
const CORNER_OFF: f64 = 0.03;
/// What a face adds to a measured width beside the beam spacing, m.
const WIDTH_SLACK: f64 = 0.03;
/// At most this many beams in a row that return nothing are taken for dropouts
/// on the surface going on, not for space: at MoRo's 1 % of beams lost, three
/// in a row come once in a million beams.
const DROPOUTS: usize = 3;
/// Objects wider than this are walls to the recogniser, whatever the model says
/// (Figure 39's `side_edge 200 30` is not a width range), m.
const MAX_WIDTH: f64 = 2.0;

/// A model object the scanner recognises: its name and width range, m.
#[derive(Debug, Clone, PartialEq)]
struct Kind {
    name: String,
    min: f64,
    max: f64,
}

/// The model's objects given by two widths, except `door`.
fn kinds(model: &RobotModel) -> Vec<Kind> {
    model
        .objects
        .iter()
        .filter(|o| !o.name.eq_ignore_ascii_case("door"))
        .filter_map(|o| {
            let w: Vec<f64> = o
                .params
                .iter()
                .map(|p| p.parse::<f64>().ok())
                .collect::<Option<_>>()?;
            let [a, b] = w[..] else {
                return None;
            };
            let (min, max) = (a.min(b), a.max(b));
            (min > 0.0 && max <= MAX_WIDTH).then(|| Kind {
                name: o.name.clone(),
                min,
                max,
            })
        })
        .collect()
}

/// Appends a detection for every object of the model seen in `scan`, taken at
/// `pose` (the robot's estimate): the middle of the returns on its visible
/// outline, the bearing to it from the robot as its heading. An object whose
/// width fits several kinds (0.5 m is a box and a charger) is reported as each.
pub fn objects(model: &RobotModel, scan: &Scan, pose: Pose, out: &mut Vec<Detection>) {
    let kinds = kinds(model);
    let Some(widest) = kinds.iter().map(|k| k.max).reduce(f64::max) else {
        return;
    };
    let r = &scan.ranges;
    let hit = |i: usize| scan.returned(i);
    let local = |i: usize| scan.local_point(i);
    // The first return past `from` going `step` (+1 or -1) beams on, over at most
    // `DROPOUTS` beams that return nothing; `Err(())` where the scan ends first.
    let next = |from: usize, step: isize| -> Result<Option<usize>, ()> {
        for k in 1..=DROPOUTS as isize + 1 {
            let Some(j) = from.checked_add_signed(k * step).filter(|&j| j < r.len()) else {
                return Err(());
            };
            if hit(j) {
                return Ok(Some(j));
            }
        }
        Ok(None)
    };
    // The return beside an end passes behind it: it finds nothing, or something
    // further. Past a face seen edge-on that something must not be the face
    // going on: a door jamb's end and the wall beside it, seen along the wall,
    // look like a box's corner whose far face is the wall.
    let clear = |end: usize, beside: Option<usize>, face: &Line| {
        let Some(beside) = beside else {
            return true;
        };
        let beam = Vector2::from_angle(scan.bearing(end));
        let edge_on = face.dir.perp(&beam).abs() < EDGE_ON.sin();
        r[beside] - r[end] >= SEPARATION && !(edge_on && face.off(local(beside)) < GOES_ON)
    };
    let mut run = Vec::new();
    let mut a = 0;
    while a < r.len() {
        if !hit(a) {
            a += 1;
            continue;
        }
        // The run's returns, bridging dropouts on the surface it is on.
        run.clear();
        run.push(a);
        let mut b = a;
        while let Ok(Some(j)) = next(b, 1) {
            if (r[j] - r[b]).abs() >= SAME_OBJECT {
                break;
            }
            run.push(j);
            b = j;
        }
        // The scan's edge beside either end hides what is beside the object.
        let (Ok(before), Ok(after)) = (next(a, -1), next(b, 1)) else {
            a = b + 1;
            continue;
        };
        let near = run.iter().map(|&i| r[i]).fold(f64::INFINITY, f64::min) <= MAX_RANGE;
        // A run wider than any kind is a wall: it is not fitted.
        let narrow = (local(a) - local(b)).hypot() <= widest + WIDTH_SLACK;
        if run.len() >= MIN_RETURNS && near && narrow {
            let pts: Vec<Point2<f64>> = run.iter().map(|&i| local(i)).collect();
            let spacing = r[a].max(r[b]) * scan.angle_increment.abs();
            if let Some(outline) = Outline::of(&pts, spacing)
                && clear(a, before, &outline.first_face)
                && clear(b, after, &outline.last_face)
            {
                let centre = centroid(&pts);
                let seen = pose.to_world(&centre);
                let rel = centre.coords.polar_angle();
                for k in &kinds {
                    // The outline's ends may lie up to half a beam's spacing
                    // inside the object's edges on either side.
                    let w = outline.width;
                    if w + spacing + WIDTH_SLACK >= k.min && w <= k.max + WIDTH_SLACK {
                        out.push(Detection {
                            sensor: "scanner".into(),
                            object: k.name.clone(),
                            x: seen.x,
                            y: seen.y,
                            h: crate::geometry::wrap_angle(pose.h + rel),
                            side: if rel >= 0.0 { Side::Left } else { Side::Right },
                        });
                    }
                }
            }
        }
        a = b + 1;
    }
}

/// A run of returns that looks like a box: one flat face, or two faces meeting
/// at a right angle in a corner that is on the outline.
struct Outline {
    /// The distance between its ends, m.
    width: f64,
    /// The faces at its first and last return.
    first_face: Line,
    last_face: Line,
}

impl Outline {
    /// `None` for anything rounder than a box. `spacing` is the distance
    /// between neighbouring beams there, m.
    fn of(pts: &[Point2<f64>], spacing: f64) -> Option<Outline> {
        let width = (pts[0] - pts[pts.len() - 1]).hypot();
        let whole = Line::fit(pts);
        if whole.worst(pts) <= FLAT {
            return Some(Outline {
                width,
                first_face: whole,
                last_face: whole,
            });
        }
        // The corner is where two straight faces fit best; each face has at
        // least three returns, the corner's return on both.
        let (near, far) = (FACE_RETURNS - 1..=pts.len() - FACE_RETURNS)
            .map(|k| (Line::fit(&pts[..=k]), Line::fit(&pts[k..]), k))
            .filter(|(a, b, k)| a.worst(&pts[..=*k]) <= FLAT && b.worst(&pts[*k..]) <= FLAT)
            .map(|(a, b, _)| (a, b))
            .min_by(|x, y| {
                let cost = |(a, b): &(Line, Line)| a.spread + b.spread;
                cost(x).total_cmp(&cost(y))
            })?;
        let angle = near.dir.perp(&far.dir).abs().asin();
        let corner = near.meet(&far)?;
        let on_outline = pts
            .iter()
            .map(|p| (p - corner).hypot())
            .fold(f64::INFINITY, f64::min)
            <= CORNER_OFF + spacing;
        ((std::f64::consts::FRAC_PI_2 - angle) <= CORNER_SLACK && on_outline).then_some(Outline {
            width,
            first_face: near,
            last_face: far,
        })
    }
}

/// A straight line fitted to returns by total least squares.
#[derive(Debug, Clone, Copy)]
struct Line {
    centre: Point2<f64>,
    /// Unit direction.
    dir: Vector2<f64>,
    /// Sum of the squared distances of the fitted returns from it.
    spread: f64,
}

impl Line {
    fn fit(pts: &[Point2<f64>]) -> Line {
        let centre = centroid(pts);
        let (mut xx, mut xy, mut yy) = (0.0, 0.0, 0.0);
        for p in pts {
            let d = *p - centre;
            xx += d.x * d.x;
            xy += d.x * d.y;
            yy += d.y * d.y;
        }
        let theta = 0.5 * (2.0 * xy).atan2(xx - yy);
        let dir = Vector2::from_angle(theta);
        let spread = pts.iter().map(|p| (*p - centre).perp(&dir).powi(2)).sum();
        Line {
            centre,
            dir,
            spread,
        }
    }

    fn off(&self, p: Point2<f64>) -> f64 {
        (p - self.centre).perp(&self.dir).abs()
    }

    /// The furthest of `pts` from the line.
    fn worst(&self, pts: &[Point2<f64>]) -> f64 {
        pts.iter().map(|p| self.off(*p)).fold(0.0, f64::max)
    }

    /// Where two lines cross; `None` when they are parallel.
    fn meet(&self, other: &Line) -> Option<Point2<f64>> {
        let denom = self.dir.perp(&other.dir);
        if denom.abs() < 1e-9 {
            return None;
        }
        let t = (other.centre - self.centre).perp(&other.dir) / denom;
        Some(self.centre + self.dir * t)
    }
}

#[cfg(test)]
mod tests {
    use super::super::scan_at;
    use super::*;
    use crate::config::RobotConfig;
    use crate::geometry::{Circle, Obb, Scene, Shape, Solid, SolidRef};

    /// `scan_at` with the scanner's noise, seeded.
    fn noisy_scan_at(scene: &Scene, pose: Pose, seed: u64) -> Scan {
        let mut scan = scan_at(scene, pose);
        let sigma = RobotConfig::moro().scanner.noise_sigma;
        let mut rng = crate::rng::Rng::new(seed);
        for r in scan.ranges.iter_mut().filter(|r| **r < scan.max_range) {
            *r += rng.gauss(sigma);
        }
        scan
    }

    fn model(objects: &str) -> RobotModel {
        let text = format!("[OBJECTS]\n{objects}\n[END]\n");
        RobotModel::parse(&text, "test").0
    }

    fn pickup(x: f64, y: f64, heading: f64) -> Solid {
        Solid::new(
            Shape::Box(Obb::new(Point2::new(x, y), heading, 0.4, 0.3)),
            SolidRef::PickupBox(0),
        )
    }

    /// A room wall 3 m ahead of the robot at the origin facing +x.
    fn back_wall() -> Solid {
        Solid::new(
            Shape::Box(Obb::from_segment(
                Point2::new(5.0, -5.0),
                Point2::new(5.0, 5.0),
                0.15,
            )),
            SolidRef::Wall(0),
        )
    }

    fn found(objects: &str, scene: &Scene, pose: Pose) -> Vec<Detection> {
        let mut out = Vec::new();
        objects_in(&model(objects), scene, pose, &mut out);
        out
    }

    fn objects_in(model: &RobotModel, scene: &Scene, pose: Pose, out: &mut Vec<Detection>) {
        objects(model, &scan_at(scene, pose), pose, out);
    }

    #[test]
    fn a_box_face_on_and_at_a_corner_is_found_near_its_middle() {
        for heading in [0.0, 0.5, std::f64::consts::FRAC_PI_4] {
            let scene = Scene::new(vec![pickup(2.5, 1.0, heading), back_wall()]);
            let d = found("box 0.3 0.5", &scene, Pose::new(0.0, 0.0, 0.0));
            assert_eq!(d.len(), 1, "{heading}: {d:?}");
            assert_eq!(d[0].object, "box");
            assert_eq!(d[0].sensor, "scanner");
            assert_eq!(d[0].side, Side::Left);
            // The visible outline's middle: within the box's half-diagonal.
            assert!(
                (d[0].x - 2.5).hypot(d[0].y - 1.0) < 0.25,
                "{heading}: {:?}",
                d[0]
            );
        }
    }

    #[test]
    fn round_things_and_walls_of_a_box_width_are_not_boxes() {
        let pillar = Solid::new(
            Shape::Circle(Circle::new(Point2::new(2.5, -1.0), 0.22)),
            SolidRef::Obstacle(0),
        );
        let scene = Scene::new(vec![pillar, back_wall()]);
        let d = found("box 0.3 0.5", &scene, Pose::new(0.0, 0.0, 0.0));
        assert!(d.is_empty(), "{d:?}");
        // Something flat on the wall does not stand clear of it.
        let plate = Solid::new(
            Shape::Box(Obb::new(Point2::new(4.85, 0.0), 0.0, 0.15, 0.4)),
            SolidRef::Obstacle(0),
        );
        let scene = Scene::new(vec![plate, back_wall()]);
        assert!(found("box 0.3 0.5", &scene, Pose::new(0.0, 0.0, 0.0)).is_empty());
    }

    #[test]
    fn the_width_decides_the_kind_and_overlapping_kinds_are_each_reported() {
        let scene = Scene::new(vec![pickup(2.5, 0.0, 0.0), back_wall()]);
        let pose = Pose::new(0.0, 0.0, 0.0);
        // Face on, the 0.3 m side shows.
        assert!(found("charger 0.5 0.7", &scene, pose).is_empty());
        let crate_box = Solid::new(
            Shape::Box(Obb::new(Point2::new(2.5, 0.0), 0.0, 0.5, 0.5)),
            SolidRef::Obstacle(0),
        );
        let scene = Scene::new(vec![crate_box, back_wall()]);
        let d = found("box 0.3 0.5\ncharger 0.5 0.7", &scene, pose);
        let names: Vec<&str> = d.iter().map(|d| d.object.as_str()).collect();
        assert_eq!(names, ["box", "charger"], "{d:?}");
    }

    #[test]
    fn objects_that_are_not_width_ranges_are_not_looked_for() {
        let scene = Scene::new(vec![pickup(2.5, 0.0, 0.0), back_wall()]);
        let pose = Pose::new(0.0, 0.0, 0.0);
        assert!(found("door 0.2 0.5\nside_edge 200 30", &scene, pose).is_empty());
        assert!(found("user yellow 30", &scene, pose).is_empty());
    }

    #[test]
    fn through_the_scanner_noise_a_box_is_found_in_nearly_every_scan() {
        let scene = Scene::new(vec![pickup(3.5, 0.3, 0.3), back_wall()]);
        let pose = Pose::new(0.0, 0.0, 0.0);
        let m = model("box 0.3 0.5");
        let found = (0..100)
            .filter(|&seed| {
                let mut out = Vec::new();
                objects(&m, &noisy_scan_at(&scene, pose, seed), pose, &mut out);
                out.len() == 1 && (out[0].x - 3.5).hypot(out[0].y - 0.3) < 0.25
            })
            .count();
        assert!(found >= 90, "{found} of 100 scans");
    }

    #[test]
    fn a_stretch_of_wall_between_dropouts_is_not_a_box() {
        // Figure 20's calibrated runs took pieces of the hall's walls for the
        // box: a dropout (a beam that returns nothing) either side of 0.3-0.5 m
        // of wall looked like a flat face with space beside it.
        let m = model("box 0.3 0.5");
        let pose = Pose::new(0.0, 0.0, 0.0);
        let scene = Scene::new(vec![back_wall()]);
        let clean = scan_at(&scene, pose);
        // The back wall 4.9 m ahead: half a degree is 4.3 cm there, so ten
        // beams span 0.43 m. Every such stretch across the wall, cut out by
        // one to three dropouts either side.
        let middle = clean.ranges.len() / 2;
        for start in (middle - 60..middle + 50).step_by(7) {
            for gap in 1..=DROPOUTS {
                let mut scan = clean.clone();
                for k in 0..gap {
                    scan.ranges[start - 1 - k] = scan.max_range;
                    scan.ranges[start + 10 + k] = scan.max_range;
                }
                let mut out = Vec::new();
                objects(&m, &scan, pose, &mut out);
                assert!(out.is_empty(), "beams {start}.., {gap} dropped: {out:?}");
            }
        }
        // A real box keeps being found when a beam beside it, on the wall
        // behind, drops out.
        let scene = Scene::new(vec![pickup(2.5, 0.0, 0.0), back_wall()]);
        let mut scan = scan_at(&scene, pose);
        let first = (0..scan.ranges.len())
            .find(|&i| scan.ranges[i] < 3.0)
            .unwrap_or_else(|| unreachable!("the box is ahead"));
        scan.ranges[first - 1] = scan.max_range;
        let mut out = Vec::new();
        objects(&m, &scan, pose, &mut out);
        assert_eq!(out.len(), 1, "{out:?}");
    }

    #[test]
    fn a_person_is_not_a_box_near_or_far() {
        let m = model("box 0.3 0.5\ncharger 0.5 0.7");
        for d in [1.5, 2.5, 4.0, 6.0, 9.0] {
            let person = Solid::new(
                Shape::Circle(Circle::new(Point2::new(0.85 + d, 0.4), 0.25)),
                SolidRef::Target(0),
            );
            let wall = Solid::new(
                Shape::Box(Obb::from_segment(
                    Point2::new(d + 3.0, -9.0),
                    Point2::new(d + 3.0, 9.0),
                    0.15,
                )),
                SolidRef::Wall(0),
            );
            let scene = Scene::new(vec![person, wall]);
            let pose = Pose::new(0.0, 0.0, 0.0);
            for seed in 0..40 {
                let mut out = Vec::new();
                objects(&m, &noisy_scan_at(&scene, pose, seed), pose, &mut out);
                assert!(out.is_empty(), "{d} m, seed {seed}: {out:?}");
            }
        }
    }

    #[test]
    fn walls_seen_edge_on_and_door_jambs_are_not_boxes() {
        // Along the office's main corridor and the north wing's hall, past
        // door jambs near and far: every box found is one of the world's.
        let office = crate::world::shipped("office")
            .and_then(Result::ok)
            .unwrap_or_else(|| unreachable!("the office world ships"));
        let scene = office.scene();
        let real: Vec<Point2<f64>> = office
            .pickup_boxes
            .iter()
            .map(|b| b.shape.center)
            .chain(office.obstacles.iter().map(|o| o.center()))
            .collect();
        let m = RobotModel::builtin("moro").unwrap_or_else(|| unreachable!());
        let mut seed = 0;
        let along = [(12.5, 3..31), (28.0, 9..31)]
            .into_iter()
            .flat_map(|(y, xs)| {
                xs.flat_map(move |x| {
                    [0.0, 0.2, std::f64::consts::PI, std::f64::consts::PI - 0.2]
                        .map(|h| Pose::new(f64::from(x), y, h))
                })
            });
        // Through the store room's door and H's, as Figure 20 turns into them.
        let doors = [(24.5, 1.0), (8.0, -1.0)].into_iter().flat_map(|(x, dir)| {
            (0..8).flat_map(move |k| {
                let y = 28.0 + dir * (0.5 + 0.25 * f64::from(k));
                [50.0f64, 70.0, 90.0, 110.0, 130.0]
                    .map(|deg| Pose::new(x, y, dir * deg.to_radians()))
            })
        });
        for pose in along.chain(doors) {
            seed += 1;
            let mut out = Vec::new();
            objects(&m, &noisy_scan_at(&scene, pose, seed), pose, &mut out);
            for d in out.iter().filter(|d| d.object == "box") {
                let at = Point2::new(d.x, d.y);
                assert!(
                    real.iter().any(|c| (c - at).hypot() < 0.5),
                    "from {pose:?}: {d:?}"
                );
            }
        }
    }
}

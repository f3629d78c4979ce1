//! Door openings found in one laser scan, for `sensor(scanner,door[,side])`.
//!
//! A door is a gap in a wall (section 4.1: an opening 0.8-1.2 m wide, the
//! model's `door` parameters). In a scan it shows as two jambs: a return
//! where the wall ends, beams that go on through the opening (or find
//! nothing), and a return where the wall starts again. Seen obliquely, as a
//! robot driving along a wall sees a door, the far jamb is further away than
//! the near one, so the opening is closed by the first beam that comes back
//! nearer than the beam before it, not by one as near as the first jamb.
//! Both jambs must lie on one wall: a few returns before the first and after
//! the second run along the line between them, which tells a door from a
//! gap between furniture.

use crate::geometry::{PlaneVector, Point2, Pose, Vector2, centroid};
use crate::sensors::Scan;
use ilmr_hal::{Detection, Side};
use ilmr_model::RobotModel;

/// A range step at least this large starts or ends an opening, m. The
/// scanner's noise is a centimetre; a person standing in a doorway is
/// further behind it than this.
const EDGE_JUMP: f64 = 0.4;
/// The far jamb is looked for within this angle of the near one, radians:
/// a 1.2 m door seen from 1 m away spans about 60 degrees.
const SEARCH_WINDOW: f64 = std::f64::consts::FRAC_PI_3;
/// What a jamb's face adds to a measured width beside the beam spacing, m.
const JAMB_SLACK: f64 = 0.03;
/// Beams through the opening meet something at least this far behind the
/// line between the jambs, m.
const BEHIND: f64 = 0.3;
/// Wall returns beside a jamb that are checked against the jambs' line, m.
const WALL_REACH: f64 = 1.0;
/// At least this many of them, so one stray return is not a wall.
const WALL_RETURNS: usize = 3;
/// How far a jamb may lie off its wall's line, m: the wall's thickness (a
/// jamb may be measured on its face) and the scanner's noise. Returns along
/// the wall keep within half of it.
const WALL_OFF: f64 = 0.2;

/// A jamb's return further than this off the line of the two wall returns
/// beyond it is a mixed pixel (a beam whose spot fell on the jamb's edge and
/// read between it and what is behind the door), m: three times the range
/// noise of two returns extrapolated. Seen along the wall at 20 degrees such a
/// return 0.2 m behind the wall's line is 0.5 m along it, and the door so
/// measured 0.8 m wide and 0.25 m off its middle (Figure 20's store room, seed
/// 1016, held backing out 0.08 m from a jamb). A return on a jamb's end face is
/// off the line too: stepping to the wall's face beside it moves the jamb by
/// a beam's spacing.
const MIXED_OFF: f64 = 0.08;
/// At least this many beams pass through an opening for it to be a door: fewer
/// are a door seen too obliquely or too far off to be located (three beams
/// through room H's door 9 m ahead, as MoRo turns out of Figure 20's
/// three-point turn in the hall), or a gap that dropouts and mixed pixels
/// make as well.
const MIN_THROUGH: usize = 4;
/// At most this many returns are stepped over at each jamb.
const MIXED_STEPS: usize = 2;

/// The model's door widths, smallest and largest, m.
fn widths(model: &RobotModel) -> Option<(String, f64, f64)> {
    let door = model.object("door")?;
    let w: Vec<f64> = door
        .params
        .iter()
        .filter_map(|p| p.parse::<f64>().ok())
        .collect();
    match w.as_slice() {
        [a, b, ..] if a.is_finite() && b.is_finite() => {
            Some((door.name.clone(), a.min(*b), a.max(*b)))
        }
        _ => None,
    }
}

/// Appends a detection for every door opening in `scan`, taken at `pose`
/// (the robot's estimate): the middle of the gap, heading through it away
/// from the robot, on the side of the robot it lies.
pub fn doors(model: &RobotModel, scan: &Scan, pose: Pose, out: &mut Vec<Detection>) {
    let Some((name, min_w, max_w)) = widths(model) else {
        return;
    };
    let r = &scan.ranges;
    let hit = |i: usize| scan.returned(i);
    let local = |i: usize| scan.local_point(i);
    let window = (SEARCH_WINDOW / scan.angle_increment.abs().max(1e-6)).ceil() as usize;
    let mut i = 0;
    while i + 1 < r.len() {
        if !(hit(i) && r[i + 1] - r[i] >= EDGE_JUMP) {
            i += 1;
            continue;
        }
        // Each beam that comes back nearer than the one before it may be the
        // far jamb; beams through the door may also pass through a door
        // behind it, which makes such a step too.
        let ia = on_wall(scan, i, -1);
        let a = local(ia);
        let door = (i + 1 + MIN_THROUGH..r.len().min(i + 2 + window))
            .filter(|&j| hit(j) && r[j - 1] - r[j] >= EDGE_JUMP)
            .find_map(|j| {
                let jb = on_wall(scan, j, 1);
                let b = local(jb);
                let width = (a - b).hypot();
                // A jamb is measured to a beam's spacing, and a beam may graze its face.
                let slack = JAMB_SLACK + r[ia].max(r[jb]) * scan.angle_increment.abs();
                let fits = (min_w - slack..=max_w + slack).contains(&width);
                (fits && through(scan, i, j, a, b))
                    .then(|| wall_line(scan, a, b, ia, jb))
                    .flatten()
                    .map(|along| (jb, b, along))
            });
        let Some((j, b, along)) = door else {
            i += 1;
            continue;
        };
        let (wa, wb) = (pose.to_world(&a), pose.to_world(&b));
        let mid = nalgebra::center(&wa, &wb);
        let mut normal = Vector2::from_angle(pose.h + along.polar_angle()).rotated_left();
        if normal.dot(&(mid - pose.position())) < 0.0 {
            normal *= -1.0;
        }
        let rel = crate::geometry::wrap_angle((mid - pose.position()).polar_angle() - pose.h);
        out.push(Detection {
            sensor: "scanner".into(),
            object: name.clone(),
            x: mid.x,
            y: mid.y,
            h: normal.polar_angle(),
            side: if rel >= 0.0 { Side::Left } else { Side::Right },
        });
        i = j;
    }
}

/// The jamb's return `k`, or the wall's beside it going `step` (+1 or -1)
/// where `k` is a mixed pixel: off the line through the next two returns by
/// more than `MIXED_OFF`.
fn on_wall(scan: &Scan, mut k: usize, step: isize) -> usize {
    let r = &scan.ranges;
    let at = |i: usize| scan.local_point(i);
    for _ in 0..MIXED_STEPS {
        let beyond = [1, 2].map(|n| k.checked_add_signed(n * step).filter(|&i| i < r.len()));
        let [Some(p), Some(q)] = beyond else {
            break;
        };
        if !(scan.returned(p) && scan.returned(q)) {
            break;
        }
        let (pp, pq) = (at(p), at(q));
        let along = pq - pp;
        let len = along.hypot();
        if len < 1e-9 || (at(k) - pp).perp(&along).abs() / len <= MIXED_OFF {
            break;
        }
        k = p;
    }
    k
}

/// Whether every beam between the jambs `i` and `j` passes the line `a`-`b`
/// by at least `BEHIND` (or returns nothing).
fn through(scan: &Scan, i: usize, j: usize, a: Point2<f64>, b: Point2<f64>) -> bool {
    let o = scan.mount;
    (i + 1..j).all(|k| {
        let dir = Vector2::from_angle(scan.bearing(k));
        // Where the beam crosses the line through the jambs.
        let ab = b - a;
        let denom = dir.perp(&ab);
        if denom.abs() < 1e-12 {
            return false;
        }
        let t = (a - o).perp(&ab) / denom;
        scan.ranges[k] >= t + BEHIND
    })
}

/// The returns in `order` within `WALL_REACH` of `jamb`, up to the first
/// beam without one.
fn beside(scan: &Scan, jamb: Point2<f64>, order: impl Iterator<Item = usize>) -> Vec<Point2<f64>> {
    order
        .map_while(|k| scan.returned(k).then(|| scan.local_point(k)))
        .take_while(|p| (p - jamb).hypot() <= WALL_REACH)
        .collect()
}

/// The direction of the wall the jambs `a` (beam `i`) and `b` (beam `j`)
/// stand in, in the scanner's frame: at least `WALL_RETURNS` returns beside
/// each jamb, outside the gap, all within `WALL_OFF` of the line through the
/// two sides' centroids, and the jambs on that line too. `None` when the
/// gap is not in a wall.
fn wall_line(
    scan: &Scan,
    a: Point2<f64>,
    b: Point2<f64>,
    i: usize,
    j: usize,
) -> Option<Vector2<f64>> {
    let near = beside(scan, a, (0..i).rev());
    let far = beside(scan, b, j + 1..scan.ranges.len());
    if near.len() < WALL_RETURNS || far.len() < WALL_RETURNS {
        return None;
    }
    let (c0, c1) = (centroid(&near), centroid(&far));
    let along = c1 - c0;
    let len = along.hypot();
    if len < 1e-9 {
        return None;
    }
    let u = along * (1.0 / len);
    let off = |p: Point2<f64>| (p - c0).perp(&u).abs();
    let (sa, sb) = ((a - c0).dot(&u), (b - c0).dot(&u));
    let (lo, hi) = (sa.min(sb), sa.max(sb));
    let beside_gap = |p: &Point2<f64>| {
        let s = (*p - c0).dot(&u);
        s <= lo + 0.05 || s >= hi - 0.05
    };
    let straight = near
        .iter()
        .chain(&far)
        .all(|p| off(*p) <= WALL_OFF / 2.0 && beside_gap(p));
    (straight && off(a) <= WALL_OFF && off(b) <= WALL_OFF).then_some(u)
}

#[cfg(test)]
mod tests {
    use super::super::scan_at;
    use super::*;
    use crate::geometry::{Obb, Scene, Shape, Solid, SolidRef};

    fn wall(x0: f64, y0: f64, x1: f64, y1: f64, id: usize) -> Solid {
        Solid::new(
            Shape::Box(Obb::from_segment(
                Point2::new(x0, y0),
                Point2::new(x1, y1),
                0.15,
            )),
            SolidRef::Wall(id),
        )
    }

    fn moro() -> RobotModel {
        RobotModel::builtin("moro").unwrap_or_else(|| unreachable!())
    }

    /// A corridor wall along y = 2.75 with a door of `width` centred at
    /// x = 5, a far wall 2 m behind it, and the robot at (9, 0) facing -x
    /// (Figure 58's lab, the door ahead on the right).
    fn lab(width: f64) -> Scene {
        let half = width / 2.0;
        Scene::new(vec![
            wall(-5.0, 2.75, 5.0 - half, 2.75, 0),
            wall(5.0 + half, 2.75, 15.0, 2.75, 1),
            wall(-5.0, 4.75, 15.0, 4.75, 2),
        ])
    }

    fn found(scene: &Scene, pose: Pose) -> Vec<Detection> {
        let mut out = Vec::new();
        doors(&moro(), &scan_at(scene, pose), pose, &mut out);
        out
    }

    #[test]
    fn a_door_seen_obliquely_ahead_right_is_found_at_its_middle() {
        let pose = Pose::new(9.0, 0.0, std::f64::consts::PI);
        let d = found(&lab(1.2), pose);
        assert_eq!(d.len(), 1, "{d:?}");
        // The jambs' faces are 7.5 cm from the wall's line.
        assert!((d[0].x - 5.0).abs() < 0.1, "{:?}", d[0]);
        assert!((d[0].y - 2.75).abs() < 0.1, "{:?}", d[0]);
        assert_eq!(d[0].side, Side::Right);
        // Heading through it, away from the robot: north.
        assert!((d[0].h - std::f64::consts::FRAC_PI_2).abs() < 0.1);
    }

    /// The beams where `scan` opens onto the door and closes again.
    fn opening(scan: &Scan) -> (usize, usize) {
        let r = &scan.ranges;
        let i = (0..r.len() - 1)
            .find(|&i| r[i + 1] - r[i] >= EDGE_JUMP)
            .unwrap_or_else(|| unreachable!("the door opens in the scan"));
        let j = (i + 2..r.len())
            .find(|&j| r[j - 1] - r[j] >= EDGE_JUMP)
            .unwrap_or_else(|| unreachable!("and closes"));
        (i, j)
    }

    #[test]
    fn a_mixed_pixel_at_the_far_jamb_does_not_move_the_door() {
        // The beam that grazes the far jamb's edge reads between it and the
        // room behind: 0.1-0.2 m behind the wall's line it passed for the jamb,
        // and made the store room's door of Figure 20 0.8 m wide and 0.25 m
        // off its middle.
        let pose = Pose::new(9.0, 0.0, std::f64::consts::PI);
        let clean = scan_at(&lab(1.2), pose);
        let (_, j) = opening(&clean);
        // The beam's angle to the wall (along x).
        let sin = Vector2::from_angle(pose.h + clean.bearing(j)).y.abs();
        for behind in [0.1, 0.15, 0.19] {
            let mut scan = clean.clone();
            scan.ranges[j] += behind / sin;
            let mut d = Vec::new();
            doors(&moro(), &scan, pose, &mut d);
            assert_eq!(d.len(), 1, "{behind}: {d:?}");
            assert!((d[0].x - 5.0).abs() < 0.1, "{behind}: {:?}", d[0]);
            assert!((d[0].y - 2.75).abs() < 0.1, "{behind}: {:?}", d[0]);
        }
    }

    #[test]
    fn a_door_seen_through_fewer_than_four_beams_is_not_yet_a_door() {
        // Along the wall, 2.75 m off it, from 14 m short of the door to 4 m.
        let mut few = 0;
        for k in 0..40 {
            let pose = Pose::new(9.0 + 0.25 * f64::from(k), 0.0, std::f64::consts::PI);
            let (i, j) = opening(&scan_at(&lab(1.2), pose));
            let through = j - i - 1;
            let d = found(&lab(1.2), pose);
            if through < MIN_THROUGH {
                few += 1;
                assert!(d.is_empty(), "{through} beams from {pose:?}: {d:?}");
            } else if k <= 12 {
                assert_eq!(d.len(), 1, "{through} beams from {pose:?}");
            }
        }
        assert!(few > 0, "some poses see the door through fewer beams");
    }

    #[test]
    fn the_same_door_from_the_corridor_and_from_abeam() {
        // From the far side, facing east: the door is on the right.
        let d = found(&lab(1.0), Pose::new(1.0, 3.75, 0.0));
        assert_eq!(d.len(), 1, "{d:?}");
        assert!((d[0].x - 5.0).abs() < 0.1);
        assert_eq!(d[0].side, Side::Right);
        assert!(
            (d[0].h + std::f64::consts::FRAC_PI_2).abs() < 0.1,
            "{:?}",
            d[0]
        );
        // Facing east below it: on the left, ahead and nearly abeam of the
        // scanner (0.85 m ahead of MoRo's reference point).
        for x in [2.0, 3.0] {
            let d = found(&lab(1.0), Pose::new(x, 0.5, 0.0));
            assert_eq!(d.len(), 1, "{x}: {d:?}");
            assert_eq!(d[0].side, Side::Left);
            assert!((d[0].x - 5.0).abs() < 0.1);
        }
    }

    #[test]
    fn the_office_lab_door_from_where_figure_58_looks_for_it() {
        // After the two left turns round the bench, facing west.
        let office = crate::world::shipped("office")
            .and_then(Result::ok)
            .unwrap_or_else(|| unreachable!());
        let pose = Pose::new(9.13, 8.81, std::f64::consts::PI);
        let d = found(&office.scene(), pose);
        assert_eq!(d.len(), 1, "{d:?}");
        assert!((d[0].x - 5.0).abs() < 0.1 && (d[0].y - 11.5).abs() < 0.1);
        assert_eq!(d[0].side, Side::Right);
    }

    #[test]
    fn openings_too_narrow_or_too_wide_are_not_doors() {
        let pose = Pose::new(9.0, 0.0, std::f64::consts::PI);
        assert!(found(&lab(0.5), pose).is_empty());
        assert!(found(&lab(2.0), pose).is_empty());
    }

    #[test]
    fn a_gap_between_two_boxes_is_not_a_door() {
        // Two cabinets 1 m apart, their faces not in line with each other.
        let scene = Scene::new(vec![
            Solid::new(
                Shape::Box(Obb::new(Point2::new(4.0, 2.5), 0.0, 0.5, 0.5)),
                SolidRef::Obstacle(0),
            ),
            Solid::new(
                Shape::Box(Obb::new(Point2::new(5.5, 3.5), 0.0, 0.5, 0.5)),
                SolidRef::Obstacle(1),
            ),
            wall(-5.0, 6.0, 15.0, 6.0, 0),
        ]);
        assert!(found(&scene, Pose::new(9.0, 0.0, std::f64::consts::PI)).is_empty());
    }

    #[test]
    fn nothing_without_a_door_in_the_model() {
        let mut model = moro();
        model
            .objects
            .retain(|o| !o.name.eq_ignore_ascii_case("door"));
        let pose = Pose::new(9.0, 0.0, std::f64::consts::PI);
        let mut out = Vec::new();
        doors(&model, &scan_at(&lab(1.0), pose), pose, &mut out);
        assert!(out.is_empty());
    }
}

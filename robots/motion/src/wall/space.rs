//! "When turn(left) or turn(right) is given, the space for turning is first
//! checked. If there is space, the trajectory is generated and executed"
//! (section 4.5.3): the space is the floor the robot's outline sweeps on the
//! quarter circle it will drive, at its own turning radius, and the way on
//! after it that the avoider will look along.

use crate::arc::Arc;
use crate::path::Path;
use crate::pose::{Pose, Side};
use nalgebra::{Point2, Vector2};
use std::f64::consts::FRAC_PI_2;

/// True when no map point lies within `half_width` of the path.
pub fn path_is_free(path: &Path, points: &[Point2<f64>], half_width: f64) -> bool {
    points.iter().all(|p| path.distance_to(p) > half_width)
}

/// A leg of wall following that runs into a wall ahead (the end of a
/// corridor), cut where the robot's front, `stop` metres ahead of a point of
/// the leg along it, first comes within `half_width` of a map point (or the
/// leg itself does); `None` when the leg is clear. Driven whole, the leg would
/// lead the robot into the avoider's area, which finds the wall with no way
/// round it: the robot stood blocked while the leg kept pointing into it.
pub fn leg_short_of_wall(
    leg: &Path,
    points: &[Point2<f64>],
    half_width: f64,
    stop: f64,
) -> Option<Path> {
    let pts = leg.points();
    let start = pts[0].position();
    let reach = leg.length() + stop.max(0.0) + half_width;
    let near: Vec<&Point2<f64>> = points
        .iter()
        .filter(|p| (*p - start).norm() <= reach)
        .collect();
    let blocked = |q: Point2<f64>| near.iter().any(|p| (*p - q).norm() < half_width);
    let hit = pts.iter().find(|q| {
        let h = q.travel_heading();
        let front = q.position() + stop.max(0.0) * Vector2::new(h.cos(), h.sin());
        blocked(q.position()) || blocked(front)
    })?;
    let (head, _) = leg.split_at_remaining(leg.length() - hit.s);
    Some(head)
}

/// The robot's outline about its reference point (the point whose pose it
/// reports), metres: to its front, to its rear, and half its width.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Outline {
    pub front: f64,
    pub rear: f64,
    pub half_width: f64,
}

impl Outline {
    /// How far the point `(x, y)` of the robot's frame (x ahead, y to the
    /// left) lies from the outline, m; 0 on or inside it. The points within a
    /// margin of the outline are the outline grown by the margin with
    /// rounded corners: growing it square would ask for the margin's
    /// diagonal, 1.4 times as much, past each corner.
    pub fn clearance(&self, x: f64, y: f64) -> f64 {
        let dx = (x - self.front).max(-self.rear - x).max(0.0);
        let dy = (y.abs() - self.half_width).max(0.0);
        dx.hypot(dy)
    }
}

/// What a quarter turn needs room for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TurnRoom {
    /// Of the quarter circle the reference point drives, 1/m (unsigned).
    pub curvature: f64,
    pub outline: Outline,
    /// Kept clear round the outline all the way, m.
    pub margin: f64,
    /// How far ahead of the reference point the way must be clear after the
    /// turn, m: where the avoider's area reaches (equation (11) from the
    /// front), so the turn is not begun only to be blocked at its end.
    pub lead_out: f64,
    /// Half the width of the avoider's area (equation (12)), which runs
    /// along the reference point's circle and on along the way after it:
    /// that band is kept clear too, or the avoider (or, with avoidance off,
    /// the supervisor) would stop the robot in the turn it has begun.
    pub lead_half_width: f64,
}

/// True when the robot's outline, grown by the margin, sweeps no map point
/// on a quarter turn to `side` from `pose`, nor on the straight after it, and
/// none lies in the avoider's band round the reference point's circle.
///
/// The sweep is the outline turned about the turn's centre. It is checked at
/// poses so close that the outline's farthest corner moves at most half the
/// margin between two of them: a point the outline itself would touch between
/// them lies within a quarter margin of the grown outline at one of them, so
/// the outline keeps at least three quarters of the margin everywhere.
pub fn turn_space_free(pose: &Pose, side: Side, room: &TurnRoom, points: &[Point2<f64>]) -> bool {
    let TurnRoom {
        curvature,
        outline,
        margin,
        lead_out,
        lead_half_width,
    } = *room;
    let sizes = [outline.front, outline.rear, outline.half_width, margin];
    if !(curvature.is_finite()
        && curvature > 0.0
        && lead_out.is_finite()
        && lead_half_width.is_finite()
        && sizes.iter().all(|v| v.is_finite() && *v >= 0.0))
    {
        return false;
    }
    let radius = 1.0 / curvature;
    // In the start pose's frame (x ahead, y to the left) the turn's centre is
    // a radius to the side; turning by `a` carries the outline round it.
    let centre = Vector2::new(0.0, side.sign() * radius);
    let (ahead, behind) = (outline.front + margin, outline.rear + margin);
    let half = outline.half_width + margin;
    let reach = ahead.max(behind).hypot(radius + half);
    let inner = radius - half;
    let steps = ((FRAC_PI_2 * reach / (0.5 * margin).max(1e-3)).ceil() as usize).max(1);
    let turned: Vec<(f64, f64)> = (0..=steps)
        .map(|i| (side.sign() * FRAC_PI_2 * i as f64 / steps as f64).sin_cos())
        .collect();
    let end = pose.advance(FRAC_PI_2 * radius, side.sign() * curvature);
    let band = Arc {
        start: *pose,
        curvature: side.sign() * curvature,
        length: FRAC_PI_2 * radius,
    };
    // The way on and the band are the avoider's area (equations (11) and
    // (12)), which has its own margin in it: a point outside it is no
    // obstacle to the avoider. Only the outline, where it reaches beyond
    // that area, keeps the margin.
    let way_half = lead_half_width.max(outline.half_width + margin);
    let way_ahead = lead_out.max(outline.front + margin);
    let swept = |l: Point2<f64>| {
        let from_centre = l.coords - centre;
        let r = from_centre.norm();
        if r > reach || r < inner {
            return false;
        }
        // The point as the outline sees it once turned by `a`: turned back
        // by `a` about the centre.
        turned.iter().any(|&(s, c)| {
            let q = Vector2::new(
                c * from_centre.x + s * from_centre.y,
                -s * from_centre.x + c * from_centre.y,
            ) + centre;
            outline.clearance(q.x, q.y) <= margin
        })
    };
    points.iter().all(|p| {
        let on_way = end.to_local(p);
        let blocks_way = (-behind..=way_ahead).contains(&on_way.x) && on_way.y.abs() <= way_half;
        !blocks_way && band.distance_to(p) > way_half && !swept(pose.to_local(p))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// MoRo (docs/robot-model.md): 0.95 m ahead of the rear axle to its
    /// front, 0.25 m behind it, 0.6 m wide, turning at 0.75 m.
    const MORO: Outline = Outline {
        front: 0.95,
        rear: 0.25,
        half_width: 0.3,
    };

    fn room(curvature: f64, margin: f64, lead_out: f64) -> TurnRoom {
        TurnRoom {
            curvature,
            outline: MORO,
            margin,
            lead_out,
            lead_half_width: 0.36,
        }
    }

    fn wall(from: (f64, f64), to: (f64, f64)) -> Vec<Point2<f64>> {
        let n = ((to.0 - from.0).hypot(to.1 - from.1) / 0.05).ceil() as usize;
        (0..=n)
            .map(|i| {
                let t = i as f64 / n as f64;
                Point2::new(from.0 + t * (to.0 - from.0), from.1 + t * (to.1 - from.1))
            })
            .collect()
    }

    /// The office's lab door (robots/worlds/office.toml): 1.2 m wide in the
    /// south wall of the 2 m corridor, middle at x = 5, the corridor running
    /// west to the wall at x = 0.5.
    fn office_door() -> Vec<Point2<f64>> {
        [
            wall((0.5, 11.5), (4.4, 11.5)),
            wall((5.6, 11.5), (12.0, 11.5)),
            wall((0.5, 13.5), (12.0, 13.5)),
            wall((0.5, 11.5), (0.5, 13.5)),
        ]
        .concat()
    }

    #[test]
    fn figure_58_turns_left_out_of_the_door_into_the_2_m_corridor() {
        let pts = office_door();
        let door = Pose::new(5.0, 11.5, FRAC_PI_2);
        let moro = room(1.0 / 0.75, 0.2, 2.55);
        assert!(turn_space_free(&door, Side::Left, &moro, &pts));
        // The far wall is 2 m ahead: a turn at 1.5 m radius sweeps into it.
        assert!(!turn_space_free(
            &door,
            Side::Left,
            &room(1.0 / 1.5, 0.2, 2.55),
            &pts
        ));
        // To the right the corridor is as wide, but 5 m of the avoider's
        // way ahead after the turn would reach the far end.
        assert!(turn_space_free(&door, Side::Right, &moro, &pts));
        assert!(!turn_space_free(
            &door,
            Side::Left,
            &room(1.0 / 0.75, 0.2, 5.0),
            &pts
        ));
        // Half a metre short of the door, the door's posts are in the way.
        let short = Pose::new(5.0, 11.0, FRAC_PI_2);
        assert!(!turn_space_free(&short, Side::Left, &moro, &pts));
    }

    #[test]
    fn the_margin_round_a_corner_of_the_outline_is_round() {
        // Beside, ahead and behind the outline the clearance is the distance
        // to its side; past a corner, to the corner.
        assert_eq!(MORO.clearance(0.0, 0.0), 0.0);
        assert!((MORO.clearance(0.0, -0.5) - 0.2).abs() < 1e-12);
        assert!((MORO.clearance(1.15, 0.1) - 0.2).abs() < 1e-12);
        assert!((MORO.clearance(-0.45, 0.0) - 0.2).abs() < 1e-12);
        let diagonal = MORO.clearance(0.95 + 0.15, 0.3 + 0.15);
        assert!((diagonal - 0.15 * 2f64.sqrt()).abs() < 1e-12);
        // 0.21 m from the corner: outside a 0.2 m margin, though inside the
        // square the margin would grow the outline to.
        assert!(MORO.clearance(0.95 + 0.15, -0.3 - 0.14) > 0.2);
    }

    #[test]
    fn figure_58_turns_out_of_the_door_when_the_robot_is_off_its_middle() {
        // Seed 1002 of the calibrated MoRo (issue 15 item 4): through the
        // door 5 cm right of its middle, heading 2 degrees right of north,
        // with the far wall seen 5 cm near (the scan taken while moving).
        // The avoider's area after the turn is 0.36 m each side of the way
        // on, which runs 1 m from the far wall: a turn with the outline's
        // 0.2 m margin fits while the rear axle is within 0.1 m of the
        // door's line.
        let pts = [
            wall((0.5, 11.5), (4.4, 11.5)),
            wall((5.6, 11.5), (12.0, 11.5)),
            wall((0.5, 13.45), (12.0, 13.45)),
            wall((0.5, 11.5), (0.5, 13.45)),
        ]
        .concat();
        let moro = room(1.0, 0.2, 2.55);
        let off = |y: f64| Pose::new(5.05, y, 88f64.to_radians());
        assert!(turn_space_free(&off(11.5), Side::Left, &moro, &pts));
        assert!(turn_space_free(&off(11.6), Side::Left, &moro, &pts));
        // Further on the far wall is in the front's sweep; short of it, the
        // door's posts are in the avoider's band.
        assert!(!turn_space_free(&off(11.7), Side::Left, &moro, &pts));
        assert!(!turn_space_free(&off(11.0), Side::Left, &moro, &pts));
        // Grown square, the outline's corners would close the way: the
        // margin's diagonal past the front's outer corner reaches the far wall.
        let square = TurnRoom {
            outline: Outline {
                front: MORO.front + 0.2,
                rear: MORO.rear + 0.2,
                half_width: MORO.half_width + 0.2,
            },
            margin: 0.0,
            ..moro
        };
        assert!(!turn_space_free(&off(11.6), Side::Left, &square, &pts));
    }

    #[test]
    fn left_turn_is_free_only_past_the_corner() {
        // A corridor 2 m wide along x, its left wall ending at x = 4.
        let pts = [
            wall((0.0, 1.0), (4.0, 1.0)),
            wall((0.0, -1.0), (12.0, -1.0)),
        ]
        .concat();
        let moro = room(1.0 / 0.75, 0.2, 0.0);
        assert!(!turn_space_free(
            &Pose::new(2.0, 0.0, 0.0),
            Side::Left,
            &moro,
            &pts
        ));
        // The reference point is the rear axle, which drives the innermost
        // circle: it may turn a little before the wall's end, as a driver does.
        assert!(!turn_space_free(
            &Pose::new(3.6, 0.0, 0.0),
            Side::Left,
            &moro,
            &pts
        ));
        assert!(turn_space_free(
            &Pose::new(4.0, 0.0, 0.0),
            Side::Left,
            &moro,
            &pts
        ));
        // The right side is a wall all along.
        assert!(!turn_space_free(
            &Pose::new(4.6, 0.0, 0.0),
            Side::Right,
            &moro,
            &pts
        ));
        assert!(!turn_space_free(
            &Pose::new(4.6, 0.0, 0.0),
            Side::Left,
            &room(0.0, 0.2, 0.0),
            &pts
        ));
        assert!(!turn_space_free(
            &Pose::new(4.6, 0.0, 0.0),
            Side::Left,
            &room(f64::NAN, 0.2, 0.0),
            &pts
        ));
    }

    #[test]
    fn the_way_on_after_the_turn_must_be_clear_too() {
        // The side corridor the robot turns into ends 2.5 m on in a wall:
        // the turn fits, but the avoider's area would find the wall at once.
        let pts = [
            wall((0.0, 1.0), (4.0, 1.0)),
            wall((0.0, -1.0), (12.0, -1.0)),
            wall((4.0, 3.0), (6.0, 3.0)),
        ]
        .concat();
        let at = Pose::new(4.0, 0.0, 0.0);
        assert!(turn_space_free(
            &at,
            Side::Left,
            &room(1.0 / 0.75, 0.2, 0.0),
            &pts
        ));
        assert!(!turn_space_free(
            &at,
            Side::Left,
            &room(1.0 / 0.75, 0.2, 2.55),
            &pts
        ));
        assert!(turn_space_free(
            &at,
            Side::Left,
            &room(1.0 / 0.75, 0.2, 1.8),
            &pts
        ));
    }

    #[test]
    fn a_leg_into_a_wall_ahead_stops_with_its_front_short_of_it() {
        let leg = crate::path::straight(Pose::new(4.0, 0.0, std::f64::consts::PI), 3.0, 0.05)
            .expect("a straight leg");
        let end_wall = wall((0.5, -1.0), (0.5, 1.0));
        let cut = leg_short_of_wall(&leg, &end_wall, 0.36, 1.15).expect("cut short");
        // The front (1.15 m on) stops 0.36 m short of the wall at x = 0.5.
        let end = cut.end_pose();
        assert!((end.x - 2.01).abs() < 0.06, "ends at {end:?}");
        assert!(leg_short_of_wall(&leg, &end_wall, 0.36, 0.1).is_none());
        // A wall alongside, further than the half width, is no reason to stop.
        let side = wall((0.0, 0.5), (5.0, 0.5));
        assert!(leg_short_of_wall(&leg, &side, 0.36, 1.15).is_none());
    }

    #[test]
    fn the_checked_poses_are_dense_enough_to_keep_most_of_the_margin() {
        // Against the outline swept at a thousand poses: a point the coarse
        // check lets pass is never within three quarters of the margin of
        // the outline at any pose, and one it stops at is in the outline's
        // way, the avoider's band or the way on.
        let dense = |pose: &Pose, side: Side, c: f64, margin: f64, p: &Point2<f64>| {
            let r = 1.0 / c;
            (0..=1000).any(|i| {
                let a = side.sign() * FRAC_PI_2 * f64::from(i) / 1000.0;
                let at = pose.advance(a * r * side.sign(), side.sign() * c);
                let l = at.to_local(p);
                MORO.clearance(l.x, l.y) <= margin
            })
        };
        let mut state = 5u64;
        let mut next = move || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let (mut free, mut blocked) = (0, 0);
        for round in 0..4000 {
            let side = if round % 2 == 0 {
                Side::Left
            } else {
                Side::Right
            };
            let c = [1.0 / 0.75, 0.25, 1.0][round % 3];
            let margin = 0.2;
            let p = Point2::new(5.0 * next() - 2.5, 5.0 * next() - 2.5);
            let pose = Pose::new(0.0, 0.0, 0.0);
            let coarse = turn_space_free(&pose, side, &room(c, margin, 0.0), &[p]);
            let end = pose.advance(FRAC_PI_2 / c, side.sign() * c).to_local(&p);
            let on_way = (-MORO.rear - margin..=MORO.front + margin).contains(&end.x)
                && end.y.abs() <= 0.36 + margin;
            let band = Arc {
                start: pose,
                curvature: side.sign() * c,
                length: FRAC_PI_2 / c,
            };
            let in_band = band.distance_to(&p) <= 0.36 + margin;
            if coarse {
                assert!(
                    !dense(&pose, side, c, 0.75 * margin, &p),
                    "round {round}: {p}"
                );
                free += 1;
            } else {
                assert!(
                    on_way || in_band || dense(&pose, side, c, margin, &p),
                    "round {round}: {p}"
                );
                blocked += 1;
            }
        }
        assert!(
            free > 500 && blocked > 500,
            "{free} free, {blocked} blocked"
        );
    }
}

//! The area checked for obstacles: length by equation (11), width by
//! equation (12), bent along the robot's current curvature, but no further
//! than the route turns: past that the area goes straight on.

use super::bounds::Bounds;
use super::grid::PointGrid;
use crate::arc::Arc;
use crate::path::{Direction, Path};
use crate::pose::{Pose, angle_diff};
use nalgebra::Point2;
use serde::{Deserialize, Serialize};

#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct AreaParams {
    /// R_max of equation (11): the robot's maximum curvature, 1/m.
    pub max_curvature: f64,
    /// robot_width of equation (12), m.
    pub robot_width: f64,
    /// From the pose's reference point to the front (in the direction of
    /// travel), m: the area starts there.
    pub front_offset: f64,
}

/// Equation (11): the turning radius plus two seconds of travel, at least
/// half a metre.
pub fn check_length(max_curvature: f64, speed: f64) -> f64 {
    let radius = if max_curvature > 0.0 {
        1.0 / max_curvature
    } else {
        0.0
    };
    (radius + 2.0 * speed.abs()).max(0.5)
}

/// Equation (12).
pub fn check_width(robot_width: f64) -> f64 {
    1.2 * robot_width
}

/// How far, in radians, the route turns towards the side of `curvature`
/// from the robot's heading, over the `reach` metres of `reference` from
/// index `k` on (0 when it turns the other way or not at all).
///
/// The robot steers along its route: once its heading has caught up with
/// the route's it straightens, so the area need bend no further. Bent the
/// whole length of equation (11) at a tight curvature, it would sweep round
/// through the wall the robot is turning past (the end of the lab bench in
/// Figure 58).
pub fn route_turn(reference: &Path, k: usize, travel: &Pose, curvature: f64, reach: f64) -> f64 {
    let pts = reference.points();
    let k = reference.clamp_index(k);
    let side = curvature.signum();
    let s_end = pts[k].s + reach.max(0.0);
    let mut heading = travel.h;
    let mut turned: f64 = 0.0;
    let mut most: f64 = 0.0;
    for p in pts[k..].iter().take_while(|p| p.s <= s_end) {
        let h = p.travel_heading();
        turned += angle_diff(h, heading);
        heading = h;
        most = most.max(side * turned);
    }
    most
}

/// True when `p`, found in the checked area, lies on the way the robot at
/// `pose` goes: within `half` of its `route` over the `reach` metres from
/// index `k`, widened by how far the robot is off the route now. The area of
/// equations (11) and (12) reaches straight on past where its bend ends,
/// while the route may turn on (round the end of Figure 58's lab bench) or
/// away (into a 2 m corridor from a door) or end (short of the wall at a
/// corridor's end): what lies there is not in the robot's way.
pub fn on_the_way(
    route: &Path,
    k: usize,
    pose: &Pose,
    p: &Point2<f64>,
    reach: f64,
    half: f64,
) -> bool {
    let off = route.distance_to_stretch(&pose.position(), k, 0.0);
    route.distance_to_stretch(p, k, reach) <= half + off
}

/// A map point inside the area, in the area's own coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    pub index: usize,
    /// Distance along the area from its start (the robot's front).
    pub s: f64,
    /// Offset to the left of the area's centre line.
    pub n: f64,
}

/// The checked area: a band of `width` around an arc of the robot's
/// current curvature, continued by a straight band of length `straight`
/// where the route stops turning; a rectangle when the robot drives
/// straight.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CheckArea {
    pub arc: Arc,
    pub straight: f64,
    pub width: f64,
}

impl CheckArea {
    /// The area in front of a robot at `pose` that moves in `direction`
    /// with steering `curvature` at `speed`, bent along the whole length.
    pub fn new(
        pose: &Pose,
        direction: Direction,
        curvature: f64,
        speed: f64,
        params: &AreaParams,
    ) -> CheckArea {
        Self::turning_at_most(pose, direction, curvature, speed, params, f64::INFINITY)
    }

    /// As `new`, but the area turns through at most `max_turn` radians
    /// (measured from the robot's heading, the stretch to the front
    /// included) and goes straight on after that.
    pub fn turning_at_most(
        pose: &Pose,
        direction: Direction,
        curvature: f64,
        speed: f64,
        params: &AreaParams,
        max_turn: f64,
    ) -> CheckArea {
        let travel = match direction {
            Direction::Forward => *pose,
            Direction::Backward => pose.flipped(),
        };
        let geometric = direction.sign() * curvature;
        let bend = if geometric == 0.0 || max_turn.is_nan() {
            f64::INFINITY
        } else {
            max_turn.max(0.0) / geometric.abs()
        };
        let length = check_length(params.max_curvature, speed);
        // The front: along the arc as far as the bend goes, then straight.
        let to_front = params.front_offset.min(bend);
        let start = travel
            .advance(to_front, geometric)
            .advance(params.front_offset - to_front, 0.0);
        let arc_length = length.min((bend - to_front).max(0.0));
        let arc_curvature = if arc_length > 0.0 { geometric } else { 0.0 };
        CheckArea {
            arc: Arc {
                start,
                curvature: arc_curvature,
                length: arc_length,
            },
            straight: length - arc_length,
            width: check_width(params.robot_width),
        }
    }

    /// Total length of the area, m.
    pub fn length(&self) -> f64 {
        self.arc.length + self.straight
    }

    /// Every point of the area lies within this distance of the arc's start:
    /// its length along the path plus half its width.
    pub fn reach(&self) -> f64 {
        self.arc.length.max(0.0) + self.straight.max(0.0) + 0.5 * self.width
    }

    pub fn hit(&self, index: usize, p: &Point2<f64>) -> Option<Hit> {
        self.hit_from(index, p, |p| {
            let l = self.arc.end().to_local(p);
            (l.x, l.y)
        })
    }

    /// `hit`, with `from_end` giving a point's coordinates in the frame of
    /// the arc's end (the straight band's).
    fn hit_from(
        &self,
        index: usize,
        p: &Point2<f64>,
        from_end: impl FnOnce(&Point2<f64>) -> (f64, f64),
    ) -> Option<Hit> {
        let half = 0.5 * self.width;
        // Most mapped points are rejected here, before the trigonometry of
        // the arc's coordinates.
        let reach = self.reach();
        let (dx, dy) = (p.x - self.arc.start.x, p.y - self.arc.start.y);
        if dx * dx + dy * dy > reach * reach {
            return None;
        }
        let (s, n) = self.arc.coords(p);
        if s >= 0.0 && s <= self.arc.length && n.abs() <= half {
            return Some(Hit { index, s, n });
        }
        if self.straight <= 0.0 {
            return None;
        }
        let (x, y) = from_end(p);
        (x >= 0.0 && x <= self.straight && y.abs() <= half).then_some(Hit {
            index,
            s: self.arc.length + x,
            n: y,
        })
    }

    /// Every map point inside the area, nearest first (ties by index).
    pub fn hits(&self, points: &[Point2<f64>]) -> Vec<Hit> {
        let mut hits: Vec<Hit> = points
            .iter()
            .enumerate()
            .filter_map(|(i, p)| self.hit(i, p))
            .collect();
        hits.sort_by(|a, b| a.s.total_cmp(&b.s).then(a.index.cmp(&b.index)));
        hits
    }

    /// As `hits`, visiting only the points `grid` (an index of `points`)
    /// places near the area; the same hits in the same order (the sort is a
    /// total order). A grid of
    /// another length than `points` is not trusted: every point is checked.
    pub fn hits_near(&self, points: &[Point2<f64>], grid: &PointGrid) -> Vec<Hit> {
        if grid.len() != points.len() {
            return self.hits(points);
        }
        let tester = self.tester();
        let mut near = Vec::new();
        grid.within(&tester.bounds(), &mut near);
        let mut hits: Vec<Hit> = near
            .into_iter()
            .filter_map(|i| tester.hit(i, &points[i]))
            .collect();
        hits.sort_by(|a, b| a.s.total_cmp(&b.s).then(a.index.cmp(&b.index)));
        hits
    }

    /// "If one or more of them is inside the defined area, an obstacle is
    /// found": the nearest such point.
    pub fn first_hit(&self, points: &[Point2<f64>]) -> Option<Hit> {
        self.hits(points).into_iter().next()
    }

    /// `hit` for testing many points against this area.
    pub fn tester(&self) -> AreaTester {
        AreaTester::new(*self)
    }
}

/// Slack of the screen's bounds: rounding in the arc's coordinates, m.
const SCREEN_SLACK: f64 = 1e-6;
/// Tighter than this (1/m), the band round the arc is screened as a ring
/// round its centre; flatter, the ring's radius would swamp the slack.
const RING_CURVATURE: f64 = 1e-3;

/// `CheckArea::hit` for many points: the same answers, with a cheap screen
/// in front (the start and end frames' sines and cosines worked out once)
/// that every point the area accepts passes, so the arc's trigonometry is
/// spent only on points near its band; and the box to ask a grid for.
#[derive(Clone, Copy, Debug)]
pub struct AreaTester {
    area: CheckArea,
    /// Nothing is screened out: the area has a value that is not finite.
    open: bool,
    start: Frame,
    end: Frame,
    /// The arc's band in the start frame: `lo` to `hi` along each axis.
    arc_lo: (f64, f64),
    arc_hi: (f64, f64),
    /// The ring's centre in the start frame, its radius and half width.
    ring: Option<((f64, f64), f64, f64)>,
    /// The straight band in the end frame (none without one).
    straight: Option<((f64, f64), (f64, f64))>,
}

/// A pose's translation with its heading's sine and cosine.
#[derive(Clone, Copy, Debug)]
struct Frame {
    x: f64,
    y: f64,
    s: f64,
    c: f64,
}

impl Frame {
    fn of(p: &Pose) -> Frame {
        let (s, c) = p.h.sin_cos();
        Frame {
            x: p.x,
            y: p.y,
            s,
            c,
        }
    }

    fn local(&self, p: &Point2<f64>) -> (f64, f64) {
        let (dx, dy) = (p.x - self.x, p.y - self.y);
        (self.c * dx + self.s * dy, -self.s * dx + self.c * dy)
    }

    fn bounds(&self, (lo, hi): ((f64, f64), (f64, f64))) -> Bounds {
        Bounds::turned((self.x, self.y), (self.s, self.c), lo, hi)
    }
}

fn within((lo, hi): ((f64, f64), (f64, f64)), (x, y): (f64, f64)) -> bool {
    x >= lo.0 && x <= hi.0 && y >= lo.1 && y <= hi.1
}

impl AreaTester {
    fn new(area: CheckArea) -> AreaTester {
        let half = 0.5 * area.width;
        let (k, len) = (area.arc.curvature, area.arc.length);
        let end = area.arc.end();
        let open = ![
            half,
            k,
            len,
            area.straight,
            area.arc.start.x,
            area.arc.start.y,
            area.arc.start.h,
            end.x,
            end.y,
            end.h,
        ]
        .iter()
        .all(|v| v.is_finite());
        let m = SCREEN_SLACK + 1e-9 * (len.abs() + area.straight.abs() + half.abs());
        let band = half.abs() + m;
        // A point of the band is `n` off the arc at arc length `s` in
        // [0, len]: ahead of the start by at most `s + |n|`, behind it only
        // once the arc has turned past a right angle (then by at most the
        // radius plus |n|), and aside, towards the side the arc bends, by
        // at most the arc's own sideways run plus |n|.
        let radius = if k == 0.0 {
            f64::INFINITY
        } else {
            1.0 / k.abs()
        };
        let back = if k.abs() * len > std::f64::consts::FRAC_PI_2 {
            radius
        } else {
            0.0
        };
        let aside = (0.5 * k.abs() * len * len).min(2.0 * radius);
        let (y_lo, y_hi) = if k > 0.0 {
            (-band, aside + band)
        } else if k < 0.0 {
            (-aside - band, band)
        } else {
            (-band, band)
        };
        let ring = (k.abs() >= RING_CURVATURE).then(|| ((0.0, 1.0 / k), radius, band));
        let side = half.abs() + SCREEN_SLACK;
        AreaTester {
            area,
            open,
            start: Frame::of(&area.arc.start),
            end: Frame::of(&end),
            arc_lo: (-band - back, y_lo),
            arc_hi: (len.max(0.0) + band, y_hi),
            ring,
            straight: (area.straight > 0.0).then_some(((-m, -side), (area.straight + m, side))),
        }
    }

    /// Whether `p` may lie in the area: true for every point it holds.
    fn may_hit(&self, p: &Point2<f64>) -> bool {
        if self.open {
            return true;
        }
        let l = self.start.local(p);
        let on_arc = within((self.arc_lo, self.arc_hi), l)
            && self.ring.is_none_or(|((cx, cy), r, band)| {
                let (dx, dy) = (l.0 - cx, l.1 - cy);
                ((dx * dx + dy * dy).sqrt() - r).abs() <= band
            });
        on_arc || self.straight.is_some_and(|b| within(b, self.end.local(p)))
    }

    /// Exactly `CheckArea::hit`: the end frame's sine and cosine are the
    /// ones `Pose::to_local` works out, and the arithmetic is its own.
    pub fn hit(&self, index: usize, p: &Point2<f64>) -> Option<Hit> {
        if self.may_hit(p) {
            self.area.hit_from(index, p, |p| self.end.local(p))
        } else {
            None
        }
    }

    /// A box that holds every point the area accepts.
    pub fn bounds(&self) -> Bounds {
        if self.open {
            return Bounds::ALL;
        }
        let start = &self.area.arc.start;
        // `hit` compares squares: a negative reach bounds by its size.
        let disc = Bounds::square((start.x, start.y), self.area.reach());
        let arc = self.start.bounds((self.arc_lo, self.arc_hi));
        let band = match self.straight {
            Some(b) => arc.or(&self.end.bounds(b)),
            None => arc,
        };
        band.and(&disc)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_what_lies_along_the_route_is_in_the_way() {
        // Out of a door heading north, a quarter turn left at 1 m radius:
        // the far wall of the 2 m corridor lies straight ahead, not on the way.
        let door = Pose::new(5.0, 11.5, std::f64::consts::FRAC_PI_2);
        let spec = crate::path::TurnSpec::degrees(90.0, 1.0);
        let route = crate::path::turn(door, &spec, Direction::Forward, 0.05).expect("a turn");
        let far_wall = Point2::new(5.0, 13.5);
        assert!(!on_the_way(&route, 0, &door, &far_wall, 2.55, 0.36));
        // A box on the arc, or beside it within the half width, is.
        assert!(on_the_way(
            &route,
            0,
            &door,
            &Point2::new(4.0, 12.5),
            2.55,
            0.36
        ));
        assert!(on_the_way(
            &route,
            0,
            &door,
            &Point2::new(4.3, 12.2),
            2.55,
            0.36
        ));
        // Beyond the reach it is not yet.
        assert!(!on_the_way(
            &route,
            0,
            &door,
            &Point2::new(4.0, 12.5),
            0.5,
            0.36
        ));
        // A robot 0.5 m off its route (round an obstacle) widens the band.
        let off = Pose::new(5.5, 11.5, std::f64::consts::FRAC_PI_2);
        let beside = Point2::new(5.8, 11.6);
        assert!(!on_the_way(&route, 0, &door, &beside, 2.55, 0.36));
        assert!(on_the_way(&route, 0, &off, &beside, 2.55, 0.36));
    }

    const MORO: AreaParams = AreaParams {
        max_curvature: 1.0 / 0.75,
        robot_width: 0.6,
        front_offset: 0.9,
    };

    #[test]
    fn dimensions_follow_equations_11_and_12() {
        assert!((check_length(1.0 / 0.75, 0.4) - (0.75 + 0.8)).abs() < 1e-12);
        assert!((check_length(0.25, 0.0) - 4.0).abs() < 1e-12);
        // Equation (11) has a floor of half a metre.
        assert_eq!(check_length(10.0, 0.1), 0.5);
        assert!((check_width(0.6) - 0.72).abs() < 1e-12);
        let a = CheckArea::new(
            &Pose::new(0.0, 0.0, 0.0),
            Direction::Forward,
            0.0,
            0.4,
            &MORO,
        );
        assert!((a.arc.length - 1.55).abs() < 1e-12 && (a.width - 0.72).abs() < 1e-12);
    }

    #[test]
    fn straight_area_is_a_rectangle_ahead_of_the_front() {
        let a = CheckArea::new(
            &Pose::new(0.0, 0.0, 0.0),
            Direction::Forward,
            0.0,
            0.4,
            &MORO,
        );
        assert!(a.hit(0, &Point2::new(1.0, 0.35)).is_some());
        assert!(a.hit(0, &Point2::new(1.0, 0.37)).is_none());
        assert!(
            a.hit(0, &Point2::new(0.8, 0.0)).is_none(),
            "behind the front"
        );
        assert!(a.hit(0, &Point2::new(2.44, 0.0)).is_some());
        assert!(a.hit(0, &Point2::new(2.46, 0.0)).is_none(), "beyond l_obs");
    }

    #[test]
    fn curving_area_follows_the_turn() {
        let a = CheckArea::new(
            &Pose::new(0.0, 0.0, 0.0),
            Direction::Forward,
            1.0,
            0.4,
            &MORO,
        );
        // Straight ahead at the far end lies outside the bent band, a point
        // on the arc there inside it.
        let on_arc = a.arc.point_at(1.4);
        assert!(a.hit(0, &on_arc).is_some());
        assert!(a.hit(0, &Point2::new(0.9 + 1.4, 0.0)).is_none());
    }

    #[test]
    fn reversing_checks_behind() {
        let a = CheckArea::new(
            &Pose::new(0.0, 0.0, 0.0),
            Direction::Backward,
            0.0,
            0.3,
            &MORO,
        );
        assert!(a.hit(0, &Point2::new(-1.2, 0.0)).is_some());
        assert!(a.hit(0, &Point2::new(1.2, 0.0)).is_none());
    }

    #[test]
    fn first_hit_is_the_nearest() {
        let a = CheckArea::new(
            &Pose::new(0.0, 0.0, 0.0),
            Direction::Forward,
            0.0,
            0.4,
            &MORO,
        );
        let pts = [
            Point2::new(2.0, 0.1),
            Point2::new(5.0, 0.0),
            Point2::new(1.2, -0.2),
        ];
        assert_eq!(a.first_hit(&pts).map(|h| h.index), Some(2));
        assert_eq!(a.hits(&pts).len(), 2);
    }

    #[test]
    fn hits_near_finds_exactly_the_hits_of_a_full_scan() {
        use crate::obstacle::grid::tests::{Rng, cloud};
        use crate::obstacle::grid_of;
        let mut rng = Rng::new(11);
        let mut found = 0;
        for round in 0..400 {
            let n = 50 + (rng.next_u64() % 600) as usize;
            let pts = cloud(&mut rng, n, 0.05);
            let grid = grid_of([0.05, 0.25, 0.7][round % 3], &pts);
            let pose = Pose::new(
                rng.range(-3.0, 3.0),
                rng.range(-3.0, 3.0),
                rng.range(-4.0, 4.0),
            );
            let direction = if rng.next_u64().is_multiple_of(3) {
                Direction::Backward
            } else {
                Direction::Forward
            };
            let curvature = [0.0, rng.range(-1.5, 1.5), 1e-10][(rng.next_u64() % 3) as usize];
            let max_turn = [f64::INFINITY, rng.range(0.0, 2.0)][(rng.next_u64() % 2) as usize];
            let area = CheckArea::turning_at_most(
                &pose,
                direction,
                curvature,
                rng.range(0.0, 1.2),
                &MORO,
                max_turn,
            );
            let want = area.hits(&pts);
            found += want.len();
            assert_eq!(area.hits_near(&pts, &grid), want, "round {round}");
        }
        assert!(found > 1000, "the areas hit something: {found}");
        // A grid of another cloud is not trusted.
        let pts = [Point2::new(1.5, 0.0)];
        let area = CheckArea::new(
            &Pose::new(0.0, 0.0, 0.0),
            Direction::Forward,
            0.0,
            0.4,
            &MORO,
        );
        assert_eq!(area.hits_near(&pts, &grid_of(0.25, &[])).len(), 1);
    }

    #[test]
    fn the_tester_answers_exactly_as_the_area() {
        use crate::obstacle::grid::tests::Rng;
        let mut rng = Rng::new(5);
        let (mut hits, mut screened) = (0, 0);
        for round in 0..3000 {
            let pose = Pose::new(
                rng.range(-2.0, 2.0),
                rng.range(-2.0, 2.0),
                rng.range(-4.0, 4.0),
            );
            let direction = if rng.next_u64().is_multiple_of(3) {
                Direction::Backward
            } else {
                Direction::Forward
            };
            let curvature = match rng.next_u64() % 6 {
                0 => 0.0,
                1 => rng.range(-1e-3, 1e-3),
                2 => rng.range(-1e-8, 1e-8),
                3 => [1.0 / 0.75, -1.0 / 0.75, 4.0][(rng.next_u64() % 3) as usize],
                _ => rng.range(-2.0, 2.0),
            };
            let max_turn = match rng.next_u64() % 3 {
                0 => f64::INFINITY,
                1 => 0.0,
                _ => rng.range(0.0, 3.5),
            };
            let params = AreaParams {
                max_curvature: [1.0 / 0.75, 0.25, 0.01][(rng.next_u64() % 3) as usize],
                robot_width: rng.range(0.3, 1.4),
                front_offset: rng.range(0.0, 1.2),
            };
            let area = CheckArea::turning_at_most(
                &pose,
                direction,
                curvature,
                rng.range(0.0, 1.5),
                &params,
                max_turn,
            );
            let tester = area.tester();
            for i in 0..60 {
                // Half the points on or just off the band's edges, where
                // the screen is tightest.
                let p = if i % 2 == 0 {
                    let s = rng.range(-0.2, area.length() + 0.2);
                    let n = (0.5 * area.width + rng.range(-1e-9, 1e-9))
                        * [1.0, -1.0, rng.range(-1.0, 1.0)][(rng.next_u64() % 3) as usize];
                    let on = if s <= area.arc.length {
                        area.arc.start.advance(s, area.arc.curvature)
                    } else {
                        area.arc.end().advance(s - area.arc.length, 0.0)
                    };
                    on.to_world(&Point2::new(0.0, n))
                } else {
                    Point2::new(rng.range(-8.0, 8.0), rng.range(-8.0, 8.0))
                };
                let want = area.hit(i, &p);
                let bits = |h: Option<Hit>| h.map(|h| (h.index, h.s.to_bits(), h.n.to_bits()));
                assert_eq!(
                    bits(tester.hit(i, &p)),
                    bits(want),
                    "round {round}, point {p:?}"
                );
                if want.is_some() {
                    assert!(
                        tester.bounds().contains((p.x, p.y)),
                        "round {round}: {p:?} outside"
                    );
                }
                hits += usize::from(want.is_some());
                screened += usize::from(!tester.may_hit(&p));
            }
        }
        assert!(
            hits > 20_000 && screened > 40_000,
            "{hits} hits, {screened} screened out"
        );
    }

    #[test]
    fn the_area_bends_no_further_than_the_route_turns() {
        // A quarter circle of radius 1 to the left, then straight north.
        let spec = crate::path::TurnSpec {
            lead_out: 3.0,
            ..crate::path::TurnSpec::degrees(90.0, 1.0)
        };
        let route = crate::path::turn(Pose::new(0.0, 0.0, 0.0), &spec, Direction::Forward, 0.05)
            .expect("valid");
        let at = Pose::new(0.0, 0.0, 0.0);
        let turn = route_turn(&route, 0, &at, 1.0, 4.0);
        assert!((turn - std::f64::consts::FRAC_PI_2).abs() < 1e-9, "{turn}");
        // Steering right against a left route: nothing to bend for.
        assert_eq!(route_turn(&route, 0, &at, -1.0, 4.0), 0.0);

        let full = CheckArea::new(&at, Direction::Forward, 1.0, 0.4, &MORO);
        let limited = CheckArea::turning_at_most(&at, Direction::Forward, 1.0, 0.4, &MORO, turn);
        assert!((limited.length() - full.length()).abs() < 1e-12);
        assert!(limited.straight > 0.0 && full.straight == 0.0);
        // Inside the circle past the quarter, where the full bend sweeps
        // (the wall the robot turns round); the limited area goes north.
        let inside = Point2::new(0.55, 1.45);
        assert!(full.hit(0, &inside).is_some());
        assert!(limited.hit(0, &inside).is_none());
        let ahead = Point2::new(1.0, 1.6);
        let h = limited.hit(0, &ahead).expect("on the route after the turn");
        assert!(h.n.abs() < 1e-9 && h.s > limited.arc.length);
    }
}

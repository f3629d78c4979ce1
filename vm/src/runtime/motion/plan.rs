//! Reference paths for each movement command, built with ilmr-motion:
//! straights and arcs (`goahead`, `turn(d=..,c=..)`), Bezier curves to a
//! pose with the reverse-and-turn fallback of `r` (`gotoxy`, `gotorelxy`,
//! `turn(variable)`, `approach`), taught paths made drivable (`followpath`,
//! joined where the robot can meet them), and the
//! first leg of the behaviours (`followwall`, `turn(left|right)`,
//! `followtarget`).

use std::f64::consts::FRAC_PI_2;

use ilmr_hal::Hal;
use ilmr_motion::obstacle::{check_length, check_width};
use ilmr_motion::path::{JOIN_TOLERANCE, TurnSpec, straight, taught, turn};
use ilmr_motion::wall::{
    FOLLOWWALL_AHEAD, Outline, TurnRoom, WallParams, fit_wall, followwall_goal, leg_short_of_wall,
    middle_goal, turn_space_free,
};
use ilmr_motion::{Direction, Path, PlanError, PlanParams, Pose, Side, plan_with};
use nalgebra::{Point2, Vector2};

use super::{Mode, WallSide};
use crate::bytecode::{NameId, VarId};
use crate::runtime::Vm;
use crate::runtime::clock::Clock;
use crate::runtime::nodes::{MoveSpec, WallMode};
use crate::runtime::safety::{Code, Refusal};

/// Distance between the points of a reference path, m.
pub(crate) const SPACING: f64 = 0.05;
/// A `goahead` without a distance is planned this far and extended as it goes.
pub(crate) const ENDLESS_LEG: f64 = 30.0;
/// Clearance `turn(left|right)` keeps round the robot's outline, m: the
/// controller, ramping its curvature at `curinc`, falls behind the quarter
/// circle at its start before it catches up (MoRo at 0.3 m/s: a few
/// centimetres), and the map's cells are 5 cm.
pub(crate) const TURN_MARGIN: f64 = 0.2;
/// How much further than the robot's leading end the straight into a
/// position with a heading begins, m: the controller's lag behind a bend
/// (MoRo at 0.3 m/s, calibrated: a few centimetres) and the map's 5 cm cells.
const LINE_UP_MARGIN: f64 = 0.2;
/// `followpath` may join its path this many turning radii past the first
/// point. A three-point turn at a path's end leaves the robot a radius
/// back and a radius aside, facing across the path; the Bezier of
/// equations (2)-(3) bends up to about 1.4 times as sharply as a circle, so
/// it meets the path some three to four radii along.
const JOIN_REACH: f64 = 5.0;
/// Candidate joins are this far apart along the path, m.
const JOIN_STEP: f64 = 0.25;

fn err(e: impl std::fmt::Display) -> String {
    e.to_string()
}

/// The path and behaviour a movement starts with.
pub(crate) struct Planned {
    pub path: Path,
    pub mode: Mode,
    /// A behaviour's leg that ends short of a wall ahead: the robot brakes
    /// for its end.
    pub walled: bool,
}

impl Planned {
    fn path(path: Path) -> Planned {
        Planned {
            path,
            mode: Mode::Path,
            walled: false,
        }
    }
}

/// A leg of wall following, and whether it was cut short of a wall ahead.
pub(crate) struct Leg {
    pub path: Path,
    pub walled: bool,
}

impl<H: Hal, C: Clock> Vm<H, C> {
    /// Forwards, or backwards after a negative `speed(..)`.
    pub(crate) fn travel_direction(&self) -> Direction {
        Direction::of(self.motion.speed)
    }

    fn plan_params(&self, direction: Direction, allow_reverse: bool) -> PlanParams {
        PlanParams {
            allow_reverse,
            direction,
            spacing: SPACING,
            ..PlanParams::new(self.cfg.max_curvature)
        }
    }

    /// A Bezier from `start` to `goal` (body headings), or with `r` the
    /// reverse-and-turn manoeuvre when the direct curve is too tight.
    pub(crate) fn bezier(
        &self,
        start: Pose,
        goal: Pose,
        direction: Direction,
        allow_reverse: bool,
    ) -> Result<Path, Refusal> {
        plan_with(start, goal, &self.plan_params(direction, allow_reverse))
            .map_err(|e| match e {
                PlanError::NoAdmissiblePath { .. } => Refusal::new(Code::PathTooCurved, err(e)),
                e => Refusal::from(err(e)),
            })?
            .path()
            .map_err(|e| Refusal::from(err(e)))
    }

    /// The body heading that faces (or, reversing, backs towards) `to`.
    fn facing(start: &Pose, to: &Point2<f64>, direction: Direction) -> f64 {
        let bearing = (to.y - start.y).atan2(to.x - start.x);
        match direction {
            Direction::Forward => bearing,
            Direction::Backward => bearing + std::f64::consts::PI,
        }
    }

    fn goto(&self, start: Pose, to: Point2<f64>, h: Option<f64>, r: bool) -> Result<Path, Refusal> {
        let dir = self.travel_direction();
        let h = h.unwrap_or_else(|| Self::facing(&start, &to, dir));
        self.bezier(start, Pose::new(to.x, to.y, h), dir, r)
    }

    /// To `to` arriving with heading `h`, the last stretch straight along it
    /// for as far as the robot's leading end reaches past its reference point
    /// (and `LINE_UP_MARGIN`), so that the whole body crosses a door's line
    /// already facing through it. Ending the Bezier at the door point itself,
    /// the reference point (MoRo's rear axle) lines up there, when its front,
    /// 0.95 m ahead, has long crossed the line still turning, its corner
    /// swung out towards the door post (Figure 58's `gotoxy(door)`, seed 11:
    /// held 0.2 m from the lab door's west post). Where the robot is already
    /// past where the straight would begin, or the shorter curve is too
    /// tight, the Bezier ends at the point as before.
    fn goto_lined_up(
        &self,
        start: Pose,
        to: Point2<f64>,
        h: f64,
        r: bool,
    ) -> Result<Path, Refusal> {
        let dir = self.travel_direction();
        let reach = match dir {
            Direction::Forward => self.cfg.front_offset,
            Direction::Backward => self.cfg.robot_length - self.cfg.front_offset,
        };
        let lead = reach.max(0.0) + LINE_UP_MARGIN;
        let travel = dir.sign() * Vector2::new(h.cos(), h.sin());
        let from = to - lead * travel;
        if (from - start.position()).dot(&travel) > 0.0 {
            let lined = self
                .bezier(start, Pose::new(from.x, from.y, h), dir, r)
                .and_then(|bend| {
                    let last =
                        straight(bend.end_pose(), dir.sign() * lead, SPACING).map_err(err)?;
                    bend.concat(&last, JOIN_TOLERANCE)
                        .map_err(|e| err(e).into())
                });
            if let Ok(path) = lined {
                return Ok(path);
            }
        }
        self.goto(start, to, Some(h), r)
    }

    fn approach_point(&self, start: Pose, tx: f64, ty: f64, d: f64) -> Result<Path, Refusal> {
        let target = Point2::new(tx, ty);
        let dist = start.distance_to(&target);
        if dist <= d {
            return Ok(straight(start, 0.0, SPACING).map_err(err)?);
        }
        let bearing = (ty - start.y).atan2(tx - start.x);
        let goal = Point2::new(tx - d * bearing.cos(), ty - d * bearing.sin());
        self.goto(start, goal, Some(bearing), false)
    }

    fn var_position(&self, var: u32) -> Result<(f64, f64), String> {
        let r = self.vars.get(var);
        if r.status < 1.0 {
            let name = self
                .module
                .global(VarId(var))
                .map_or("?", |g| g.name.as_str());
            return Err(format!("{name} holds no position yet"));
        }
        Ok((r.x, r.y))
    }

    fn relative(start: &Pose, x: f64, y: f64) -> Point2<f64> {
        start.to_world(&Point2::new(x, y))
    }

    /// Where an object of the model is seen now (camera detections).
    pub(crate) fn seen(&self, object: u32) -> Option<(f64, f64)> {
        let name = self.module.name(NameId(object));
        self.snap
            .detections
            .iter()
            .find(|o| o.object.eq_ignore_ascii_case(name))
            .map(|o| (o.x, o.y))
    }

    /// The arc of `turn(d=deg,c=c)`.
    pub(crate) fn turn_spec(&self, deg: f32, c: f32) -> Result<TurnSpec, Refusal> {
        let (deg, c) = (f64::from(deg), f64::from(c));
        if !(c.is_finite() && c != 0.0) {
            return Err("a turn needs a curvature other than 0".to_string().into());
        }
        // A curvature beyond the robot's is driven at the robot's: the
        // arc is longer, but it turns through `d`. Planned as given, the
        // controller's output is clipped (Figure 48) and the turn ended
        // where the path did, up to half the angle short on Workpartner
        // (maximum 0.25 1/m) at c = 1.
        Ok(TurnSpec::degrees(deg, c.abs().min(self.cfg.max_curvature)))
    }

    pub(crate) fn plan_spec(&self, spec: MoveSpec, start: Pose) -> Result<Planned, Refusal> {
        let dir = self.travel_direction();
        Ok(match spec {
            MoveSpec::Goahead { d } if d.is_nan() => Planned {
                path: straight(start, dir.sign() * ENDLESS_LEG, SPACING).map_err(err)?,
                mode: Mode::Endless,
                walled: false,
            },
            MoveSpec::Goahead { d } => {
                let d = f64::from(d);
                // A negative distance or a negative speed reverses: Figure 52
                // writes both (`speed(-0.4)` then `goahead(-0.7)`).
                let back = d < 0.0 || dir == Direction::Backward;
                let signed = if back { -d.abs() } else { d.abs() };
                Planned::path(straight(start, signed, SPACING).map_err(err)?)
            }
            MoveSpec::TurnExact { deg, c } => {
                let spec = self.turn_spec(deg, c)?;
                Planned::path(turn(start, &spec, dir, SPACING).map_err(err)?)
            }
            MoveSpec::TurnSide { left } => {
                let s = if left { Side::Left } else { Side::Right };
                if self.turn_has_room(&start, s) {
                    Planned::path(self.quarter_turn(start, s)?)
                } else {
                    let kept = self.wall_distance(&start, s);
                    let leg = self.wall_leg(start, WallSide::Side(s), kept)?;
                    Planned {
                        path: leg.path,
                        mode: Mode::TurnSide {
                            side: s,
                            distance: kept,
                        },
                        walled: leg.walled,
                    }
                }
            }
            MoveSpec::To { x, y, h, rel, r } => {
                let (x, y) = (f64::from(x), f64::from(y));
                let to = if rel {
                    Self::relative(&start, x, y)
                } else {
                    Point2::new(x, y)
                };
                let h = (!h.is_nan()).then(|| {
                    let h = f64::from(h).to_radians();
                    if rel { start.h + h } else { h }
                });
                Planned::path(self.goto(start, to, h, r)?)
            }
            MoveSpec::ToVar { var, rel, r } => {
                let (x, y) = self.var_position(var)?;
                let (to, h) = if rel {
                    (Self::relative(&start, x, y), start.h + self.vars.get(var).h)
                } else {
                    (Point2::new(x, y), self.vars.get(var).h)
                };
                // A position variable has a heading (Table 8): through a door
                // found by the scanner, or where the robot faced when it was
                // saved. Arriving with it lines the robot up with a door, as
                // Figures 20 and 58 need to turn on from there; where that
                // curve is too tight and `r` is not given, the robot arrives
                // facing the point instead.
                let path = match self.goto_lined_up(start, to, h, r) {
                    Ok(path) => path,
                    Err(_) => self.goto(start, to, None, r)?,
                };
                Planned::path(path)
            }
            MoveSpec::ApproachVar { var, d } => {
                let (x, y) = self.var_position(var)?;
                Planned::path(self.approach_point(start, x, y, f64::from(d))?)
            }
            MoveSpec::ApproachObject { object, d } => {
                let name = self.module.name(NameId(object));
                let (x, y) = self
                    .seen(object)
                    .ok_or_else(|| format!("no {name} in view"))?;
                Planned::path(self.approach_point(start, x, y, f64::from(d))?)
            }
            MoveSpec::FollowPath {
                name,
                reverse,
                backwards,
            } => Planned::path(self.follow_path(start, name, reverse, backwards)?),
            MoveSpec::FollowWall { mode, d } => {
                let d = if d.is_nan() {
                    self.cfg.followwall_d
                } else {
                    f64::from(d)
                };
                let side = match mode {
                    WallMode::Side(s) => WallSide::Side(s),
                    WallMode::Middle => WallSide::Middle,
                };
                let leg = self.wall_leg(start, side, d)?;
                Planned {
                    path: leg.path,
                    mode: Mode::Wall { side, distance: d },
                    walled: leg.walled,
                }
            }
            MoveSpec::FollowTarget { object, d } => {
                let d = f64::from(d);
                let (path, target) = match self.seen(object) {
                    Some((x, y)) => (self.approach_point(start, x, y, d)?, Some((x, y))),
                    None => (straight(start, 0.0, SPACING).map_err(err)?, None),
                };
                Planned {
                    path,
                    mode: Mode::Target {
                        object,
                        distance: d,
                        target,
                        since: 0.0,
                    },
                    walled: false,
                }
            }
        })
    }

    /// The room `turn(left|right)` needs: the robot's outline swept round
    /// its turning circle, and past the turn as far as the avoider's area
    /// reaches ahead of it (equations (11) and (12) from the front), so the
    /// turn is not begun only to be blocked at its end.
    pub(crate) fn turn_room(&self) -> TurnRoom {
        let front = self.cfg.front_offset;
        TurnRoom {
            curvature: self.cfg.turn_curvature,
            outline: Outline {
                front,
                rear: (self.cfg.robot_length - front).max(0.0),
                half_width: 0.5 * self.cfg.robot_width,
            },
            margin: TURN_MARGIN,
            lead_out: front + check_length(self.cfg.obstacle_curvature, self.motion.speed),
            lead_half_width: 0.5 * check_width(self.cfg.robot_width),
        }
    }

    /// Whether a quarter turn to `s` from `pose` has room.
    pub(crate) fn turn_has_room(&self, pose: &Pose, s: Side) -> bool {
        turn_space_free(pose, s, &self.turn_room(), self.motion.map.points())
    }

    /// `turn(left|right)` once there is room: a quarter circle at the
    /// configured curvature.
    pub(crate) fn quarter_turn(&self, start: Pose, s: Side) -> Result<Path, String> {
        let spec = TurnSpec::degrees(s.sign() * FRAC_PI_2.to_degrees(), self.cfg.turn_curvature);
        turn(start, &spec, self.travel_direction(), SPACING).map_err(err)
    }

    /// The distance to the wall on `side` now, or the model's `followwall_d`
    /// when no wall is seen there.
    fn wall_distance(&self, pose: &Pose, s: Side) -> f64 {
        fit_wall(pose, self.motion.map.points(), s, &WallParams::default())
            .map(|w| w.signed_distance(&pose.position()).abs())
            .unwrap_or(self.cfg.followwall_d)
    }

    /// One leg of wall following (section 4.5.3): project onto the fitted
    /// wall, take the point 3 m on at the distance, and plan a Bezier to it.
    /// Without a wall in the map the robot goes straight on and looks again.
    /// At a corridor's end the leg stops `TURN_MARGIN` short of the wall ahead
    /// (its front does), where the avoider, finding no way round the wall,
    /// would otherwise hold the robot with the leg still pointing into it.
    pub(crate) fn wall_leg(&self, pose: Pose, side: WallSide, d: f64) -> Result<Leg, String> {
        let path = self.wall_leg_whole(pose, side, d)?;
        let half = 0.5 * check_width(self.cfg.robot_width);
        let stop = self.cfg.front_offset + TURN_MARGIN;
        Ok(
            match leg_short_of_wall(&path, self.motion.map.points(), half, stop) {
                Some(path) => Leg { path, walled: true },
                None => Leg {
                    path,
                    walled: false,
                },
            },
        )
    }

    fn wall_leg_whole(&self, pose: Pose, side: WallSide, d: f64) -> Result<Path, String> {
        let pts = self.motion.map.points();
        let params = WallParams::default();
        let goal = match side {
            WallSide::Side(s) => fit_wall(&pose, pts, s, &params)
                .ok()
                .map(|w| followwall_goal(&pose, &w, s, d)),
            WallSide::Middle => match (
                fit_wall(&pose, pts, Side::Left, &params),
                fit_wall(&pose, pts, Side::Right, &params),
            ) {
                (Ok(l), Ok(r)) => Some(middle_goal(&pose, &l, &r)),
                _ => None,
            },
        };
        let dir = self.travel_direction();
        match goal.map(|g| self.bezier(pose, g, dir, false)) {
            Some(Ok(path)) => Ok(path),
            _ => straight(pose, dir.sign() * FOLLOWWALL_AHEAD, SPACING).map_err(err),
        }
    }

    fn follow_path(
        &self,
        start: Pose,
        name: u32,
        reverse: bool,
        backwards: bool,
    ) -> Result<Path, Refusal> {
        let key = self.module.name(NameId(name)).to_lowercase();
        let pts = self
            .paths
            .get(&key)
            .ok_or_else(|| format!("no path {key}"))?;
        let mut waypoints: Vec<Point2<f64>> = pts.iter().map(|&(x, y)| Point2::new(x, y)).collect();
        if backwards {
            waypoints.reverse();
        }
        let dir = if reverse {
            Direction::Backward
        } else {
            self.travel_direction()
        };
        let path = taught(&waypoints, self.cfg.max_curvature, dir, SPACING)
            .map_err(|e| format!("path {key}: {e}"))?;
        let first = path.start_pose();
        if start.distance_to(&first.position()) <= 0.05 {
            return Ok(path);
        }
        let joined = self
            .bezier(start, first, dir, false)
            .ok()
            .map(|lead| (lead, path.clone()))
            .or_else(|| self.join_later(start, &path, dir));
        let (lead, rest) = match joined {
            Some(j) => j,
            // Nowhere near reachable going on: reverse and turn to its start.
            None => (self.bezier(start, first, dir, true)?, path),
        };
        lead.concat(&rest, ilmr_motion::path::JOIN_TOLERANCE)
            .map_err(|e| Refusal::from(err(e)))
    }

    /// Joins `path` past its first point where a lead-in from `start` fits
    /// the robot's curvature: after a three-point turn at the end of a taught
    /// path (Figure 56's TURN1), the robot faces across the path and can only
    /// meet it a turning diameter or more along, as a driver would. The
    /// search looks no further than `JOIN_REACH` turning radii along the
    /// path. TURN1 reverses on full lock, which leaves the path exactly one
    /// turning radius ahead: no curve within the robot's curvature meets it
    /// going on, so the second pass lets the robot back up a little first
    /// (the `r` manoeuvre) at a few whole radii along.
    fn join_later(&self, start: Pose, path: &Path, dir: Direction) -> Option<(Path, Path)> {
        let radius = 1.0 / self.cfg.max_curvature;
        let reach = JOIN_REACH * radius;
        let step = (JOIN_STEP / SPACING).ceil().max(1.0) as usize;
        let pts = path.points();
        let going_on = pts
            .iter()
            .enumerate()
            .skip(1)
            .step_by(step)
            .take_while(|(_, p)| p.s <= reach)
            .find_map(|(k, p)| {
                let lead = self.bezier(start, p.pose(), dir, false).ok()?;
                Some((lead, path.tail_from(k)))
            });
        // The shortest lead-in of these wins: the nearest join may need the
        // longest reversing.
        going_on.or_else(|| {
            (2..=JOIN_REACH as usize)
                .filter_map(|n| {
                    let k = path.index_at_remaining(path.length() - n as f64 * radius);
                    (k > 0).then_some(())?;
                    let lead = self.bezier(start, pts[k].pose(), dir, true).ok()?;
                    Some((lead, path.tail_from(k)))
                })
                .min_by(|a, b| a.0.length().total_cmp(&b.0.length()))
        })
    }
}

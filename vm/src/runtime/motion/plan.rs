//! Reference paths for each movement command, built with ilmr-motion:
//! straights and arcs (`goahead`, `turn(d=..,c=..)`), Bezier curves to a
//! pose with the reverse-and-turn fallback of `r` (`gotoxy`, `gotorelxy`,
//! `turn(variable)`, `approach`), filleted polylines (`followpath`), and the
//! first leg of the behaviours (`followwall`, `turn(left|right)`,
//! `followtarget`).

use std::f64::consts::FRAC_PI_2;

use ilmr_hal::Hal;
use ilmr_motion::obstacle::check_length;
use ilmr_motion::path::{TurnSpec, polyline, straight, turn};
use ilmr_motion::wall::{
    FOLLOWWALL_AHEAD, WallParams, fit_wall, followwall_goal, middle_goal, turn_space_free,
};
use ilmr_motion::{Direction, Path, PlanParams, Pose, Side, plan_with};
use nalgebra::Point2;

use super::{Mode, WallSide};
use crate::bytecode::{NameId, VarId};
use crate::runtime::Vm;
use crate::runtime::clock::Clock;
use crate::runtime::nodes::{MoveSpec, WallMode};

/// Distance between the points of a reference path, m.
pub(crate) const SPACING: f64 = 0.05;
/// A `goahead` without a distance is planned this far and extended as it goes.
pub(crate) const ENDLESS_LEG: f64 = 30.0;
/// Clearance kept by `turn(left|right)` beyond half the checked width, m.
/// It absorbs the controller catching up with the quarter circle (tighter
/// than the path for a moment, so the avoider's area swings inside it) and
/// the map's 5 cm cells at a wall's corner; with 0.1 m the turn round the
/// end of Figure 58's lab bench began 1 cm too early and ended blocked.
pub(crate) const TURN_MARGIN: f64 = 0.25;
/// Recorded paths are thinned to waypoints at least this far apart, in turn,
/// until their corners fit the robot's curvature.
const THINNING: [f64; 5] = [0.0, 0.3, 0.6, 1.2, 2.5];

pub(crate) fn side(s: ilmr_hal::Side) -> Side {
    match s {
        ilmr_hal::Side::Left => Side::Left,
        ilmr_hal::Side::Right => Side::Right,
    }
}

fn err(e: impl std::fmt::Display) -> String {
    e.to_string()
}

/// The path and behaviour a movement starts with.
pub(crate) struct Planned {
    pub path: Path,
    pub mode: Mode,
}

impl Planned {
    fn path(path: Path) -> Planned {
        Planned {
            path,
            mode: Mode::Path,
        }
    }
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
    ) -> Result<Path, String> {
        plan_with(start, goal, &self.plan_params(direction, allow_reverse))
            .map_err(err)?
            .path()
            .map_err(err)
    }

    /// The body heading that faces (or, reversing, backs towards) `to`.
    fn facing(start: &Pose, to: &Point2<f64>, direction: Direction) -> f64 {
        let bearing = (to.y - start.y).atan2(to.x - start.x);
        match direction {
            Direction::Forward => bearing,
            Direction::Backward => bearing + std::f64::consts::PI,
        }
    }

    fn goto(&self, start: Pose, to: Point2<f64>, h: Option<f64>, r: bool) -> Result<Path, String> {
        let dir = self.travel_direction();
        let h = h.unwrap_or_else(|| Self::facing(&start, &to, dir));
        self.bezier(start, Pose::new(to.x, to.y, h), dir, r)
    }

    fn approach_point(&self, start: Pose, tx: f64, ty: f64, d: f64) -> Result<Path, String> {
        let target = Point2::new(tx, ty);
        let dist = start.distance_to(&target);
        if dist <= d {
            return straight(start, 0.0, SPACING).map_err(err);
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

    pub(crate) fn plan_spec(&self, spec: MoveSpec, start: Pose) -> Result<Planned, String> {
        let dir = self.travel_direction();
        Ok(match spec {
            MoveSpec::Goahead { d } if d.is_nan() => Planned {
                path: straight(start, dir.sign() * ENDLESS_LEG, SPACING).map_err(err)?,
                mode: Mode::Endless,
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
                let (deg, c) = (f64::from(deg), f64::from(c));
                if !(c.is_finite() && c != 0.0) {
                    return Err("a turn needs a curvature other than 0".into());
                }
                let spec = TurnSpec::degrees(deg, c.abs());
                Planned::path(turn(start, &spec, dir, SPACING).map_err(err)?)
            }
            MoveSpec::TurnSide { left } => {
                let s = if left { Side::Left } else { Side::Right };
                let c = self.cfg.turn_curvature;
                if turn_space_free(
                    &start,
                    s,
                    c,
                    self.cfg.robot_width,
                    TURN_MARGIN,
                    self.turn_lead_out(),
                    self.motion.map.points(),
                ) {
                    Planned::path(self.quarter_turn(start, s)?)
                } else {
                    let kept = self.wall_distance(&start, s);
                    Planned {
                        path: self.wall_leg(start, WallSide::Side(s), kept)?,
                        mode: Mode::TurnSide {
                            side: s,
                            distance: kept,
                        },
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
                let to = if rel {
                    Self::relative(&start, x, y)
                } else {
                    Point2::new(x, y)
                };
                Planned::path(self.goto(start, to, None, r)?)
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
                    WallMode::Side(s) => WallSide::Side(side(s)),
                    WallMode::Middle => WallSide::Middle,
                };
                Planned {
                    path: self.wall_leg(start, side, d)?,
                    mode: Mode::Wall { side, distance: d },
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
                }
            }
        })
    }

    /// How far past a `turn(left|right)` the way must be clear too: as far as
    /// the avoider's area reaches ahead of the robot (equation (11) from
    /// the front), so the turn is not begun only to be blocked at its end.
    pub(crate) fn turn_lead_out(&self) -> f64 {
        self.cfg.front_offset + check_length(self.cfg.obstacle_curvature, self.motion.speed)
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
    pub(crate) fn wall_leg(&self, pose: Pose, side: WallSide, d: f64) -> Result<Path, String> {
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
    ) -> Result<Path, String> {
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
        let mut last = None;
        let mut path = None;
        for gap in THINNING {
            let thinned = thin(&waypoints, gap);
            match polyline(&thinned, self.cfg.max_curvature, dir, SPACING) {
                Ok(p) => {
                    path = Some(p);
                    break;
                }
                Err(e) => last = Some(e),
            }
        }
        let path = match (path, last) {
            (Some(p), _) => p,
            (None, Some(e)) => return Err(format!("path {key}: {e}")),
            (None, None) => return Err(format!("path {key} is empty")),
        };
        // From where the robot stands to the path's first point.
        let first = path.start_pose();
        if start.distance_to(&first.position()) <= 0.05 {
            return Ok(path);
        }
        let lead = self.bezier(start, first, dir, true)?;
        lead.concat(&path, ilmr_motion::path::JOIN_TOLERANCE)
            .map_err(err)
    }
}

/// Waypoints at least `gap` apart, always keeping the first and the last.
fn thin(points: &[Point2<f64>], gap: f64) -> Vec<Point2<f64>> {
    let mut out: Vec<Point2<f64>> = Vec::with_capacity(points.len());
    for (i, p) in points.iter().enumerate() {
        let last = i + 1 == points.len();
        match out.last() {
            Some(q) if (p - q).norm() < gap && !last => {}
            Some(q) if last && (p - q).norm() < gap && out.len() > 1 => {
                let n = out.len();
                out[n - 1] = *p;
            }
            _ => out.push(*p),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::thin;
    use nalgebra::Point2;

    #[test]
    fn thinning_keeps_the_ends() {
        let pts: Vec<_> = (0..=10)
            .map(|i| Point2::new(f64::from(i) * 0.1, 0.0))
            .collect();
        let t = thin(&pts, 0.3);
        assert_eq!(t.first(), pts.first());
        assert_eq!(t.last(), pts.last());
        assert!(t.len() < pts.len());
        assert_eq!(thin(&pts, 0.0), pts);
    }
}

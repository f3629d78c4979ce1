//! The behaviours that re-plan their reference while they run: `followwall`
//! every 2 m, `turn(left|right)` until the turn fits, `followtarget` as the
//! target moves, and an endless `goahead` extended before it runs out.

use ilmr_hal::Hal;
use ilmr_motion::controller::has_arrived;
use ilmr_motion::path::straight;
use ilmr_motion::wall::FOLLOWWALL_REPLAN;
use ilmr_motion::{Path, Pose, Side};

use super::plan::{ENDLESS_LEG, SPACING};
use super::{Mode, WallSide};
use crate::runtime::Vm;
use crate::runtime::clock::Clock;

/// `followtarget` re-plans when the target has moved this far, m, or after
/// `TARGET_REPLAN_S` seconds.
const TARGET_MOVED: f64 = 0.3;
const TARGET_REPLAN_S: f64 = 1.0;
/// An endless `goahead` is extended when less than this remains, m.
const ENDLESS_MARGIN: f64 = 10.0;
/// A behaviour's leg has brought the robot to rest below this speed, m/s.
const STOOD_SPEED: f64 = 0.01;

fn side_name(s: Side) -> &'static str {
    match s {
        Side::Left => "left",
        Side::Right => "right",
    }
}

impl<H: Hal, C: Clock> Vm<H, C> {
    /// Re-plans the running behaviour's reference if it is due.
    pub(super) fn update_behaviour(&mut self, pose: Pose) -> Result<(), String> {
        let Some(run) = self.motion.run.as_ref() else {
            return Ok(());
        };
        let s = run.path.points()[run.path.clamp_index(run.k)].s;
        // Within a turning diameter of the end of a leg cut short of a wall
        // ahead: where the corner turn can begin.
        let near_wall =
            run.walled && run.path.remaining(run.k) <= 2.0 / self.cfg.turn_curvature.max(1e-9);
        // Standing at the end of a leg cut short of a wall ahead: no re-plan
        // moves the robot from there, so a turn that still has no room will
        // never have it, and the command is refused rather than left standing.
        let stuck = run.walled
            && self.motion.v <= STOOD_SPEED
            && has_arrived(
                &run.path,
                run.k,
                &pose,
                run.advance,
                self.cfg.goal_tolerance,
            );
        let next: Option<(Path, Mode, bool)> = match run.mode {
            Mode::Path => None,
            Mode::Endless => {
                if run.path.remaining(run.k) < ENDLESS_MARGIN {
                    let end = run.path.end_pose();
                    let dir = run.path.last().direction;
                    let more = straight(end, dir.sign() * ENDLESS_LEG, SPACING)
                        .map_err(|e| e.to_string())?;
                    let path = run
                        .path
                        .tail_from(run.k)
                        .concat(&more, ilmr_motion::path::JOIN_TOLERANCE)
                        .map_err(|e| e.to_string())?;
                    Some((path, Mode::Endless, false))
                } else {
                    None
                }
            }
            Mode::Wall {
                side: WallSide::Side(wall),
                ..
            } if near_wall => {
                // The corner at a corridor's end: the wall ahead is followed
                // on, round the corner away from the wall kept so far, as
                // soon as the turn has room; until then the leg goes on, and
                // at its end the robot stands short of the wall.
                let away = wall.opposite();
                if self.turn_has_room(&pose, away) {
                    Some((self.quarter_turn(pose, away)?, run.mode, false))
                } else if stuck {
                    return Err(format!(
                        "a wall ahead ends the wall on the {}, and there is no room to turn {} round the corner",
                        side_name(wall),
                        side_name(away)
                    ));
                } else {
                    None
                }
            }
            Mode::Wall {
                side: WallSide::Middle,
                ..
            } if stuck => return Err("a wall ahead ends the corridor".to_string()),
            // A corner turn is followed by a fresh leg as it ends.
            Mode::Wall { side, distance } => (s >= FOLLOWWALL_REPLAN
                || (!run.walled && run.path.remaining(run.k) < self.cfg.link_distance))
                .then(|| {
                    self.wall_leg(pose, side, distance)
                        .map(|leg| (leg.path, run.mode, leg.walled))
                })
                .transpose()?,
            Mode::TurnSide { side, distance } => {
                if self.turn_has_room(&pose, side) {
                    Some((self.quarter_turn(pose, side)?, Mode::Path, false))
                } else if stuck {
                    return Err(format!(
                        "no room to turn {} before the wall ahead",
                        side_name(side)
                    ));
                } else if s >= FOLLOWWALL_REPLAN {
                    let leg = self.wall_leg(pose, WallSide::Side(side), distance)?;
                    Some((leg.path, run.mode, leg.walled))
                } else {
                    None
                }
            }
            Mode::Target {
                object,
                distance,
                target,
                since,
            } => {
                let since = since + self.cfg.period;
                let seen = self.seen(object);
                let due = match (seen, target) {
                    (Some((x, y)), Some((tx, ty))) => {
                        (x - tx).hypot(y - ty) >= TARGET_MOVED || since >= TARGET_REPLAN_S
                    }
                    (Some(_), None) => true,
                    (None, _) => false,
                };
                match seen {
                    Some((x, y)) if due => {
                        let mode = Mode::Target {
                            object,
                            distance,
                            target: Some((x, y)),
                            since: 0.0,
                        };
                        // A target too close or too sharply placed for a
                        // Bezier is followed by the old path until it moves.
                        match self.approach_target(pose, x, y, distance) {
                            Ok(p) => Some((p, mode, false)),
                            Err(_) => {
                                self.set_mode(mode);
                                None
                            }
                        }
                    }
                    _ => {
                        self.set_mode(Mode::Target {
                            object,
                            distance,
                            target,
                            since,
                        });
                        None
                    }
                }
            }
        };
        if let (Some((path, mode, walled)), Some(run)) = (next, self.motion.run.as_mut()) {
            run.replan(path, &pose.position());
            run.mode = mode;
            run.walled = walled;
            if mode == Mode::Path {
                self.motion.goal = run.path.end_pose();
            }
            self.trace_reference();
        }
        Ok(())
    }

    fn set_mode(&mut self, mode: Mode) {
        if let Some(run) = self.motion.run.as_mut() {
            run.mode = mode;
        }
    }

    fn approach_target(&self, pose: Pose, x: f64, y: f64, d: f64) -> Result<Path, String> {
        let here = nalgebra::Point2::new(x, y);
        if pose.distance_to(&here) <= d {
            return straight(pose, 0.0, SPACING).map_err(|e| e.to_string());
        }
        let bearing = (y - pose.y).atan2(x - pose.x);
        let goal = Pose::new(x - d * bearing.cos(), y - d * bearing.sin(), bearing);
        self.bezier(pose, goal, self.travel_direction(), false)
            .map_err(|r| r.message)
    }
}

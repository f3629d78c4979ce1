//! The movement reservation (section 4.5.2): movement commands start one at a time in
//! issue order; the running one is stepped first in every tick so that control never
//! starves; a queued successor is joined to the running one near its end (linking).
//!
//! Paths, the controller, the speed profile, obstacle avoidance and wall following
//! are ilmr-motion's; this module keeps their state between ticks and feeds them the
//! robot's snapshot and the environmental map.

mod behave;
mod cells;
mod drive;
mod forget;
mod halt;
mod map;
mod plan;

use std::collections::VecDeque;

use ilmr_hal::Hal;
use ilmr_motion::controller::HeadingEnd;
use ilmr_motion::obstacle::{AreaParams, AvoidMode, AvoidParams, AvoidState, Avoider, SideParams};
use ilmr_motion::path::JOIN_TOLERANCE;
use ilmr_motion::{Direction, Path, Pose, Side};
use nalgebra::Point2;

use super::Vm;
use super::clock::Clock;
use super::config::{Config, TraceLevel};
use super::nodes::{Kind, MoveSpec, NodeRef};
use super::safety::Refusal;
use super::stmt_of;
use super::trace::{self, EventKind};
use super::vars::NONE;
use ilmr_stdlib::Command;
use map::EnvMap;

/// The wall `followwall` keeps to.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum WallSide {
    Side(Side),
    Middle,
}

/// What steers the reference path of the running movement.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Mode {
    /// A planned path that ends where the command is done.
    Path,
    /// `goahead` without a distance: extended as it goes, ended only by `break`.
    Endless,
    /// `followwall`: a leg re-planned every 2 m.
    Wall { side: WallSide, distance: f64 },
    /// `turn(left|right)` following the wall at `distance` until there is room.
    TurnSide { side: Side, distance: f64 },
    /// `followtarget`: re-planned as the target moves. `since`: seconds since
    /// the last re-plan.
    Target {
        object: u32,
        distance: f64,
        target: Option<(f64, f64)>,
        since: f64,
    },
}

/// The running movement's reference and progress.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Run {
    pub path: Path,
    /// Reference index, never decreasing (ilmr-motion's k).
    pub k: usize,
    /// Length of a linked predecessor's remainder at the path's start: this
    /// command's distance starts after it.
    pub offset: f64,
    /// Distance driven on legs that were replaced by re-planning.
    pub base: f64,
    /// `advancestop(d)` in force for this movement, m.
    pub advance: f64,
    pub mode: Mode,
    /// A behaviour's leg that ends short of a wall ahead: braked for.
    pub walled: bool,
    /// The avoider's path round an obstacle and its own index.
    pub detour: Option<(Path, usize)>,
    /// `turn(d=..,c=..)`: the heading it ends on, and whether its arc has
    /// been continued past the planned end (`path` then runs on beyond the
    /// turn's end, so nothing is linked to it).
    pub heading_end: Option<HeadingEnd>,
    pub overrun: bool,
}

impl Run {
    /// The command's `dist` with the robot at `at`: along the reference,
    /// after any joined remainder.
    pub fn dist(&self, at: &Point2<f64>) -> f64 {
        (self.base + self.along(at) - self.offset).max(0.0)
    }

    /// How far along the reference the robot at `at` has come, m.
    pub fn along(&self, at: &Point2<f64>) -> f64 {
        self.path.last().s - self.path.remaining_from(self.k, at)
    }

    /// The heading the running turn ends on, once its arc runs on past the
    /// planned end (it ends standing there, not linked).
    pub fn ending_heading(&self) -> Option<HeadingEnd> {
        self.heading_end.filter(|_| self.overrun)
    }

    /// Replaces the reference (a re-planned leg) with the robot at `at`,
    /// keeping the distance.
    pub fn replan(&mut self, path: Path, at: &Point2<f64>) {
        self.base = self.dist(at);
        self.offset = 0.0;
        self.path = path;
        self.k = 0;
    }

    /// The command has a fixed end.
    pub fn ends(&self) -> bool {
        self.mode == Mode::Path
    }

    /// A successor can be joined at the path's end.
    pub fn linkable(&self) -> bool {
        self.ends() && !self.overrun
    }
}

#[derive(Debug)]
pub(crate) struct Motion {
    pub queue: VecDeque<NodeRef>,
    pub head: Option<NodeRef>,
    run: Option<Run>,
    /// The remainder of a linked predecessor, joined before the next path.
    joined: Option<Path>,
    /// The running movement's goal pose (body heading).
    goal: Pose,
    pub last_goal: Option<Pose>,
    pub speed: f64,
    pub stopped: bool,
    pub use_goalpos: bool,
    pub advance_stop: Option<f64>,
    avoider: Avoider,
    /// The avoider's state as last traced.
    pub avoid_state: AvoidState,
    map: EnvMap,
    /// Speed magnitude and curvature commanded last tick: the controller's
    /// v and c_now.
    v: f64,
    c: f64,
    /// The direction of the speed commanded last tick (+1 or -1).
    sign: f64,
    /// Nothing is commanded: the robot was brought to rest (or never moved).
    /// With no movement holding the reservation and `idle` false, the halt ramp
    /// runs.
    idle: bool,
    /// The robot did not take the last setpoint (the call failed): at rest the
    /// VM keeps sending 0 until it does, or a drive that comes back would go on
    /// with the last speed it took.
    unsent: bool,
    /// The supervisor holds the running movement (as `stop` does).
    pub held: bool,
    /// The supervisor's speed limit, m/s.
    pub limit: Option<f64>,
    avoid_mode: AvoidMode,
}

fn avoid_params(cfg: &Config) -> AvoidParams {
    AvoidParams {
        area: AreaParams {
            max_curvature: cfg.obstacle_curvature,
            robot_width: cfg.robot_width,
            front_offset: cfg.front_offset,
        },
        side: SideParams {
            robot_width: cfg.robot_width,
            robot_length: cfg.robot_length,
            front_offset: cfg.front_offset,
            margin: 0.1,
            max_offset: 2.0,
        },
        security_wait: cfg.security_wait,
        spacing: plan::SPACING,
    }
}

impl Motion {
    pub fn new(cfg: &Config) -> Motion {
        Motion {
            queue: VecDeque::new(),
            head: None,
            run: None,
            joined: None,
            goal: Pose::default(),
            last_goal: None,
            speed: cfg.default_speed,
            stopped: false,
            use_goalpos: false,
            advance_stop: None,
            avoider: Avoider::new(AvoidMode::Off, avoid_params(cfg)),
            avoid_state: AvoidState::Normal,
            map: EnvMap::default(),
            v: 0.0,
            c: 0.0,
            sign: 1.0,
            idle: true,
            unsent: false,
            held: false,
            limit: None,
            avoid_mode: AvoidMode::Off,
        }
    }

    pub fn is_idle(&self) -> bool {
        self.idle
    }

    pub fn avoid_mode(&self) -> AvoidMode {
        self.avoid_mode
    }

    /// The direction of the speed commanded last, +1 or -1.
    pub fn last_sign(&self) -> f64 {
        self.sign
    }

    pub fn commanded_curvature(&self) -> f64 {
        if self.idle { 0.0 } else { self.c }
    }

    /// The running movement's reference and index.
    pub fn running_path(&self) -> Option<(&Path, usize)> {
        self.run.as_ref().map(|r| (&r.path, r.k))
    }

    /// The running movement's path where the command ends at its end (not a
    /// behaviour, which plans on), and the reference index.
    pub fn ending_path(&self) -> Option<(&Path, usize)> {
        self.run
            .as_ref()
            .filter(|r| r.ends())
            .map(|r| (&r.path, r.k))
    }

    /// The direction the running movement's reference goes at its index.
    pub fn running_direction(&self) -> Option<ilmr_motion::Direction> {
        self.running_path()
            .map(|(p, k)| p.points()[p.clamp_index(k)].direction)
    }

    /// The environmental map's points, world coordinates.
    pub fn map_points(&self) -> &[Point2<f64>] {
        self.map.points()
    }

    /// The environmental map, for queries near a place.
    pub fn map(&self) -> &map::EnvMap {
        &self.map
    }

    /// The speed magnitude commanded last tick, m/s.
    pub fn commanded_speed(&self) -> f64 {
        if self.idle { 0.0 } else { self.v }
    }

    /// `locate(..)` moved the robot's frame: the map's points are in the old one.
    pub fn relocated(&mut self) {
        self.map.clear();
    }

    /// `obsavoid(on|off|stop)`.
    pub fn set_obsavoid(&mut self, word: &str) -> Result<(), String> {
        let mode = [
            ("on", AvoidMode::On),
            ("off", AvoidMode::Off),
            ("stop", AvoidMode::Stop),
        ]
        .into_iter()
        .find(|(n, _)| n.eq_ignore_ascii_case(word))
        .map(|(_, m)| m)
        .ok_or_else(|| format!("obsavoid takes on, off or stop, not {word}"))?;
        self.avoider.set_mode(mode);
        self.avoid_mode = mode;
        Ok(())
    }
}

impl<H: Hal, C: Clock> Vm<H, C> {
    /// A movement command was issued: it starts now if the reservation is free.
    pub(super) fn queue_movement(&mut self, node: NodeRef) {
        self.motion.queue.push_back(node);
        if self.motion.head.is_none() {
            self.start_next_movement(false);
        }
    }

    /// The first queued movement that is still live and not being ended.
    fn first_queued(&self) -> Option<NodeRef> {
        self.motion
            .queue
            .iter()
            .copied()
            .find(|r| self.nodes.alive(*r) && !self.nodes.get(r.idx).dying)
    }

    /// Gives the reservation to the first queued movement that can plan a path.
    pub(super) fn start_next_movement(&mut self, linked: bool) {
        loop {
            let next = self.first_queued();
            let Some(next) = next else {
                // Nothing to drive: the halt ramp brings the robot to rest from the
                // next tick on (`halt.rs`), never a jump of the setpoint to 0.
                self.motion.joined = None;
                return;
            };
            self.motion.queue.retain(|r| *r != next);
            let planned = match self.check_movement_allowed() {
                Ok(()) => self.plan_movement(next.idx, linked),
                Err(refusal) => Err(refusal),
            };
            match planned {
                Ok(()) => {
                    self.motion.head = Some(next);
                    self.motion.idle = false;
                    let node = *self.nodes.get(next.idx);
                    self.push_event(stmt_of(node.stmt), EventKind::Start { iteration: None });
                    self.trace_reference();
                    if node.bind != NONE {
                        self.write_fields(
                            node.bind,
                            &[(ilmr_stdlib::Field::Dist, 0.0)],
                            None,
                            node.stmt,
                            true,
                        );
                    }
                    return;
                }
                Err(refusal) => self.end_refused(next.idx, refusal),
            }
        }
    }

    fn plan_movement(&mut self, idx: u32, linked: bool) -> Result<(), Refusal> {
        let Kind::Movement { spec, command } = self.nodes.get(idx).kind else {
            return Err(Refusal::from("not a movement".to_string()));
        };
        let current = self.snap.pose;
        let joined = if linked {
            self.motion.joined.take()
        } else {
            None
        };
        let start = match &joined {
            Some(j) => j.end_pose(),
            None if self.motion.use_goalpos => self.motion.last_goal.unwrap_or(current).wrapped(),
            None => current.wrapped(),
        };
        self.update_map();
        let planned = self.plan_spec(spec, start)?;
        if matches!(command, Command::GotoXY | Command::GotoRelXY) {
            let end = planned.path.end_pose();
            self.check_target(end.x, end.y)?;
        }
        // A reversing turn ends on its heading (section 4.1 on Figure 20's
        // `Turn(d=-90,c=1)`: "the parameters for command must be precise since
        // there is no scanner pointing backward"): the robot backs on blind
        // along the line it ends on. A forward turn ends where its arc does,
        // as Table 10's did: ended on the heading, Workpartner's forward
        // `turn(d=90,c=0.25)`, kept below full lock by the steering's play and
        // short of the heading at the arc's end point, drives on past it, and
        // Test 1's mean maximum deviation (fitted at +8 % of Table 10's) came
        // out +47 %.
        let heading_end = match spec {
            MoveSpec::TurnExact { deg, c } if self.travel_direction() == Direction::Backward => {
                self.turn_spec(deg, c).ok().and_then(|t| {
                    HeadingEnd::of_turn(start, &t, Direction::Backward, planned.path.length())
                })
            }
            _ => None,
        };
        let (path, offset) = match joined {
            Some(j) => match j.concat(&planned.path, JOIN_TOLERANCE) {
                Ok(p) => (p, j.length()),
                Err(_) => (planned.path, 0.0),
            },
            None => (planned.path, 0.0),
        };
        let heading_end = heading_end.map(|h| h.shifted(offset));
        if !linked && self.motion.idle {
            // Steer on from where the wheel stands. The speed starts from the
            // last setpoint (0 at rest), not from what the drive still rolls:
            // starting from a drive that lags its setpoint would step it.
            self.motion.v = 0.0;
            self.motion.c = self.snap.curvature;
        }
        // Otherwise the setpoint goes on from what was commanded last (a halt ramp
        // in progress), so that it never jumps.
        let advance = self.motion.advance_stop.take().unwrap_or(0.0).max(0.0);
        self.motion.goal = path.end_pose();
        self.motion.run = Some(Run {
            path,
            k: 0,
            offset,
            base: 0.0,
            advance,
            mode: planned.mode,
            walled: planned.walled,
            detour: None,
            heading_end,
            overrun: false,
        });
        Ok(())
    }

    /// Traces the running movement's reference path (a `path` event), for plots.
    pub(super) fn trace_reference(&mut self) {
        if self.cfg.trace != TraceLevel::Full {
            return;
        }
        let (Some(head), Some(run)) = (self.motion.head, self.motion.run.as_ref()) else {
            return;
        };
        let points: Vec<(f64, f64)> = run.path.points().iter().map(|p| (p.x, p.y)).collect();
        let points = trace::outline(&points, trace::OUTLINE_TOLERANCE);
        let stmt = self.nodes.get(head.idx).stmt;
        self.push_event(stmt_of(stmt), EventKind::Path { points });
    }

    /// Whether a queued movement can start from the end of `tail`, the running
    /// movement's remainder, before that one ends linked to it. Those that cannot
    /// plan a path from there are refused now, as `start_next_movement` would refuse
    /// them; when none is left, the running movement is not linked and drives to
    /// its end, rather than ending early with nothing to take over its remainder.
    pub(super) fn successor_starts_from(&mut self, tail: &Path) -> bool {
        loop {
            let next = self.first_queued();
            let Some(next) = next else {
                return false;
            };
            let Kind::Movement { spec, command } = self.nodes.get(next.idx).kind else {
                return true;
            };
            let planned = self.check_movement_allowed().and_then(|()| {
                let path = self.plan_spec(spec, tail.end_pose())?.path;
                if matches!(command, Command::GotoXY | Command::GotoRelXY) {
                    let end = path.end_pose();
                    self.check_target(end.x, end.y)?;
                }
                Ok(())
            });
            match planned {
                Ok(()) => return true,
                Err(refusal) => {
                    self.motion.queue.retain(|r| *r != next);
                    self.end_refused(next.idx, refusal);
                }
            }
        }
    }

    /// A successor is queued and nothing waits on the running movement's variable.
    fn can_link(&self, head: NodeRef) -> bool {
        let queued = self.first_queued().is_some();
        if !queued || !self.motion.run.as_ref().is_some_and(Run::linkable) {
            return false;
        }
        let bind = self.nodes.get(head.idx).bind;
        if bind == NONE {
            return true;
        }
        let mut waited = false;
        self.vars.for_each_subscriber(bind, |n| {
            if matches!(self.nodes.get(n).kind, Kind::WaitVar { .. }) {
                waited = true;
            }
        });
        !waited
    }

    /// Distance travelled and end pose of a movement that is ending (`None` for
    /// anything else).
    pub(super) fn movement_result(&self, idx: u32) -> Option<(f64, f64, f64, f64)> {
        if !matches!(self.nodes.get(idx).kind, Kind::Movement { .. }) {
            return None;
        }
        let p = self.snap.pose;
        let d = match (&self.motion.run, self.motion.head) {
            (Some(run), Some(h)) if h.idx == idx => run.dist(&p.position()),
            _ => 0.0,
        };
        Some((d, p.x, p.y, p.h))
    }

    /// Releases the reservation if `idx` held it; returns whether it did.
    pub(super) fn motion_node_ended(&mut self, idx: u32) -> bool {
        if self.motion.head.is_some_and(|h| h.idx == idx) {
            self.motion.head = None;
            let ended = self.motion.run.take();
            // A behaviour has no planned end: the next plan starts where it stopped.
            self.motion.last_goal = Some(match ended {
                Some(run) if run.ends() => self.motion.goal,
                _ => self.snap.pose,
            });
            return true;
        }
        if matches!(self.nodes.get(idx).kind, Kind::Movement { .. }) {
            self.motion.queue.retain(|r| r.idx != idx);
        }
        false
    }
}

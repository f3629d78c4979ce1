//! The movement reservation (section 4.5.2): movement commands start one at a time in
//! issue order; the running one is stepped first in every tick so that control never
//! starves; a queued successor is joined to the running one near its end (linking).

mod path;
mod track;

use std::collections::VecDeque;

use ilmr_hal::{Hal, Pose};

use super::Vm;
use super::clock::Clock;
use super::nodes::{Kind, MoveSpec, NodeRef};
use super::stmt_of;
use super::trace::EventKind;
use super::vars::{How, NONE};
use path::{Path, wrap};

#[derive(Debug, Default)]
pub(crate) struct Motion {
    pub queue: VecDeque<NodeRef>,
    pub head: Option<NodeRef>,
    path: Path,
    /// The remainder of a linked predecessor, joined before the next path.
    joined: Path,
    plan: Path,
    seg: usize,
    s: f64,
    /// Length of the joined remainder: the successor's distance starts after it.
    offset: f64,
    /// The running movement's goal pose (body heading).
    goal: Pose,
    pub last_goal: Option<Pose>,
    pub speed: f64,
    pub stopped: bool,
    pub use_goalpos: bool,
    pub advance_stop: Option<f64>,
    /// `on`, `off` or `stop`; recorded for the obstacle behaviour.
    pub obsavoid: String,
    idle: bool,
}

impl Motion {
    pub fn new(speed: f64) -> Motion {
        Motion {
            speed,
            idle: true,
            ..Motion::default()
        }
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

    /// Gives the reservation to the first queued movement that can plan a path.
    pub(super) fn start_next_movement(&mut self, linked: bool) {
        loop {
            let next = self
                .motion
                .queue
                .iter()
                .copied()
                .find(|r| self.nodes.alive(*r) && !self.nodes.get(r.idx).dying);
            let Some(next) = next else {
                if !self.motion.idle {
                    self.motion.idle = true;
                    if let Err(e) = self.hal.set_motion(0.0, 0.0) {
                        self.error(None, format!("stopping the robot failed: {e}"));
                    }
                }
                return;
            };
            self.motion.queue.retain(|r| *r != next);
            match self.plan_movement(next.idx, linked) {
                Ok(()) => {
                    self.motion.head = Some(next);
                    self.motion.idle = false;
                    let node = *self.nodes.get(next.idx);
                    self.push_event(stmt_of(node.stmt), EventKind::Start { iteration: None });
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
                Err(why) => self.end_node(next.idx, How::Refused, false, Some(why), true),
            }
        }
    }

    fn plan_movement(&mut self, idx: u32, linked: bool) -> Result<(), String> {
        let Kind::Movement { spec, .. } = self.nodes.get(idx).kind else {
            return Err("not a movement".into());
        };
        let current = self.snap.pose;
        let start = if linked {
            self.motion.goal
        } else if self.motion.use_goalpos {
            self.motion.last_goal.unwrap_or(current)
        } else {
            current
        };
        let dir = if self.motion.speed < 0.0 { -1.0 } else { 1.0 };
        let travel = |dir: f64| {
            if dir < 0.0 {
                wrap(start.h + std::f64::consts::PI)
            } else {
                start.h
            }
        };
        let mut plan = std::mem::take(&mut self.motion.plan);
        plan.reset(start.x, start.y, travel(dir), dir);
        let target = |vm: &Self, var: u32| -> Result<(f64, f64), String> {
            let r = vm.vars.get(var);
            if r.status < 1.0 {
                let name = vm
                    .module
                    .global(crate::bytecode::VarId(var))
                    .map_or("?", |g| g.name.as_str());
                return Err(format!("{name} holds no position yet"));
            }
            Ok((r.x, r.y))
        };
        let result = (|| -> Result<(), String> {
            match spec {
                MoveSpec::Goahead { d } => {
                    let d = if d.is_nan() {
                        f64::INFINITY
                    } else {
                        f64::from(d)
                    };
                    let eff = dir * d.signum();
                    plan.reset(start.x, start.y, travel(eff), eff);
                    plan.line(d.abs());
                }
                MoveSpec::TurnExact { deg, c } => {
                    let (deg, c) = (f64::from(deg), f64::from(c));
                    if c == 0.0 || !c.is_finite() {
                        return Err("a turn needs a curvature other than 0".into());
                    }
                    let rad = deg.to_radians();
                    plan.arc(rad.signum() * c.abs(), rad.abs() / c.abs());
                }
                MoveSpec::TurnSide { left } => {
                    let rad = if left { 90f64 } else { -90f64 }.to_radians();
                    let c = self.cfg.turn_curvature;
                    plan.arc(rad.signum() * c, rad.abs() / c);
                }
                MoveSpec::To { x, y, h, rel } => {
                    let (x, y) = (f64::from(x), f64::from(y));
                    let h = (!h.is_nan()).then_some(f64::from(h));
                    let (gx, gy) = if rel {
                        (
                            start.x + x * start.h.cos() - y * start.h.sin(),
                            start.y + x * start.h.sin() + y * start.h.cos(),
                        )
                    } else {
                        (x, y)
                    };
                    let gh = h.map(|h| {
                        let body = if rel {
                            start.h + h.to_radians()
                        } else {
                            h.to_radians()
                        };
                        if dir < 0.0 {
                            body + std::f64::consts::PI
                        } else {
                            body
                        }
                    });
                    goto(&mut plan, gx, gy, gh);
                }
                MoveSpec::ToVar { var, rel } => {
                    let (x, y) = target(self, var)?;
                    let (gx, gy) = if rel {
                        (
                            start.x + x * start.h.cos() - y * start.h.sin(),
                            start.y + x * start.h.sin() + y * start.h.cos(),
                        )
                    } else {
                        (x, y)
                    };
                    goto(&mut plan, gx, gy, None);
                }
                MoveSpec::ApproachVar { var, d } => {
                    let (x, y) = target(self, var)?;
                    approach(&mut plan, x, y, f64::from(d));
                }
                MoveSpec::ApproachObject { object, d } => {
                    let name = self.module.name(crate::bytecode::NameId(object));
                    let det = self
                        .snap
                        .detections
                        .iter()
                        .find(|o| o.object.eq_ignore_ascii_case(name))
                        .ok_or_else(|| format!("no {name} in view"))?;
                    approach(&mut plan, det.x, det.y, f64::from(d));
                }
                MoveSpec::FollowPath {
                    name,
                    reverse,
                    backwards,
                } => {
                    let key = self
                        .module
                        .name(crate::bytecode::NameId(name))
                        .to_lowercase();
                    let pts = self
                        .paths
                        .get(&key)
                        .ok_or_else(|| format!("no path {key}"))?;
                    let d = if reverse { -dir } else { dir };
                    plan.reset(start.x, start.y, travel(d), d);
                    let mut add = |&(x, y): &(f64, f64)| plan.line_to(x, y);
                    if backwards {
                        pts.iter().rev().for_each(&mut add);
                    } else {
                        pts.iter().for_each(&mut add);
                    }
                }
                MoveSpec::FollowWall => {
                    return Err(
                        "followwall needs the wall follower of ilmr-motion, not wired yet".into(),
                    );
                }
                MoveSpec::FollowTarget => {
                    return Err("followtarget needs target tracking, not available yet".into());
                }
            }
            Ok(())
        })();
        if let Err(e) = result {
            self.motion.plan = plan;
            return Err(e);
        }
        if let Some(by) = self.motion.advance_stop.take() {
            plan.trim_end(by);
        }
        let m = &mut self.motion;
        if linked && !m.joined.segs.is_empty() && m.joined.dir == plan.dir {
            std::mem::swap(&mut m.path, &mut m.joined);
            m.offset = m.path.total();
            m.path.extend(&plan);
        } else {
            std::mem::swap(&mut m.path, &mut plan);
            m.offset = 0.0;
        }
        m.joined.segs.clear();
        m.plan = plan;
        m.seg = 0;
        m.s = 0.0;
        let (x, y, th) = m.path.end();
        let h = if m.path.dir < 0.0 {
            wrap(th + std::f64::consts::PI)
        } else {
            wrap(th)
        };
        m.goal = Pose::new(x, y, h);
        Ok(())
    }

    /// Steps the running movement: setpoints, distance, arrival, linking.
    pub(super) fn step_motion(&mut self) {
        let Some(head) = self.motion.head else {
            return;
        };
        if !self.nodes.alive(head) {
            self.motion.head = None;
            return;
        }
        let brake = !self.can_link(head);
        let m = &mut self.motion;
        let ctl = track::control(
            &m.path,
            &mut m.seg,
            &mut m.s,
            self.snap.pose,
            m.speed,
            &self.cfg,
            brake,
        );
        let (v, c) = if self.motion.stopped {
            (0.0, ctl.curvature)
        } else {
            (ctl.speed, ctl.curvature)
        };
        if let Err(e) = self.hal.set_motion(v, c) {
            let stmt = stmt_of(self.nodes.get(head.idx).stmt);
            self.error(stmt, format!("setting speed and curvature failed: {e}"));
        }
        let node = *self.nodes.get(head.idx);
        if node.bind != NONE {
            let d = (self.motion.s - self.motion.offset).max(0.0);
            self.write_fields(
                node.bind,
                &[(ilmr_stdlib::Field::Dist, d)],
                None,
                node.stmt,
                true,
            );
        }
        if !ctl.remaining.is_finite() || self.motion.stopped {
            return;
        }
        if ctl.remaining <= self.cfg.goal_tolerance {
            self.end_node(head.idx, How::Completed, false, None, true);
        } else if !brake && ctl.remaining <= self.cfg.link_distance {
            let m = &mut self.motion;
            m.path.remainder_into(m.s, &mut m.joined);
            self.end_node(head.idx, How::Completed, true, None, true);
        }
    }

    /// A successor is queued and nothing waits on the running movement's variable.
    fn can_link(&self, head: NodeRef) -> bool {
        let queued = self
            .motion
            .queue
            .iter()
            .any(|r| self.nodes.alive(*r) && !self.nodes.get(r.idx).dying);
        if !queued || !self.motion.path.total().is_finite() {
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
        let d = if self.motion.head.is_some_and(|h| h.idx == idx) {
            (self.motion.s - self.motion.offset).max(0.0)
        } else {
            0.0
        };
        Some((d, p.x, p.y, p.h))
    }

    /// Releases the reservation if `idx` held it; returns whether it did.
    pub(super) fn motion_node_ended(&mut self, idx: u32) -> bool {
        if self.motion.head.is_some_and(|h| h.idx == idx) {
            self.motion.head = None;
            self.motion.last_goal = Some(self.motion.goal);
            return true;
        }
        if matches!(self.nodes.get(idx).kind, Kind::Movement { .. }) {
            self.motion.queue.retain(|r| r.idx != idx);
        }
        false
    }
}

fn goto(plan: &mut Path, gx: f64, gy: f64, gh: Option<f64>) {
    let (x0, y0, _) = plan.end();
    let h = gh.unwrap_or_else(|| (gy - y0).atan2(gx - x0));
    if (gx - x0).hypot(gy - y0) > 1e-6 {
        plan.bezier_to(gx, gy, h);
    }
}

fn approach(plan: &mut Path, tx: f64, ty: f64, d: f64) {
    let (x0, y0, _) = plan.end();
    let dist = (tx - x0).hypot(ty - y0);
    if dist <= d {
        return;
    }
    let h = (ty - y0).atan2(tx - x0);
    plan.bezier_to(tx - d * h.cos(), ty - d * h.sin(), h);
}

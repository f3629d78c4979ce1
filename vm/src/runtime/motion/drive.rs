//! One control cycle of the running movement: the environmental map, the
//! obstacle avoider (which suppresses the position controller while it
//! drives round an obstacle), the predictive curvature controller, the speed
//! profile, arrival and linking.

use ilmr_hal::{Hal, HalError};
use ilmr_motion::controller::{
    self, ControlInput, ControllerParams, SpeedLimits, has_arrived, link_distance, next_speed,
    stop_in,
};
use ilmr_motion::obstacle::Observation;
use ilmr_motion::{Path, Pose};

use crate::runtime::Vm;
use crate::runtime::clock::Clock;
use crate::runtime::stmt_of;
use crate::runtime::trace::EventKind;
use crate::runtime::vars::{How, NONE};

/// At a cusp of an `r` manoeuvre the robot has stopped when this close, m,
/// and this slow, m/s; the reference then moves on to the other direction.
const CUSP_REACHED: f64 = 0.03;
const CUSP_SPEED: f64 = 0.05;
/// A movement has arrived when at its end and commanded no faster than this, m/s.
const ARRIVED_SPEED: f64 = 0.05;

/// The first point after a cusp right at `k`, if the robot stands at one.
fn past_cusp(path: &Path, k: usize, pose: &Pose, v: f64) -> Option<usize> {
    let pts = path.points();
    let dir = pts.get(k)?.direction;
    if v > CUSP_SPEED || path.distance_to_stop_from(k, Some(&pose.position())) > CUSP_REACHED {
        return None;
    }
    pts.iter()
        .enumerate()
        .skip(k)
        .find(|(_, p)| p.direction != dir)
        .map(|(j, _)| j)
}

impl<H: Hal, C: Clock> Vm<H, C> {
    pub(super) fn controller_params(&self) -> ControllerParams {
        let base = ControllerParams::new(self.cfg.max_curvature, self.cfg.curinc, self.cfg.period);
        ControllerParams {
            min_lookahead: self.cfg.lookahead,
            max_lookahead: self.cfg.lookahead.max(3.0),
            min_lookahead_radii: match self.cfg.controller.lookahead_floor {
                true => base.min_lookahead_radii,
                false => 0.0,
            },
            ..base
        }
    }

    pub(super) fn speed_limits(&self) -> SpeedLimits {
        SpeedLimits {
            max_accel: self.cfg.acceleration,
            max_decel: self.cfg.deceleration,
        }
    }

    /// Takes a new scan into the environmental map.
    pub(in crate::runtime) fn update_map(&mut self) {
        let pose = self.snap.pose.wrapped();
        self.motion
            .map
            .update(self.snap.scan.as_ref(), &pose, self.cfg.scanner_offset);
    }

    /// Steps the running movement: setpoints, distance, arrival, linking.
    pub(in crate::runtime) fn step_motion(&mut self) {
        self.update_map();
        let Some(head) = self.motion.head else {
            self.ramp_down();
            return;
        };
        if !self.nodes.alive(head) || self.motion.run.is_none() {
            self.motion.head = None;
            self.ramp_down();
            return;
        }
        let pose = self.snap.pose.wrapped();
        if let Err(why) = self.update_behaviour(pose) {
            self.end_node(head.idx, How::Refused, false, Some(why), true);
            return;
        }
        let linkable = self.can_link(head);
        let params = self.controller_params();
        let limits = self.speed_limits();
        let dt = self.cfg.period;
        let target_speed = match self.motion.limit {
            Some(limit) => self.motion.speed.abs().min(limit),
            None => self.motion.speed.abs(),
        };
        // The supervisor's hold pauses the movement exactly as `stop` does.
        let stopped = self.motion.stopped || self.motion.held;
        let (v_now, c_now, last_sign) = (self.motion.v, self.motion.c, self.motion.sign);
        let c_fed_back = match self.cfg.controller.commanded_curvature {
            true => c_now,
            false => self.snap.curvature,
        };
        let super::Motion {
            run, avoider, map, ..
        } = &mut self.motion;
        let Some(run) = run.as_mut() else {
            return;
        };
        let here = pose.position();
        run.k = run.path.closest_index(&here, run.k, params.max_lookahead);
        if let Some(end) = run.heading_end.filter(|_| !run.overrun && !linkable) {
            // The last stretch of a turn that ends standing: from here the
            // heading says where it ends, and the arc goes on for a robot
            // that is still short of it at the planned end.
            let in_window = end.to_turn(&pose, run.along(&here)).is_some();
            if let Some(longer) = in_window
                .then(|| end.overrun(&run.path, super::plan::SPACING).ok())
                .flatten()
            {
                run.path = longer;
                run.overrun = true;
            }
        }
        if let Some(j) = past_cusp(&run.path, run.k, &pose, v_now) {
            run.k = j;
        }
        let direction = run.path.points()[run.path.clamp_index(run.k)].direction;

        let decision = avoider.step_indexed(
            &Observation {
                pose,
                direction,
                curvature: c_now,
                speed: v_now,
                reference: &run.path,
                k: run.k,
                points: map.points(),
                dt,
            },
            map.grid(),
        );
        let (halt, obs_control) = (decision.halt, decision.obs_control);
        let avoid_state = decision.state;
        match decision.detour {
            Some(d) if run.detour.as_ref().is_none_or(|(p, _)| p != d) => {
                run.detour = Some((d.clone(), 0));
            }
            Some(_) => {}
            None => run.detour = None,
        }

        let (path, k) = match (&run.detour, obs_control) {
            (Some((p, k)), true) => (p, *k),
            _ => (&run.path, run.k),
        };
        let out = controller::step(
            &params,
            &ControlInput {
                path,
                k,
                pose,
                curvature: c_fed_back,
                speed: direction.sign() * v_now,
            },
        );
        let out = match out {
            Ok(o) => o,
            Err(e) => {
                let why = format!("position control failed: {e}");
                self.end_node(head.idx, How::Refused, false, Some(why), true);
                return;
            }
        };
        let sign = path.points()[out.k].direction.sign();
        match (&mut run.detour, obs_control) {
            (Some((_, dk)), true) => *dk = out.k,
            _ => run.k = out.k,
        }

        let linked = linkable && run.ends();
        let (target, stop) = if halt || stopped {
            (0.0, None)
        } else {
            // Behaviours re-plan before their leg ends: never brake for it.
            let drive_through = linked || !(run.ends() || run.walled);
            let on_path = stop_in(&run.path, run.k, &pose, run.advance, drive_through);
            let on_heading = run
                .ending_heading()
                .and_then(|end| end.to_drive(&pose, run.along(&here)))
                .map(|d| (d - run.advance).max(0.0));
            let stop = match (on_path, on_heading) {
                (Some(a), Some(b)) => Some(a.min(b)),
                (a, b) => a.or(b),
            };
            (target_speed, stop)
        };
        // The braking curve towards a stop point falls a little faster than the
        // deceleration in its last steps (and wins over it for a late
        // `advancestop`); the setpoint never does: the robot cannot brake harder.
        let mut v = next_speed(v_now, target, stop, &limits, dt).max(v_now - limits.max_decel * dt);
        let mut sign = sign;
        let mut c = out.curvature;
        if sign != last_sign && v_now > 0.0 {
            // Still rolling the other way (a movement started during a halt ramp,
            // or the last few centimetres before a cusp): brake to rest first, at
            // most by the deceleration, along the old arc. Flipping the sign at
            // any speed above 0 would step the setpoint through zero.
            v = next_speed(v_now, 0.0, None, &limits, dt);
            sign = last_sign;
            c = c_now;
        }
        let dist = run.dist(&here);
        // A movement that nothing is linked to ends standing: the next one
        // starts from rest, as `wait(m)` between them asks.
        let tolerance = self.cfg.goal_tolerance;
        let arrived = run.ends()
            && !obs_control
            && v <= ARRIVED_SPEED
            && (has_arrived(&run.path, run.k, &pose, run.advance, tolerance)
                || run.ending_heading().is_some_and(|end| {
                    end.reached(&pose, run.along(&here), tolerance + run.advance)
                }));
        let near_end = linked
            && !obs_control
            && !stopped
            && run.path.remaining_from(run.k, &here)
                <= self.cfg.link_distance.max(link_distance(v, &limits, dt));
        let tail = near_end.then(|| run.path.tail_from(run.k));
        let link_now = match tail {
            Some(tail) if self.successor_starts_from(&tail) => {
                self.motion.joined = Some(tail);
                true
            }
            _ => false,
        };
        self.motion.v = v;
        self.motion.c = c;
        self.motion.sign = sign;
        if avoid_state != self.motion.avoid_state {
            self.motion.avoid_state = avoid_state;
            let stmt = stmt_of(self.nodes.get(head.idx).stmt);
            self.push_event(stmt, EventKind::Avoid { state: avoid_state });
        }

        let sent = self.hal.set_motion(sign * v, c);
        self.motion.unsent = sent.is_err();
        match sent {
            // A robot that refuses motion while the supervisor holds it says what the
            // hold already said (a ROS 2 base holding for the same stale scan): the
            // hold is told and counted, not an error of the task.
            Err(HalError::Refused(_)) if self.supervisor.holding() => {}
            Err(e) => {
                let stmt = stmt_of(self.nodes.get(head.idx).stmt);
                self.error(stmt, format!("setting speed and curvature failed: {e}"));
            }
            Ok(()) => {}
        }
        let node = *self.nodes.get(head.idx);
        if node.bind != NONE {
            self.write_fields(
                node.bind,
                &[(ilmr_stdlib::Field::Dist, dist)],
                None,
                node.stmt,
                true,
            );
        }
        if stopped {
            return;
        }
        if link_now {
            self.end_node(head.idx, How::Completed, true, None, true);
        } else if arrived {
            self.end_node(head.idx, How::Completed, false, None, true);
        }
    }
}

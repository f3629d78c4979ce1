//! The supervisor: checked every tick, right after the robot's snapshot, before the
//! movement is stepped. It watches what the HAL reports (stamps of scans, odometry
//! and navigation fixes, the battery, the pose, failing calls) and the environment
//! map, raises and clears [`Fault`]s with `fault`/`recovered` trace events, and
//! sets what the movement obeys (hold, lockout, speed limit). Its most urgent fault
//! is what `sensor(supervisor)` reads.

use ilmr_hal::{Hal, Pose};
use ilmr_motion::obstacle::{AreaParams, AvoidMode, CheckArea, on_the_way, route_turn};
use ilmr_motion::{Direction, controller::braking_distance};
use nalgebra::Point2;

use super::codes::{FAULTS, Fault, Reaction};
use super::{frame, sweep};
use crate::runtime::Vm;
use crate::runtime::activity::REST_SPEED;
use crate::runtime::clock::Clock;
use crate::runtime::trace::EventKind;

/// A battery must climb this far above `LowBattery` before `battery_low` clears, V,
/// so that a voltage sagging under load does not raise it over and over.
const BATTERY_HYSTERESIS: f64 = 0.1;
/// Reversing, the robot keeps this much further from the known map's walls than
/// from what its scanner saw: the error dead reckoning may have run up, m.
const REVERSE_CLEARANCE: f64 = 0.3;
/// Known-map points further than this (plus the braking distance) along either
/// axis are not looked at: the checked area is never longer, m.
const KNOWN_MAP_REACH: f64 = 4.0;
/// The way ahead must be this much longer than needed before `obstacle_near`
/// clears, m, so that a robot standing at the margin does not flicker.
const OBSTACLE_HYSTERESIS: f64 = 0.1;

/// The stamps of one stream of samples. A stream is watched once its stamp has
/// advanced: a robot says what it has by reporting it, and a stamp that never
/// moved (a test's fixed scan) is a constant, not a stream that stopped.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
struct Stream {
    last: Option<f64>,
    live: bool,
}

impl Stream {
    /// Takes this tick's stamp; returns how old the latest sample is, once live.
    fn age(&mut self, stamp: Option<f64>, now: f64) -> Option<f64> {
        if let Some(s) = stamp.filter(|s| s.is_finite()) {
            match self.last {
                Some(l) if s > l + 1e-9 => {
                    self.live = true;
                    self.last = Some(s);
                }
                Some(_) => {}
                None => self.last = Some(s),
            }
        }
        self.last.filter(|_| self.live).map(|l| now - l)
    }
}

#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct Supervisor {
    active: [bool; FAULTS.len()],
    scan: Stream,
    odometry: Stream,
    nav: Stream,
    last_pose: Option<Pose>,
    /// `locate` moved the frame: the next pose is not compared with the last.
    pub relocated: bool,
    /// An update or snapshot call failed this tick.
    pub link_failed: bool,
    scratch: Scratch,
}

/// Buffers of the obstacle checks, kept between ticks so that a steady tick
/// does not allocate for them.
#[derive(Debug, Clone, Default, PartialEq)]
struct Scratch {
    /// Indices of candidate points.
    near: Vec<usize>,
    /// Known-map points near the robot, in the estimate's frame, with their
    /// indices.
    known: Vec<(usize, Point2<f64>)>,
    /// Hits of the checked area: (index, distance along it).
    hits: Vec<(usize, f64)>,
}

/// The nearest of `hits`, folded in index order as a scan of every point
/// would: a minimum over 0.0 and -0.0 depends on the order.
fn nearest(hits: &mut [(usize, f64)]) -> f64 {
    hits.sort_unstable_by_key(|h| h.0);
    hits.iter().map(|h| h.1).fold(f64::INFINITY, f64::min)
}

fn slot(f: Fault) -> usize {
    (f.number() - 1) as usize
}

impl Supervisor {
    pub fn is_active(&self, f: Fault) -> bool {
        self.active[slot(f)]
    }

    /// The fault that locks movement, if one is active.
    pub fn locking(&self) -> Option<Fault> {
        FAULTS
            .into_iter()
            .find(|f| f.reaction() == Reaction::Lockout && self.is_active(*f))
    }

    /// The running movement must stand still.
    pub fn holding(&self) -> bool {
        FAULTS.into_iter().any(|f| {
            self.is_active(f) && matches!(f.reaction(), Reaction::Hold | Reaction::Lockout)
        })
    }

    pub fn slowing(&self) -> bool {
        FAULTS
            .into_iter()
            .any(|f| self.is_active(f) && f.reaction() == Reaction::SlowDown)
    }

    /// What `sensor(supervisor)` reads: the most urgent active fault's number, 0
    /// when there is none.
    pub fn reading(&self) -> f64 {
        FAULTS
            .into_iter()
            .filter(|f| self.is_active(*f))
            .max_by_key(|f| f.urgency())
            .map_or(0.0, |f| f64::from(f.number()))
    }
}

impl<H: Hal, C: Clock> Vm<H, C> {
    /// One round of checks; see `docs/reliability.md` for each threshold and
    /// reaction.
    pub(in crate::runtime) fn supervise(&mut self) {
        let now = self.time();
        let s = self.cfg.safety;
        let link = std::mem::take(&mut self.supervisor.link_failed);
        self.set_fault(Fault::RobotLink, link, || {
            "the robot did not answer update or snapshot".into()
        });

        let scan_t = self.snap.scan.as_ref().map(|sc| sc.t);
        let age = self.supervisor.scan.age(scan_t, now);
        self.stream_check(Fault::ScannerLost, age, s.scanner_timeout, "scan");
        let age = self.supervisor.odometry.age(self.snap.odometry_t, now);
        self.stream_check(
            Fault::OdometryLost,
            age,
            s.odometry_timeout,
            "odometry sample",
        );
        let age = self.supervisor.nav.age(self.snap.nav_t, now);
        self.stream_check(Fault::NavLost, age, s.nav_timeout, "navigation fix");

        if let (Some(low), Some(v)) = (s.low_battery, self.snap.device("battery")) {
            let was = self.supervisor.is_active(Fault::BatteryLow);
            let low_now = v < low || (was && v < low + BATTERY_HYSTERESIS);
            self.set_fault(Fault::BatteryLow, low_now, || {
                format!("battery {v:.2} V is below LowBattery {low} V")
            });
        }

        self.check_jump();
        self.check_obstacle();
        if self.supervisor.is_active(Fault::LocalizationJump) && self.at_rest() {
            self.set_fault(Fault::LocalizationJump, false, String::new);
        }
        self.motion.held = self.supervisor.holding();
        self.motion.limit = self.supervisor.slowing().then_some(s.degraded_speed);
    }

    fn at_rest(&self) -> bool {
        self.snap.speed.abs() < REST_SPEED && self.motion.commanded_speed() < REST_SPEED
    }

    fn stream_check(&mut self, f: Fault, age: Option<f64>, timeout: Option<f64>, what: &str) {
        let Some(timeout) = timeout else {
            return;
        };
        let stale = age.is_some_and(|a| a > timeout);
        self.set_fault(f, stale, || {
            format!(
                "no {what} for {:.2} s ({}_timeout {timeout} s)",
                age.unwrap_or(0.0),
                f.name().trim_end_matches("_lost")
            )
        });
    }

    /// The estimate moved or turned further in one tick than the robot can drive
    /// and than `localization_jump`/`localization_jump_h` allow.
    fn check_jump(&mut self) {
        let pose = self.snap.pose;
        let last = self.supervisor.last_pose.replace(pose);
        if std::mem::take(&mut self.supervisor.relocated) {
            return;
        }
        let Some(last) = last else {
            return;
        };
        let s = self.cfg.safety;
        let v = self.snap.speed.abs().max(self.motion.commanded_speed());
        let dt = self.cfg.period;
        let moved = (pose.x - last.x).hypot(pose.y - last.y);
        let turned = ilmr_motion::pose::angle_diff(pose.h, last.h).abs();
        let can_turn = self.cfg.max_curvature * v * dt;
        let jumped = moved > v * dt + s.localization_jump
            || turned > can_turn + s.localization_jump_h
            || !(pose.x.is_finite() && pose.y.is_finite() && pose.h.is_finite());
        if !jumped {
            return;
        }
        let message = format!(
            "the pose estimate moved {moved:.2} m and turned {:.1} deg in one tick",
            turned.to_degrees()
        );
        if !self.supervisor.is_active(Fault::LocalizationJump) {
            let m = message.clone();
            self.set_fault(Fault::LocalizationJump, true, || m);
        }
        // The map's points and the running path are in the frame that jumped.
        self.motion.relocated();
        self.end_movement_for(Fault::LocalizationJump, message);
    }

    /// With obstacle avoidance off, or driving backwards (where the scanner does
    /// not look and the avoider cannot help), an obstacle in the checked area
    /// (equations (11)-(12), bent along the curvature and the route) nearer than
    /// the braking distance plus `stop_margin`. Obstacles are the mapped scan
    /// points and, where the robot has a site plan, the known map's walls.
    fn check_obstacle(&mut self) {
        let mut scratch = std::mem::take(&mut self.supervisor.scratch);
        self.check_obstacle_with(&mut scratch);
        self.supervisor.scratch = scratch;
    }

    fn check_obstacle_with(&mut self, scratch: &mut Scratch) {
        let Some(margin) = self.cfg.safety.stop_margin else {
            return;
        };
        let moving = !self.motion.is_idle();
        let direction = self
            .motion
            .running_direction()
            .unwrap_or(Direction::of(self.motion.last_sign()));
        let blind = direction == Direction::Backward;
        // With no movement running the robot is only coming to rest after
        // one ended: a hold would stop it no sooner, and what its last
        // curvature, kept while it slows, points at is no way it will go.
        let stopping = self.motion.running_path().is_none();
        if !moving || stopping {
            self.set_fault(Fault::ObstacleNear, false, String::new);
            return;
        }
        let v = self.snap.speed.abs().max(self.motion.commanded_speed());
        let decel = self.cfg.deceleration;
        let was = self.supervisor.is_active(Fault::ObstacleNear);
        let needed = if was {
            braking_distance(self.motion.speed.abs(), decel) + margin + OBSTACLE_HYSTERESIS
        } else {
            braking_distance(v, decel) + margin
        };
        // A movement that ends at its path's end drives no further than the
        // rest of it and its braking: what the commanded arc would meet beyond
        // that is not in its way. At the end of a quarter turn the robot still
        // steers at full curvature, and the arc swept on would cut into what it
        // turned past (the end of the office's lab bench after `goahead(1)`,
        // `turn(left)` from (8, 5)).
        let here = Point2::new(self.snap.pose.x, self.snap.pose.y);
        let needed = match self.motion.ending_path() {
            Some((path, k)) => {
                needed.min(path.remaining_from(k, &here) + braking_distance(v, decel))
            }
            None => needed,
        };
        let distance = needed.max(braking_distance(v, decel) + margin);
        let swept = self.swept_contact(direction, distance, scratch);
        if self.motion.avoid_mode() != AvoidMode::Off && !blind {
            // The avoider steers round what it sees; the sweep catches it failing.
            self.set_fault(Fault::ObstacleNear, swept < needed, || {
                format!(
                    "the robot would touch an obstacle after {swept:.2} m, inside the stopping distance {needed:.2} m"
                )
            });
            return;
        }
        let pose = self.snap.pose.wrapped();
        let c = self.motion.commanded_curvature();
        let params = AreaParams {
            max_curvature: self.cfg.max_curvature,
            robot_width: self.cfg.robot_width,
            front_offset: match direction {
                Direction::Forward => self.cfg.front_offset,
                Direction::Backward => (self.cfg.robot_length - self.cfg.front_offset).max(0.0),
            },
        };
        let travel = match direction {
            Direction::Forward => pose,
            Direction::Backward => pose.flipped(),
        };
        let turn = self
            .motion
            .running_path()
            .map_or(f64::INFINITY, |(path, k)| {
                route_turn(path, k, &travel, direction.sign() * c, 3.0)
            });
        let (scanned, planned) =
            self.area_obstacles(&pose, direction, c, v, turn, &params, scratch);
        let nearest = scanned.min(planned).min(swept);
        self.set_fault(Fault::ObstacleNear, nearest < needed, || {
            format!(
                "an obstacle {nearest:.2} m ahead is inside the stopping distance {needed:.2} m"
            )
        });
    }

    /// The nearest scanned and known-map obstacles in the checked area of a
    /// robot at `pose` moving in `direction` at curvature `c` and speed `v`,
    /// bent no further than `turn`.
    #[allow(clippy::too_many_arguments)]
    fn area_obstacles(
        &self,
        pose: &ilmr_motion::Pose,
        direction: Direction,
        c: f64,
        v: f64,
        turn: f64,
        params: &AreaParams,
        scratch: &mut Scratch,
    ) -> (f64, f64) {
        let area = CheckArea::turning_at_most(pose, direction, c, v, params, turn);
        // What the area finds off the route it bends away from is not in the way.
        let (route, reach) = (
            self.motion.running_path(),
            area.length() + params.front_offset,
        );
        let half = 0.5 * area.width;
        let on_route = |p: &Point2<f64>| {
            route.is_none_or(|(path, k)| on_the_way(path, k, pose, p, reach, half))
        };
        // Only the points near the area: the same hits as over every point.
        let tester = area.tester();
        let region = tester.bounds();
        let map = self.motion.map();
        map.near(&region, &mut scratch.near);
        let points = map.points();
        scratch.hits.clear();
        scratch.hits.extend(
            scratch
                .near
                .iter()
                .filter_map(|&i| tester.hit(i, &points[i]))
                .filter(|h| on_route(&points[h.index]))
                .map(|h| (h.index, h.s)),
        );
        let scanned = nearest(&mut scratch.hits);
        let reach = KNOWN_MAP_REACH + v * v / (2.0 * self.cfg.deceleration.max(1e-6));
        let here = frame::to_map(self.map_from_estimate, (self.snap.pose.x, self.snap.pose.y));
        self.known.near(
            self.map_from_estimate,
            here,
            reach,
            &region,
            &mut scratch.near,
            &mut scratch.known,
        );
        scratch.hits.clear();
        scratch.hits.extend(
            scratch
                .known
                .iter()
                .filter(|(_, p)| on_route(p))
                .filter_map(|(i, p)| tester.hit(*i, p))
                .map(|h| (h.index, h.s)),
        );
        let planned = nearest(&mut scratch.hits);
        (scanned, planned)
    }

    /// How far the robot can drive along its commanded arc, up to `distance`,
    /// before its outline meets a mapped point (or, reversing, a wall of the
    /// known map); infinity when it meets none.
    fn swept_contact(&self, direction: Direction, distance: f64, scratch: &mut Scratch) -> f64 {
        let footprint = sweep::Footprint {
            front: self.cfg.front_offset,
            rear: (self.cfg.robot_length - self.cfg.front_offset).max(0.0),
            half_width: 0.5 * self.cfg.robot_width,
        };
        let p = self.snap.pose;
        let sign = direction.sign();
        let c = self.motion.commanded_curvature();
        // Over a positive distance the first contact is a minimum over points
        // of travels that are never 0, whatever order the points come in;
        // otherwise they go in index order, as a scan of every point would.
        let in_order = distance.is_nan() || distance <= 0.0;
        let ahead = footprint.sweep((p.x, p.y, p.h), sign, c, distance);
        let map = self.motion.map();
        map.near(&ahead.bounds(), &mut scratch.near);
        if in_order {
            scratch.near.sort_unstable();
        }
        let points = map.points();
        let scanned = ahead.first_contact(scratch.near.iter().map(|&i| points[i]));
        if direction != Direction::Backward || self.known.is_empty() {
            return scanned;
        }
        let here = frame::to_map(self.map_from_estimate, (p.x, p.y));
        let reach = KNOWN_MAP_REACH + distance;
        let clear = footprint.sweep((p.x, p.y, p.h), sign, c, distance + REVERSE_CLEARANCE);
        self.known.near(
            self.map_from_estimate,
            here,
            reach,
            &clear.bounds(),
            &mut scratch.near,
            &mut scratch.known,
        );
        if in_order {
            scratch.known.sort_unstable_by_key(|k| k.0);
        }
        // The walls are placed by the pose estimate, which dead reckoning may
        // have carried off (a biased odometer); nothing behind the robot can
        // correct it, so it keeps this much further from them.
        let planned =
            clear.first_contact(scratch.known.iter().map(|(_, p)| *p)) - REVERSE_CLEARANCE;
        scanned.min(planned.max(0.0))
    }

    /// Raises or clears a fault, tracing the change and applying a raise's one-off
    /// reaction.
    /// `message` is only made when the fault is raised: a steady tick does not
    /// allocate.
    pub(in crate::runtime) fn set_fault(
        &mut self,
        f: Fault,
        on: bool,
        message: impl FnOnce() -> String,
    ) {
        let i = slot(f);
        if self.supervisor.active[i] == on {
            return;
        }
        self.supervisor.active[i] = on;
        if !on {
            self.push_event(None, EventKind::Recovered { fault: f });
            return;
        }
        let message = message();
        if f.reaction() == Reaction::Lockout {
            self.push_event(
                None,
                EventKind::Fault {
                    fault: f,
                    message: message.clone(),
                },
            );
            self.end_movement_for(f, message);
        } else {
            self.push_event(None, EventKind::Fault { fault: f, message });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_stream_is_watched_once_its_stamp_moves() {
        let mut s = Stream::default();
        assert_eq!(s.age(Some(0.0), 5.0), None, "one sample is not a stream");
        assert_eq!(s.age(Some(0.0), 6.0), None);
        assert_eq!(s.age(Some(6.5), 7.0), Some(0.5));
        assert_eq!(s.age(None, 9.0), Some(2.5), "gone: as old as the last");
        assert_eq!(s.age(Some(f64::NAN), 9.5), Some(3.0));
    }

    #[test]
    fn the_reading_is_the_most_urgent_active_fault() {
        let mut s = Supervisor::default();
        assert_eq!(s.reading(), 0.0);
        s.active[slot(Fault::BatteryLow)] = true;
        s.active[slot(Fault::ScannerLost)] = true;
        assert_eq!(s.reading(), 2.0);
        assert!(s.holding() && s.locking().is_none());
        s.active[slot(Fault::OdometryLost)] = true;
        assert_eq!(s.reading(), 3.0);
        assert_eq!(s.locking(), Some(Fault::OdometryLost));
    }
}

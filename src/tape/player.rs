//! A robot made of recorded inputs.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, OnceLock};

use ilmr_hal::{AsyncOp, BodyPose, Hal, HalError, KnownMap, OpId, OpStatus, Pose, Scan, Snapshot};
use ilmr_trace::{Exchange, Input, Num, OpState, PlacedScan};

use super::{at, describe, known_map, op_status, operation, play_snapshot, pose, result};
use crate::run::backend::{Robot, WorldScan};

/// How a replay went, read by whoever replays once the run is over (the player itself
/// is then inside the VM).
#[derive(Debug, Default)]
pub struct Played {
    /// The first point where the replay's calls differ from the recording's.
    divergence: OnceLock<Divergence>,
    /// Ticks the replay ran through.
    ticks: AtomicUsize,
    /// The replay wanted a tick past the last one recorded.
    ran_out: AtomicBool,
}

impl Played {
    pub fn divergence(&self) -> Option<&Divergence> {
        self.divergence.get()
    }

    pub fn ticks(&self) -> usize {
        self.ticks.load(Ordering::Relaxed)
    }

    pub fn ran_out(&self) -> bool {
        self.ran_out.load(Ordering::Relaxed)
    }
}

/// The first point where the replayed VM did not do what the recorded one did.
#[derive(Debug, Clone, PartialEq)]
pub struct Divergence {
    /// The tick (from 0) whose calls differ, and its time.
    pub tick: usize,
    pub t: f64,
    /// The call the recording has there; `None` when the replay made a call past the
    /// end of the tick's recorded calls.
    pub recorded: Option<Exchange>,
    /// The call the replay made; `None` when it made fewer calls than the recording.
    pub replayed: Option<Exchange>,
}

impl Divergence {
    pub fn describe(&self) -> String {
        let at = format!("t = {} s (tick {})", ilmr_trace::fmt_num(self.t), self.tick);
        match (&self.recorded, &self.replayed) {
            (Some(r), Some(p)) => format!(
                "at {at} the recorded run called {}, the replay calls {}",
                describe(r),
                describe(p)
            ),
            (Some(r), None) => format!(
                "at {at} the recorded run called {}, the replay makes no more calls in that tick",
                describe(r)
            ),
            (None, Some(p)) => format!(
                "at {at} the replay calls {}, which the recorded run did not",
                describe(p)
            ),
            (None, None) => format!("at {at}"),
        }
    }
}

/// Answers the VM from a recording, tick by tick. A call that matches the next
/// recorded one (same call, same arguments, bit for bit) gets the recorded answer.
/// One that does not is the [`Divergence`] (only the first is kept); it then gets the
/// answer of the tick's next recorded call of its kind, or a plain one (accepted; an
/// operation the recording never started fails), so that the replay goes on with what
/// the robot sensed.
pub struct Player {
    ticks: Vec<Input>,
    /// The tick being answered.
    tick: usize,
    /// The next recorded call of that tick.
    cursor: usize,
    /// The run ended the tick: the next call starts the next one.
    ended: bool,
    last_scan: Option<Scan>,
    played: Arc<Played>,
    /// Time of the tick being answered, for the divergence.
    t: f64,
}

impl Player {
    /// The player of `ticks`, and where it will say how the replay went.
    pub fn new(ticks: Vec<Input>) -> (Player, Arc<Played>) {
        let played = Arc::new(Played::default());
        let player = Player {
            ticks,
            tick: 0,
            cursor: 0,
            ended: false,
            last_scan: None,
            played: Arc::clone(&played),
            t: 0.0,
        };
        (player, played)
    }

    fn calls(&self) -> &[Exchange] {
        self.ticks.get(self.tick).map_or(&[], |i| &i.calls)
    }

    fn diverge(&mut self, recorded: Option<Exchange>, replayed: Option<Exchange>) {
        let _ = self.played.divergence.set(Divergence {
            tick: self.tick,
            t: self.t,
            recorded,
            replayed,
        });
    }

    /// The recorded exchange that answers `made`; `None` when the tick has none of
    /// its kind left.
    fn answer(&mut self, made: Exchange) -> Option<Exchange> {
        if self.ended {
            self.ended = false;
            self.tick += 1;
            self.cursor = 0;
        }
        if let Exchange::Update { t, .. } = &made {
            self.t = t.0;
        }
        let next = self.calls().get(self.cursor).cloned();
        if next.as_ref().is_some_and(|r| same_call(r, &made)) {
            self.cursor += 1;
            return next;
        }
        self.diverge(next, Some(made.clone()));
        let found = self.calls()[self.cursor.min(self.calls().len())..]
            .iter()
            .position(|r| r.name() == made.name());
        found.map(|i| {
            self.cursor += i + 1;
            self.calls()[self.cursor - 1].clone()
        })
    }

    fn seen(&self) -> Option<&ilmr_trace::Seen> {
        self.ticks.get(self.tick).map(|i| &i.robot)
    }

    fn world_scan(&self, s: &PlacedScan) -> WorldScan {
        let ranges = match &s.ranges {
            Some(r) => r.iter().map(|x| x.0).collect(),
            None => self
                .last_scan
                .as_ref()
                .map(|l| l.ranges.clone())
                .unwrap_or_default(),
        };
        WorldScan {
            t: s.t.0,
            origin: pose(&s.origin),
            angle_min: s.angle_min.0,
            angle_step: s.angle_step.0,
            max_range: s.max_range.0,
            ranges,
        }
    }
}

/// Whether two exchanges are the same call with the same arguments (their answers
/// aside).
fn same_call(a: &Exchange, b: &Exchange) -> bool {
    use Exchange as E;
    match (a, b) {
        (E::Update { t: x, .. }, E::Update { t: y, .. }) => x == y,
        (E::Snapshot { .. }, E::Snapshot { .. }) | (E::KnownMap { .. }, E::KnownMap { .. }) => true,
        (
            E::SetMotion {
                speed: s1,
                curvature: c1,
                ..
            },
            E::SetMotion {
                speed: s2,
                curvature: c2,
                ..
            },
        ) => s1 == s2 && c1 == c2,
        (
            E::Actuator {
                id: i1, value: v1, ..
            },
            E::Actuator {
                id: i2, value: v2, ..
            },
        ) => i1 == i2 && v1 == v2,
        (E::Locmode { mode: m1, .. }, E::Locmode { mode: m2, .. }) => m1 == m2,
        (
            E::Bodypose {
                roll: r1,
                pitch: p1,
                clearance: c1,
                ..
            },
            E::Bodypose {
                roll: r2,
                pitch: p2,
                clearance: c2,
                ..
            },
        ) => r1 == r2 && p1 == p2 && c1 == c2,
        (E::Locate { pose: p1, .. }, E::Locate { pose: p2, .. }) => p1 == p2,
        (E::Start { op: o1, .. }, E::Start { op: o2, .. }) => o1 == o2,
        (E::Poll { id: i1, .. }, E::Poll { id: i2, .. })
        | (E::Cancel { id: i1, .. }, E::Cancel { id: i2, .. }) => i1 == i2,
        (E::ActuatorRange { id: i1, .. }, E::ActuatorRange { id: i2, .. }) => i1 == i2,
        _ => false,
    }
}

/// The answer of a call the recording has no answer for.
fn unrecorded(what: &str) -> HalError {
    HalError::Refused(format!("{what}: not in the recording"))
}

impl Hal for Player {
    fn update(&mut self, t: f64) -> Result<(), HalError> {
        match self.answer(Exchange::Update {
            t: Num(t),
            error: None,
        }) {
            Some(Exchange::Update { error, .. }) => result(&error, ()),
            _ => Ok(()),
        }
    }

    fn snapshot(&mut self, out: &mut Snapshot) -> Result<(), HalError> {
        let made = Exchange::Snapshot {
            snapshot: Box::new(super::record_snapshot(out, &mut None)),
            error: None,
        };
        match self.answer(made) {
            Some(Exchange::Snapshot { snapshot, error }) => {
                play_snapshot(&snapshot, out, &mut self.last_scan);
                result(&error, ())
            }
            // Past the recording the robot keeps its last state.
            _ => Ok(()),
        }
    }

    fn set_motion(&mut self, speed: f64, curvature: f64) -> Result<(), HalError> {
        match self.answer(Exchange::SetMotion {
            speed: Num(speed),
            curvature: Num(curvature),
            error: None,
        }) {
            Some(Exchange::SetMotion { error, .. }) => result(&error, ()),
            _ => Ok(()),
        }
    }

    fn actuator(&mut self, id: &str, value: f64) -> Result<(), HalError> {
        match self.answer(Exchange::Actuator {
            id: id.to_string(),
            value: Num(value),
            error: None,
        }) {
            Some(Exchange::Actuator { error, .. }) => result(&error, ()),
            _ => Ok(()),
        }
    }

    fn locmode(&mut self, mode: &str) -> Result<(), HalError> {
        match self.answer(Exchange::Locmode {
            mode: mode.to_string(),
            error: None,
        }) {
            Some(Exchange::Locmode { error, .. }) => result(&error, ()),
            _ => Ok(()),
        }
    }

    fn bodypose(&mut self, p: BodyPose) -> Result<(), HalError> {
        match self.answer(Exchange::Bodypose {
            roll: p.roll.map(Num),
            pitch: p.pitch.map(Num),
            clearance: p.clearance.map(Num),
            error: None,
        }) {
            Some(Exchange::Bodypose { error, .. }) => result(&error, ()),
            _ => Ok(()),
        }
    }

    fn locate(&mut self, p: Pose) -> Result<(), HalError> {
        match self.answer(Exchange::Locate {
            pose: at(p),
            error: None,
        }) {
            Some(Exchange::Locate { error, .. }) => result(&error, ()),
            _ => Ok(()),
        }
    }

    fn start(&mut self, op: &AsyncOp) -> Result<OpId, HalError> {
        let made = Exchange::Start {
            op: operation(op),
            id: None,
            error: None,
        };
        let what = describe(&made);
        match self.answer(made) {
            Some(Exchange::Start { id, error, .. }) => {
                result(&error, ())?;
                id.map(OpId).ok_or_else(|| unrecorded(&what))
            }
            _ => Err(unrecorded(&what)),
        }
    }

    fn poll(&mut self, op: OpId) -> Result<OpStatus, HalError> {
        match self.answer(Exchange::Poll {
            id: op.0,
            status: None,
            error: None,
        }) {
            Some(Exchange::Poll { status, error, .. }) => {
                result(&error, ())?;
                Ok(op_status(&status.unwrap_or(OpState::Pending)))
            }
            _ => Err(HalError::UnknownOp(op)),
        }
    }

    fn cancel(&mut self, op: OpId) -> Result<(), HalError> {
        match self.answer(Exchange::Cancel {
            id: op.0,
            error: None,
        }) {
            Some(Exchange::Cancel { error, .. }) => result(&error, ()),
            _ => Ok(()),
        }
    }

    fn known_map(&mut self) -> Option<KnownMap> {
        match self.answer(Exchange::KnownMap { map: None }) {
            Some(Exchange::KnownMap { map }) => map.as_ref().map(known_map),
            _ => None,
        }
    }

    fn actuator_range(&mut self, id: &str) -> Option<(f64, f64)> {
        match self.answer(Exchange::ActuatorRange {
            id: id.to_string(),
            range: None,
        }) {
            Some(Exchange::ActuatorRange { range, .. }) => range.map(|(a, b)| (a.0, b.0)),
            _ => None,
        }
    }
}

impl Robot for Player {
    fn at_rest(&self) -> bool {
        self.seen().is_none_or(|s| s.at_rest)
    }

    fn true_pose(&self) -> Option<Pose> {
        self.seen()?.true_pose.as_ref().map(pose)
    }

    fn true_motion(&self) -> Option<(f64, f64)> {
        self.seen()?.motion.map(|(v, c)| (v.0, c.0))
    }

    fn new_scan(&mut self) -> Option<WorldScan> {
        let placed = self.seen()?.scan.clone()?;
        Some(self.world_scan(&placed))
    }

    fn contacts(&self) -> u64 {
        self.seen().map_or(0, |s| s.contacts)
    }

    fn end_tick(&mut self) -> Option<Input> {
        if let Some(missed) = self.calls().get(self.cursor).cloned() {
            self.diverge(Some(missed), None);
        }
        self.ended = true;
        self.played.ticks.store(self.tick + 1, Ordering::Relaxed);
        None
    }

    fn inputs_exhausted(&self) -> bool {
        let out = self.ended && self.tick + 1 >= self.ticks.len();
        if out {
            self.played.ran_out.store(true, Ordering::Relaxed);
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::run::backend::NoRobot;
    use crate::tape::Taping;

    /// One tick of a robot without a world that the VM asked to move: `update`,
    /// `snapshot`, `set_motion` (refused) and the run's look at it.
    fn recorded() -> Vec<Input> {
        let mut taping = Taping::new(NoRobot);
        let mut snap = Snapshot::default();
        taping.update(0.0).ok();
        taping.snapshot(&mut snap).ok();
        assert!(taping.set_motion(0.3, 0.0).is_err());
        vec![
            taping
                .end_tick()
                .expect("a taping robot hands its tick over"),
        ]
    }

    #[test]
    fn the_same_calls_get_the_recorded_answers() {
        let (mut player, played) = Player::new(recorded());
        let mut snap = Snapshot::default();
        assert_eq!(player.update(0.0), Ok(()));
        assert_eq!(player.snapshot(&mut snap), Ok(()));
        let refused = player.set_motion(0.3, 0.0).unwrap_err();
        assert!(refused.to_string().contains("--robot none"), "{refused}");
        player.end_tick();
        assert!(played.divergence().is_none());
        assert_eq!(played.ticks(), 1);
        assert!(player.inputs_exhausted() && played.ran_out());
    }

    #[test]
    fn a_call_with_other_arguments_is_the_divergence_and_gets_its_kinds_answer() {
        let (mut player, played) = Player::new(recorded());
        player.update(0.0).ok();
        player.snapshot(&mut Snapshot::default()).ok();
        assert!(player.set_motion(0.2, 0.0).is_err(), "the recorded answer");
        let d = played.divergence().expect("a divergence");
        assert_eq!((d.tick, d.t), (0, 0.0));
        let said = d.describe();
        assert!(
            said.contains("the recorded run called set_motion(speed 0.3, curvature 0), the replay calls set_motion(speed 0.2, curvature 0)"),
            "{said}"
        );
    }

    /// A replay that makes fewer calls than the recording in the last tick still
    /// parts from it: nothing comes after to notice.
    #[test]
    fn a_call_left_out_of_the_last_tick_is_a_divergence() {
        let (mut player, played) = Player::new(recorded());
        player.update(0.0).ok();
        player.snapshot(&mut Snapshot::default()).ok();
        player.end_tick();
        let d = played.divergence().expect("a divergence");
        assert!(
            d.describe()
                .contains("the replay makes no more calls in that tick"),
            "{}",
            d.describe()
        );
    }

    #[test]
    fn an_operation_the_recording_never_started_fails() {
        let (mut player, _) = Player::new(recorded());
        player.update(0.0).ok();
        let e = player.start(&AsyncOp::MoveMode("crab".into())).unwrap_err();
        assert!(e.to_string().contains("not in the recording"), "{e}");
    }
}

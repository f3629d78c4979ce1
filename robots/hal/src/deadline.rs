//! [`Deadline`]: a robot driver on its own thread, every call given a deadline, so
//! that a driver that hangs cannot hold up the VM's tick (issue 7: the VM survives
//! the robot).
//!
//! While a call is overdue the driver is busy with it; later calls are not queued
//! behind it (a stale `set_motion` arriving seconds late would be worse than none)
//! but fail at once with [`HalError::Timeout`] until the overdue call returns. Its
//! late answer is dropped. A driver that never returns keeps its thread; the VM goes
//! on without it.

use std::sync::mpsc::{Receiver, RecvTimeoutError, Sender, TryRecvError, channel};
use std::thread;
use std::time::{Duration, Instant};

use crate::hal::Hal;
use crate::types::{AsyncOp, BodyPose, HalError, KnownMap, OpId, OpStatus, Pose, Snapshot};

enum Request {
    Update(f64),
    /// The buffer to fill, handed over and back so that a steady run does not
    /// allocate.
    Snapshot(Box<Snapshot>),
    SetMotion(f64, f64),
    Actuator(String, f64),
    LocMode(String),
    BodyPose(BodyPose),
    Locate(Pose),
    Start(AsyncOp),
    Poll(OpId),
    Cancel(OpId),
    KnownMap,
    ActuatorRange(String),
}

impl Request {
    fn name(&self) -> &'static str {
        match self {
            Request::Update(_) => "update",
            Request::Snapshot(_) => "snapshot",
            Request::SetMotion(..) => "set_motion",
            Request::Actuator(..) => "actuator",
            Request::LocMode(_) => "locmode",
            Request::BodyPose(_) => "bodypose",
            Request::Locate(_) => "locate",
            Request::Start(_) => "start",
            Request::Poll(_) => "poll",
            Request::Cancel(_) => "cancel",
            Request::KnownMap => "known_map",
            Request::ActuatorRange(_) => "actuator_range",
        }
    }
}

enum Reply {
    Done(Result<(), HalError>),
    Snapshot(Box<Snapshot>, Result<(), HalError>),
    Started(Result<OpId, HalError>),
    Polled(Result<OpStatus, HalError>),
    Map(Option<KnownMap>),
    Range(Option<(f64, f64)>),
}

fn serve<H: Hal>(mut driver: H, requests: Receiver<(u64, Request)>, replies: Sender<(u64, Reply)>) {
    while let Ok((seq, request)) = requests.recv() {
        let reply = match request {
            Request::Update(t) => Reply::Done(driver.update(t)),
            Request::Snapshot(mut buf) => {
                let r = driver.snapshot(&mut buf);
                Reply::Snapshot(buf, r)
            }
            Request::SetMotion(v, c) => Reply::Done(driver.set_motion(v, c)),
            Request::Actuator(id, value) => Reply::Done(driver.actuator(&id, value)),
            Request::LocMode(mode) => Reply::Done(driver.locmode(&mode)),
            Request::BodyPose(pose) => Reply::Done(driver.bodypose(pose)),
            Request::Locate(pose) => Reply::Done(driver.locate(pose)),
            Request::Start(op) => Reply::Started(driver.start(&op)),
            Request::Poll(op) => Reply::Polled(driver.poll(op)),
            Request::Cancel(op) => Reply::Done(driver.cancel(op)),
            Request::KnownMap => Reply::Map(driver.known_map()),
            Request::ActuatorRange(id) => Reply::Range(driver.actuator_range(&id)),
        };
        if replies.send((seq, reply)).is_err() {
            return;
        }
    }
}

/// A [`Hal`] that forwards every call to a driver running on its own thread and
/// waits at most `deadline` for each answer.
pub struct Deadline {
    requests: Sender<(u64, Request)>,
    replies: Receiver<(u64, Reply)>,
    deadline: Duration,
    seq: u64,
    /// The overdue call the driver is still in: its sequence number and name.
    busy: Option<(u64, &'static str)>,
    /// A snapshot buffer to hand to the driver; `out`'s old buffer comes back here.
    spare: Box<Snapshot>,
}

impl Deadline {
    /// Moves `driver` to a new thread. Each call waits at most `deadline`.
    pub fn spawn<H: Hal + Send + 'static>(driver: H, deadline: Duration) -> Deadline {
        let (requests, inbox) = channel();
        let (outbox, replies) = channel();
        // The thread ends when this handle is dropped (its channel closes), or never
        // if the driver hangs for good: it is not joined.
        thread::spawn(move || serve(driver, inbox, outbox));
        Deadline {
            requests,
            replies,
            deadline,
            seq: 0,
            busy: None,
            spare: Box::default(),
        }
    }

    /// The name of the call the driver has not answered in time, while it is in it.
    pub fn overdue(&mut self) -> Option<&'static str> {
        self.drain();
        self.busy.map(|(_, name)| name)
    }

    /// Takes late answers; the overdue call's frees the driver.
    fn drain(&mut self) {
        loop {
            match self.replies.try_recv() {
                Ok((seq, reply)) => self.late(seq, reply),
                Err(TryRecvError::Empty | TryRecvError::Disconnected) => return,
            }
        }
    }

    fn late(&mut self, seq: u64, reply: Reply) {
        if self.busy.is_some_and(|(s, _)| s == seq) {
            self.busy = None;
        }
        if let Reply::Snapshot(buf, _) = reply {
            self.spare = buf;
        }
    }

    fn call(&mut self, request: Request) -> Result<Reply, HalError> {
        self.drain();
        if let Some((_, name)) = self.busy {
            return Err(HalError::Timeout(format!(
                "the robot driver is still in an overdue {name} call"
            )));
        }
        self.seq += 1;
        let seq = self.seq;
        let name = request.name();
        if self.requests.send((seq, request)).is_err() {
            return Err(HalError::Link("the robot driver has stopped".into()));
        }
        let due = Instant::now() + self.deadline;
        loop {
            let left = due.saturating_duration_since(Instant::now());
            match self.replies.recv_timeout(left) {
                Ok((s, reply)) if s == seq => return Ok(reply),
                Ok((s, reply)) => self.late(s, reply),
                Err(RecvTimeoutError::Timeout) => {
                    self.busy = Some((seq, name));
                    return Err(HalError::Timeout(format!(
                        "{name} took longer than {} ms",
                        self.deadline.as_millis()
                    )));
                }
                Err(RecvTimeoutError::Disconnected) => {
                    return Err(HalError::Link("the robot driver has stopped".into()));
                }
            }
        }
    }

    fn done(&mut self, request: Request) -> Result<(), HalError> {
        match self.call(request)? {
            Reply::Done(r) => r,
            _ => Err(HalError::Link(
                "the robot driver answered another call".into(),
            )),
        }
    }
}

impl Hal for Deadline {
    fn update(&mut self, t: f64) -> Result<(), HalError> {
        self.done(Request::Update(t))
    }

    fn snapshot(&mut self, out: &mut Snapshot) -> Result<(), HalError> {
        let mut buf = std::mem::take(&mut self.spare);
        buf.as_mut().clone_from(out);
        match self.call(Request::Snapshot(buf))? {
            Reply::Snapshot(mut filled, r) => {
                if r.is_ok() {
                    std::mem::swap(out, &mut filled);
                }
                self.spare = filled;
                r
            }
            _ => Err(HalError::Link(
                "the robot driver answered another call".into(),
            )),
        }
    }

    fn set_motion(&mut self, speed: f64, curvature: f64) -> Result<(), HalError> {
        self.done(Request::SetMotion(speed, curvature))
    }

    fn actuator(&mut self, id: &str, value: f64) -> Result<(), HalError> {
        self.done(Request::Actuator(id.to_string(), value))
    }

    fn locmode(&mut self, mode: &str) -> Result<(), HalError> {
        self.done(Request::LocMode(mode.to_string()))
    }

    fn bodypose(&mut self, pose: BodyPose) -> Result<(), HalError> {
        self.done(Request::BodyPose(pose))
    }

    fn locate(&mut self, pose: Pose) -> Result<(), HalError> {
        self.done(Request::Locate(pose))
    }

    fn start(&mut self, op: &AsyncOp) -> Result<OpId, HalError> {
        match self.call(Request::Start(op.clone()))? {
            Reply::Started(r) => r,
            _ => Err(HalError::Link(
                "the robot driver answered another call".into(),
            )),
        }
    }

    fn poll(&mut self, op: OpId) -> Result<OpStatus, HalError> {
        match self.call(Request::Poll(op))? {
            Reply::Polled(r) => r,
            _ => Err(HalError::Link(
                "the robot driver answered another call".into(),
            )),
        }
    }

    fn cancel(&mut self, op: OpId) -> Result<(), HalError> {
        self.done(Request::Cancel(op))
    }

    fn known_map(&mut self) -> Option<KnownMap> {
        match self.call(Request::KnownMap) {
            Ok(Reply::Map(m)) => m,
            _ => None,
        }
    }

    fn actuator_range(&mut self, id: &str) -> Option<(f64, f64)> {
        match self.call(Request::ActuatorRange(id.to_string())) {
            Ok(Reply::Range(r)) => r,
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Limits, ScriptedRobot};
    use std::sync::Arc;
    use std::sync::atomic::{AtomicU64, Ordering};

    /// A driver whose `snapshot` blocks while `hold_ms` is non-zero (sleeping that
    /// long, once) or forever (`u64::MAX`).
    struct Sticky {
        inner: ScriptedRobot,
        hold_ms: Arc<AtomicU64>,
    }

    impl Hal for Sticky {
        fn update(&mut self, t: f64) -> Result<(), HalError> {
            self.inner.update(t)
        }
        fn snapshot(&mut self, out: &mut Snapshot) -> Result<(), HalError> {
            match self.hold_ms.swap(0, Ordering::SeqCst) {
                0 => {}
                u64::MAX => loop {
                    thread::park();
                },
                ms => thread::sleep(Duration::from_millis(ms)),
            }
            self.inner.snapshot(out)
        }
        fn set_motion(&mut self, v: f64, c: f64) -> Result<(), HalError> {
            self.inner.set_motion(v, c)
        }
        fn actuator(&mut self, id: &str, value: f64) -> Result<(), HalError> {
            self.inner.actuator(id, value)
        }
        fn locmode(&mut self, mode: &str) -> Result<(), HalError> {
            self.inner.locmode(mode)
        }
        fn bodypose(&mut self, pose: BodyPose) -> Result<(), HalError> {
            self.inner.bodypose(pose)
        }
        fn locate(&mut self, pose: Pose) -> Result<(), HalError> {
            self.inner.locate(pose)
        }
        fn start(&mut self, op: &AsyncOp) -> Result<OpId, HalError> {
            self.inner.start(op)
        }
        fn poll(&mut self, op: OpId) -> Result<OpStatus, HalError> {
            self.inner.poll(op)
        }
    }

    fn sticky(hold_ms: u64) -> (Deadline, Arc<AtomicU64>) {
        let hold = Arc::new(AtomicU64::new(hold_ms));
        let driver = Sticky {
            inner: ScriptedRobot::new(Limits::default()).battery(0.0, 24.0),
            hold_ms: Arc::clone(&hold),
        };
        (Deadline::spawn(driver, Duration::from_millis(50)), hold)
    }

    #[test]
    fn calls_pass_through_when_the_driver_answers() {
        let (mut hal, _) = sticky(0);
        let mut snap = Snapshot::default();
        hal.update(0.01).expect("update");
        hal.snapshot(&mut snap).expect("snapshot");
        assert_eq!(snap.battery, Some(24.0));
        assert!((snap.t - 0.01).abs() < 1e-12);
        assert!(
            hal.set_motion(f64::NAN, 0.0).is_err(),
            "the driver's own error"
        );
        assert_eq!(hal.overdue(), None);
    }

    #[test]
    fn a_driver_that_blocks_forever_costs_one_deadline_then_fails_fast() {
        let (mut hal, _) = sticky(u64::MAX);
        let mut snap = Snapshot::default();
        hal.update(0.01).expect("update");
        snap.t = 7.0;
        let started = Instant::now();
        let err = hal.snapshot(&mut snap).expect_err("hangs");
        assert!(matches!(err, HalError::Timeout(_)), "{err}");
        assert!(started.elapsed() < Duration::from_secs(2));
        assert_eq!(snap.t, 7.0, "a failed snapshot leaves the old data");
        let started = Instant::now();
        for _ in 0..100 {
            assert!(matches!(hal.update(0.02), Err(HalError::Timeout(_))));
        }
        assert!(
            started.elapsed() < Duration::from_millis(50),
            "later calls do not wait for the hung driver"
        );
        assert_eq!(hal.overdue(), Some("snapshot"));
    }

    #[test]
    fn a_driver_that_comes_back_is_used_again_and_its_late_answer_dropped() {
        let (mut hal, _) = sticky(150);
        let mut snap = Snapshot::default();
        hal.update(0.01).expect("update");
        assert!(matches!(hal.snapshot(&mut snap), Err(HalError::Timeout(_))));
        let until = Instant::now() + Duration::from_secs(5);
        while hal.overdue().is_some() && Instant::now() < until {
            thread::sleep(Duration::from_millis(10));
        }
        assert_eq!(hal.overdue(), None, "the slow call returned");
        hal.update(0.02).expect("answers again");
        hal.snapshot(&mut snap).expect("answers again");
        assert!(
            (snap.t - 0.02).abs() < 1e-12,
            "this call's data, not the late one's"
        );
    }
}

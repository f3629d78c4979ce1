//! A robot that writes down what passes between it and the VM.

use ilmr_hal::{AsyncOp, BodyPose, Hal, HalError, KnownMap, OpId, OpStatus, Pose, Scan, Snapshot};
use ilmr_trace::{Exchange, Input, Num, PlacedScan, Seen};

use super::{at, error_of, map, nums, op_state, operation, record_snapshot};
use crate::run::backend::{Robot, WorldScan};

/// `inner`, with every HAL call and its answer kept until the tick ends
/// ([`Robot::end_tick`] hands them over as one `input` line).
pub struct Taping<R> {
    inner: R,
    calls: Vec<Exchange>,
    /// The last scan written in a snapshot: a snapshot that holds it again says so
    /// rather than repeating it.
    last_scan: Option<Scan>,
    /// The scan the run took this tick ([`Robot::new_scan`]).
    placed: Option<WorldScan>,
}

impl<R: Robot> Taping<R> {
    pub fn new(inner: R) -> Taping<R> {
        Taping {
            inner,
            calls: Vec::new(),
            last_scan: None,
            placed: None,
        }
    }

    fn placed_scan(&self, s: &WorldScan) -> PlacedScan {
        let same = self
            .last_scan
            .as_ref()
            .is_some_and(|last| last.ranges == s.ranges);
        PlacedScan {
            t: Num(s.t),
            origin: at(s.origin),
            angle_min: Num(s.angle_min),
            angle_step: Num(s.angle_step),
            max_range: Num(s.max_range),
            ranges: (!same).then(|| nums(&s.ranges)),
        }
    }
}

impl<R: Robot> Hal for Taping<R> {
    fn update(&mut self, t: f64) -> Result<(), HalError> {
        let r = self.inner.update(t);
        self.calls.push(Exchange::Update {
            t: Num(t),
            error: error_of(&r),
        });
        r
    }

    fn snapshot(&mut self, out: &mut Snapshot) -> Result<(), HalError> {
        let r = self.inner.snapshot(out);
        self.calls.push(Exchange::Snapshot {
            snapshot: Box::new(record_snapshot(out, &mut self.last_scan)),
            error: error_of(&r),
        });
        r
    }

    fn set_motion(&mut self, speed: f64, curvature: f64) -> Result<(), HalError> {
        let r = self.inner.set_motion(speed, curvature);
        self.calls.push(Exchange::SetMotion {
            speed: Num(speed),
            curvature: Num(curvature),
            error: error_of(&r),
        });
        r
    }

    fn actuator(&mut self, id: &str, value: f64) -> Result<(), HalError> {
        let r = self.inner.actuator(id, value);
        self.calls.push(Exchange::Actuator {
            id: id.to_string(),
            value: Num(value),
            error: error_of(&r),
        });
        r
    }

    fn locmode(&mut self, mode: &str) -> Result<(), HalError> {
        let r = self.inner.locmode(mode);
        self.calls.push(Exchange::Locmode {
            mode: mode.to_string(),
            error: error_of(&r),
        });
        r
    }

    fn bodypose(&mut self, pose: BodyPose) -> Result<(), HalError> {
        let r = self.inner.bodypose(pose);
        self.calls.push(Exchange::Bodypose {
            roll: pose.roll.map(Num),
            pitch: pose.pitch.map(Num),
            clearance: pose.clearance.map(Num),
            error: error_of(&r),
        });
        r
    }

    fn locate(&mut self, pose: Pose) -> Result<(), HalError> {
        let r = self.inner.locate(pose);
        self.calls.push(Exchange::Locate {
            pose: at(pose),
            error: error_of(&r),
        });
        r
    }

    fn start(&mut self, op: &AsyncOp) -> Result<OpId, HalError> {
        let r = self.inner.start(op);
        self.calls.push(Exchange::Start {
            op: operation(op),
            id: r.as_ref().ok().map(|id| id.0),
            error: error_of(&r),
        });
        r
    }

    fn poll(&mut self, op: OpId) -> Result<OpStatus, HalError> {
        let r = self.inner.poll(op);
        self.calls.push(Exchange::Poll {
            id: op.0,
            status: r.as_ref().ok().map(op_state),
            error: error_of(&r),
        });
        r
    }

    fn cancel(&mut self, op: OpId) -> Result<(), HalError> {
        let r = self.inner.cancel(op);
        self.calls.push(Exchange::Cancel {
            id: op.0,
            error: error_of(&r),
        });
        r
    }

    fn known_map(&mut self) -> Option<KnownMap> {
        let m = self.inner.known_map();
        self.calls.push(Exchange::KnownMap {
            map: m.as_ref().map(map),
        });
        m
    }

    fn actuator_range(&mut self, id: &str) -> Option<(f64, f64)> {
        let r = self.inner.actuator_range(id);
        self.calls.push(Exchange::ActuatorRange {
            id: id.to_string(),
            range: r.map(|(a, b)| (Num(a), Num(b))),
        });
        r
    }
}

impl<R: Robot> Robot for Taping<R> {
    fn at_rest(&self) -> bool {
        self.inner.at_rest()
    }

    fn true_pose(&self) -> Option<Pose> {
        self.inner.true_pose()
    }

    fn true_motion(&self) -> Option<(f64, f64)> {
        self.inner.true_motion()
    }

    fn new_scan(&mut self) -> Option<WorldScan> {
        let scan = self.inner.new_scan();
        self.placed.clone_from(&scan);
        scan
    }

    fn contacts(&self) -> u64 {
        self.inner.contacts()
    }

    fn link_stats(&self) -> Option<ilmr_ros2::LinkStats> {
        self.inner.link_stats()
    }

    fn scanner_mount(&self) -> Option<Pose> {
        self.inner.scanner_mount()
    }

    fn record_ros2_messages(&mut self) {
        self.inner.record_ros2_messages()
    }

    fn take_ros2_messages(&mut self) -> Vec<ilmr_ros2::robot::Recorded> {
        self.inner.take_ros2_messages()
    }

    fn inputs_exhausted(&self) -> bool {
        self.inner.inputs_exhausted()
    }

    fn end_tick(&mut self) -> Option<Input> {
        self.inner.end_tick();
        let scan = self.placed.take().map(|s| self.placed_scan(&s));
        Some(Input {
            calls: std::mem::take(&mut self.calls),
            robot: Seen {
                at_rest: self.inner.at_rest(),
                true_pose: self.inner.true_pose().map(at),
                motion: self.inner.true_motion().map(|(v, c)| (Num(v), Num(c))),
                contacts: self.inner.contacts(),
                scan,
            },
        })
    }
}

//! Recording what the VM receives from the robot, and playing it back.
//!
//! [`Taping`] wraps any robot and writes down every HAL call the VM makes with the
//! robot's answer, tick by tick, as the trace's `input` lines (`ilmr_trace::input`).
//! [`Player`] is a robot made of such lines: it answers each call as the recording
//! says, so the VM runs the task again exactly as it ran, without the robot or the
//! simulator (`ilmrc replay --inputs`, docs/testing.md). When the task has changed, the
//! VM's calls part from the recording's at some tick; the player notes the first such
//! [`Divergence`] and goes on answering from the recording where it can.
//!
//! This module converts between the HAL's types and the recording's; the two kinds
//! of robot are in `taping.rs` and `player.rs`.

mod player;
mod taping;

pub use player::Player;
pub use taping::Taping;

use ilmr_hal::{
    AsyncOp, Detection, DeviceReading, HalError, KnownMap, ManipTask, OpId, OpStatus, Pose, Scan,
    Side, Snapshot, Solid,
};
use ilmr_sim::RobotKind;
use ilmr_trace::{
    At, Event, Exchange, Failure, INPUT_FORMAT, Map, Num, OpState, Operation, Ranges, Reading,
    Record, Sighting, Snapshot as Recorded, Tape, TaughtPath,
};

use crate::run::RunArgs;
use crate::run::scenario::Scenario;
use crate::run::setup::{Backend, Setup};

pub fn at(p: Pose) -> At {
    At {
        x: Num(p.x),
        y: Num(p.y),
        h: Num(p.h),
    }
}

pub fn pose(a: &At) -> Pose {
    // As the trace wrote it: a heading rounded to four decimals may lie past pi.
    Pose {
        x: a.x.0,
        y: a.y.0,
        h: a.h.0,
    }
}

pub fn failure(e: &HalError) -> Failure {
    match e {
        HalError::Unsupported(m) => Failure::Unsupported { message: m.clone() },
        HalError::Refused(m) => Failure::Refused { message: m.clone() },
        HalError::UnknownOp(id) => Failure::UnknownOp { id: id.0 },
        HalError::Link(m) => Failure::Link { message: m.clone() },
        HalError::Timeout(m) => Failure::Timeout { message: m.clone() },
    }
}

pub fn hal_error(f: &Failure) -> HalError {
    match f {
        Failure::Unsupported { message } => HalError::Unsupported(message.clone()),
        Failure::Refused { message } => HalError::Refused(message.clone()),
        Failure::UnknownOp { id } => HalError::UnknownOp(OpId(*id)),
        Failure::Link { message } => HalError::Link(message.clone()),
        Failure::Timeout { message } => HalError::Timeout(message.clone()),
    }
}

/// The failure of `result`, if it failed.
pub fn error_of<T>(result: &Result<T, HalError>) -> Option<Failure> {
    result.as_ref().err().map(failure)
}

/// `Ok(value)`, or the recorded failure.
pub fn result<T>(error: &Option<Failure>, value: T) -> Result<T, HalError> {
    match error {
        Some(f) => Err(hal_error(f)),
        None => Ok(value),
    }
}

pub fn operation(op: &AsyncOp) -> Operation {
    match op {
        AsyncOp::Init(addresses) => Operation::Init(addresses.clone()),
        AsyncOp::Manipulate(task) => Operation::Manipulate(manip_name(*task).to_string()),
        AsyncOp::MoveMode(mode) => Operation::MoveMode(mode.clone()),
    }
}

fn manip_name(task: ManipTask) -> &'static str {
    match task {
        ManipTask::Take => "take",
        ManipTask::Leave => "leave",
        ManipTask::GetBall => "getball",
        ManipTask::GiveBall => "giveball",
    }
}

pub fn op_state(status: &OpStatus) -> OpState {
    match status {
        OpStatus::Pending => OpState::Pending,
        OpStatus::Done => OpState::Done,
        OpStatus::Failed(why) => OpState::Failed(why.clone()),
    }
}

pub fn op_status(state: &OpState) -> OpStatus {
    match state {
        OpState::Pending => OpStatus::Pending,
        OpState::Done => OpStatus::Done,
        OpState::Failed(why) => OpStatus::Failed(why.clone()),
    }
}

pub fn map(m: &KnownMap) -> Map {
    Map {
        bounds: m
            .bounds
            .map(|(a, b, c, d)| (Num(a), Num(b), Num(c), Num(d))),
        solids: m
            .solids
            .iter()
            .map(|s| ilmr_trace::Solid {
                a: (Num(s.a.0), Num(s.a.1)),
                b: (Num(s.b.0), Num(s.b.1)),
                radius: Num(s.radius),
                name: s.name.clone(),
            })
            .collect(),
    }
}

pub fn known_map(m: &Map) -> KnownMap {
    KnownMap {
        bounds: m.bounds.map(|(a, b, c, d)| (a.0, b.0, c.0, d.0)),
        solids: m
            .solids
            .iter()
            .map(|s| Solid {
                a: (s.a.0.0, s.a.1.0),
                b: (s.b.0.0, s.b.1.0),
                radius: s.radius.0,
                name: s.name.clone(),
            })
            .collect(),
    }
}

pub fn nums(xs: &[f64]) -> Vec<Num> {
    xs.iter().copied().map(Num).collect()
}

fn floats(xs: &[Num]) -> Vec<f64> {
    xs.iter().map(|x| x.0).collect()
}

fn side_name(side: Side) -> &'static str {
    match side {
        Side::Left => "left",
        Side::Right => "right",
    }
}

/// `snap` as recorded; its scan is written only when it is not `last_scan`, which is
/// then updated.
pub fn record_snapshot(snap: &Snapshot, last_scan: &mut Option<Scan>) -> Recorded {
    let kept = snap.scan.is_some() && snap.scan == *last_scan;
    let scan = match &snap.scan {
        Some(s) if !kept => {
            *last_scan = Some(s.clone());
            Some(Ranges {
                device: s.device.clone(),
                t: Num(s.t),
                angle_min: Num(s.angle_min),
                angle_step: Num(s.angle_step),
                ranges: nums(&s.ranges),
            })
        }
        _ => None,
    };
    Recorded {
        t: Num(snap.t),
        pose: at(snap.pose),
        true_pose: snap.true_pose.map(at),
        speed: Num(snap.speed),
        curvature: Num(snap.curvature),
        scan,
        scan_kept: kept,
        battery: snap.battery.map(Num),
        devices: snap
            .devices
            .iter()
            .map(|d| Reading {
                name: d.name.clone(),
                value: d.value.map(Num),
            })
            .collect(),
        detections: snap
            .detections
            .iter()
            .map(|d| Sighting {
                sensor: d.sensor.clone(),
                object: d.object.clone(),
                x: Num(d.x),
                y: Num(d.y),
                h: Num(d.h),
                side: side_name(d.side).to_string(),
            })
            .collect(),
        odometry_t: snap.odometry_t.map(Num),
        nav_t: snap.nav_t.map(Num),
    }
}

/// Fills `out` with a recorded snapshot; a kept scan is `last_scan`, a new one
/// becomes it.
pub fn play_snapshot(rec: &Recorded, out: &mut Snapshot, last_scan: &mut Option<Scan>) {
    if let Some(r) = &rec.scan {
        *last_scan = Some(Scan {
            device: r.device.clone(),
            t: r.t.0,
            angle_min: r.angle_min.0,
            angle_step: r.angle_step.0,
            ranges: floats(&r.ranges),
        });
    }
    out.t = rec.t.0;
    out.pose = pose(&rec.pose);
    out.true_pose = rec.true_pose.as_ref().map(pose);
    out.speed = rec.speed.0;
    out.curvature = rec.curvature.0;
    out.scan = if rec.scan.is_some() || rec.scan_kept {
        last_scan.clone()
    } else {
        None
    };
    out.battery = rec.battery.map(|b| b.0);
    out.devices = rec
        .devices
        .iter()
        .map(|d| DeviceReading {
            name: d.name.clone(),
            value: d.value.map(|v| v.0),
        })
        .collect();
    out.detections = rec
        .detections
        .iter()
        .map(|d| Detection {
            sensor: d.sensor.clone(),
            object: d.object.clone(),
            x: d.x.0,
            y: d.y.0,
            h: d.h.0,
            side: if d.side == "right" {
                Side::Right
            } else {
                Side::Left
            },
        })
        .collect();
    out.odometry_t = rec.odometry_t.map(|t| t.0);
    out.nav_t = rec.nav_t.map(|t| t.0);
}

/// The call of `e` as a person reads it: `set_motion(speed 0.4, curvature 0)`, its
/// numbers exact, since two calls may differ in their last digit.
pub fn describe(e: &Exchange) -> String {
    let n = |x: &Num| {
        if x.0.is_finite() {
            x.0.to_string()
        } else {
            ilmr_trace::fmt_num(x.0)
        }
    };
    let args = match e {
        Exchange::Update { t, .. } => n(t),
        Exchange::Snapshot { .. } | Exchange::KnownMap { .. } => String::new(),
        Exchange::SetMotion {
            speed, curvature, ..
        } => format!("speed {}, curvature {}", n(speed), n(curvature)),
        Exchange::Actuator { id, value, .. } => format!("{id}, {}", n(value)),
        Exchange::Locmode { mode, .. } => mode.clone(),
        Exchange::Bodypose {
            roll,
            pitch,
            clearance,
            ..
        } => [("roll", roll), ("pitch", pitch), ("clearance", clearance)]
            .iter()
            .filter_map(|(k, v)| v.as_ref().map(|v| format!("{k} {}", n(v))))
            .collect::<Vec<_>>()
            .join(", "),
        Exchange::Locate { pose, .. } => {
            format!("{}, {}, {}", n(&pose.x), n(&pose.y), n(&pose.h))
        }
        Exchange::Start { op, .. } => match op {
            Operation::Init(a) => format!("init {}", a.join(" ")),
            Operation::Manipulate(t) => format!("manipulate {t}"),
            Operation::MoveMode(m) => format!("movemode {m}"),
        },
        Exchange::Poll { id, .. } | Exchange::Cancel { id, .. } => format!("operation {id}"),
        Exchange::ActuatorRange { id, .. } => id.clone(),
    };
    format!("{}({args})", e.name())
}

/// The `tape` line of a run that records its inputs: what `ilmrc replay --inputs`
/// needs besides the task and the inputs to set the run up as it was.
pub fn header(
    setup: &Setup,
    scenario: &Scenario,
    args: &RunArgs,
    scanner_offset: Option<f64>,
) -> Record<'static> {
    let (backend, body) = match setup.backend {
        Backend::None => ("none", None),
        Backend::Scripted => ("scripted", None),
        Backend::Ros2 => ("ros2", None),
        Backend::Sim(kind) => ("sim", Some(body_name(kind))),
    };
    Record::new(
        0.0,
        Event::Tape(Tape {
            format: INPUT_FORMAT,
            ilmrc: env!("CARGO_PKG_VERSION").to_string(),
            backend: backend.to_string(),
            model: setup.model_spec.clone(),
            body: body.map(str::to_string),
            scanner_offset: scanner_offset.map(Num),
            pose_every: args.pose_every,
            scan_every: Num(args.scan_every),
            max_time: Num(args.max_time),
            hold_limit: Num(args.hold_limit),
            paths: scenario
                .paths
                .iter()
                .map(|(name, points)| TaughtPath {
                    name: name.clone(),
                    points: points.clone().into(),
                })
                .collect(),
        }),
    )
}

/// The names a `tape` line gives the simulated bodies.
pub const BODIES: [(&str, RobotKind); 2] = [
    ("moro", RobotKind::Moro),
    ("workpartner", RobotKind::Workpartner),
];

fn body_name(kind: RobotKind) -> &'static str {
    BODIES
        .iter()
        .find(|(_, k)| *k == kind)
        .map_or("moro", |(n, _)| n)
}

//! Issuing the catalogue's define, movement and action commands, and stepping the
//! ones that stay live (readings, searches, asynchronous operations, `speed(v,w)`).
//! Arguments are told apart with the catalogue's keywords, never by a restated list.

use ilmr_hal::{AsyncOp, BodyPose, Hal, ManipTask, OpId, OpStatus, Pose, Side};
use ilmr_stdlib::{Command, Field};

use super::clock::Clock;
use super::nodes::{Kind, MoveSpec, NodeRef, SensorSpec, WallMode, Which};
use super::safety::Refusal;
use super::trace::EventKind;
use super::vars::{How, NONE};
use super::{Follower, Recording, Vm, stmt_of};
use crate::bytecode::{Arg, ArgRange};

fn side_of(word: &str) -> Option<Side> {
    if word.eq_ignore_ascii_case("left") {
        Some(Side::Left)
    } else if word.eq_ignore_ascii_case("right") {
        Some(Side::Right)
    } else {
        None
    }
}

impl<H: Hal, C: Clock> Vm<H, C> {
    pub(in crate::runtime) fn arg(&self, r: ArgRange, i: u32) -> Option<Arg> {
        if i < r.len {
            self.module.args.get((r.start + i) as usize).copied()
        } else {
            None
        }
    }

    pub(in crate::runtime) fn word_of(&self, a: Option<Arg>) -> Option<&str> {
        match a {
            Some(Arg::Word(n)) => Some(self.module.name(n)),
            _ => None,
        }
    }

    fn has_word(&self, command: Command, r: ArgRange, word: &str) -> bool {
        (0..r.len).any(|i| {
            self.word_of(self.arg(r, i))
                .is_some_and(|w| w.eq_ignore_ascii_case(word) && command.spec().has_keyword(w))
        })
    }

    pub(in crate::runtime) fn number(&mut self, a: Option<Arg>) -> Result<f64, String> {
        match a {
            Some(Arg::Num(e)) => self.eval(e).map_err(str::to_string),
            Some(Arg::Var(v)) => {
                let kind = self.module.global(v).map(|g| g.kind);
                let field = kind.and_then(|k| k.numeric_field()).unwrap_or(Field::Value);
                Ok(self.vars.get(v.0).get(field))
            }
            Some(Arg::Setting { value, .. }) => self.eval(value).map_err(str::to_string),
            _ => Err("a number is missing".into()),
        }
    }

    pub(in crate::runtime) fn setting(
        &mut self,
        r: ArgRange,
        key: &str,
    ) -> Result<Option<f64>, String> {
        for i in 0..r.len {
            if let Some(Arg::Setting { key: k, value }) = self.arg(r, i)
                && self.module.name(k).eq_ignore_ascii_case(key)
            {
                return self.eval(value).map(Some).map_err(str::to_string);
            }
        }
        Ok(None)
    }

    fn numbers<const N: usize>(&mut self, r: ArgRange) -> Result<([f64; N], usize), String> {
        let mut out = [0.0; N];
        let mut n = 0;
        for i in 0..r.len {
            let a = self.arg(r, i);
            if matches!(a, Some(Arg::Num(_))) && n < N {
                out[n] = self.number(a)?;
                n += 1;
            }
        }
        Ok((out, n))
    }

    fn refuse_hal(e: ilmr_hal::HalError) -> String {
        e.to_string()
    }

    /// Issues a command from block `blk`; returns its node when it stays live.
    pub(super) fn issue(
        &mut self,
        blk: u32,
        stmt: u32,
        command: Command,
        args: ArgRange,
        bind: u32,
    ) -> Option<NodeRef> {
        let decoded = match self.refuse_unsafe(command, args) {
            Ok(()) => self
                .decode(command, args, bind, stmt)
                .map_err(Refusal::from),
            Err(refusal) => Err(refusal),
        };
        match decoded {
            Ok(None) => {
                if bind != NONE {
                    self.write_fields(
                        bind,
                        &[(Field::Status, 1.0)],
                        Some(Some(How::Completed)),
                        stmt,
                        false,
                    );
                }
                None
            }
            Ok(Some(kind)) => {
                self.bind_issue(bind, stmt);
                let node = self.nodes.alloc(blk, stmt, bind, kind);
                match kind {
                    Kind::Movement { .. } => self.queue_movement(node),
                    Kind::Sensor { .. } | Kind::Async { .. } | Kind::SpeedAfter { .. } => {
                        let key = self.search_key(kind);
                        self.step_node(node);
                        if self.nodes.alive(node) {
                            self.active.push(super::Active { node, key });
                        }
                    }
                    _ => {}
                }
                Some(node).filter(|n| self.nodes.alive(*n))
            }
            Err(Refusal { code, message }) => {
                self.push_event(
                    stmt_of(stmt),
                    EventKind::End {
                        how: How::Refused,
                        linked: false,
                        code,
                        reason: Some(message),
                    },
                );
                if bind != NONE {
                    self.write_fields(
                        bind,
                        &[(Field::Status, 1.0)],
                        Some(Some(How::Refused)),
                        stmt,
                        false,
                    );
                }
                None
            }
        }
    }

    /// Runs an instant command, or returns the live node's kind.
    fn decode(
        &mut self,
        command: Command,
        r: ArgRange,
        bind: u32,
        stmt: u32,
    ) -> Result<Option<Kind>, String> {
        let first_word = self.word_of(self.arg(r, 0)).map(str::to_string);
        let word0 = first_word.as_deref().unwrap_or("");
        match command {
            Command::MoveMode => {
                let op = self
                    .hal
                    .start(&AsyncOp::MoveMode(word0.to_string()))
                    .map_err(Self::refuse_hal)?;
                if let Some(Arg::Word(mode)) = self.arg(r, 0) {
                    self.mode_ops.push((op.0, mode));
                }
                Ok(Some(self.async_kind(op)))
            }
            Command::LocMode => {
                self.hal.locmode(word0).map_err(Self::refuse_hal)?;
                Ok(None)
            }
            Command::Speed => {
                let v = self.number(self.arg(r, 0))?;
                if self.has_word(command, r, "w")
                    && let Some(head) = self.motion.head
                {
                    return Ok(Some(Kind::SpeedAfter {
                        value: v as f32,
                        node: head.idx,
                        epoch: head.epoch,
                    }));
                }
                self.motion.speed = v;
                Ok(None)
            }
            Command::BodyPose => {
                let pose = BodyPose {
                    roll: self.setting(r, "r")?,
                    pitch: self.setting(r, "p")?,
                    clearance: self.setting(r, "rc")?,
                };
                self.hal.bodypose(pose).map_err(Self::refuse_hal)?;
                Ok(None)
            }
            Command::Locate => {
                let (n, count) = self.numbers::<3>(r)?;
                if count == 3 {
                    // The heading as the task gave it; the robot folds it.
                    let after = Pose {
                        x: n[0],
                        y: n[1],
                        h: n[2].to_radians(),
                    };
                    self.hal.locate(after).map_err(Self::refuse_hal)?;
                    self.map_from_estimate = super::safety::frame::relocated(
                        self.map_from_estimate,
                        self.snap.pose,
                        after,
                    );
                    self.motion.relocated();
                    self.supervisor.relocated = true;
                    return Ok(None);
                }
                let field = match word0.to_ascii_lowercase().as_str() {
                    "x" => Field::X,
                    "y" => Field::Y,
                    "h" => Field::H,
                    _ => return Err("locate needs x, y and h, or one of x, y, h".into()),
                };
                Ok(Some(self.sensor_kind(SensorSpec::Locate { field }, false)))
            }
            Command::AdvanceStop => {
                self.motion.advance_stop = Some(self.number(self.arg(r, 0))?);
                Ok(None)
            }
            Command::ObsAvoid => {
                self.motion.set_obsavoid(word0)?;
                Ok(None)
            }
            Command::Record => {
                if command.spec().has_keyword(word0) {
                    self.recording = None;
                } else {
                    let key = word0.to_lowercase();
                    let p = self.snap.pose;
                    self.paths.insert(key.clone(), vec![(p.x, p.y)]);
                    self.recording = Some(Recording {
                        path: key,
                        last: (p.x, p.y),
                    });
                }
                Ok(None)
            }
            Command::Use => {
                self.motion.use_goalpos = word0.eq_ignore_ascii_case("goalpos");
                Ok(None)
            }
            Command::SavePos => {
                // `savepos(name,laser)`: where the pointing device's beam hits,
                // which the robot reports as that device's detection (4.5.1).
                let pointed = match self.word_of(self.arg(r, 1)) {
                    Some(device) => Some(
                        self.snap
                            .detections
                            .iter()
                            .find(|d| d.sensor.eq_ignore_ascii_case(device))
                            .map(|d| ilmr_hal::Pose {
                                x: d.x,
                                y: d.y,
                                h: d.h,
                            })
                            .ok_or_else(|| format!("{device} points at nothing now"))?,
                    ),
                    None => None,
                };
                let var = if bind != NONE {
                    bind
                } else {
                    self.module.find_global(word0).map_or(NONE, |v| v.0)
                };
                if var == NONE {
                    return Err(format!("no variable {word0} to save the position in"));
                }
                let p = pointed.unwrap_or(self.snap.pose);
                self.write_fields(
                    var,
                    &[
                        (Field::X, p.x),
                        (Field::Y, p.y),
                        (Field::H, p.h),
                        (Field::Status, 1.0),
                    ],
                    Some(Some(How::Completed)),
                    stmt,
                    false,
                );
                Ok(None)
            }
            Command::CreatePath => {
                let mut pts = Vec::new();
                let mut pending = None;
                for i in 1..r.len {
                    let v = self.number(self.arg(r, i))?;
                    match pending.take() {
                        None => pending = Some(v),
                        Some(x) => pts.push((x, v)),
                    }
                }
                if pending.is_some() {
                    return Err("createpath needs x, y pairs".into());
                }
                self.paths.insert(word0.to_lowercase(), pts);
                Ok(None)
            }
            Command::Goahead
            | Command::Turn
            | Command::FollowPath
            | Command::FollowWall
            | Command::FollowTarget
            | Command::GotoXY
            | Command::GotoRelXY
            | Command::Approach => {
                let spec = self.move_spec(command, r)?;
                Ok(Some(Kind::Movement { command, spec }))
            }
            Command::Sensor | Command::FindTarget => {
                let spec = self.sensor_spec(command, r)?;
                let forever = self.has_word(command, r, "forever");
                Ok(Some(self.sensor_kind(spec, forever)))
            }
            Command::Actuator => {
                let value = match self.arg(r, 1) {
                    Some(Arg::Word(n)) => {
                        let w = self.module.name(n);
                        if w.eq_ignore_ascii_case("on") {
                            1.0
                        } else if w.eq_ignore_ascii_case("off") {
                            0.0
                        } else {
                            return Err(format!("actuator value {w} is neither on nor off"));
                        }
                    }
                    a => self.number(a)?,
                };
                self.hal.actuator(word0, value).map_err(Self::refuse_hal)?;
                Ok(None)
            }
            Command::Manipulate => {
                let task = ManipTask::from_name(word0)
                    .ok_or_else(|| format!("no manipulation task {word0}"))?;
                let op = self
                    .hal
                    .start(&AsyncOp::Manipulate(task))
                    .map_err(Self::refuse_hal)?;
                Ok(Some(self.async_kind(op)))
            }
            Command::Init => {
                let names = (0..r.len)
                    .filter_map(|i| self.word_of(self.arg(r, i)).map(str::to_string))
                    .collect();
                let op = self
                    .hal
                    .start(&AsyncOp::Init(names))
                    .map_err(Self::refuse_hal)?;
                Ok(Some(self.async_kind(op)))
            }
            other => Err(format!("{other} is not issued as a command")),
        }
    }

    fn async_kind(&self, op: OpId) -> Kind {
        Kind::Async {
            op: op.0,
            since: u32::try_from(self.tick).unwrap_or(u32::MAX),
        }
    }

    fn sensor_kind(&self, spec: SensorSpec, forever: bool) -> Kind {
        Kind::Sensor {
            spec,
            forever,
            since: u32::try_from(self.tick).unwrap_or(u32::MAX),
        }
    }

    fn sensor_spec(&mut self, command: Command, r: ArgRange) -> Result<SensorSpec, String> {
        let device = match self.arg(r, 0) {
            Some(Arg::Word(n)) => n.0,
            _ => return Err("sensor numbers must be resolved to names by the compiler".into()),
        };
        let second = self.arg(r, 1);
        match second {
            Some(Arg::Word(n)) => {
                let w = self.module.name(n);
                if command.spec().has_keyword(w) {
                    match side_of(w) {
                        Some(side) => Ok(SensorSpec::Reading {
                            device,
                            which: Which::Side(side),
                        }),
                        None => Ok(SensorSpec::Reading {
                            device,
                            which: Which::All,
                        }),
                    }
                } else {
                    let side = self.word_of(self.arg(r, 2)).and_then(side_of);
                    Ok(SensorSpec::Search {
                        sensor: device,
                        object: n.0,
                        side,
                    })
                }
            }
            Some(a @ Arg::Num(_)) => {
                let i = self.number(Some(a))?;
                if !(i >= 0.0 && i.fract() == 0.0 && i <= f64::from(u32::MAX)) {
                    return Err(format!("reading index {i} is not a whole number"));
                }
                Ok(SensorSpec::Reading {
                    device,
                    which: Which::Index(i as u32),
                })
            }
            _ => Ok(SensorSpec::Reading {
                device,
                which: Which::All,
            }),
        }
    }

    fn move_spec(&mut self, command: Command, r: ArgRange) -> Result<MoveSpec, String> {
        let var0 = match self.arg(r, 0) {
            Some(Arg::Var(v)) => Some(v.0),
            _ => None,
        };
        let has_r = self.has_word(command, r, "r");
        Ok(match command {
            Command::Goahead => MoveSpec::Goahead {
                d: if r.len == 0 {
                    f32::NAN
                } else {
                    self.number(self.arg(r, 0))? as f32
                },
            },
            Command::Turn => {
                if let (Some(deg), Some(c)) = (self.setting(r, "d")?, self.setting(r, "c")?) {
                    MoveSpec::TurnExact {
                        deg: deg as f32,
                        c: c as f32,
                    }
                } else if let Some(v) = var0 {
                    MoveSpec::ToVar {
                        var: v,
                        rel: false,
                        r: has_r,
                    }
                } else {
                    match self.word_of(self.arg(r, 0)).and_then(side_of) {
                        Some(side) => MoveSpec::TurnSide {
                            left: side == Side::Left,
                        },
                        None => {
                            return Err("turn needs d= and c=, left, right or a position".into());
                        }
                    }
                }
            }
            Command::GotoXY | Command::GotoRelXY => {
                let rel = command == Command::GotoRelXY;
                match var0 {
                    Some(var) => MoveSpec::ToVar { var, rel, r: has_r },
                    None => {
                        let (n, count) = self.numbers::<3>(r)?;
                        if count < 2 {
                            return Err(format!("{command} needs x and y"));
                        }
                        MoveSpec::To {
                            x: n[0] as f32,
                            y: n[1] as f32,
                            h: if count == 3 { n[2] as f32 } else { f32::NAN },
                            rel,
                            r: has_r,
                        }
                    }
                }
            }
            Command::FollowPath => match self.arg(r, 0) {
                Some(Arg::Word(n)) => MoveSpec::FollowPath {
                    name: n.0,
                    reverse: self.has_word(command, r, "reverse"),
                    backwards: self.has_word(command, r, "backwards"),
                },
                _ => return Err("followpath needs a path name".into()),
            },
            Command::FollowWall => {
                let word = self.word_of(self.arg(r, 0)).unwrap_or("");
                let mode = match side_of(word) {
                    Some(side) => WallMode::Side(side),
                    None if word.eq_ignore_ascii_case("middle") => WallMode::Middle,
                    None => return Err("followwall needs left, right or middle".into()),
                };
                let d = match self.arg(r, 1) {
                    Some(a) => self.number(Some(a))?,
                    None => f64::NAN,
                };
                if d <= 0.0 {
                    return Err(format!("followwall distance {d} m is not positive"));
                }
                MoveSpec::FollowWall { mode, d: d as f32 }
            }
            Command::FollowTarget => {
                let object = match self.arg(r, 0) {
                    Some(Arg::Word(n)) => n.0,
                    _ => return Err("followtarget needs an object of the robot model".into()),
                };
                let d = match self.arg(r, 1) {
                    Some(a) => self.number(Some(a))?,
                    None => 0.0,
                };
                if !(d >= 0.0 && d.is_finite()) {
                    return Err(format!("followtarget distance {d} m is not usable"));
                }
                MoveSpec::FollowTarget {
                    object,
                    d: d as f32,
                }
            }
            Command::Approach => {
                let d = match self.arg(r, 1) {
                    Some(a) => self.number(Some(a))?,
                    None => 0.0,
                };
                match (var0, self.arg(r, 0)) {
                    (Some(var), _) => MoveSpec::ApproachVar { var, d: d as f32 },
                    (None, Some(Arg::Word(n))) => MoveSpec::ApproachObject {
                        object: n.0,
                        d: d as f32,
                    },
                    _ => return Err("approach needs a position or an object".into()),
                }
            }
            other => return Err(format!("{other} is not a movement command")),
        })
    }

    /// The (sensor, object) pair a search looks for, as an index into
    /// `search_keys` (added if new); NONE for anything but a search.
    fn search_key(&mut self, kind: Kind) -> u32 {
        let Kind::Sensor {
            spec: SensorSpec::Search { sensor, object, .. },
            ..
        } = kind
        else {
            return NONE;
        };
        match self.search_keys.iter().position(|k| *k == (sensor, object)) {
            Some(i) => i as u32,
            None => {
                self.search_keys.push((sensor, object));
                self.key_hit.push(false);
                (self.search_keys.len() - 1) as u32
            }
        }
    }

    /// Which search keys this tick's detections match: a search whose key has no
    /// match is not looked at (it waits for a detection, so it costs nothing).
    pub(super) fn resolve_search_keys(&mut self) {
        let dets = &self.snap.detections;
        for (i, &(sensor, object)) in self.search_keys.iter().enumerate() {
            let (s, o) = (
                self.module.name(crate::bytecode::NameId(sensor)),
                self.module.name(crate::bytecode::NameId(object)),
            );
            self.key_hit[i] = dets
                .iter()
                .any(|d| d.sensor.eq_ignore_ascii_case(s) && d.object.eq_ignore_ascii_case(o));
        }
    }

    /// Steps every live reading, search and asynchronous operation once, in issue
    /// order. The list is dense (12 bytes a command) and a search without a matching
    /// detection is skipped without touching its node; entries of ended commands are
    /// dropped when they come to outnumber the live ones.
    pub(super) fn step_active(&mut self) {
        let c = &self.nodes.classes;
        let live =
            c[super::nodes::Class::Active as usize] + c[super::nodes::Class::Endless as usize];
        if self.active.len() > 2 * live + 64 {
            let nodes = &self.nodes;
            self.active.retain(|a| nodes.alive(a.node));
        }
        self.resolve_search_keys();
        for i in 0..self.active.len() {
            let a = self.active[i];
            if a.key != NONE && !self.key_hit[a.key as usize] {
                continue;
            }
            self.step_node(a.node);
        }
    }

    fn step_node(&mut self, r: NodeRef) {
        if !self.nodes.alive(r) {
            return;
        }
        let node = *self.nodes.get(r.idx);
        match node.kind {
            Kind::Sensor {
                spec,
                forever,
                since,
            } => self.step_sensor(r.idx, node.bind, node.stmt, spec, forever, since),
            Kind::Async { op, since } => self.step_async(r.idx, op, since),
            Kind::SpeedAfter { value, node, epoch }
                if !self.nodes.alive(NodeRef { idx: node, epoch }) =>
            {
                self.motion.speed = f64::from(value);
                self.end_node(r.idx, How::Completed, false, None, true);
            }
            _ => {}
        }
    }

    /// Polls an operation; gives it up after `operation_timeout`. A poll that fails
    /// ends it refused with the robot's error.
    fn step_async(&mut self, idx: u32, op: u32, since: u32) {
        let status = match self.hal.poll(OpId(op)) {
            Ok(s) => s,
            Err(e) => OpStatus::Failed(e.to_string()),
        };
        let done = match status {
            OpStatus::Pending => {
                let waited = self.tick.saturating_sub(u64::from(since)) as f64 * self.cfg.period;
                let Some(limit) = self.cfg.safety.operation_timeout.filter(|l| waited >= *l) else {
                    return;
                };
                if let Err(e) = self.hal.cancel(OpId(op)) {
                    let stmt = stmt_of(self.nodes.get(idx).stmt);
                    self.error(stmt, format!("cancelling the operation failed: {e}"));
                }
                let message = format!("no answer from the robot in {limit} s (operation_timeout)");
                let fault = super::safety::Fault::OperationTimeout;
                self.push_event(
                    stmt_of(self.nodes.get(idx).stmt),
                    EventKind::Fault {
                        fault,
                        message: message.clone(),
                    },
                );
                self.mode_ops.retain(|(o, _)| *o != op);
                self.end_coded(idx, super::safety::Code::Fault(fault), message);
                return;
            }
            OpStatus::Done => {
                if let Some(&(_, mode)) = self.mode_ops.iter().find(|(o, _)| *o == op) {
                    self.move_mode = Some(mode);
                }
                None
            }
            OpStatus::Failed(why) => Some(why),
        };
        self.mode_ops.retain(|(o, _)| *o != op);
        match done {
            None => self.end_node(idx, How::Completed, false, None, true),
            Some(why) => self.end_node(idx, How::Refused, false, Some(why), true),
        }
    }

    fn step_sensor(
        &mut self,
        idx: u32,
        bind: u32,
        stmt: u32,
        spec: SensorSpec,
        forever: bool,
        since: u32,
    ) {
        if let SensorSpec::Search {
            sensor,
            object,
            side,
        } = spec
        {
            if self.snap.detections.is_empty() {
                return;
            }
            let (s, o) = (
                self.module.name(crate::bytecode::NameId(sensor)),
                self.module.name(crate::bytecode::NameId(object)),
            );
            let found = self.snap.detections.iter().find(|d| {
                d.sensor.eq_ignore_ascii_case(s)
                    && d.object.eq_ignore_ascii_case(o)
                    && side.is_none_or(|w| w == d.side)
            });
            if let Some(d) = found {
                let (x, y, h) = (d.x, d.y, d.h);
                if bind != NONE {
                    let how = if forever {
                        None
                    } else {
                        Some(Some(How::Completed))
                    };
                    self.write_fields(
                        bind,
                        &[
                            (Field::X, x),
                            (Field::Y, y),
                            (Field::H, h),
                            (Field::Status, 1.0),
                        ],
                        how,
                        stmt,
                        false,
                    );
                }
                if !forever {
                    self.end_node(idx, How::Completed, false, None, true);
                }
            }
            return;
        }
        match self.read_sensor(spec) {
            Ok(Some(v)) => {
                if bind != NONE {
                    self.write_fields(bind, &[(Field::Value, v)], None, stmt, false);
                }
                if !forever {
                    self.end_node(idx, How::Completed, false, None, true);
                } else if bind != NONE {
                    self.write_fields(bind, &[(Field::Status, 1.0)], None, stmt, false);
                }
            }
            Ok(None) => {
                let waited = (self.tick.saturating_sub(u64::from(since))) as f64 * self.cfg.period;
                if waited >= self.cfg.sensor_timeout {
                    let name = match spec {
                        SensorSpec::Reading { device, .. } => self
                            .module
                            .name(crate::bytecode::NameId(device))
                            .to_string(),
                        _ => "the sensor".into(),
                    };
                    let why = format!("no data from {name}");
                    self.end_node(idx, How::Refused, false, Some(why), true);
                }
            }
            Err(why) => self.end_node(idx, How::Refused, false, Some(why), true),
        }
    }

    /// The current value of a reading; `Ok(None)` while the device gives no data.
    pub(super) fn read_sensor(&self, spec: SensorSpec) -> Result<Option<f64>, String> {
        match spec {
            SensorSpec::Locate { field } => {
                let p = self.snap.pose;
                Ok(Some(match field {
                    Field::X => p.x,
                    Field::Y => p.y,
                    _ => p.h,
                }))
            }
            SensorSpec::Reading { device, which } => {
                let name = self.module.name(crate::bytecode::NameId(device));
                if name.eq_ignore_ascii_case(ilmr_model::SUPERVISOR) {
                    return Ok(Some(self.supervisor.reading()));
                }
                if let Some(scan) = self
                    .snap
                    .scan
                    .as_ref()
                    .filter(|s| s.device.eq_ignore_ascii_case(name))
                {
                    let angle = |i: usize| scan.angle_min + i as f64 * scan.angle_step;
                    let nearest = |keep: &dyn Fn(f64) -> bool| {
                        scan.ranges
                            .iter()
                            .enumerate()
                            .filter(|(i, _)| keep(angle(*i)))
                            .map(|(_, r)| *r)
                            .fold(None, |m: Option<f64>, r| Some(m.map_or(r, |m| m.min(r))))
                    };
                    return match which {
                        Which::All => Ok(nearest(&|_| true)),
                        Which::Side(Side::Left) => Ok(nearest(&|a| a > 0.0)),
                        Which::Side(Side::Right) => Ok(nearest(&|a| a < 0.0)),
                        Which::Index(i) => scan
                            .ranges
                            .get(i as usize)
                            .copied()
                            .map(Some)
                            .ok_or_else(|| format!("{name} has no reading {i}")),
                    };
                }
                match which {
                    Which::All => Ok(self.snap.device(name)),
                    _ => Err(format!("{name} is not a scanner")),
                }
            }
            SensorSpec::Search { .. } => Ok(None),
        }
    }

    /// A completed reading leaves its variable following the sensor.
    pub(super) fn follow_after(&mut self, kind: Kind, var: u32, stmt: u32) {
        if let Kind::Sensor { spec, .. } = kind
            && matches!(spec, SensorSpec::Reading { .. } | SensorSpec::Locate { .. })
        {
            self.followers.retain(|f| f.var != var);
            self.followers.push(Follower { var, spec, stmt });
        }
    }
}

//! The VM: a tree of live commands stepped at 100 Hz. See `vm/README.md` for the order
//! of a tick and `docs/bytecode.md` for the instructions.

pub mod activity;
pub mod clock;
mod commands;
pub mod config;
mod decode;
mod exec;
mod frame;
mod motion;
mod nodes;
pub mod safety;
mod targets;
pub use targets::{BREAK_TARGETS, NODES_PER_OP};
mod timers;
pub mod trace;
pub mod vars;
mod watch;

use std::collections::{BTreeMap, VecDeque};

use ilmr_hal::{Hal, KnownMap, Snapshot};

use crate::bytecode::limits::EXPR_STACK;
use crate::bytecode::{BlockId, Fragment, Global, Module, ModuleBuilder, ModuleError, StmtId};
use activity::{Activity, REST_SPEED};
use clock::Clock;
use config::{Config, TraceLevel};
use motion::Motion;
use nodes::{Class, Kind, NodeRef, Nodes};
use trace::{Event, EventKind};
use vars::{NONE, VarRecord, Vars};

/// What a reading variable keeps following after its command
/// ended (`v = sensor(battery)`).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Follower {
    var: u32,
    spec: nodes::SensorSpec,
    /// The reading that started it, for the trace.
    stmt: u32,
}

/// A command stepped every tick: its node and, for a search, its key in
/// `Vm::search_keys` (NONE otherwise).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Active {
    node: NodeRef,
    key: u32,
}

/// `record(name)` in progress.
#[derive(Debug, Clone, PartialEq)]
struct Recording {
    path: String,
    last: (f64, f64),
}

pub struct Vm<H: Hal, C: Clock> {
    module: Module,
    hal: H,
    clock: C,
    cfg: Config,
    tick: u64,
    snap: Snapshot,
    vars: Vars,
    nodes: Nodes,
    root: u32,
    ready: VecDeque<exec::Packed>,
    /// Reused buffer of the subscribers of a woken variable.
    woken: Vec<vars::Woken>,
    /// Nodes stepped every tick (sensors, searches, asynchronous operations).
    active: Vec<Active>,
    /// The distinct (sensor, object) name pairs of searches, and whether this tick's
    /// detections match each.
    search_keys: Vec<(u32, u32)>,
    key_hit: Vec<bool>,
    /// The `wait(seconds)` wake-ups; stale alarms (a block ended, or its sleep was
    /// broken) are skipped.
    timers: timers::Timers,
    motion: Motion,
    followers: Vec<Follower>,
    paths: BTreeMap<String, Vec<(f64, f64)>>,
    recording: Option<Recording>,
    /// The block that ran `priority = highest`, while it lives.
    priority: Option<NodeRef>,
    /// Interactive blocks waiting for a priority block to end.
    pending: Vec<u32>,
    events: Vec<Event>,
    coalesce: trace::Coalesce,
    ops_left: u32,
    /// The statements each `break(pattern)` can end, found at the first break run.
    targets: Option<targets::Targets>,
    marks: targets::Marks,
    /// Nodes `break(pattern)` has looked at (`Vm::break_looks`).
    break_looks: u64,
    scratch: Vec<u32>,
    stack: [f64; EXPR_STACK],
    /// Every expression of the module, decoded for [`Vm::eval`].
    decoded: decode::Decoder,
    /// The flat code of the module's frame-shaped blocks.
    frames: frame::Frames,
    /// Per node, the iterations of a frame's open loops, with the trace on only
    /// (`Vm::frame_iters`).
    frame_iters: Vec<[u32; frame::MAX_LOOPS]>,
    /// Ready queues run in one go (`Vm::run_round`).
    rounds_fused: u64,
    /// Frames' visits of such rounds run as one step along a plan (`Vm::run_plan`).
    plans_run: u64,
    /// Per ready entry of a round run in one go, one bit: its frame's plan holds.
    round_planned: Vec<u64>,
    /// This tick's due alarms, not yet woken: `fire_timers` leaves them for
    /// `run_ready` when nothing between the two can look at a frame
    /// (`Vm::defer_alarms`), so that a round can run straight from them.
    deferred: Option<Vec<timers::Alarm>>,
    /// Rounds run straight from the wheel's due slot (`Vm::run_slot_round`).
    slot_rounds: u64,
    /// Of those, rounds run in one pass over the alarms (`Vm::run_slot_once`).
    slot_once: u64,
    /// Rounds that pass ran in part and took back (`Vm::run_slot_once`).
    slot_undone: u64,
    /// The values a round run in one pass overwrote, in order, to write back if a
    /// later frame shows the round cannot be run so (`Vm::run_slot_once`).
    slot_log: Vec<f64>,
    /// Where such a round's runs of frames at one pc begin: (alarm index, pc).
    slot_runs: Vec<(u32, u32)>,
    supervisor: safety::supervisor::Supervisor,
    /// The robot's static map, asked for once at the start.
    known_map: Option<KnownMap>,
    /// From the frame of the robot's estimate to the known map's, moved by `locate`.
    map_from_estimate: ilmr_hal::Pose,
    /// The known map's surfaces as points (map frame), for the reversing check.
    known: safety::known::KnownSurface,
    /// The movement mode the last completed `movemode` set.
    move_mode: Option<crate::bytecode::NameId>,
    /// `movemode` operations in progress and the mode each asks for.
    mode_ops: Vec<(u32, crate::bytecode::NameId)>,
    /// The stable code of the next `end` event, set by `end_coded`.
    end_code: Option<safety::Code>,
}

/// A runtime-level failure of a call into the VM (never of the task itself).
#[derive(Debug, Clone, PartialEq)]
pub enum VmError {
    Module(ModuleError),
}

impl std::fmt::Display for VmError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            VmError::Module(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for VmError {}

/// Why [`Vm::add_line`] joined nothing.
#[derive(Debug, Clone, PartialEq)]
pub enum LineError<E> {
    /// The lowering refused the line.
    Lower(E),
    /// What the lowering added does not validate.
    Invalid(ModuleError),
    /// The lowering replaced the builder it was lent.
    Replaced,
}

impl<E: std::fmt::Display> std::fmt::Display for LineError<E> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            LineError::Lower(e) => write!(f, "{e}"),
            LineError::Invalid(e) => write!(f, "{e}"),
            LineError::Replaced => write!(f, "the lowering replaced the builder it was lent"),
        }
    }
}

impl<H: Hal, C: Clock> Vm<H, C> {
    /// Validates the module and starts the task's top-level blocks (they run from the
    /// first tick).
    pub fn new(module: Module, mut hal: H, clock: C, config: Config) -> Result<Vm<H, C>, VmError> {
        module.validate().map_err(VmError::Module)?;
        let known_map = hal.known_map();
        let known = safety::known::KnownSurface::new(known_map.as_ref());
        let mut nodes = Nodes::default();
        let root = nodes.alloc(NONE, NONE, NONE, Kind::Root).idx;
        let mut vm = Vm {
            vars: Vars::new(module.globals.len()),
            module,
            hal,
            clock,
            motion: Motion::new(&config),
            cfg: config,
            tick: 0,
            snap: Snapshot::default(),
            nodes,
            root,
            ready: VecDeque::new(),
            woken: Vec::new(),
            active: Vec::new(),
            search_keys: Vec::new(),
            key_hit: Vec::new(),
            timers: timers::Timers::default(),
            followers: Vec::new(),
            paths: BTreeMap::new(),
            recording: None,
            priority: None,
            pending: Vec::new(),
            events: Vec::new(),
            coalesce: trace::Coalesce::default(),
            ops_left: 0,
            targets: None,
            marks: targets::Marks::default(),
            break_looks: 0,
            scratch: Vec::new(),
            stack: [0.0; EXPR_STACK],
            decoded: decode::Decoder::default(),
            frames: frame::Frames::default(),
            frame_iters: Vec::new(),
            rounds_fused: 0,
            plans_run: 0,
            round_planned: Vec::new(),
            deferred: None,
            slot_rounds: 0,
            slot_once: 0,
            slot_undone: 0,
            slot_log: Vec::new(),
            slot_runs: Vec::new(),
            supervisor: Default::default(),
            known_map,
            map_from_estimate: ilmr_hal::Pose::default(),
            known,
            move_mode: None,
            mode_ops: Vec::new(),
            end_code: None,
        };
        vm.decoded.grow(&vm.module);
        vm.frames.grow(&vm.module, &vm.decoded.all, vm.cfg.period);
        let main = vm.module.main.index();
        let blocks = vm.module.units[main].blocks.clone();
        // Every top-level block starts now and is queued: room for exactly them,
        // where growing by doubling would leave up to half of it unused.
        vm.nodes.all.reserve_exact(blocks.len());
        vm.ready.reserve_exact(blocks.len());
        for b in blocks {
            vm.start_block(root, b.0, 0);
        }
        Ok(vm)
    }

    /// Runs one tick: reads the robot, wakes timers, steps the movement, the sensors and
    /// every ready block within the budget. See `vm/README.md` for the order.
    pub fn tick(&mut self) {
        self.clock.begin_tick(self.tick, self.cfg.period);
        let t = self.time();
        // A failing robot is recorded and supervised (`robot_link`); the tick goes
        // on with the last snapshot it gave.
        if let Err(e) = self.hal.update(t) {
            self.supervisor.link_failed = true;
            self.error(None, format!("robot update failed: {e}"));
        }
        if let Err(e) = self.hal.snapshot(&mut self.snap) {
            self.supervisor.link_failed = true;
            self.error(None, format!("robot snapshot failed: {e}"));
        }
        self.update_map();
        self.supervise();
        self.start_pending();
        self.fire_timers();
        self.step_motion();
        self.step_recording();
        self.step_active();
        self.step_followers();
        self.run_ready();
        if self.cfg.trace == TraceLevel::Full
            && self.cfg.pose_every > 0
            && self.tick.is_multiple_of(u64::from(self.cfg.pose_every))
        {
            self.pose_event();
        }
        self.tick += 1;
    }

    /// Ticks until the task has ended or `seconds` of logical time have passed;
    /// returns whether the task ended.
    pub fn run_for(&mut self, seconds: f64) -> bool {
        let ticks = (seconds / self.cfg.period).round().max(0.0) as u64;
        for _ in 0..ticks {
            if self.finished() {
                return true;
            }
            self.tick();
        }
        self.finished()
    }

    /// No command is live and nothing waits to start.
    pub fn finished(&self) -> bool {
        self.nodes.get(self.root).children == 0 && self.pending.is_empty()
    }

    /// What is still live; see [`Activity`]. Costs nothing per live command.
    pub fn activity(&self) -> Activity {
        let c = &self.nodes.classes;
        let running_movement = usize::from(self.motion.head.is_some_and(|h| self.nodes.alive(h)));
        Activity {
            running_commands: c[Class::Active as usize]
                + c[Class::Endless as usize]
                + running_movement,
            endless_readings: c[Class::Endless as usize],
            queued_movements: c[Class::Movement as usize].saturating_sub(running_movement),
            waiting_guards: c[Class::Guard as usize],
            sleeping: c[Class::Sleep as usize],
            issuing_blocks: c[Class::Issuing as usize],
            ready: self.ready.len() + self.pending.len(),
            robot_at_rest: self.snap.speed.abs() < REST_SPEED
                && self.motion.commanded_speed().abs() < REST_SPEED,
        }
    }

    /// The statements of the live commands, guards, loops and skill calls (blocks
    /// have none), sorted, one entry per live node: what a status view lists. Walks
    /// the node arena, so it is for occasional queries, not for every tick.
    pub fn live_statements(&self) -> Vec<StmtId> {
        let mut live = Vec::new();
        for n in &self.nodes.all {
            match n.kind {
                Kind::Free | Kind::Root => {}
                Kind::Block(b) if b.holder == nodes::SLEEPING => live.extend(self.sleep_stmt(&b)),
                Kind::Block(_) => {}
                Kind::Frame(f) => self.frame_statements(&f, &mut live),
                _ => live.extend(stmt_of(n.stmt)),
            }
        }
        live.sort_unstable_by_key(|s| s.0);
        live
    }

    /// Nothing is left but waiting `if` guards and the robot is at rest (the guide's
    /// end of a run); [`Vm::finished`] is the stricter "nothing is left at all".
    pub fn only_guards_waiting(&self) -> bool {
        self.activity().only_guards_waiting()
    }

    /// The supervisor's faults in force, most urgent first (what `sensor(supervisor)`
    /// reads is the first's number).
    pub fn faults_in_force(&self) -> Vec<safety::Fault> {
        let mut faults: Vec<safety::Fault> = safety::FAULTS
            .into_iter()
            .filter(|f| self.supervisor.is_active(*f))
            .collect();
        faults.sort_by_key(|f| std::cmp::Reverse(f.urgency()));
        faults
    }

    /// Logical time of the current tick, seconds.
    pub fn time(&self) -> f64 {
        self.tick as f64 * self.cfg.period
    }

    pub fn ticks(&self) -> u64 {
        self.tick
    }

    /// Ticks whose ready queue ran in one go, each frame's visits one after the
    /// other, because no one could tell the order from the tree's (`Vm::run_round`
    /// in `frame.rs`; docs/performance.md, issue 14, session 12).
    pub fn rounds_fused(&self) -> u64 {
        self.rounds_fused
    }

    /// Frames whose visits of a round run in one go ran as one step along their
    /// plan (`Vm::run_plan` in `frame.rs`).
    pub fn plans_run(&self) -> u64 {
        self.plans_run
    }

    /// Nodes (live or free places of the arena) that `break(pattern)` has looked at: a
    /// break whose pattern no live statement can hold looks at none.
    pub fn break_looks(&self) -> u64 {
        self.break_looks
    }

    /// Rounds run in one go straight from the timer wheel's due slot, without
    /// the ready queue (`Vm::run_slot_round` in `frame/slot.rs`).
    pub fn slot_rounds(&self) -> u64 {
        self.slot_rounds
    }

    /// Of [`Vm::slot_rounds`], the rounds run in one pass over the alarms
    /// (`Vm::run_slot_once` in `frame/slot.rs`).
    pub fn slot_once(&self) -> u64 {
        self.slot_once
    }

    /// Rounds the one pass over the alarms began, found it could not finish and
    /// took back, for the look ahead to take (`Vm::run_slot_once`).
    pub fn slot_undone(&self) -> u64 {
        self.slot_undone
    }

    /// Live nodes: commands, guards, loops, calls and blocks.
    pub fn live(&self) -> usize {
        (self.nodes.live + self.nodes.sleepers).saturating_sub(1)
    }

    /// Bytes held by the run-time state (nodes, variables, subscriptions, queues,
    /// timers), not counting the module or the trace.
    pub fn footprint(&self) -> usize {
        self.footprint_parts().iter().map(|(_, bytes)| bytes).sum()
    }

    /// [`Vm::footprint`] part by part: what a live block costs, and where.
    pub fn footprint_parts(&self) -> [(&'static str, usize); 6] {
        use std::mem::size_of;
        [
            (
                "nodes",
                self.nodes.footprint()
                    + self.frame_iters.capacity() * size_of::<[u32; frame::MAX_LOOPS]>(),
            ),
            ("variables", self.vars.footprint()),
            (
                "ready queue",
                self.ready.capacity() * size_of::<exec::Packed>()
                    + self.round_planned.capacity() * size_of::<u64>()
                    + self.slot_log.capacity() * size_of::<f64>()
                    + self.slot_runs.capacity() * size_of::<(u32, u32)>(),
            ),
            ("timers", self.timers.footprint()),
            (
                "active commands",
                self.active.capacity() * size_of::<Active>()
                    + self.followers.capacity() * size_of::<Follower>(),
            ),
            (
                "wake buffer",
                self.woken.capacity() * size_of::<vars::Woken>(),
            ),
        ]
    }

    pub fn module(&self) -> &Module {
        &self.module
    }

    pub fn hal(&self) -> &H {
        &self.hal
    }

    pub fn hal_mut(&mut self) -> &mut H {
        &mut self.hal
    }

    pub fn clock(&self) -> &C {
        &self.clock
    }

    pub fn config(&self) -> &Config {
        &self.cfg
    }

    /// What `sensor(supervisor)` reads now: the number of the most urgent active
    /// fault, 0 when there is none (`docs/reliability.md`).
    pub fn supervisor_reading(&self) -> f64 {
        self.supervisor.reading()
    }

    /// Whether a supervisor fault is active now.
    pub fn fault_active(&self, fault: safety::Fault) -> bool {
        self.supervisor.is_active(fault)
    }

    /// A variable by name (any letter case).
    pub fn var(&self, name: &str) -> Option<VarRecord> {
        self.module.find_global(name).map(|v| self.vars.get(v.0))
    }

    /// Every global variable with its record, in the module's order: a walk over all
    /// of them without a lookup by name each, which [`Vm::var`] makes.
    pub fn globals(&self) -> impl Iterator<Item = (&Global, VarRecord)> + '_ {
        (0u32..)
            .zip(&self.module.globals)
            .map(|(id, g)| (g, self.vars.get(id)))
    }

    pub fn events(&self) -> &[Event] {
        &self.events
    }

    pub fn take_events(&mut self) -> Vec<Event> {
        std::mem::take(&mut self.events)
    }

    /// Named paths (`record`, `createpath`, or taught beforehand).
    pub fn paths(&self) -> &BTreeMap<String, Vec<(f64, f64)>> {
        &self.paths
    }

    /// Adds a path taught beforehand, for `followpath(name)`.
    pub fn add_path(&mut self, name: &str, points: Vec<(f64, f64)>) {
        self.paths.insert(name.to_lowercase(), points);
    }

    /// Joins an interactive line (compiled with `ModuleBuilder::extending` against this
    /// VM's module) as new top-level blocks; they start at the next tick.
    pub fn add_block(&mut self, fragment: &Fragment) -> Result<(), VmError> {
        self.module.append(fragment).map_err(VmError::Module)?;
        self.joined(fragment.start.iter().map(|b| b.0));
        Ok(())
    }

    /// Lowers an interactive line straight into the live module: `lower` gets a
    /// builder that owns this VM's module (moved, not copied), appends the line and
    /// returns the blocks to start. Only what it added is validated; on any error the
    /// module is as it was. The cost is the line's, not the program's: this is the
    /// fast form of `ModuleBuilder::extending` + `finish_fragment` + [`Vm::add_block`],
    /// which copies the module twice.
    ///
    /// `lower` must leave the builder it is given in place (a lowering that takes it
    /// by value with `std::mem::take` puts it back); a replaced builder is refused
    /// with [`LineError::Replaced`] and leaves the VM without its program.
    pub fn add_line<E>(
        &mut self,
        lower: impl FnOnce(&mut ModuleBuilder) -> Result<Vec<BlockId>, E>,
    ) -> Result<(), LineError<E>> {
        let base = self.module.counts();
        let live = std::mem::replace(&mut self.module, ModuleBuilder::new().into_extended().0);
        let mut b = ModuleBuilder::lent(live);
        let lowered = lower(&mut b);
        let (module, lent) = b.into_extended();
        self.module = module;
        if lent != Some(base) {
            return Err(LineError::Replaced);
        }
        let start = match lowered {
            Ok(start) => start,
            Err(e) => {
                self.module.truncate(&base);
                return Err(LineError::Lower(e));
            }
        };
        let checked = self.module.validate_from(&base).and_then(|()| {
            match start.iter().find(|b| b.index() >= self.module.blocks.len()) {
                Some(b) => Err(ModuleError::Index {
                    what: "line start block",
                    index: b.0,
                    len: self.module.blocks.len(),
                }),
                None => Ok(()),
            }
        });
        if let Err(e) = checked {
            self.module.truncate(&base);
            return Err(LineError::Invalid(e));
        }
        self.joined(start.iter().map(|b| b.0));
        Ok(())
    }

    /// The module grew: size the variables to it, and queue
    /// the new top-level blocks.
    fn joined(&mut self, start: impl Iterator<Item = u32>) {
        self.vars.grow(self.module.globals.len());
        self.decoded.grow(&self.module);
        self.frames
            .grow(&self.module, &self.decoded.all, self.cfg.period);
        self.pending.extend(start);
    }

    /// Lets lines start although a `priority = highest` block runs: for an operator's
    /// emergency stop, which is above the task's own priorities. The block runs on;
    /// the lines held back start at the next tick, in the order they came.
    pub fn lift_priority(&mut self) -> bool {
        self.priority.take().is_some_and(|p| self.nodes.alive(p))
    }

    fn start_pending(&mut self) {
        if self.pending.is_empty() {
            return;
        }
        if let Some(p) = self.priority {
            if self.nodes.alive(p) {
                return;
            }
            self.priority = None;
        }
        let pending = std::mem::take(&mut self.pending);
        for b in pending {
            self.start_block(self.root, b, 0);
        }
    }

    fn fire_timers(&mut self) {
        let due = self.timers.due(self.tick);
        if !due.is_empty() && self.defer_alarms() {
            self.deferred = Some(due);
            return;
        }
        self.wake_alarms(&due);
        self.timers.done(due);
    }

    /// Whether this tick's due alarms may wait for `run_ready` to wake them: with
    /// the trace off, nothing queued, and nothing that `step_motion`, `step_active`
    /// or `step_followers` could run (no movement, no stepped command, no follower),
    /// so that no node ends, no variable is written and nothing is queued between
    /// the two, and nothing can tell frames still asleep from frames woken.
    fn defer_alarms(&self) -> bool {
        !self.tracing()
            && self.cfg.frames
            && self.ready.is_empty()
            && self.motion.head.is_none()
            && self.active.is_empty()
            && self.followers.is_empty()
    }

    /// Wakes alarms `due` in order: what `fire_timers` does with a tick's alarms.
    fn wake_alarms(&mut self, due: &[timers::Alarm]) {
        for a in due {
            if self.wake_frame(a) {
                continue;
            }
            if self.nodes.asleep(a.node, a.nap) {
                self.end_sleep(a.node.idx, vars::How::Completed);
                self.enqueue(a.node.idx);
            }
        }
    }

    /// The alarms `fire_timers` left (`Vm::defer_alarms`): a round run straight
    /// from them if it can be (`Vm::run_slot_round`); otherwise woken now, their
    /// entries before anything queued since, where waking them in `fire_timers`
    /// would have put them. Returns true when the round ran and nothing is left.
    fn run_deferred(&mut self) -> bool {
        let Some(due) = self.deferred.take() else {
            return false;
        };
        let Err(due) = self.run_slot_round(due) else {
            return true;
        };
        let since = self.ready.len();
        self.wake_alarms(&due);
        self.ready.rotate_left(since);
        self.timers.done(due);
        false
    }

    fn step_followers(&mut self) {
        for i in 0..self.followers.len() {
            let f = self.followers[i];
            if let Ok(Some(v)) = self.read_sensor(f.spec) {
                self.write_fields(
                    f.var,
                    &[(ilmr_stdlib::Field::Value, v)],
                    None,
                    f.stmt,
                    false,
                );
            }
        }
    }

    fn step_recording(&mut self) {
        let Some(rec) = self.recording.as_mut() else {
            return;
        };
        let p = self.snap.pose;
        if (p.x - rec.last.0).hypot(p.y - rec.last.1) >= self.cfg.record_spacing {
            rec.last = (p.x, p.y);
            let key = rec.path.clone();
            self.paths.entry(key).or_default().push((p.x, p.y));
        }
    }

    /// Traces the pose the last tick read, unless that tick's pose sample did: a run
    /// that ends between samples still ends on the pose it stopped at.
    pub fn trace_last_pose(&mut self) {
        let Some(last) = self.tick.checked_sub(1) else {
            return;
        };
        let every = u64::from(self.cfg.pose_every);
        if self.cfg.trace != TraceLevel::Full || (every > 0 && last.is_multiple_of(every)) {
            return;
        }
        let kind = self.pose_now();
        self.events
            .push(Event::new(last, last as f64 * self.cfg.period, None, kind));
    }

    fn pose_event(&mut self) {
        let kind = self.pose_now();
        self.push_event(None, kind);
    }

    fn pose_now(&self) -> EventKind {
        let (pose, truth) = match self.snap.true_pose {
            Some(p) => (p, true),
            None => (self.snap.pose, false),
        };
        EventKind::Pose {
            x: pose.x,
            y: pose.y,
            h: pose.h,
            speed: self.snap.speed,
            curvature: self.snap.curvature,
            truth,
        }
    }

    /// Whether events are recorded: callers that must build an event test it first,
    /// so that with the trace off the event is never made.
    #[inline]
    fn tracing(&self) -> bool {
        self.cfg.trace != TraceLevel::Off
    }

    /// Inlined so that, with the trace off, a statement pays one comparison for it.
    #[inline]
    fn push_event(&mut self, stmt: Option<StmtId>, kind: EventKind) {
        if self.cfg.trace == TraceLevel::Off {
            return;
        }
        self.record_event(stmt, kind);
    }

    #[inline(never)]
    fn record_event(&mut self, stmt: Option<StmtId>, kind: EventKind) {
        let e = Event::new(self.tick, self.time(), stmt, kind);
        self.coalesce.push(&mut self.events, e);
    }

    fn error(&mut self, stmt: Option<StmtId>, message: String) {
        self.push_event(stmt, EventKind::Error { message });
    }
}

fn stmt_of(stmt: u32) -> Option<StmtId> {
    (stmt != NONE).then_some(StmtId(stmt))
}

//! The VM: a tree of live commands stepped at 100 Hz. See `vm/README.md` for the order
//! of a tick and `docs/bytecode.md` for the instructions.

pub mod clock;
mod commands;
pub mod config;
mod exec;
mod motion;
mod nodes;
pub mod trace;
pub mod vars;

use std::collections::{BTreeMap, BinaryHeap, VecDeque};

use ilmr_hal::{Hal, Snapshot};

use crate::bytecode::{Fragment, Module, ModuleError, StmtId};
use clock::Clock;
use config::{Config, TraceLevel};
use motion::Motion;
use nodes::{Kind, NodeRef, Nodes};
use trace::{Event, EventKind};
use vars::{NONE, VarRecord, Vars};

/// Depth of the expression stack; `Module::validate` rejects deeper expressions.
pub const EXPR_STACK: usize = 32;

/// What a reading variable keeps following after its command
/// ended (`v = sensor(battery)`).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Follower {
    var: u32,
    spec: nodes::SensorSpec,
    /// The reading that started it, for the trace.
    stmt: u32,
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
    ready: VecDeque<NodeRef>,
    /// Nodes stepped every tick (sensors, searches, asynchronous operations).
    active: Vec<NodeRef>,
    /// `(due tick, sequence, node)` in a min-heap; stale entries are skipped.
    timers: BinaryHeap<std::cmp::Reverse<(u64, u64, u32, u32)>>,
    timer_seq: u64,
    motion: Motion,
    followers: Vec<Follower>,
    paths: BTreeMap<String, Vec<(f64, f64)>>,
    recording: Option<Recording>,
    /// The block that ran `priority = highest`, while it lives.
    priority: Option<NodeRef>,
    /// Interactive blocks waiting for a priority block to end.
    pending: Vec<u32>,
    events: Vec<Event>,
    ops_left: u32,
    /// Lower-case statement texts for `break(pattern)`.
    lower: Vec<String>,
    scratch: Vec<u32>,
    stack: [f64; EXPR_STACK],
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

impl<H: Hal, C: Clock> Vm<H, C> {
    /// Validates the module and starts the task's top-level blocks (they run from the
    /// first tick).
    pub fn new(module: Module, hal: H, clock: C, config: Config) -> Result<Vm<H, C>, VmError> {
        module.validate().map_err(VmError::Module)?;
        let mut nodes = Nodes::default();
        let root = nodes.alloc(NONE, NONE, NONE, Kind::Root).idx;
        let lower = module.stmts.iter().map(|s| s.text.to_lowercase()).collect();
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
            active: Vec::new(),
            timers: BinaryHeap::new(),
            timer_seq: 0,
            followers: Vec::new(),
            paths: BTreeMap::new(),
            recording: None,
            priority: None,
            pending: Vec::new(),
            events: Vec::new(),
            ops_left: 0,
            lower,
            scratch: Vec::new(),
            stack: [0.0; EXPR_STACK],
        };
        let main = vm.module.main.index();
        let blocks = vm.module.units[main].blocks.clone();
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
        if let Err(e) = self.hal.update(t) {
            self.error(None, format!("robot update failed: {e}"));
        }
        if let Err(e) = self.hal.snapshot(&mut self.snap) {
            self.error(None, format!("robot snapshot failed: {e}"));
        }
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

    /// Logical time of the current tick, seconds.
    pub fn time(&self) -> f64 {
        self.tick as f64 * self.cfg.period
    }

    pub fn ticks(&self) -> u64 {
        self.tick
    }

    /// Live nodes: commands, guards, loops, calls and blocks.
    pub fn live(&self) -> usize {
        self.nodes.live.saturating_sub(1)
    }

    /// Bytes held by the run-time state (nodes, variables, subscriptions, queues,
    /// timers), not counting the module or the trace.
    pub fn footprint(&self) -> usize {
        use std::mem::size_of;
        self.nodes.footprint()
            + self.vars.footprint()
            + self.active.capacity() * size_of::<NodeRef>()
            + self.ready.capacity() * size_of::<NodeRef>()
            + self.timers.capacity() * size_of::<(u64, u64, u32, u32)>()
            + self.followers.capacity() * size_of::<Follower>()
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

    /// A variable by name (any letter case).
    pub fn var(&self, name: &str) -> Option<VarRecord> {
        self.module.find_global(name).map(|v| self.vars.get(v.0))
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
        self.vars.grow(self.module.globals.len());
        self.lower.extend(
            self.module.stmts[self.lower.len()..]
                .iter()
                .map(|s| s.text.to_lowercase()),
        );
        self.pending.extend(fragment.start.iter().map(|b| b.0));
        Ok(())
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
        while let Some(std::cmp::Reverse((due, _, idx, epoch))) = self.timers.peek().copied() {
            if due > self.tick {
                break;
            }
            self.timers.pop();
            let r = NodeRef { idx, epoch };
            if self.nodes.alive(r) {
                self.end_node(idx, vars::How::Completed, false, None, true);
            }
        }
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

    fn pose_event(&mut self) {
        let (pose, truth) = match self.snap.true_pose {
            Some(p) => (p, true),
            None => (self.snap.pose, false),
        };
        self.push_event(
            None,
            EventKind::Pose {
                x: pose.x,
                y: pose.y,
                h: pose.h,
                speed: self.snap.speed,
                curvature: self.snap.curvature,
                truth,
            },
        );
    }

    fn push_event(&mut self, stmt: Option<StmtId>, kind: EventKind) {
        if self.cfg.trace == TraceLevel::Off {
            return;
        }
        self.events.push(Event {
            tick: self.tick,
            t: self.time(),
            stmt,
            kind,
        });
    }

    fn error(&mut self, stmt: Option<StmtId>, message: String) {
        self.push_event(stmt, EventKind::Error { message });
    }
}

fn stmt_of(stmt: u32) -> Option<StmtId> {
    (stmt != NONE).then_some(StmtId(stmt))
}

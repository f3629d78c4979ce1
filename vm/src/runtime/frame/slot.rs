//! A round run straight from the timer wheel's due slot. When a tick's ready queue
//! would hold nothing but the frames its alarms wake, the alarms are that queue in
//! its order: `Vm::run_round` would find every entry pushed by `fire_timers`, read
//! it in its look ahead and pop it again, looking at the frame's node each time.
//! Here the round reads the due alarms twice, once to show it is safe (the
//! conditions of `Vm::run_round`, and those of `Vm::wake_frame` for each alarm) and
//! once to wake and run each frame, with no queue entry made. What it leaves is
//! what waking the alarms and running the queue would leave.
//!
//! Both passes take the frames of one pc (a million counting blocks share one)
//! as a batch, as Lua runs one function's code for every coroutine: what the pc's
//! plan needs (its checks, its writes, its sleep) is read once per run of equal
//! pcs, not once per frame. Where every woken frame runs along a plan, the new
//! alarms for the first tick they set are written back into the due slot's own
//! buffer, each over an alarm already read, and the buffer becomes that tick's
//! slot: what setting them one by one into the empty slot would leave.

use ilmr_hal::Hal;
use ilmr_stdlib::Field;

use super::super::Vm;
use super::super::clock::Clock;
use super::super::nodes::{Class, Kind, Node, NodeRef};
use super::super::timers::Alarm;
use super::super::vars::{Core, NONE};
use super::super::watch::Cmp;
use super::{Arith, FrameState, Moved, PLAN_STEPS, Quick, trace_ahead};

/// A variable of a pc's plan, for the frames at it: `var_at(id, base)` as
/// `(base & mask) + id`, the mark read once per pc.
#[derive(Clone, Copy)]
struct Slot {
    mask: u32,
    id: u32,
}

impl Slot {
    fn of(id: u32) -> Slot {
        Slot {
            mask: (id >> 31).wrapping_sub(1),
            id: id & !super::ABSOLUTE,
        }
    }

    #[inline(always)]
    fn at(self, base: u32) -> u32 {
        (base & self.mask).wrapping_add(self.id)
    }
}

/// What the look ahead needs of a pc, read once for the frames at it.
struct Ahead {
    pc: u32,
    span: u32,
    /// The plan's visits; 0 where the pc has none.
    visits: u32,
    ops: u32,
    /// The plan ends in a sleep, so a frame is run along it as one step.
    runs: bool,
    checks: [(Slot, Field, Cmp, f64); 2],
    nchecks: usize,
    writes: [Slot; 2],
    nwrites: usize,
}

impl Ahead {
    /// None where a frame at `pc` is not woken by `Vm::wake_frame` (its sleep
    /// binds a variable) or names variables below its base.
    fn of(frames: &super::Frames, pc: u32) -> Option<Ahead> {
        let unbound = pc
            .checked_sub(1)
            .and_then(|p| frames.quick.get(p as usize))
            .is_some_and(|w| matches!(w, Quick::Sleep { .. }));
        let span = *frames.spans.get(pc as usize)?;
        if !unbound || span == NONE {
            return None;
        }
        let plan = frames.plans.get(pc as usize).copied().unwrap_or_default();
        let mut checks = [(Slot::of(0), Field::Value, Cmp::Truthy, 1.0); 2];
        let mut nchecks = 0;
        for c in plan.checks {
            if let Some(&Quick::CheckVK {
                src, field, cmp, k, ..
            }) = frames.quick.get(c as usize)
            {
                checks[nchecks] = (Slot::of(src), field, cmp, k);
                nchecks += 1;
            } else {
                break;
            }
        }
        let mut writes = [Slot::of(0); 2];
        let mut nwrites = 0;
        for w in plan.writes {
            if w == NONE {
                break;
            }
            writes[nwrites] = Slot::of(w);
            nwrites += 1;
        }
        let runs = plan.sleep != 0
            && matches!(
                frames.quick.get(plan.sleep as usize),
                Some(Quick::Sleep { .. })
            );
        Some(Ahead {
            pc,
            span,
            visits: u32::from(plan.visits),
            ops: plan.ops,
            runs,
            checks,
            nchecks,
            writes,
            nwrites,
        })
    }
}

/// A write of a plan: `var = src.field op k`, or `var = k` (`src` None).
#[derive(Clone, Copy)]
struct Write {
    var: Slot,
    src: Option<(Slot, Field, Arith)>,
    k: f64,
}

/// What the run needs of a pc whose frames go along its plan, read once for them.
struct Run {
    pc: u32,
    ops: u32,
    ends: bool,
    moved: Moved,
    sleep: u32,
    ticks: u32,
    steps: [Write; PLAN_STEPS],
    nsteps: usize,
}

impl Run {
    fn of(frames: &super::Frames, pc: u32) -> Run {
        let plan = frames.plans[pc as usize];
        let Some(&Quick::Sleep { ticks, .. }) = frames.quick.get(plan.sleep as usize) else {
            unreachable!("the look ahead saw a plan that ends in a sleep");
        };
        let none = Write {
            var: Slot::of(0),
            src: None,
            k: 0.0,
        };
        let mut steps = [none; PLAN_STEPS];
        let mut nsteps = 0;
        for s in plan.steps {
            steps[nsteps] = match frames.quick.get(s as usize) {
                Some(&Quick::SetVK {
                    var,
                    src,
                    field,
                    op,
                    k,
                    ..
                }) => Write {
                    var: Slot::of(var),
                    src: Some((Slot::of(src), field, op)),
                    k,
                },
                Some(&Quick::SetK { var, k, .. }) => Write {
                    var: Slot::of(var),
                    src: None,
                    k,
                },
                _ => break,
            };
            nsteps += 1;
        }
        Run {
            pc,
            ops: plan.ops,
            ends: plan.ends,
            moved: plan.moved,
            sleep: plan.sleep,
            ticks,
            steps,
            nsteps,
        }
    }
}

/// A pc's plan as [`Vm::run_slot_once`] runs a batch of frames at it: checks and
/// writes on variables' status and value only (every quick form's field but a
/// pose's), so that a frame's step reads the dense records directly, with no
/// `match` on a field or a lookup of who hears a variable.
struct Kernel {
    pc: u32,
    span: u32,
    ops: u32,
    /// (variable, reads its status rather than its value, comparison, constant).
    checks: [(Slot, bool, Cmp, f64); 2],
    nchecks: usize,
    writes: [Slot; 2],
    nwrites: usize,
    steps: [KStep; PLAN_STEPS],
    nsteps: usize,
    next_pc: u32,
    moved: Moved,
}

/// A length of [`Kernel::batch_of`] read from the plan.
const ANY: usize = usize::MAX;

/// A write of a [`Kernel`]: the variable written, what it reads (variable,
/// its status rather than its value, operator), the constant.
type KStep = (Slot, Option<(Slot, bool, Arith)>, f64);

/// Reads `field` of a dense record: None for a field the kernel does not take.
fn dense_field(field: Field) -> Option<bool> {
    match field {
        Field::Value => Some(false),
        Field::Status => Some(true),
        _ => None,
    }
}

impl Kernel {
    fn of(ahead: &Ahead, run: &Run) -> Option<Kernel> {
        let mut checks = [(Slot::of(0), false, Cmp::Truthy, 0.0); 2];
        for (c, &(src, field, cmp, k)) in checks.iter_mut().zip(&ahead.checks[..ahead.nchecks]) {
            *c = (src, dense_field(field)?, cmp, k);
        }
        let mut steps = [(Slot::of(0), None, 0.0); PLAN_STEPS];
        for (s, w) in steps.iter_mut().zip(&run.steps[..run.nsteps]) {
            let src = match w.src {
                Some((src, field, op)) => Some((src, dense_field(field)?, op)),
                None => None,
            };
            *s = (w.var, src, w.k);
        }
        Some(Kernel {
            pc: ahead.pc,
            span: ahead.span,
            ops: run.ops,
            checks,
            nchecks: ahead.nchecks,
            writes: ahead.writes,
            nwrites: ahead.nwrites,
            steps,
            nsteps: run.nsteps,
            next_pc: run.sleep + 1,
            moved: run.moved,
        })
    }

    /// Runs the frames of `due` from `i` on while each is at this pc and meets
    /// the one pass's conditions on its own (above `free` and `floor`, the
    /// budget enough, the checks true, the variables it writes of status 1),
    /// as the general step of [`Vm::run_slot_once`] would run it; skips stale
    /// alarms. Returns the index of the first alarm it leaves to that step.
    /// Its own function so that the slices, borrowed apart, stay in registers.
    #[inline(never)]
    #[allow(clippy::too_many_arguments)]
    fn batch(
        &self,
        due: &mut [Alarm],
        i: usize,
        kept: &mut usize,
        all: &mut [Node],
        dense: (&mut [Core], u32),
        free: &mut u32,
        ops_left: &mut u32,
        log: &mut Vec<f64>,
        live: &mut usize,
        classes: &mut [usize; Class::COUNT],
    ) -> usize {
        // A loop of one check and one write (`while(c<100)`, `c=c+1`, `wait`, the
        // common loop) with its lengths known, so that the per-frame loops over
        // the checks and writes unroll; any other plan, the lengths read.
        match (self.nchecks, self.nwrites, self.nsteps) {
            (1, 1, 1) => self
                .batch_of::<1, 1, 1>(due, i, kept, all, dense, free, ops_left, log, live, classes),
            _ => self.batch_of::<ANY, ANY, ANY>(
                due, i, kept, all, dense, free, ops_left, log, live, classes,
            ),
        }
    }

    /// [`Kernel::batch`] for plans of `C` checks, `W` variables written and `S`
    /// writes ([`ANY`]: as many as the plan has).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn batch_of<const C: usize, const W: usize, const S: usize>(
        &self,
        due: &mut [Alarm],
        mut i: usize,
        kept: &mut usize,
        all: &mut [Node],
        (cores, floor): (&mut [Core], u32),
        free: &mut u32,
        ops_left: &mut u32,
        log: &mut Vec<f64>,
        live: &mut usize,
        classes: &mut [usize; Class::COUNT],
    ) -> usize {
        let (nchecks, nwrites, nsteps) = (
            if C == ANY { self.nchecks } else { C },
            if W == ANY { self.nwrites } else { W },
            if S == ANY { self.nsteps } else { S },
        );
        // In locals for the loop, written back once: stores through the
        // references each frame cost as much as a check.
        let (mut free_at, mut ops, mut kept_at) = (*free, *ops_left, *kept);
        let read = |cores: &[Core], v: u32, status: bool| {
            cores
                .get(v as usize)
                .map_or(0.0, |c| if status { c.status } else { c.value })
        };
        'frames: while let Some(&a) = due.get(i) {
            let Some(n) = all.get_mut(a.node.idx as usize) else {
                i += 1;
                continue;
            };
            if n.epoch != a.node.epoch {
                i += 1;
                continue;
            }
            let f = match &mut n.kind {
                Kind::Frame(f) => f,
                Kind::Free => {
                    i += 1;
                    continue;
                }
                _ => break 'frames,
            };
            if !f.asleep || f.nap != a.nap {
                i += 1;
                continue;
            }
            let base = f.base;
            if n.queued || f.parked || f.pc != self.pc || base < free_at || base < floor {
                break 'frames;
            }
            if ops < self.ops {
                break 'frames;
            }
            for &(src, status, cmp, k) in &self.checks[..nchecks] {
                if !cmp.holds(read(cores, src.at(base), status), k) {
                    break 'frames;
                }
            }
            for w in &self.writes[..nwrites] {
                let plain = cores
                    .get(w.at(base) as usize)
                    .is_some_and(|c| c.status.to_bits() == 1.0f64.to_bits());
                if !plain {
                    break 'frames;
                }
            }
            free_at = base.saturating_add(self.span);
            ops -= self.ops;
            for &(var, src, k) in &self.steps[..nsteps] {
                let v = match src {
                    Some((src, status, op)) => op.apply(read(cores, src.at(base), status), k),
                    None => k,
                };
                // In range: every step writes one of `writes`, found above.
                let old = match cores.get_mut(var.at(base) as usize) {
                    Some(c) => std::mem::replace(&mut c.value, v),
                    None => 0.0,
                };
                log.push(old);
            }
            f.pc = self.next_pc;
            f.nap = f.nap.wrapping_add(1);
            due[kept_at] = Alarm {
                node: a.node,
                nap: f.nap,
            };
            kept_at += 1;
            super::move_counts(self.moved, live, classes);
            i += 1;
        }
        (*free, *ops_left, *kept) = (free_at, ops, kept_at);
        i
    }
}

/// What the look ahead found of the round: its ops, whether any frame takes its
/// quick forms, and whether any frame wakes at all.
struct Look {
    ops: u64,
    quick: bool,
    woken: bool,
}

impl<H: Hal, C: Clock> Vm<H, C> {
    /// Runs this tick's round straight from its due alarms `due`, each woken
    /// frame's visits one after the other, as `Vm::run_round` runs a queue of the
    /// entries waking them would have pushed. Gives `due` back, having done
    /// nothing, unless, with nothing queued, every alarm is stale or wakes a frame
    /// as `Vm::wake_frame` would and those frames meet `Vm::run_round`'s conditions
    /// (each reaches its next sleep on quick forms, the variables each names lie
    /// above the last one's and nothing hears them, the visits do not fall along
    /// the alarms, the budget covers every op).
    pub(in crate::runtime) fn run_slot_round(
        &mut self,
        mut due: Vec<Alarm>,
    ) -> Result<(), Vec<Alarm>> {
        if self.tracing() || !self.ready.is_empty() {
            return Err(due);
        }
        if self.run_slot_once(&mut due) {
            return Ok(());
        }
        let look = self.look_at_slot(&mut due);
        let Some(look) = look.filter(|l| l.ops <= u64::from(self.ops_left)) else {
            return Err(due);
        };
        if look.woken {
            // What waking them spends (`end_sleep`'s end code).
            self.end_code = None;
            self.rounds_fused += 1;
            self.slot_rounds += 1;
        }
        if look.quick {
            for a in &due {
                self.wake_in_round(a.node);
                let Kind::Frame(f) = &self.nodes.all[a.node.idx as usize].kind else {
                    continue;
                };
                // What the look ahead found: the frames before this one wrote
                // their own variables only, so it finds it again.
                let along = self
                    .frames
                    .foresee(&self.vars, f)
                    .is_some_and(|(_, _, along)| along);
                if !(along && self.run_plan(a.node.idx)) {
                    self.run_quick::<true>(a.node.idx);
                }
            }
            self.timers.done(due);
        } else {
            self.run_slot_along(due);
        }
        Ok(())
    }

    /// The round of [`Vm::run_slot_along`] in one pass over the due alarms `due`,
    /// without the look ahead: each frame is shown to meet the look ahead's
    /// conditions and run along its plan at once, the values it overwrites kept in
    /// `slot_log`. It asks a little more than the look ahead, so that what it did
    /// can be taken back exactly: every woken frame goes along a plan ending in a
    /// sleep, all of them to one tick whose slot was empty (their alarms written
    /// over the ones read), and each variable written is [`Vars::plain`] (an
    /// assignment writes its value only). Where a frame shows the round cannot be
    /// run so, everything done is undone in reverse (values, pcs, naps, alarms,
    /// counts, budget) and `due` is left as the alarms it held, less stale ones,
    /// for the look ahead to take: returns false. Frames before it wrote only
    /// their own variables, which lie below its own, so it reads and hears what it
    /// would have after the look ahead, and each check sees what it would.
    ///
    /// [`Vars::plain`]: super::super::vars::Vars::plain
    fn run_slot_once(&mut self, due: &mut Vec<Alarm>) -> bool {
        let Vm {
            nodes,
            vars,
            timers,
            frames,
            ops_left,
            end_code,
            tick,
            slot_log,
            slot_runs,
            ..
        } = self;
        let super::super::nodes::Nodes {
            all, live, classes, ..
        } = nodes;
        let saved = (*ops_left, *end_code, *live, *classes);
        slot_log.clear();
        slot_runs.clear();
        let tick = *tick;
        let (mut visits, mut free) = (0u32, 0u32);
        // The tick every new alarm is for, decided at the first run of frames.
        let mut into: Option<u64> = None;
        let mut kept = 0usize;
        let mut at: Option<(Ahead, Run, Option<Kernel>)> = None;
        let mut failed = None;
        slot_log.reserve(due.len());
        let mut i = 0;
        while i < due.len() {
            // The frames at the current pc in a batch, where its plan is a
            // kernel's; the general step below takes the alarm it stops at.
            if let Some((_, _, Some(kernel))) = &at {
                i = kernel.batch(
                    due,
                    i,
                    &mut kept,
                    all,
                    vars.dense(),
                    &mut free,
                    ops_left,
                    slot_log,
                    live,
                    classes,
                );
                if i >= due.len() {
                    break;
                }
            }
            let a = due[i];
            i += 1;
            let Some(n) = all.get_mut(a.node.idx as usize) else {
                continue;
            };
            if n.epoch != a.node.epoch {
                continue;
            }
            let f = match &mut n.kind {
                Kind::Frame(f) => f,
                Kind::Free => continue,
                _ => {
                    failed = Some(i - 1);
                    break;
                }
            };
            if !f.asleep || f.nap != a.nap {
                continue;
            }
            if n.queued || f.parked {
                failed = Some(i - 1);
                break;
            }
            if at.as_ref().is_none_or(|(h, _, _)| h.pc != f.pc) {
                let Some(ahead) = Ahead::of(frames, f.pc).filter(|h| h.runs && h.visits != 0)
                else {
                    failed = Some(i - 1);
                    break;
                };
                let run = Run::of(frames, f.pc);
                let due_at = tick.saturating_add(u64::from(run.ticks));
                match into {
                    None if timers.empty_slot(due_at) => into = Some(due_at),
                    Some(t) if t == due_at => {}
                    _ => {
                        failed = Some(i - 1);
                        break;
                    }
                }
                if run.ends {
                    *end_code = None;
                }
                slot_runs.push((kept as u32, f.pc));
                let kernel = Kernel::of(&ahead, &run);
                at = Some((ahead, run, kernel));
            }
            let Some((ahead, run, _)) = &at else {
                continue;
            };
            // The look ahead's conditions: variables above the last frame's,
            // visits in the queue's order, the checks true, the writes unheard
            // (and plain, to be taken back), the budget enough.
            let base = f.base;
            let holds = base >= free
                && ahead.visits >= visits
                && *ops_left >= run.ops
                && ahead.checks[..ahead.nchecks]
                    .iter()
                    .all(|&(src, field, cmp, k)| cmp.holds(vars.field(src.at(base), field), k))
                && ahead.writes[..ahead.nwrites].iter().all(|w| {
                    let v = w.at(base);
                    vars.quiet(v) && vars.plain(v)
                });
            if !holds {
                failed = Some(i - 1);
                break;
            }
            free = base.saturating_add(ahead.span);
            visits = ahead.visits;
            *ops_left -= run.ops;
            for w in &run.steps[..run.nsteps] {
                let v = match w.src {
                    Some((src, field, op)) => op.apply(vars.field(src.at(base), field), w.k),
                    None => w.k,
                };
                slot_log.push(vars.swap_value(w.var.at(base), v));
            }
            f.pc = run.sleep + 1;
            f.nap = f.nap.wrapping_add(1);
            due[kept] = Alarm {
                node: a.node,
                nap: f.nap,
            };
            kept += 1;
            super::move_counts(run.moved, live, classes);
        }
        if let Some(i) = failed {
            // Back to where the round began, latest first.
            for k in (0..kept).rev() {
                let r = slot_runs.partition_point(|&(first, _)| first as usize <= k) - 1;
                let pc = slot_runs[r].1;
                let run = Run::of(frames, pc);
                let a = &mut due[k];
                let Some(Kind::Frame(f)) = all.get_mut(a.node.idx as usize).map(|n| &mut n.kind)
                else {
                    unreachable!("a frame the round ran");
                };
                for w in run.steps[..run.nsteps].iter().rev() {
                    let old = slot_log.pop().expect("one value per write");
                    vars.swap_value(w.var.at(f.base), old);
                }
                f.pc = pc;
                f.nap = f.nap.wrapping_sub(1);
                a.nap = f.nap;
            }
            (*ops_left, *end_code, *live, *classes) = saved;
            due.drain(kept..i);
            self.slot_undone += u64::from(kept > 0);
            return false;
        }
        if kept > 0 {
            // What waking them spends (`end_sleep`'s end code).
            *end_code = None;
            self.rounds_fused += 1;
            self.slot_rounds += 1;
            self.slot_once += 1;
        }
        self.plans_run += kept as u64;
        let due = std::mem::take(due);
        match into {
            Some(t) if kept > 0 => {
                let mut due = due;
                due.truncate(kept);
                self.timers.adopt(t, due);
            }
            _ => self.timers.done(due),
        }
        true
    }

    /// The look ahead over the due alarms: None where the round cannot be run
    /// from the slot. Stale alarms, which neither way wakes, are taken out of
    /// `due` as it goes, so that what it leaves are the frames to wake, in order.
    fn look_at_slot(&self, due: &mut Vec<Alarm>) -> Option<Look> {
        let (mut ops, mut visits, mut free) = (0u64, 0u32, 0u32);
        let mut look = Look {
            ops: 0,
            quick: false,
            woken: false,
        };
        let mut at: Option<Ahead> = None;
        let mut kept = 0;
        for i in 0..due.len() {
            let a = due[i];
            let Some(n) = self.nodes.all.get(a.node.idx as usize) else {
                continue;
            };
            if n.epoch != a.node.epoch {
                continue;
            }
            let f = match &n.kind {
                Kind::Frame(f) => f,
                Kind::Free => continue,
                // A block asleep in place: the general wake-up takes it.
                _ => return None,
            };
            if !f.asleep || f.nap != a.nap {
                continue;
            }
            if n.queued || f.parked {
                return None;
            }
            if at.as_ref().is_none_or(|h| h.pc != f.pc) {
                at = Some(Ahead::of(&self.frames, f.pc)?);
            }
            let Some(ahead) = &at else {
                continue;
            };
            if f.base < free {
                return None;
            }
            free = f.base.saturating_add(ahead.span);
            let (v, o, quick) = self.foresee_at(ahead, f)?;
            if v < visits {
                return None;
            }
            visits = v;
            ops += u64::from(o);
            look.quick |= quick;
            due[kept] = a;
            kept += 1;
        }
        due.truncate(kept);
        look.woken = kept > 0;
        look.ops = ops;
        Some(look)
    }

    /// `Frames::foresee` for frame `f` at `ahead`'s pc, with the plan's checks and
    /// writes read once for the pc: visits, ops and how the run takes the frame.
    #[inline(always)]
    fn foresee_at(&self, ahead: &Ahead, f: &FrameState) -> Option<(u32, u32, bool)> {
        let holds = ahead.visits != 0
            && ahead.checks[..ahead.nchecks]
                .iter()
                .all(|&(src, field, cmp, k)| cmp.holds(self.vars.field(src.at(f.base), field), k));
        if !holds {
            let (v, o) = trace_ahead(&self.frames, &self.vars, f)?;
            return Some((v, o, true));
        }
        for w in &ahead.writes[..ahead.nwrites] {
            if !self.vars.quiet(w.at(f.base)) {
                return None;
            }
        }
        Some((ahead.visits, ahead.ops, !ahead.runs))
    }

    /// Frame `r`, asleep and due, woken as `Vm::wake_frame` wakes it, its node not
    /// queued: the round takes it at once.
    fn wake_in_round(&mut self, r: NodeRef) {
        if let Kind::Frame(f) = &mut self.nodes.all[r.idx as usize].kind {
            f.asleep = false;
            let sleep = &mut self.nodes.classes[super::Class::Sleep as usize];
            *sleep = sleep.saturating_sub(1);
            self.nodes.sleepers = self.nodes.sleepers.saturating_sub(1);
        }
    }

    /// The run of a round whose woken frames all go along their plans: each is
    /// woken and run as `Along::go` runs it, with the plan read once per run of
    /// frames at one pc. A frame wakes and sleeps again within the step, so the
    /// sleep counts, which its own sleep holds at one at least, are left as they
    /// are. The alarms for the first tick set, if its slot is empty, are written
    /// over the alarms already read and the buffer handed to the wheel.
    fn run_slot_along(&mut self, mut due: Vec<Alarm>) {
        let Vm {
            nodes,
            vars,
            timers,
            frames,
            ops_left,
            end_code,
            tick,
            plans_run,
            ..
        } = self;
        let super::super::nodes::Nodes {
            all, live, classes, ..
        } = nodes;
        // Where new alarms go in place: the tick, decided at the first alarm set
        // (None: set one by one), and how many are written.
        let mut into: Option<u64> = None;
        let mut kept = 0usize;
        let mut run: Option<Run> = None;
        let tick = *tick;
        for i in 0..due.len() {
            let a = due[i];
            let Some(Kind::Frame(f)) = all.get_mut(a.node.idx as usize).map(|n| &mut n.kind) else {
                continue;
            };
            if run.as_ref().is_none_or(|r| r.pc != f.pc) {
                let r = Run::of(frames, f.pc);
                if r.ends {
                    *end_code = None;
                }
                if i == 0 {
                    let at = tick.saturating_add(u64::from(r.ticks));
                    into = timers.empty_slot(at).then_some(at);
                }
                run = Some(r);
            }
            let Some(r) = &run else {
                continue;
            };
            *ops_left = ops_left.saturating_sub(r.ops);
            for w in &r.steps[..r.nsteps] {
                let v = match w.src {
                    Some((src, field, op)) => op.apply(vars.field(src.at(f.base), field), w.k),
                    None => w.k,
                };
                vars.assign(w.var.at(f.base), v);
            }
            f.pc = r.sleep + 1;
            f.nap = f.nap.wrapping_add(1);
            let alarm = Alarm {
                node: a.node,
                nap: f.nap,
            };
            let at = tick.saturating_add(u64::from(r.ticks));
            if Some(at) == into {
                due[kept] = alarm;
                kept += 1;
            } else {
                timers.set(at, alarm);
            }
            super::move_counts(r.moved, live, classes);
        }
        *plans_run += due.len() as u64;
        match into {
            Some(at) if kept > 0 => {
                due.truncate(kept);
                timers.adopt(at, due);
            }
            _ => timers.done(due),
        }
    }
}

//! Blocks, control flow and the ending of commands: the ready queue, instruction
//! execution under the tick budget, expression evaluation, `break`, `priority`.

use ilmr_hal::Hal;
use ilmr_stdlib::Field;

use super::clock::Clock;
use super::frame::{FInstr, FOp, FrameHit};
use super::nodes::{BlockState, Kind, NodeRef, SLEEPING};
use super::targets::{self, Found, Targets};
use super::trace::EventKind;
use super::vars::{FieldMask, How, NONE, Waiter, Woken};
use super::watch::{Cmp, Shape};
use super::{Vm, stmt_of};
use crate::bytecode::limits::EXPR_STACK;
use crate::bytecode::{BlockId, ExprId, ExprOp, Instr, Op, StmtId};

/// What running a block's instructions came to.
enum Flow {
    /// Every instruction issued.
    Done,
    /// A wait or init holds the block.
    Held,
    /// The budget ran out; the block stays first in the ready queue.
    Suspended,
    /// The block was ended by one of its own statements.
    Gone,
    /// A skill call: its first block continues this strand.
    Enter(NodeRef),
}

/// An entry of the ready queue.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Ready {
    /// A block to run, or a guard, loop or wait to look at.
    Node(NodeRef),
    /// A variable changed: evaluate its subscribers (guards and waits) in place, in
    /// subscription order. One entry however many subscribe.
    Wake(u32),
}

/// The index of a [`Packed`] wake: no node has it (the arena would be 256 GB).
const WAKE: u32 = NONE - 1;

/// A [`Ready`] as the queue holds it: 8 bytes where the enum takes 12 (every live
/// block is queued at once when a task starts). A node is its index and
/// generation; a wake has the index [`WAKE`] and its variable for the generation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Packed {
    idx: u32,
    word: u32,
}

impl From<Ready> for Packed {
    #[inline]
    fn from(r: Ready) -> Packed {
        match r {
            Ready::Node(n) => Packed {
                idx: n.idx,
                word: n.epoch,
            },
            Ready::Wake(var) => Packed {
                idx: WAKE,
                word: var,
            },
        }
    }
}

impl From<Packed> for Ready {
    #[inline]
    fn from(p: Packed) -> Ready {
        if p.idx == WAKE {
            Ready::Wake(p.word)
        } else {
            Ready::Node(NodeRef {
                idx: p.idx,
                epoch: p.word,
            })
        }
    }
}

impl<H: Hal, C: Clock> Vm<H, C> {
    pub(super) fn start_block(&mut self, parent: u32, block: u32, depth: u16) -> NodeRef {
        if let Some(r) = self.start_frame(parent, block) {
            return r;
        }
        let r = self.new_block(parent, block, depth, false);
        self.enqueue(r.idx);
        r
    }

    fn new_block(&mut self, parent: u32, block: u32, depth: u16, inline: bool) -> NodeRef {
        self.nodes.alloc(
            parent,
            NONE,
            NONE,
            Kind::Block(BlockState {
                block,
                pc: 0,
                holder: NONE,
                nap: 0,
                issued: false,
                depth,
                inline,
            }),
        )
    }

    #[inline]
    pub(super) fn enqueue(&mut self, idx: u32) {
        let n = self.nodes.get_mut(idx);
        if !n.queued {
            n.queued = true;
            let r = NodeRef {
                idx,
                epoch: n.epoch,
            };
            self.ready.push_back(Ready::Node(r).into());
        }
    }

    /// Runs ready nodes in FIFO order until the queue is empty or the budget is spent.
    pub(super) fn run_ready(&mut self) {
        self.ops_left = self.cfg.budget_ops;
        if self.run_deferred() || self.run_round() {
            return;
        }
        while let Some(entry) = self.ready.pop_front().map(Ready::from) {
            let r = match entry {
                Ready::Node(r) => r,
                Ready::Wake(var) => {
                    if self.ops_left == 0 {
                        self.ready.push_front(entry.into());
                        self.overrun(NONE);
                        return;
                    }
                    if !self.wake(var) {
                        return;
                    }
                    continue;
                }
            };
            // `Nodes::alive`, with the node looked up once for the whole visit.
            let Some(n) = self.nodes.all.get_mut(r.idx as usize) else {
                continue;
            };
            if n.epoch != r.epoch || matches!(n.kind, Kind::Free) {
                continue;
            }
            if self.ops_left == 0 {
                self.ready.push_front(entry.into());
                self.overrun(r.idx);
                return;
            }
            n.queued = false;
            // A frame, the common entry, without copying its node's kind.
            if let Kind::Frame(_) = n.kind {
                if self.run_frame(r.idx) {
                    self.nodes.get_mut(r.idx).queued = true;
                    self.ready.push_front(entry.into());
                    self.overrun(r.idx);
                    return;
                }
                continue;
            }
            let kind = n.kind;
            match kind {
                Kind::Block(_) => {
                    if let Some(at) = self.run_strand(r) {
                        self.nodes.get_mut(at.idx).queued = true;
                        self.ready.push_front(Ready::Node(at).into());
                        self.overrun(at.idx);
                        return;
                    }
                }
                Kind::If { .. } => self.check_guard(r.idx),
                Kind::While { .. } => self.check_while(r.idx),
                Kind::WaitVar { var } if self.vars.get(var).status >= 1.0 => {
                    self.end_node(r.idx, How::Completed, false, None, true);
                }
                _ => {}
            }
        }
    }

    /// A queued wake of `var`: its waits are ended if its status is 1, its general
    /// guards' conditions evaluated straight from the subscription records, and its
    /// compiled guards that now hold evaluated and fired; compiled guards that stay
    /// false are not touched. All in subscription order. Returns false when the
    /// budget ran out: the subscribers not yet looked at are queued first, one by one.
    fn wake(&mut self, var: u32) -> bool {
        let mut subs = std::mem::take(&mut self.woken);
        subs.clear();
        self.vars.take_wake(var, &mut subs);
        let mut done = true;
        for (i, w) in subs.iter().enumerate() {
            // A dead compiled entry is no subscriber: it costs nothing, not even
            // budget.
            if matches!(w.waiter, Waiter::Watch { .. }) && !self.waiting(w) {
                continue;
            }
            if self.ops_left == 0 {
                for later in subs[i..].iter().rev() {
                    if self.waiting(later) && !self.nodes.get(later.node).queued {
                        self.nodes.get_mut(later.node).queued = true;
                        let r = self.nodes.at(later.node);
                        self.ready.push_front(Ready::Node(r).into());
                    }
                }
                self.overrun(w.node);
                done = false;
                break;
            }
            let node = w.node;
            let cond = match w.waiter {
                Waiter::Wait => {
                    if self.vars.field(var, Field::Status) >= 1.0
                        && matches!(self.nodes.get(node).kind, Kind::WaitVar { .. })
                    {
                        self.end_node(node, How::Completed, false, None, true);
                    }
                    continue;
                }
                Waiter::Guard { cond } => cond,
                Waiter::Watch { .. } => match self.nodes.get(node).kind {
                    Kind::If { cond, .. } => cond,
                    _ => continue,
                },
            };
            self.ops_left -= 1;
            match self.eval(ExprId(cond)) {
                Ok(v) if v != 0.0 => {
                    // Only an unfired guard is subscribed; it may have fired already
                    // in this wake when it reads the variable twice.
                    if matches!(self.nodes.get(node).kind, Kind::If { fired: false, .. }) {
                        self.fire_guard(node);
                    }
                }
                Ok(_) => {}
                Err(e) => {
                    let stmt = stmt_of(self.nodes.get(node).stmt);
                    self.error(stmt, e.to_string());
                }
            }
        }
        self.woken = subs;
        let nodes = &self.nodes;
        self.vars.settle_wake(|e| {
            watching(
                nodes,
                NodeRef {
                    idx: e.node,
                    epoch: e.epoch,
                },
            )
        });
        done
    }

    /// A woken subscriber still waits: a compiled guard's entry may be dead.
    fn waiting(&self, w: &Woken) -> bool {
        match w.waiter {
            Waiter::Watch { epoch } => watching(&self.nodes, NodeRef { idx: w.node, epoch }),
            _ => self.nodes.get(w.node).kind != Kind::Free,
        }
    }

    fn overrun(&mut self, idx: u32) {
        if idx == NONE {
            let pending = self.ready.len() as u32;
            self.push_event(None, EventKind::Overrun { pending });
            return;
        }
        let stmt = match self.nodes.get(idx).kind {
            Kind::Block(b) => {
                let code = self.module.block_code(crate::bytecode::BlockId(b.block));
                code.get(b.pc as usize).map_or(NONE, |i| i.stmt.0)
            }
            Kind::Frame(f) => self.frames.instr(f.pc, f.block).map_or(NONE, |i| i.stmt),
            _ => self.nodes.get(idx).stmt,
        };
        let pending = self.ready.len() as u32;
        self.push_event(stmt_of(stmt), EventKind::Overrun { pending });
    }

    /// Runs a strand of blocks from `r`: into the first block of every skill it calls,
    /// and back out to the caller when that block has issued its last statement.
    /// Returns the block to resume first next tick when the budget ran out.
    fn run_strand(&mut self, mut r: NodeRef) -> Option<NodeRef> {
        loop {
            match self.run_block(r) {
                Flow::Enter(first) => r = first,
                Flow::Suspended => return Some(r),
                Flow::Held | Flow::Gone => return None,
                Flow::Done => match self.finish_issuing(r) {
                    Some(caller) => r = caller,
                    None => return None,
                },
            }
        }
    }

    /// A block has issued its last statement: it ends when its commands have. The
    /// first block of a skill call also hands the strand back to its caller, which
    /// is returned to go on at once.
    fn finish_issuing(&mut self, r: NodeRef) -> Option<NodeRef> {
        let Kind::Block(b) = self.nodes.get(r.idx).kind else {
            return None;
        };
        self.nodes.set_issued(r.idx, true);
        let mut caller = None;
        if b.inline {
            let call = self.nodes.get(r.idx).parent;
            let up = if call == NONE {
                NONE
            } else {
                self.nodes.get(call).parent
            };
            if up != NONE
                && let Kind::Block(c) = self.nodes.get(up).kind
                && c.holder == call
            {
                // Released before this block may end (and with it the call), so that
                // the caller is not also queued.
                self.set_block(up, |s| s.holder = NONE);
                caller = Some(self.nodes.at(up));
            }
        }
        if self.nodes.get(r.idx).children == 0 {
            self.end_node(r.idx, How::Completed, false, None, true);
        }
        caller.filter(|c| self.nodes.alive(*c))
    }

    fn run_block(&mut self, r: NodeRef) -> Flow {
        loop {
            if !self.nodes.alive(r) {
                return Flow::Gone;
            }
            let Kind::Block(b) = self.nodes.get(r.idx).kind else {
                return Flow::Gone;
            };
            if b.holder != NONE {
                return Flow::Held;
            }
            let instr = self.module.instr_at(BlockId(b.block), b.pc).copied();
            let Some(instr) = instr else {
                return Flow::Done;
            };
            if self.ops_left == 0 {
                return Flow::Suspended;
            }
            self.ops_left -= 1;
            self.set_block(r.idx, |s| s.pc += 1);
            if let Some(first) = self.exec(r.idx, b.depth, instr.op, instr.stmt) {
                return Flow::Enter(first);
            }
        }
    }

    fn set_block(&mut self, idx: u32, f: impl FnOnce(&mut BlockState)) {
        if let Kind::Block(b) = &mut self.nodes.get_mut(idx).kind {
            f(b);
        }
    }

    fn hold(&mut self, block: u32, child: NodeRef) {
        if self.nodes.alive(child) {
            self.set_block(block, |s| s.holder = child.idx);
        }
    }

    /// Executes one statement instruction of block `blk`. Returns the block that
    /// continues the strand when the instruction called a skill.
    fn exec(&mut self, blk: u32, depth: u16, op: Op, stmt: StmtId) -> Option<NodeRef> {
        self.issue_event(stmt.0);
        let s = stmt.0;
        match op {
            Op::Issue {
                command,
                args,
                bind,
            } => {
                let bind = bind.map_or(NONE, |v| v.0);
                if let Some(child) = self.issue(blk, s, command, args, bind)
                    && command.spec().holds_block
                {
                    self.hold(blk, child);
                }
            }
            Op::Assign { var, expr } => self.assign(var.0, expr, stmt),
            Op::Copy { to, from } => self.copy(to.0, from.0, s),
            Op::WaitTime { seconds, bind } => {
                let ticks = self.wait_ticks(seconds);
                self.bind_issue(bind.map_or(NONE, |v| v.0), s);
                let nap = self.nodes.sleep(blk);
                let node = self.nodes.at(blk);
                self.timers.set(
                    self.tick.saturating_add(ticks),
                    super::timers::Alarm { node, nap },
                );
            }
            Op::WaitVar { var, bind } => {
                let bind = bind.map_or(NONE, |v| v.0);
                self.bind_issue(bind, s);
                let child = self.nodes.alloc(blk, s, bind, Kind::WaitVar { var: var.0 });
                if self.vars.get(var.0).status >= 1.0 {
                    self.end_node(child.idx, How::Completed, false, None, true);
                } else {
                    let mut head = NONE;
                    self.vars.subscribe(child.idx, NONE, var.0, &mut head);
                    self.nodes.get_mut(child.idx).subs = head;
                    self.hold(blk, child);
                }
            }
            Op::If { cond, body, bind } => {
                let bind = bind.map_or(NONE, |v| v.0);
                self.bind_issue(bind, s);
                let child = self.nodes.alloc(
                    blk,
                    s,
                    bind,
                    Kind::If {
                        cond: cond.0,
                        body: body.0,
                        fired: false,
                    },
                );
                self.check_guard(child.idx);
            }
            Op::While { cond, body, bind } => {
                let bind = bind.map_or(NONE, |v| v.0);
                self.bind_issue(bind, s);
                let child = self.nodes.alloc(
                    blk,
                    s,
                    bind,
                    Kind::While {
                        cond: cond.0,
                        body: body.0,
                        iteration: 0,
                    },
                );
                self.check_while(child.idx);
            }
            Op::Call { unit, bind } => return self.call(blk, depth, s, unit.index(), bind),
            Op::Break { pattern } => self.break_pattern(pattern.0),
            // Both brake through the ramp (motion/halt.rs, drive.rs): the setpoint
            // falls by the model's deceleration, never to 0 at once.
            Op::BreakAll => self.end_children_of(self.root, NONE),
            Op::Stop => self.motion.stopped = true,
            Op::Cont => self.motion.stopped = false,
            Op::Priority => self.priority_highest(blk),
            Op::Clear { var } => {
                self.followers.retain(|f| f.var != var.0);
                let mask = self.vars.clear(var.0);
                self.changed(var.0, mask, s, false);
            }
        }
        None
    }

    /// The `issue` event of a statement, when the trace is on.
    #[inline]
    pub(super) fn issue_event(&mut self, stmt: u32) {
        if self.tracing() {
            self.push_event(Some(StmtId(stmt)), EventKind::Issue);
        }
    }

    /// `var = expr`.
    #[inline]
    pub(super) fn assign(&mut self, var: u32, expr: ExprId, stmt: StmtId) {
        match self.eval(expr) {
            Ok(v) => {
                // As `write_reporting` of value and status with no `how`, on the
                // record in place: the value is traced even when unchanged.
                let mask = self.vars.assign(var, v);
                self.changed(var, mask, stmt.0, false);
            }
            Err(e) => self.error(Some(stmt), e.to_string()),
        }
    }

    /// `to = from` for a record: every field and how its command ended.
    pub(super) fn copy(&mut self, to: u32, from: u32, stmt: u32) {
        let r = self.vars.get(from);
        let fields = [
            (Field::Status, r.status),
            (Field::X, r.x),
            (Field::Y, r.y),
            (Field::H, r.h),
            (Field::Value, r.value),
            (Field::Dist, r.dist),
        ];
        let report = FieldMask(
            FieldMask::bit(Field::Status)
                | FieldMask::bit(Field::X)
                | FieldMask::bit(Field::Y)
                | FieldMask::bit(Field::H),
        );
        self.write_reporting(to, &fields, Some(r.how), stmt, false, report);
    }

    /// The ticks a `wait(seconds)` sleeps ([`super::frame::ticks_of`]).
    #[inline]
    pub(super) fn wait_ticks(&mut self, seconds: ExprId) -> u64 {
        let secs = self.eval(seconds).unwrap_or(0.0);
        super::frame::ticks_of(secs, self.cfg.period)
    }

    /// A skill call, issued in line (section 4.2.2.2: the skill's commands are
    /// appended where the call stands). The skill's first block continues the
    /// caller's strand, which the call holds until that block has issued its last
    /// statement; its further blocks start now as new strands. The call node is the
    /// frame: it ends, and sets its variable, when all of them have ended.
    fn call(
        &mut self,
        blk: u32,
        depth: u16,
        stmt: u32,
        unit: usize,
        bind: Option<crate::bytecode::VarId>,
    ) -> Option<NodeRef> {
        let bind = bind.map_or(NONE, |v| v.0);
        self.bind_issue(bind, stmt);
        let d = depth.saturating_add(1);
        let child = self.nodes.alloc(
            blk,
            stmt,
            bind,
            Kind::Call {
                unit: unit as u32,
                depth: d,
            },
        );
        if d > self.cfg.max_call_depth {
            let why = format!("skill calls nested deeper than {}", self.cfg.max_call_depth);
            self.end_node(child.idx, How::Refused, false, Some(why), true);
            return None;
        }
        let count = self.module.units.get(unit).map_or(0, |u| u.blocks.len());
        if count == 0 {
            self.end_node(child.idx, How::Completed, false, None, true);
            return None;
        }
        for i in 1..count {
            let b = self.module.units[unit].blocks[i];
            self.start_block(child.idx, b.0, d);
        }
        let first = self.module.units[unit].blocks[0];
        let strand = self.new_block(child.idx, first.0, d, true);
        self.hold(blk, child);
        Some(strand)
    }

    /// A statement bound to `var` was issued: its status is 0 until it ends.
    pub(super) fn bind_issue(&mut self, var: u32, stmt: u32) {
        if var != NONE {
            self.write_fields(var, &[(Field::Status, 0.0)], Some(None), stmt, false);
        }
    }

    /// Evaluates an expression: a decoded shape at once, any other on the stack.
    #[inline]
    pub(super) fn eval(&mut self, id: ExprId) -> Result<f64, &'static str> {
        match self.decoded.all.get(id.index()) {
            Some(d) => {
                self.ops_left = self.ops_left.saturating_sub(d.len);
                match d.value(&self.vars) {
                    Some(v) => Ok(v),
                    None => self.eval_stack(id),
                }
            }
            None => {
                let len = self.module.expr_ops(id).len() as u32;
                self.ops_left = self.ops_left.saturating_sub(len);
                self.eval_stack(id)
            }
        }
    }

    /// Evaluates an expression on the fixed stack (the budget is charged already).
    #[inline(never)]
    fn eval_stack(&mut self, id: ExprId) -> Result<f64, &'static str> {
        let ops = self.module.expr_ops(id);
        let mut sp = 0usize;
        let tol = self.cfg.position_tolerance;
        for op in ops {
            let v = match *op {
                ExprOp::Const(c) => self.module.consts.get(c.index()).copied().unwrap_or(0.0),
                ExprOp::Field(v, f) => self.vars.field(v.0, f),
                ExprOp::PosEq(a, b) => {
                    let (a, b) = (self.vars.get(a.0), self.vars.get(b.0));
                    let same =
                        a.status >= 1.0 && b.status >= 1.0 && (a.x - b.x).hypot(a.y - b.y) <= tol;
                    f64::from(u8::from(same))
                }
                ExprOp::Neg => {
                    let top = sp.checked_sub(1).ok_or("stack underflow")?;
                    self.stack[top] = -self.stack[top];
                    continue;
                }
                bin => {
                    if sp < 2 {
                        return Err("stack underflow");
                    }
                    sp -= 2;
                    let (a, b) = (self.stack[sp], self.stack[sp + 1]);
                    match bin {
                        ExprOp::Add => a + b,
                        ExprOp::Sub => a - b,
                        ExprOp::Mul => a * b,
                        ExprOp::Div => {
                            if b == 0.0 {
                                return Err("division by zero");
                            }
                            a / b
                        }
                        cmp => {
                            let r = Cmp::of(cmp).unwrap_or(Cmp::Ge).holds(a, b);
                            f64::from(u8::from(r))
                        }
                    }
                }
            };
            if sp >= EXPR_STACK {
                return Err("expression too deep");
            }
            self.stack[sp] = v;
            sp += 1;
        }
        if sp == 1 {
            Ok(self.stack[0])
        } else {
            Err("malformed expression")
        }
    }

    /// Evaluates an `if` guard: fire its body, or sleep until a variable it reads
    /// changes.
    pub(super) fn check_guard(&mut self, idx: u32) {
        let Kind::If { cond, fired, .. } = self.nodes.get(idx).kind else {
            return;
        };
        if fired {
            return;
        }
        self.ops_left = self.ops_left.saturating_sub(1);
        let truth = match self.eval(ExprId(cond)) {
            Ok(v) => v != 0.0,
            Err(e) => {
                let stmt = stmt_of(self.nodes.get(idx).stmt);
                self.error(stmt, e.to_string());
                false
            }
        };
        // Subscriptions persist while the guard is false: its inputs are fixed, so
        // it is woken exactly when one of them changes.
        if truth {
            self.fire_guard(idx);
        } else if self.nodes.get(idx).subs == NONE {
            let shape = Shape::compile(self.module.expr_ops(ExprId(cond)), &self.module.consts);
            let epoch = self.nodes.get(idx).epoch;
            let nodes = &self.nodes;
            let watched = shape.and_then(|shape| {
                self.vars.watch(shape, idx, epoch, |e| {
                    watching(
                        nodes,
                        NodeRef {
                            idx: e.node,
                            epoch: e.epoch,
                        },
                    )
                })
            });
            let subs = match watched {
                Some(head) => head,
                None => {
                    let mut subs = NONE;
                    self.subscribe_expr(idx, cond, &mut subs);
                    subs
                }
            };
            self.nodes.get_mut(idx).subs = subs;
        }
    }

    /// A guard's condition is true: it stops listening and starts its body once.
    fn fire_guard(&mut self, idx: u32) {
        let Kind::If { body, .. } = self.nodes.get(idx).kind else {
            return;
        };
        let mut subs = self.nodes.get(idx).subs;
        self.vars.unsubscribe_all(&mut subs);
        self.nodes.get_mut(idx).subs = subs;
        self.nodes.update_kind(idx, |k| {
            if let Kind::If { fired, .. } = k {
                *fired = true;
            }
        });
        let stmt = stmt_of(self.nodes.get(idx).stmt);
        self.push_event(stmt, EventKind::Start { iteration: None });
        let depth = self.depth_of(idx);
        self.start_block(idx, body, depth);
    }

    fn subscribe_expr(&mut self, idx: u32, cond: u32, subs: &mut u32) {
        let ops = self.module.expr_ops(ExprId(cond));
        for i in 0..ops.len() {
            match self.module.expr_ops(ExprId(cond))[i] {
                ExprOp::Field(v, _) => self.vars.subscribe(idx, cond, v.0, subs),
                ExprOp::PosEq(a, b) => {
                    self.vars.subscribe(idx, cond, a.0, subs);
                    self.vars.subscribe(idx, cond, b.0, subs);
                }
                _ => {}
            }
        }
    }

    pub(super) fn check_while(&mut self, idx: u32) {
        let Kind::While {
            cond,
            body,
            iteration,
        } = self.nodes.get(idx).kind
        else {
            return;
        };
        self.ops_left = self.ops_left.saturating_sub(1);
        match self.eval(ExprId(cond)) {
            Ok(v) if v != 0.0 => {
                if let Kind::While { iteration, .. } = &mut self.nodes.get_mut(idx).kind {
                    *iteration = iteration.wrapping_add(1);
                }
                if self.tracing() {
                    let stmt = stmt_of(self.nodes.get(idx).stmt);
                    let iteration = Some(iteration.wrapping_add(1));
                    self.push_event(stmt, EventKind::Start { iteration });
                }
                let last = self.nodes.get(idx).first_child;
                if self.nodes.parked(last) {
                    let r = self.nodes.unpark(last);
                    if let Kind::Frame(_) = self.nodes.get(r.idx).kind
                        && let Some(f) = self.frames.start(body)
                    {
                        self.nodes.get_mut(r.idx).kind = Kind::Frame(f);
                        self.frame_account(None, Some(f.pc));
                    }
                    self.enqueue(r.idx);
                } else {
                    let depth = self.depth_of(idx);
                    self.start_block(idx, body, depth);
                }
            }
            Ok(_) => self.end_node(idx, How::Completed, false, None, true),
            Err(e) => self.end_node(idx, How::Refused, false, Some(e.to_string()), true),
        }
    }

    /// The skill call depth of the block a node stands in.
    fn depth_of(&self, mut idx: u32) -> u16 {
        while idx != NONE {
            if let Kind::Block(b) = self.nodes.get(idx).kind {
                return b.depth;
            }
            idx = self.nodes.get(idx).parent;
        }
        0
    }

    /// Writes fields of a variable; traces and wakes subscribers if anything changed.
    /// `how`: `Some(h)` also sets how its command ended. `quiet`: no trace event (for
    /// the distance of a running movement, which changes every tick).
    pub(super) fn write_fields(
        &mut self,
        var: u32,
        fields: &[(Field, f64)],
        how: Option<Option<How>>,
        stmt: u32,
        quiet: bool,
    ) {
        self.write_reporting(var, fields, how, stmt, quiet, FieldMask::default());
    }

    /// As [`Self::write_fields`], tracing the fields in `report` even if unchanged
    /// (an assignment's value, a movement's final distance and pose).
    pub(super) fn write_reporting(
        &mut self,
        var: u32,
        fields: &[(Field, f64)],
        how: Option<Option<How>>,
        stmt: u32,
        quiet: bool,
        report: FieldMask,
    ) {
        let mut mask = report;
        for &(f, v) in fields {
            if self.vars.set(var, f, v) {
                mask.0 |= FieldMask::bit(f);
            }
        }
        if let Some(h) = how {
            self.vars.set_how(var, h);
        }
        self.changed(var, mask, stmt, quiet);
    }

    pub(super) fn changed(&mut self, var: u32, mask: FieldMask, stmt: u32, quiet: bool) {
        if mask.is_empty() {
            return;
        }
        if !quiet && self.cfg.trace != super::config::TraceLevel::Off {
            let record = self.vars.get(var);
            self.push_event(
                stmt_of(stmt),
                EventKind::Var {
                    var: crate::bytecode::VarId(var),
                    changed: mask,
                    record,
                },
            );
        }
        if self.vars.queue_wake(var) {
            self.ready.push_back(Ready::Wake(var).into());
        }
    }

    /// Ends one node: trace, variable, command-specific cleanup, unlink, free. With
    /// `notify` its parent learns of it (blocks resume, loops iterate, ifs end).
    pub(super) fn end_node(
        &mut self,
        idx: u32,
        how: How,
        linked: bool,
        reason: Option<String>,
        notify: bool,
    ) {
        let Some(parent) = self.end_one(idx, how, linked, reason) else {
            return;
        };
        if notify {
            self.notify_up(parent, idx);
        }
    }

    /// Tells `parent` that `child` ended, and its parent in turn when that ends it too.
    /// A loop rather than recursion: the chain is as long as the nesting, blocks inside
    /// skills inside blocks, which no native stack need hold.
    fn notify_up(&mut self, mut parent: u32, mut child: u32) {
        while parent != NONE {
            let Some(grandparent) = self.child_ended(parent, child) else {
                return;
            };
            child = parent;
            parent = grandparent;
        }
    }

    /// [`Vm::end_node`] without telling the parent, which it returns (`None` when the
    /// node had ended already).
    fn end_one(&mut self, idx: u32, how: How, linked: bool, reason: Option<String>) -> Option<u32> {
        let kind = self.nodes.get(idx).kind;
        if matches!(kind, Kind::Block(_) | Kind::Frame(_)) {
            if let Kind::Block(b) = kind
                && b.holder == SLEEPING
            {
                // Its wait would have been its last child, ended just before it.
                self.end_sleep(idx, how);
            }
            // What a frame stands for ends innermost first, as a subtree; a parked
            // one (a loop's body between iterations) stands for nothing.
            if let Kind::Frame(f) = kind
                && !f.parked
            {
                self.end_frame_loops(idx, 0, how);
                if let Kind::Frame(f) = self.nodes.get(idx).kind {
                    self.frame_account(Some(f.pc), None);
                }
            }
            // A block is no command: no event, no variable, no subscription, no
            // movement; only the code meant for a command's `end` is spent.
            self.end_code = None;
            let n = self.nodes.get(idx);
            let parent = n.parent;
            // A loop's body that completed (was not ended with its subtree) waits
            // for the next iteration in place.
            if !n.dying
                && parent != NONE
                && matches!(self.nodes.get(parent).kind, Kind::While { .. })
            {
                self.nodes.park(idx);
                return Some(parent);
            }
            self.nodes.unlink(idx);
            self.nodes.free(idx);
            return Some(parent);
        }
        let node = *self.nodes.get(idx);
        if node.kind == Kind::Free {
            return None;
        }
        if matches!(node.kind, Kind::While { .. }) && self.nodes.parked(node.first_child) {
            self.nodes.unlink(node.first_child);
            self.nodes.free(node.first_child);
        }
        let is_command = node.kind != Kind::Root;
        let code = self.end_code.take();
        if is_command {
            self.push_event(
                stmt_of(node.stmt),
                EventKind::End {
                    how,
                    linked,
                    code,
                    reason,
                },
            );
        }
        let mut subs = node.subs;
        self.vars.unsubscribe_all(&mut subs);
        self.nodes.get_mut(idx).subs = NONE;
        let travelled = self.movement_result(idx);
        let was_head = self.motion_node_ended(idx);
        if node.bind != NONE {
            let mut fields = [(Field::Status, 1.0); 5];
            let n = match travelled {
                Some((d, x, y, h)) => {
                    fields[1..].copy_from_slice(&[
                        (Field::Dist, d),
                        (Field::X, x),
                        (Field::Y, y),
                        (Field::H, h),
                    ]);
                    5
                }
                None => 1,
            };
            let mut report = FieldMask::default();
            for (f, _) in &fields[1..n] {
                report.0 |= FieldMask::bit(*f);
            }
            self.write_reporting(
                node.bind,
                &fields[..n],
                Some(Some(how)),
                node.stmt,
                false,
                report,
            );
            if how == How::Completed {
                self.follow_after(node.kind, node.bind, node.stmt);
            }
        }
        let parent = node.parent;
        self.nodes.unlink(idx);
        self.nodes.free(idx);
        if was_head {
            self.start_next_movement(linked);
        }
        Some(parent)
    }

    /// Ends the `wait(seconds)` block `idx` sleeps in, as [`Vm::end_one`] ends a
    /// command: its `end` event and its variable. The block is held no longer; the
    /// caller queues it or ends it.
    pub(super) fn end_sleep(&mut self, idx: u32, how: How) {
        let (stmt, bind) = match self.nodes.get(idx).kind {
            Kind::Block(b) => {
                self.nodes.wake(idx);
                let instr =
                    b.pc.checked_sub(1)
                        .and_then(|pc| self.module.instr_at(BlockId(b.block), pc))
                        .copied();
                let Some(Instr {
                    op: Op::WaitTime { bind, .. },
                    stmt,
                }) = instr
                else {
                    self.end_code = None;
                    return;
                };
                (stmt.0, bind.map_or(NONE, |v| v.0))
            }
            Kind::Frame(f) => {
                self.nodes.wake(idx);
                let instr =
                    f.pc.checked_sub(1)
                        .and_then(|pc| self.frames.instr(pc, f.block));
                let Some(FInstr {
                    op: FOp::Wait { bind, .. },
                    stmt,
                    ..
                }) = instr
                else {
                    self.end_code = None;
                    return;
                };
                (stmt, bind)
            }
            _ => return,
        };
        self.end_in_place(stmt, bind, how, None);
    }

    /// The `wait(seconds)` a sleeping block sleeps in (the instruction before its pc).
    pub(super) fn sleep_stmt(&self, b: &BlockState) -> Option<StmtId> {
        let pc = b.pc.checked_sub(1)?;
        self.module.instr_at(BlockId(b.block), pc).map(|i| i.stmt)
    }

    /// Ends a node as refused with a stable code (issue 7's refusals and faults).
    pub(super) fn end_coded(&mut self, idx: u32, code: super::safety::Code, message: String) {
        self.end_code = Some(code);
        self.end_node(idx, How::Refused, false, Some(message), true);
    }

    pub(super) fn end_refused(&mut self, idx: u32, refusal: super::safety::Refusal) {
        self.end_code = refusal.code;
        self.end_node(idx, How::Refused, false, Some(refusal.message), true);
    }

    /// What `parent` does when `child` has ended; when that ends `parent` as well, its
    /// own parent, to be told next.
    fn child_ended(&mut self, parent: u32, child: u32) -> Option<u32> {
        let p = self.nodes.get(parent);
        let (kind, children) = (p.kind, p.children);
        match kind {
            Kind::Block(b) => {
                if b.holder == child {
                    self.set_block(parent, |s| s.holder = NONE);
                    self.enqueue(parent);
                    None
                } else if b.issued && children == 0 {
                    self.end_one(parent, How::Completed, false, None)
                } else {
                    None
                }
            }
            Kind::If { .. } => self.end_one(parent, How::Completed, false, None),
            Kind::While { .. } => {
                self.enqueue(parent);
                None
            }
            Kind::Call { .. } if children == 0 => self.end_one(parent, How::Completed, false, None),
            _ => None,
        }
    }

    /// Ends a node and everything inside it: descendants first (without waking their
    /// parents, which end too), then the node itself, whose parent is told.
    pub(super) fn end_subtree(&mut self, idx: u32, how: How) {
        self.mark_dying(idx);
        loop {
            let mut c = idx;
            while self.nodes.get(c).first_child != NONE {
                c = self.nodes.get(c).first_child;
            }
            if c == idx {
                break;
            }
            self.end_node(c, how, false, None, false);
        }
        self.end_node(idx, how, false, None, true);
    }

    fn mark_dying(&mut self, idx: u32) {
        let mut stack = std::mem::take(&mut self.scratch);
        stack.clear();
        stack.push(idx);
        while let Some(n) = stack.pop() {
            self.nodes.get_mut(n).dying = true;
            let mut c = self.nodes.get(n).first_child;
            while c != NONE {
                stack.push(c);
                c = self.nodes.get(c).next;
            }
        }
        self.scratch = stack;
    }

    /// Ends every child subtree of `parent` except `keep`.
    fn end_children_of(&mut self, parent: u32, keep: u32) {
        let mut kids = Vec::new();
        let mut c = self.nodes.get(parent).first_child;
        while c != NONE {
            if c != keep {
                kids.push(self.nodes.at(c));
            }
            c = self.nodes.get(c).next;
        }
        for k in kids {
            if self.nodes.alive(k) {
                self.end_subtree(k.idx, How::Broken);
            }
        }
    }

    fn break_pattern(&mut self, pattern: u32) {
        if !(self.targets.as_ref()).is_some_and(|t| t.current(&self.module)) {
            self.targets = Some(Targets::new(&self.module));
        }
        let Some(targets) = &self.targets else {
            return;
        };
        let looks = self.nodes.all.len() as u64;
        let hits = match targets.of(pattern) {
            // An empty pattern matches no statement (as the checker reads it), not all;
            // nor does one found only in statements that are never live.
            Found::Statements([]) => return,
            Found::Statements(stmts) => {
                self.marks.set(stmts, self.module.stmts.len());
                let hits = self.live_hits(|s| self.marks.has(s.0));
                self.marks.clear(stmts);
                self.pay_for_break((self.live() + stmts.len()) / targets::NODES_PER_OP);
                hits
            }
            Found::Unknown => {
                let pat = self
                    .module
                    .name(crate::bytecode::NameId(pattern))
                    .trim()
                    .to_lowercase();
                if pat.is_empty() {
                    return;
                }
                let hits = self.live_hits(|s| {
                    (self.module.stmts.get(s.index()))
                        .is_some_and(|t| t.text.to_lowercase().contains(&pat))
                });
                self.pay_for_break(self.live());
                hits
            }
        };
        self.break_looks += looks;
        self.end_hits(hits);
    }

    /// A break that looked at the live nodes pays from the tick's budget for them, so
    /// that thousands of breaks among thousands of blocks overrun ticks rather than
    /// hold one for seconds. What it pays is counted as the tree counts live nodes,
    /// not by the arena (frames stand for several), so that frames and the tree run
    /// the same steps in each tick.
    fn pay_for_break(&mut self, ops: usize) {
        let ops = u32::try_from(ops).unwrap_or(u32::MAX);
        self.ops_left = self.ops_left.saturating_sub(ops);
    }

    /// What a break whose statements `matches` tells ends among the live nodes, in the
    /// arena's order (which is the order they end in, and the trace's).
    fn live_hits(&self, matches: impl Fn(StmtId) -> bool) -> Vec<Hit> {
        let matches = |stmt: Option<StmtId>| stmt.is_some_and(&matches);
        // A hit is a node, the `wait(seconds)` a block sleeps in (its nap), or what
        // a frame stands for (an open loop, its sleep).
        let mut hits = Vec::new();
        for (i, n) in self.nodes.all.iter().enumerate() {
            let r = NodeRef {
                idx: i as u32,
                epoch: n.epoch,
            };
            match n.kind {
                Kind::Free => {}
                Kind::Block(b) if b.holder == SLEEPING => {
                    if matches(self.sleep_stmt(&b)) {
                        hits.push(Hit::Sleep(r, b.nap));
                    }
                }
                Kind::Frame(f) => self.frame_hits(r, &f, &mut |h, stmt| {
                    if matches(Some(StmtId(stmt))) {
                        hits.push(Hit::Frame(h));
                    }
                }),
                _ => {
                    if matches(stmt_of(n.stmt)) {
                        hits.push(Hit::Node(r));
                    }
                }
            }
        }
        hits
    }

    fn end_hits(&mut self, hits: Vec<Hit>) {
        for h in hits {
            match h {
                Hit::Node(r) if self.nodes.alive(r) => self.end_subtree(r.idx, How::Broken),
                Hit::Sleep(r, nap) | Hit::Frame(FrameHit::Sleep { frame: r, nap })
                    if self.nodes.asleep(r, nap) =>
                {
                    self.end_sleep(r.idx, How::Broken);
                    self.enqueue(r.idx);
                }
                Hit::Frame(FrameHit::Loop { frame, level })
                    if self.frame_loop_open(frame, level) =>
                {
                    self.break_frame_loop(frame.idx, level);
                }
                _ => {}
            }
        }
    }

    /// `priority = highest`: end everything that is neither this block's ancestor nor
    /// inside it.
    fn priority_highest(&mut self, blk: u32) {
        self.priority = Some(self.nodes.at(blk));
        let mut keep = blk;
        let mut parent = self.nodes.get(blk).parent;
        while parent != NONE {
            self.end_children_of(parent, keep);
            keep = parent;
            parent = self.nodes.get(parent).parent;
        }
    }
}

/// What `break(pattern)` ends.
enum Hit {
    Node(NodeRef),
    Sleep(NodeRef, u32),
    Frame(FrameHit),
}

/// A compiled guard's entry is live: the same node, not yet fired.
fn watching(nodes: &super::nodes::Nodes, r: NodeRef) -> bool {
    nodes.alive(r) && matches!(nodes.get(r.idx).kind, Kind::If { fired: false, .. })
}

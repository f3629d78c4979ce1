//! Compact frames: a block that only computes and sleeps (`ASSIGN`, `COPY`,
//! `WAITTIME`, and a `WHILE` as its last statement whose body is of the same shape,
//! loops nested at most [`MAX_LOOPS`] deep) runs as one node holding a pc into a
//! flat instruction array, as Lua's `lvm.c` runs a function: `while` is a check
//! that jumps into its body or past it, `endwhile` a jump back to the check, the
//! `wait` a timer-wheel entry naming the frame. The tree would hold the block, a node
//! per loop and a node per body; the frame is queued at exactly the points where the
//! tree queues those (the check after a body ends, the body after a check), so the
//! ready queue's order, and with it every event and variable write, is the tree's.
//!
//! What a frame stands for at each pc (the loops and bodies the tree would hold
//! live, and whether one of its blocks is still issuing) is a fact of the pc, decoded
//! with the code ([`FInstr::live`], [`FInstr::issuing`]), so `Vm::live` and
//! `Vm::activity` count a frame as the nodes it replaces.

use ilmr_hal::Hal;
use ilmr_stdlib::Field;

use super::Vm;
use super::clock::Clock;
use super::exec::Ready;
use super::nodes::{Class, Kind, NodeRef};
use super::trace::EventKind;
use super::vars::{FieldMask, How, NONE};
use crate::bytecode::{BlockId, ExprId, ExprOp, Module, Op, StmtId};

/// Loops a frame can hold open at once (a loop in the block, a loop in its body).
/// A block nested deeper keeps the tree.
pub(crate) const MAX_LOOPS: usize = 2;

/// A frame instruction. Expression, variable and statement operands are the
/// module's ids.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum FOp {
    Assign {
        var: u32,
        expr: u32,
    },
    Copy {
        to: u32,
        from: u32,
    },
    Wait {
        seconds: u32,
        bind: u32,
        /// The ticks of a constant time, worked out once as `Vm::wait_ticks` would
        /// (0: evaluate the expression).
        ticks: u64,
    },
    /// Issues the loop at `level` and checks it at once: its [`FOp::Check`] is the
    /// next instruction.
    While {
        bind: u32,
        level: u8,
    },
    /// A visit of the loop at `level` (the tree's `while` node): true starts its
    /// body, the next instruction, in a later turn of the ready queue; false ends
    /// the loop and goes on at `exit`, the enclosing block's end.
    Check {
        cond: u32,
        bind: u32,
        level: u8,
        exit: u32,
    },
    /// The body of a loop has ended: its check is queued.
    EndBody {
        check: u32,
    },
    /// The frame's own block has ended.
    End,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct FInstr {
    pub op: FOp,
    /// The statement traced for it (a check's is its `while`'s); NONE for the ends
    /// of blocks.
    pub stmt: u32,
    /// Nodes the tree would hold live besides the block itself with the frame
    /// resting here: a loop and a body per enclosing loop, a check's own body parked.
    pub live: u8,
    /// A block of the frame still has statements to issue here.
    pub issuing: bool,
    /// The checks of the loops open here, outermost first (NONE beyond `loops`).
    pub checks: [u32; MAX_LOOPS],
    /// How many loops are open here.
    pub loops: u8,
}

/// The flat code of every frame-shaped block of a module.
#[derive(Debug, Default)]
pub(crate) struct Frames {
    pub code: Vec<FInstr>,
    /// Per block: the pc its frame starts at, or NONE when it keeps the tree.
    entry: Vec<u32>,
    period: f64,
}

impl Frames {
    /// Compiles the blocks the module gained since the last call.
    pub fn grow(&mut self, m: &Module, period: f64) {
        self.period = period;
        for b in self.entry.len()..m.blocks.len() {
            let start = self.code.len();
            let mut checks = [NONE; MAX_LOOPS];
            let entry = if self.block(m, b as u32, 0, &mut checks) {
                self.code.push(end(FOp::End, 0, &checks));
                start as u32
            } else {
                self.code.truncate(start);
                NONE
            };
            self.entry.push(entry);
        }
    }

    /// The pc a block's frame starts at, if it is frame-shaped.
    #[inline]
    pub fn entry(&self, block: u32) -> Option<u32> {
        self.entry
            .get(block as usize)
            .copied()
            .filter(|&e| e != NONE)
    }

    /// Appends block `b`'s statements with `level` loops open around them; false
    /// when the block is not frame-shaped. The caller appends the block's end.
    fn block(&mut self, m: &Module, b: u32, level: usize, checks: &mut [u32; MAX_LOOPS]) -> bool {
        let code = m.block_code(BlockId(b));
        let stmt_in = |stmt: u32, op: FOp| FInstr {
            op,
            stmt,
            live: (2 * level) as u8,
            issuing: true,
            checks: *checks,
            loops: level as u8,
        };
        for (i, instr) in code.iter().enumerate() {
            let stmt = instr.stmt.0;
            let op = match instr.op {
                Op::Assign { var, expr } => FOp::Assign {
                    var: var.0,
                    expr: expr.0,
                },
                Op::Copy { to, from } => FOp::Copy {
                    to: to.0,
                    from: from.0,
                },
                Op::WaitTime { seconds, bind } => FOp::Wait {
                    seconds: seconds.0,
                    bind: bind.map_or(NONE, |v| v.0),
                    ticks: match m.expr_ops(seconds) {
                        [ExprOp::Const(k)] => m
                            .consts
                            .get(k.index())
                            .map_or(0, |&secs| ticks_of(secs, self.period)),
                        _ => 0,
                    },
                },
                Op::While { cond, body, bind } if i + 1 == code.len() && level < MAX_LOOPS => {
                    let bind = bind.map_or(NONE, |v| v.0);
                    self.code.push(stmt_in(
                        stmt,
                        FOp::While {
                            bind,
                            level: level as u8,
                        },
                    ));
                    let check = self.code.len();
                    checks[level] = check as u32;
                    self.code.push(FInstr {
                        op: FOp::Check {
                            cond: cond.0,
                            bind,
                            level: level as u8,
                            exit: NONE,
                        },
                        stmt,
                        live: (2 * level + 1) as u8,
                        issuing: false,
                        checks: *checks,
                        loops: level as u8 + 1,
                    });
                    if !self.block(m, body.0, level + 1, checks) {
                        return false;
                    }
                    self.code.push(end(
                        FOp::EndBody {
                            check: check as u32,
                        },
                        level + 1,
                        checks,
                    ));
                    checks[level] = NONE;
                    // The loop's exit is its block's end, which the caller appends next.
                    let exit = self.code.len() as u32;
                    if let FOp::Check { exit: e, .. } = &mut self.code[check].op {
                        *e = exit;
                    }
                    return true;
                }
                _ => return false,
            };
            self.code.push(stmt_in(stmt, op));
        }
        true
    }
}

/// The ticks a `wait(secs)` sleeps: at least one. `wait(1e26)` checks (a
/// non-negative time) and its tick count saturates; it must wait for ever, not
/// overflow the tick or wrap round to now.
pub(crate) fn ticks_of(secs: f64, period: f64) -> u64 {
    ((secs.max(0.0) / period).round() as u64).max(1)
}

/// The end of a block with `level` loops open around it.
fn end(op: FOp, level: usize, checks: &[u32; MAX_LOOPS]) -> FInstr {
    FInstr {
        op,
        stmt: NONE,
        live: (2 * level) as u8,
        issuing: true,
        checks: *checks,
        loops: level as u8,
    }
}

/// A frame's state, in its node.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct FrameState {
    pub pc: u32,
    /// How many times the frame has slept: names the current sleep to its timer.
    pub nap: u32,
    /// The iteration of each open loop, for its `start` events.
    pub iters: [u32; MAX_LOOPS],
    pub asleep: bool,
    /// A loop's body that ended, kept under its `while` for the next iteration.
    pub parked: bool,
}

impl FrameState {
    pub fn at(pc: u32) -> FrameState {
        FrameState {
            pc,
            nap: 0,
            iters: [0; MAX_LOOPS],
            asleep: false,
            parked: false,
        }
    }
}

impl<H: Hal, C: Clock> Vm<H, C> {
    /// Starts block `block` under `parent` as a frame, if it is frame-shaped.
    pub(super) fn start_frame(&mut self, parent: u32, block: u32) -> Option<NodeRef> {
        if !self.cfg.frames {
            return None;
        }
        let entry = self.frames.entry(block)?;
        let r = self
            .nodes
            .alloc(parent, NONE, NONE, Kind::Frame(FrameState::at(entry)));
        self.frame_account(None, Some(entry));
        self.enqueue(r.idx);
        Some(r)
    }

    /// Moves the counts of what a frame stands for from resting at `from` to resting
    /// at `to` (`None`: not live).
    #[inline]
    pub(super) fn frame_account(&mut self, from: Option<u32>, to: Option<u32>) {
        let of = |pc: Option<u32>| match pc.and_then(|pc| self.frames.code.get(pc as usize)) {
            Some(i) => (usize::from(i.live), usize::from(i.issuing)),
            None => (0, 0),
        };
        let ((live0, iss0), (live1, iss1)) = (of(from), of(to));
        if live0 == live1 && iss0 == iss1 {
            return;
        }
        self.nodes.live = (self.nodes.live + live1).saturating_sub(live0);
        let n = &mut self.nodes.classes[Class::Issuing as usize];
        *n = (*n + iss1).saturating_sub(iss0);
    }

    /// One visit of a frame from the ready queue: runs its instructions until it
    /// sleeps, queues itself where the tree would queue a loop or a body, or ends.
    /// Returns true when the budget ran out before an instruction: the frame stays
    /// first in the queue.
    pub(super) fn run_frame(&mut self, idx: u32) -> bool {
        let Kind::Frame(mut f) = self.nodes.get(idx).kind else {
            return false;
        };
        let from = f.pc;
        loop {
            let Some(&ins) = self.frames.code.get(f.pc as usize) else {
                // Unreachable for compiled code (every run ends in `End`); end the
                // frame rather than spin.
                self.frame_store(idx, f, from);
                self.end_node(idx, How::Completed, false, None, true);
                return false;
            };
            let stmt = ins.stmt;
            match ins.op {
                FOp::Assign { .. } | FOp::Copy { .. } | FOp::Wait { .. } | FOp::While { .. }
                    if self.ops_left == 0 =>
                {
                    self.frame_store(idx, f, from);
                    return true;
                }
                FOp::Assign { var, expr } => {
                    self.ops_left -= 1;
                    f.pc += 1;
                    self.issue_event(stmt);
                    self.assign(var, ExprId(expr), StmtId(stmt));
                }
                FOp::Copy { to, from } => {
                    self.ops_left -= 1;
                    f.pc += 1;
                    self.issue_event(stmt);
                    self.copy(to, from, stmt);
                }
                FOp::Wait {
                    seconds,
                    bind,
                    ticks,
                } => {
                    self.ops_left -= 1;
                    f.pc += 1;
                    self.issue_event(stmt);
                    let ticks = if ticks == 0 {
                        self.wait_ticks(ExprId(seconds))
                    } else {
                        // The constant's one op, as evaluating it would charge.
                        self.ops_left = self.ops_left.saturating_sub(1);
                        ticks
                    };
                    self.bind_issue(bind, stmt);
                    f.nap = f.nap.wrapping_add(1);
                    f.asleep = true;
                    self.nodes.classes[Class::Sleep as usize] += 1;
                    self.nodes.sleepers += 1;
                    let node = self.nodes.at(idx);
                    self.timers.set(
                        self.tick.saturating_add(ticks),
                        super::timers::Alarm { node, nap: f.nap },
                    );
                    self.frame_store(idx, f, from);
                    return false;
                }
                FOp::While { bind, level } => {
                    self.ops_left -= 1;
                    f.pc += 1;
                    self.issue_event(stmt);
                    self.bind_issue(bind, stmt);
                    if let Some(i) = f.iters.get_mut(usize::from(level)) {
                        *i = 0;
                    }
                }
                FOp::Check {
                    cond,
                    bind,
                    level,
                    exit,
                } => {
                    self.ops_left = self.ops_left.saturating_sub(1);
                    match self.eval(ExprId(cond)) {
                        Ok(v) if v != 0.0 => {
                            let mut iteration = 0;
                            if let Some(i) = f.iters.get_mut(usize::from(level)) {
                                *i = i.wrapping_add(1);
                                iteration = *i;
                            }
                            if self.tracing() {
                                let start = EventKind::Start {
                                    iteration: Some(iteration),
                                };
                                self.push_event(Some(StmtId(stmt)), start);
                            }
                            f.pc += 1;
                            self.frame_store(idx, f, from);
                            self.enqueue(idx);
                            return false;
                        }
                        Ok(_) => self.end_in_place(stmt, bind, How::Completed, None),
                        Err(e) => self.end_in_place(stmt, bind, How::Refused, Some(e.to_string())),
                    }
                    f.pc = exit;
                }
                FOp::EndBody { check } => {
                    // A body ends as a block does: it spends the code meant for a
                    // command's end.
                    self.end_code = None;
                    f.pc = check;
                    self.frame_store(idx, f, from);
                    self.enqueue(idx);
                    return false;
                }
                FOp::End => {
                    self.frame_store(idx, f, from);
                    self.end_node(idx, How::Completed, false, None, true);
                    return false;
                }
            }
        }
    }

    #[inline]
    fn frame_store(&mut self, idx: u32, f: FrameState, from: u32) {
        self.nodes.get_mut(idx).kind = Kind::Frame(f);
        if from != f.pc {
            self.frame_account(Some(from), Some(f.pc));
        }
    }

    /// A due alarm of a frame asleep in a wait with neither trace nor bound
    /// variable: it wakes and is queued, as `end_sleep` and `enqueue` would, on one
    /// look at its node. Returns false for any other alarm, which takes the
    /// general path.
    #[inline]
    pub(super) fn wake_frame(&mut self, a: &super::timers::Alarm) -> bool {
        if self.tracing() {
            return false;
        }
        let Some(n) = self.nodes.all.get_mut(a.node.idx as usize) else {
            return false;
        };
        let Kind::Frame(f) = &mut n.kind else {
            return false;
        };
        if n.epoch != a.node.epoch || !f.asleep || f.nap != a.nap {
            return false;
        }
        let unbound =
            f.pc.checked_sub(1)
                .and_then(|pc| self.frames.code.get(pc as usize))
                .is_some_and(|w| matches!(w.op, FOp::Wait { bind: NONE, .. }));
        if !unbound || n.queued {
            return false;
        }
        f.asleep = false;
        n.queued = true;
        self.ready.push_back(Ready::Node(a.node));
        let sleep = &mut self.nodes.classes[Class::Sleep as usize];
        *sleep = sleep.saturating_sub(1);
        self.nodes.sleepers = self.nodes.sleepers.saturating_sub(1);
        // `end_sleep` spends the code meant for a command's end.
        self.end_code = None;
        true
    }

    /// A statement that has no node of its own ends (a frame's loop, a sleep): what
    /// ending its node would write, its `end` event and its variable (`bind`, or NONE).
    pub(super) fn end_in_place(&mut self, stmt: u32, bind: u32, how: How, reason: Option<String>) {
        let code = self.end_code.take();
        if self.tracing() {
            let end = EventKind::End {
                how,
                linked: false,
                code,
                reason,
            };
            self.push_event(Some(StmtId(stmt)), end);
        }
        if bind != NONE {
            self.write_reporting(
                bind,
                &[(Field::Status, 1.0)],
                Some(Some(how)),
                stmt,
                false,
                FieldMask::default(),
            );
        }
    }

    /// Ends the loops of frame `idx` from the innermost down to `level` (and its
    /// sleep first), as ending their subtrees would, innermost first. Leaves the
    /// frame at the exit of loop `level`, or where it was when none was open.
    pub(super) fn end_frame_loops(&mut self, idx: u32, level: usize, how: How) {
        let Kind::Frame(f) = self.nodes.get(idx).kind else {
            return;
        };
        if f.asleep {
            self.end_sleep(idx, how);
        }
        let Some(&at) = self.frames.code.get(f.pc as usize) else {
            return;
        };
        let mut pc = f.pc;
        for l in (level..usize::from(at.loops)).rev() {
            let check = at.checks[l];
            let Some(&c) = self.frames.code.get(check as usize) else {
                continue;
            };
            if let FOp::Check { bind, exit, .. } = c.op {
                self.end_in_place(c.stmt, bind, how, None);
                pc = exit;
            }
        }
        if let Kind::Frame(g) = &mut self.nodes.get_mut(idx).kind {
            let from = g.pc;
            g.pc = pc;
            self.frame_account(Some(from), Some(pc));
        }
    }

    /// `break` hit the loop at `level` of frame `idx`: it ends with everything inside
    /// it, and the block holding it ends (it has issued everything): the frame ends
    /// with the outermost loop, or its enclosing loop is checked next.
    pub(super) fn break_frame_loop(&mut self, idx: u32, level: usize) {
        self.end_frame_loops(idx, level, How::Broken);
        if level == 0 {
            self.end_node(idx, How::Completed, false, None, true);
            return;
        }
        self.end_code = None;
        let Kind::Frame(f) = self.nodes.get(idx).kind else {
            return;
        };
        let Some(&at) = self.frames.code.get(f.pc as usize) else {
            return;
        };
        // Resting at the end of the enclosing body, whose check is queued next.
        if let FOp::EndBody { check } = at.op {
            if self.nodes.get(idx).queued {
                // The tree's queued body or loop is gone: its entry wakes nothing.
                for e in self.ready.iter_mut() {
                    if *e == Ready::Node(self.nodes.at(idx)) {
                        *e = Ready::Node(NodeRef {
                            idx: NONE,
                            epoch: 0,
                        });
                    }
                }
                self.nodes.get_mut(idx).queued = false;
            }
            if let Kind::Frame(g) = &mut self.nodes.get_mut(idx).kind {
                g.pc = check;
            }
            self.frame_account(Some(f.pc), Some(check));
            self.enqueue(idx);
        }
    }

    /// What `break(pattern)` can hit in frame `r`: its open loops, outermost first,
    /// and its sleep.
    pub(super) fn frame_hits(
        &self,
        r: NodeRef,
        f: &FrameState,
        hit: &mut impl FnMut(FrameHit, u32),
    ) {
        if f.parked {
            return;
        }
        let Some(at) = self.frames.code.get(f.pc as usize) else {
            return;
        };
        for l in 0..usize::from(at.loops) {
            if let Some(c) = self.frames.code.get(at.checks[l] as usize) {
                hit(FrameHit::Loop { frame: r, level: l }, c.stmt);
            }
        }
        if f.asleep
            && let Some(w) =
                f.pc.checked_sub(1)
                    .and_then(|pc| self.frames.code.get(pc as usize))
        {
            hit(
                FrameHit::Sleep {
                    frame: r,
                    nap: f.nap,
                },
                w.stmt,
            );
        }
    }

    /// The loop at `level` of frame `r` is still open.
    pub(super) fn frame_loop_open(&self, r: NodeRef, level: usize) -> bool {
        self.nodes.alive(r)
            && matches!(self.nodes.get(r.idx).kind, Kind::Frame(f)
                if !f.parked && self.frames.code.get(f.pc as usize).is_some_and(|i| usize::from(i.loops) > level))
    }

    /// The statements a frame's open loops and sleep stand for, for `live_statements`.
    pub(super) fn frame_statements(&self, f: &FrameState, out: &mut Vec<StmtId>) {
        self.frame_hits(
            NodeRef {
                idx: NONE,
                epoch: 0,
            },
            f,
            &mut |_, stmt| out.push(StmtId(stmt)),
        );
    }
}

/// Something of a frame `break(pattern)` ends.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum FrameHit {
    Loop { frame: NodeRef, level: usize },
    Sleep { frame: NodeRef, nap: u32 },
}

//! Compact frames: a block that only computes and sleeps (`ASSIGN`, `COPY`,
//! `WAITTIME`, and a `WHILE` as its last statement whose body is of the same shape,
//! loops nested at most [`MAX_LOOPS`] deep) runs as one node holding a pc into a
//! flat instruction array, as Lua's `lvm.c` runs a function: `while` is a check
//! that jumps into its body or past it, `endwhile` a jump back to the check, the
//! `wait` a timer-wheel entry naming the frame. The tree would hold the block, a node
//! per loop and a node per body; the frame is queued at exactly the points where the
//! tree queues those (the check after a body ends, the body after a check), so the
//! ready queue's order, and with it every event and variable write, is the tree's.
//! Blocks of one shape share one such array: its ids are relative to where each
//! block's own start ([`Ctx`]), as Lua's coroutines share a function and address
//! their registers from a base, so a million counting blocks read one program.
//!
//! What a frame stands for at each pc (the loops and bodies the tree would hold
//! live, and whether one of its blocks is still issuing) is a fact of the pc, decoded
//! with the code ([`FInstr::live`], [`FInstr::issuing`]), so `Vm::live` and
//! `Vm::activity` count a frame as the nodes it replaces.

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hash, Hasher};

use ilmr_hal::Hal;
use ilmr_stdlib::Field;

use super::Vm;
use super::clock::Clock;
use super::decode::{Bin, Decoded, Operand, Shape};
use super::exec::{Packed, Ready};
use super::nodes::{Class, Kind, NodeRef};
use super::timers::Alarm;
use super::trace::EventKind;
use super::vars::{FieldMask, How, NONE};
use super::watch::Cmp;
use crate::bytecode::{BlockId, ExprId, ExprOp, Module, Op, StmtId};

mod slot;

/// Loops a frame can hold open at once (a loop in the block, a loop in its body).
/// A block nested deeper keeps the tree.
pub(crate) const MAX_LOOPS: usize = 2;

/// A frame instruction. Expression, variable and statement operands are the
/// module's ids, relative to a block's [`Ctx`] in [`Frames::code`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
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

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
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

/// An arithmetic operator of [`Quick::SetVK`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Arith {
    Add,
    Sub,
    Mul,
}

impl Arith {
    #[inline]
    fn apply(self, a: f64, k: f64) -> f64 {
        match self {
            Arith::Add => a + k,
            Arith::Sub => a - k,
            Arith::Mul => a * k,
        }
    }
}

/// How the counts of what a frame stands for (`Nodes::live` and the issuing
/// blocks) move when it goes from one pc to another: worked out when the code is
/// compiled, so that a step does not look the two pcs up.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) struct Moved {
    live: i8,
    issuing: i8,
}

impl Moved {
    fn between(code: &[FInstr], from: usize, to: usize) -> Moved {
        let of = |pc: usize| {
            code.get(pc)
                .map_or((0, 0), |i| (i.live as i8, i8::from(i.issuing)))
        };
        let ((l0, i0), (l1, i1)) = (of(from), of(to));
        Moved {
            live: l1 - l0,
            issuing: i1 - i0,
        }
    }
}

/// The trace-off form of a frame instruction, one per pc beside [`FInstr`]: the
/// common shapes with their operands inline, as Lua's `OP_ADDK` and `OP_LTI` carry
/// theirs, so that a step reads no expression table and copies no instruction. Each
/// does exactly what its [`FOp`] does with the trace off (the budget charged the
/// same ops, the same variable written the same way, the same counts moved);
/// anything else is [`Quick::Slow`], the general path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Quick {
    /// `var = src.field op k` (`c=c+1`): an `ASSIGN` of three expression ops.
    SetVK {
        var: u32,
        src: u32,
        field: Field,
        op: Arith,
        next: Moved,
        k: f64,
    },
    /// `var = k`: an `ASSIGN` of one expression op.
    SetK {
        var: u32,
        next: Moved,
        k: f64,
    },
    /// A `wait` of a constant number of ticks that binds nothing.
    Sleep {
        next: Moved,
        ticks: u32,
    },
    /// A loop's check `src.field cmp k` (`while(c<100)`) that binds nothing: true
    /// moves to the body (`next`), false to `exit` (`out`).
    CheckVK {
        src: u32,
        field: Field,
        cmp: Cmp,
        next: Moved,
        out: Moved,
        exit: u32,
        k: f64,
    },
    /// [`FOp::EndBody`].
    EndBody {
        check: u32,
        back: Moved,
    },
    Slow,
}

impl Quick {
    /// The ops each form charges the budget: its statement's and its expression's.
    const SET_VK: u32 = 1 + 3;
    const SET_K: u32 = 1 + 1;
    const SLEEP: u32 = 1 + 1;
    const CHECK_VK: u32 = 1 + 3;

    fn of(code: &[FInstr], pc: usize, decoded: &[Decoded]) -> Quick {
        let shape = |e: u32| decoded.get(e as usize).map(|d| (d.shape, d.len));
        let next = Moved::between(code, pc, pc + 1);
        match code[pc].op {
            FOp::Assign { var, expr } => match shape(expr) {
                Some((Shape::Two(Operand::Field(src, field), Operand::Const(k), bin), 3)) => {
                    let op = match bin {
                        Bin::Add => Arith::Add,
                        Bin::Sub => Arith::Sub,
                        Bin::Mul => Arith::Mul,
                        Bin::Cmp(_) => return Quick::Slow,
                    };
                    Quick::SetVK {
                        var,
                        src,
                        field,
                        op,
                        next,
                        k,
                    }
                }
                Some((Shape::One(Operand::Const(k)), 1)) => Quick::SetK { var, next, k },
                _ => Quick::Slow,
            },
            FOp::Wait {
                bind: NONE, ticks, ..
            } if ticks != 0 => match u32::try_from(ticks) {
                Ok(ticks) => Quick::Sleep { next, ticks },
                Err(_) => Quick::Slow,
            },
            FOp::Check {
                cond,
                bind: NONE,
                exit,
                ..
            } => match shape(cond) {
                Some((
                    Shape::Two(Operand::Field(src, field), Operand::Const(k), Bin::Cmp(cmp)),
                    3,
                )) => Quick::CheckVK {
                    src,
                    field,
                    cmp,
                    next,
                    out: Moved::between(code, pc, exit as usize),
                    exit,
                    k,
                },
                _ => Quick::Slow,
            },
            FOp::EndBody { check } => Quick::EndBody {
                check,
                back: Moved::between(code, pc, check as usize),
            },
            _ => Quick::Slow,
        }
    }
}

/// Where a block's ids start: its frame's code names variables, expressions and
/// statements relative to these, so that blocks of one shape (a million counting
/// blocks) run one program, as Lua's coroutines share one function and address
/// their registers from a base.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) struct Ctx {
    pub var: u32,
    pub expr: u32,
    pub stmt: u32,
    /// The quick forms name variables `var..var + span` only; NONE when they
    /// name one below `var` (shared with other blocks). [`Vm::run_round`] tells
    /// frames apart by it.
    pub span: u32,
}

/// rustc's FxHash: the shapes' table hashes a block's code once at load, where
/// SipHash cost as much as compiling the block.
#[derive(Default)]
struct Fx(u64);

impl Hasher for Fx {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(u64::from(b));
        }
    }
    fn write_u32(&mut self, w: u32) {
        self.write_u64(u64::from(w));
    }
    fn write_u64(&mut self, w: u64) {
        self.0 = (self.0.rotate_left(5) ^ w).wrapping_mul(0x517c_c1b7_2722_0a95);
    }
    fn write_usize(&mut self, w: usize) {
        self.write_u64(w as u64);
    }
}

/// Marks an id in shared code that is not relative: one below the block's base,
/// such as a variable every block reads or an expression they all use.
const ABSOLUTE: u32 = 1 << 31;

/// `id` relative to `base`, or itself marked [`ABSOLUTE`] below it; NONE stays
/// NONE. Ids are below [`ABSOLUTE`] ([`Frames::share`] keeps a block with others on
/// the tree).
fn rel(id: u32, base: u32) -> u32 {
    if id == NONE {
        NONE
    } else if id >= base {
        id - base
    } else {
        id | ABSOLUTE
    }
}

/// Frame `f` (node `node`) sleeps until tick `due`: its nap counted, the sleepers'
/// counts moved and its alarm set. The quick forms' `Sleep` and a plan run as one
/// step end so, and must alike, for the two to leave the same state.
#[inline]
fn fall_asleep(
    f: &mut FrameState,
    node: NodeRef,
    due: u64,
    classes: &mut [usize; Class::COUNT],
    sleepers: &mut usize,
    timers: &mut super::timers::Timers,
) {
    f.nap = f.nap.wrapping_add(1);
    f.asleep = true;
    classes[Class::Sleep as usize] += 1;
    *sleepers += 1;
    timers.set(due, Alarm { node, nap: f.nap });
}

/// The live and issuing counts moved as a frame's forms moved them.
#[inline]
fn move_counts(m: Moved, live: &mut usize, classes: &mut [usize; Class::COUNT]) {
    if m.live != 0 || m.issuing != 0 {
        *live = live.saturating_add_signed(isize::from(m.live));
        let n = &mut classes[Class::Issuing as usize];
        *n = n.saturating_add_signed(isize::from(m.issuing));
    }
}

/// A quick form's variable back from `base` (never NONE), without a branch: the
/// base counts unless the id is marked [`ABSOLUTE`].
#[inline(always)]
fn var_at(id: u32, base: u32) -> u32 {
    let relative = (id >> 31).wrapping_sub(1);
    (base & relative).wrapping_add(id & !ABSOLUTE)
}

/// An id of shared code back from `base`; NONE stays NONE.
#[inline]
fn abs(id: u32, base: u32) -> u32 {
    if id == NONE {
        NONE
    } else if id & ABSOLUTE != 0 {
        id & !ABSOLUTE
    } else {
        base.wrapping_add(id)
    }
}

impl FOp {
    /// The op with its variable ids through `var`, its expression ids through
    /// `expr` and its pcs through `pc`.
    fn map(
        self,
        mut var: impl FnMut(u32) -> u32,
        mut expr: impl FnMut(u32) -> u32,
        mut pc: impl FnMut(u32) -> u32,
    ) -> FOp {
        match self {
            FOp::Assign { var: v, expr: e } => FOp::Assign {
                var: var(v),
                expr: expr(e),
            },
            FOp::Copy { to, from } => FOp::Copy {
                to: var(to),
                from: var(from),
            },
            FOp::Wait {
                seconds,
                bind,
                ticks,
            } => FOp::Wait {
                seconds: expr(seconds),
                bind: var(bind),
                ticks,
            },
            FOp::While { bind, level } => FOp::While {
                bind: var(bind),
                level,
            },
            FOp::Check {
                cond,
                bind,
                level,
                exit,
            } => FOp::Check {
                cond: expr(cond),
                bind: var(bind),
                level,
                exit: pc(exit),
            },
            FOp::EndBody { check } => FOp::EndBody { check: pc(check) },
            FOp::End => FOp::End,
        }
    }
}

impl FInstr {
    fn map(
        self,
        var: impl Fn(u32) -> u32,
        expr: impl Fn(u32) -> u32,
        stmt: impl Fn(u32) -> u32,
        mut pc: impl FnMut(u32) -> u32,
    ) -> FInstr {
        let mut checks = self.checks;
        for c in &mut checks {
            *c = pc(*c);
        }
        FInstr {
            op: self.op.map(var, expr, &mut pc),
            stmt: stmt(self.stmt),
            checks,
            ..self
        }
    }
}

impl Quick {
    /// The form with its variable ids through `var` and its pcs through `pc`.
    fn map(self, var: impl Fn(u32) -> u32, pc: impl Fn(u32) -> u32) -> Quick {
        match self {
            Quick::SetVK {
                var: v,
                src,
                field,
                op,
                next,
                k,
            } => Quick::SetVK {
                var: var(v),
                src: var(src),
                field,
                op,
                next,
                k,
            },
            Quick::SetK { var: v, next, k } => Quick::SetK {
                var: var(v),
                next,
                k,
            },
            Quick::CheckVK {
                src,
                field,
                cmp,
                next,
                out,
                exit,
                k,
            } => Quick::CheckVK {
                src: var(src),
                field,
                cmp,
                next,
                out,
                exit: pc(exit),
                k,
            },
            Quick::EndBody { check, back } => Quick::EndBody {
                check: pc(check),
                back,
            },
            q @ (Quick::Sleep { .. } | Quick::Slow) => q,
        }
    }

    /// The variables the form names.
    fn vars(&self) -> [u32; 2] {
        match *self {
            Quick::SetVK { var, src, .. } => [var, src],
            Quick::SetK { var, .. } => [var, NONE],
            Quick::CheckVK { src, .. } => [src, NONE],
            _ => [NONE; 2],
        }
    }
}

/// The flat code of every frame-shaped block of a module, one program per shape:
/// blocks whose code differs only by where their ids start share it.
#[derive(Debug, Default)]
pub(crate) struct Frames {
    /// Ids relative to a block's [`Ctx`]; pcs absolute.
    pub code: Vec<FInstr>,
    /// Per pc, the trace-off form of `code`'s instruction, variables relative too.
    pub quick: Vec<Quick>,
    /// Per pc, the way to the next sleep with every check true ([`Plan`]).
    plans: Vec<Plan>,
    /// Per pc, its program's [`Ctx::span`]: a fact of the relative quick forms,
    /// which the blocks sharing a program share, so a round need not read each
    /// block's `Ctx`.
    spans: Vec<u32>,
    /// Per block: the pc its frame starts at, or NONE when it keeps the tree.
    entry: Vec<u32>,
    /// Per block: where its ids start.
    ctx: Vec<Ctx>,
    /// The programs compiled so far by a hash of their code, to find a block's
    /// shape among them.
    shapes: HashMap<u64, Vec<u32>, BuildHasherDefault<Fx>>,
    /// A block's code and quick forms, relative, while it is compiled.
    scratch: (Vec<FInstr>, Vec<Quick>),
    period: f64,
}

impl Frames {
    /// Compiles the blocks the module gained since the last call (`decoded`: the
    /// module's expressions, decoded).
    pub fn grow(&mut self, m: &Module, decoded: &[Decoded], period: f64) {
        self.period = period;
        let mut local = Vec::new();
        for b in self.entry.len()..m.blocks.len() {
            local.clear();
            let mut checks = [NONE; MAX_LOOPS];
            let compiled = block(m, b as u32, 0, &mut checks, &mut local, period);
            let (entry, ctx) = if compiled {
                local.push(end(FOp::End, 0, &checks));
                self.share(&local, decoded)
                    .unwrap_or((NONE, Ctx::default()))
            } else {
                (NONE, Ctx::default())
            };
            self.entry.push(entry);
            self.ctx.push(ctx);
        }
    }

    /// How many variables from its frame's base block `b`'s quick forms name
    /// ([`Ctx::span`]).
    #[inline]
    pub fn span(&self, b: u32) -> u32 {
        self.ctx.get(b as usize).map_or(NONE, |c| c.span)
    }

    /// The pc of the program that runs `local` (a block's code, ids absolute, pcs
    /// from 0), compiled now unless one of its shape already is, and where its ids
    /// start: each kind at the first id of it the code names, so that ids below
    /// it (shared by many blocks) stay absolute. None for ids too large to mark.
    fn share(&mut self, local: &[FInstr], decoded: &[Decoded]) -> Option<(u32, Ctx)> {
        let (mut relative, mut quick) = std::mem::take(&mut self.scratch);
        quick.clear();
        quick.extend((0..local.len()).map(|pc| Quick::of(local, pc, decoded)));
        let large = std::cell::Cell::new(false);
        let first = |first: &mut u32, id: u32| {
            if id != NONE {
                large.set(large.get() || id >= ABSOLUTE);
                if *first == NONE {
                    *first = id;
                }
            }
            id
        };
        let (mut var, mut expr, mut stmt) = (NONE, NONE, NONE);
        for i in local {
            i.op.map(|v| first(&mut var, v), |e| first(&mut expr, e), |p| p);
            first(&mut stmt, i.stmt);
        }
        for id in quick.iter().flat_map(Quick::vars) {
            first(&mut var, id);
        }
        if large.get() {
            self.scratch = (relative, quick);
            return None;
        }
        let zero = |id: u32| if id == NONE { 0 } else { id };
        let ctx = Ctx {
            var: zero(var),
            expr: zero(expr),
            stmt: zero(stmt),
            span: 0,
        };
        relative.clear();
        relative.extend(local.iter().map(|i| {
            i.map(
                |v| rel(v, ctx.var),
                |e| rel(e, ctx.expr),
                |s| rel(s, ctx.stmt),
                |p| p,
            )
        }));
        let mut ctx = ctx;
        for q in &mut quick {
            *q = q.map(|v| rel(v, ctx.var), |p| p);
            for v in q.vars() {
                ctx.span = match v {
                    NONE => ctx.span,
                    v if v & ABSOLUTE != 0 || ctx.span == NONE => NONE,
                    v => ctx.span.max(v + 1),
                };
            }
        }
        let hash = {
            let mut h = Fx::default();
            relative.hash(&mut h);
            h.finish()
        };
        let at = |e: u32| move |p: u32| abs(p, e);
        let n = relative.len();
        let found = self.shapes.get(&hash).and_then(|entries| {
            entries.iter().copied().find(|&e| {
                let (s, t) = (e as usize, e as usize + n);
                self.code.get(s..t).is_some_and(|code| {
                    code.iter()
                        .zip(&relative)
                        .all(|(c, r)| *c == r.map(|v| v, |x| x, |x| x, at(e)))
                }) && self.quick.get(s..t).is_some_and(|qs| {
                    qs.iter()
                        .zip(&quick)
                        .all(|(c, q)| *c == q.map(|v| v, at(e)))
                })
            })
        });
        let e = match found {
            Some(e) => e,
            None => {
                let e = self.code.len() as u32;
                self.code
                    .extend(relative.iter().map(|r| r.map(|v| v, |x| x, |x| x, at(e))));
                self.quick.extend(quick.iter().map(|q| q.map(|v| v, at(e))));
                for pc in e as usize..self.quick.len() {
                    self.plans.push(Plan::of(&self.quick, pc));
                    self.spans.push(ctx.span);
                }
                self.shapes.entry(hash).or_default().push(e);
                e
            }
        };
        self.scratch = (relative, quick);
        Some((e, ctx))
    }

    /// The state a block's frame starts in, if it is frame-shaped.
    #[inline]
    pub fn start(&self, block: u32) -> Option<FrameState> {
        let pc = self
            .entry
            .get(block as usize)
            .copied()
            .filter(|&e| e != NONE)?;
        Some(FrameState {
            pc,
            nap: 0,
            block,
            base: self.ctx[block as usize].var,
            asleep: false,
            parked: false,
        })
    }

    /// The instruction at `pc` of `block`'s frame, its ids absolute.
    pub fn instr(&self, pc: u32, block: u32) -> Option<FInstr> {
        let i = *self.code.get(pc as usize)?;
        let c = self.ctx.get(block as usize).copied().unwrap_or_default();
        Some(i.map(
            |v| abs(v, c.var),
            |e| abs(e, c.expr),
            |s| abs(s, c.stmt),
            |p| p,
        ))
    }
}

/// Appends block `b`'s statements with `level` loops open around them to `code`
/// (ids absolute, pcs from the start of `code`); false when the block is not
/// frame-shaped. The caller appends the block's end.
fn block(
    m: &Module,
    b: u32,
    level: usize,
    checks: &mut [u32; MAX_LOOPS],
    out: &mut Vec<FInstr>,
    period: f64,
) -> bool {
    let code = m.block_code(BlockId(b));
    let stmt_in = |stmt: u32, op: FOp, checks: &[u32; MAX_LOOPS]| FInstr {
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
                        .map_or(0, |&secs| ticks_of(secs, period)),
                    _ => 0,
                },
            },
            Op::While { cond, body, bind } if i + 1 == code.len() && level < MAX_LOOPS => {
                let bind = bind.map_or(NONE, |v| v.0);
                out.push(stmt_in(
                    stmt,
                    FOp::While {
                        bind,
                        level: level as u8,
                    },
                    checks,
                ));
                let check = out.len();
                checks[level] = check as u32;
                out.push(FInstr {
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
                if !block(m, body.0, level + 1, checks, out, period) {
                    return false;
                }
                out.push(end(
                    FOp::EndBody {
                        check: check as u32,
                    },
                    level + 1,
                    checks,
                ));
                checks[level] = NONE;
                // The loop's exit is its block's end, which the caller appends next.
                let exit = out.len() as u32;
                if let FOp::Check { exit: e, .. } = &mut out[check].op {
                    *e = exit;
                }
                return true;
            }
            _ => return false,
        };
        out.push(stmt_in(stmt, op, checks));
    }
    true
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
    /// Its block, whose [`Ctx`] turns the shared code's ids into the module's.
    pub block: u32,
    /// Where the block's variables start ([`Ctx::var`]), for the quick forms.
    pub base: u32,
    pub asleep: bool,
    /// A loop's body that ended, kept under its `while` for the next iteration.
    pub parked: bool,
}

impl<H: Hal, C: Clock> Vm<H, C> {
    /// Starts block `block` under `parent` as a frame, if it is frame-shaped.
    pub(super) fn start_frame(&mut self, parent: u32, block: u32) -> Option<NodeRef> {
        if !self.cfg.frames {
            return None;
        }
        let f = self.frames.start(block)?;
        let r = self.nodes.alloc(parent, NONE, NONE, Kind::Frame(f));
        self.frame_account(None, Some(f.pc));
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
        if !self.tracing()
            && let Some(overrun) = self.run_quick::<false>(idx)
        {
            return overrun;
        }
        let Kind::Frame(mut f) = self.nodes.get(idx).kind else {
            return false;
        };
        let from = f.pc;
        loop {
            let Some(ins) = self.frames.instr(f.pc, f.block) else {
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
                    self.frame_sleep(idx, &mut f, ticks);
                    self.frame_store(idx, f, from);
                    return false;
                }
                FOp::While { bind, level } => {
                    self.ops_left -= 1;
                    f.pc += 1;
                    self.issue_event(stmt);
                    self.bind_issue(bind, stmt);
                    if self.tracing()
                        && let Some(i) = self.frame_iters(idx).get_mut(usize::from(level))
                    {
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
                            if self.tracing() {
                                let mut iteration = 0;
                                if let Some(i) = self.frame_iters(idx).get_mut(usize::from(level)) {
                                    *i = i.wrapping_add(1);
                                    iteration = *i;
                                }
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

    /// A visit of frame `idx` with the trace off, on the instructions' [`Quick`]
    /// forms, as Lua's `luaV_execute` runs: a dense array, a `match`, the state in
    /// locals, nothing allocated. Returns what [`Vm::run_frame`] returns, or `None`
    /// at a [`Quick::Slow`] instruction, the frame's state stored, for the general
    /// loop to go on from. `FUSE` (from [`Vm::run_round`] only) runs on where the
    /// frame would queue itself, as its later visits of the round would.
    #[inline]
    fn run_quick<const FUSE: bool>(&mut self, idx: u32) -> Option<bool> {
        let Vm {
            nodes,
            vars,
            ready,
            timers,
            frames,
            ops_left,
            end_code,
            tick,
            ..
        } = self;
        let super::nodes::Nodes {
            all,
            live,
            classes,
            sleepers,
            ..
        } = nodes;
        let node = all.get_mut(idx as usize)?;
        let epoch = node.epoch;
        let Kind::Frame(f) = &mut node.kind else {
            return None;
        };
        let (mut moved_live, mut moved_issuing) = (0i8, 0i8);
        let mut step = |m: Moved| {
            moved_live += m.live;
            moved_issuing += m.issuing;
        };
        let mut queue = false;
        let result = loop {
            match frames.quick.get(f.pc as usize) {
                Some(&Quick::SetVK {
                    var,
                    src,
                    field,
                    op,
                    next,
                    k,
                }) => {
                    if *ops_left == 0 {
                        break Some(true);
                    }
                    // The statement's op and its expression's three.
                    *ops_left = (*ops_left - 1).saturating_sub(Quick::SET_VK - 1);
                    let v = op.apply(vars.field(var_at(src, f.base), field), k);
                    // What `assign` does after its evaluation, with the trace off.
                    let var = var_at(var, f.base);
                    vars.assign(var, v);
                    // In a round run in one go nothing hears it (`Vm::run_round`).
                    if !FUSE && vars.queue_wake(var) {
                        ready.push_back(Ready::Wake(var).into());
                    }
                    f.pc += 1;
                    step(next);
                }
                Some(&Quick::SetK { var, next, k }) => {
                    if *ops_left == 0 {
                        break Some(true);
                    }
                    *ops_left = (*ops_left - 1).saturating_sub(Quick::SET_K - 1);
                    let var = var_at(var, f.base);
                    vars.assign(var, k);
                    if !FUSE && vars.queue_wake(var) {
                        ready.push_back(Ready::Wake(var).into());
                    }
                    f.pc += 1;
                    step(next);
                }
                Some(&Quick::Sleep { next, ticks }) => {
                    if *ops_left == 0 {
                        break Some(true);
                    }
                    // The statement's op and its constant's.
                    *ops_left = (*ops_left - 1).saturating_sub(Quick::SLEEP - 1);
                    f.pc += 1;
                    step(next);
                    let due = tick.saturating_add(u64::from(ticks));
                    fall_asleep(f, NodeRef { idx, epoch }, due, classes, sleepers, timers);
                    break Some(false);
                }
                Some(&Quick::CheckVK {
                    src,
                    field,
                    cmp,
                    next,
                    out,
                    exit,
                    k,
                }) => {
                    // The check's op and its expression's three.
                    *ops_left = ops_left.saturating_sub(Quick::CHECK_VK);
                    // The loop's iteration is counted only for `start` events: with
                    // the trace on, which takes the general path.
                    if cmp.holds(vars.field(var_at(src, f.base), field), k) {
                        f.pc += 1;
                        step(next);
                        if FUSE {
                            continue;
                        }
                        queue = true;
                        break Some(false);
                    }
                    // `end_in_place` with the trace off and nothing bound.
                    *end_code = None;
                    f.pc = exit;
                    step(out);
                }
                Some(&Quick::EndBody { check, back }) => {
                    *end_code = None;
                    f.pc = check;
                    step(back);
                    if FUSE {
                        continue;
                    }
                    queue = true;
                    break Some(false);
                }
                _ => break None,
            }
        };
        let moved = Moved {
            live: moved_live,
            issuing: moved_issuing,
        };
        move_counts(moved, live, classes);
        if queue && !node.queued {
            node.queued = true;
            ready.push_back(Ready::Node(NodeRef { idx, epoch }).into());
        }
        result
    }

    /// Runs the whole ready queue in one go, each frame's visits of this tick one
    /// after the other (its check and its body right after its body's end, as Lua
    /// runs a loop), where the tree's order would visit every queued frame once,
    /// then each again in a later turn of the queue, and so on. Returns false, having
    /// done nothing, unless the two orders are provably the same to anything that
    /// can look, which holds when, with the trace off:
    /// - every entry is a frame that reaches its next sleep on quick forms alone
    ///   ([`foresee`]), so none ends, none runs the general path, and no entry but
    ///   these frames runs in the tick;
    /// - no variable they write is heard (no wait, guard or queued wake), and no two
    ///   of them name one variable (the variables each names lie above the last
    ///   one's, [`Ctx::span`]), so no frame reads what another writes and each
    ///   computes what it would in the tree's order;
    /// - the visits each takes do not fall along the queue, so their alarms are set
    ///   in the tree's order (it sets them round by round) and fire in it;
    /// - the budget covers every op of the round, so none overruns in either order.
    ///
    /// What is left to see after the tick (variables, counts, alarms, naps, the
    /// frames' pcs) is then the same.
    pub(super) fn run_round(&mut self) -> bool {
        if self.tracing() || self.ready.is_empty() {
            return false;
        }
        // `visits`: the most any frame so far takes; `free`: the first variable no
        // frame so far names.
        let (mut ops, mut visits, mut free) = (0u64, 0u32, 0u32);
        // Per entry, one bit: its frame's plan holds (its checks true), so the run
        // goes along it without evaluating them again.
        let planned = &mut self.round_planned;
        planned.clear();
        planned.resize(self.ready.len().div_ceil(64), 0);
        for (i, p) in self.ready.iter().enumerate() {
            let Ready::Node(r) = Ready::from(*p) else {
                return false;
            };
            // Entries of ended nodes, skipped in either order.
            let Some(n) = self.nodes.all.get(r.idx as usize) else {
                continue;
            };
            if n.epoch != r.epoch || matches!(n.kind, Kind::Free) {
                continue;
            }
            let Kind::Frame(f) = &n.kind else {
                return false;
            };
            let span = self.frames.span(f.block);
            if f.asleep || f.parked || span == NONE || f.base < free {
                return false;
            }
            free = f.base.saturating_add(span);
            match self.frames.foresee(&self.vars, f) {
                Some((v, o, along)) if v >= visits => {
                    visits = v;
                    ops += u64::from(o);
                    planned[i / 64] |= u64::from(along) << (i % 64);
                }
                _ => return false,
            }
        }
        if ops > u64::from(self.ops_left) {
            return false;
        }
        // Nothing in the round queues anything, so the entries keep their places.
        let mut i = 0usize;
        while let Some(p) = self.ready.pop_front() {
            let along = self
                .round_planned
                .get(i / 64)
                .is_some_and(|w| w >> (i % 64) & 1 != 0);
            i += 1;
            let Ready::Node(r) = Ready::from(p) else {
                continue;
            };
            let Some(n) = self.nodes.all.get_mut(r.idx as usize) else {
                continue;
            };
            if n.epoch != r.epoch || matches!(n.kind, Kind::Free) {
                continue;
            }
            n.queued = false;
            if !(along && self.run_plan(r.idx)) {
                self.run_quick::<true>(r.idx);
            }
        }
        self.rounds_fused += 1;
        true
    }

    /// Frame `idx`'s visits of a round run in one go, as one step along its pc's
    /// [`Plan`], where it has one that ends in a sleep: what [`Vm::run_quick`] with
    /// `FUSE` does along that way (the same ops charged, writes made, counts moved,
    /// alarm set), without dispatching each form. The caller has found the plan's
    /// checks true ([`Frames::foresee`]), and they still are: the frames before this
    /// one in the round wrote their own variables only, and no check of a plan reads
    /// what the way writes before it ([`Plan::of`]). Returns false, having done
    /// nothing, where the pc has no plan that ends in a sleep (the quick forms take
    /// it).
    #[inline]
    fn run_plan(&mut self, idx: u32) -> bool {
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
        let super::nodes::Nodes {
            all,
            live,
            classes,
            sleepers,
            ..
        } = nodes;
        let Some(node) = all.get_mut(idx as usize) else {
            return false;
        };
        let epoch = node.epoch;
        let Kind::Frame(f) = &mut node.kind else {
            return false;
        };
        let along = Along {
            frames,
            vars,
            timers,
            ops_left,
            end_code,
            tick: *tick,
            live,
            classes,
            sleepers,
        };
        if !along.go(f, NodeRef { idx, epoch }) {
            return false;
        }
        *plans_run += 1;
        true
    }

    /// The iterations of frame `idx`'s open loops, for their `start` events: kept
    /// beside the arena, and only with the trace on, which alone reads them (a
    /// frame's node holds what every step needs).
    fn frame_iters(&mut self, idx: u32) -> &mut [u32; MAX_LOOPS] {
        let i = idx as usize;
        if self.frame_iters.len() <= i {
            self.frame_iters.resize(i + 1, [0; MAX_LOOPS]);
        }
        &mut self.frame_iters[i]
    }

    /// Frame `idx` (its state `f`) goes to sleep for `ticks`: a wheel alarm names it
    /// and this sleep.
    #[inline]
    fn frame_sleep(&mut self, idx: u32, f: &mut FrameState, ticks: u64) {
        f.nap = f.nap.wrapping_add(1);
        f.asleep = true;
        self.nodes.classes[Class::Sleep as usize] += 1;
        self.nodes.sleepers += 1;
        let node = self.nodes.at(idx);
        self.timers
            .set(self.tick.saturating_add(ticks), Alarm { node, nap: f.nap });
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
    pub(super) fn wake_frame(&mut self, a: &Alarm) -> bool {
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
                .and_then(|pc| self.frames.quick.get(pc as usize))
                .is_some_and(|w| matches!(w, Quick::Sleep { .. }));
        if !unbound || n.queued {
            return false;
        }
        f.asleep = false;
        n.queued = true;
        self.ready.push_back(Ready::Node(a.node).into());
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
            let Some(c) = self.frames.instr(check, f.block) else {
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
                    if Ready::from(*e) == Ready::Node(self.nodes.at(idx)) {
                        *e = Packed::from(Ready::Node(NodeRef {
                            idx: NONE,
                            epoch: 0,
                        }));
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
            if let Some(c) = self.frames.instr(at.checks[l], f.block) {
                hit(FrameHit::Loop { frame: r, level: l }, c.stmt);
            }
        }
        if f.asleep
            && let Some(w) =
                f.pc.checked_sub(1)
                    .and_then(|pc| self.frames.instr(pc, f.block))
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

/// Visits a frame may take in a round that [`Vm::run_round`] runs in one go: past
/// them it is taken for a loop that does not sleep.
const ROUND_VISITS: u32 = 8;

/// Variables a frame may write in a round that [`Vm::run_round`] runs in one go.
const ROUND_WRITES: usize = 4;

/// The way from a pc to the next sleep on quick forms with every check true, worked
/// out when the code is compiled, so that [`Frames::foresee`] evaluates its checks
/// and looks at its writes and nothing else. It has one only where no check on the
/// way reads a variable written before it on the way (the counting loop's: from its
/// body's end, `c<100`, then `c=c+1` and the sleep); elsewhere `visits` is 0.
///
/// A round run in one go also runs a frame along its plan as one step
/// ([`Vm::run_plan`]), Lua's superinstruction: the ops charged and the counts moved
/// once, the checks (true, as the look ahead found them) not run again, then the
/// writes and the sleep.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct Plan {
    visits: u8,
    ops: u32,
    /// The checks' pcs, NONE beyond.
    checks: [u32; 2],
    /// The variables written, relative to the frame's base, NONE beyond.
    writes: [u32; 2],
    /// The pcs of the writes, in the order the way takes them, NONE beyond; a way
    /// of more writes is not run as one step (`steps[0]` NONE and `sleep` 0).
    steps: [u32; PLAN_STEPS],
    /// The pc of the sleep the way ends in; 0: the way is not run as one step.
    sleep: u32,
    /// The counts' moves along the whole way, each form's added up.
    moved: Moved,
    /// The way passes a body's end (which spends the end code, as `EndBody` does).
    ends: bool,
}

/// Writes a [`Plan`] run as one step may take.
const PLAN_STEPS: usize = 3;

impl Plan {
    fn of(quick: &[Quick], from: usize) -> Plan {
        let none = Plan::default();
        let mut plan = Plan {
            visits: 1,
            ops: 0,
            checks: [NONE; 2],
            writes: [NONE; 2],
            steps: [NONE; PLAN_STEPS],
            sleep: 0,
            moved: Moved::default(),
            ends: false,
        };
        let (mut steps, mut fits) = (0, true);
        let step = |plan: &mut Plan, m: Moved| {
            plan.moved.live += m.live;
            plan.moved.issuing += m.issuing;
        };
        let add =
            |list: &mut [u32; 2], x: u32| match list.iter_mut().find(|s| **s == NONE || **s == x) {
                Some(s) => {
                    *s = x;
                    true
                }
                None => false,
            };
        let mut pc = from;
        while u32::from(plan.visits) <= ROUND_VISITS {
            let (ops, wrote) = match quick.get(pc) {
                Some(&Quick::SetVK { var, next, .. }) | Some(&Quick::SetK { var, next, .. }) => {
                    step(&mut plan, next);
                    match plan.steps.get_mut(steps) {
                        Some(s) => *s = pc as u32,
                        None => fits = false,
                    }
                    steps += 1;
                    let ops = match quick[pc] {
                        Quick::SetVK { .. } => Quick::SET_VK,
                        _ => Quick::SET_K,
                    };
                    (ops, var)
                }
                Some(&Quick::Sleep { next, .. }) => {
                    step(&mut plan, next);
                    plan.ops += Quick::SLEEP;
                    if fits && pc > 0 {
                        plan.sleep = pc as u32;
                    } else {
                        plan.steps = [NONE; PLAN_STEPS];
                    }
                    return plan;
                }
                Some(&Quick::CheckVK { src, next, .. }) => {
                    if plan.writes.contains(&src) || !add(&mut plan.checks, pc as u32) {
                        return none;
                    }
                    step(&mut plan, next);
                    plan.visits += 1;
                    (Quick::CHECK_VK, NONE)
                }
                Some(&Quick::EndBody { check, back }) => {
                    step(&mut plan, back);
                    plan.ends = true;
                    plan.visits += 1;
                    pc = check as usize;
                    continue;
                }
                _ => return none,
            };
            plan.ops += ops;
            if wrote != NONE && !add(&mut plan.writes, wrote) {
                return none;
            }
            pc += 1;
        }
        none
    }
}

/// What running a frame along its [`Plan`] touches, borrowed apart from the VM, so
/// that a round run from the ready queue ([`Vm::run_plan`]) and one run straight
/// from the wheel's due slot (`slot.rs`) take the one way.
pub(super) struct Along<'a> {
    pub frames: &'a Frames,
    pub vars: &'a mut super::vars::Vars,
    pub timers: &'a mut super::timers::Timers,
    pub ops_left: &'a mut u32,
    pub end_code: &'a mut Option<super::safety::Code>,
    pub tick: u64,
    pub live: &'a mut usize,
    pub classes: &'a mut [usize; Class::COUNT],
    pub sleepers: &'a mut usize,
}

impl Along<'_> {
    /// Frame `f` (node `node`), awake, run along its pc's plan as one step: what
    /// [`Vm::run_quick`] with `FUSE` does along that way (the same ops charged,
    /// writes made, counts moved, alarm set), without dispatching each form.
    /// Returns false, having done nothing, where the pc has no plan that ends in a
    /// sleep.
    #[inline(always)]
    pub fn go(self, f: &mut FrameState, node: NodeRef) -> bool {
        let Along {
            frames,
            vars,
            timers,
            ops_left,
            end_code,
            tick,
            live,
            classes,
            sleepers,
        } = self;
        let Some(plan) = frames.plans.get(f.pc as usize) else {
            return false;
        };
        let Some(&Quick::Sleep { ticks, .. }) = frames.quick.get(plan.sleep as usize) else {
            return false;
        };
        if plan.sleep == 0 {
            return false;
        }
        // The round's budget covers its ops: charged at once, as one by one.
        *ops_left = ops_left.saturating_sub(plan.ops);
        if plan.ends {
            *end_code = None;
        }
        for s in plan.steps {
            match frames.quick.get(s as usize) {
                Some(&Quick::SetVK {
                    var,
                    src,
                    field,
                    op,
                    k,
                    ..
                }) => {
                    let v = op.apply(vars.field(var_at(src, f.base), field), k);
                    vars.assign(var_at(var, f.base), v);
                }
                Some(&Quick::SetK { var, k, .. }) => {
                    vars.assign(var_at(var, f.base), k);
                }
                _ => break,
            }
        }
        f.pc = plan.sleep + 1;
        let due = tick.saturating_add(u64::from(ticks));
        fall_asleep(f, node, due, classes, sleepers, timers);
        move_counts(plan.moved, live, classes);
        true
    }
}

impl Frames {
    /// What frame `f`'s visits from the ready queue come to, up to its next sleep,
    /// with the trace off: how many visits and the ops charged ([`trace_ahead`]),
    /// from the pc's [`Plan`] where it has one and its checks hold.
    #[inline]
    fn foresee(&self, vars: &super::vars::Vars, f: &FrameState) -> Option<(u32, u32, bool)> {
        let plan = self.plans.get(f.pc as usize).copied().unwrap_or_default();
        let off = |(v, o)| (v, o, false);
        if plan.visits == 0 {
            return trace_ahead(self, vars, f).map(off);
        }
        for c in plan.checks {
            if c == NONE {
                break;
            }
            if let Some(&Quick::CheckVK {
                src, field, cmp, k, ..
            }) = self.quick.get(c as usize)
                && !cmp.holds(vars.field(var_at(src, f.base), field), k)
            {
                // Another way: out of the loop.
                return trace_ahead(self, vars, f).map(off);
            }
        }
        for w in plan.writes {
            if w != NONE && !vars.quiet(var_at(w, f.base)) {
                return None;
            }
        }
        Some((u32::from(plan.visits), plan.ops, true))
    }
}

/// What frame `f`'s visits from the ready queue come to, up to its next sleep, with
/// the trace off: how many visits (it queues itself after a body's end and a true
/// check) and the ops charged. Follows the quick forms without running them: the
/// values the frame writes are kept aside for its own later reads. None when it
/// reaches any other form, writes a variable something hears, or writes more than
/// [`ROUND_WRITES`] variables or takes more than [`ROUND_VISITS`] visits.
fn trace_ahead(frames: &Frames, vars: &super::vars::Vars, f: &FrameState) -> Option<(u32, u32)> {
    let mut written = [(NONE, 0.0); ROUND_WRITES];
    // What an assignment leaves: the value, and status 1.
    let read =
        |written: &[(u32, f64)], v: u32, field: Field| match written.iter().find(|w| w.0 == v) {
            Some(&(_, value)) if field == Field::Value => value,
            Some(_) if field == Field::Status => 1.0,
            _ => vars.field(v, field),
        };
    let write = |written: &mut [(u32, f64)], v: u32, value: f64| {
        if !vars.quiet(v) {
            return false;
        }
        match written.iter_mut().find(|w| w.0 == v || w.0 == NONE) {
            Some(w) => {
                *w = (v, value);
                true
            }
            None => false,
        }
    };
    let (mut pc, mut visits, mut ops) = (f.pc, 1, 0);
    while visits <= ROUND_VISITS {
        match *frames.quick.get(pc as usize)? {
            Quick::SetVK {
                var,
                src,
                field,
                op,
                k,
                ..
            } => {
                ops += Quick::SET_VK;
                let v = op.apply(read(&written, var_at(src, f.base), field), k);
                if !write(&mut written, var_at(var, f.base), v) {
                    return None;
                }
                pc += 1;
            }
            Quick::SetK { var, k, .. } => {
                ops += Quick::SET_K;
                if !write(&mut written, var_at(var, f.base), k) {
                    return None;
                }
                pc += 1;
            }
            Quick::Sleep { .. } => return Some((visits, ops + Quick::SLEEP)),
            Quick::CheckVK {
                src,
                field,
                cmp,
                exit,
                k,
                ..
            } => {
                ops += Quick::CHECK_VK;
                if cmp.holds(read(&written, var_at(src, f.base), field), k) {
                    pc += 1;
                    visits += 1;
                } else {
                    pc = exit;
                }
            }
            Quick::EndBody { check, .. } => {
                pc = check;
                visits += 1;
            }
            Quick::Slow => return None,
        }
    }
    None
}

/// Something of a frame `break(pattern)` ends.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum FrameHit {
    Loop { frame: NodeRef, level: usize },
    Sleep { frame: NodeRef, nap: u32 },
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(op: FOp, live: u8, issuing: bool) -> FInstr {
        FInstr {
            op,
            stmt: 0,
            live,
            issuing,
            checks: [NONE; MAX_LOOPS],
            loops: 0,
        }
    }

    #[test]
    fn the_counting_loop_runs_on_quick_forms_but_its_while() {
        // `c=0` / `while(c<100)` / `c=c+1` / `wait(0.01)` / `endwhile`, as
        // `block` lays it out; expressions 0 `0`, 1 `c<100`, 2 `c+1`, 3 `0.01`.
        let c = Operand::Field(0, Field::Value);
        let decoded = [
            Decoded {
                shape: Shape::One(Operand::Const(0.0)),
                len: 1,
            },
            Decoded {
                shape: Shape::Two(c, Operand::Const(100.0), Bin::Cmp(Cmp::Lt)),
                len: 3,
            },
            Decoded {
                shape: Shape::Two(c, Operand::Const(1.0), Bin::Add),
                len: 3,
            },
            Decoded {
                shape: Shape::One(Operand::Const(0.01)),
                len: 1,
            },
        ];
        let code = [
            at(FOp::Assign { var: 0, expr: 0 }, 0, true),
            at(
                FOp::While {
                    bind: NONE,
                    level: 0,
                },
                0,
                true,
            ),
            at(
                FOp::Check {
                    cond: 1,
                    bind: NONE,
                    level: 0,
                    exit: 6,
                },
                1,
                false,
            ),
            at(FOp::Assign { var: 0, expr: 2 }, 2, true),
            at(
                FOp::Wait {
                    seconds: 3,
                    bind: NONE,
                    ticks: 1,
                },
                2,
                true,
            ),
            at(FOp::EndBody { check: 2 }, 2, true),
            at(FOp::End, 0, true),
        ];
        let quick: Vec<Quick> = (0..code.len())
            .map(|pc| Quick::of(&code, pc, &decoded))
            .collect();
        let same = Moved {
            live: 0,
            issuing: 0,
        };
        assert_eq!(
            quick[0],
            Quick::SetK {
                var: 0,
                next: same,
                k: 0.0
            }
        );
        assert_eq!(quick[1], Quick::Slow);
        assert_eq!(
            quick[2],
            Quick::CheckVK {
                src: 0,
                field: Field::Value,
                cmp: Cmp::Lt,
                // Into the body: its loop and body live, a block issuing again.
                next: Moved {
                    live: 1,
                    issuing: 1,
                },
                // Out of the loop: the block's end.
                out: Moved {
                    live: -1,
                    issuing: 1,
                },
                exit: 6,
                k: 100.0,
            }
        );
        assert_eq!(
            quick[3],
            Quick::SetVK {
                var: 0,
                src: 0,
                field: Field::Value,
                op: Arith::Add,
                next: same,
                k: 1.0,
            }
        );
        assert_eq!(
            quick[4],
            Quick::Sleep {
                next: same,
                ticks: 1
            }
        );
        assert_eq!(
            quick[5],
            Quick::EndBody {
                check: 2,
                back: Moved {
                    live: -1,
                    issuing: -1,
                },
            }
        );
        assert_eq!(quick[6], Quick::Slow);
        // A bound wait, a division and a wait whose time is computed keep the
        // general path.
        let bound = at(
            FOp::Wait {
                seconds: 3,
                bind: 1,
                ticks: 1,
            },
            0,
            true,
        );
        assert_eq!(Quick::of(&[bound], 0, &decoded), Quick::Slow);
        let computed = at(
            FOp::Wait {
                seconds: 2,
                bind: NONE,
                ticks: 0,
            },
            0,
            true,
        );
        assert_eq!(Quick::of(&[computed], 0, &decoded), Quick::Slow);
    }

    /// The counting block (`c=0` / `while(c<k)` / `c=c+1` / `wait(0.01)` /
    /// `endwhile`) with its variable at `var`, its expressions from `expr` and its
    /// statements from `stmt`, as [`block`] lays it out, and its decoded expressions.
    fn counting(var: u32, expr: u32, stmt: u32, k: f64) -> (Vec<FInstr>, Vec<Decoded>) {
        let c = Operand::Field(var, Field::Value);
        let mut decoded = vec![
            Decoded {
                shape: Shape::One(Operand::Const(0.0)),
                len: 1,
            };
            expr as usize
        ];
        decoded.extend([
            Decoded {
                shape: Shape::One(Operand::Const(0.0)),
                len: 1,
            },
            Decoded {
                shape: Shape::Two(c, Operand::Const(k), Bin::Cmp(Cmp::Lt)),
                len: 3,
            },
            Decoded {
                shape: Shape::Two(c, Operand::Const(1.0), Bin::Add),
                len: 3,
            },
            Decoded {
                shape: Shape::One(Operand::Const(0.01)),
                len: 1,
            },
        ]);
        let with = |op, live, issuing, s: u32| FInstr {
            stmt: stmt + s,
            ..at(op, live, issuing)
        };
        let code = vec![
            with(FOp::Assign { var, expr }, 0, true, 0),
            with(
                FOp::While {
                    bind: NONE,
                    level: 0,
                },
                0,
                true,
                1,
            ),
            with(
                FOp::Check {
                    cond: expr + 1,
                    bind: NONE,
                    level: 0,
                    exit: 6,
                },
                1,
                false,
                1,
            ),
            with(
                FOp::Assign {
                    var,
                    expr: expr + 2,
                },
                2,
                true,
                2,
            ),
            with(
                FOp::Wait {
                    seconds: expr + 3,
                    bind: NONE,
                    ticks: 1,
                },
                2,
                true,
                3,
            ),
            FInstr {
                stmt: NONE,
                ..at(FOp::EndBody { check: 2 }, 2, true)
            },
            FInstr {
                stmt: NONE,
                ..at(FOp::End, 0, true)
            },
        ];
        (code, decoded)
    }

    #[test]
    fn blocks_of_one_shape_share_one_program() {
        let mut frames = Frames::default();
        let (first, decoded) = counting(3, 4, 10, 100.0);
        assert_eq!(
            frames.share(&first, &decoded),
            Some((
                0,
                Ctx {
                    var: 3,
                    expr: 4,
                    stmt: 10,
                    span: 1,
                }
            ))
        );
        // Another block of the shape, its ids further on: the same program.
        let (second, decoded) = counting(7, 8, 14, 100.0);
        let (entry, ctx) = frames.share(&second, &decoded).expect("shares");
        assert_eq!(entry, 0);
        assert_eq!(frames.code.len(), first.len());
        // Its instructions, the ids made absolute again, are its own.
        frames.ctx.push(Ctx::default());
        frames.ctx.push(ctx);
        for (pc, own) in second.iter().enumerate() {
            assert_eq!(frames.instr(pc as u32, 1), Some(*own));
        }
        // And its quick forms name its variable from the frame's base.
        assert!(matches!(
            frames.quick[3],
            Quick::SetVK { var: 0, src: 0, .. }
        ));
        // A block that counts to another bound is another program, after the first.
        let (third, decoded) = counting(11, 12, 18, 50.0);
        let (entry, _) = frames.share(&third, &decoded).expect("shares");
        assert_eq!(entry, first.len() as u32);
        assert_eq!(
            frames.quick[entry as usize + 5],
            Quick::EndBody {
                check: entry + 2,
                back: Moved {
                    live: -1,
                    issuing: -1
                },
            }
        );
        // Blocks that wait on one expression, below their own: it stays absolute,
        // and they share a program of their own.
        let shared_wait = |var, expr, stmt| {
            let (mut code, decoded) = counting(var, expr, stmt, 100.0);
            if let FOp::Wait { seconds, .. } = &mut code[4].op {
                *seconds = 1;
            }
            (code, decoded)
        };
        let (a, decoded) = shared_wait(20, 20, 30);
        let (e1, _) = frames.share(&a, &decoded).expect("shares");
        let (b, decoded) = shared_wait(24, 30, 40);
        let (e2, c) = frames.share(&b, &decoded).expect("shares");
        assert_eq!((e1, e1 as usize + a.len()), (e2, frames.code.len()));
        frames.ctx[1] = c;
        assert_eq!(frames.instr(e2 + 4, 1), Some(b[4]));
        // The quick forms' branch-free read of a variable agrees.
        for id in [0, 5, 7 | ABSOLUTE, ABSOLUTE - 1] {
            assert_eq!(var_at(id, 40), abs(id, 40));
        }
        // An id too large to mark keeps the block on the tree.
        let (huge, decoded) = counting(ABSOLUTE, 0, 0, 100.0);
        assert_eq!(frames.share(&huge, &decoded), None);
    }
}

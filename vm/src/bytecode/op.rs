//! The instruction set. Statement instructions ([`Op`]) run in a block; expression
//! instructions ([`ExprOp`]) run on a small f64 stack. `docs/bytecode.md` lists every
//! opcode on one line; a test keeps that table and [`Opcode::ALL`] in step.

use ilmr_stdlib::{Command, Field};
use serde::{Deserialize, Serialize};

use super::ids::{BlockId, ConstId, ExprId, NameId, UnitId, VarId};
use super::serde_field;

/// One argument of an `ISSUE`, in source order.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Arg {
    /// A number, evaluated when the command is issued.
    Num(ExprId),
    /// A keyword of the command's grammar, a robot-model name (device, object, mode,
    /// service) or a path name. The VM tells keywords apart with the catalogue.
    Word(NameId),
    /// `key = value` (`d=90`, `rc=0.5`).
    Setting { key: NameId, value: ExprId },
    /// A variable by name (`gotoxy(door)`); read when the command starts.
    Var(VarId),
}

/// A contiguous run of [`Arg`]s in `Module::args`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct ArgRange {
    pub start: u32,
    pub len: u32,
}

/// A statement instruction. Every instruction carries the statement it came from.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "op")]
pub enum Op {
    /// Issue a define, movement or action command of the catalogue.
    Issue {
        command: Command,
        args: ArgRange,
        bind: Option<VarId>,
    },
    /// `var = expression`.
    Assign {
        var: VarId,
        expr: ExprId,
    },
    /// `to = from` where `from` is a record (a position): every field of `from`'s
    /// record, and how its command ended, is copied to `to`.
    Copy {
        to: VarId,
        from: VarId,
    },
    /// `wait(seconds)`: holds its block.
    WaitTime {
        seconds: ExprId,
        bind: Option<VarId>,
    },
    /// `wait(variable)`: holds its block until the variable's status is 1.
    WaitVar {
        var: VarId,
        bind: Option<VarId>,
    },
    /// `if(cond) body endif`: a guard that runs `body` once when `cond` holds.
    If {
        cond: ExprId,
        body: BlockId,
        bind: Option<VarId>,
    },
    /// `while(cond) body endwhile`.
    While {
        cond: ExprId,
        body: BlockId,
        bind: Option<VarId>,
    },
    /// A skill call: starts every top-level block of `unit`.
    Call {
        unit: UnitId,
        bind: Option<VarId>,
    },
    /// `break(pattern)`.
    Break {
        pattern: NameId,
    },
    /// Bare `break`.
    BreakAll,
    Stop,
    Cont,
    /// `priority = highest`; only valid as the first instruction of a block.
    Priority,
    /// `clear(var)`.
    Clear {
        var: VarId,
    },
}

/// An instruction and the statement (source map entry) it was lowered from.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Instr {
    #[serde(flatten)]
    pub op: Op,
    pub stmt: super::ids::StmtId,
}

impl Instr {
    pub fn new(op: Op, stmt: super::ids::StmtId) -> Instr {
        Instr { op, stmt }
    }
}

/// An expression instruction. Expressions are postfix; comparisons push 1 or 0.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ExprOp {
    Const(ConstId),
    Field(VarId, #[serde(with = "serde_field")] Field),
    Add,
    Sub,
    Mul,
    Div,
    Neg,
    Lt,
    Le,
    Eq,
    Ne,
    Gt,
    Ge,
    /// Two position variables are at the same place (within the VM's tolerance).
    PosEq(VarId, VarId),
}

impl ExprOp {
    /// Values popped and pushed.
    pub fn stack_effect(self) -> (u32, u32) {
        match self {
            ExprOp::Const(_) | ExprOp::Field(..) | ExprOp::PosEq(..) => (0, 1),
            ExprOp::Neg => (1, 1),
            _ => (2, 1),
        }
    }
}

/// The opcodes, statement then expression, in the order of `docs/bytecode.md`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[repr(u8)]
pub enum Opcode {
    Issue,
    Assign,
    Copy,
    WaitTime,
    WaitVar,
    If,
    While,
    Call,
    Break,
    BreakAll,
    Stop,
    Cont,
    Priority,
    Clear,
    Const,
    Field,
    Add,
    Sub,
    Mul,
    Div,
    Neg,
    Lt,
    Le,
    Eq,
    Ne,
    Gt,
    Ge,
    PosEq,
}

// Adding an opcode means adding it to ALL, to the mnemonic table below and to the doc
// table; `docs_table_matches_opcodes` fails until all three agree.
const _: () = assert!(Opcode::ALL.len() == Opcode::PosEq as usize + 1);

impl Opcode {
    pub const ALL: [Opcode; 28] = [
        Opcode::Issue,
        Opcode::Assign,
        Opcode::Copy,
        Opcode::WaitTime,
        Opcode::WaitVar,
        Opcode::If,
        Opcode::While,
        Opcode::Call,
        Opcode::Break,
        Opcode::BreakAll,
        Opcode::Stop,
        Opcode::Cont,
        Opcode::Priority,
        Opcode::Clear,
        Opcode::Const,
        Opcode::Field,
        Opcode::Add,
        Opcode::Sub,
        Opcode::Mul,
        Opcode::Div,
        Opcode::Neg,
        Opcode::Lt,
        Opcode::Le,
        Opcode::Eq,
        Opcode::Ne,
        Opcode::Gt,
        Opcode::Ge,
        Opcode::PosEq,
    ];

    pub fn mnemonic(self) -> &'static str {
        match self {
            Opcode::Issue => "ISSUE",
            Opcode::Assign => "ASSIGN",
            Opcode::Copy => "COPY",
            Opcode::WaitTime => "WAITTIME",
            Opcode::WaitVar => "WAITVAR",
            Opcode::If => "IF",
            Opcode::While => "WHILE",
            Opcode::Call => "CALL",
            Opcode::Break => "BREAK",
            Opcode::BreakAll => "BREAKALL",
            Opcode::Stop => "STOP",
            Opcode::Cont => "CONT",
            Opcode::Priority => "PRIORITY",
            Opcode::Clear => "CLEAR",
            Opcode::Const => "CONST",
            Opcode::Field => "FIELD",
            Opcode::Add => "ADD",
            Opcode::Sub => "SUB",
            Opcode::Mul => "MUL",
            Opcode::Div => "DIV",
            Opcode::Neg => "NEG",
            Opcode::Lt => "LT",
            Opcode::Le => "LE",
            Opcode::Eq => "EQ",
            Opcode::Ne => "NE",
            Opcode::Gt => "GT",
            Opcode::Ge => "GE",
            Opcode::PosEq => "POSEQ",
        }
    }
}

impl Op {
    pub fn opcode(&self) -> Opcode {
        match self {
            Op::Issue { .. } => Opcode::Issue,
            Op::Assign { .. } => Opcode::Assign,
            Op::Copy { .. } => Opcode::Copy,
            Op::WaitTime { .. } => Opcode::WaitTime,
            Op::WaitVar { .. } => Opcode::WaitVar,
            Op::If { .. } => Opcode::If,
            Op::While { .. } => Opcode::While,
            Op::Call { .. } => Opcode::Call,
            Op::Break { .. } => Opcode::Break,
            Op::BreakAll => Opcode::BreakAll,
            Op::Stop => Opcode::Stop,
            Op::Cont => Opcode::Cont,
            Op::Priority => Opcode::Priority,
            Op::Clear { .. } => Opcode::Clear,
        }
    }

    /// The variable this instruction binds (`v = ...`), if any.
    pub fn bind(&self) -> Option<VarId> {
        match *self {
            Op::Issue { bind, .. }
            | Op::WaitTime { bind, .. }
            | Op::WaitVar { bind, .. }
            | Op::If { bind, .. }
            | Op::While { bind, .. }
            | Op::Call { bind, .. } => bind,
            _ => None,
        }
    }
}

impl ExprOp {
    pub fn opcode(self) -> Opcode {
        match self {
            ExprOp::Const(_) => Opcode::Const,
            ExprOp::Field(..) => Opcode::Field,
            ExprOp::Add => Opcode::Add,
            ExprOp::Sub => Opcode::Sub,
            ExprOp::Mul => Opcode::Mul,
            ExprOp::Div => Opcode::Div,
            ExprOp::Neg => Opcode::Neg,
            ExprOp::Lt => Opcode::Lt,
            ExprOp::Le => Opcode::Le,
            ExprOp::Eq => Opcode::Eq,
            ExprOp::Ne => Opcode::Ne,
            ExprOp::Gt => Opcode::Gt,
            ExprOp::Ge => Opcode::Ge,
            ExprOp::PosEq(..) => Opcode::PosEq,
        }
    }
}

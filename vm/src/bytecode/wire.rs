//! The module's tables as the `.ilmb` payload carries them, in postcard. Most types
//! serialise as they are; `Op` is internally tagged and `Instr` flattens it for the
//! JSON listing, which a format without field names cannot read back, so instructions
//! travel as [`WireOp`] (externally tagged, a variant number on the wire) with their
//! statement. Fields and variable kinds travel as numbers here and as names in JSON
//! (`serde_kinds`).

use ilmr_stdlib::Command;
use serde::{Deserialize, Serialize, Serializer};

use super::ids::{BlockId, ExprId, NameId, StmtId, UnitId, VarId};
use super::op::{Arg, ArgRange, ExprOp, Instr, Op};
use super::{Block, Expr, Global, Header, Module, Stmt, Unit};

#[derive(Serialize)]
pub(super) struct TablesRef<'a> {
    files: &'a [String],
    stmts: &'a [Stmt],
    consts: &'a [f64],
    names: &'a [String],
    globals: &'a [Global],
    units: &'a [Unit],
    main: UnitId,
    blocks: &'a [Block],
    #[serde(serialize_with = "code")]
    code: &'a [Instr],
    args: &'a [Arg],
    exprs: &'a [Expr],
    expr_code: &'a [ExprOp],
}

#[derive(Deserialize)]
pub(super) struct Tables {
    files: Vec<String>,
    stmts: Vec<Stmt>,
    consts: Vec<f64>,
    names: Vec<String>,
    globals: Vec<Global>,
    units: Vec<Unit>,
    main: UnitId,
    blocks: Vec<Block>,
    code: Vec<(WireOp, StmtId)>,
    args: Vec<Arg>,
    exprs: Vec<Expr>,
    expr_code: Vec<ExprOp>,
}

fn code<S: Serializer>(code: &&[Instr], s: S) -> Result<S::Ok, S::Error> {
    s.collect_seq(code.iter().map(|i| (WireOp::from(i.op), i.stmt)))
}

impl<'a> TablesRef<'a> {
    pub(super) fn of(m: &'a Module) -> TablesRef<'a> {
        TablesRef {
            files: &m.files,
            stmts: &m.stmts,
            consts: &m.consts,
            names: &m.names,
            globals: &m.globals,
            units: &m.units,
            main: m.main,
            blocks: &m.blocks,
            code: &m.code,
            args: &m.args,
            exprs: &m.exprs,
            expr_code: &m.expr_code,
        }
    }
}

impl Tables {
    pub(super) fn into_module(self, header: Header) -> Module {
        Module {
            header,
            files: self.files,
            stmts: self.stmts,
            consts: self.consts,
            names: self.names,
            globals: self.globals,
            units: self.units,
            main: self.main,
            blocks: self.blocks,
            code: self
                .code
                .into_iter()
                .map(|(op, stmt)| Instr::new(op.into(), stmt))
                .collect(),
            args: self.args,
            exprs: self.exprs,
            expr_code: self.expr_code,
        }
    }
}

/// [`Op`], variant for variant, field for field.
#[derive(Serialize, Deserialize)]
enum WireOp {
    Issue {
        command: Command,
        args: ArgRange,
        bind: Option<VarId>,
    },
    Assign {
        var: VarId,
        expr: ExprId,
    },
    Copy {
        to: VarId,
        from: VarId,
    },
    WaitTime {
        seconds: ExprId,
        bind: Option<VarId>,
    },
    WaitVar {
        var: VarId,
        bind: Option<VarId>,
    },
    If {
        cond: ExprId,
        body: BlockId,
        bind: Option<VarId>,
    },
    While {
        cond: ExprId,
        body: BlockId,
        bind: Option<VarId>,
    },
    Call {
        unit: UnitId,
        bind: Option<VarId>,
    },
    Break {
        pattern: NameId,
    },
    BreakAll,
    Stop,
    Cont,
    Priority,
    Clear {
        var: VarId,
    },
}

/// Both directions in one table, so that a variant added to [`Op`] fails to compile
/// until it has a form on the wire.
macro_rules! same_variants {
    ($($name:ident $({ $($field:ident),* })?),* $(,)?) => {
        impl From<Op> for WireOp {
            fn from(op: Op) -> WireOp {
                match op {
                    $(Op::$name $({ $($field),* })? => WireOp::$name $({ $($field),* })?,)*
                }
            }
        }
        impl From<WireOp> for Op {
            fn from(op: WireOp) -> Op {
                match op {
                    $(WireOp::$name $({ $($field),* })? => Op::$name $({ $($field),* })?,)*
                }
            }
        }
    };
}

same_variants! {
    Issue { command, args, bind },
    Assign { var, expr },
    Copy { to, from },
    WaitTime { seconds, bind },
    WaitVar { var, bind },
    If { cond, body, bind },
    While { cond, body, bind },
    Call { unit, bind },
    Break { pattern },
    BreakAll,
    Stop,
    Cont,
    Priority,
    Clear { var },
}

//! [`Module::validate`]: every index in range and every expression well formed, so the
//! VM can index without checks that could panic. Never panics on any module.

use ilmr_stdlib::{Category, Command, Syntax};

use super::Module;
use super::op::{Arg, ArgRange, ExprOp, Op};

#[derive(Debug, Clone, PartialEq)]
pub enum ModuleError {
    /// The tables of an `.ilmb` file cannot be read.
    Decode(String),
    /// The bytes do not start as an `.ilmb` file does.
    NotModule,
    Version {
        found: u32,
        expected: u32,
    },
    /// The file is not as long as its header says (cut short, or with bytes after it).
    Length {
        promised: u64,
        found: u64,
    },
    /// The file's checksum does not match its bytes: it changed after it was written.
    Checksum {
        stored: u32,
        computed: u32,
    },
    Index {
        what: &'static str,
        index: u32,
        len: usize,
    },
    Expr {
        expr: u32,
        reason: &'static str,
    },
    PriorityNotFirst {
        block: u32,
    },
    NotIssuable(Command),
    /// A fragment compiled against another state of the module.
    StaleFragment,
}

impl std::fmt::Display for ModuleError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ModuleError::Decode(e) => write!(f, "a damaged module: {e}"),
            ModuleError::NotModule => write!(
                f,
                "not an ILMR module (an `.ilmb` file written by `ilmrc build` starts otherwise)"
            ),
            ModuleError::Version { found, expected } => write!(
                f,
                "module format version {found}, this ilmrc reads version {expected}: build the task again with `ilmrc build`"
            ),
            ModuleError::Length { promised, found } => write!(
                f,
                "the file holds {found} byte(s) where its header promises {promised}: it was cut short or added to"
            ),
            ModuleError::Checksum { stored, computed } => write!(
                f,
                "the checksum does not match (stored {stored:08x}, computed {computed:08x}): the file changed after it was written"
            ),
            ModuleError::Index { what, index, len } => {
                write!(f, "{what} {index} out of range (table holds {len})")
            }
            ModuleError::Expr { expr, reason } => write!(f, "expression {expr}: {reason}"),
            ModuleError::PriorityNotFirst { block } => {
                write!(f, "block {block}: priority = highest must come first")
            }
            ModuleError::NotIssuable(c) => {
                write!(f, "{c} has its own instruction and cannot be issued")
            }
            ModuleError::StaleFragment => {
                write!(f, "the fragment was compiled against another module")
            }
        }
    }
}

impl std::error::Error for ModuleError {}

fn check(what: &'static str, index: u32, len: usize) -> Result<(), ModuleError> {
    if (index as usize) < len {
        Ok(())
    } else {
        Err(ModuleError::Index { what, index, len })
    }
}

fn check_range(what: &'static str, start: u32, len: u32, table: usize) -> Result<(), ModuleError> {
    if u64::from(start) + u64::from(len) <= table as u64 {
        Ok(())
    } else {
        Err(ModuleError::Index {
            what,
            index: start.saturating_add(len),
            len: table,
        })
    }
}

/// Whether `command` is issued with `ISSUE` (control flow has its own opcodes).
pub(crate) fn issuable(command: Command) -> bool {
    let spec = command.spec();
    spec.syntax == Syntax::Call
        && matches!(
            spec.category,
            Category::Define | Category::Movement | Category::Action
        )
}

impl Module {
    pub fn validate(&self) -> Result<(), ModuleError> {
        self.validate_from(&super::Counts::default())
    }

    /// Validates the entries at or past `base` in every table, against the whole
    /// module: what a fragment added to a module that was valid with `base`'s counts.
    /// Entries before `base` are trusted (the tables only grow), so joining a line
    /// costs in proportion to the line, not to the program.
    pub fn validate_from(&self, base: &super::Counts) -> Result<(), ModuleError> {
        fn from<T>(v: &[T], n: u32) -> impl Iterator<Item = (usize, &T)> {
            v.iter().enumerate().skip(n as usize)
        }
        check("main unit", self.main.0, self.units.len())?;
        for (_, s) in from(&self.stmts, base.stmts) {
            check("file", s.file.0, self.files.len())?;
        }
        for (_, u) in from(&self.units, base.units) {
            for b in &u.blocks {
                check("block", b.0, self.blocks.len())?;
            }
        }
        for (_, b) in from(&self.blocks, base.blocks) {
            check_range("block code", b.start, b.len, self.code.len())?;
        }
        for (i, e) in from(&self.exprs, base.exprs) {
            check_range("expression code", e.start, e.len, self.expr_code.len())?;
            self.validate_expr(i as u32)?;
        }
        let vars = self.globals.len();
        for (_, instr) in from(&self.code, base.code) {
            check("statement", instr.stmt.0, self.stmts.len())?;
            if let Some(v) = instr.op.bind() {
                check("variable", v.0, vars)?;
            }
            match instr.op {
                Op::Issue { command, args, .. } => {
                    if !issuable(command) {
                        return Err(ModuleError::NotIssuable(command));
                    }
                    self.validate_args(args)?;
                }
                Op::Assign { var, expr } => {
                    check("variable", var.0, vars)?;
                    check("expression", expr.0, self.exprs.len())?;
                }
                Op::Copy { to, from } => {
                    check("variable", to.0, vars)?;
                    check("variable", from.0, vars)?;
                }
                Op::WaitTime { seconds, .. } => check("expression", seconds.0, self.exprs.len())?,
                Op::WaitVar { var, .. } | Op::Clear { var } => check("variable", var.0, vars)?,
                Op::If { cond, body, .. } | Op::While { cond, body, .. } => {
                    check("expression", cond.0, self.exprs.len())?;
                    check("block", body.0, self.blocks.len())?;
                }
                Op::Call { unit, .. } => check("unit", unit.0, self.units.len())?,
                Op::Break { pattern } => check("name", pattern.0, self.names.len())?,
                Op::BreakAll | Op::Stop | Op::Cont | Op::Priority => {}
            }
        }
        // Few tasks set a priority: where no new instruction does and no new block
        // covers trusted code, no block can have one out of place.
        let mut priorities = from(&self.code, base.code)
            .filter(|(_, instr)| instr.op == Op::Priority)
            .peekable();
        let covers_trusted =
            || from(&self.blocks, base.blocks).any(|(_, b)| b.len > 0 && b.start < base.code);
        if priorities.peek().is_some() || covers_trusted() {
            for (i, _) in from(&self.blocks, base.blocks) {
                let code = self.block_code(super::BlockId(i as u32));
                if code.iter().skip(1).any(|c| c.op == Op::Priority) {
                    return Err(ModuleError::PriorityNotFirst { block: i as u32 });
                }
            }
            // Trusted blocks cover only trusted code, so new code can only start a
            // new block.
            let starts: std::collections::BTreeSet<u32> = from(&self.blocks, base.blocks)
                .filter(|(_, b)| b.len > 0)
                .map(|(_, b)| b.start)
                .collect();
            if priorities.any(|(pc, _)| !starts.contains(&(pc as u32))) {
                return Err(ModuleError::PriorityNotFirst { block: u32::MAX });
            }
        }
        Ok(())
    }

    fn validate_args(&self, args: ArgRange) -> Result<(), ModuleError> {
        check_range("arguments", args.start, args.len, self.args.len())?;
        for a in self.arg_list(args) {
            match *a {
                Arg::Num(e) => check("expression", e.0, self.exprs.len())?,
                Arg::Word(n) => check("name", n.0, self.names.len())?,
                Arg::Setting { key, value } => {
                    check("name", key.0, self.names.len())?;
                    check("expression", value.0, self.exprs.len())?;
                }
                Arg::Var(v) => check("variable", v.0, self.globals.len())?,
            }
        }
        Ok(())
    }

    fn validate_expr(&self, id: u32) -> Result<(), ModuleError> {
        let ops = self.expr_ops(super::ExprId(id));
        if ops.is_empty() {
            return Err(ModuleError::Expr {
                expr: id,
                reason: "empty",
            });
        }
        let mut depth: u32 = 0;
        for op in ops {
            match *op {
                ExprOp::Const(c) => check("constant", c.0, self.consts.len())?,
                ExprOp::Field(v, _) => check("variable", v.0, self.globals.len())?,
                ExprOp::PosEq(a, b) => {
                    check("variable", a.0, self.globals.len())?;
                    check("variable", b.0, self.globals.len())?;
                }
                _ => {}
            }
            let (pop, push) = op.stack_effect();
            depth = depth.checked_sub(pop).ok_or(ModuleError::Expr {
                expr: id,
                reason: "stack underflow",
            })? + push;
            if depth as usize > super::limits::EXPR_STACK {
                return Err(ModuleError::Expr {
                    expr: id,
                    reason: "too deep",
                });
            }
        }
        if depth != 1 {
            return Err(ModuleError::Expr {
                expr: id,
                reason: "leaves other than one value",
            });
        }
        Ok(())
    }
}

//! Statements and blocks. Inner blocks are built before the instruction that refers to
//! them, so every block's code stays contiguous (the builder's rule).

use ilmr_model::RobotModel;
use ilmr_stdlib::{Category, Command, Syntax};
use ilmr_vm::Module;
use ilmr_vm::bytecode::{BlockId, Instr, ModuleBuilder, Op, StmtId, VarId};

use super::scope::Scope;
use super::{build_error, internal};
use crate::ast::{self, Call, ExprKind, Name, Stmt, StmtKind};
use crate::check::needle;
use crate::check::{Resolved, Target};
use crate::diagnostic::{Diagnostic, FileId};
use crate::span::Span;

/// A statement that cannot be lowered says why; boxed, since the happy path is hot.
pub type Lowered<T> = Result<T, Box<Diagnostic>>;

pub struct Lowerer<'m> {
    pub b: ModuleBuilder,
    pub model: &'m RobotModel,
    pub diags: Vec<Diagnostic>,
    /// Counts the units made for bodies of several blocks, to name them apart.
    synthetic: u32,
    /// The instructions of the blocks being lowered, innermost last: a block's are
    /// handed to the builder and popped when it ends, so no block allocates its own.
    code: Vec<Instr>,
    /// The same for the ids of blocks that start together.
    ids: Vec<BlockId>,
}

/// Whether the VM issues this command with `ISSUE` (control flow has its own opcodes).
pub fn issuable(command: Command) -> bool {
    let spec = command.spec();
    spec.syntax == Syntax::Call
        && matches!(
            spec.category,
            Category::Define | Category::Movement | Category::Action
        )
}

impl<'m> Lowerer<'m> {
    pub fn new(model: &'m RobotModel) -> Lowerer<'m> {
        Lowerer::with_builder(ModuleBuilder::new(), model)
    }

    pub fn with_builder(b: ModuleBuilder, model: &'m RobotModel) -> Lowerer<'m> {
        Lowerer {
            b,
            model,
            diags: Vec::new(),
            synthetic: 0,
            code: Vec::new(),
            ids: Vec::new(),
        }
    }

    /// The module, or every problem met on the way.
    pub fn finish(self, file: FileId) -> Result<Module, Vec<Diagnostic>> {
        if !self.diags.is_empty() {
            return Err(self.diags);
        }
        self.b
            .finish()
            .map_err(|e| vec![*build_error(file, Span::default(), e)])
    }

    /// Lowers blocks that start together; a statement that fails is reported and left
    /// out, so that one run reports every failure.
    pub fn blocks(&mut self, sc: &Scope<'_>, blocks: &[ast::Block<'_>]) -> Vec<BlockId> {
        let from = self.ids.len();
        self.start_blocks(sc, blocks);
        self.ids.split_off(from)
    }

    /// Lowers the blocks onto `self.ids`.
    fn start_blocks(&mut self, sc: &Scope<'_>, blocks: &[ast::Block<'_>]) {
        for block in blocks {
            let from = self.code.len();
            for stmt in &block.stmts {
                if let Err(d) = self.stmt(sc, stmt) {
                    self.diags.push(*d);
                }
            }
            let built = self.b.block(&self.code[from..]);
            self.code.truncate(from);
            match built {
                Ok(id) => self.ids.push(id),
                Err(e) => self.diags.push(*build_error(sc.file, block.span, e)),
            }
        }
    }

    fn stmt(&mut self, sc: &Scope<'_>, stmt: &Stmt<'_>) -> Lowered<()> {
        if matches!(stmt.kind, StmtKind::Check { .. }) {
            return Ok(());
        }
        let id = self.record(sc, stmt.span)?;
        if let Some(op) = self.op(sc, stmt)? {
            self.code.push(Instr::new(op, id));
        }
        Ok(())
    }

    /// The statement's source map entry.
    fn record(&mut self, sc: &Scope<'_>, span: Span) -> Lowered<StmtId> {
        self.b
            .stmt(
                sc.module_file,
                sc.line(span),
                (span.start, span.end),
                sc.slice(span),
            )
            .map_err(|e| build_error(sc.file, span, e))
    }

    fn op(&mut self, sc: &Scope<'_>, stmt: &Stmt<'_>) -> Lowered<Option<Op>> {
        let span = stmt.span;
        Ok(Some(match &stmt.kind {
            StmtKind::Call { bind, call } => return self.call(sc, span, bind.as_ref(), call),
            StmtKind::Assign { target, value } => match (sc.targets.get(&span), &value.kind) {
                (Some(Target::Copy(from)), _) => self.copy(sc, span, target, *from)?,
                (Some(_), ExprKind::Name(name)) => {
                    let call = Call {
                        name: *name,
                        args: None,
                    };
                    return self.call(sc, span, Some(target), &call);
                }
                _ => Op::Assign {
                    var: self.bound(sc, target)?,
                    expr: self.value(sc, value)?,
                },
            },
            StmtKind::If(c) => Op::If {
                cond: self.condition(sc, &c.cond)?,
                body: self.body(sc, &c.body, span)?,
                bind: None,
            },
            StmtKind::While { bind, body } => Op::While {
                cond: self.condition(sc, &body.cond)?,
                body: self.body(sc, &body.body, span)?,
                bind: bind.as_ref().map(|n| self.bound(sc, n)).transpose()?,
            },
            StmtKind::Break { pattern: None } => Op::BreakAll,
            StmtKind::Break { pattern: Some(p) } => {
                let needle = needle(p);
                // An empty pattern matches nothing for the checker (W0701); the VM
                // would take it as matching every statement, so nothing is emitted.
                if needle.is_empty() {
                    return Ok(None);
                }
                let pattern = self
                    .b
                    .name(needle)
                    .map_err(|e| build_error(sc.file, span, e))?;
                Op::Break { pattern }
            }
            StmtKind::Priority => Op::Priority,
            StmtKind::Check { .. } => return Ok(None),
            StmtKind::Error => return Err(internal(sc.file, span, "the line does not parse")),
        }))
    }

    /// A body of one block is that block; several blocks become a unit of their own,
    /// started by one call, so that they start together as on the top level.
    fn body(&mut self, sc: &Scope<'_>, blocks: &[ast::Block<'_>], span: Span) -> Lowered<BlockId> {
        let from = self.ids.len();
        self.start_blocks(sc, blocks);
        let fail = |e| build_error(sc.file, span, e);
        let made = match self.ids[from..] {
            [] => self.b.block(&[]).map_err(fail),
            [one] => Ok(one),
            _ => self.several(sc, from, span),
        };
        self.ids.truncate(from);
        made
    }

    /// A body of several blocks: a unit of its own, started by one call.
    fn several(&mut self, sc: &Scope<'_>, from: usize, span: Span) -> Lowered<BlockId> {
        let fail = |e| build_error(sc.file, span, e);
        self.synthetic += 1;
        let name = format!("{}@{}#{}", sc.slice(span), sc.line(span), self.synthetic);
        let unit = self.b.declare_unit(&name, false).map_err(fail)?;
        self.b.define_unit(unit, &self.ids[from..]);
        // A statement of its own, so that each statement has one instruction
        // (the run loop follows commands by statement).
        let stmt = self.record(sc, span)?;
        let call = Instr::new(Op::Call { unit, bind: None }, stmt);
        self.b.block(&[call]).map_err(fail)
    }

    fn call(
        &mut self,
        sc: &Scope<'_>,
        span: Span,
        bind: Option<&Name<'_>>,
        call: &Call<'_>,
    ) -> Lowered<Option<Op>> {
        let Some(target) = sc.targets.get(&span).copied() else {
            return Err(internal(
                sc.file,
                span,
                "the checker resolved no command here",
            ));
        };
        let bind = bind.map(|n| self.bound(sc, n)).transpose()?;
        let command = match target {
            Target::Skill(id) => {
                let unit = (sc.skill_unit)(id, sc.specials.get(&span).copied())
                    .ok_or_else(|| internal(sc.file, span, "the skill has no unit"))?;
                return Ok(Some(Op::Call { unit, bind }));
            }
            Target::Copy(_) => return Err(internal(sc.file, span, "a copy is not a call")),
            Target::Command { command, form } => {
                if issuable(command) {
                    let args = self.args(sc, command, form, call, span)?;
                    return Ok(Some(Op::Issue {
                        command,
                        args,
                        bind,
                    }));
                }
                command
            }
        };
        let unbindable = || {
            Box::new(
                Diagnostic::new(
                    crate::diagnostic::Code::ArgumentKind,
                    sc.file,
                    span,
                    format!("`{command}` gives no value to bind"),
                )
                .with_label("write it without `v =`"),
            )
        };
        let first = call.args.as_ref().and_then(|a| a.items.first());
        Ok(Some(match command {
            Command::Wait => {
                let Some(ast::Arg::Positional(e)) = first else {
                    return Err(internal(sc.file, span, "wait has no argument"));
                };
                match self.variable_of(sc, e) {
                    Some(var) => Op::WaitVar { var, bind },
                    None => Op::WaitTime {
                        seconds: self.value(sc, e)?,
                        bind,
                    },
                }
            }
            Command::Stop | Command::Cont | Command::Clear if bind.is_some() => {
                return Err(unbindable());
            }
            Command::Stop => Op::Stop,
            Command::Cont => Op::Cont,
            Command::Clear => {
                let var = match first {
                    Some(ast::Arg::Positional(e)) => self.variable_of(sc, e),
                    _ => None,
                };
                Op::Clear {
                    var: var.ok_or_else(|| internal(sc.file, span, "clear names no variable"))?,
                }
            }
            other => {
                return Err(internal(
                    sc.file,
                    span,
                    format!("`{other}` has no instruction"),
                ));
            }
        }))
    }

    /// `a = b`: numbers, readings and statuses copy their value; a position has no
    /// single value, and the bytecode has no instruction that copies a whole record.
    fn copy(
        &mut self,
        sc: &Scope<'_>,
        span: Span,
        target: &Name<'_>,
        from: crate::check::VarId,
    ) -> Lowered<Op> {
        let source = sc.vars.get(from);
        let Some(field) = source.kind.numeric_field() else {
            return Err(Box::new(
                Diagnostic::new(
                    crate::diagnostic::Code::WrongVariableKind,
                    sc.file,
                    span,
                    format!(
                        "`{}` holds a position, which cannot be copied",
                        source.spelling
                    ),
                )
                .with_label("a position is copied by the command that found it")
                .with_help("save it with `savepos(name)`, or use the variable itself"),
            ));
        };
        let src = self.slot(sc, from, span)?;
        let expr = self
            .b
            .expr(&[ilmr_vm::bytecode::ExprOp::Field(src, field)])
            .map_err(|e| build_error(sc.file, span, e))?;
        Ok(Op::Assign {
            var: self.bound(sc, target)?,
            expr,
        })
    }

    /// The variable a name binds or reads, by the checker's resolution.
    pub fn bound(&mut self, sc: &Scope<'_>, name: &Name<'_>) -> Lowered<VarId> {
        match sc.resolved(name.span) {
            Some(Resolved::Variable(id)) => self.slot(sc, id, name.span),
            _ => Err(internal(
                sc.file,
                name.span,
                format!("`{}` is not a variable", name.text),
            )),
        }
    }

    /// A bare name that the checker resolved to a variable.
    pub fn variable_of(&mut self, sc: &Scope<'_>, e: &ast::Expr<'_>) -> Option<VarId> {
        let ExprKind::Name(n) = &e.kind else {
            return None;
        };
        match sc.resolved(n.span) {
            Some(Resolved::Variable(id)) => self.slot(sc, id, n.span).ok(),
            _ => None,
        }
    }

    /// The module's slot for one of the unit's variables, looked up by name the first
    /// time the unit uses it and remembered by the checker's id after that. A variable
    /// the program binds with two kinds keeps the first: expressions name their field
    /// explicitly, so the slot's kind only labels the record in listings and traces.
    pub fn slot(&mut self, sc: &Scope<'_>, id: crate::check::VarId, span: Span) -> Lowered<VarId> {
        if let Some(v) = sc.slot(id) {
            return Ok(v);
        }
        let var = sc.vars.get(id);
        let v = self
            .b
            .global_keeping_kind(&var.spelling, var.kind)
            .map_err(|e| build_error(sc.file, span, e))?;
        sc.remember(id, v);
        Ok(v)
    }
}

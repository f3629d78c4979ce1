//! Interactive lines (requirement 6): a line of text given while a task runs is parsed
//! and checked on its own against the live module's variables and skills, then lowered
//! to a [`Fragment`] that `Vm::add_block` joins as new top-level blocks. A bad line
//! returns its diagnostics and changes nothing.
//!
//! The checker's statement walker works on a whole program; a line has instead the
//! live module's variables (all bound) and its skill units. This walker follows the
//! checker's rules statement for statement, through the checker's own public pieces
//! (`Cx::match_forms`, `Cx::value`, `Cx::condition`), so that a line and a file get
//! the same diagnostics.

use std::collections::HashMap;

use ilmr_model::RobotModel;
use ilmr_stdlib::{Command, Syntax, VarKind};
use ilmr_vm::Module;
use ilmr_vm::bytecode::{Fragment, ModuleBuilder, UnitId};

use super::scope::Scope;
use super::stmt::Lowerer;
use super::{build_error, robotless};
use crate::ast::{Block, Call, ExprKind, FileKind, Name, Stmt, StmtKind};
use crate::check::{Cx, Findings, Resolved, SkillId, Target, Vars, suggest};
use crate::diagnostic::{Code, Diagnostic, FileId};
use crate::parser;
use crate::span::Span;

/// How a line is taken.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct LineOptions {
    /// The task runs with `--robot none`: commands that need a robot are refused.
    pub robotless: bool,
}

/// Parses, checks and lowers `text` against `live`. Diagnostics point into `text` as
/// file 0. Warnings do not stop a line.
pub fn lower_line(
    text: &str,
    live: &Module,
    model: &RobotModel,
    options: LineOptions,
) -> Result<Fragment, Vec<Diagnostic>> {
    let file = FileId(0);
    let parsed = parser::parse(text, file);
    let mut diags: Vec<Diagnostic> = parsed.diagnostics;
    if parsed.file.kind == FileKind::Skills {
        let span = parsed
            .file
            .skills
            .first()
            .map_or(Span::default(), |s| s.header);
        diags.push(
            Diagnostic::new(
                Code::NestedSkillHeader,
                file,
                span,
                "a skill cannot be defined by an interactive line",
            )
            .with_label("skill header")
            .with_help("put the skill in a skill file and start the task with it"),
        );
    }
    if diags.iter().any(Diagnostic::is_error) {
        return Err(errors(diags));
    }

    let mut w = LineWalker::new(model, live);
    w.blocks(&parsed.file.blocks);
    if w.diags.iter().any(Diagnostic::is_error) {
        return Err(errors(w.diags));
    }

    let mut b = ModuleBuilder::extending(live);
    let path = format!("<line {}>", live.files.len() + 1);
    let module_file = b
        .file(&path)
        .map_err(|e| vec![*build_error(file, Span::default(), e)])?;
    let base_code = live.code.len();
    let skill_unit = |id: SkillId| Some(UnitId(id.0));
    let scope = Scope::from_parts(
        file,
        module_file,
        text,
        &w.refs,
        &w.targets,
        &w.vars,
        &skill_unit,
    );
    let mut low = Lowerer::with_builder(b, model);
    let blocks = low.blocks(&scope, &parsed.file.blocks);
    if !low.diags.is_empty() {
        return Err(low.diags);
    }
    if options.robotless {
        let m = low.b.module();
        let refused = robotless::uses_in(m, m.code.get(base_code..).unwrap_or(&[]), |_| file);
        if !refused.is_empty() {
            return Err(refused);
        }
    }
    low.b
        .finish_fragment(&blocks)
        .map_err(|e| vec![*build_error(file, Span::default(), e)])
}

fn errors(diags: Vec<Diagnostic>) -> Vec<Diagnostic> {
    diags.into_iter().filter(Diagnostic::is_error).collect()
}

/// Checks the statements of a line, recording what the lowering needs.
struct LineWalker<'a, 'm> {
    model: &'m RobotModel,
    live: &'a Module,
    vars: Vars,
    refs: Vec<(Span, Resolved)>,
    targets: HashMap<Span, Target>,
    diags: Vec<Diagnostic>,
    constants: crate::check::Constants,
    buf: String,
}

const FILE: FileId = FileId(0);

impl<'a, 'm> LineWalker<'a, 'm> {
    fn new(model: &'m RobotModel, live: &'a Module) -> LineWalker<'a, 'm> {
        let mut vars = Vars::default();
        for g in &live.globals {
            vars.bind(&g.name, g.kind, FILE, Span::default());
        }
        LineWalker {
            model,
            live,
            vars,
            refs: Vec::new(),
            targets: HashMap::new(),
            diags: Vec::new(),
            constants: crate::check::Constants::new(model),
            buf: String::new(),
        }
    }

    fn cx(&mut self) -> Cx<'_, '_> {
        Cx {
            model: self.model,
            constants: &self.constants,
            vars: &mut self.vars,
            file: FILE,
            buf: &mut self.buf,
        }
    }

    fn absorb(&mut self, f: Findings) {
        for (id, span) in f.uses {
            self.vars.use_at(id, FILE, span);
        }
        self.refs.extend(f.refs);
        self.diags.extend(f.diags);
    }

    /// A live skill unit of this name (any case); skill ids of a line are unit numbers.
    fn skill(&self, name: &str) -> Option<SkillId> {
        self.live
            .units
            .iter()
            .position(|u| u.skill && u.name.eq_ignore_ascii_case(name))
            .and_then(|i| u32::try_from(i).ok())
            .map(SkillId)
    }

    fn blocks(&mut self, blocks: &[Block<'_>]) {
        for block in blocks {
            for (i, stmt) in block.stmts.iter().enumerate() {
                if matches!(stmt.kind, StmtKind::Priority) && i != 0 {
                    self.diags.push(
                        Diagnostic::new(
                            Code::MisplacedPriority,
                            FILE,
                            stmt.span,
                            "`priority = highest` must be the first statement of its block",
                        )
                        .with_label("not first in its block"),
                    );
                }
                self.stmt(stmt);
            }
        }
    }

    fn stmt(&mut self, stmt: &Stmt<'_>) {
        match &stmt.kind {
            StmtKind::Call { bind, call } => {
                if let (Some(kind), Some(bind)) = (self.call(call, stmt.span), bind) {
                    self.bind(bind, kind);
                }
            }
            StmtKind::Assign { target, value } => {
                let kind = match &value.kind {
                    ExprKind::Name(name) => self.assign_name(name, stmt.span),
                    _ => {
                        let mut f = Findings::default();
                        self.cx().value(&mut f, value);
                        self.absorb(f);
                        Some(VarKind::Number)
                    }
                };
                if let Some(kind) = kind {
                    self.bind(target, kind);
                }
            }
            StmtKind::If(c) => {
                let mut f = Findings::default();
                self.cx().condition(&mut f, &c.cond);
                self.absorb(f);
                self.blocks(&c.body);
            }
            StmtKind::While { bind, body } => {
                let mut f = Findings::default();
                self.cx().condition(&mut f, &body.cond);
                self.absorb(f);
                if let Some(bind) = bind {
                    self.bind(bind, VarKind::Status);
                }
                self.blocks(&body.body);
            }
            StmtKind::Check { body, .. } => {
                let before = self.vars.snapshot();
                self.blocks(body);
                self.vars.restore(before);
            }
            StmtKind::Break { .. } | StmtKind::Priority | StmtKind::Error => {}
        }
    }

    /// `v = name`: a skill call, a bare command, a copy of a variable or a constant.
    fn assign_name(&mut self, name: &Name<'_>, stmt: Span) -> Option<VarKind> {
        let bound = self.vars.bound(name.text);
        if bound.is_none() && self.cx().model_constant(name.text).is_none() {
            let call = Call {
                name: *name,
                args: None,
            };
            if self.skill(name.text).is_some() || Command::from_name(name.text).is_some() {
                return self.call(&call, stmt);
            }
        }
        let mut f = Findings::default();
        let e = crate::ast::Expr {
            kind: ExprKind::Name(*name),
            span: name.span,
        };
        self.cx().value(&mut f, &e);
        f.diags.retain(|d| d.code != Code::WrongVariableKind);
        self.absorb(f);
        let kind = bound.map(|id| self.vars.get(id).kind);
        if let Some(id) = bound {
            self.targets.insert(stmt, Target::Copy(id));
        }
        Some(kind.unwrap_or(VarKind::Number))
    }

    fn call(&mut self, call: &Call<'_>, stmt: Span) -> Option<VarKind> {
        if let Some(command) = Command::from_name(call.name.text) {
            let spec = command.spec();
            if spec.syntax == Syntax::Structural {
                self.diags.push(
                    Diagnostic::new(
                        Code::Syntax,
                        FILE,
                        call.name.span,
                        format!("`{}` cannot be used this way", spec.name),
                    )
                    .with_label(format!("the grammar is: {}", spec.grammar)),
                );
                return None;
            }
            self.refs.push((call.name.span, Resolved::Command(command)));
            let at = call.args.as_ref().map_or(call.name.span, |a| a.span);
            let m = self.cx().match_forms(spec, call.args.as_ref(), at);
            let kind = spec
                .forms
                .get(m.form)
                .map_or(VarKind::Status, |f| f.produces);
            let form = m.form;
            let position = m.binds_position;
            self.absorb(m.findings);
            if let Some(name) = position {
                self.bind(&name, VarKind::Position);
            }
            self.targets.insert(stmt, Target::Command { command, form });
            return Some(kind);
        }
        if let Some(id) = self.skill(call.name.text) {
            self.refs.push((call.name.span, Resolved::Skill(id)));
            if let Some(args) = &call.args {
                self.diags.push(
                    Diagnostic::new(
                        Code::ArgumentCount,
                        FILE,
                        args.span,
                        format!("skill `{}` takes no arguments", call.name.text),
                    )
                    .with_label("skills are called by name alone"),
                );
            }
            self.targets.insert(stmt, Target::Skill(id));
            return Some(VarKind::Status);
        }
        let candidates = Command::all()
            .filter(|c| c.spec().syntax == Syntax::Call)
            .map(|c| c.name())
            .chain(
                self.live
                    .units
                    .iter()
                    .filter(|u| u.skill)
                    .map(|u| u.name.as_str()),
            );
        let d = Diagnostic::new(
            Code::UnknownCommand,
            FILE,
            call.name.span,
            format!(
                "`{}` is neither a command nor a skill of the running task",
                call.name.text
            ),
        );
        self.diags
            .push(match suggest::closest(call.name.text, candidates) {
                Some(s) => d.with_label(format!("did you mean `{s}`?")).with_fix(
                    format!("replace with `{s}`"),
                    call.name.span,
                    s,
                ),
                None => d.with_label("unknown name"),
            });
        None
    }

    fn bind(&mut self, name: &Name<'_>, kind: VarKind) {
        let reserved = if Command::from_name(name.text).is_some() {
            Some("a command")
        } else if self.skill(name.text).is_some() {
            Some("a skill")
        } else if self.model.parameter(name.text).is_some()
            || self.model.identifier(name.text).is_some()
            || self.model.color(name.text).is_some()
        {
            Some("a constant of the robot model")
        } else {
            None
        };
        if let Some(what) = reserved {
            self.diags.push(
                Diagnostic::new(
                    Code::ReservedName,
                    FILE,
                    name.span,
                    format!("`{}` is {what} and cannot be a variable", name.text),
                )
                .with_label("choose another name"),
            );
            return;
        }
        // The running task's variable keeps its kind: its readers were compiled for it.
        if let Some(g) = self
            .live
            .find_global(name.text)
            .and_then(|v| self.live.global(v))
            .filter(|g| g.kind != kind)
        {
            self.diags.push(
                Diagnostic::new(
                    Code::WrongVariableKind,
                    FILE,
                    name.span,
                    format!(
                        "`{}` is {} in the running task and cannot become {}",
                        g.name,
                        g.kind.describe(),
                        kind.describe()
                    ),
                )
                .with_label("bound with another kind"),
            );
            return;
        }
        let id = self.vars.bind(name.text, kind, FILE, name.span);
        self.refs.push((name.span, Resolved::Variable(id)));
    }
}

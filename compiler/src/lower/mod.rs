//! Lowering: a checked program to the VM's bytecode (`docs/bytecode.md`), through
//! `ilmr_vm::ModuleBuilder`. Every instruction carries its statement (file, line, span,
//! trimmed text); numbers keep the units the source writes, because the VM converts
//! degrees itself (`turn(d=..)`, `gotoxy(..,h)`, `locate(..,h)`); model constants are
//! folded; device numbers become device names; defaults the catalogue leaves to the
//! model (`approach` distance, `followwall` distance) are filled in from it.
//!
//! [`lower`] lowers a whole task with the skills it reaches; [`lower_line`] checks and
//! lowers one interactive line (or block) against a live module.

mod args;
mod expr;
mod line;
mod refs;
mod robotless;
mod scope;
mod stmt;

use std::collections::HashMap;

use ilmr_model::RobotModel;
use ilmr_vm::Module;
use ilmr_vm::bytecode::{BuildError, UnitId};

use crate::ast::{Block, StmtKind};
use crate::check::{Analysis, SkillId};
use crate::diagnostic::{Code, Diagnostic, FileId};
use crate::span::{LineIndex, Span};

pub use line::{LineOptions, lower_line, lower_line_into, lower_line_warned, lower_line_with};
pub use robotless::robot_uses;

use scope::Scope;
use stmt::Lowerer;

/// Lowers the task in `task_file` and every skill it reaches. Refuses a program with
/// errors (returning them); warnings do not stop it.
pub fn lower(
    analysis: &Analysis<'_>,
    model: &RobotModel,
    task_file: FileId,
) -> Result<Module, Vec<Diagnostic>> {
    let errors: Vec<Diagnostic> = analysis
        .diagnostics
        .iter()
        .filter(|d| d.is_error())
        .cloned()
        .collect();
    if !errors.is_empty() {
        return Err(errors);
    }
    let fail = |message: String| vec![*internal(task_file, Span::default(), message)];
    let Some(entry) = analysis.files.get(task_file.0 as usize) else {
        return Err(fail(format!("no file {} in the analysis", task_file.0)));
    };
    let Some(task) = analysis
        .units
        .iter()
        .find(|u| u.file == task_file && u.skill.is_none())
    else {
        return Err(fail(format!("`{}` is not a checked task file", entry.path)));
    };

    let mut low = Lowerer::new(model);
    // Files keep the checker's numbering, so a statement's file is a diagnostic's file.
    for f in &analysis.files {
        low.b.file(f.path).map_err(|e| fail(e.to_string()))?;
    }
    let main = low
        .b
        .declare_unit(entry.path, false)
        .map_err(|e| fail(e.to_string()))?;
    low.b.set_main(main);

    let checked_units = checked_units(analysis);
    let reached = reachable(analysis, task, &checked_units);
    let mut units: HashMap<Reach, UnitId> = HashMap::new();
    for &r in &reached {
        let name = match r {
            Reach::Skill(id) => &analysis.skills.get(id).name,
            Reach::Special(i) => &analysis.specials[i as usize].label,
        };
        let unit = low
            .b
            .declare_unit(name, true)
            .map_err(|e| fail(e.to_string()))?;
        units.insert(r, unit);
    }
    let skill_unit = |id: SkillId, special: Option<u32>| {
        let reach = special.map_or(Reach::Skill(id), Reach::Special);
        units.get(&reach).copied()
    };

    // Each file's lines indexed once, not once per skill in it.
    let lines: Vec<LineIndex> = analysis
        .files
        .iter()
        .map(|f| LineIndex::new(f.text))
        .collect();
    let bodies = reached.iter().filter_map(|&r| body(analysis, r));
    let statements: usize = std::iter::once(&entry.tree.blocks[..])
        .chain(bodies)
        .map(|b| statements(b))
        .sum();
    low.b.reserve(statements, task.vars.len());
    let Some(scope) = Scope::new(analysis, &lines, task, &skill_unit) else {
        return Err(fail(format!("no file {} in the analysis", task_file.0)));
    };
    let blocks = low.blocks(&scope, &entry.tree.blocks);
    low.b.define_unit(main, &blocks);
    for &r in &reached {
        let id = match r {
            Reach::Skill(id) => id,
            Reach::Special(i) => analysis.specials[i as usize].skill,
        };
        let info = analysis.skills.get(id);
        let (Some(unit), Some(checked)) = (units.get(&r).copied(), checked_units.get(&r).copied())
        else {
            low.diags.push(*internal(
                info.file,
                info.header,
                format!("skill `{}` was not checked", info.name),
            ));
            continue;
        };
        let Some(body) = body(analysis, r) else {
            continue;
        };
        let Some(scope) = Scope::new(analysis, &lines, checked, &skill_unit) else {
            continue;
        };
        let blocks = low.blocks(&scope, body);
        low.b.define_unit(unit, &blocks);
    }
    low.finish(task_file)
}

/// How many statements the blocks hold, inside bodies too.
fn statements(blocks: &[Block<'_>]) -> usize {
    blocks
        .iter()
        .flat_map(|b| &b.stmts)
        .map(|stmt| match &stmt.kind {
            StmtKind::If(c) | StmtKind::While { body: c, .. } => 1 + statements(&c.body),
            _ => 1,
        })
        .sum()
}

/// A skill to lower: a skill as written, or a parameterized skill specialized by a
/// call's arguments (`Analysis::specials`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(super) enum Reach {
    Skill(SkillId),
    Special(u32),
}

/// The blocks a reached skill lowers: its own, or its specialization's.
pub(super) fn body<'a, 's>(analysis: &'a Analysis<'s>, r: Reach) -> Option<&'a [Block<'s>]> {
    match r {
        Reach::Skill(id) => {
            let info = analysis.skills.get(id);
            let file = analysis.files.get(info.file.0 as usize)?;
            Some(&file.tree.skills.get(info.index)?.blocks)
        }
        Reach::Special(i) => analysis.special_blocks.get(i as usize).map(|b| &b[..]),
    }
}

/// The skills a task calls, directly or through other skills, in the order first
/// reached (depth first, calls in text order), so that module layout is stable. Calls
/// inside `check` blocks never run and reach nothing.
pub(super) fn reachable(
    analysis: &Analysis<'_>,
    task: &crate::check::Unit,
    checked_units: &HashMap<Reach, &crate::check::Unit>,
) -> Vec<Reach> {
    fn calls(analysis: &Analysis<'_>, unit: &crate::check::Unit) -> Vec<Reach> {
        let blocks = match (unit.special, unit.skill) {
            (Some(i), _) => body(analysis, Reach::Special(i)),
            (None, Some(id)) => body(analysis, Reach::Skill(id)),
            (None, None) => analysis
                .files
                .get(unit.file.0 as usize)
                .map(|e| &e.tree.blocks[..]),
        };
        let mut out = Vec::new();
        if let Some(blocks) = blocks {
            walk(blocks, unit, &mut out);
        }
        out
    }
    fn walk(blocks: &[Block<'_>], unit: &crate::check::Unit, out: &mut Vec<Reach>) {
        for stmt in blocks.iter().flat_map(|b| &b.stmts) {
            match &stmt.kind {
                // Only a call, or an assignment of a call's value, can run a skill.
                StmtKind::Call { .. } | StmtKind::Assign { .. } => {
                    if let Some(crate::check::Target::Skill(id)) = unit.targets.get(&stmt.span) {
                        out.push(match unit.specials.get(&stmt.span) {
                            Some(&i) => Reach::Special(i),
                            None => Reach::Skill(*id),
                        });
                    }
                }
                StmtKind::If(c) | StmtKind::While { body: c, .. } => walk(&c.body, unit, out),
                _ => {}
            }
        }
    }
    let mut order = Vec::new();
    let mut seen = std::collections::HashSet::new();
    let mut stack: Vec<Reach> = calls(analysis, task).into_iter().rev().collect();
    while let Some(r) = stack.pop() {
        if !seen.insert(r) {
            continue;
        }
        order.push(r);
        if let Some(unit) = checked_units.get(&r) {
            stack.extend(calls(analysis, unit).into_iter().rev());
        }
    }
    order
}

/// A failure of the lowering itself on a program the checker accepted. It has no code
/// of its own in the catalogue of diagnostics, so it travels as a syntax error whose
/// message says what happened.
pub(crate) fn internal(file: FileId, span: Span, message: impl Into<String>) -> Box<Diagnostic> {
    Box::new(
        Diagnostic::new(
            Code::Syntax,
            file,
            span,
            format!("cannot lower this statement: {}", message.into()),
        )
        .with_label("the checker accepted it, but it has no bytecode"),
    )
}

pub(crate) fn build_error(file: FileId, span: Span, e: BuildError) -> Box<Diagnostic> {
    match e {
        BuildError::KindConflict { name, was, now } => Box::new(
            Diagnostic::new(
                Code::WrongVariableKind,
                file,
                span,
                format!(
                    "`{name}` is {} and cannot also be {}",
                    was.describe(),
                    now.describe()
                ),
            )
            .with_label("bound with another kind"),
        ),
        other => internal(file, span, other.to_string()),
    }
}

/// Each skill's checked unit (and each specialization's), found once rather than by a
/// search per skill.
pub(crate) fn checked_units<'a>(
    analysis: &'a Analysis<'_>,
) -> HashMap<Reach, &'a crate::check::Unit> {
    analysis
        .units
        .iter()
        .filter_map(|u| {
            let reach = match u.special {
                Some(i) => Reach::Special(i),
                None => Reach::Skill(u.skill?),
            };
            Some((reach, u))
        })
        .collect()
}

//! Interactive lines (requirement 6): a line of text given while a task runs is parsed
//! and checked on its own against the live module's variables and skills, then lowered
//! to a [`Fragment`] that `Vm::add_block` joins as new top-level blocks. A bad line
//! returns its diagnostics and changes nothing.
//!
//! The line is checked by the checker's own walker (`check::check_fragment`), with the
//! live module's variables (all bound, kinds fixed) and skills, so that a line and a
//! file get the same diagnostics.

use std::collections::HashMap;

use ilmr_model::RobotModel;
use ilmr_vm::Module;
use ilmr_vm::bytecode::{BlockId, Fragment, ModuleBuilder, UnitId};

use super::scope::Scope;
use super::stmt::Lowerer;
use super::{Reach, body, build_error, reachable, robotless};
use crate::ast::FileKind;
use crate::check::{Analysis, SkillId, Source};
use crate::diagnostic::{Code, Diagnostic, FileId};
use crate::parser;
use crate::span::{LineIndex, Span};

/// The start of a typed line's file name: `<typed 1>`, `<typed 2>`, ...
pub const TYPED: &str = "<typed ";

/// How a line is taken.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct LineOptions {
    /// The task runs with `--robot none`: commands that need a robot are refused.
    pub robotless: bool,
}

/// Parses, checks and lowers `text` against `live` into a fragment for
/// `Vm::add_block`. Diagnostics point into `text` as file 0. Warnings do not stop a
/// line.
pub fn lower_line(
    text: &str,
    live: &Module,
    model: &RobotModel,
    options: LineOptions,
) -> Result<Fragment, Vec<Diagnostic>> {
    let mut b = ModuleBuilder::extending(live);
    let blocks = lower_line_into(text, &mut b, model, options)?;
    b.finish_fragment(&blocks)
        .map_err(|e| vec![*build_error(FileId(0), Span::default(), e)])
}

/// The same, appending to the builder `Vm::add_line` lends, which holds the running
/// module itself: nothing is copied, so a line costs the same in a large program as in
/// a small one. Returns the blocks to start.
pub fn lower_line_into(
    text: &str,
    b: &mut ModuleBuilder,
    model: &RobotModel,
    options: LineOptions,
) -> Result<Vec<BlockId>, Vec<Diagnostic>> {
    lower_line_warned(text, b, model, options, &mut Vec::new())
}

/// [`lower_line_into`], also handing back the warnings of a line that was lowered
/// (they are appended to `warnings` only on success), for a front end that shows them.
pub fn lower_line_warned(
    text: &str,
    b: &mut ModuleBuilder,
    model: &RobotModel,
    options: LineOptions,
    warnings: &mut Vec<Diagnostic>,
) -> Result<Vec<BlockId>, Vec<Diagnostic>> {
    lower_line_with(text, b, model, options, None, warnings)
}

/// [`lower_line_warned`] for a front end that keeps the skill files the task was
/// started with (`ilmrc shell`, `ilmrc serve`). The running module holds only the
/// skills its task reached, each parameterized one only as the specializations the
/// task's calls made; a line that names a skill the module has no unit for (E0301
/// against the module alone) is checked again with `library` and the built-in skills
/// at hand (`check::check_line`): it may then call any of them, a parameterized skill
/// with arguments of its own, its arguments checked as a task file's are, and the
/// skills it reaches that the module lacks join with it as new units.
pub fn lower_line_with(
    text: &str,
    b: &mut ModuleBuilder,
    model: &RobotModel,
    options: LineOptions,
    library: Option<&[Source]>,
    warnings: &mut Vec<Diagnostic>,
) -> Result<Vec<BlockId>, Vec<Diagnostic>> {
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

    let live = b.module();
    // The running program's skills, in unit order: the checker's `SkillId(i)` is the
    // i-th of them.
    let skill_units: Vec<u32> = live
        .units
        .iter()
        .enumerate()
        .filter(|(_, u)| u.skill)
        .map(|(i, _)| i as u32)
        .collect();
    let (unit, checked) = crate::check::check_fragment(
        &parsed.file,
        file,
        model,
        live.globals.iter().map(|g| (g.name.as_str(), g.kind)),
        live.units
            .iter()
            .filter(|u| u.skill)
            .map(|u| u.name.as_str()),
    );
    if checked.iter().any(Diagnostic::is_error) {
        if let Some(library) = library
            && checked.iter().any(|d| d.code == Code::UnknownCommand)
        {
            return with_library(text, b, model, options, library, warnings);
        }
        return Err(errors(checked));
    }

    // Named by the order lines were typed in, whatever files the task came with.
    let typed = live.files.iter().filter(|f| f.starts_with(TYPED)).count();
    let path = format!("{TYPED}{}>", typed + 1);
    let base_code = live.code.len();
    let module_file = b
        .new_file(&path)
        .map_err(|e| vec![*build_error(file, Span::default(), e)])?;
    let skill_unit =
        |id: SkillId, _: Option<u32>| skill_units.get(id.0 as usize).map(|&i| UnitId(i));
    let lines = LineIndex::new(text);
    let scope = Scope::from_parts(file, module_file, text, &lines, &unit, &skill_unit);
    // The lowerer owns its builder; lend it this one and put it back whatever happens.
    let mut low = Lowerer::with_builder(std::mem::take(b), model);
    let blocks = low.blocks(&scope, &parsed.file.blocks);
    let lowered = std::mem::take(&mut low.diags);
    *b = low.b;
    if !lowered.is_empty() {
        return Err(lowered);
    }
    if options.robotless {
        let m = b.module();
        let refused = robotless::uses_in(m, m.code.get(base_code..).unwrap_or(&[]), |_| file);
        if !refused.is_empty() {
            return Err(refused);
        }
    }
    warnings.extend(diags.into_iter().chain(checked).filter(|d| !d.is_error()));
    Ok(blocks)
}

/// A line checked with the skill library (`check::check_line`), lowered with the
/// skills and specializations it reaches that the module has no unit for.
fn with_library(
    text: &str,
    b: &mut ModuleBuilder,
    model: &RobotModel,
    options: LineOptions,
    library: &[Source],
    warnings: &mut Vec<Diagnostic>,
) -> Result<Vec<BlockId>, Vec<Diagnostic>> {
    let file = FileId(0);
    let live = b.module();
    let analysis = crate::check::check_line(
        text,
        library,
        model,
        live.globals.iter().map(|g| (g.name.as_str(), g.kind)),
    );
    let Some(line_unit) = analysis.units.first() else {
        return Err(vec![*super::internal(
            file,
            Span::default(),
            "the line was not checked",
        )]);
    };
    let first = analysis.files[0]
        .tree
        .blocks
        .iter()
        .flat_map(|b| b.stmts.first())
        .next()
        .map_or(Span::default(), |s| s.span);
    let said: Vec<Diagnostic> = analysis
        .diagnostics
        .iter()
        .filter(|d| {
            // A skill's own warnings were the task's to give; those the line's
            // arguments cause are the line's.
            d.file == file || d.is_error() || d.secondary.iter().any(|l| l.file == file)
        })
        .map(|d| said_of_line(d, &analysis, first))
        .collect();
    if said.iter().any(Diagnostic::is_error) {
        return Err(errors(said));
    }

    let checked_units = super::checked_units(&analysis);
    let typed = live.files.iter().filter(|f| f.starts_with(TYPED)).count();
    let path = format!("{TYPED}{}>", typed + 1);
    let base_code = live.code.len();
    let fail = |e| vec![*build_error(file, Span::default(), e)];
    let module_file = b.new_file(&path).map_err(fail)?;
    // The module's unit for each skill the line reaches: the running program's where
    // it has one of that name, else a new one, lowered below.
    let mut units: HashMap<Reach, UnitId> = HashMap::new();
    let mut new_units = Vec::new();
    for r in reachable(&analysis, line_unit, &checked_units) {
        let name = match r {
            Reach::Skill(id) => &analysis.skills.get(id).name,
            Reach::Special(i) => &analysis.specials[i as usize].label,
        };
        let unit = match b.find_unit(name) {
            Some(u) => u,
            None => {
                let u = b.declare_unit(name, true).map_err(fail)?;
                new_units.push(r);
                u
            }
        };
        units.insert(r, unit);
    }
    let skill_unit = |id: SkillId, special: Option<u32>| {
        let reach = special.map_or(Reach::Skill(id), Reach::Special);
        units.get(&reach).copied()
    };
    // Each new unit's file, in the module's numbering, and its lines.
    let mut files = Vec::with_capacity(new_units.len());
    for &r in &new_units {
        let Some(&unit) = checked_units.get(&r) else {
            continue;
        };
        let entry = &analysis.files[unit.file.0 as usize];
        let module_file = b.file(entry.path).map_err(fail)?;
        files.push((r, unit, module_file, LineIndex::new(entry.text)));
    }
    let lines = LineIndex::new(text);
    let scope = Scope::from_parts(file, module_file, text, &lines, line_unit, &skill_unit);
    let mut low = Lowerer::with_builder(std::mem::take(b), model);
    let blocks = low.blocks(&scope, &analysis.files[0].tree.blocks);
    for (r, unit, module_file, lines) in &files {
        let Some(body) = body(&analysis, *r) else {
            continue;
        };
        let entry = &analysis.files[unit.file.0 as usize];
        let scope = Scope::from_parts(
            unit.file,
            *module_file,
            entry.text,
            lines,
            unit,
            &skill_unit,
        );
        let skill_blocks = low.blocks(&scope, body);
        if let Some(&id) = units.get(r) {
            low.b.define_unit(id, &skill_blocks);
        }
    }
    let lowered = std::mem::take(&mut low.diags);
    *b = low.b;
    if !lowered.is_empty() {
        return Err(lowered
            .iter()
            .map(|d| said_of_line(d, &analysis, first))
            .collect());
    }
    if options.robotless {
        let m = b.module();
        let refused = robotless::uses_in(m, m.code.get(base_code..).unwrap_or(&[]), |_| file);
        if !refused.is_empty() {
            return Err(refused);
        }
    }
    warnings.extend(said.into_iter().filter(|d| !d.is_error()));
    Ok(blocks)
}

/// A diagnostic of the line's check, as the line's front ends can show it: they
/// show the line's text alone. One in a skill's file keeps its code, message and
/// help, and points at the line's call that made it (else at the line's first
/// statement); its label says where in the skill it stands.
fn said_of_line(d: &Diagnostic, analysis: &Analysis<'_>, first: Span) -> Diagnostic {
    let line = FileId(0);
    if d.file == line {
        return d.clone();
    }
    let at = d.secondary.iter().find(|l| l.file == line);
    let entry = analysis.files.get(d.file.0 as usize);
    let place = entry.map_or_else(String::new, |e| {
        let (l, c) = LineIndex::new(e.text).line_col(e.text, d.span.start as usize);
        format!("{}:{l}:{c}", e.path)
    });
    let label = match at {
        Some(call) => format!("{} (at {place}, {})", d.label, call.message),
        None => format!("{} (at {place})", d.label),
    };
    let mut out = Diagnostic::new(
        d.code,
        line,
        at.map_or(first, |l| l.span),
        d.message.clone(),
    )
    .with_label(label);
    out.help = d.help.clone();
    out
}

fn errors(diags: Vec<Diagnostic>) -> Vec<Diagnostic> {
    diags.into_iter().filter(Diagnostic::is_error).collect()
}

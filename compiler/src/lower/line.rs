//! Interactive lines (requirement 6): a line of text given while a task runs is parsed
//! and checked on its own against the live module's variables and skills, then lowered
//! to a [`Fragment`] that `Vm::add_block` joins as new top-level blocks. A bad line
//! returns its diagnostics and changes nothing.
//!
//! The line is checked by the checker's own walker (`check::check_fragment`), with the
//! live module's variables (all bound, kinds fixed) and skills, so that a line and a
//! file get the same diagnostics.

use ilmr_model::RobotModel;
use ilmr_vm::Module;
use ilmr_vm::bytecode::{BlockId, Fragment, ModuleBuilder, UnitId};

use super::scope::Scope;
use super::stmt::Lowerer;
use super::{build_error, robotless};
use crate::ast::FileKind;
use crate::check::SkillId;
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

fn errors(diags: Vec<Diagnostic>) -> Vec<Diagnostic> {
    diags.into_iter().filter(Diagnostic::is_error).collect()
}

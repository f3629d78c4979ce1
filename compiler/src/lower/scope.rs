//! What the lowering of one unit (the task, a skill or an interactive line) needs to
//! know about its names: the checker's resolutions by span, the command or skill each
//! call statement runs, the unit's variables, and which module unit runs each skill.

use std::cell::{Cell, RefCell};

use ilmr_vm::bytecode::{UnitId, VarId as ModuleVar};
use rustc_hash::FxHashMap;

use super::refs::Refs;

use crate::check::{Analysis, Resolved, SkillId, Target, Unit, VarId, Vars};
use crate::diagnostic::FileId;
use crate::span::{LineIndex, Span};

pub struct Scope<'a> {
    /// Where diagnostics point.
    pub file: FileId,
    /// The module's number for the same file, which statements record.
    pub module_file: ilmr_vm::bytecode::FileId,
    pub text: &'a str,
    pub lines: &'a LineIndex,
    /// The checker's resolution of each name.
    refs: Refs<'a>,
    pub targets: &'a FxHashMap<Span, Target>,
    pub vars: &'a Vars,
    /// The module unit that runs a skill, or one of its specializations.
    pub skill_unit: &'a dyn Fn(SkillId, Option<u32>) -> Option<UnitId>,
    /// Calls of parameterized skills: the specialization each runs.
    pub specials: &'a FxHashMap<Span, u32>,
    /// The module's variable for each of `vars` the unit has used so far (`NO_SLOT`
    /// for the others), so that a name is hashed once per unit, not once per use.
    slots: RefCell<Vec<u32>>,
    /// The 0-based line of the last statement recorded.
    line_hint: Cell<usize>,
}

const NO_SLOT: u32 = u32::MAX;

impl<'a> Scope<'a> {
    /// `lines` indexes each of the analysis's files, in its order.
    pub fn new(
        analysis: &'a Analysis<'_>,
        lines: &'a [LineIndex],
        unit: &'a Unit,
        skill_unit: &'a dyn Fn(SkillId, Option<u32>) -> Option<UnitId>,
    ) -> Option<Scope<'a>> {
        let file = unit.file.0 as usize;
        Some(Scope::from_parts(
            unit.file,
            ilmr_vm::bytecode::FileId(unit.file.0),
            analysis.files.get(file)?.text,
            lines.get(file)?,
            unit,
            skill_unit,
        ))
    }

    pub fn from_parts(
        file: FileId,
        module_file: ilmr_vm::bytecode::FileId,
        text: &'a str,
        lines: &'a LineIndex,
        unit: &'a Unit,
        skill_unit: &'a dyn Fn(SkillId, Option<u32>) -> Option<UnitId>,
    ) -> Scope<'a> {
        Scope {
            file,
            module_file,
            text,
            lines,
            refs: Refs::new(&unit.refs),
            targets: &unit.targets,
            vars: &unit.vars,
            skill_unit,
            specials: &unit.specials,
            slots: RefCell::new(Vec::new()),
            line_hint: Cell::new(0),
        }
    }

    pub fn slot(&self, id: VarId) -> Option<ModuleVar> {
        let slots = self.slots.borrow();
        slots
            .get(id.0 as usize)
            .filter(|&&s| s != NO_SLOT)
            .map(|&s| ModuleVar(s))
    }

    pub fn remember(&self, id: VarId, var: ModuleVar) {
        let mut slots = self.slots.borrow_mut();
        let i = id.0 as usize;
        if slots.len() <= i {
            slots.resize(i + 1, NO_SLOT);
        }
        slots[i] = var.0;
    }

    pub fn resolved(&self, span: Span) -> Option<Resolved> {
        self.refs.get(span)
    }

    /// 1-based line of a span's start. Statements are recorded in source order, so the
    /// line is looked for first just after the last one's.
    pub fn line(&self, span: Span) -> u32 {
        let offset = span.start as usize;
        let count = self.lines.line_count();
        let starts_by = |l: usize| l < count && self.lines.line_start(l) <= offset;
        let mut l = self.line_hint.get().min(count.saturating_sub(1));
        for _ in 0..4 {
            if !starts_by(l + 1) {
                break;
            }
            l += 1;
        }
        if !starts_by(l) || starts_by(l + 1) {
            l = self.lines.line_of(offset);
        }
        self.line_hint.set(l);
        u32::try_from(l + 1).unwrap_or(u32::MAX)
    }

    pub fn slice(&self, span: Span) -> &'a str {
        self.text.get(span.range()).unwrap_or("")
    }
}

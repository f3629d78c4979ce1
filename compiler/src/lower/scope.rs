//! What the lowering of one unit (the task, a skill or an interactive line) needs to
//! know about its names: the checker's resolutions by span, the command or skill each
//! call statement runs, the unit's variables, and which module unit runs each skill.

use std::collections::HashMap;

use ilmr_vm::bytecode::UnitId;

use crate::check::{Analysis, Resolved, SkillId, Target, Unit, Vars};
use crate::diagnostic::FileId;
use crate::span::{LineIndex, Span};

pub struct Scope<'a> {
    /// Where diagnostics point.
    pub file: FileId,
    /// The module's number for the same file, which statements record.
    pub module_file: ilmr_vm::bytecode::FileId,
    pub text: &'a str,
    pub lines: LineIndex,
    /// The last resolution recorded for each span (a name is resolved once per role).
    pub refs: HashMap<Span, Resolved>,
    pub targets: &'a rustc_hash::FxHashMap<Span, Target>,
    pub vars: &'a Vars,
    pub skill_unit: &'a dyn Fn(SkillId) -> Option<UnitId>,
}

impl<'a> Scope<'a> {
    pub fn new(
        analysis: &'a Analysis<'_>,
        unit: &'a Unit,
        skill_unit: &'a dyn Fn(SkillId) -> Option<UnitId>,
    ) -> Scope<'a> {
        let text = analysis
            .files
            .get(unit.file.0 as usize)
            .map_or("", |f| f.text);
        Scope::from_parts(
            unit.file,
            ilmr_vm::bytecode::FileId(unit.file.0),
            text,
            &unit.refs,
            &unit.targets,
            &unit.vars,
            skill_unit,
        )
    }

    pub fn from_parts(
        file: FileId,
        module_file: ilmr_vm::bytecode::FileId,
        text: &'a str,
        refs: &[(Span, Resolved)],
        targets: &'a rustc_hash::FxHashMap<Span, Target>,
        vars: &'a Vars,
        skill_unit: &'a dyn Fn(SkillId) -> Option<UnitId>,
    ) -> Scope<'a> {
        Scope {
            file,
            module_file,
            text,
            lines: LineIndex::new(text),
            refs: refs.iter().copied().collect(),
            targets,
            vars,
            skill_unit,
        }
    }

    pub fn resolved(&self, span: Span) -> Option<Resolved> {
        self.refs.get(&span).copied()
    }

    /// 1-based line of a byte offset.
    pub fn line(&self, span: Span) -> u32 {
        u32::try_from(self.lines.line_of(span.start as usize) + 1).unwrap_or(u32::MAX)
    }

    pub fn slice(&self, span: Span) -> &'a str {
        self.text.get(span.range()).unwrap_or("")
    }
}

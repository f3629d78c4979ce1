//! Checks a program (task files, skill files and the built-in skills) against the robot
//! model. Checking never stops at the first problem: every statement is checked and the
//! problems accumulate as diagnostics, next to what was resolved (for the lowering and
//! the language server).

mod args;
mod breaks;
pub mod constants;
mod expr;
mod fold;
mod keywords;
mod loops;
mod names;
mod owners;
pub mod params;
mod paths;
pub mod schedule;
mod scope;
mod skills;
mod starve;
mod stream;
pub mod suggest;
mod wakes;

use ilmr_model::RobotModel;
use ilmr_stdlib::{Command, Syntax, VarKind};
use rustc_hash::FxHashMap;

use crate::ast::{Arg, Block, Call, ExprKind, FileKind, Name, SourceFile, Stmt, StmtKind};
use crate::diagnostic::{Code, Diagnostic, FileId};
use crate::kept::{Kept, Past};
use crate::parser;
use crate::span::Span;

/// An unknown call with no close match lists this many known skills, the nearest first.
const SKILLS_LISTED: usize = 5;

pub use args::fits;
pub use breaks::{breakable, matches, needle};
pub use constants::Constants;
pub use ilmr_stdlib::pattern::Needles;
pub use scope::{Places, Var, VarId, Vars};
pub use skills::SkillId;

/// One file of a program.
#[derive(Debug, Clone)]
pub struct Source {
    pub path: String,
    pub text: String,
    /// A file of a skill library (`--skills DIR`): its skills are checked where a task
    /// calls them, since a library may hold skills for other robots too.
    pub library: bool,
}

impl Source {
    pub fn new(path: impl Into<String>, text: impl Into<String>) -> Source {
        Source {
            path: path.into(),
            text: text.into(),
            library: false,
        }
    }

    pub fn library(path: impl Into<String>, text: impl Into<String>) -> Source {
        Source {
            library: true,
            ..Source::new(path, text)
        }
    }
}

/// What a name in the program turned out to be.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Resolved {
    Variable(VarId),
    Model,
    Keyword,
    Path,
    Command(Command),
    Skill(SkillId),
}

/// What a call statement (or `v = name`) runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Target {
    /// A command and the index of the form its arguments matched.
    Command {
        command: Command,
        form: usize,
    },
    Skill(SkillId),
    /// `v = w` copies the record of another variable.
    Copy(VarId),
}

#[derive(Debug)]
pub struct FileEntry<'s> {
    pub path: &'s str,
    pub text: &'s str,
    pub tree: SourceFile<'s>,
    /// Shipped with the toolchain (`<stdlib>/...`).
    pub builtin: bool,
    /// Checked only where called: built-in skills and `--skills` libraries.
    pub library: bool,
    /// `Parsed::break_patterns`: whether a `break(pattern)` may be in the tree.
    pub break_patterns: bool,
    /// The parser's errors, those past the diagnostics' limit (`Parsed::past`) among
    /// them: the analysis may keep fewer than the parser found.
    pub syntax_errors: usize,
    /// `Parsed::binds`: at least as many as the file's variables.
    pub binds: usize,
    /// `Parsed::seen`: what the passes after the walk may find in the file.
    pub seen: parser::Seen,
}

impl<'s> FileEntry<'s> {
    /// The file parsed, with the parser's diagnostics and the count of those past the
    /// limit.
    fn parse(
        path: &'s str,
        text: &'s str,
        file: FileId,
        builtin: bool,
        library: bool,
    ) -> (FileEntry<'s>, Vec<Diagnostic>, Past) {
        let parsed = parser::parse(text, file);
        let syntax_errors =
            parsed.diagnostics.iter().filter(|d| d.is_error()).count() + parsed.past.errors;
        let entry = FileEntry {
            path,
            text,
            tree: parsed.file,
            builtin,
            library,
            break_patterns: parsed.break_patterns,
            syntax_errors,
            binds: parsed.binds,
            seen: parsed.seen,
        };
        (entry, parsed.diagnostics, parsed.past)
    }
}

/// How much of what the checker resolves an analysis keeps. The diagnostics are the
/// same either way.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Detail {
    /// Everything, for the lowering and the language server: every name's resolution,
    /// every statement's target, every definition and use of each variable.
    Full,
    /// What the diagnostics need (`ilmrc check`): `Unit::refs` stays empty,
    /// `Unit::targets` holds only skill calls, and a variable keeps only its first
    /// definition and its first use. Task files are read block by block where the
    /// diagnostics allow (`stream.rs`): such a file's `FileEntry::tree` is left empty.
    Diagnostics,
}

/// A task file or a skill, checked with its own view of the variables.
#[derive(Debug)]
pub struct Unit {
    pub file: FileId,
    pub skill: Option<SkillId>,
    /// A specialization of a parameterized skill (`Analysis::specials`), checked with
    /// one call's arguments in place of its parameters.
    pub special: Option<u32>,
    /// Calls of parameterized skills in this unit: the call statement's span and the
    /// specialization it runs.
    pub specials: FxHashMap<Span, u32>,
    pub vars: Vars,
    pub refs: Vec<(Span, Resolved)>,
    pub targets: FxHashMap<Span, Target>,
}

impl Unit {
    fn new(file: FileId, skill: Option<SkillId>, special: Option<u32>, vars: Vars) -> Unit {
        Unit {
            file,
            skill,
            special,
            specials: FxHashMap::default(),
            vars,
            refs: Vec::new(),
            targets: FxHashMap::default(),
        }
    }
}

#[derive(Debug)]
pub struct Analysis<'s> {
    pub files: Vec<FileEntry<'s>>,
    pub skills: skills::Skills,
    /// Parameterized skills as the program's calls specialize them, and each one's
    /// body with the arguments in place of the parameters.
    pub specials: Vec<params::Special>,
    pub special_blocks: Vec<Box<[Block<'s>]>>,
    pub units: Vec<Unit>,
    /// Sorted by file and position.
    pub diagnostics: Vec<Diagnostic>,
}

impl Analysis<'_> {
    pub fn has_errors(&self) -> bool {
        self.diagnostics.iter().any(Diagnostic::is_error)
    }
}

/// Problems and resolutions found while checking one piece of a statement; kept apart
/// until the argument matcher knows which form they belong to.
#[derive(Debug, Default)]
pub struct Findings {
    pub diags: Vec<Diagnostic>,
    pub uses: Vec<(VarId, Span)>,
    pub refs: Vec<(Span, Resolved)>,
}

/// The checking context of one unit.
pub struct Cx<'m, 'v> {
    pub model: &'m RobotModel,
    pub constants: &'m constants::Constants,
    pub vars: &'v mut Vars,
    pub file: FileId,
    pub buf: &'v mut String,
    /// Emptied findings, kept for their capacity: a statement's findings are gathered
    /// apart and then absorbed, and most statements have some.
    pub spare: &'v mut Vec<Findings>,
    /// Whether the statement's diagnostics fall past the limit (`crate::kept`), so
    /// need no suggestions: they will be counted, not shown.
    pub quiet: bool,
    /// What searches over the program's own names may still spend.
    pub suggestions: &'v mut suggest::Budget,
}

impl Cx<'_, '_> {
    pub fn findings(&mut self) -> Findings {
        self.spare.pop().unwrap_or_default()
    }

    /// Returns findings that were not taken.
    pub fn discard(&mut self, mut f: Findings) {
        f.diags.clear();
        f.uses.clear();
        f.refs.clear();
        self.spare.push(f);
    }
}

pub fn analyze<'s>(sources: &'s [Source], model: &RobotModel) -> Analysis<'s> {
    analyze_with(sources, model, Detail::Full)
}

/// What the program is given from outside its files.
#[derive(Debug, Clone, Default)]
pub struct Given {
    /// Paths taught beforehand (a scenario's `paths`), which `followpath` may drive
    /// without the program recording them.
    pub paths: Vec<String>,
}

pub fn analyze_with<'s>(sources: &'s [Source], model: &RobotModel, detail: Detail) -> Analysis<'s> {
    analyze_given(sources, model, detail, &Given::default())
}

pub fn analyze_given<'s>(
    sources: &'s [Source],
    model: &RobotModel,
    detail: Detail,
    given: &Given,
) -> Analysis<'s> {
    if detail == Detail::Diagnostics
        && let Some(streamed) = stream::analyze(sources, model, given)
    {
        return streamed;
    }
    let mut diagnostics = Kept::new();
    let mut files: Vec<FileEntry<'s>> = Vec::with_capacity(sources.len() + 1);
    let builtins = ilmr_stdlib::skills::BUILTIN_SKILL_FILES
        .iter()
        .map(|b| (b.path, b.source, true, true));
    let user = sources
        .iter()
        .map(|s| (s.path.as_str(), s.text.as_str(), false, s.library));
    for (i, (path, text, builtin, library)) in user.chain(builtins).enumerate() {
        let (entry, found, past) = FileEntry::parse(path, text, FileId(i as u32), builtin, library);
        if !builtin {
            diagnostics.extend(found);
            diagnostics.add_past(past);
        }
        files.push(entry);
    }

    let mut skills = skills::Skills::collect(&files, model, &mut diagnostics);
    let mut specials = params::Specials::default();
    let constants = constants::Constants::new(model);
    let names = names::Names::new(&constants, &skills);
    let mut units = Vec::new();
    for (i, entry) in files.iter().enumerate() {
        if entry.tree.kind != FileKind::Task || entry.library {
            continue;
        }
        // Sized once: a large task's table would be copied as it doubles.
        let vars = Vars::with_capacity(entry.binds).with_detail(detail);
        let mut unit = Unit::new(FileId(i as u32), None, None, vars);
        Walker::new(
            model,
            &constants,
            &names,
            &skills,
            &mut unit,
            &mut diagnostics,
            detail,
            &mut specials,
        )
        .blocks(&entry.tree.blocks);
        units.push(unit);
    }
    let special_blocks = check_skills(
        &files,
        &mut skills,
        &mut specials,
        &mut units,
        &mut diagnostics,
        model,
        &constants,
        &names,
        detail,
    );

    breaks::check_patterns(&files, &skills, &mut diagnostics);
    let variables = units.iter().map(|u| u.vars.len()).sum();
    loops::check_frozen_loops(&files, &skills, variables, &mut diagnostics);
    wakes::check_waits(&files, &mut diagnostics);
    paths::check_paths(&files, &given.paths, &mut diagnostics);
    owners::check_owners(&files, &skills, &units, model, &mut diagnostics);
    unused_variables(&files, &units, &mut diagnostics);

    Analysis {
        files,
        skills,
        specials: specials.list,
        special_blocks,
        units,
        diagnostics: diagnostics.into_reported(),
    }
}

/// The skills a program's task units reach, after the task files' walk: those of the
/// files given to check first, then the library skills that anything checked so far
/// calls (library skills are checked only where called), then the specializations of
/// parameterized skills. Returns the specializations' bodies.
#[allow(clippy::too_many_arguments)]
fn check_skills<'s>(
    files: &[FileEntry<'s>],
    skills: &mut skills::Skills,
    specials: &mut params::Specials,
    units: &mut Vec<Unit>,
    diagnostics: &mut Kept,
    model: &RobotModel,
    constants: &constants::Constants,
    names: &names::Names,
    detail: Detail,
) -> Vec<Box<[Block<'s>]>> {
    // Keyed as a skill's table looks them up; a later binding of a name replaces an
    // earlier one.
    let globals = std::rc::Rc::new(skills_view(None, skills, units));
    // Skills of the files given to check first; then the library skills that anything
    // checked so far calls (library skills are checked only where called).
    for library in [false, true] {
        if library {
            let called: Vec<SkillId> = units
                .iter()
                .flat_map(|u| u.targets.values())
                .filter_map(|t| match t {
                    Target::Skill(id) => Some(*id),
                    _ => None,
                })
                .collect();
            for id in called {
                skills.mark_called(id);
            }
        }
        let ids: Vec<SkillId> = skills
            .iter()
            .filter(|(id, s)| {
                let entry = &files[s.file.0 as usize];
                entry.library == library && (!library || skills.is_called(*id))
            })
            .map(|(id, _)| id)
            .collect();
        for id in ids {
            let unit = check_skill(
                id,
                files,
                skills,
                specials,
                diagnostics,
                Checking {
                    model,
                    constants,
                    names,
                    globals: &globals,
                    detail,
                },
            );
            units.push(unit);
        }
    }
    check_specials(
        files,
        skills,
        specials,
        units,
        diagnostics,
        Checking {
            model,
            constants,
            names,
            globals: &globals,
            detail,
        },
    )
}

/// What checking a unit needs besides the unit.
struct Checking<'c> {
    model: &'c RobotModel,
    constants: &'c constants::Constants,
    names: &'c names::Names,
    globals: &'c std::rc::Rc<fold::FoldMap<VarKind>>,
    detail: Detail,
}

/// Checks one skill's body as a unit of its own. A parameterized skill is checked on
/// its own with its number parameters bound as numbers and each keyword parameter as
/// its first word; each call's specialization is checked again by [`check_specials`].
fn check_skill<'s>(
    id: SkillId,
    files: &[FileEntry<'s>],
    skills: &skills::Skills,
    specials: &mut params::Specials,
    diagnostics: &mut Kept,
    c: Checking<'_>,
) -> Unit {
    let skill = skills.get(id);
    let entry = &files[skill.file.0 as usize];
    let mut unit = Unit::new(
        skill.file,
        Some(id),
        None,
        Vars::with_globals(c.globals.clone()).with_detail(c.detail),
    );
    let blocks = &entry.tree.skills[skill.index].blocks;
    let abstract_blocks;
    let blocks = if skill.params.is_empty() {
        blocks
    } else {
        let with: Vec<params::Replace<'s>> = skill
            .params
            .iter()
            .map(|p| match p.word_spans.first() {
                Some(w) => params::Replace::Text(w.slice(entry.text)),
                None => params::Replace::Keep,
            })
            .collect();
        for p in skill.params.iter().filter(|p| p.words.is_empty()) {
            unit.vars.bind(&p.name, VarKind::Number, skill.file, p.span);
        }
        abstract_blocks = params::substitute(blocks, &skill.params, &with);
        &abstract_blocks
    };
    let mut walker = Walker::new(
        c.model,
        c.constants,
        c.names,
        skills,
        &mut unit,
        diagnostics,
        c.detail,
        specials,
    );
    walker.own_params = &skill.params;
    walker.blocks(blocks);
    unit
}

/// Checks each specialization of a parameterized skill (those its checking makes
/// too), and returns their bodies. What the skill's own check said already is not
/// said again; the rest points at the call whose arguments made it.
fn check_specials<'s>(
    files: &[FileEntry<'s>],
    skills: &skills::Skills,
    specials: &mut params::Specials,
    units: &mut Vec<Unit>,
    diagnostics: &mut Kept,
    c: Checking<'_>,
) -> Vec<Box<[Block<'s>]>> {
    let mut bodies = Vec::new();
    while bodies.len() < specials.list.len() {
        let i = bodies.len();
        let special = specials.list[i].clone();
        let info = skills.get(special.skill);
        let entry = &files[info.file.0 as usize];
        let with: Vec<params::Replace<'s>> = special
            .args
            .iter()
            .map(|g| match *g {
                params::Given::Number(v) => params::Replace::Number(v),
                params::Given::Text(f, span) => {
                    params::Replace::Text(span.slice(files[f.0 as usize].text))
                }
            })
            .collect();
        let blocks = params::substitute(&entry.tree.skills[info.index].blocks, &info.params, &with);
        let mut unit = Unit::new(
            info.file,
            Some(special.skill),
            Some(i as u32),
            Vars::with_globals(c.globals.clone()).with_detail(c.detail),
        );
        let mut found = Kept::new();
        Walker::new(
            c.model,
            c.constants,
            c.names,
            skills,
            &mut unit,
            &mut found,
            c.detail,
            specials,
        )
        .blocks(&blocks);
        let (call_file, call) = special.call;
        let (found, past) = found.finish();
        diagnostics.add_past(past);
        for d in found {
            if diagnostics.contains(&d) {
                continue;
            }
            diagnostics.push(d.with_secondary(
                call_file,
                call,
                format!("with the arguments of this call: `{}`", special.label),
            ));
        }
        units.push(unit);
        bodies.push(blocks);
    }
    bodies
}

/// Checks a fragment (an interactive line or block) that joins a running program: the
/// program's variables are bound and keep their kinds, its skills can be called. The
/// same walker as for files, so a line and a file get the same diagnostics.
pub fn check_fragment<'n>(
    tree: &SourceFile<'_>,
    file: FileId,
    model: &RobotModel,
    globals: impl IntoIterator<Item = (&'n str, VarKind)>,
    skill_names: impl IntoIterator<Item = &'n str>,
) -> (Unit, Vec<Diagnostic>) {
    let skills = skills::Skills::from_names(skill_names);
    let constants = constants::Constants::new(model);
    let names = names::Names::unindexed();
    let globals = std::rc::Rc::new(keyed(globals));
    let mut unit = Unit::new(file, None, None, Vars::with_fixed_globals(globals));
    let mut diagnostics = Kept::new();
    Walker::new(
        model,
        &constants,
        &names,
        &skills,
        &mut unit,
        &mut diagnostics,
        Detail::Full,
        &mut params::Specials::default(),
    )
    .blocks(&tree.blocks);
    (unit, diagnostics.into_reported())
}

/// The file name a line has in [`check_line`]'s analysis.
pub const LINE_FILE: &str = "<line>";

/// Checks an interactive line with the skill files the running program was started
/// with (`library`, checked as `--skills` libraries are) and the built-in skills at
/// hand, so that the line may call any of them, a parameterized skill with arguments
/// of its own too, whether or not the running program ever called it. The line is
/// file 0 and unit 0, checked by the same walker as [`check_fragment`] with the
/// program's variables bound and their kinds fixed; the skills it reaches and the
/// specializations its calls make are checked as a task's are, so that the lowering
/// can add those the running module lacks. Only the walk is run, as for
/// [`check_fragment`]: a line is not a program of its own.
pub fn check_line<'s, 'n>(
    line: &'s str,
    library: &'s [Source],
    model: &RobotModel,
    globals: impl IntoIterator<Item = (&'n str, VarKind)>,
) -> Analysis<'s> {
    let mut diagnostics = Kept::new();
    let mut files: Vec<FileEntry<'s>> = Vec::with_capacity(library.len() + 8);
    let (entry, found, past) = FileEntry::parse(LINE_FILE, line, FileId(0), false, false);
    diagnostics.extend(found);
    diagnostics.add_past(past);
    files.push(entry);
    let builtins = ilmr_stdlib::skills::BUILTIN_SKILL_FILES
        .iter()
        .map(|b| (b.path, b.source, true));
    let given = library
        .iter()
        .map(|s| (s.path.as_str(), s.text.as_str(), false));
    for (path, text, builtin) in given.chain(builtins) {
        // The library was checked when the program was; what it says of itself was
        // said then.
        let file = FileId(files.len() as u32);
        files.push(FileEntry::parse(path, text, file, builtin, true).0);
    }
    let mut skills = skills::Skills::collect(&files, model, &mut Kept::new());
    let constants = constants::Constants::new(model);
    let names = names::Names::new(&constants, &skills);
    let mut specials = params::Specials::default();

    let fixed = keyed(globals);
    let mut unit = Unit::new(
        FileId(0),
        None,
        None,
        Vars::with_fixed_globals(std::rc::Rc::new(fixed.clone())),
    );
    Walker::new(
        model,
        &constants,
        &names,
        &skills,
        &mut unit,
        &mut diagnostics,
        Detail::Full,
        &mut specials,
    )
    .blocks(&files[0].tree.blocks);

    // What a skill sees: the program's variables, the line's, and what skills bind.
    let globals = std::rc::Rc::new(skills_view(
        Some(fixed),
        &skills,
        std::slice::from_ref(&unit),
    ));
    let called: Vec<SkillId> = unit
        .targets
        .values()
        .filter_map(|t| match t {
            Target::Skill(id) => Some(*id),
            _ => None,
        })
        .collect();
    for id in called {
        skills.mark_called(id);
    }
    let checking = || Checking {
        model,
        constants: &constants,
        names: &names,
        globals: &globals,
        detail: Detail::Full,
    };
    let mut units = vec![unit];
    let ids: Vec<SkillId> = skills
        .iter()
        .filter(|(id, _)| skills.is_called(*id))
        .map(|(id, _)| id)
        .collect();
    for id in ids {
        let unit = check_skill(
            id,
            &files,
            &skills,
            &mut specials,
            &mut diagnostics,
            checking(),
        );
        units.push(unit);
    }
    let special_blocks = check_specials(
        &files,
        &skills,
        &mut specials,
        &mut units,
        &mut diagnostics,
        checking(),
    );
    Analysis {
        files,
        skills,
        specials: specials.list,
        special_blocks,
        units,
        diagnostics: diagnostics.into_reported(),
    }
}

/// Variables named by a running program, keyed as the checker looks them up.
fn keyed<'n>(vars: impl IntoIterator<Item = (&'n str, VarKind)>) -> fold::FoldMap<VarKind> {
    let mut table = fold::FoldMap::default();
    let mut buf = String::new();
    for (name, kind) in vars {
        table.insert(constants::key(name, &mut buf), kind);
    }
    table
}

/// What a skill sees: `base` (a running program's variables), then what skills bind,
/// then the variables of `units`, keyed as a skill's table looks them up; a later
/// binding of a name replaces an earlier one. Without a base the table is sized once:
/// a large task's would be copied as it doubles.
fn skills_view(
    base: Option<fold::FoldMap<VarKind>>,
    skills: &skills::Skills,
    units: &[Unit],
) -> fold::FoldMap<VarKind> {
    let skill_binds = skills.all_binds();
    let mut table = base.unwrap_or_else(|| {
        fold::FoldMap::with_capacity(
            skill_binds.len() + units.iter().map(|u| u.vars.len()).sum::<usize>(),
        )
    });
    let mut buf = String::new();
    for (name, kind) in skill_binds {
        table.insert(constants::key(&name, &mut buf), kind);
    }
    for unit in units {
        for (key, id) in unit.vars.keys() {
            table.insert(key, unit.vars.get(id).kind);
        }
    }
    table
}

/// W0502: a task variable that nothing reads, in the task or in any skill.
fn unused_variables(files: &[FileEntry<'_>], units: &[Unit], diagnostics: &mut Kept) {
    let mut skill_reads = fold::FoldMap::default();
    for unit in units.iter().filter(|u| u.skill.is_some()) {
        for (key, id) in unit.vars.keys() {
            if !unit.vars.get(id).uses.is_empty() {
                skill_reads.insert(key, ());
            }
        }
    }
    let mut buf = String::new();
    for unit in units.iter().filter(|u| u.skill.is_none()) {
        for (_, var) in unit.vars.iter() {
            if var.uses.is_empty()
                && skill_reads
                    .get(fold::lookup(&var.spelling, &mut buf))
                    .is_none()
            {
                let (file, span) = var.defs[0];
                if files[file.0 as usize].builtin {
                    continue;
                }
                diagnostics.push(
                    Diagnostic::new(
                        Code::UnusedVariable,
                        file,
                        span,
                        format!("`{}` is bound but never used", var.spelling),
                    )
                    .with_label("nothing reads this variable"),
                );
            }
        }
    }
}

/// Walks the statements of one unit in text order.
struct Walker<'a, 'm> {
    model: &'m RobotModel,
    constants: &'m constants::Constants,
    names: &'a names::Names,
    skills: &'a skills::Skills,
    unit: &'a mut Unit,
    diagnostics: &'a mut Kept,
    /// Whether to record resolutions and targets beyond what the diagnostics need.
    full: bool,
    buf: String,
    spare: Vec<Findings>,
    /// The specializations calls of parameterized skills make.
    specials: &'a mut params::Specials,
    /// The parameters of the skill being checked, which cannot be bound.
    own_params: &'a [params::Param],
    /// The statement being checked.
    at: Span,
}

impl<'a, 'm> Walker<'a, 'm> {
    // Each argument is a table the walk reads or fills; bundling them would only move
    // the list into a struct built once per call.
    #[allow(clippy::too_many_arguments)]
    fn new(
        model: &'m RobotModel,
        constants: &'m constants::Constants,
        names: &'a names::Names,
        skills: &'a skills::Skills,
        unit: &'a mut Unit,
        diagnostics: &'a mut Kept,
        detail: Detail,
        specials: &'a mut params::Specials,
    ) -> Self {
        Walker {
            specials,
            own_params: &[],
            model,
            constants,
            names,
            skills,
            unit,
            diagnostics,
            full: detail == Detail::Full,
            buf: String::new(),
            spare: Vec::new(),
            at: Span::empty(0),
        }
    }

    fn cx(&mut self) -> Cx<'m, '_> {
        Cx {
            model: self.model,
            constants: self.constants,
            vars: &mut self.unit.vars,
            file: self.unit.file,
            buf: &mut self.buf,
            spare: &mut self.spare,
            quiet: !self.diagnostics.admits(self.unit.file, self.at),
            suggestions: &mut self.diagnostics.suggestions,
        }
    }

    fn findings(&mut self) -> Findings {
        self.spare.pop().unwrap_or_default()
    }

    fn absorb(&mut self, mut f: Findings) {
        let file = self.unit.file;
        for (id, span) in f.uses.drain(..) {
            self.unit.vars.use_at(id, file, span);
        }
        if self.full {
            self.unit.refs.append(&mut f.refs);
        } else {
            f.refs.clear();
        }
        self.diagnostics.append(&mut f.diags);
        self.spare.push(f);
    }

    fn resolved(&mut self, span: Span, resolved: Resolved) {
        if self.full {
            self.unit.refs.push((span, resolved));
        }
    }

    /// Skill calls are kept in any detail: which library skills get checked depends on
    /// them.
    fn target(&mut self, stmt: Span, target: Target) {
        if self.full || matches!(target, Target::Skill(_)) {
            self.unit.targets.insert(stmt, target);
        }
    }

    fn meaning(&mut self, name: &str) -> names::Meaning {
        self.names
            .meaning(name, self.constants, self.skills, &mut self.buf)
    }

    fn blocks(&mut self, blocks: &[Block<'_>]) {
        for block in blocks {
            for (i, stmt) in block.stmts.iter().enumerate() {
                if matches!(stmt.kind, StmtKind::Priority) && i != 0 {
                    self.diagnostics.push(
                        Diagnostic::new(
                            Code::MisplacedPriority,
                            self.unit.file,
                            stmt.span,
                            "`priority = highest` must be the first statement of its block",
                        )
                        .with_label("not first in its block")
                        .with_secondary(
                            self.unit.file,
                            block.stmts[0].span,
                            "the block starts here",
                        )
                        .with_help("separate it from the statements above with an empty line"),
                    );
                }
                self.stmt(stmt);
            }
        }
    }

    fn stmt(&mut self, stmt: &Stmt<'_>) {
        self.at = stmt.span;
        match &stmt.kind {
            StmtKind::Call { bind, call } => {
                let kind = self.call(call, stmt.span);
                if let (Some(bind), Some(kind)) = (bind, kind) {
                    self.bind(bind, kind);
                }
            }
            StmtKind::Assign { target, value } => {
                let kind = match &value.kind {
                    ExprKind::Name(name) => self.assign_name(name, stmt.span),
                    _ => {
                        let mut f = self.findings();
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
                let mut f = self.findings();
                self.cx().condition(&mut f, &c.cond);
                self.absorb(f);
                self.blocks(&c.body);
            }
            StmtKind::While { bind, body } => {
                let mut f = self.findings();
                self.cx().condition(&mut f, &body.cond);
                self.absorb(f);
                if let Some(bind) = bind {
                    self.bind(bind, VarKind::Status);
                }
                self.blocks(&body.body);
            }
            StmtKind::Check { body, .. } => {
                let before = self.unit.vars.snapshot();
                self.blocks(body);
                self.unit.vars.restore(before);
            }
            StmtKind::Break { .. } | StmtKind::Priority | StmtKind::Error => {}
        }
    }

    /// `v = name`: a skill call, a bare command, a copy of a variable or a model constant.
    fn assign_name(&mut self, name: &Name<'_>, stmt: Span) -> Option<VarKind> {
        if self.unit.vars.bound(name.text).is_none() {
            let meaning = self.meaning(name.text);
            // A misspelt command or skill is reported as one, with its did-you-mean,
            // unless a variable or constant is spelt closer.
            let misspelt_call = meaning == names::Meaning::default()
                && self.call_suggestion(name.text).is_some()
                && self.cx().unbound(name).fix.is_none();
            if misspelt_call
                || meaning.constant.is_none()
                    && (meaning.skill.is_some() || meaning.command.is_some())
            {
                let call = Call {
                    name: *name,
                    args: None,
                };
                return self.call(&call, stmt);
            }
        }
        let mut f = self.findings();
        let copied = self.unit.vars.bound(name.text);
        self.cx().value(
            &mut f,
            &crate::ast::Expr {
                kind: ExprKind::Name(*name),
                span: name.span,
            },
        );
        // A position copied keeps being a position; `value` reports it as a misuse only
        // where a number is needed, so take the copy before that check.
        let kind = copied.map(|id| self.unit.vars.get(id).kind);
        f.diags.retain(|d| d.code != Code::WrongVariableKind);
        self.absorb(f);
        if let Some(id) = copied {
            self.target(stmt, Target::Copy(id));
        }
        Some(kind.unwrap_or(VarKind::Number))
    }

    /// Checks a call and returns what a variable bound to it would hold.
    fn call(&mut self, call: &Call<'_>, stmt: Span) -> Option<VarKind> {
        let file = self.unit.file;
        let meaning = self.meaning(call.name.text);
        if let Some(command) = meaning.command {
            let spec = command.spec();
            if spec.syntax == Syntax::Structural {
                self.diagnostics.push(
                    Diagnostic::new(
                        Code::Syntax,
                        file,
                        call.name.span,
                        format!("`{}` cannot be used this way", spec.name),
                    )
                    .with_label(format!("the grammar is: {}", spec.grammar)),
                );
                return None;
            }
            self.resolved(call.name.span, Resolved::Command(command));
            if let Some(device) = spec.needs_device.filter(|d| self.model.device(d).is_none()) {
                self.diagnostics
                    .push(self.missing_device(spec.name, device, call.name.span));
            }
            let at = call.args.as_ref().map_or(call.name.span, |a| a.span);
            let m = self.cx().match_forms(spec, call.args.as_ref(), at);
            let kind = args::produced(spec, m.form);
            self.absorb(m.findings);
            if let Some(name) = m.binds_position {
                self.bind(&name, VarKind::Position);
            }
            self.target(
                stmt,
                Target::Command {
                    command,
                    form: m.form,
                },
            );
            return Some(kind);
        }
        if let Some(id) = meaning.skill {
            self.resolved(call.name.span, Resolved::Skill(id));
            if !self.skills.get(id).params.is_empty() {
                self.skill_args(id, call, stmt);
            } else if let Some(args) = &call.args {
                self.diagnostics.push(
                    Diagnostic::new(
                        Code::ArgumentCount,
                        file,
                        args.span,
                        format!("skill `{}` takes no arguments", call.name.text),
                    )
                    .with_label("skills are called by name alone"),
                );
            }
            for (name, kind) in self.skills.transitive_binds(id) {
                self.unit.vars.bind(name, *kind, file, call.name.span);
            }
            self.target(stmt, Target::Skill(id));
            return Some(VarKind::Status);
        }
        if !self.diagnostics.admits(file, call.name.span) {
            // Past the limit: its suggestions are a search over every known name.
            self.diagnostics.count_dropped(Code::UnknownCommand);
            return None;
        }
        let d = Diagnostic::new(
            Code::UnknownCommand,
            file,
            call.name.span,
            format!(
                "`{}` is neither a command nor a known skill",
                call.name.text
            ),
        );
        let d = match self.call_suggestion(call.name.text) {
            Some(s) => d.with_label(format!("did you mean `{s}`?")).with_fix(
                format!("replace with `{s}`"),
                call.name.span,
                s,
            ),
            None => {
                let nearest = suggest::nearest(call.name.text, self.skills.names(), SKILLS_LISTED);
                let known = if nearest.is_empty() {
                    "this program knows no skills".to_string()
                } else {
                    format!(
                        "the nearest known skills are {}",
                        suggest::one_of(&nearest).trim_start_matches("one of ")
                    )
                };
                d.with_label("unknown name").with_help(format!(
                    "{known}; skills are found in the task's skill files, in `--skills DIR` and among the built-in skills"
                ))
            }
        };
        self.diagnostics.push(d);
        None
    }

    /// The arguments of a call of a parameterized skill, checked against its header
    /// like a command's: a number where it takes a number, one of its words where it
    /// takes a word. When they fit, the call runs the skill's specialization for them.
    fn skill_args(&mut self, id: SkillId, call: &Call<'_>, stmt: Span) {
        let file = self.unit.file;
        let skill = self.skills.get(id);
        let signature = params::signature(&skill.name, &skill.params);
        let items: &[Arg<'_>] = call.args.as_ref().map_or(&[], |a| &a.items);
        if items.len() != skill.params.len() {
            let at = call.args.as_ref().map_or(call.name.span, |a| a.span);
            self.diagnostics.push(
                Diagnostic::new(
                    Code::ArgumentCount,
                    file,
                    at,
                    format!(
                        "skill `{}` takes {} argument{}, given {}",
                        call.name.text,
                        skill.params.len(),
                        if skill.params.len() == 1 { "" } else { "s" },
                        items.len()
                    ),
                )
                .with_label(format!("the header is `{signature}:`")),
            );
            return;
        }
        let mut given = Vec::with_capacity(items.len());
        let mut fits = true;
        for (param, arg) in skill.params.iter().zip(items) {
            let e = match arg {
                Arg::Positional(e) => e,
                Arg::Setting { .. } => {
                    self.diagnostics.push(
                        Diagnostic::new(
                            Code::ArgumentKind,
                            file,
                            arg.span(),
                            "a skill's arguments are given in order, without names",
                        )
                        .with_label(format!("the header is `{signature}:`")),
                    );
                    fits = false;
                    continue;
                }
            };
            if !param.words.is_empty() {
                let word = match &e.kind {
                    ExprKind::Name(n) if param.words.iter().any(|w| n.is(w)) => Some(n),
                    _ => None,
                };
                match word {
                    Some(n) => {
                        self.resolved(n.span, Resolved::Keyword);
                        given.push((params::Given::Text(file, n.span), n.text));
                    }
                    None => {
                        let words: Vec<&str> = param.words.iter().map(String::as_str).collect();
                        let mut d = Diagnostic::new(
                            Code::UnknownKeyword,
                            file,
                            e.span,
                            format!(
                                "parameter `{}` of `{}` takes {}",
                                param.name,
                                skill.name,
                                suggest::one_of(&words)
                            ),
                        )
                        .with_label(format!("the header is `{signature}:`"));
                        if let ExprKind::Name(n) = &e.kind
                            && let Some(s) = suggest::closest(n.text, words.iter().copied())
                        {
                            d = d.with_fix(format!("replace with `{s}`"), n.span, s);
                        }
                        self.diagnostics.push(d);
                        fits = false;
                    }
                }
                continue;
            }
            if let Some(v) = params::number(e) {
                given.push((params::Given::Number(v), ""));
                continue;
            }
            match &e.kind {
                ExprKind::Name(n) => {
                    let mut f = self.findings();
                    self.cx().value(&mut f, e);
                    fits &= f.diags.is_empty();
                    self.absorb(f);
                    given.push((params::Given::Text(file, n.span), n.text));
                }
                _ => {
                    self.diagnostics.push(
                        Diagnostic::new(
                            Code::ArgumentKind,
                            file,
                            e.span,
                            format!(
                                "parameter `{}` of `{}` takes a number, a variable or a constant",
                                param.name, skill.name
                            ),
                        )
                        .with_label("arithmetic of variables")
                        .with_help(format!(
                            "the skill uses `{}` as if the argument were written there; write the value into a variable first (`v = ...`, then `{}(v, ...)`)",
                            param.name, skill.name
                        )),
                    );
                    fits = false;
                }
            }
        }
        // A parameterized skill checked on its own has no values for its parameters
        // to pass on: its specializations make theirs.
        if !fits || !self.own_params.is_empty() {
            return;
        }
        let name = skill.name.clone();
        if let Some(i) = self.specials.get_or_add(id, &name, given, (file, stmt)) {
            self.unit.specials.insert(stmt, i);
        }
    }

    /// The command or skill a misspelt call most likely meant.
    /// E0407 for a command whose device the robot lacks, naming what it has instead.
    fn missing_device(&self, command: &str, device: &str, at: Span) -> Diagnostic {
        let has: Vec<&str> = self.model.devices.iter().map(|d| d.name.as_str()).collect();
        Diagnostic::new(
            Code::Unsupported,
            self.unit.file,
            at,
            format!(
                "robot `{}` has no `{device}`: `{command}` cannot run on it",
                self.model.name
            ),
        )
        .with_label(format!("needs a `{device}` in [SENSORSANDACTUATORS]"))
        .with_help(format!(
            "`{}` has {}; run it on a robot whose model has a `{device}`",
            self.model.name,
            has.join(", ")
        ))
    }

    fn call_suggestion(&mut self, name: &str) -> Option<&'a str> {
        let candidates = Command::all()
            .filter(|c| c.spec().syntax == Syntax::Call)
            .map(|c| c.name())
            .chain(self.skills.names());
        self.diagnostics.suggestions.closest(name, candidates)
    }

    fn bind(&mut self, name: &Name<'_>, kind: VarKind) {
        let file = self.unit.file;
        let meaning = self.meaning(name.text);
        let reserved = if meaning.command.is_some() {
            Some("a command")
        } else if meaning.skill.is_some() {
            Some("a skill")
        } else if meaning.constant.is_some() {
            Some("a constant of the robot model")
        } else {
            None
        };
        if let Some(what) = reserved {
            self.diagnostics.push(
                Diagnostic::new(
                    Code::ReservedName,
                    file,
                    name.span,
                    format!("`{}` is {what} and cannot be a variable", name.text),
                )
                .with_label("choose another name"),
            );
            return;
        }
        if self.own_params.iter().any(|p| name.is(&p.name)) {
            self.diagnostics.push(
                Diagnostic::new(
                    Code::ReservedName,
                    file,
                    name.span,
                    format!(
                        "`{}` is a parameter of this skill and cannot be bound",
                        name.text
                    ),
                )
                .with_label("a parameter stands for what the call gives")
                .with_help("bind another name"),
            );
            return;
        }
        if let Some(fixed) = self.unit.vars.fixed_kind(name.text).filter(|k| *k != kind) {
            self.diagnostics.push(
                Diagnostic::new(
                    Code::WrongVariableKind,
                    file,
                    name.span,
                    format!(
                        "`{}` is {} in the running task and cannot become {}",
                        name.text,
                        fixed.describe(),
                        kind.describe()
                    ),
                )
                .with_label("bound with another kind"),
            );
            return;
        }
        let id = self.unit.vars.bind(name.text, kind, file, name.span);
        self.resolved(name.span, Resolved::Variable(id));
    }
}

//! One checked program: the workspace's task and skill files analysed together, kept
//! with the texts the analysis borrows from, and the lookups every feature shares (what
//! is at an offset, which unit a position belongs to, every occurrence of a name).

use std::panic::AssertUnwindSafe;

use ilmr_compiler::Span;
use ilmr_compiler::ast::{SourceFile, Stmt, StmtKind};
use ilmr_compiler::check::{Analysis, Resolved, SkillId, Source, Unit};
use ilmr_compiler::diagnostic::FileId;
use ilmr_model::RobotModel;
use self_cell::self_cell;

self_cell!(
    struct Cell {
        owner: Vec<Source>,
        #[covariant]
        dependent: Analysis,
    }
);

/// How program files are analysed: the compiler's `check::analyze`, which tests may
/// replace to prove that a failing analysis is isolated.
pub type Analyzer = for<'s> fn(&'s [Source], &RobotModel) -> Analysis<'s>;

/// The analysis of every program file of the workspace. File `i` of the analysis is
/// `uris[i]`; the built-in skills come after them and have no URI.
pub struct Program {
    cell: Cell,
    uris: Vec<String>,
    /// Files the analysis failed on (a bug in the checker), left out of `cell`.
    failed: Vec<Failure>,
}

/// A file whose analysis panicked, with the panic's message.
#[derive(Debug, Clone, PartialEq)]
pub struct Failure {
    pub uri: String,
    pub panic: String,
}

/// A name's meaning across the whole program, by which its occurrences are gathered.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Symbol {
    /// Variables are global records: one lower-cased name is one variable everywhere.
    Variable(String),
    Skill(SkillId),
    /// A path of `record`/`followpath`, by lower-cased name.
    Path(String),
}

impl Program {
    /// `files` are (URI, text) in a stable order. A panic inside the analysis costs the
    /// files that cause it, not the server: when the whole program's analysis fails,
    /// each file is analysed alone, and the program is analysed again without those
    /// that fail alone (without any file, if none fails alone).
    pub fn check(files: Vec<(String, String)>, model: &RobotModel, analyzer: Analyzer) -> Program {
        let sources: Vec<Source> = files
            .into_iter()
            .map(|(uri, text)| Source::new(uri, text))
            .collect();
        let (sources, panic) = match analyse(sources, model, analyzer) {
            Ok(program) => return program,
            Err(failed) => failed,
        };
        let mut failed: Vec<Failure> = sources
            .iter()
            .filter_map(|source| {
                let alone = analyse(vec![source.clone()], model, analyzer).err()?;
                Some(Failure {
                    uri: source.path.clone(),
                    panic: alone.1,
                })
            })
            .collect();
        if failed.is_empty() {
            failed = sources
                .iter()
                .map(|s| Failure {
                    uri: s.path.clone(),
                    panic: panic.clone(),
                })
                .collect();
        }
        let rest: Vec<Source> = sources
            .into_iter()
            .filter(|s| !failed.iter().any(|f| f.uri == s.path))
            .collect();
        let mut program = match analyse(rest, model, analyzer) {
            Ok(program) => program,
            Err((rest, panic)) => {
                failed.extend(rest.iter().map(|s| Failure {
                    uri: s.path.clone(),
                    panic: panic.clone(),
                }));
                // The built-in skills alone: if even they fail, the panic reaches the
                // engine's thread, which keeps the previous analysis.
                match analyse(Vec::new(), model, analyzer) {
                    Ok(program) => program,
                    Err((_, panic)) => std::panic::resume_unwind(Box::new(panic)),
                }
            }
        };
        program.failed = failed;
        program
    }

    /// The files the analysis failed on.
    pub fn failures(&self) -> &[Failure] {
        &self.failed
    }

    pub fn analysis(&self) -> &Analysis<'_> {
        self.cell.borrow_dependent()
    }

    pub fn file_id(&self, uri: &str) -> Option<FileId> {
        self.uris
            .iter()
            .position(|u| u == uri)
            .map(|i| FileId(i as u32))
    }

    /// `None` for the built-in skills, which no editor can open.
    pub fn uri(&self, file: FileId) -> Option<&str> {
        self.uris.get(file.0 as usize).map(String::as_str)
    }

    pub fn text(&self, file: FileId) -> &str {
        self.analysis().files[file.0 as usize].text
    }

    pub fn tree(&self, file: FileId) -> &SourceFile<'_> {
        &self.analysis().files[file.0 as usize].tree
    }

    /// The unit whose statements hold `offset`: the skill around it, else the task.
    pub fn unit_at(&self, file: FileId, offset: usize) -> Option<&Unit> {
        let analysis = self.analysis();
        let tree = self.tree(file);
        let skill = tree
            .skills
            .iter()
            .position(|s| s.span.contains(offset) || s.header.contains(offset));
        match skill {
            Some(index) => analysis.units.iter().find(|u| {
                u.skill.is_some_and(|id| {
                    let info = analysis.skills.get(id);
                    info.file == file && info.index == index
                })
            }),
            None => analysis
                .units
                .iter()
                .find(|u| u.file == file && u.skill.is_none()),
        }
    }

    pub fn units_of(&self, file: FileId) -> impl Iterator<Item = &Unit> {
        self.analysis().units.iter().filter(move |u| u.file == file)
    }

    /// The resolved name under the cursor (a name's end counts, where typing happens).
    pub fn resolved_at(&self, file: FileId, offset: usize) -> Option<(Span, Resolved, &Unit)> {
        self.units_of(file).find_map(|unit| {
            unit.refs
                .iter()
                .find(|(span, _)| span.contains(offset))
                .map(|&(span, r)| (span, r, unit))
        })
    }

    /// The skill whose header name is under the cursor.
    pub fn skill_header_at(&self, file: FileId, offset: usize) -> Option<SkillId> {
        let tree = self.tree(file);
        let index = tree
            .skills
            .iter()
            .position(|s| s.name.span.contains(offset))?;
        self.analysis()
            .skills
            .iter()
            .find(|(_, info)| info.file == file && info.index == index)
            .map(|(id, _)| id)
    }

    /// What the name under the cursor means program-wide.
    pub fn symbol_at(&self, file: FileId, offset: usize) -> Option<(Span, Symbol)> {
        if let Some(id) = self.skill_header_at(file, offset) {
            let info = self.analysis().skills.get(id);
            let name = self.tree(file).skills[info.index].name.span;
            return Some((name, Symbol::Skill(id)));
        }
        let (span, resolved, unit) = self.resolved_at(file, offset)?;
        let symbol = match resolved {
            Resolved::Variable(id) => Symbol::Variable(unit.vars.get(id).spelling.to_lowercase()),
            Resolved::Skill(id) => Symbol::Skill(id),
            Resolved::Path => Symbol::Path(span.slice(self.text(file)).to_lowercase()),
            _ => return None,
        };
        Some((span, symbol))
    }

    /// Every occurrence of a symbol in the program's files, sorted, without repeats.
    pub fn occurrences(&self, symbol: &Symbol) -> Vec<(FileId, Span)> {
        let analysis = self.analysis();
        let mut out = Vec::new();
        for unit in &analysis.units {
            let text = self.text(unit.file);
            for &(span, resolved) in &unit.refs {
                let hit = match (symbol, resolved) {
                    (Symbol::Variable(name), Resolved::Variable(id)) => {
                        unit.vars.get(id).spelling.to_lowercase() == *name
                    }
                    (Symbol::Skill(want), Resolved::Skill(id)) => *want == id,
                    (Symbol::Path(name), Resolved::Path) => {
                        span.slice(text).to_lowercase() == *name
                    }
                    _ => false,
                };
                if hit {
                    out.push((unit.file, span));
                }
            }
        }
        if let Symbol::Skill(id) = symbol {
            let info = analysis.skills.get(*id);
            out.push((info.file, self.tree(info.file).skills[info.index].name.span));
        }
        out.retain(|(file, _)| self.uri(*file).is_some());
        out.sort();
        out.dedup();
        out
    }

    /// Where a variable gets its value: the binding statements' names, in every unit,
    /// leaving out the skill calls that bind it only by running a skill.
    pub fn variable_defs(&self, name: &str) -> Vec<(FileId, Span)> {
        let analysis = self.analysis();
        let mut out = Vec::new();
        for unit in &analysis.units {
            // A set, not a search per binding: a name bound on every line of a long
            // file would make that quadratic.
            let mut via_skill: Option<std::collections::HashSet<Span>> = None;
            for (_, var) in unit.vars.iter() {
                if var.spelling.to_lowercase() != name {
                    continue;
                }
                let via_skill = via_skill.get_or_insert_with(|| {
                    unit.refs
                        .iter()
                        .filter(|(_, r)| matches!(r, Resolved::Skill(_)))
                        .map(|(s, _)| *s)
                        .collect()
                });
                for &(file, span) in &var.defs {
                    if !via_skill.contains(&span) {
                        out.push((file, span));
                    }
                }
            }
        }
        out.sort();
        out.dedup();
        out
    }

    /// The innermost statement whose own line holds `offset`.
    pub fn stmt_at(&self, file: FileId, offset: usize) -> Option<&Stmt<'_>> {
        stmt_containing(self.tree(file), Span::empty(offset))
    }
}

/// The program's analysis, or the sources back with the panic's message.
fn analyse(
    sources: Vec<Source>,
    model: &RobotModel,
    analyzer: Analyzer,
) -> Result<Program, (Vec<Source>, String)> {
    let uris = sources.iter().map(|s| s.path.clone()).collect();
    let cell = Cell::try_new_or_recover(sources, |sources| {
        std::panic::catch_unwind(AssertUnwindSafe(|| analyzer(sources, model)))
            .map_err(|payload| panic_message(payload.as_ref()))
    })?;
    Ok(Program {
        cell,
        uris,
        failed: Vec::new(),
    })
}

/// A panic's message, as `panic!` formatted it.
pub fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "a panic without a message".to_string())
}

/// The innermost statement whose own line holds all of `span`.
pub fn stmt_containing<'a, 's>(tree: &'a SourceFile<'s>, name: Span) -> Option<&'a Stmt<'s>> {
    let mut found: Option<&'a Stmt<'s>> = None;
    walk(&tree.blocks, name, &mut found);
    for skill in &tree.skills {
        walk(&skill.blocks, name, &mut found);
    }
    found
}

fn walk<'a, 's>(
    blocks: &'a [ilmr_compiler::ast::Block<'s>],
    at: Span,
    found: &mut Option<&'a Stmt<'s>>,
) {
    for block in blocks {
        for stmt in &block.stmts {
            if stmt.span.contains(at.start as usize) && stmt.span.contains(at.end as usize) {
                *found = Some(stmt);
            }
            match &stmt.kind {
                StmtKind::If(c) | StmtKind::While { body: c, .. } => walk(&c.body, at, found),
                StmtKind::Check { body, .. } => walk(body, at, found),
                _ => {}
            }
        }
    }
}

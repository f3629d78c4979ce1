//! Paths followed but never recorded (W0903). `followpath(P)` drives a path the VM
//! holds by name: recorded with `record(P)`, made with `createpath(P, ...)`, or taught
//! beforehand (a scenario's `paths`, which `ilmrc run --scenario` gives the check).
//! When nothing in the program can make `P` and nothing gave it, the movement is
//! refused when it starts.
//!
//! Only that certain case is said. A `record(P)` that stands after the `followpath`
//! may still come first: the path is looked up when the movement starts, which waits
//! for every movement queued before it.

use rustc_hash::FxHashSet;

use crate::ast::{Arg, Args, Block, Expr, ExprKind, Name, StmtKind};
use crate::check::FileEntry;
use crate::diagnostic::{Code, Diagnostic, FileId};
use crate::kept::Kept;
use crate::span::Span;
use ilmr_stdlib::Command;

struct Follow<'s> {
    file: FileId,
    name: &'s str,
    at: Span,
    /// The first statement of the block the `followpath` stands in.
    block_start: Span,
}

pub fn check_paths(files: &[FileEntry<'_>], given: &[String], diags: &mut Kept) {
    Paths::new(given).finish(files, 0, diags);
}

/// W0903 gathered as a streamed task's blocks come (`check/stream.rs`): the paths made
/// and the `followpath`s met, judged in [`Paths::finish`] once every file is read.
pub struct Paths<'s> {
    made: FxHashSet<String>,
    follows: Vec<Follow<'s>>,
}

impl<'s> Paths<'s> {
    pub fn new(given: &[String]) -> Paths<'s> {
        Paths {
            made: given.iter().map(|p| p.to_lowercase()).collect(),
            follows: Vec::new(),
        }
    }

    /// One top-level block of a streamed task file.
    pub fn block(&mut self, file: FileId, block: &Block<'s>) {
        let blocks = std::slice::from_ref(block);
        walk(file, blocks, true, &mut self.made, &mut self.follows);
    }

    /// The files from `from` on, then the verdicts.
    pub fn finish(mut self, files: &[FileEntry<'s>], from: usize, diags: &mut Kept) {
        // Only a `followpath` outside a library is reported: without one, nothing to walk.
        if !files.iter().any(|f| !f.library && f.seen.follows_path) {
            return;
        }
        for (i, entry) in files.iter().enumerate().skip(from) {
            let file = FileId(i as u32);
            let report = !entry.library;
            walk(
                file,
                &entry.tree.blocks,
                report,
                &mut self.made,
                &mut self.follows,
            );
            for skill in &entry.tree.skills {
                walk(
                    file,
                    &skill.blocks,
                    report,
                    &mut self.made,
                    &mut self.follows,
                );
            }
        }
        report(&self.made, self.follows, diags);
    }
}

fn report(made: &FxHashSet<String>, follows: Vec<Follow<'_>>, diags: &mut Kept) {
    for f in follows {
        if made.contains(&f.name.to_lowercase()) {
            continue;
        }
        let name = f.name;
        let mut d = Diagnostic::new(
            Code::PathNeverRecorded,
            f.file,
            f.at,
            format!("no statement records or creates the path `{name}`"),
        )
        .with_label(format!("`{name}` is not recorded (`record`) or created (`createpath`) anywhere in the program"))
        .with_help(format!(
            "record it before this in its block (`record({name})`, drive the way, `record(close)`), make it with `createpath({name},x1,y1,x2,y2...)`, or give it in a scenario's `paths` (`ilmrc run --scenario`); otherwise the movement is refused when it starts"
        ));
        if f.block_start != f.at {
            d = d.with_secondary(
                f.file,
                f.block_start,
                format!("`record({name})` here, before the `followpath`, would provide it"),
            );
        }
        diags.push(d);
    }
}

fn walk<'s>(
    file: FileId,
    blocks: &[Block<'s>],
    report: bool,
    made: &mut FxHashSet<String>,
    follows: &mut Vec<Follow<'s>>,
) {
    for block in blocks {
        // What is inside `check` never runs: no place to record.
        let Some(first) = block
            .stmts
            .iter()
            .find(|s| !matches!(s.kind, StmtKind::Check { .. }))
        else {
            continue;
        };
        for stmt in &block.stmts {
            match &stmt.kind {
                StmtKind::Call { call, .. } => {
                    // Three names compared, not every command looked up: this runs
                    // for every call of the program.
                    let is = |c: Command| call.name.is(c.name());
                    let makes = is(Command::Record) || is(Command::CreatePath);
                    let follows_path = report && is(Command::FollowPath);
                    if !makes && !follows_path {
                        continue;
                    }
                    let Some(name) = first_name(call.args.as_ref()) else {
                        continue;
                    };
                    if makes
                        && !(is(Command::Record) && Command::Record.spec().has_keyword(name.text))
                    {
                        // `record(close)` stops recording; it names no path.
                        made.insert(name.text.to_lowercase());
                    } else if follows_path {
                        follows.push(Follow {
                            file,
                            name: name.text,
                            at: name.span,
                            block_start: first.span,
                        });
                    }
                }
                StmtKind::If(c) | StmtKind::While { body: c, .. } => {
                    walk(file, &c.body, report, made, follows);
                }
                // Never runs: records nothing, follows nothing.
                StmtKind::Check { .. } => {}
                _ => {}
            }
        }
    }
}

fn first_name<'a, 's>(args: Option<&'a Args<'s>>) -> Option<&'a Name<'s>> {
    match args?.items.first()? {
        Arg::Positional(Expr {
            kind: ExprKind::Name(n),
            ..
        }) => Some(n),
        _ => None,
    }
}

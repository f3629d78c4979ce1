//! Waits that never wake (W0904): `wait(v)` holds its block until `v`'s status is 1,
//! which the command bound to `v` sets when it ends. When every statement that sets
//! `v` is one that never ends by itself (a `followwall`, an endless `goahead()`, a
//! `while` whose condition is a constant other than 0) and nothing the program holds
//! can end it (no bare `break`, no `break(pattern)` whose pattern is found in it or in
//! a statement round it, no `priority` block), the wait holds its block for good.
//!
//! Anything else that names `v` (an assignment, another command bound to it or taking
//! it as an argument, a skill) may set its status and silences the warning: it is
//! said only where it is certain that nothing in the program can wake the wait.

use ilmr_stdlib::Command;

use crate::ast::{Arg, Block, Expr, ExprKind, Stmt, StmtKind};
use crate::check::FileEntry;
use crate::check::breaks::needle;
use crate::check::constants;
use crate::check::fold::{self, FoldMap};
use crate::diagnostic::{Code, Diagnostic, FileId};
use crate::kept::Kept;
use crate::limits;
use crate::span::Span;
use ilmr_stdlib::pattern::Needles;
use std::cell::Cell;

/// A statement that never ends by itself, and the statements it stands inside (a
/// break that ends one of them ends it too).
struct Endless<'s> {
    var: &'s str,
    file: FileId,
    stmt: Span,
    around: Vec<Span>,
    /// Inside a skill: a break may also end it through the call.
    in_skill: bool,
}

/// The first pass: waits, the statements that never end, and what can end them.
#[derive(Default)]
struct Scan<'s> {
    waits: Vec<(FileId, Span, &'s str)>,
    endless: Vec<Endless<'s>>,
    bare_break: bool,
    priority: bool,
    patterns: Vec<&'s str>,
}

pub fn check_waits(files: &[FileEntry<'_>], diags: &mut Kept) {
    // A wait is said never to wake only on a statement that never ends: without one,
    // nothing to walk.
    if !files.iter().any(|f| f.seen.never_ending) {
        return;
    }
    let never: Vec<Command> = Command::never_ending().collect();
    let mut scan = Scan::default();
    for (i, entry) in files.iter().enumerate() {
        let file = FileId(i as u32);
        let mut around = Vec::new();
        // A library's waits are its business; its statements and breaks still count.
        let waits = !entry.library;
        let mut cx = Pass1 {
            scan: &mut scan,
            never: &never,
            file,
            around: &mut around,
            in_skill: false,
            waits,
        };
        cx.blocks(&entry.tree.blocks);
        cx.in_skill = true;
        for skill in &entry.tree.skills {
            cx.blocks(&skill.blocks);
        }
    }
    if scan.waits.is_empty() || scan.endless.is_empty() || scan.bare_break || scan.priority {
        return;
    }
    // Variables waited on that a never-ending statement sets; the second pass looks
    // for anything else that sets them.
    let mut buf = String::new();
    let waited: FoldMap<()> = {
        let mut m = FoldMap::default();
        for w in &scan.waits {
            m.insert(constants::key(w.2, &mut buf), ());
        }
        m
    };
    // The never-ending statements of each variable waited on, and whether something
    // else sets it (the second pass finds out).
    let mut suspects: FoldMap<(Vec<usize>, Cell<bool>)> = FoldMap::default();
    for (i, e) in scan.endless.iter().enumerate() {
        if waited.get(fold::lookup(e.var, &mut buf)).is_some() {
            suspects
                .get_or_insert_with(constants::key(e.var, &mut buf), Default::default)
                .0
                .push(i);
        }
    }
    if suspects.len() == 0 {
        return;
    }
    for entry in files {
        let mut set_other = |name: &str| {
            if let Some((_, other)) = suspects.get(fold::lookup(name, &mut buf)) {
                other.set(true);
            }
        };
        entry.tree.for_each_stmt(&mut |stmt: &Stmt<'_>| {
            others(stmt, &never, &mut set_other);
        });
    }
    // Whether a break can end one of a variable's setters is the same for every wait
    // on it: decided once, at its first wait.
    let mut reachable: FoldMap<bool> = FoldMap::default();
    let needles = Needles::new(scan.patterns.iter().copied(), limits::PATTERN_MATCHES);
    for (file, span, var) in &scan.waits {
        let Some((indices, other)) = suspects.get(fold::lookup(var, &mut buf)) else {
            continue;
        };
        if other.get() {
            continue;
        }
        let setters = || indices.iter().map(|&i| &scan.endless[i]);
        let ends = match reachable.get(fold::lookup(var, &mut buf)) {
            Some(&ends) => ends,
            None => {
                // Past the search's limit, a break may end it for all that is known.
                let ends = setters().any(|e| {
                    let text = files[e.file.0 as usize].text;
                    (e.in_skill && !scan.patterns.is_empty())
                        || std::iter::once(&e.stmt)
                            .chain(&e.around)
                            .any(|s| needles.any_in(s.slice(text)).unwrap_or(true))
                });
                reachable.insert(constants::key(var, &mut buf), ends);
                ends
            }
        };
        if ends {
            continue;
        }
        let first = &scan.endless[indices[0]];
        let shown = first.stmt.slice(files[first.file.0 as usize].text);
        let shown = shown.lines().next().unwrap_or("").trim();
        let d = Diagnostic::new(
            Code::WaitNeverWakes,
            *file,
            *span,
            format!(
                "`wait({var})` never wakes: `{var}` is set only by commands that never end by themselves, and nothing in the program ends them"
            ),
        )
        .with_label(format!("holds its block until `{var}` ends"))
        .with_help(format!(
            "end it with `{}` where it should stop (in a guard `if(...)`), or wait for something that ends; otherwise only a refusal, or a line typed while the task runs, wakes this wait",
            suggest_break(shown)
        ))
        .with_places(
            setters().map(|e| (e.file, e.stmt)),
            indices.len(),
            "never ends by itself, and no break ends it",
        );
        diags.push(d);
    }
}

/// Whether a bound statement never ends by itself.
fn endless_stmt(stmt: &Stmt<'_>, never: &[Command]) -> bool {
    match &stmt.kind {
        StmtKind::Call {
            bind: Some(_),
            call,
        } => {
            let args = call.args.as_ref().map_or(0, |a| a.items.len());
            never
                .iter()
                .any(|c| call.name.is(c.name()) && c.spec().ends.never(args))
        }
        StmtKind::While {
            bind: Some(_),
            body,
        } => constant_true(&body.cond),
        _ => false,
    }
}

/// The names a statement sets, or may set, other than by never ending: what it
/// assigns, binds to a command that ends, or names as an argument (except `wait`,
/// which only reads).
fn others<'s>(stmt: &Stmt<'s>, never: &[Command], f: &mut impl FnMut(&'s str)) {
    match &stmt.kind {
        StmtKind::Call { bind, call } => {
            if let Some(b) = bind
                && !endless_stmt(stmt, never)
            {
                f(b.text);
            }
            if call.name.is(Command::Wait.name()) {
                return;
            }
            for a in call.args.iter().flat_map(|a| a.items.iter()) {
                if let Arg::Positional(Expr {
                    kind: ExprKind::Name(n),
                    ..
                }) = a
                {
                    f(n.text);
                }
            }
        }
        StmtKind::Assign { target, .. } => f(target.text),
        StmtKind::While { bind: Some(b), .. } if !endless_stmt(stmt, never) => f(b.text),
        _ => {}
    }
}

/// `break(followwall)` for `w = followwall(left)`.
fn suggest_break(statement: &str) -> String {
    let call = statement
        .split_once('=')
        .map_or(statement, |(_, rest)| rest)
        .trim();
    let word: String = call
        .chars()
        .take_while(|c| c.is_alphanumeric() || *c == '_')
        .collect();
    format!("break({word})")
}

struct Pass1<'a, 's> {
    scan: &'a mut Scan<'s>,
    never: &'a [Command],
    file: FileId,
    around: &'a mut Vec<Span>,
    in_skill: bool,
    waits: bool,
}

impl<'s> Pass1<'_, 's> {
    fn blocks(&mut self, blocks: &'s [Block<'s>]) {
        for block in blocks {
            for stmt in &block.stmts {
                self.stmt(stmt);
            }
        }
    }

    fn stmt(&mut self, stmt: &'s Stmt<'s>) {
        match &stmt.kind {
            StmtKind::Call { bind, call } => {
                if call.name.is(Command::Wait.name()) {
                    if let (
                        Some(Arg::Positional(Expr {
                            kind: ExprKind::Name(n),
                            ..
                        })),
                        true,
                    ) = (call.args.as_ref().and_then(|a| a.items.first()), self.waits)
                    {
                        self.scan.waits.push((self.file, stmt.span, n.text));
                    }
                } else if let Some(b) = bind
                    && endless_stmt(stmt, self.never)
                {
                    self.endless(b.text, stmt.span);
                }
            }
            StmtKind::If(c) => {
                self.around.push(stmt.span);
                self.blocks(&c.body);
                self.around.pop();
            }
            StmtKind::While { bind, body } => {
                if let Some(b) = bind
                    && endless_stmt(stmt, self.never)
                {
                    self.endless(b.text, stmt.span);
                }
                self.around.push(stmt.span);
                self.blocks(&body.body);
                self.around.pop();
            }
            // Never runs.
            StmtKind::Check { .. } => {}
            StmtKind::Break { pattern: None } => self.scan.bare_break = true,
            StmtKind::Break { pattern: Some(p) } => self.scan.patterns.push(needle(p)),
            StmtKind::Priority => self.scan.priority = true,
            StmtKind::Assign { .. } | StmtKind::Error => {}
        }
    }

    fn endless(&mut self, var: &'s str, stmt: Span) {
        self.scan.endless.push(Endless {
            var,
            file: self.file,
            stmt,
            around: self.around.clone(),
            in_skill: self.in_skill,
        });
    }
}

/// A condition of numbers alone whose value is not 0 (`while(1)`).
fn constant_true(e: &Expr<'_>) -> bool {
    fn value(e: &Expr<'_>) -> Option<f64> {
        match &e.kind {
            ExprKind::Number(n) => Some(*n),
            ExprKind::Neg(inner) => value(inner).map(|v| -v),
            ExprKind::Binary { op, lhs, rhs } => {
                let (a, b) = (value(lhs)?, value(rhs)?);
                Some(match op {
                    crate::ast::BinOp::Add => a + b,
                    crate::ast::BinOp::Sub => a - b,
                    crate::ast::BinOp::Mul => a * b,
                    crate::ast::BinOp::Div if b != 0.0 => a / b,
                    crate::ast::BinOp::Div => return None,
                })
            }
            ExprKind::Compare { op, lhs, rhs, .. } => {
                let (a, b) = (value(lhs)?, value(rhs)?);
                let holds = match op {
                    crate::ast::CmpOp::Lt => a < b,
                    crate::ast::CmpOp::Le => a <= b,
                    crate::ast::CmpOp::Eq => a == b,
                    crate::ast::CmpOp::Ne => a != b,
                    crate::ast::CmpOp::Gt => a > b,
                    crate::ast::CmpOp::Ge => a >= b,
                };
                Some(if holds { 1.0 } else { 0.0 })
            }
            ExprKind::Name(_) | ExprKind::Error => None,
        }
    }
    value(e).is_some_and(|v| v != 0.0)
}

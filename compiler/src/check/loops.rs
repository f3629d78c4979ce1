//! Loops that cannot end by themselves (W0901): a `while` whose condition reads only
//! variables that nothing can change while it runs. Figure 27's inner loop is one:
//! `claps=0` / `while(claps<2)` / `clap_hands` / `endwhile` claps for ever.
//!
//! A variable can change while a loop runs when a command is bound to it (a reading
//! follows its sensor, a movement's `dist` grows, a status turns 1), when a command
//! names it as an argument (`savepos(p)`, `record(p)`), or when an assignment to it can
//! run at the same time as the loop or inside it: in the loop's body, after the loop in
//! its block (a `while` does not hold its block back), in a guard, another block or a
//! skill. Only the assignments issued before the loop, one after another in its own
//! block and the blocks round it, are over when it starts. Lines typed while the task
//! runs could still change the variable; the help says so.

use std::cell::Cell;

use smallvec::SmallVec;

use crate::ast::{Block, Expr, ExprKind, Stmt, StmtKind};
use crate::check::FileEntry;
use crate::check::fold::FoldMap;
use crate::check::skills::Skills;
use crate::check::starve;
use crate::diagnostic::{Code, Diagnostic, FileId};
use crate::kept::Kept;
use crate::span::Span;

/// How a variable is written, over the whole program.
#[derive(Default)]
struct Writes {
    /// A command binds it or names it: it can change at any time.
    by_command: bool,
    /// Where it is assigned: most variables once or twice (a counter's start and
    /// step), kept without an allocation.
    assigned: SmallVec<[(FileId, Span); 2]>,
    /// How many of those the walk has issued before the statement it is at: all of
    /// them, when the loop it looks at is the only thing left that reads them.
    issued: Cell<usize>,
}

/// W0901, and W0902 (`starve.rs`) for the same loops. `variables` is how many
/// variables the program's units hold, which sizes the table of writes once.
pub fn check_frozen_loops(
    files: &[FileEntry<'_>],
    skills: &Skills,
    variables: usize,
    diags: &mut Kept,
) {
    let Some(writes) = writes(files, variables) else {
        return;
    };
    let is_variable = |name: &str| find(&writes, name).is_some();
    let program = starve::Program {
        skills,
        is_variable: &is_variable,
    };
    // A library's skills are checked where they are called; their loops are the
    // library's business.
    for (i, entry) in files.iter().enumerate().filter(|(_, e)| !e.library) {
        let file = FileId(i as u32);
        let mut walk = Walk {
            file,
            text: entry.text,
            writes: &writes,
            program: &program,
            before: Vec::new(),
            names: Vec::new(),
            diags,
        };
        walk.blocks(&entry.tree.blocks);
        for skill in &entry.tree.skills {
            walk.blocks(&skill.blocks);
        }
    }
}

/// The writes of `name`, in any case.
fn find<'w>(writes: &'w FoldMap<Writes>, name: &str) -> Option<&'w Writes> {
    if name.is_ascii() {
        writes.get(name)
    } else {
        writes.get(&name.to_lowercase())
    }
}

/// Keyed without a copy of each name: the table is filled from every statement of
/// the program, and most names are found in it (a variable is bound, then named or
/// assigned again). One walk also tells whether there is a loop. `None` when the program has no loop, which is all it is for.
fn writes(files: &[FileEntry<'_>], variables: usize) -> Option<FoldMap<Writes>> {
    let mut writes: FoldMap<Writes> = FoldMap::with_capacity(variables);
    let mut any_loop = false;
    let mut buf = String::new();
    fn entry<'w>(writes: &'w mut FoldMap<Writes>, buf: &mut String, name: &str) -> &'w mut Writes {
        writes.get_or_insert_named(name, buf, Writes::default)
    }
    for (i, entry_file) in files.iter().enumerate() {
        let file = FileId(i as u32);
        entry_file
            .tree
            .for_each_stmt(&mut |s: &Stmt<'_>| match &s.kind {
                StmtKind::Call { bind, call } => {
                    if let Some(b) = bind {
                        entry(&mut writes, &mut buf, b.text).by_command = true;
                    }
                    for arg in call.args.iter().flat_map(|a| a.items.iter()) {
                        if let crate::ast::Arg::Positional(Expr {
                            kind: ExprKind::Name(n),
                            ..
                        }) = arg
                        {
                            entry(&mut writes, &mut buf, n.text).by_command = true;
                        }
                    }
                }
                StmtKind::While { bind, .. } => {
                    any_loop = true;
                    if let Some(b) = bind {
                        entry(&mut writes, &mut buf, b.text).by_command = true;
                    }
                }
                StmtKind::Assign { target, value } => {
                    // `v = Skill` or `v = command` bound bare: a command's variable.
                    let bare = matches!(value.kind, ExprKind::Name(_));
                    let w = entry(&mut writes, &mut buf, target.text);
                    w.assigned.push((file, s.span));
                    w.by_command |= bare;
                }
                _ => {}
            });
    }
    any_loop.then_some(writes)
}

struct Walk<'a, 'd> {
    file: FileId,
    text: &'a str,
    writes: &'a FoldMap<Writes>,
    program: &'a starve::Program<'a>,
    /// The variables of the assignments issued, one after another, before the
    /// statement being looked at, each counted in its [`Writes::issued`].
    before: Vec<&'a Writes>,
    /// The names of the condition being looked at, reused from loop to loop.
    names: Vec<&'a str>,
    diags: &'d mut Kept,
}

impl<'a> Walk<'a, '_> {
    fn blocks(&mut self, blocks: &'a [Block<'a>]) {
        for block in blocks {
            let outer = self.before.len();
            for stmt in &block.stmts {
                match &stmt.kind {
                    StmtKind::Assign { target, .. } => {
                        let w = find(self.writes, target.text)
                            .expect("the table of writes holds every assignment");
                        w.issued.set(w.issued.get() + 1);
                        self.before.push(w);
                    }
                    StmtKind::If(c) => self.blocks(&c.body),
                    StmtKind::While { body, .. } => {
                        self.frozen(stmt, &body.cond);
                        starve::check(
                            self.program,
                            self.file,
                            self.text,
                            stmt,
                            &body.cond,
                            &body.body,
                            self.diags,
                        );
                        self.blocks(&body.body);
                    }
                    // Never runs.
                    StmtKind::Check { .. } => {}
                    _ => {}
                }
            }
            for w in self.before.drain(outer..) {
                w.issued.set(w.issued.get() - 1);
            }
        }
    }

    /// W0901 when no variable of the loop's condition can change while it runs.
    fn frozen(&mut self, stmt: &Stmt<'_>, cond: &'a Expr<'a>) {
        let mut names = std::mem::take(&mut self.names);
        names.clear();
        names_in(cond, &mut names);
        self.frozen_names(stmt, &names);
        self.names = names;
    }

    fn frozen_names(&mut self, stmt: &Stmt<'_>, names: &[&str]) {
        if names.is_empty() {
            return;
        }
        let mut set_before: Vec<&Writes> = Vec::new();
        let mut variables = Vec::new();
        for name in names {
            // Never written: a model constant, or an unbound name the checker reports
            // itself.
            let Some(w) = find(self.writes, name) else {
                continue;
            };
            variables.push(*name);
            // The walk issues only its own file's assignments, each once.
            let only_before = !w.by_command && w.issued.get() == w.assigned.len();
            if !only_before {
                return;
            }
            set_before.push(w);
        }
        if variables.is_empty() {
            return;
        }
        let mut listed: Vec<&str> = Vec::new();
        for n in &variables {
            if !listed.iter().any(|l| l.eq_ignore_ascii_case(n)) {
                listed.push(n);
            }
        }
        let quoted: Vec<String> = listed.iter().map(|n| format!("`{n}`")).collect();
        let what = quoted.join(", ");
        let d = Diagnostic::new(
            Code::FrozenLoop,
            self.file,
            stmt.span,
            format!(
                "`{}` never ends by itself: nothing changes {what} while it runs",
                stmt.span.slice(self.text)
            ),
        )
        .with_label(format!("{what} only set before the loop"))
        .with_help(format!(
            "change {what} in the loop's body (`{0} = {0} + 1`), or end the loop with `break`; otherwise only a line typed while the task runs could change it",
            listed[0]
        ));
        let d = d.with_places(
            set_before.iter().flat_map(|w| w.assigned.iter().copied()),
            set_before.iter().map(|w| w.assigned.len()).sum(),
            "set here, before the loop starts",
        );
        self.diags.push(d);
    }
}

pub(super) fn names_in<'s>(e: &Expr<'s>, out: &mut impl Extend<&'s str>) {
    match &e.kind {
        ExprKind::Name(n) => out.extend([n.text]),
        ExprKind::Neg(inner) => names_in(inner, out),
        ExprKind::Binary { lhs, rhs, .. } | ExprKind::Compare { lhs, rhs, .. } => {
            names_in(lhs, out);
            names_in(rhs, out);
        }
        ExprKind::Number(_) | ExprKind::Error => {}
    }
}

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
    Frozen::with_capacity(variables).finish(files, 0, skills, diags);
}

/// W0901 gathered as a streamed task's blocks come (`check/stream.rs`), then judged
/// with the whole program's writes: a loop's verdict needs the assignments after it
/// too, so each loop met is kept as its condition's names and how many assignments of
/// each its block issued before it, and judged in [`Frozen::finish`].
pub struct Frozen<'s> {
    writes: FoldMap<Writes>,
    any_loop: bool,
    buf: String,
    pending: Vec<Pending<'s>>,
}

struct Pending<'s> {
    file: FileId,
    stmt: Span,
    /// Each name of the condition, with the assignments of it issued before the loop.
    names: SmallVec<[(&'s str, usize); 2]>,
}

impl<'s> Frozen<'s> {
    pub fn with_capacity(variables: usize) -> Frozen<'s> {
        Frozen {
            writes: FoldMap::with_capacity(variables),
            any_loop: false,
            buf: String::new(),
            pending: Vec::new(),
        }
    }

    /// One top-level block of a streamed task file, the last time it is seen: its
    /// writes go into the table and its loops are kept for [`Frozen::finish`]. False
    /// when a loop of it may starve (W0902 needs the whole program's variables to say
    /// how): the caller checks the file as usual.
    pub fn block(&mut self, file: FileId, block: &Block<'s>, skills: &Skills) -> bool {
        let blocks = std::slice::from_ref(block);
        self.any_loop |= add_writes(&mut self.writes, &mut self.buf, file, blocks);
        let never = |_: &str| false;
        let program = starve::Program {
            skills,
            is_variable: &never,
        };
        let mut walk = Walk {
            file,
            text: "",
            writes: &self.writes,
            program: &program,
            before: Vec::new(),
            names: Vec::new(),
            diags: None,
            pending: Some(&mut self.pending),
            starves: false,
        };
        walk.blocks(blocks);
        !walk.starves
    }

    /// The writes of the files from `from` on, their loops, and the loops of the
    /// blocks streamed before: W0901 and W0902 said.
    pub fn finish(
        mut self,
        files: &[FileEntry<'_>],
        from: usize,
        skills: &Skills,
        diags: &mut Kept,
    ) {
        for (i, entry) in files.iter().enumerate().skip(from) {
            let file = FileId(i as u32);
            let tree = &entry.tree;
            self.any_loop |= add_writes(&mut self.writes, &mut self.buf, file, &tree.blocks);
            for skill in &tree.skills {
                self.any_loop |= add_writes(&mut self.writes, &mut self.buf, file, &skill.blocks);
            }
        }
        if !self.any_loop {
            return;
        }
        let writes = self.writes;
        let is_variable = |name: &str| find(&writes, name).is_some();
        let program = starve::Program {
            skills,
            is_variable: &is_variable,
        };
        for p in &self.pending {
            let text = files[p.file.0 as usize].text;
            frozen_names(
                &writes,
                p.file,
                text,
                p.stmt,
                p.names.iter().copied(),
                diags,
            );
        }
        // A library's skills are checked where they are called; their loops are the
        // library's business.
        for (i, entry) in files
            .iter()
            .enumerate()
            .skip(from)
            .filter(|(_, e)| !e.library)
        {
            let file = FileId(i as u32);
            let mut walk = Walk {
                file,
                text: entry.text,
                writes: &writes,
                program: &program,
                before: Vec::new(),
                names: Vec::new(),
                diags: Some(&mut *diags),
                pending: None,
                starves: false,
            };
            walk.blocks(&entry.tree.blocks);
            for skill in &entry.tree.skills {
                walk.blocks(&skill.blocks);
            }
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

/// Adds the writes of `blocks` to the table, keyed without a copy of each name: the
/// table is filled from every statement of the program, and most names are found in
/// it (a variable is bound, then named or assigned again). Returns whether there is a
/// loop among them, which is all the table is for.
fn add_writes(
    writes: &mut FoldMap<Writes>,
    buf: &mut String,
    file: FileId,
    blocks: &[Block<'_>],
) -> bool {
    let mut any_loop = false;
    fn entry<'w>(writes: &'w mut FoldMap<Writes>, buf: &mut String, name: &str) -> &'w mut Writes {
        writes.get_or_insert_named(name, buf, Writes::default)
    }
    crate::ast::for_each_stmt_in(blocks, &mut |s: &Stmt<'_>| match &s.kind {
        StmtKind::Call { bind, call } => {
            if let Some(b) = bind {
                entry(writes, buf, b.text).by_command = true;
            }
            for arg in call.args.iter().flat_map(|a| a.items.iter()) {
                if let crate::ast::Arg::Positional(Expr {
                    kind: ExprKind::Name(n),
                    ..
                }) = arg
                {
                    entry(writes, buf, n.text).by_command = true;
                }
            }
        }
        StmtKind::While { bind, .. } => {
            any_loop = true;
            if let Some(b) = bind {
                entry(writes, buf, b.text).by_command = true;
            }
        }
        StmtKind::Assign { target, value } => {
            // `v = Skill` or `v = command` bound bare: a command's variable.
            let bare = matches!(value.kind, ExprKind::Name(_));
            let w = entry(writes, buf, target.text);
            w.assigned.push((file, s.span));
            w.by_command |= bare;
        }
        _ => {}
    });
    any_loop
}

struct Walk<'a, 's, 'd> {
    file: FileId,
    text: &'a str,
    writes: &'a FoldMap<Writes>,
    program: &'a starve::Program<'a>,
    /// The variables of the assignments issued, one after another, before the
    /// statement being looked at, each counted in its [`Writes::issued`].
    before: Vec<&'a Writes>,
    /// The names of the condition being looked at, reused from loop to loop.
    names: Vec<&'s str>,
    /// Where verdicts go; `None` while the program is streamed, when loops are kept
    /// in `pending` to be judged once every write is known.
    diags: Option<&'d mut Kept>,
    pending: Option<&'d mut Vec<Pending<'s>>>,
    /// A loop was met that may starve (W0902), which a streamed check cannot judge.
    starves: bool,
}

impl<'a, 's> Walk<'a, 's, '_> {
    fn blocks(&mut self, blocks: &[Block<'s>]) {
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
                        match self.diags.as_deref_mut() {
                            Some(diags) => starve::check(
                                self.program,
                                self.file,
                                self.text,
                                stmt,
                                &body.cond,
                                &body.body,
                                diags,
                            ),
                            None => {
                                self.starves |=
                                    starve::may_starve(self.program.skills, &body.cond, &body.body)
                            }
                        }
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
    fn frozen(&mut self, stmt: &Stmt<'_>, cond: &Expr<'s>) {
        let mut names = std::mem::take(&mut self.names);
        names.clear();
        names_in(cond, &mut names);
        let issued = |name: &str| find(self.writes, name).map_or(0, |w| w.issued.get());
        if let Some(pending) = self.pending.as_deref_mut() {
            if !names.is_empty() {
                pending.push(Pending {
                    file: self.file,
                    stmt: stmt.span,
                    names: names.iter().map(|n| (*n, issued(n))).collect(),
                });
            }
        } else if let Some(diags) = self.diags.as_deref_mut() {
            let named = names.iter().map(|n| (*n, issued(n)));
            frozen_names(self.writes, self.file, self.text, stmt.span, named, diags);
        }
        self.names = names;
    }
}

/// W0901 for the loop at `stmt` when no name of its condition can change while it
/// runs: each was written only by the assignments issued before it (`issued` of each).
fn frozen_names<'n>(
    writes: &FoldMap<Writes>,
    file: FileId,
    text: &str,
    stmt: Span,
    names: impl Iterator<Item = (&'n str, usize)>,
    diags: &mut Kept,
) {
    let mut set_before: Vec<&Writes> = Vec::new();
    let mut variables = Vec::new();
    for (name, issued) in names {
        // Never written: a model constant, or an unbound name the checker reports
        // itself.
        let Some(w) = find(writes, name) else {
            continue;
        };
        variables.push(name);
        // The walk issues only its own file's assignments, each once.
        let only_before = !w.by_command && issued == w.assigned.len();
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
        file,
        stmt,
        format!(
            "`{}` never ends by itself: nothing changes {what} while it runs",
            stmt.slice(text)
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
    diags.push(d);
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

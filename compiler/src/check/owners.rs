//! Actuators set by two blocks in one tick (W0905). `speed`, `bodypose`, `stop` and
//! `cont`, and `actuator` (per device) act the instant they are issued and outside the
//! movement queue (the catalogue's `Sets`), and the robot keeps the last value set.
//! Two statements of one block are issued in the order written; but when two blocks
//! that run at the same time set the same thing in the same tick, the robot keeps
//! whichever the VM happens to issue last, and nothing at run time says so.
//!
//! When a statement is issued is read from the text as a chain of what its block
//! waited for since its unit started: a task's top-level blocks (and a skill's blocks,
//! and the blocks of one `if` or `while` body) start together; a block goes on in the
//! same tick until a `wait`, an `init`, or a call of a skill whose first block holds
//! (the call holds the caller until that block has issued its last statement).
//! `wait(v)` is woken in one tick for every block that waits on `v`; `wait(2)` from
//! one tick ends in one tick; anything else (an `init`, a holding skill call, a guard's
//! or a loop's body) is a moment of its own. Two statements with the same chain are
//! issued in the same tick. Only the last setting of each block in that tick
//! matters, so a conflict is two blocks whose last settings of one thing in one tick
//! differ. Statements are grouped by what they set and when, so the check is linear
//! in the statements plus a sort of the settings, never a comparison of every pair.
//!
//! A skill call brings the settings its skill makes when it starts (the first block
//! in line, in the caller's block; the others as blocks of their own), reported at
//! the call.

use std::rc::Rc;

use ilmr_model::RobotModel;
use ilmr_stdlib::{Command, Sets};
use rustc_hash::FxHashMap;

use crate::ast::{Arg, Args, Block, Call, Expr, ExprKind, Stmt, StmtKind};
use crate::check::FileEntry;
use crate::check::skills::{SkillId, Skills};
use crate::diagnostic::{Code, Diagnostic, FileId};
use crate::span::Span;

/// A skill's settings at its start beyond this many are not followed into its callers
/// (nested skills could multiply them); the skill's own blocks are still checked.
const SKILL_SETTINGS_KEPT: usize = 256;

/// Other blocks named in one warning beyond the one it is said at.
const SECONDARY_SHOWN: usize = 3;

/// One step of the chain that says when a statement is issued.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
enum Step {
    /// A task file's top-level blocks, or a skill's blocks, starting.
    Unit(u32, u32),
    /// A `wait(v)`: every block waiting on `v` wakes in one tick.
    Woken(u32),
    /// A `wait(seconds)` of a number written out.
    Delay(u64),
    /// A moment of its own: after an `init` or a holding skill call, a guard's or a
    /// loop's body (the file and the statement's start).
    Own(u32, u32),
}

/// A setting a skill makes when it starts, relative to a call of it.
#[derive(Debug, Clone)]
struct SkillSet {
    target: u32,
    value: u32,
    /// 0: the first block, which runs in the caller's block; others: blocks of their
    /// own, numbered within the skill's expansion.
    strand: u32,
    /// The statement inside the skill, for the message.
    file: FileId,
    span: Span,
}

#[derive(Debug, Clone, Copy)]
struct Record {
    target: u32,
    key: u32,
    strand: u32,
    value: u32,
    file: FileId,
    span: Span,
    /// The skill statement behind a call's record, or the record's own.
    via: (FileId, Span),
    /// The call expansion it came from (0: written in the unit itself).
    origin: u32,
    order: u32,
}

struct Owners<'a, 's> {
    files: &'a [FileEntry<'s>],
    skills: &'a Skills,
    model: &'a RobotModel,
    keys: FxHashMap<(u32, Step), u32>,
    words: FxHashMap<String, u32>,
    /// What each target id is called in messages.
    targets: Vec<String>,
    records: Vec<Record>,
    strands: u32,
    origins: u32,
    /// Per skill: whether a call of it holds its caller, and its settings at start.
    holds: FxHashMap<u32, bool>,
    starts: FxHashMap<u32, Rc<Vec<SkillSet>>>,
    buf: String,
}

pub fn check_owners(
    files: &[FileEntry<'_>],
    skills: &Skills,
    model: &RobotModel,
    diags: &mut Vec<Diagnostic>,
) {
    let mut o = Owners {
        files,
        skills,
        model,
        keys: FxHashMap::default(),
        words: FxHashMap::default(),
        targets: Vec::new(),
        records: Vec::new(),
        strands: 0,
        origins: 0,
        holds: FxHashMap::default(),
        starts: FxHashMap::default(),
        buf: String::new(),
    };
    for (i, entry) in files.iter().enumerate() {
        if entry.library {
            continue;
        }
        let file = FileId(i as u32);
        let key = o.key(0, Step::Unit(file.0, 0));
        o.blocks(file, &entry.tree.blocks, key);
        for (s, skill) in entry.tree.skills.iter().enumerate() {
            let key = o.key(0, Step::Unit(file.0, s as u32 + 1));
            o.blocks(file, &skill.blocks, key);
        }
    }
    o.report(diags);
}

impl<'s> Owners<'_, 's> {
    fn key(&mut self, parent: u32, step: Step) -> u32 {
        let next = self.keys.len() as u32 + 1;
        *self.keys.entry((parent, step)).or_insert(next)
    }

    /// An id for a word or a value's text, the same for any letter case.
    fn word(&mut self, text: &str) -> u32 {
        self.buf.clear();
        self.buf.extend(text.chars().flat_map(char::to_lowercase));
        if let Some(&id) = self.words.get(self.buf.as_str()) {
            return id;
        }
        let id = self.words.len() as u32;
        self.words.insert(self.buf.clone(), id);
        id
    }

    fn strand(&mut self) -> u32 {
        self.strands += 1;
        self.strands
    }

    /// Sibling blocks: each its own strand, all starting at `key`.
    fn blocks(&mut self, file: FileId, blocks: &[Block<'_>], key: u32) {
        for block in blocks {
            let strand = self.strand();
            self.block(file, block, key, strand);
        }
    }

    fn block(&mut self, file: FileId, block: &Block<'_>, mut key: u32, strand: u32) {
        for stmt in &block.stmts {
            key = self.stmt(file, stmt, key, strand);
        }
    }

    /// Records what `stmt` sets and returns when the next statement of its block is
    /// issued.
    fn stmt(&mut self, file: FileId, stmt: &Stmt<'_>, key: u32, strand: u32) -> u32 {
        let own = |o: &mut Self| o.key(key, Step::Own(file.0, stmt.span.start));
        match &stmt.kind {
            StmtKind::Call { call, .. } => self.call(file, stmt.span, call, key, strand),
            StmtKind::Assign { value, .. } => match &value.kind {
                // `v = name`: a bare command or a skill call, or a copy.
                ExprKind::Name(n) => {
                    let call = Call {
                        name: *n,
                        args: None,
                    };
                    self.call(file, stmt.span, &call, key, strand)
                }
                _ => key,
            },
            StmtKind::If(c) => {
                let body = own(self);
                self.blocks(file, &c.body, body);
                key
            }
            StmtKind::While { body, .. } => {
                let at = own(self);
                self.blocks(file, &body.body, at);
                key
            }
            StmtKind::Check { .. }
            | StmtKind::Break { .. }
            | StmtKind::Priority
            | StmtKind::Error => key,
        }
    }

    fn call(&mut self, file: FileId, at: Span, call: &Call<'_>, key: u32, strand: u32) -> u32 {
        if let Some(command) = Command::from_name(call.name.text) {
            let spec = command.spec();
            if let Some((target, value)) = self.setting(file, command, call.args.as_ref()) {
                let order = self.records.len() as u32;
                self.records.push(Record {
                    target,
                    key,
                    strand,
                    value,
                    file,
                    span: at,
                    via: (file, at),
                    origin: 0,
                    order,
                });
            }
            if !spec.holds_block {
                return key;
            }
            let waited = call.args.as_ref().and_then(|a| match a.items.first() {
                Some(Arg::Positional(e)) if a.items.len() == 1 => Some(e),
                _ => None,
            });
            let step = match (command, waited.map(|e| &e.kind)) {
                (Command::Wait, Some(ExprKind::Name(n))) => Step::Woken(self.word(n.text)),
                (Command::Wait, Some(ExprKind::Number(s))) => Step::Delay(s.to_bits()),
                _ => Step::Own(file.0, at.start),
            };
            return self.key(key, step);
        }
        let Some(id) = self.skills.find(call.name.text) else {
            return key;
        };
        let sets = self.skill_start(id, &mut Vec::new());
        if !sets.is_empty() {
            self.origins += 1;
            let origin = self.origins;
            let mut fresh = FxHashMap::default();
            for s in sets.iter() {
                let strand = if s.strand == 0 {
                    strand
                } else {
                    *fresh.entry(s.strand).or_insert_with(|| {
                        self.strands += 1;
                        self.strands
                    })
                };
                let order = self.records.len() as u32;
                self.records.push(Record {
                    target: s.target,
                    key,
                    strand,
                    value: s.value,
                    file,
                    span: at,
                    via: (s.file, s.span),
                    origin,
                    order,
                });
            }
        }
        if self.skill_holds(id, &mut Vec::new()) {
            self.key(key, Step::Own(file.0, at.start))
        } else {
            key
        }
    }

    /// What a statement of `command` sets, and a value that is equal for statements
    /// that set the same: the target's id and the value's.
    fn setting(
        &mut self,
        file: FileId,
        command: Command,
        args: Option<&Args<'_>>,
    ) -> Option<(u32, u32)> {
        let items: &[Arg<'_>] = args.map_or(&[], |a| &a.items);
        let words = items.iter().filter_map(|a| match a {
            Arg::Positional(Expr {
                kind: ExprKind::Name(n),
                ..
            }) => Some(n.text),
            _ => None,
        });
        let (target, rest) = match command.spec().sets.applies(words) {
            Sets::Nothing => return None,
            Sets::Setting { what, .. } => (what.to_string(), items),
            Sets::Device => {
                let Some(Arg::Positional(first)) = items.first() else {
                    return None;
                };
                let text = self.files[file.0 as usize].text;
                let device = match &first.kind {
                    ExprKind::Name(n) => self.model.device(n.text).map(|d| d.name.clone()),
                    ExprKind::Number(n) => {
                        self.model.device_by_id(*n as i64).map(|d| d.name.clone())
                    }
                    _ => None,
                }
                .unwrap_or_else(|| first.span.slice(text).trim().to_string());
                (format!("actuator `{device}`"), &items[1..])
            }
        };
        let mut value = String::from(command.name());
        let mut settings: Vec<String> = Vec::new();
        for a in rest {
            match a {
                Arg::Positional(e) => {
                    value.push(',');
                    canonical(e, &mut value);
                }
                Arg::Setting { key, value: e } => {
                    let mut s = key.text.to_lowercase();
                    s.push('=');
                    canonical(e, &mut s);
                    settings.push(s);
                }
            }
        }
        // Settings may come in any order.
        settings.sort();
        for s in settings {
            value.push(',');
            value.push_str(&s);
        }
        let target = {
            let id = self.word(&target);
            if id as usize >= self.targets.len() {
                self.targets.resize(id as usize + 1, String::new());
            }
            if self.targets[id as usize].is_empty() {
                self.targets[id as usize] = target;
            }
            id
        };
        Some((target, self.word(&value)))
    }

    /// Whether a call of the skill holds its caller: its first block waits (a `wait`,
    /// an `init` or a call that holds) before it has issued its last statement.
    fn skill_holds(&mut self, id: SkillId, open: &mut Vec<u32>) -> bool {
        if let Some(&h) = self.holds.get(&id.0) {
            return h;
        }
        if open.contains(&id.0) || open.len() >= max_call_depth() {
            // Recursion (E0601) or a chain the VM refuses (E0603): say it holds,
            // which warns of less.
            return true;
        }
        open.push(id.0);
        let info = self.skills.get(id);
        let files = self.files;
        let blocks = &files[info.file.0 as usize].tree.skills[info.index].blocks;
        let mut holds = false;
        for stmt in blocks.first().map_or(&[][..], |b| &b.stmts) {
            let name = match &stmt.kind {
                StmtKind::Call { call, .. } => call.name.text,
                StmtKind::Assign { value, .. } => match &value.kind {
                    ExprKind::Name(n) => n.text,
                    _ => continue,
                },
                _ => continue,
            };
            holds = match Command::from_name(name) {
                Some(c) => c.spec().holds_block,
                None => self
                    .skills
                    .find(name)
                    .is_some_and(|inner| self.skill_holds(inner, open)),
            };
            if holds {
                break;
            }
        }
        open.pop();
        self.holds.insert(id.0, holds);
        holds
    }

    /// The settings a skill makes in the tick it is called: the statements of each of
    /// its blocks up to the first that holds, through the skills they call.
    fn skill_start(&mut self, id: SkillId, open: &mut Vec<u32>) -> Rc<Vec<SkillSet>> {
        if let Some(s) = self.starts.get(&id.0) {
            return s.clone();
        }
        if open.contains(&id.0) || open.len() >= max_call_depth() {
            return Rc::default();
        }
        open.push(id.0);
        let info = self.skills.get(id);
        let file = info.file;
        let files = self.files;
        let blocks = &files[file.0 as usize].tree.skills[info.index].blocks;
        let mut out: Vec<SkillSet> = Vec::new();
        let mut strands = 0u32;
        for (b, block) in blocks.iter().enumerate() {
            let strand = if b == 0 {
                0
            } else {
                strands += 1;
                strands
            };
            for stmt in &block.stmts {
                let (name, args) = match &stmt.kind {
                    StmtKind::Call { call, .. } => (call.name.text, call.args.as_ref()),
                    StmtKind::Assign { value, .. } => match &value.kind {
                        ExprKind::Name(n) => (n.text, None),
                        _ => continue,
                    },
                    // Guards and loops run their bodies later; they do not hold.
                    _ => continue,
                };
                let span = stmt.span;
                if let Some(command) = Command::from_name(name) {
                    if let Some((target, value)) = self.setting(file, command, args) {
                        out.push(SkillSet {
                            target,
                            value,
                            strand,
                            file,
                            span,
                        });
                    }
                    if command.spec().holds_block {
                        break;
                    }
                    continue;
                }
                let Some(inner) = self.skills.find(name) else {
                    continue;
                };
                let nested = self.skill_start(inner, open);
                let mut fresh = FxHashMap::default();
                for s in nested.iter() {
                    let strand = if s.strand == 0 {
                        strand
                    } else {
                        *fresh.entry(s.strand).or_insert_with(|| {
                            strands += 1;
                            strands
                        })
                    };
                    out.push(SkillSet {
                        strand,
                        ..s.clone()
                    });
                }
                if self.skill_holds(inner, open) {
                    break;
                }
            }
        }
        // Only the last setting of a block in the tick is seen by the others.
        let mut seen = FxHashMap::default();
        for (i, s) in out.iter().enumerate() {
            seen.insert((s.target, s.strand), i);
        }
        let mut kept: Vec<usize> = seen.into_values().collect();
        kept.sort_unstable();
        kept.truncate(SKILL_SETTINGS_KEPT);
        let out = Rc::new(kept.into_iter().map(|i| out[i].clone()).collect::<Vec<_>>());
        open.pop();
        self.starts.insert(id.0, out.clone());
        out
    }

    fn report(&mut self, diags: &mut Vec<Diagnostic>) {
        let mut records = std::mem::take(&mut self.records);
        records.sort_unstable_by_key(|r| (r.target, r.key, r.strand, r.order));
        // The last setting of each block in each tick.
        let mut last: Vec<Record> = Vec::new();
        for r in records {
            match last.last_mut() {
                Some(l) if (l.target, l.key, l.strand) == (r.target, r.key, r.strand) => *l = r,
                _ => last.push(r),
            }
        }
        for group in last.chunk_by(|a, b| (a.target, a.key) == (b.target, b.key)) {
            if group.len() < 2 || group.iter().all(|r| r.value == group[0].value) {
                continue;
            }
            // A skill's own blocks are reported in the skill, not at each call.
            if group[0].origin != 0 && group.iter().all(|r| r.origin == group[0].origin) {
                continue;
            }
            let primary = group.iter().max_by_key(|r| r.order).copied().unwrap();
            let others: Vec<&Record> = group.iter().filter(|r| r.value != primary.value).collect();
            diags.push(self.diagnostic(&primary, &others));
        }
    }

    fn statement(&self, (file, span): (FileId, Span)) -> &str {
        let text = span.slice(self.files[file.0 as usize].text);
        text.lines().next().unwrap_or("").trim()
    }

    fn diagnostic(&self, primary: &Record, others: &[&Record]) -> Diagnostic {
        let what = &self.targets[primary.target as usize];
        let shown = |r: &Record| {
            let own = self.statement(r.via);
            if r.origin == 0 {
                format!("`{own}`")
            } else {
                format!("`{}` (through `{own}`)", self.statement((r.file, r.span)))
            }
        };
        let mut d = Diagnostic::new(
            Code::SettingRace,
            primary.file,
            primary.span,
            format!(
                "{} and {} set the robot's {what} in the same tick from blocks that run at the same time",
                shown(primary),
                shown(others[0]),
            ),
        )
        .with_label(if primary.origin == 0 {
            format!("sets {what}")
        } else {
            format!("sets {what} through the skill: `{}`", self.statement(primary.via))
        });
        for r in others.iter().take(SECONDARY_SHOWN) {
            let label = if r.origin == 0 {
                format!("also sets {what} in that tick, to another value")
            } else {
                format!(
                    "also sets {what} in that tick, through the skill: `{}`",
                    self.statement(r.via)
                )
            };
            d = d.with_secondary(r.file, r.span, label);
        }
        let more = others.len().saturating_sub(SECONDARY_SHOWN);
        let more = if more > 0 {
            format!(" ({more} more blocks set it in that tick too)")
        } else {
            String::new()
        };
        d.with_help(format!(
            "the robot keeps whichever the VM issues last, which the order of the blocks decides, not the text{more}; set it in one block, in the order meant, or hold one of them (`wait(v)`) until the other's moment has passed"
        ))
    }
}

/// The VM's skill call depth: deeper chains are refused (E0603), and following them
/// would recurse as deep as they go.
fn max_call_depth() -> usize {
    usize::from(ilmr_vm::Config::default().max_call_depth)
}

/// A value's text with numbers folded (`0.2*2` and `.4` are `0.4`) and names as
/// written (the caller ignores case).
fn canonical(e: &Expr<'_>, out: &mut String) {
    if let Some(v) = number(e) {
        use std::fmt::Write;
        let _ = write!(out, "{v}");
        return;
    }
    match &e.kind {
        ExprKind::Number(n) => out.push_str(&n.to_string()),
        ExprKind::Name(n) => out.push_str(n.text),
        ExprKind::Neg(inner) => {
            out.push_str("-(");
            canonical(inner, out);
            out.push(')');
        }
        ExprKind::Binary { op, lhs, rhs } => {
            out.push('(');
            canonical(lhs, out);
            out.push_str(op.symbol());
            canonical(rhs, out);
            out.push(')');
        }
        ExprKind::Compare { op, lhs, rhs, .. } => {
            canonical(lhs, out);
            out.push_str(op.symbol());
            canonical(rhs, out);
        }
        ExprKind::Error => out.push('?'),
    }
}

/// The value of an expression of numbers alone.
fn number(e: &Expr<'_>) -> Option<f64> {
    match &e.kind {
        ExprKind::Number(n) => Some(*n),
        ExprKind::Neg(inner) => number(inner).map(|v| -v),
        ExprKind::Binary { op, lhs, rhs } => {
            let (a, b) = (number(lhs)?, number(rhs)?);
            match op {
                crate::ast::BinOp::Add => Some(a + b),
                crate::ast::BinOp::Sub => Some(a - b),
                crate::ast::BinOp::Mul => Some(a * b),
                crate::ast::BinOp::Div => (b != 0.0).then(|| a / b),
            }
        }
        _ => None,
    }
}

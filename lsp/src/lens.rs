//! The concurrency lens: inlay hints that say, per statement, when it is issued relative
//! to the others ("starts at t=0 with block 2", "held until `wait(t1)` at line 8",
//! "guard: runs once when d>10", "queued after line 12 (movement)") and which
//! `break(pattern)` can end it. When a statement starts is the compiler's own model of
//! the schedule (`check::schedule`, the walk of the W0905 check); which statements a
//! pattern ends is the checker's own matching (`check::breakable`, `check::matches`).
//!
//! Only the statements in the range the client shows are labelled, found by skipping
//! the blocks outside it. The program's break patterns are searched for all at once in
//! each statement's text (the checker's automaton, `check::Needles`), so a request costs
//! the visible statements' text plus the breaks it names, and the file's schedule and
//! the program's breaks once per check (cached by the engine). A label names a few of
//! the breaks and priority blocks that end a statement and counts the rest: a program
//! of 2,000 `break(w)` lines made 120 MB of labels when each named all of them.

use ilmr_compiler::Span;
use ilmr_compiler::ast::{Block, Stmt, StmtKind};
use ilmr_compiler::check::schedule::{Moment, Start};
use ilmr_compiler::check::{Needles, breakable, matches, needle};
use ilmr_compiler::diagnostic::FileId;

use crate::analysis::Program;
use crate::in_view::statements_reaching;
use crate::line_index::LineIndex;

/// A quoted statement in a label is cut to this many characters.
const QUOTED_CHARS: usize = 32;

/// Top-level blocks named one by one in "starts at t=0 with blocks 2, 3"; more are
/// counted.
const BLOCKS_NAMED: u32 = 3;

/// Bare breaks named one by one in "ended by break at line 9, line 20"; more are
/// counted.
const BREAKS_NAMED: usize = 2;

/// Pattern breaks and priority blocks that end a statement named one by one, each kind;
/// more are counted.
const ENDERS_NAMED: usize = 3;

/// Statements a break's hover lists; more are counted.
pub const ENDED_LISTED: usize = 20;

/// What ends statements that are running when it is issued.
#[derive(Debug, Clone)]
pub enum Ender {
    /// `break(pattern)`, with its needle (`check::needle`): the statements whose text
    /// contains it, and what stands inside a matched `if` or `while`.
    Pattern(String),
    /// A bare `break`: every command of the program.
    All,
    /// `priority = highest`, first in a block: when the block starts, every command
    /// that is neither inside the block nor an `if`, `while` or skill call around it.
    /// The lens names it at the statements of its own unit only: whether a statement
    /// of another unit stands inside the block (a skill called from it) or around it
    /// (the call that runs the block's skill) the text alone does not say.
    Priority {
        /// The task's blocks (`None`) or the skill (its index in the file).
        unit: Option<usize>,
        /// The block it opens.
        block: Span,
        /// The `if`s and `while`s the block stands in, which it does not end.
        around: Vec<Span>,
    },
}

/// A `break`, `break(pattern)` or `priority = highest` of the program.
#[derive(Debug, Clone)]
pub struct BreakAt {
    pub file: FileId,
    pub span: Span,
    pub ender: Ender,
}

/// The program's breaks, sorted by what they end.
pub struct Breaks {
    /// In the order of the files and their text.
    pub all: Vec<BreakAt>,
    /// The distinct needles of the pattern breaks.
    needles: Needles,
    /// For each distinct needle, the pattern breaks that have it (indices in `all`, in
    /// order).
    with_needle: Vec<Vec<u32>>,
    /// The priority blocks and the bare breaks (indices in `all`, in order).
    priorities: Vec<u32>,
    bare: Vec<u32>,
}

/// Every `break`, `break(pattern)` and `priority = highest` in the program's files that
/// an editor can open, leaving out what stands between `check` and `checkend` (which
/// never runs).
pub fn breaks(program: &Program) -> Breaks {
    let all = all_breaks(program);
    let mut patterns = Vec::new();
    let mut priorities = Vec::new();
    let mut bare = Vec::new();
    for (i, b) in all.iter().enumerate() {
        match &b.ender {
            Ender::Pattern(needle) => patterns.push((i as u32, needle.as_str())),
            Ender::Priority { .. } => priorities.push(i as u32),
            Ender::All => bare.push(i as u32),
        }
    }
    let needles = Needles::new(
        patterns.iter().map(|&(_, needle)| needle),
        ilmr_compiler::limits::PATTERN_MATCHES,
    );
    let mut with_needle = vec![Vec::new(); needles.distinct()];
    for (k, &(i, _)) in patterns.iter().enumerate() {
        if let Some(id) = needles.id(k) {
            with_needle[id as usize].push(i);
        }
    }
    Breaks {
        all,
        needles,
        with_needle,
        priorities,
        bare,
    }
}

fn all_breaks(program: &Program) -> Vec<BreakAt> {
    let mut out = Vec::new();
    for i in 0..program.analysis().files.len() {
        let file = FileId(i as u32);
        if program.uri(file).is_none() {
            continue;
        }
        let tree = program.tree(file);
        let mut around = Vec::new();
        enders(file, None, &tree.blocks, &mut around, &mut out);
        for (s, skill) in tree.skills.iter().enumerate() {
            enders(file, Some(s), &skill.blocks, &mut around, &mut out);
        }
    }
    out
}

fn enders(
    file: FileId,
    unit: Option<usize>,
    blocks: &[Block<'_>],
    around: &mut Vec<Span>,
    out: &mut Vec<BreakAt>,
) {
    for block in blocks {
        for stmt in &block.stmts {
            let ender = match &stmt.kind {
                StmtKind::Break { pattern: Some(p) } => Ender::Pattern(needle(p).to_string()),
                StmtKind::Break { pattern: None } => Ender::All,
                StmtKind::Priority => Ender::Priority {
                    unit,
                    block: block.span,
                    around: around.clone(),
                },
                StmtKind::If(c) | StmtKind::While { body: c, .. } => {
                    around.push(stmt.span);
                    enders(file, unit, &c.body, around, out);
                    around.pop();
                    continue;
                }
                _ => continue,
            };
            out.push(BreakAt {
                file,
                span: stmt.span,
                ender,
            });
        }
    }
}

/// One statement's label, at the end of its line.
#[derive(Debug, Clone, PartialEq)]
pub struct Label {
    pub at: usize,
    pub text: String,
    pub tooltip: String,
}

/// What the lens needs of one open file.
pub struct FileLens<'a> {
    pub program: &'a Program,
    pub file: FileId,
    pub text: &'a str,
    pub index: &'a LineIndex,
    /// The file's schedule, sorted by position (`check::schedule`).
    pub moments: &'a [Moment],
    pub breaks: &'a Breaks,
}

/// An `if` or `while` around the statements being labelled, with the distinct needles
/// its line contains (`None`: not searched, past the matches' limit).
struct Around {
    span: Span,
    needles: Option<Vec<u32>>,
}

/// Where a statement's text or an `if`/`while` around it contains a break's needle.
#[derive(Clone, Copy)]
enum Through {
    Itself,
    Around(Span),
}

impl FileLens<'_> {
    /// Labels of the statements that start inside `range`, in order.
    pub fn labels(&self, range: Span) -> Vec<Label> {
        self.breaks.needles.refill();
        let tree = self.program.tree(self.file);
        let mut out = Vec::new();
        let mut around = Vec::new();
        self.blocks(&tree.blocks, None, range, &mut around, &mut out);
        for (s, skill) in tree.skills.iter().enumerate() {
            if overlaps(skill.span, range) {
                self.blocks(&skill.blocks, Some(s), range, &mut around, &mut out);
            }
        }
        out
    }

    fn blocks<'t>(
        &self,
        blocks: &'t [Block<'t>],
        unit: Option<usize>,
        range: Span,
        around: &mut Vec<Around>,
        out: &mut Vec<Label>,
    ) {
        for stmt in statements_reaching(blocks, range) {
            if stmt.span.start >= range.start {
                self.label(stmt, unit, around, out);
            }
            match &stmt.kind {
                StmtKind::If(c) | StmtKind::While { body: c, .. } => {
                    let mut needles = Vec::new();
                    let searched = self.breaks.needles.each_in(
                        stmt.span.slice(self.text),
                        &mut Vec::new(),
                        |id| needles.push(id),
                    );
                    around.push(Around {
                        span: stmt.span,
                        needles: searched.map(|()| needles),
                    });
                    self.blocks(&c.body, unit, range, around, out);
                    around.pop();
                }
                // Never runs: nothing to say of when.
                StmtKind::Check { .. } => {}
                _ => {}
            }
        }
    }

    fn label(&self, stmt: &Stmt<'_>, unit: Option<usize>, around: &[Around], out: &mut Vec<Label>) {
        let mut parts = Vec::new();
        let mut tips = Vec::new();
        if let Some(m) = self.moment(stmt.span) {
            if m.first {
                let (part, tip) = self.start(&m.start);
                parts.push(part);
                tips.push(tip);
            }
            if let Some(q) = m.queued_after {
                parts.push(format!("queued after line {} (movement)", self.line(q)));
                tips.push(format!(
                    "A movement command: it starts when `{}` (line {}), queued before it in its block, has given up the movement reservation.",
                    self.quote(q),
                    self.line(q)
                ));
            }
        }
        if !matches!(stmt.kind, StmtKind::Break { .. } | StmtKind::Priority) {
            self.enders(stmt, unit, around, &mut parts, &mut tips);
        }
        if !parts.is_empty() {
            out.push(Label {
                at: stmt.span.end as usize,
                text: parts.join(" · "),
                tooltip: tips.join("\n\n"),
            });
        }
    }

    /// What ends `stmt` if it is running then: the breaks whose pattern it (or an `if`
    /// or `while` around it) contains, the program's bare breaks, and the priority
    /// blocks of its unit that it stands outside of. The first few of each kind are
    /// named in the program's order, the rest counted.
    fn enders(
        &self,
        stmt: &Stmt<'_>,
        unit: Option<usize>,
        around: &[Around],
        parts: &mut Vec<String>,
        tips: &mut Vec<String>,
    ) {
        let breaks = self.breaks;
        let mut named: Vec<(u32, Option<Through>)> = Vec::new();
        let mut priorities_more = 0usize;
        for &i in &breaks.priorities {
            let b = &breaks.all[i as usize];
            let Ender::Priority {
                unit: u,
                block,
                around: holders,
            } = &b.ender
            else {
                continue;
            };
            let inside = block.start <= stmt.span.start && stmt.span.end <= block.end;
            if b.file != self.file || *u != unit || inside || holders.contains(&stmt.span) {
                continue;
            }
            if named.len() < ENDERS_NAMED {
                named.push((i, None));
            } else {
                priorities_more += 1;
            }
        }
        let (patterns, patterns_more, searched) = self.pattern_enders(stmt, around);
        named.extend(patterns.into_iter().map(|(i, through)| (i, Some(through))));
        named.sort_unstable_by_key(|&(i, _)| i);
        for (i, through) in named {
            let b = &breaks.all[i as usize];
            let at = self.place(b.file, b.span);
            let Some(through) = through else {
                let line = self.line(b.span);
                parts.push(format!(
                    "ended when the priority block at line {line} starts"
                ));
                tips.push(format!(
                    "The block at line {line} starts with `priority = highest`: when it starts, it ends every running command that is neither inside it nor an `if`, a `while` or a skill call around it, and runs alone."
                ));
                continue;
            };
            let Ender::Pattern(needle) = &b.ender else {
                continue;
            };
            parts.push(format!("ended by break at {at}"));
            tips.push(match through {
                Through::Itself => format!(
                    "`{}` at {at} ends it if it is running then: its text contains `{needle}`.",
                    self.program_quote(b.file, b.span),
                ),
                Through::Around(s) => format!(
                    "`{}` at {at} ends `{}` (line {}) and so everything inside it.",
                    self.program_quote(b.file, b.span),
                    self.quote(s),
                    self.line(s)
                ),
            });
        }
        if patterns_more > 0 {
            parts.push(format!("and by {}", counted(patterns_more, "more break")));
            tips.push(format!(
                "{patterns_more} more `break(pattern)` statements end it, or an `if` or `while` around it, if it is running then; hover on a break to see all it ends."
            ));
        }
        if priorities_more > 0 {
            parts.push(format!(
                "and by {}",
                counted(priorities_more, "more priority block")
            ));
            tips.push(format!(
                "{priorities_more} more blocks that start with `priority = highest` end it when they start, if it is running then."
            ));
        }
        if !searched {
            parts.push("break patterns not all searched".to_string());
            tips.push(format!(
                "The program's break patterns occur in its text more than {} times; this request stopped searching for them, so a `break(pattern)` not named here may end it too.",
                ilmr_compiler::limits::PATTERN_MATCHES
            ));
        }
        if let Some(&first) = breaks.bare.first() {
            let named: Vec<String> = (breaks.bare.iter().take(BREAKS_NAMED))
                .map(|&i| {
                    let b = &breaks.all[i as usize];
                    self.place(b.file, b.span)
                })
                .collect();
            let more = breaks.bare.len().saturating_sub(BREAKS_NAMED);
            let more = if more > 0 {
                format!(" and {more} more")
            } else {
                String::new()
            };
            parts.push(format!("ended by break at {}{more}", named.join(", ")));
            let first = &breaks.all[first as usize];
            tips.push(format!(
                "A bare `break` (the first at {}) stops the robot and ends every command of the program: this one too, if it is running then.",
                self.place(first.file, first.span)
            ));
        }
    }

    /// The first [`ENDERS_NAMED`] pattern breaks (in the program's order) that end
    /// `stmt` and how, how many more do, and whether every needle was searched for.
    fn pattern_enders(
        &self,
        stmt: &Stmt<'_>,
        around: &[Around],
    ) -> (Vec<(u32, Through)>, usize, bool) {
        let breaks = self.breaks;
        // Each needle found, with where: in the statement itself if it is there, else
        // in the innermost `if` or `while` around it that has it (the one the tooltip
        // names).
        let mut found: Vec<(u32, usize)> = Vec::new();
        let mut searched = breaks
            .needles
            .each_in(stmt.span.slice(self.text), &mut Vec::new(), |id| {
                found.push((id, 0))
            })
            .is_some();
        for (depth, a) in around.iter().rev().enumerate() {
            match &a.needles {
                Some(ids) => found.extend(ids.iter().map(|&id| (id, depth + 1))),
                None => searched = false,
            }
        }
        found.sort_unstable();
        found.dedup_by_key(|&mut (id, _)| id);
        let through = |depth: usize| match depth {
            0 => Through::Itself,
            d => Through::Around(around[around.len() - d].span),
        };
        let mut first: Vec<(u32, Through)> = Vec::new();
        let mut total = 0;
        for &(id, depth) in &found {
            let with = &breaks.with_needle[id as usize];
            total += with.len();
            first.extend(with.iter().take(ENDERS_NAMED).map(|&i| (i, through(depth))));
        }
        first.sort_unstable_by_key(|&(i, _)| i);
        first.truncate(ENDERS_NAMED);
        let more = total - first.len();
        (first, more, searched)
    }

    fn moment(&self, span: Span) -> Option<&Moment> {
        let i = self.moments.partition_point(|m| m.span.start < span.start);
        self.moments.get(i).filter(|m| m.span == span)
    }

    /// The label of a moment's start and its tooltip.
    fn start(&self, start: &Start) -> (String, String) {
        match *start {
            Start::Unit {
                skill,
                block,
                blocks,
            } => {
                let when = if skill {
                    "starts when the skill is called"
                } else {
                    "starts at t=0"
                };
                let with = others(block, blocks);
                let tip = if skill {
                    format!(
                        "Block {block} of the skill's {blocks}: the first block runs in the caller's block, the others beside it, all when the skill is called."
                    )
                } else {
                    format!(
                        "Block {block} of the task's {blocks} top-level blocks, which all start together when the task starts."
                    )
                };
                (format!("{when}{with}"), tip)
            }
            Start::HeldBy { by } => (
                format!("held until `{}` at line {}", self.quote(by), self.line(by)),
                format!(
                    "Its block is held back by `{}` (line {}): a `wait`, an `init` or a call of a skill whose first block holds. What follows it in the block is issued when it lets go.",
                    self.quote(by),
                    self.line(by)
                ),
            ),
            Start::Guard {
                guard,
                block,
                blocks,
            } => (
                format!(
                    "guard: runs once when {}{}",
                    self.condition(guard),
                    part(block, blocks)
                ),
                format!(
                    "In the body of the guard at line {}: the `if` does not hold its block; its condition is evaluated every tick from when it is issued until it holds, then the body runs once.",
                    self.line(guard)
                ),
            ),
            Start::Loop {
                guard,
                block,
                blocks,
            } => (
                format!(
                    "loop: runs each time {} holds{}",
                    self.condition(guard),
                    part(block, blocks)
                ),
                format!(
                    "In the body of the loop at line {}: the condition is evaluated again when every command an iteration started has ended.",
                    self.line(guard)
                ),
            ),
        }
    }

    fn line(&self, span: Span) -> usize {
        self.index.line_of(span.start as usize) + 1
    }

    fn quote(&self, span: Span) -> String {
        cut(span.slice(self.text).trim())
    }

    /// A statement of any file of the program.
    fn program_quote(&self, file: FileId, span: Span) -> String {
        cut(span.slice(self.program.text(file)).trim())
    }

    /// "line 20" in this file, "skills.ilms:20" in another.
    fn place(&self, file: FileId, span: Span) -> String {
        if file == self.file {
            return format!("line {}", self.line(span));
        }
        let text = self.program.text(file);
        let line = text[..span.start as usize].matches('\n').count() + 1;
        let uri = self.program.uri(file).unwrap_or("");
        let name = uri.rsplit('/').next().unwrap_or(uri);
        format!("{name}:{line}")
    }

    /// The condition of an `if(...)`/`while(...)` line, without its parentheses.
    fn condition(&self, guard: Span) -> String {
        let line = guard.slice(self.text);
        let inner = match (line.find('('), line.rfind(')')) {
            (Some(a), Some(b)) if a < b => &line[a + 1..b],
            (Some(a), _) => &line[a + 1..],
            _ => line,
        };
        cut(inner.trim())
    }
}

/// Every statement a `break(pattern)` ends when they run: those whose text contains the
/// needle, and, through an `if` or `while` they stand in, those inside a matched one.
/// Each with whether it is matched through a block around it.
pub fn ended_by(program: &Program, needle: &str) -> Vec<(FileId, Span, bool)> {
    let analysis = program.analysis();
    let mut out: Vec<(FileId, Span, bool)> = Vec::new();
    let mut matched: Vec<(FileId, Span)> = Vec::new();
    for (file, span, text) in breakable(&analysis.files, &analysis.skills) {
        if matches(text, needle) {
            out.push((file, span, false));
            matched.push((file, span));
        }
    }
    // The bodies of matched `if`s and `while`s: one walk of each file that has one,
    // not one per match (`break(while)` can match every loop of a long file).
    let heads: std::collections::HashSet<(FileId, Span)> = matched.iter().copied().collect();
    let mut files: Vec<FileId> = matched.iter().map(|(f, _)| *f).collect();
    files.dedup();
    for file in files {
        let tree = program.tree(file);
        let mut inside = Vec::new();
        let mut heads_in = |blocks: &[Block<'_>]| {
            within(blocks, &|span| heads.contains(&(file, span)), &mut inside)
        };
        heads_in(&tree.blocks);
        for skill in &tree.skills {
            heads_in(&skill.blocks);
        }
        out.extend(inside.into_iter().map(|s| (file, s, true)));
    }
    out.sort_by_key(|&(f, s, _)| (f, s.start));
    out.dedup_by_key(|&mut (f, s, _)| (f, s));
    out
}

/// The statements inside the `if`s and `while`s that `head` names.
fn within(blocks: &[Block<'_>], head: &dyn Fn(Span) -> bool, out: &mut Vec<Span>) {
    for block in blocks {
        for stmt in &block.stmts {
            if let StmtKind::If(c) | StmtKind::While { body: c, .. } = &stmt.kind {
                if head(stmt.span) {
                    collect(&c.body, out);
                } else {
                    within(&c.body, head, out);
                }
            }
        }
    }
}

fn collect(blocks: &[Block<'_>], out: &mut Vec<Span>) {
    for block in blocks {
        for stmt in &block.stmts {
            match &stmt.kind {
                StmtKind::Break { .. } | StmtKind::Error | StmtKind::Check { .. } => {}
                StmtKind::If(c) | StmtKind::While { body: c, .. } => {
                    out.push(stmt.span);
                    collect(&c.body, out);
                }
                _ => out.push(stmt.span),
            }
        }
    }
}

/// " with block 2", " with blocks 1, 3", " with 41 other blocks", or nothing alone.
fn others(block: u32, blocks: u32) -> String {
    if blocks <= 1 {
        return String::new();
    }
    if blocks - 1 > BLOCKS_NAMED {
        return format!(" with {} other blocks", blocks - 1);
    }
    let names: Vec<String> = (1..=blocks)
        .filter(|&b| b != block)
        .map(|b| b.to_string())
        .collect();
    let s = if names.len() == 1 { "" } else { "s" };
    format!(" with block{s} {}", names.join(", "))
}

/// " (block 2 of 3)" for a body of several blocks.
fn part(block: u32, blocks: u32) -> String {
    if blocks <= 1 {
        String::new()
    } else {
        format!(" (block {block} of {blocks})")
    }
}

fn cut(text: &str) -> String {
    match text.char_indices().nth(QUOTED_CHARS) {
        Some((i, _)) => format!("{}…", &text[..i]),
        None => text.to_string(),
    }
}

/// "1 more break", "2 more breaks".
fn counted(n: usize, what: &str) -> String {
    if n == 1 {
        format!("1 {what}")
    } else {
        format!("{n} {what}s")
    }
}

fn overlaps(a: Span, b: Span) -> bool {
    a.start <= b.end && b.start <= a.end
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn other_blocks_are_named_then_counted() {
        assert_eq!(others(1, 1), "");
        assert_eq!(others(1, 2), " with block 2");
        assert_eq!(others(2, 4), " with blocks 1, 3, 4");
        assert_eq!(others(3, 5), " with 4 other blocks");
        assert_eq!(part(1, 1), "");
        assert_eq!(part(2, 3), " (block 2 of 3)");
    }

    #[test]
    fn long_statements_are_cut_on_a_character() {
        assert_eq!(cut("wait(t1)"), "wait(t1)");
        let long = "ä".repeat(40);
        assert_eq!(cut(&long), format!("{}…", "ä".repeat(QUOTED_CHARS)));
    }
}

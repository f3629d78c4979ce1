//! Nests parsed lines into blocks: `if`/`while`/`check` bodies, skills under their
//! headers, and blocks separated by empty lines (section 4.3). Unbalanced structure is
//! reported and repaired (a missing `endif` is taken to be where the enclosing block
//! ends), so the tree is always complete.

use crate::ast::{
    Args, Block, Conditional, Expr, FileKind, Name, Skill, SourceFile, Stmt, StmtKind,
};
use crate::diagnostic::{Code, Diagnostic, FileId};
use crate::kept::Kept;
use crate::limits::MAX_BLOCK_DEPTH;
use crate::parser::lines::{Line, ParsedLine};
use crate::span::Span;
use ilmr_stdlib::Command;

enum Opener<'s> {
    Root,
    Skill {
        name: Name<'s>,
        params: Option<Args<'s>>,
        header: Span,
    },
    If {
        keyword: Span,
        cond: Expr<'s>,
    },
    While {
        bind: Option<Name<'s>>,
        keyword: Span,
        cond: Expr<'s>,
    },
    Check,
}

struct Frame<'s> {
    opener: Opener<'s>,
    /// The opening line.
    head: Span,
    /// Where this frame's finished blocks and its current block's statements begin in
    /// the builder's parts: only the top frame grows, so the open frames' parts lie on
    /// the two stacks in frame order.
    blocks: usize,
    stmts: usize,
}

impl<'s> Frame<'s> {
    fn new(opener: Opener<'s>, head: Span, parts: &Parts<'s>) -> Self {
        Frame {
            opener,
            head,
            blocks: parts.blocks.len(),
            stmts: parts.stmts.len(),
        }
    }

    /// Which closer ends this frame, for matching and for messages.
    fn closer(&self) -> Option<Closer> {
        match self.opener {
            Opener::If { .. } => Some(Closer::EndIf),
            Opener::While { .. } => Some(Closer::EndWhile),
            Opener::Check => Some(Closer::Checkend),
            Opener::Root | Opener::Skill { .. } => None,
        }
    }
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Closer {
    EndIf,
    EndWhile,
    Checkend,
}

impl Closer {
    fn word(self) -> &'static str {
        match self {
            Closer::EndIf => "endif",
            Closer::EndWhile => "endwhile",
            Closer::Checkend => "checkend",
        }
    }
}

/// The statements and blocks of the open frames, which become exact-size slices of the
/// tree as their frames close: no list in the tree keeps spare room.
struct Parts<'s> {
    blocks: Vec<Block<'s>>,
    stmts: Vec<Stmt<'s>>,
}

impl<'s> Parts<'s> {
    /// Ends the current block of the frame whose statements begin at `from`.
    fn flush(&mut self, from: usize) {
        if let (Some(first), Some(last)) = (self.stmts.get(from), self.stmts.last()) {
            let span = first.span.to(last.span);
            let stmts = self.stmts.drain(from..).collect();
            self.blocks.push(Block { stmts, span });
        }
    }

    /// The finished blocks of the frame whose blocks begin at `from`.
    fn take_blocks(&mut self, from: usize) -> Box<[Block<'s>]> {
        self.blocks.drain(from..).collect()
    }
}

/// Takes the lines of a file in order, as they are parsed.
pub struct Builder<'s> {
    file: FileId,
    source: &'s str,
    stack: Vec<Frame<'s>>,
    parts: Parts<'s>,
    skills: Vec<Skill<'s>>,
    /// Statements before the first skill header, kept as the task's blocks.
    task_blocks: Option<Box<[Block<'s>]>>,
    /// Blocks open past [`MAX_BLOCK_DEPTH`], counted but not built: their lines are
    /// dropped until the closers bring the depth back within the limit.
    skipped: usize,
    diagnostics: Kept,
    /// Statements that bind a variable (`v = ...`, `v = command(...)`, `v = while`):
    /// at least as many as the file's variables, so the checker sizes its lists of
    /// variables once.
    pub binds: usize,
    /// What the passes after the checker's walk look for, noted as lines come so that
    /// a pass with nothing to find skips its walk of the whole tree (at 10x the
    /// corpus's tree is far larger than the cache, and each walk reads all of it).
    pub seen: Seen,
    /// Commands that never end by themselves (`Ends::Never`, `Ends::NeverBare`).
    never: Vec<Command>,
    /// A call of `record`, `createpath` or `followpath` since the finished blocks were
    /// last taken ([`Builder::take_paths`]).
    paths: bool,
}

/// Statements a pass after the walk needs, noted by the block builder (`Parsed::seen`).
/// Each flag is a superset of what its pass looks for: false means the pass would find
/// nothing in the file.
#[derive(Debug, Clone, Copy, Default)]
pub struct Seen {
    /// A call of `followpath` (W0903, `check/paths.rs`).
    pub follows_path: bool,
    /// A bound call of a command that never ends by itself, or a bound `while`: the
    /// statements whose waits may never wake (W0904, `check/wakes.rs`).
    pub never_ending: bool,
}

impl<'s> Builder<'s> {
    pub fn new(source: &'s str, file: FileId) -> Self {
        let parts = Parts {
            blocks: Vec::new(),
            stmts: Vec::new(),
        };
        Builder {
            file,
            source,
            stack: vec![Frame::new(Opener::Root, Span::empty(0), &parts)],
            parts,
            skills: Vec::new(),
            task_blocks: None,
            skipped: 0,
            diagnostics: Kept::new(),
            binds: 0,
            seen: Seen::default(),
            never: Command::never_ending().collect(),
            paths: false,
        }
    }

    fn top(&self) -> &Frame<'s> {
        self.stack.last().expect("the root frame is never popped")
    }

    /// Opens a frame above the top one.
    fn open(&mut self, opener: Opener<'s>, head: Span) {
        let frame = Frame::new(opener, head, &self.parts);
        self.stack.push(frame);
    }

    /// Opens a block, unless that would pass [`MAX_BLOCK_DEPTH`]: then it is reported
    /// and skipped with everything inside it.
    fn open_block(&mut self, opener: Opener<'s>, head: Span) {
        // A skill's frame, when there is one, lies right above the root.
        let skill = matches!(
            self.stack.get(1).map(|f| &f.opener),
            Some(Opener::Skill { .. })
        );
        let depth = self.stack.len() - 1 - usize::from(skill);
        if depth < MAX_BLOCK_DEPTH {
            self.open(opener, head);
        } else {
            self.too_deep(head, depth);
        }
    }

    #[cold]
    fn too_deep(&mut self, head: Span, depth: usize) {
        self.skipped = 1;
        self.diagnostics.push(
            Diagnostic::new(
                Code::TooDeep,
                self.file,
                head,
                format!("blocks nested more than {MAX_BLOCK_DEPTH} deep"),
            )
            .with_label(format!(
                "this block would be level {}; it and its contents are not checked",
                depth + 1
            ))
            .with_help("move the inner part into a skill, or join the conditions"),
        );
    }

    /// Whether a line is inside a skipped block, where only openers and closers count.
    /// A skill header ends every open block, skipped ones too.
    #[cold]
    fn skip(&mut self, line: &Line<'s>) -> bool {
        match line {
            Line::IfHead { .. } | Line::WhileHead { .. } | Line::Check => self.skipped += 1,
            Line::EndIf | Line::EndWhile | Line::Checkend => self.skipped -= 1,
            Line::SkillHeader(..) => {
                self.skipped = 0;
                return false;
            }
            _ => {}
        }
        true
    }

    /// Whether a top-level block has finished since the last [`Builder::ready`].
    pub fn has_ready(&self) -> bool {
        self.stack.len() == 1 && !self.parts.blocks.is_empty()
    }

    /// The top-level blocks finished since the last call, taken out of the tree (a
    /// streamed parse, `parser::parse_streamed`). Only while no block is open: then
    /// every finished block is the root's.
    pub fn ready(&mut self) -> std::vec::Drain<'_, Block<'s>> {
        debug_assert_eq!(self.stack.len(), 1);
        self.parts.blocks.drain(..)
    }

    /// Whether a block finished since the last call may make or follow a path: W0903's
    /// scan of a streamed block (`check/paths.rs`) is skipped when none does. True for
    /// every block taken at once when one of them does.
    pub fn take_paths(&mut self) -> bool {
        std::mem::take(&mut self.paths)
    }

    /// Whether the file so far is one a streamed parse gives up on: not a plain task
    /// (a skill header), structure reported, or a statement that never ends (W0904
    /// reads the whole program for what may end it).
    pub fn refuses_streaming(&self) -> bool {
        self.task_blocks.is_some() || !self.diagnostics.is_empty() || self.seen.never_ending
    }

    /// Ends the top frame's current block.
    fn flush(&mut self) {
        let from = self.top().stmts;
        self.parts.flush(from);
    }

    /// Whether the line that ends at `span` (an empty line's span starts at its line
    /// break) holds a comment.
    fn holds_comment(&self, span: Span) -> bool {
        let end = (span.start as usize).min(self.source.len());
        let Some(text) = self.source.get(..end) else {
            return false;
        };
        let start = text.rfind('\n').map_or(0, |i| i + 1);
        text[start..].contains("//")
    }

    pub fn line(&mut self, parsed: ParsedLine<'s>) {
        let span = parsed.span;
        if self.skipped > 0 && self.skip(&parsed.line) {
            return;
        }
        match parsed.line {
            // A line with only a comment has no tokens, yet it is not empty: commenting
            // out a line must not split a block and change what runs concurrently
            // (docs/language.md).
            Line::Blank if self.holds_comment(span) => {}
            Line::Blank => self.flush(),
            Line::Stmt(kind) => {
                let binds = matches!(
                    kind,
                    StmtKind::Assign { .. } | StmtKind::Call { bind: Some(_), .. }
                );
                self.binds += usize::from(binds);
                if let StmtKind::Call { bind, call } = &kind {
                    let follows = call.name.is(Command::FollowPath.name());
                    self.seen.follows_path |= follows;
                    self.paths |= follows
                        || call.name.is(Command::Record.name())
                        || call.name.is(Command::CreatePath.name());
                    self.seen.never_ending |=
                        bind.is_some() && self.never.iter().any(|c| call.name.is(c.name()));
                }
                self.parts.stmts.push(Stmt { kind, span });
            }
            Line::IfHead { keyword, cond } => self.open_block(Opener::If { keyword, cond }, span),
            Line::WhileHead {
                bind,
                keyword,
                cond,
            } => {
                self.binds += usize::from(bind.is_some());
                self.seen.never_ending |= bind.is_some();
                self.open_block(
                    Opener::While {
                        bind,
                        keyword,
                        cond,
                    },
                    span,
                )
            }
            Line::Check => self.open_block(Opener::Check, span),
            Line::EndIf => self.close(Closer::EndIf, span),
            Line::EndWhile => self.close(Closer::EndWhile, span),
            Line::Checkend => self.close(Closer::Checkend, span),
            Line::SkillHeader(name, params) => self.skill_header(name, params, span),
        }
    }

    fn close(&mut self, closer: Closer, span: Span) {
        let open = self
            .stack
            .iter()
            .rposition(|f| f.closer() == Some(closer))
            .filter(|&i| {
                // A closer never reaches across a skill boundary.
                !self.stack[i..]
                    .iter()
                    .any(|f| matches!(f.opener, Opener::Skill { .. }))
            });
        let Some(open) = open else {
            let (code, opener) = match closer {
                Closer::EndIf => (Code::StrayEndIf, "if"),
                Closer::EndWhile => (Code::StrayEndWhile, "while"),
                Closer::Checkend => (Code::StrayCheckend, "check"),
            };
            self.diagnostics.push(
                Diagnostic::new(
                    code,
                    self.file,
                    span,
                    format!("`{}` closes no open `{opener}`", closer.word()),
                )
                .with_label("nothing to close here"),
            );
            return;
        };
        while self.stack.len() > open + 1 {
            self.pop_unclosed(span.start as usize);
        }
        self.pop(Some(span));
    }

    fn skill_header(&mut self, name: Name<'s>, params: Option<Args<'s>>, span: Span) {
        if self.stack.len() > 1 && !matches!(self.stack[1].opener, Opener::Skill { .. })
            || self.stack.len() > 2
        {
            self.diagnostics.push(
                Diagnostic::new(
                    Code::NestedSkillHeader,
                    self.file,
                    span,
                    format!("skill header `{}:` inside an open block", name.text),
                )
                .with_label("a skill can start only at the top level"),
            );
        }
        while self.stack.len() > 1 {
            if matches!(self.top().opener, Opener::Skill { .. }) {
                self.pop(None);
            } else {
                self.pop_unclosed(span.start as usize);
            }
        }
        if self.task_blocks.is_none() {
            self.flush();
            self.task_blocks = Some(self.parts.take_blocks(self.top().blocks));
        }
        self.open(
            Opener::Skill {
                name,
                params,
                header: span,
            },
            span,
        );
    }

    /// Closes the top frame for lack of its closer, which is taken to stand at `at`.
    fn pop_unclosed(&mut self, at: usize) {
        let frame = self.top();
        let (code, word) = match frame.opener {
            Opener::If { .. } => (Code::UnclosedIf, "if"),
            Opener::While { .. } => (Code::UnclosedWhile, "while"),
            Opener::Check => (Code::UnclosedCheck, "check"),
            Opener::Root | Opener::Skill { .. } => unreachable!("only blocks are unclosed"),
        };
        let closer = frame.closer().expect("blocks have closers").word();
        let head = frame.head;
        let insert = if at >= self.source.len() && !self.source.ends_with('\n') {
            format!("\n{closer}\n")
        } else {
            format!("{closer}\n")
        };
        self.diagnostics.push(
            Diagnostic::new(
                code,
                self.file,
                head,
                format!("this `{word}` has no `{closer}`"),
            )
            .with_label(format!("`{word}` opened here is never closed"))
            .with_help(format!(
                "add `{closer}` on its own line where the block should end"
            ))
            .with_fix(format!("insert `{closer}`"), Span::empty(at), insert),
        );
        self.pop(None);
    }

    fn pop(&mut self, end: Option<Span>) {
        self.flush();
        let frame = self.stack.pop().expect("pop above the root");
        let body = self.parts.take_blocks(frame.blocks);
        let last = body.last().map_or(frame.head, |b| b.span);
        let span = frame.head;
        let kind = match frame.opener {
            Opener::If { keyword, cond } => StmtKind::If(Box::new(Conditional {
                keyword,
                cond,
                body,
                end,
            })),
            Opener::While {
                bind,
                keyword,
                cond,
            } => StmtKind::While {
                bind,
                body: Box::new(Conditional {
                    keyword,
                    cond,
                    body,
                    end,
                }),
            },
            Opener::Check => StmtKind::Check { body, end },
            Opener::Skill {
                name,
                params,
                header,
            } => {
                self.skills.push(Skill {
                    name,
                    params,
                    header,
                    span: header.to(last),
                    blocks: body,
                });
                return;
            }
            Opener::Root => unreachable!("the root frame is never popped"),
        };
        self.parts.stmts.push(Stmt { kind, span });
    }

    /// The tree, and the diagnostics of its structure.
    pub fn finish(mut self, comments: Vec<Span>) -> (SourceFile<'s>, Kept) {
        let end = self.source.len();
        while self.stack.len() > 1 {
            if matches!(self.top().opener, Opener::Skill { .. }) {
                self.pop(None);
            } else {
                self.pop_unclosed(end);
            }
        }
        self.flush();
        let root = self.stack.pop().expect("root frame");
        let (kind, blocks) = match self.task_blocks {
            Some(before_first_skill) => (FileKind::Skills, before_first_skill),
            None => (FileKind::Task, self.parts.take_blocks(root.blocks)),
        };
        if kind == FileKind::Skills
            && let Some(first) = blocks.first().and_then(|b| b.stmts.first())
        {
            self.diagnostics.push(
                Diagnostic::new(
                    Code::OutsideSkill,
                    self.file,
                    first.span,
                    "statement before the first skill header",
                )
                .with_label("this belongs to no skill")
                .with_help("put a `NAME:` header above it, or move it to a task file"),
            );
        }
        let tree = SourceFile {
            kind,
            blocks,
            skills: self.skills,
            comments,
            span: Span::new(0, end),
        };
        (tree, self.diagnostics)
    }
}

#[cfg(test)]
mod tests {
    use crate::ast::StmtKind;
    use crate::diagnostic::FileId;
    use crate::parser::parse;

    /// Statements per top-level block, and per block of the first `if` body found.
    fn shape(source: &str) -> (Vec<usize>, Vec<usize>) {
        let parsed = parse(source, FileId(0));
        assert!(parsed.diagnostics.is_empty(), "{:?}", parsed.diagnostics);
        let top = parsed.file.blocks.iter().map(|b| b.stmts.len()).collect();
        let inner = parsed
            .file
            .blocks
            .iter()
            .flat_map(|b| b.stmts.iter())
            .find_map(|s| match &s.kind {
                StmtKind::If(c) => Some(c.body.iter().map(|b| b.stmts.len()).collect()),
                _ => None,
            })
            .unwrap_or_default();
        (top, inner)
    }

    /// The passes that skip their walk on these flags (W0903, W0904) would miss a
    /// warning if a flag were false where the statement is.
    #[test]
    fn seen_notes_what_the_passes_after_the_walk_look_for() {
        let seen = |source: &str| {
            let s = parse(source, FileId(0)).seen;
            (s.follows_path, s.never_ending)
        };
        assert_eq!(seen("speed(0.3)\nwait(2)\n"), (false, false));
        assert_eq!(seen("if(1)\n    FollowPath(p)\nendif\n"), (true, false));
        assert_eq!(seen("w = followwall(left)\nwait(w)\n"), (false, true));
        assert_eq!(seen("s:\nd = GOAHEAD()\n"), (false, true));
        assert_eq!(seen("followwall(left)\n"), (false, false));
        assert_eq!(
            seen("v = while(1)\n    speed(1)\nendwhile\n"),
            (false, true)
        );
    }

    #[test]
    fn a_comment_line_does_not_separate_blocks() {
        assert_eq!(shape("a=1\n// note\nb=2\n").0, vec![2]);
        assert_eq!(shape("a=1\n   // note\nb=2").0, vec![2]);
        assert_eq!(shape("// head\na=1\n\nb=2 // tail\n").0, vec![1, 1]);
        assert_eq!(shape("a=1 // x\n\nb=2\n// end").0, vec![1, 1]);
        assert_eq!(shape("a=1\r\n// note\r\nb=2\r\n").0, vec![2]);
    }

    #[test]
    fn an_empty_line_separates_blocks_inside_an_if_but_a_comment_line_does_not() {
        let (_, inner) = shape("if(1)\na=1\n// note\nb=2\n\nc=3\nendif\n");
        assert_eq!(inner, vec![2, 1]);
    }
}

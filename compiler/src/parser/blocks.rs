//! Nests parsed lines into blocks: `if`/`while`/`check` bodies, skills under their
//! headers, and blocks separated by empty lines (section 4.3). Unbalanced structure is
//! reported and repaired (a missing `endif` is taken to be where the enclosing block
//! ends), so the tree is always complete.

use crate::ast::{Block, Conditional, Expr, FileKind, Name, Skill, SourceFile, Stmt, StmtKind};
use crate::diagnostic::{Code, Diagnostic, FileId};
use crate::parser::lines::{Line, ParsedLine};
use crate::span::Span;

enum Opener<'s> {
    Root,
    Skill {
        name: Name<'s>,
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
    blocks: Vec<Block<'s>>,
    current: Vec<Stmt<'s>>,
}

impl<'s> Frame<'s> {
    fn new(opener: Opener<'s>, head: Span) -> Self {
        Frame {
            opener,
            head,
            blocks: Vec::new(),
            current: Vec::new(),
        }
    }

    fn flush(&mut self) {
        if let (Some(first), Some(last)) = (self.current.first(), self.current.last()) {
            let span = first.span.to(last.span);
            self.blocks.push(Block {
                stmts: std::mem::take(&mut self.current),
                span,
            });
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

/// Takes the lines of a file in order, as they are parsed.
pub struct Builder<'s> {
    file: FileId,
    source: &'s str,
    stack: Vec<Frame<'s>>,
    skills: Vec<Skill<'s>>,
    /// Statements before the first skill header, kept as the task's blocks.
    task_blocks: Option<Vec<Block<'s>>>,
    diagnostics: Vec<Diagnostic>,
}

impl<'s> Builder<'s> {
    pub fn new(source: &'s str, file: FileId) -> Self {
        Builder {
            file,
            source,
            stack: vec![Frame::new(Opener::Root, Span::empty(0))],
            skills: Vec::new(),
            task_blocks: None,
            diagnostics: Vec::new(),
        }
    }

    fn top(&mut self) -> &mut Frame<'s> {
        self.stack
            .last_mut()
            .expect("the root frame is never popped")
    }

    pub fn line(&mut self, parsed: ParsedLine<'s>) {
        let span = parsed.span;
        match parsed.line {
            Line::Blank => self.top().flush(),
            Line::Stmt(kind) => self.top().current.push(Stmt { kind, span }),
            Line::IfHead { keyword, cond } => self
                .stack
                .push(Frame::new(Opener::If { keyword, cond }, span)),
            Line::WhileHead {
                bind,
                keyword,
                cond,
            } => self.stack.push(Frame::new(
                Opener::While {
                    bind,
                    keyword,
                    cond,
                },
                span,
            )),
            Line::Check => self.stack.push(Frame::new(Opener::Check, span)),
            Line::EndIf => self.close(Closer::EndIf, span),
            Line::EndWhile => self.close(Closer::EndWhile, span),
            Line::Checkend => self.close(Closer::Checkend, span),
            Line::SkillHeader(name) => self.skill_header(name, span),
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

    fn skill_header(&mut self, name: Name<'s>, span: Span) {
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
            let root = self.top();
            root.flush();
            self.task_blocks = Some(std::mem::take(&mut root.blocks));
        }
        self.stack
            .push(Frame::new(Opener::Skill { name, header: span }, span));
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
        let mut frame = self.stack.pop().expect("pop above the root");
        frame.flush();
        let body = frame.blocks;
        let last = body.last().map_or(frame.head, |b| b.span);
        let span = frame.head;
        let kind = match frame.opener {
            Opener::If { keyword, cond } => StmtKind::If(Conditional {
                keyword,
                cond,
                body,
                end,
            }),
            Opener::While {
                bind,
                keyword,
                cond,
            } => StmtKind::While {
                bind,
                body: Conditional {
                    keyword,
                    cond,
                    body,
                    end,
                },
            },
            Opener::Check => StmtKind::Check { body, end },
            Opener::Skill { name, header } => {
                self.skills.push(Skill {
                    name,
                    header,
                    span: header.to(last),
                    blocks: body,
                });
                return;
            }
            Opener::Root => unreachable!("the root frame is never popped"),
        };
        self.top().current.push(Stmt { kind, span });
    }

    /// The tree, and the diagnostics of its structure.
    pub fn finish(mut self, comments: Vec<Span>) -> (SourceFile<'s>, Vec<Diagnostic>) {
        let end = self.source.len();
        while self.stack.len() > 1 {
            if matches!(self.top().opener, Opener::Skill { .. }) {
                self.pop(None);
            } else {
                self.pop_unclosed(end);
            }
        }
        let mut root = self.stack.pop().expect("root frame");
        root.flush();
        let (kind, blocks) = match self.task_blocks {
            Some(before_first_skill) => (FileKind::Skills, before_first_skill),
            None => (FileKind::Task, root.blocks),
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

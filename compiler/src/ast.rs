//! The syntax tree. It borrows names from the source (no allocation per name) and every
//! node has its span. A tree is always produced, however broken the input: lines that do
//! not parse become `StmtKind::Error`, unclosed blocks run to the end of the file.

use crate::span::Span;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FileKind {
    /// A task: top-level blocks that start together.
    Task,
    /// One or more skills, each opened by a `NAME:` header (Figure 56).
    Skills,
}

#[derive(Debug, Clone)]
pub struct SourceFile<'s> {
    pub kind: FileKind,
    /// The task's top-level blocks (for a skill file: statements before the first header,
    /// which the checker reports).
    pub blocks: Box<[Block<'s>]>,
    pub skills: Vec<Skill<'s>>,
    pub comments: Vec<Span>,
    pub span: Span,
}

#[derive(Debug, Clone)]
pub struct Skill<'s> {
    pub name: Name<'s>,
    /// `NAME(a, side=left/right):`: the parameters as written (the checker reads them).
    pub params: Option<Args<'s>>,
    /// The header line `NAME:`.
    pub header: Span,
    pub blocks: Box<[Block<'s>]>,
    pub span: Span,
}

/// Statements on one level not separated by an empty line (section 4.3).
#[derive(Debug, Clone)]
pub struct Block<'s> {
    pub stmts: Box<[Stmt<'s>]>,
    pub span: Span,
}

#[derive(Debug, Clone)]
pub struct Stmt<'s> {
    pub kind: StmtKind<'s>,
    /// The statement's own line, without a trailing comment. For `if` and `while` the
    /// opening line only: `break(pattern)` matches this text.
    pub span: Span,
}

#[derive(Debug, Clone)]
pub enum StmtKind<'s> {
    /// `name(args)` or bare `name`, optionally bound: `v = name(args)`. A bare name may be
    /// a skill call; which it is, the checker decides.
    Call {
        bind: Option<Name<'s>>,
        call: Call<'s>,
    },
    /// `v = expression`.
    Assign {
        target: Name<'s>,
        value: Expr<'s>,
    },
    If(Box<Conditional<'s>>),
    While {
        bind: Option<Name<'s>>,
        body: Box<Conditional<'s>>,
    },
    /// `check` ... `checkend`: validated, never run.
    Check {
        body: Box<[Block<'s>]>,
        end: Option<Span>,
    },
    /// `break`, or `break(pattern)` with the raw pattern text.
    Break {
        pattern: Option<Pattern<'s>>,
    },
    /// `priority = highest`.
    Priority,
    /// A line that does not parse; its diagnostic says why.
    Error,
}

#[derive(Debug, Clone)]
pub struct Conditional<'s> {
    pub keyword: Span,
    pub cond: Expr<'s>,
    pub body: Box<[Block<'s>]>,
    /// The `endif`/`endwhile` line, `None` when missing.
    pub end: Option<Span>,
}

#[derive(Debug, Clone, Copy)]
pub struct Pattern<'s> {
    pub text: &'s str,
    pub span: Span,
    pub closed: bool,
}

#[derive(Debug, Clone, Copy)]
pub struct Name<'s> {
    /// As written; lookups ignore case.
    pub text: &'s str,
    pub span: Span,
}

impl<'s> Name<'s> {
    pub fn is(&self, word: &str) -> bool {
        self.text.eq_ignore_ascii_case(word)
    }
}

#[derive(Debug, Clone)]
pub struct Call<'s> {
    pub name: Name<'s>,
    /// `None` when written bare (`stop`, `Takebox`).
    pub args: Option<Args<'s>>,
}

#[derive(Debug, Clone)]
pub struct Args<'s> {
    pub items: Box<[Arg<'s>]>,
    /// From `(` to `)` (or to the end of the line when unclosed).
    pub span: Span,
    pub closed: bool,
}

#[derive(Debug, Clone)]
pub enum Arg<'s> {
    Positional(Expr<'s>),
    /// `key = value`, as in `turn(d=90,c=0.5)`. The value is boxed: settings are rare,
    /// and inline it would make every argument 64 bytes instead of 40.
    Setting {
        key: Name<'s>,
        value: Box<Expr<'s>>,
    },
}

impl Arg<'_> {
    pub fn span(&self) -> Span {
        match self {
            Arg::Positional(e) => e.span,
            Arg::Setting { key, value } => key.span.to(value.span),
        }
    }
}

#[derive(Debug, Clone)]
pub struct Expr<'s> {
    pub kind: ExprKind<'s>,
    pub span: Span,
}

#[derive(Debug, Clone)]
pub enum ExprKind<'s> {
    Number(f64),
    /// A variable, a model name or a keyword; the checker resolves which.
    Name(Name<'s>),
    Neg(Box<Expr<'s>>),
    Binary {
        op: BinOp,
        lhs: Box<Expr<'s>>,
        rhs: Box<Expr<'s>>,
    },
    Compare {
        op: CmpOp,
        op_span: Span,
        lhs: Box<Expr<'s>>,
        rhs: Box<Expr<'s>>,
    },
    /// A part of an expression that did not parse.
    Error,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BinOp {
    Add,
    Sub,
    Mul,
    Div,
}

impl BinOp {
    pub fn symbol(self) -> &'static str {
        match self {
            BinOp::Add => "+",
            BinOp::Sub => "-",
            BinOp::Mul => "*",
            BinOp::Div => "/",
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CmpOp {
    Lt,
    Le,
    Eq,
    Ne,
    Gt,
    Ge,
}

impl CmpOp {
    /// The canonical spelling (the formatter writes `==` for `=` and `>=` for `=>`).
    pub fn symbol(self) -> &'static str {
        match self {
            CmpOp::Lt => "<",
            CmpOp::Le => "<=",
            CmpOp::Eq => "==",
            CmpOp::Ne => "!=",
            CmpOp::Gt => ">",
            CmpOp::Ge => ">=",
        }
    }
}

impl<'s> SourceFile<'s> {
    /// Every block of the file at every depth, in source order, with the blocks of skills.
    pub fn for_each_stmt(&self, f: &mut impl FnMut(&Stmt<'s>)) {
        for_each_stmt_in(&self.blocks, f);
        for skill in &self.skills {
            for_each_stmt_in(&skill.blocks, f);
        }
    }
}

/// Every statement of `blocks` and of the blocks inside them, in text order.
pub fn for_each_stmt_in<'a, 's>(blocks: &'a [Block<'s>], f: &mut impl FnMut(&'a Stmt<'s>)) {
    for block in blocks {
        for stmt in &block.stmts {
            f(stmt);
            match &stmt.kind {
                StmtKind::If(c) | StmtKind::While { body: c, .. } => for_each_stmt_in(&c.body, f),
                StmtKind::Check { body, .. } => for_each_stmt_in(body, f),
                _ => {}
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The tree of a large task is most of what checking it writes to memory: a node
    /// that grows makes every check of a large file slower (docs/performance.md).
    #[test]
    #[cfg(target_pointer_width = "64")]
    fn nodes_keep_their_sizes() {
        assert_eq!(size_of::<Name<'_>>(), 24);
        assert_eq!(size_of::<Expr<'_>>(), 40);
        assert_eq!(size_of::<Arg<'_>>(), 40);
        assert_eq!(size_of::<Stmt<'_>>(), 88);
        assert_eq!(size_of::<Block<'_>>(), 24);
    }
}

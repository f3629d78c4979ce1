//! Skills with parameters (the dissertation's future work, section 6: "the
//! parameterization of scripts"). A header `NAME(d, side=left/right):` declares a
//! number parameter `d` and a keyword parameter `side` that takes `left` or `right`; a
//! call `NAME(1.2, left)` gives them in order. A skill's commands are appended where
//! the call stands (section 4.2.2.2), so a parameter stands for what the call gives, as
//! if written in its place: each distinct argument list makes one specialization of
//! the skill, its body with the parameters replaced, checked and lowered as a skill of
//! its own. The VM runs it as any other skill; nothing of it changes.
//!
//! A number argument is a number, arithmetic of numbers, a constant of the robot model
//! or a variable (read where the skill uses it, as if written there); arithmetic of
//! variables is written into a variable first, so that every name of a specialization
//! keeps a span of the skill's own text.

use rustc_hash::FxHashMap;

use crate::ast::{Arg, Args, Block, Conditional, Expr, ExprKind, Name, Stmt, StmtKind};
use crate::check::skills::SkillId;
use crate::diagnostic::{Code, Diagnostic, FileId};
use crate::kept::Kept;
use crate::span::Span;

/// A specialization's number beyond which calls of parameterized skills are not
/// specialized further (only a program that calls skills with thousands of distinct
/// argument lists reaches it; recursion, which could make more, is E0601).
pub const MAX_SPECIALS: usize = 4096;

/// One parameter of a skill's header.
#[derive(Debug, Clone)]
pub struct Param {
    pub name: String,
    pub span: Span,
    /// The words a keyword parameter takes (lower case); empty for a number
    /// parameter.
    pub words: Vec<String>,
    /// Where each word is written in the header.
    pub word_spans: Vec<Span>,
}

impl Param {
    /// `d` or `side=left/right`, as the header declares it.
    pub fn describe(&self) -> String {
        if self.words.is_empty() {
            self.name.clone()
        } else {
            format!("{}={}", self.name, self.words.join("/"))
        }
    }
}

/// `NAME(d, side=left/right)`.
pub fn signature(name: &str, params: &[Param]) -> String {
    let list: Vec<String> = params.iter().map(Param::describe).collect();
    format!("{name}({})", list.join(", "))
}

/// Reads a header's parameters; what is not a parameter is an error.
pub fn read(args: &Args<'_>, file: FileId, diags: &mut Kept) -> Vec<Param> {
    let mut out: Vec<Param> = Vec::new();
    for a in args.items.iter() {
        let param = match a {
            Arg::Positional(Expr {
                kind: ExprKind::Name(n),
                ..
            }) => Some((n, Vec::new(), Vec::new())),
            Arg::Setting { key, value } => {
                let (mut words, mut spans) = (Vec::new(), Vec::new());
                words_of(value, &mut words, &mut spans).then_some((key, words, spans))
            }
            Arg::Positional(_) => None,
        };
        let Some((name, words, word_spans)) = param else {
            diags.push(
                Diagnostic::new(
                    Code::ArgumentKind,
                    file,
                    a.span(),
                    "a skill's parameter is a name",
                )
                .with_label("not a parameter")
                .with_help(
                    "write `d` for a parameter that takes a number, or `side=left/right` for one that takes one of those words",
                ),
            );
            continue;
        };
        if out.iter().any(|p| p.name.eq_ignore_ascii_case(name.text)) {
            diags.push(
                Diagnostic::new(
                    Code::ArgumentKind,
                    file,
                    name.span,
                    format!("parameter `{}` is declared twice", name.text),
                )
                .with_label("declared again here"),
            );
            continue;
        }
        out.push(Param {
            name: name.text.to_string(),
            span: name.span,
            words,
            word_spans,
        });
    }
    out
}

/// `left/right/ahead`: the words, when the value is names joined by `/`.
fn words_of(e: &Expr<'_>, out: &mut Vec<String>, spans: &mut Vec<Span>) -> bool {
    match &e.kind {
        ExprKind::Name(n) => {
            out.push(n.text.to_lowercase());
            spans.push(n.span);
            true
        }
        ExprKind::Binary {
            op: crate::ast::BinOp::Div,
            lhs,
            rhs,
        } => words_of(lhs, out, spans) && words_of(rhs, out, spans),
        _ => false,
    }
}

/// What a call gives a parameter.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Given {
    Number(f64),
    /// A variable or a constant of the model, or a keyword: the text at this place.
    Text(FileId, Span),
}

/// The specializations of parameterized skills that a program's calls make, each once.
#[derive(Debug, Default)]
pub struct Specials {
    pub list: Vec<Special>,
    index: FxHashMap<(SkillId, Vec<Key>), u32>,
}

/// One skill with one call's arguments.
#[derive(Debug, Clone)]
pub struct Special {
    pub skill: SkillId,
    pub args: Vec<Given>,
    /// `Corner(1.2,left)`: the name of its unit in the module.
    pub label: String,
    /// The first call that made it.
    pub call: (FileId, Span),
}

#[derive(Debug, Clone, PartialEq, Eq, Hash)]
enum Key {
    Number(u64),
    Text(String),
}

impl Specials {
    /// The specialization of `skill` for these arguments (texts as written at the
    /// call), made on first use; `None` past `MAX_SPECIALS`.
    pub fn get_or_add(
        &mut self,
        skill: SkillId,
        name: &str,
        args: Vec<(Given, &str)>,
        call: (FileId, Span),
    ) -> Option<u32> {
        let key: Vec<Key> = args
            .iter()
            .map(|(g, text)| match g {
                Given::Number(v) => Key::Number((v + 0.0).to_bits()),
                Given::Text(..) => Key::Text(text.to_lowercase()),
            })
            .collect();
        if let Some(&i) = self.index.get(&(skill, key.clone())) {
            return Some(i);
        }
        if self.list.len() >= MAX_SPECIALS {
            return None;
        }
        let i = self.list.len() as u32;
        let shown: Vec<String> = args
            .iter()
            .map(|(g, text)| match g {
                Given::Number(v) => format!("{v}"),
                Given::Text(..) => text.to_string(),
            })
            .collect();
        self.list.push(Special {
            skill,
            args: args.iter().map(|(g, _)| *g).collect(),
            label: format!("{name}({})", shown.join(",")),
            call,
        });
        self.index.insert((skill, key), i);
        Some(i)
    }
}

/// What replaces a parameter in a body.
#[derive(Debug, Clone, Copy)]
pub enum Replace<'s> {
    /// Left as a name (a number parameter checked on its own, bound as a number).
    Keep,
    Number(f64),
    Text(&'s str),
}

/// The body with each parameter's uses replaced, spans kept: a replaced name keeps
/// the span of the parameter it replaces.
pub fn substitute<'s>(
    blocks: &[Block<'s>],
    params: &[Param],
    with: &[Replace<'s>],
) -> Box<[Block<'s>]> {
    let sub = Sub { params, with };
    sub.blocks(blocks)
}

struct Sub<'p, 's> {
    params: &'p [Param],
    with: &'p [Replace<'s>],
}

impl<'s> Sub<'_, 's> {
    fn blocks(&self, blocks: &[Block<'s>]) -> Box<[Block<'s>]> {
        blocks
            .iter()
            .map(|b| Block {
                stmts: b.stmts.iter().map(|s| self.stmt(s)).collect(),
                span: b.span,
            })
            .collect()
    }

    fn stmt(&self, stmt: &Stmt<'s>) -> Stmt<'s> {
        let kind = match &stmt.kind {
            StmtKind::Call { bind, call } => StmtKind::Call {
                bind: *bind,
                call: crate::ast::Call {
                    name: call.name,
                    args: call.args.as_ref().map(|a| self.args(a)),
                },
            },
            StmtKind::Assign { target, value } => StmtKind::Assign {
                target: *target,
                value: self.expr(value),
            },
            StmtKind::If(c) => StmtKind::If(Box::new(self.cond(c))),
            StmtKind::While { bind, body } => StmtKind::While {
                bind: *bind,
                body: Box::new(self.cond(body)),
            },
            StmtKind::Check { body, end } => StmtKind::Check {
                body: self.blocks(body),
                end: *end,
            },
            other => other.clone(),
        };
        Stmt {
            kind,
            span: stmt.span,
        }
    }

    fn cond(&self, c: &Conditional<'s>) -> Conditional<'s> {
        Conditional {
            keyword: c.keyword,
            cond: self.expr(&c.cond),
            body: self.blocks(&c.body),
            end: c.end,
        }
    }

    fn args(&self, a: &Args<'s>) -> Args<'s> {
        Args {
            items: a
                .items
                .iter()
                .map(|item| match item {
                    Arg::Positional(e) => Arg::Positional(self.expr(e)),
                    Arg::Setting { key, value } => Arg::Setting {
                        key: *key,
                        value: Box::new(self.expr(value)),
                    },
                })
                .collect(),
            span: a.span,
            closed: a.closed,
        }
    }

    fn expr(&self, e: &Expr<'s>) -> Expr<'s> {
        let kind = match &e.kind {
            ExprKind::Name(n) => match self.replace(n) {
                Some(Replace::Number(v)) => ExprKind::Number(v),
                Some(Replace::Text(text)) => ExprKind::Name(Name { text, span: n.span }),
                Some(Replace::Keep) | None => ExprKind::Name(*n),
            },
            ExprKind::Neg(inner) => ExprKind::Neg(Box::new(self.expr(inner))),
            ExprKind::Binary { op, lhs, rhs } => ExprKind::Binary {
                op: *op,
                lhs: Box::new(self.expr(lhs)),
                rhs: Box::new(self.expr(rhs)),
            },
            ExprKind::Compare {
                op,
                op_span,
                lhs,
                rhs,
            } => ExprKind::Compare {
                op: *op,
                op_span: *op_span,
                lhs: Box::new(self.expr(lhs)),
                rhs: Box::new(self.expr(rhs)),
            },
            other => other.clone(),
        };
        Expr { kind, span: e.span }
    }

    fn replace(&self, n: &Name<'_>) -> Option<Replace<'s>> {
        let i = self
            .params
            .iter()
            .position(|p| p.name.eq_ignore_ascii_case(n.text))?;
        self.with.get(i).copied()
    }
}

/// The value of an expression of numbers alone.
pub fn number(e: &Expr<'_>) -> Option<f64> {
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

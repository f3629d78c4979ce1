//! A hand-written reader for the line shapes nearly every program is made of: calls,
//! bindings, arithmetic, `if(...)`/`while(...)` heads, block keywords, `break`.
//!
//! It accepts a line only when it builds exactly the `Line` the chumsky grammar of
//! `lines.rs` builds, and declines everything else, every broken line among it. The
//! grammar stays the grammar of record and the only source of syntax errors; this reader
//! only spares it the lines it would parse without trouble (chumsky spends about 1,300
//! instructions on a typical line, this reader about a tenth). The tests in
//! `parser/agreement.rs` hold the two to the same trees.
//!
//! Each function is headed by the rule of `lines.rs` it mirrors. Where the grammar's
//! ordered choice could backtrack, the reader looks one token ahead and declines when the
//! lookahead does not settle the choice the way the grammar would.

use crate::ast::{Arg, Args, BinOp, Call, CmpOp, Expr, ExprKind, Name, Pattern, StmtKind};
use crate::lexer::{self, Token};
use crate::parser::lines::Line;
use crate::span::Span;

/// Parentheses and unary minuses nested deeper than this are left to the grammar, so the
/// reader's recursion stays shallow whatever the input.
const MAX_DEPTH: u32 = 64;

/// The line made of `tokens` (without its line break), or `None` to leave it to the
/// grammar. `tokens` is not empty: blank lines never reach here.
pub fn line<'s>(tokens: &[(Token, Span)], source: &'s str) -> Option<Line<'s>> {
    let mut r = Reader {
        tokens,
        pos: 0,
        source,
        depth: 0,
    };
    let line = r.statement()?;
    r.at_end().then_some(line)
}

struct Reader<'t, 's> {
    tokens: &'t [(Token, Span)],
    pos: usize,
    source: &'s str,
    depth: u32,
}

impl<'s> Reader<'_, 's> {
    fn peek(&self) -> Option<Token> {
        self.tokens.get(self.pos).map(|(t, _)| *t)
    }

    fn peek_second(&self) -> Option<Token> {
        self.tokens.get(self.pos + 1).map(|(t, _)| *t)
    }

    fn at_end(&self) -> bool {
        self.pos == self.tokens.len()
    }

    /// Takes the next token if it is `token`, returning its span.
    fn eat(&mut self, token: Token) -> Option<Span> {
        match self.tokens.get(self.pos) {
            Some(&(t, span)) if t == token => {
                self.pos += 1;
                Some(span)
            }
            _ => None,
        }
    }

    fn name(&mut self) -> Option<Name<'s>> {
        let span = self.eat(Token::Ident)?;
        Some(Name {
            text: span.slice(self.source),
            span,
        })
    }

    /// `line_content`: the choice of `named`, `if_head`, `simple_keywords`,
    /// `unbound_while`, `break_stmt`, `priority`, each decided by the first token.
    fn statement(&mut self) -> Option<Line<'s>> {
        let &(first, span) = self.tokens.first()?;
        match first {
            Token::Ident => self.named(),
            Token::If => {
                self.pos += 1;
                let cond = self.condition()?;
                Some(Line::IfHead {
                    keyword: span,
                    cond,
                })
            }
            Token::While => {
                self.pos += 1;
                let cond = self.condition()?;
                Some(Line::WhileHead {
                    bind: None,
                    keyword: span,
                    cond,
                })
            }
            Token::EndIf => self.keyword(Line::EndIf),
            Token::EndWhile => self.keyword(Line::EndWhile),
            Token::Check => self.keyword(Line::Check),
            Token::Checkend => self.keyword(Line::Checkend),
            Token::Break => {
                self.pos += 1;
                let p = lexer::break_pattern(self.source, span);
                Some(Line::Stmt(StmtKind::Break {
                    pattern: p.inner.map(|inner| Pattern {
                        text: inner.slice(self.source),
                        span: inner,
                        closed: p.closed,
                    }),
                }))
            }
            Token::Priority => {
                self.pos += 1;
                self.eat(Token::Assign)?;
                self.eat(Token::Highest)?;
                Some(Line::Stmt(StmtKind::Priority))
            }
            _ => None,
        }
    }

    fn keyword(&mut self, line: Line<'s>) -> Option<Line<'s>> {
        self.pos += 1;
        Some(line)
    }

    /// `named`: a name, then `:` (a skill header), `= after_assign`, `(args)` or nothing.
    fn named(&mut self) -> Option<Line<'s>> {
        let name = self.name()?;
        match self.peek() {
            Some(Token::Colon) => {
                self.pos += 1;
                Some(Line::SkillHeader(name, None))
            }
            Some(Token::Assign) => {
                self.pos += 1;
                self.after_assign(name)
            }
            Some(Token::LParen) => {
                let args = self.args()?;
                if self.peek() == Some(Token::Colon) {
                    // `NAME(a, b):`, a skill with parameters.
                    self.pos += 1;
                    return Some(Line::SkillHeader(name, Some(args)));
                }
                Some(Line::Stmt(StmtKind::Call {
                    bind: None,
                    call: Call {
                        name,
                        args: Some(args),
                    },
                }))
            }
            None => Some(Line::Stmt(StmtKind::Call {
                bind: None,
                call: Call { name, args: None },
            })),
            // `args.or_not()` takes nothing and the line break is then missing: an error.
            Some(_) => None,
        }
    }

    /// `after_assign`: `while(condition)`, `name(args)`, or an expression.
    fn after_assign(&mut self, target: Name<'s>) -> Option<Line<'s>> {
        match (self.peek(), self.peek_second()) {
            (Some(Token::While), _) => {
                let keyword = self.eat(Token::While)?;
                let cond = self.condition()?;
                Some(Line::WhileHead {
                    bind: Some(target),
                    keyword,
                    cond,
                })
            }
            // Once `name(` is read the grammar's `args` cannot fail, so the choice commits.
            (Some(Token::Ident), Some(Token::LParen)) => {
                let name = self.name()?;
                let args = self.args()?;
                Some(Line::Stmt(StmtKind::Call {
                    bind: Some(target),
                    call: Call {
                        name,
                        args: Some(args),
                    },
                }))
            }
            _ => {
                let value = self.expr()?;
                Some(Line::Stmt(StmtKind::Assign { target, value }))
            }
        }
    }

    /// `args`: `(` arguments separated by `,` `)`. An unclosed list, or one the grammar
    /// would end early, is declined: the grammar reports it.
    fn args(&mut self) -> Option<Args<'s>> {
        let open = self.eat(Token::LParen)?;
        let mut items = Vec::new();
        if self.peek() != Some(Token::RParen) {
            items.reserve_exact(self.count_args());
            loop {
                items.push(self.arg()?);
                if self.eat(Token::Comma).is_none() {
                    break;
                }
            }
        }
        let close = self.eat(Token::RParen)?;
        Some(Args {
            items: items.into_boxed_slice(),
            span: open.to(close),
            closed: true,
        })
    }

    /// How many arguments follow, by the commas outside parentheses before the list's
    /// `)`: one exact allocation instead of growing the list.
    fn count_args(&self) -> usize {
        let mut depth = 0usize;
        let mut count = 1;
        for &(token, _) in &self.tokens[self.pos..] {
            match token {
                Token::LParen => depth += 1,
                Token::RParen if depth == 0 => break,
                Token::RParen => depth -= 1,
                Token::Comma if depth == 0 => count += 1,
                _ => {}
            }
        }
        count
    }

    /// `setting.or(expr)`: `key = value` when a name is followed by `=`.
    fn arg(&mut self) -> Option<Arg<'s>> {
        if self.peek() == Some(Token::Ident) && self.peek_second() == Some(Token::Assign) {
            let key = self.name()?;
            self.pos += 1;
            // A setting whose value does not parse makes the grammar fall back to a
            // positional name followed by a stray `=`: an error, so decline.
            let value = self.expr()?;
            return Some(Arg::Setting {
                key,
                value: Box::new(value),
            });
        }
        self.expr().map(Arg::Positional)
    }

    /// `condition` in parentheses: an expression, optionally compared with another.
    fn condition(&mut self) -> Option<Expr<'s>> {
        self.eat(Token::LParen)?;
        let lhs = self.expr()?;
        let op = match self.peek() {
            Some(Token::Lt) => Some(CmpOp::Lt),
            Some(Token::Le) => Some(CmpOp::Le),
            Some(Token::EqEq | Token::Assign) => Some(CmpOp::Eq),
            Some(Token::NotEq) => Some(CmpOp::Ne),
            Some(Token::Gt) => Some(CmpOp::Gt),
            Some(Token::Ge | Token::GeAlt) => Some(CmpOp::Ge),
            _ => None,
        };
        let cond = match op {
            None => lhs,
            Some(op) => {
                let op_span = self.tokens[self.pos].1;
                self.pos += 1;
                let rhs = self.expr()?;
                Expr {
                    span: lhs.span.to(rhs.span),
                    kind: ExprKind::Compare {
                        op,
                        op_span,
                        lhs: Box::new(lhs),
                        rhs: Box::new(rhs),
                    },
                }
            }
        };
        self.eat(Token::RParen)?;
        Some(cond)
    }

    /// `expression`'s sum: products folded left over `+` and `-`. An operator without an
    /// operand leaves a token no caller accepts, so it is declined at once.
    fn expr(&mut self) -> Option<Expr<'s>> {
        let mut lhs = self.product()?;
        loop {
            let op = match self.peek() {
                Some(Token::Plus) => BinOp::Add,
                Some(Token::Minus) => BinOp::Sub,
                _ => return Some(lhs),
            };
            self.pos += 1;
            let rhs = self.product()?;
            lhs = binary(op, lhs, rhs);
        }
    }

    /// `expression`'s product: unary operands folded left over `*` and `/`.
    fn product(&mut self) -> Option<Expr<'s>> {
        let mut lhs = self.unary()?;
        loop {
            let op = match self.peek() {
                Some(Token::Star) => BinOp::Mul,
                Some(Token::Slash) => BinOp::Div,
                _ => return Some(lhs),
            };
            self.pos += 1;
            let rhs = self.unary()?;
            lhs = binary(op, lhs, rhs);
        }
    }

    /// `unary`: minuses folded right onto an atom.
    fn unary(&mut self) -> Option<Expr<'s>> {
        let Some(minus) = self.eat(Token::Minus) else {
            return self.atom();
        };
        let operand = self.nested(Self::unary)?;
        Some(Expr {
            span: minus.to(operand.span),
            kind: ExprKind::Neg(Box::new(operand)),
        })
    }

    /// `atom`: a number, a name, or an expression in parentheses (which keeps the inner
    /// expression's kind under the span of the parentheses).
    fn atom(&mut self) -> Option<Expr<'s>> {
        let &(token, span) = self.tokens.get(self.pos)?;
        let kind = match token {
            Token::Number => ExprKind::Number(lexer::number(span.slice(self.source))),
            Token::Ident => ExprKind::Name(Name {
                text: span.slice(self.source),
                span,
            }),
            Token::LParen => {
                self.pos += 1;
                let inner = self.nested(Self::expr)?;
                let close = self.eat(Token::RParen)?;
                return Some(Expr {
                    kind: inner.kind,
                    span: span.to(close),
                });
            }
            _ => return None,
        };
        self.pos += 1;
        Some(Expr { kind, span })
    }

    fn nested(&mut self, f: fn(&mut Self) -> Option<Expr<'s>>) -> Option<Expr<'s>> {
        if self.depth >= MAX_DEPTH {
            return None;
        }
        self.depth += 1;
        let e = f(self);
        self.depth -= 1;
        e
    }
}

fn binary<'s>(op: BinOp, lhs: Expr<'s>, rhs: Expr<'s>) -> Expr<'s> {
    Expr {
        span: lhs.span.to(rhs.span),
        kind: ExprKind::Binary {
            op,
            lhs: Box::new(lhs),
            rhs: Box::new(rhs),
        },
    }
}

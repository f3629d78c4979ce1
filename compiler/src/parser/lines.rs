//! The grammar of one line, in chumsky. ILMR is line-oriented (one statement per line,
//! `endif` on its own line), so the parser reads a flat sequence of lines and recovers
//! from an error by skipping to the end of the broken line; `blocks.rs` nests the lines.

use chumsky::extra::ParserExtra;
use chumsky::input::{Input, ValueInput};
use chumsky::label::LabelError;
use chumsky::prelude::*;

use crate::ast::{Arg, Args, BinOp, Call, CmpOp, Expr, ExprKind, Name, Pattern, StmtKind};
use crate::lexer::Token;
use crate::span::Span;

pub type ParseError<'t> = Rich<'t, Token, Span>;

/// What one line holds before lines are nested into blocks.
#[derive(Debug, Clone)]
pub enum Line<'s> {
    Blank,
    Stmt(StmtKind<'s>),
    IfHead {
        keyword: Span,
        cond: Expr<'s>,
    },
    WhileHead {
        bind: Option<Name<'s>>,
        keyword: Span,
        cond: Expr<'s>,
    },
    EndIf,
    EndWhile,
    Check,
    Checkend,
    /// `NAME:`, or `NAME(parameters):`.
    SkillHeader(Name<'s>, Option<Args<'s>>),
}

#[derive(Debug, Clone)]
pub struct ParsedLine<'s> {
    pub line: Line<'s>,
    /// The line's content without the line break.
    pub span: Span,
}

/// Parses a token stream that ends with a `Newline` (the lexer guarantees it).
///
/// Most files parse without error, and building chumsky's rich errors for every
/// alternative a `choice` rejects on the way costs more than the parse itself. So the
/// file is first parsed with errors that cost nothing, and parsed again with rich ones
/// only when something failed.
pub fn parse_lines<'t, 's: 't>(
    tokens: &'t [(Token, Span)],
    source: &'s str,
) -> (Vec<ParsedLine<'s>>, Vec<ParseError<'t>>) {
    let eoi = Span::empty(source.len());
    let (lines, errors) = file_parser::<_, extra::Default>(source)
        .parse(tokens.map(eoi, |(t, s)| (t, s)))
        .into_output_errors();
    if let (Some(lines), true) = (lines, errors.is_empty()) {
        return (lines, Vec::new());
    }
    let (lines, errors) = file_parser::<_, extra::Err<ParseError<'t>>>(source)
        .parse(tokens.map(eoi, |(t, s)| (t, s)))
        .into_output_errors();
    (lines.unwrap_or_default(), errors)
}

fn file_parser<'t, 's: 't, I, E>(source: &'s str) -> impl Parser<'t, I, Vec<ParsedLine<'s>>, E>
where
    I: ValueInput<'t, Token = Token, Span = Span>,
    E: ParserExtra<'t, I> + 't,
    E::Error: LabelError<'t, I, &'static str>,
{
    let content = line_content(source)
        .or_not()
        .map_with(|line, e| ParsedLine {
            line: line.unwrap_or(Line::Blank),
            span: e.span(),
        });

    // A line that does not parse is kept, as an error node spanning the line, so that the
    // next lines are read as if nothing had happened. A broken `if(` or `while(` line still
    // opens its block, or its `endif` would be reported a second time as stray.
    let rest = any().filter(|t: &Token| *t != Token::Newline).repeated();
    let broken_if = just(Token::If)
        .map_with(|_, e| e.span())
        .then_ignore(rest)
        .map_with(|keyword: Span, e| Line::IfHead {
            keyword,
            cond: error_expr(e.span()),
        });
    let broken_while = name(source)
        .then_ignore(just(Token::Assign))
        .or_not()
        .then(just(Token::While).map_with(|_, e| e.span()))
        .then_ignore(rest)
        .map_with(|(bind, keyword), e| Line::WhileHead {
            bind,
            keyword,
            cond: error_expr(e.span()),
        });
    let broken_line = choice((
        broken_if,
        broken_while,
        rest.to(Line::Stmt(StmtKind::Error)),
    ))
    .map_with(|line, e| ParsedLine {
        line,
        span: e.span(),
    });

    content
        .then_ignore(just(Token::Newline))
        .recover_with(via_parser(broken_line.then_ignore(just(Token::Newline))))
        .repeated()
        .collect()
        .then_ignore(end())
}

fn error_expr<'s>(span: Span) -> Expr<'s> {
    Expr {
        kind: ExprKind::Error,
        span,
    }
}

fn name<'t, 's: 't, I, E>(source: &'s str) -> impl Parser<'t, I, Name<'s>, E> + Clone
where
    I: ValueInput<'t, Token = Token, Span = Span>,
    E: ParserExtra<'t, I> + 't,
    E::Error: LabelError<'t, I, &'static str>,
{
    just(Token::Ident)
        .map_with(move |_, e| {
            let span: Span = e.span();
            Name {
                text: span.slice(source),
                span,
            }
        })
        .labelled("name")
}

fn line_content<'t, 's: 't, I, E>(source: &'s str) -> impl Parser<'t, I, Line<'s>, E>
where
    I: ValueInput<'t, Token = Token, Span = Span>,
    E: ParserExtra<'t, I> + 't,
    E::Error: LabelError<'t, I, &'static str>,
{
    let expr = expression(source);
    let condition = condition(expr.clone())
        .delimited_by(just(Token::LParen), just(Token::RParen))
        .labelled("condition in parentheses");

    let if_head = just(Token::If)
        .map_with(|_, e| e.span())
        .then(condition.clone())
        .map(|(keyword, cond)| Line::IfHead { keyword, cond });

    let while_head = just(Token::While)
        .map_with(|_, e| e.span())
        .then(condition.clone());
    let unbound_while = while_head.clone().map(|(keyword, cond)| Line::WhileHead {
        bind: None,
        keyword,
        cond,
    });

    let simple_keywords = select! {
        Token::EndIf => Line::EndIf,
        Token::EndWhile => Line::EndWhile,
        Token::Check => Line::Check,
        Token::Checkend => Line::Checkend,
    };

    let break_stmt = just(Token::Break).map_with(move |_, e| {
        let p = crate::lexer::break_pattern(source, e.span());
        Line::Stmt(StmtKind::Break {
            pattern: p.inner.map(|span| Pattern {
                text: span.slice(source),
                span,
                closed: p.closed,
            }),
        })
    });

    let priority = just(Token::Priority)
        .then(just(Token::Assign))
        .then(just(Token::Highest).labelled("`highest`"))
        .to(Line::Stmt(StmtKind::Priority));

    let args = args(source, expr.clone());

    // Most lines start with a name (`v = ...`, `name(...)`, `NAME:`): read it once and
    // decide by what follows.
    let after_assign = choice((
        while_head.map(|(keyword, cond)| Rhs::While(keyword, cond)),
        name(source).then(args.clone()).map(|(name, args)| {
            Rhs::Call(Call {
                name,
                args: Some(args),
            })
        }),
        expr.labelled("expression").map(Rhs::Expr),
    ));
    let after_name = choice((
        just(Token::Colon).to(Tail::Header(None)),
        just(Token::Assign)
            .ignore_then(after_assign)
            .map(Tail::Assign),
        // A colon after a call makes it a header with parameters; a statement ends
        // there, so where one is broken the colon is not offered: it is told as the
        // end of the line.
        args.or_not()
            .then(just(Token::Colon).labelled("end of line").or_not())
            .map(|(args, colon)| match (args, colon) {
                // `NAME(a, b):`, a skill with parameters.
                (args, Some(_)) => Tail::Header(args),
                (args, None) => Tail::Call(args),
            }),
    ));
    let named = name(source)
        .then(after_name)
        .map(|(name, tail)| match tail {
            Tail::Header(params) => Line::SkillHeader(name, params),
            Tail::Call(args) => Line::Stmt(StmtKind::Call {
                bind: None,
                call: Call { name, args },
            }),
            Tail::Assign(Rhs::While(keyword, cond)) => Line::WhileHead {
                bind: Some(name),
                keyword,
                cond,
            },
            Tail::Assign(Rhs::Call(call)) => Line::Stmt(StmtKind::Call {
                bind: Some(name),
                call,
            }),
            Tail::Assign(Rhs::Expr(value)) => Line::Stmt(StmtKind::Assign {
                target: name,
                value,
            }),
        });

    choice((
        named,
        if_head,
        simple_keywords,
        unbound_while,
        break_stmt,
        priority,
    ))
    .labelled("statement")
}

/// What follows a line's first name.
#[derive(Clone)]
enum Tail<'s> {
    Header(Option<Args<'s>>),
    Assign(Rhs<'s>),
    Call(Option<Args<'s>>),
}

#[derive(Clone)]
enum Rhs<'s> {
    While(Span, Expr<'s>),
    Call(Call<'s>),
    Expr(Expr<'s>),
}

/// `(args)`. An unclosed argument list still yields the call, so that an editor can
/// complete inside it; `parser::parse` reports it.
fn args<'t, 's: 't, I, E>(
    source: &'s str,
    expr: impl Parser<'t, I, Expr<'s>, E> + Clone,
) -> impl Parser<'t, I, Args<'s>, E> + Clone
where
    I: ValueInput<'t, Token = Token, Span = Span>,
    E: ParserExtra<'t, I> + 't,
    E::Error: LabelError<'t, I, &'static str>,
{
    let setting = name(source)
        .then_ignore(just(Token::Assign))
        .then(expr.clone().labelled("value"))
        .map(|(key, value)| Arg::Setting {
            key,
            value: Box::new(value),
        });
    let arg = setting.or(expr.map(Arg::Positional)).labelled("argument");
    just(Token::LParen)
        .ignore_then(arg.separated_by(just(Token::Comma)).collect::<Vec<_>>())
        .then(just(Token::RParen).or_not())
        .map_with(|(items, close), e| Args {
            items: items.into_boxed_slice(),
            span: e.span(),
            closed: close.is_some(),
        })
}

fn condition<'t, 's: 't, I, E>(
    expr: impl Parser<'t, I, Expr<'s>, E> + Clone,
) -> impl Parser<'t, I, Expr<'s>, E> + Clone
where
    I: ValueInput<'t, Token = Token, Span = Span>,
    E: ParserExtra<'t, I> + 't,
    E::Error: LabelError<'t, I, &'static str>,
{
    // Section 4.5.5 writes `=` and `=>` in conditions; inside a condition they can only
    // mean comparison, so they are read as `==` and `>=`.
    let op = select! {
        Token::Lt => CmpOp::Lt,
        Token::Le => CmpOp::Le,
        Token::EqEq => CmpOp::Eq,
        Token::Assign => CmpOp::Eq,
        Token::NotEq => CmpOp::Ne,
        Token::Gt => CmpOp::Gt,
        Token::Ge => CmpOp::Ge,
        Token::GeAlt => CmpOp::Ge,
    }
    .map_with(|op, e| (op, e.span()))
    .labelled("comparison");
    expr.clone()
        .then(op.then(expr).or_not())
        .map(|(lhs, cmp)| match cmp {
            None => lhs,
            Some(((op, op_span), rhs)) => Expr {
                span: lhs.span.to(rhs.span),
                kind: ExprKind::Compare {
                    op,
                    op_span,
                    lhs: Box::new(lhs),
                    rhs: Box::new(rhs),
                },
            },
        })
}

/// Arithmetic: `+ - * /`, unary minus and parentheses over numbers and names.
fn expression<'t, 's: 't, I, E>(source: &'s str) -> impl Parser<'t, I, Expr<'s>, E> + Clone
where
    I: ValueInput<'t, Token = Token, Span = Span>,
    E: ParserExtra<'t, I> + 't,
    E::Error: LabelError<'t, I, &'static str>,
{
    recursive(|expr| {
        let atom = select! {
            Token::Number => true,
            Token::Ident => false,
        }
        .map_with(move |is_number, e| {
            let span: Span = e.span();
            let text = span.slice(source);
            let kind = if is_number {
                ExprKind::Number(crate::lexer::number(text))
            } else {
                ExprKind::Name(Name { text, span })
            };
            Expr { kind, span }
        })
        .or(expr
            .delimited_by(just(Token::LParen), just(Token::RParen))
            .map_with(|inner: Expr<'s>, e| Expr {
                kind: inner.kind,
                span: e.span(),
            }))
        .labelled("number or name");

        let unary = just(Token::Minus)
            .map_with(|_, e| e.span())
            .repeated()
            .foldr(atom, |minus: Span, operand: Expr<'s>| Expr {
                span: minus.to(operand.span),
                kind: ExprKind::Neg(Box::new(operand)),
            });

        let binary = |op: BinOp, lhs: Expr<'s>, rhs: Expr<'s>| Expr {
            span: lhs.span.to(rhs.span),
            kind: ExprKind::Binary {
                op,
                lhs: Box::new(lhs),
                rhs: Box::new(rhs),
            },
        };

        let product_op = select! { Token::Star => BinOp::Mul, Token::Slash => BinOp::Div };
        let product = unary
            .clone()
            .foldl(product_op.then(unary).repeated(), move |lhs, (op, rhs)| {
                binary(op, lhs, rhs)
            });

        let sum_op = select! { Token::Plus => BinOp::Add, Token::Minus => BinOp::Sub };
        product
            .clone()
            .foldl(sum_op.then(product).repeated(), move |lhs, (op, rhs)| {
                binary(op, lhs, rhs)
            })
    })
}

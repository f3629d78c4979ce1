//! Renders a syntax tree one node per line, with byte spans, for snapshot tests and
//! `ilmrc parse`.

use std::fmt::Write;

use crate::ast::{Arg, Block, Call, Conditional, Expr, ExprKind, FileKind, SourceFile, StmtKind};

pub fn render(file: &SourceFile<'_>) -> String {
    let mut out = String::new();
    let kind = match file.kind {
        FileKind::Task => "Task",
        FileKind::Skills => "Skills",
    };
    line(&mut out, 0, format_args!("{kind} {}", span(file.span)));
    blocks(&mut out, 1, &file.blocks);
    for skill in &file.skills {
        line(
            &mut out,
            1,
            format_args!("Skill {} {}", skill.name.text, span(skill.span)),
        );
        blocks(&mut out, 2, &skill.blocks);
    }
    out
}

fn span(s: crate::Span) -> String {
    format!("@{}..{}", s.start, s.end)
}

fn line(out: &mut String, depth: usize, text: std::fmt::Arguments<'_>) {
    for _ in 0..depth {
        out.push_str("  ");
    }
    let _ = out.write_fmt(text);
    out.push('\n');
}

fn blocks(out: &mut String, depth: usize, list: &[Block<'_>]) {
    for block in list {
        line(out, depth, format_args!("Block {}", span(block.span)));
        for stmt in &block.stmts {
            let at = span(stmt.span);
            match &stmt.kind {
                StmtKind::Call { bind, call: c } => {
                    let bind = bind.map_or(String::new(), |b| format!("{} = ", b.text));
                    line(
                        out,
                        depth + 1,
                        format_args!("Call {bind}{} {at}", c.name.text),
                    );
                    call_args(out, depth + 2, c);
                }
                StmtKind::Assign { target, value } => {
                    line(out, depth + 1, format_args!("Assign {} {at}", target.text));
                    expr(out, depth + 2, value);
                }
                StmtKind::If(c) => conditional(out, depth + 1, "If", None, c, at),
                StmtKind::While { bind, body } => {
                    conditional(out, depth + 1, "While", bind.map(|b| b.text), body, at)
                }
                StmtKind::Check { body, end } => {
                    let end = if end.is_some() { "" } else { " (unclosed)" };
                    line(out, depth + 1, format_args!("Check {at}{end}"));
                    blocks(out, depth + 2, body);
                }
                StmtKind::Break { pattern } => match pattern {
                    Some(p) => line(out, depth + 1, format_args!("Break {:?} {at}", p.text)),
                    None => line(out, depth + 1, format_args!("Break {at}")),
                },
                StmtKind::Priority => line(out, depth + 1, format_args!("Priority {at}")),
                StmtKind::Error => line(out, depth + 1, format_args!("Error {at}")),
            }
        }
    }
}

fn conditional(
    out: &mut String,
    depth: usize,
    word: &str,
    bind: Option<&str>,
    c: &Conditional<'_>,
    at: String,
) {
    let bind = bind.map_or(String::new(), |b| format!("{b} = "));
    let end = if c.end.is_some() { "" } else { " (unclosed)" };
    line(out, depth, format_args!("{bind}{word} {at}{end}"));
    expr(out, depth + 1, &c.cond);
    blocks(out, depth + 1, &c.body);
}

fn call_args(out: &mut String, depth: usize, call: &Call<'_>) {
    let Some(args) = &call.args else { return };
    if !args.closed {
        line(out, depth, format_args!("(unclosed {})", span(args.span)));
    }
    for arg in &args.items {
        match arg {
            Arg::Positional(e) => expr(out, depth, e),
            Arg::Setting { key, value } => {
                line(
                    out,
                    depth,
                    format_args!("Setting {} {}", key.text, span(key.span)),
                );
                expr(out, depth + 1, value);
            }
        }
    }
}

fn expr(out: &mut String, depth: usize, e: &Expr<'_>) {
    let at = span(e.span);
    match &e.kind {
        ExprKind::Number(n) => line(out, depth, format_args!("Number {n} {at}")),
        ExprKind::Name(n) => line(out, depth, format_args!("Name {} {at}", n.text)),
        ExprKind::Neg(inner) => {
            line(out, depth, format_args!("Neg {at}"));
            expr(out, depth + 1, inner);
        }
        ExprKind::Binary { op, lhs, rhs } => {
            line(out, depth, format_args!("Binary {} {at}", op.symbol()));
            expr(out, depth + 1, lhs);
            expr(out, depth + 1, rhs);
        }
        ExprKind::Compare { op, lhs, rhs, .. } => {
            line(out, depth, format_args!("Compare {} {at}", op.symbol()));
            expr(out, depth + 1, lhs);
            expr(out, depth + 1, rhs);
        }
        ExprKind::Error => line(out, depth, format_args!("Error {at}")),
    }
}

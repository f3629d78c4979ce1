//! Source text to syntax tree. Parsing never fails: it returns the tree and the
//! diagnostics together, one diagnostic per broken line.

mod blocks;
mod lines;

use chumsky::error::{RichPattern, RichReason};

use crate::ast::{SourceFile, StmtKind};
use crate::diagnostic::{Code, Diagnostic, FileId};
use crate::lexer::{self, Token};
use crate::span::Span;

pub struct Parsed<'s> {
    pub file: SourceFile<'s>,
    pub diagnostics: Vec<Diagnostic>,
}

pub fn parse(source: &str, file: FileId) -> Parsed<'_> {
    let lexed = lexer::lex(source);
    let mut tokens = lexed.tokens;
    // The line grammar ends every line with a line break; give the last line one.
    if tokens.last().is_none_or(|(t, _)| *t != Token::Newline) {
        tokens.push((Token::Newline, Span::empty(source.len())));
    }
    let mut diagnostics = Vec::new();
    for (token, span) in &tokens {
        if *token == Token::Break {
            if !lexer::break_pattern(source, *span).closed {
                diagnostics.push(
                    Diagnostic::new(
                        Code::UnclosedPattern,
                        file,
                        *span,
                        "`break(` has no closing `)`",
                    )
                    .with_label("the pattern runs to the end of the line"),
                );
            }
        }
    }
    let (lines, errors) = lines::parse_lines(&tokens, source);
    diagnostics.extend(
        errors
            .into_iter()
            .map(|e| syntax_diagnostic(e, file, source)),
    );
    let tree = blocks::build(lines, source, lexed.comments, file, &mut diagnostics);
    tree.for_each_stmt(&mut |stmt| {
        if let StmtKind::Call { call, .. } = &stmt.kind {
            if let Some(args) = call.args.as_ref().filter(|a| !a.closed) {
                let at = Span::empty(args.span.end as usize);
                diagnostics.push(
                    Diagnostic::new(
                        Code::UnclosedArgs,
                        file,
                        at,
                        "this argument list has no closing `)`",
                    )
                    .with_label("`)` expected here")
                    .with_fix("insert `)`", at, ")"),
                );
            }
        }
    });
    diagnostics.sort_by_key(|d| (d.span.start, d.code));
    Parsed {
        file: tree,
        diagnostics,
    }
}

fn syntax_diagnostic(error: lines::ParseError<'_>, file: FileId, source: &str) -> Diagnostic {
    let span = *error.span();
    match error.reason() {
        RichReason::Custom(message) => Diagnostic::new(Code::Syntax, file, span, message.clone()),
        RichReason::ExpectedFound { found, .. } => {
            let found = found.as_deref().map_or("end of file".to_string(), |t| {
                describe(t, span.slice(source))
            });
            let mut expected: Vec<String> = error
                .expected()
                .filter_map(|p| match p {
                    RichPattern::Token(t) => Some(t.to_string()),
                    RichPattern::Label(l) => Some(l.to_string()),
                    RichPattern::Identifier(i) => Some(format!("`{i}`")),
                    RichPattern::EndOfInput => Some("end of file".into()),
                    _ => None,
                })
                .collect();
            expected.sort();
            expected.dedup();
            let message = format!("unexpected {found}");
            let label = match expected.as_slice() {
                [] => format!("{found} is not expected here"),
                [one] => format!("expected {one}"),
                [init @ .., last] => format!("expected {} or {last}", init.join(", ")),
            };
            Diagnostic::new(Code::Syntax, file, span, message).with_label(label)
        }
    }
}

/// A found token, with its text where that helps.
fn describe(token: &Token, text: &str) -> String {
    match token {
        Token::Ident => format!("name `{text}`"),
        Token::Number => format!("number `{text}`"),
        other => other.to_string(),
    }
}

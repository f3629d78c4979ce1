//! Source text to syntax tree. Parsing never fails: it returns the tree and the
//! diagnostics together, one diagnostic per broken line.

#[cfg(test)]
mod agreement;
mod blocks;
pub use blocks::Seen;
mod characters;
mod fast;
mod hints;
mod lines;

use chumsky::error::{RichPattern, RichReason};

use crate::ast::{Block, Expr, ExprKind, FileKind, Name, SourceFile, StmtKind};
use crate::diagnostic::{Code, Diagnostic, FileId};
use crate::kept::{Kept, Past};
use crate::lexer::{self, Token};
use crate::limits;
use crate::parser::lines::{Line, ParsedLine};
use crate::span::Span;

pub struct Parsed<'s> {
    pub file: SourceFile<'s>,
    /// The first [`limits::MAX_DIAGNOSTICS`] in source order.
    pub diagnostics: Vec<Diagnostic>,
    /// Those past the limit, counted.
    pub past: Past,
    /// Whether the file has a `break(` with a pattern. When false, no statement of the
    /// tree is a `Break` with a pattern, and the checker need not look for one.
    pub break_patterns: bool,
    /// Statements that bind a variable: at least as many as the file's variables.
    pub binds: usize,
    /// What the passes after the checker's walk look for (`blocks::Seen`).
    pub seen: blocks::Seen,
}

/// Line by line: the hand-written reader takes the lines it recognises, and the chumsky
/// grammar each line it declines (every broken line among them), so a file costs the
/// grammar's price only where it is unusual. Tokens are read a line at a time into one
/// reused buffer; the file's tokens are never held at once.
pub fn parse<'s>(source: &'s str, file: FileId) -> Parsed<'s> {
    read(source, file, None::<fn(Block<'s>, bool) -> bool>)
        .expect("a parse that streams nothing is never given up")
}

/// A task file read block by block (`ilmrc check`'s streaming check, `check/stream.rs`):
/// each top-level block goes to `sink` as soon as its last line is read, and is not
/// kept in the tree, so a large task is never held whole. `None` as soon as the file
/// is anything but a task without diagnostics, breaks with patterns or statements that
/// never end (what the checker's passes after the walk need the whole tree for), or
/// when `sink` returns false: the caller then parses and checks it as usual. With each
/// block `sink` is told whether it may call `record`, `createpath` or `followpath`
/// (false: it calls none of them).
pub fn parse_streamed<'s>(
    source: &'s str,
    file: FileId,
    sink: impl FnMut(Block<'s>, bool) -> bool,
) -> Option<Parsed<'s>> {
    read(source, file, Some(sink))
}

fn read<'s, F: FnMut(Block<'s>, bool) -> bool>(
    source: &'s str,
    file: FileId,
    sink: Option<F>,
) -> Option<Parsed<'s>> {
    let mut tokens = lexer::Tokens::new(source);
    let mut line: Vec<(Token, Span)> = Vec::new();
    let mut patterns = Kept::new();
    let mut syntax = Kept::new();
    let mut sink = sink;
    let mut out = Emit {
        builder: blocks::Builder::new(source, file),
        unclosed: Kept::new(),
        file,
    };
    // The grammar spans an empty line from its line break back to the end of the token
    // before (the end of the file when there is none); the reader does the same.
    let mut previous_end = source.len() as u32;
    let mut ended = false;
    let mut break_patterns = false;
    // Whether the line holds text the lexer could not read: only then is it searched
    // for characters that stand for something.
    let mut unreadable = false;
    loop {
        let (token, span) = match tokens.next() {
            Some(next) => next,
            None if ended => break,
            // The line grammar ends every line with a line break; the last line gets one.
            None => (Token::Newline, Span::empty(source.len())),
        };
        ended = token == Token::Newline;
        if token != Token::Newline {
            if token == Token::Break {
                break_patterns |= lexer::break_pattern(source, span).inner.is_some();
                patterns.extend(unclosed_pattern(source, span, file));
            }
            unreadable |= token == Token::Error;
            line.push((token, span));
            continue;
        }
        if std::mem::take(&mut unreadable) {
            syntax.extend(characters::read_through(&mut line, source, file));
        }
        // Only a line of more tokens than the limit can pass it.
        let too_complex = (line.len() > limits::MAX_LINE_OPERATORS)
            .then(|| limits::operators_past_limit(&line))
            .flatten();
        match (line.first(), line.last(), too_complex) {
            (Some(_), Some(_), Some(at)) => {
                syntax.push(too_complex_diagnostic(at, file));
                out.line(unparsed_line(&line, source));
            }
            (Some(&(_, first)), Some(&(_, last)), None) => {
                let whole = Span {
                    start: first.start,
                    end: last.end,
                };
                if let Some((meant, d)) = hints::block_end(&line, source, file) {
                    syntax.push(d);
                    out.line(ParsedLine {
                        line: meant,
                        span: whole,
                    });
                } else if let Some(parsed) = fast::line(&line, source) {
                    out.line(ParsedLine {
                        line: parsed,
                        span: whole,
                    });
                } else if !syntax.admits(file, whole) {
                    // Past the diagnostics' limit the grammar's error recovery, its
                    // dearest path, would only feed a count: the line is read for
                    // what it opens and binds, as an unparsed one is.
                    syntax.count_dropped(Code::Syntax);
                    out.line(unparsed_line(&line, source));
                } else {
                    line.push((token, span));
                    let (lines, errors) = lines::parse_lines(&line, source);
                    let (diagnostics, read_as) = explained_errors(&line, errors, file, source);
                    syntax.extend(diagnostics);
                    for parsed in read_as.unwrap_or(lines) {
                        out.line(parsed);
                    }
                }
            }
            _ => out.line(ParsedLine {
                line: Line::Blank,
                span: Span {
                    start: span.start,
                    end: previous_end,
                },
            }),
        }
        previous_end = span.end;
        line.clear();
        // Whether to give up is asked only as blocks finish: what was read since
        // then is read again anyway when the caller parses the file as usual.
        if let Some(sink) = sink.as_mut()
            && out.builder.has_ready()
        {
            if break_patterns
                || out.builder.refuses_streaming()
                || !(patterns.is_empty() && syntax.is_empty() && out.unclosed.is_empty())
            {
                return None;
            }
            let paths = out.builder.take_paths();
            for block in out.builder.ready() {
                if !sink(block, paths) {
                    return None;
                }
            }
        }
    }
    let Emit {
        mut builder,
        unclosed,
        ..
    } = out;
    let binds = builder.binds;
    let seen = builder.seen;
    let refused = builder.refuses_streaming();
    let builder_paths = builder.take_paths();
    let (mut tree, structure) = builder.finish(tokens.comments);
    if let Some(mut sink) = sink {
        if refused
            || break_patterns
            || !(patterns.is_empty()
                && syntax.is_empty()
                && unclosed.is_empty()
                && structure.is_empty())
            || tree.kind != FileKind::Task
        {
            return None;
        }
        let paths = builder_paths;
        for block in std::mem::take(&mut tree.blocks) {
            if !sink(block, paths) {
                return None;
            }
        }
    }
    let mut parsed = finish(
        tree,
        [patterns, syntax, structure, unclosed],
        break_patterns,
    );
    parsed.binds = binds;
    parsed.seen = seen;
    Some(parsed)
}

/// Where parsed lines go: the block builder, and the check that argument lists close.
struct Emit<'s> {
    builder: blocks::Builder<'s>,
    unclosed: Kept,
    file: FileId,
}

impl<'s> Emit<'s> {
    fn line(&mut self, parsed: ParsedLine<'s>) {
        if let Some(d) = unclosed_args(&parsed.line, self.file) {
            self.unclosed.push(d);
        }
        self.builder.line(parsed);
    }
}

/// A line past [`limits::MAX_LINE_OPERATORS`], which is not parsed: what it opens (so
/// that its `endif` still matches) and what it binds are kept, its expressions become
/// errors.
fn unparsed_line<'s>(line: &[(Token, Span)], source: &'s str) -> ParsedLine<'s> {
    let (first, last) = (line[0].1, line[line.len() - 1].1);
    let span = first.to(last);
    let rest = |from: usize| Expr {
        kind: ExprKind::Error,
        span: line
            .get(from)
            .map_or(Span::empty(last.end as usize), |&(_, s)| s.to(last)),
    };
    let name = |span: Span| Name {
        text: span.slice(source),
        span,
    };
    let line = match line {
        [(Token::If, _), ..] => Line::IfHead {
            keyword: first,
            cond: rest(1),
        },
        [(Token::While, _), ..] => Line::WhileHead {
            bind: None,
            keyword: first,
            cond: rest(1),
        },
        [
            (Token::Ident, _),
            (Token::Assign, _),
            (Token::While, keyword),
            ..,
        ] => Line::WhileHead {
            bind: Some(name(first)),
            keyword: *keyword,
            cond: rest(3),
        },
        // The variable stays bound, so its later uses are not reported as well.
        [(Token::Ident, _), (Token::Assign, _), ..] => Line::Stmt(StmtKind::Assign {
            target: name(first),
            value: rest(2),
        }),
        _ => Line::Stmt(StmtKind::Error),
    };
    ParsedLine { line, span }
}

fn too_complex_diagnostic(at: Span, file: FileId) -> Diagnostic {
    Diagnostic::new(
        Code::TooComplex,
        file,
        at,
        format!(
            "this line holds more than {} operators and parentheses",
            limits::MAX_LINE_OPERATORS
        ),
    )
    .with_label("the limit is passed here; the line is not checked further")
    .with_help("split the expression into several assignments")
}

/// Diagnostics in source order; those at one place keep the order of their kinds.
fn finish<'s>(tree: SourceFile<'s>, kinds: [Kept; 4], break_patterns: bool) -> Parsed<'s> {
    let mut all = Kept::new();
    for kind in kinds {
        let (list, past) = kind.finish();
        all.extend(list);
        all.add_past(past);
    }
    let (diagnostics, past) = all.finish();
    Parsed {
        file: tree,
        diagnostics,
        past,
        break_patterns,
        binds: 0,
        seen: blocks::Seen::default(),
    }
}

fn unclosed_pattern(source: &str, span: Span, file: FileId) -> Option<Diagnostic> {
    if lexer::break_pattern(source, span).closed {
        return None;
    }
    Some(
        Diagnostic::new(
            Code::UnclosedPattern,
            file,
            span,
            "`break(` has no closing `)`",
        )
        .with_label("the pattern runs to the end of the line"),
    )
}

fn unclosed_args(line: &Line<'_>, file: FileId) -> Option<Diagnostic> {
    let Line::Stmt(StmtKind::Call { call, .. }) = line else {
        return None;
    };
    let args = call.args.as_ref().filter(|a| !a.closed)?;
    let at = Span::empty(args.span.end as usize);
    Some(
        Diagnostic::new(
            Code::UnclosedArgs,
            file,
            at,
            "this argument list has no closing `)`",
        )
        .with_label("`)` expected here")
        .with_fix("insert `)`", at, ")"),
    )
}

/// The grammar's errors on one line (ending in its line break), or the one diagnostic
/// that explains them with, where it can be told, what the line is read as instead.
fn explained_errors<'s>(
    line: &[(Token, Span)],
    errors: Vec<lines::ParseError<'_>>,
    file: FileId,
    source: &'s str,
) -> (Vec<Diagnostic>, Option<Vec<ParsedLine<'s>>>) {
    let (content, newline) = line.split_at(line.len().saturating_sub(1));
    match errors
        .first()
        .and_then(|e| hints::explain(content, source, file, *e.span()))
    {
        Some(explained) => {
            let read_as = explained.read_as.and_then(|mut tokens| {
                tokens.extend_from_slice(newline);
                let (lines, errors) = lines::parse_lines(&tokens, source);
                errors.is_empty().then_some(lines)
            });
            (vec![explained.diagnostic], read_as)
        }
        None => (
            errors
                .into_iter()
                .map(|e| syntax_diagnostic(e, file, source))
                .collect(),
            None,
        ),
    }
}

fn syntax_diagnostic(error: lines::ParseError<'_>, file: FileId, source: &str) -> Diagnostic {
    let span = *error.span();
    match error.reason() {
        RichReason::Custom(message) => Diagnostic::new(Code::Syntax, file, span, message.clone()),
        RichReason::ExpectedFound { found, .. } => {
            let found_token = found.as_deref().copied();
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
            // Text the lexer could not read is a character ILMR does not have.
            let code = match found_token {
                Some(Token::Error) => Code::UnusualCharacter,
                _ => Code::Syntax,
            };
            let d = Diagnostic::new(code, file, span, message).with_label(label);
            match span
                .slice(source)
                .chars()
                .next()
                .and_then(characters::advice)
            {
                Some(advice) if code == Code::UnusualCharacter => d.with_help(advice),
                _ => d,
            }
        }
    }
}

/// A found token, with its text where that helps.
fn describe(token: &Token, text: &str) -> String {
    match token {
        Token::Ident => format!("name `{text}`"),
        Token::Number => format!("number `{text}`"),
        Token::Error => {
            let named: Vec<String> = text.chars().map(characters::describe).collect();
            format!("character {}", named.join(" "))
        }
        other => other.to_string(),
    }
}

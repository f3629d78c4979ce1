//! Tokens of ILMR. Lexing never fails: text it cannot read becomes an `Error` token so
//! that the parser can report it in place and go on.

use std::fmt;

use logos::Logos;

use crate::span::Span;

#[derive(Logos, Debug, Clone, Copy, PartialEq)]
#[logos(skip r"[ \t\f\r]+")]
pub enum Token<'s> {
    /// A line break: statements are one per line and an empty line separates blocks.
    #[token("\n")]
    Newline,

    #[regex(r"//[^\n]*", allow_greedy = true)]
    Comment,

    #[regex(r"[0-9]+(\.[0-9]*)?|\.[0-9]+", |lex| lex.slice().parse::<f64>().ok())]
    Number(f64),

    #[regex(r"[\p{L}_][\p{L}\p{N}_]*")]
    Ident(&'s str),

    #[token("if", ignore(case))]
    If,
    #[token("endif", ignore(case))]
    EndIf,
    #[token("while", ignore(case))]
    While,
    #[token("endwhile", ignore(case))]
    EndWhile,
    #[token("check", ignore(case))]
    Check,
    #[token("checkend", ignore(case))]
    Checkend,
    #[token("priority", ignore(case))]
    Priority,
    #[token("highest", ignore(case))]
    Highest,
    /// `break` with its raw pattern: section 4.5.5 matches it as text against the
    /// commands' source, so `break(turn(d=))` must not be read as an expression.
    #[token("break", lex_break, ignore(case))]
    Break(BreakPattern),

    #[token("(")]
    LParen,
    #[token(")")]
    RParen,
    #[token(",")]
    Comma,
    #[token(":")]
    Colon,
    #[token("=")]
    Assign,
    #[token("==")]
    EqEq,
    #[token("!=")]
    NotEq,
    #[token("<")]
    Lt,
    #[token("<=")]
    Le,
    #[token(">")]
    Gt,
    #[token(">=")]
    Ge,
    /// The dissertation writes `=>` for "at least" (section 4.5.5); the formatter writes `>=`.
    #[token("=>")]
    GeAlt,
    #[token("+")]
    Plus,
    #[token("-")]
    Minus,
    #[token("*")]
    Star,
    #[token("/")]
    Slash,

    Error,
}

/// Where the text of a `break(...)` pattern lies, if one was given.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BreakPattern {
    /// The text between the parentheses; `None` for a bare `break`.
    pub inner: Option<Span>,
    /// False when the line ended before the closing parenthesis.
    pub closed: bool,
}

fn lex_break<'s>(lex: &mut logos::Lexer<'s, Token<'s>>) -> BreakPattern {
    let rest = lex.remainder();
    let bytes = rest.as_bytes();
    let mut i = 0;
    while i < bytes.len() && matches!(bytes[i], b' ' | b'\t') {
        i += 1;
    }
    if i >= bytes.len() || bytes[i] != b'(' {
        return BreakPattern {
            inner: None,
            closed: true,
        };
    }
    let open = i;
    let mut depth = 0usize;
    let mut end = None;
    while i < bytes.len() && bytes[i] != b'\n' {
        if bytes[i] == b'/' && bytes.get(i + 1) == Some(&b'/') {
            break;
        }
        match bytes[i] {
            b'(' => depth += 1,
            b')' => {
                depth -= 1;
                if depth == 0 {
                    end = Some(i);
                    break;
                }
            }
            _ => {}
        }
        i += 1;
    }
    let base = lex.span().end;
    let (inner_end, consumed, closed) = match end {
        Some(close) => (close, close + 1, true),
        None => {
            // Unclosed: take the rest of the line (without trailing blanks) as the pattern.
            let mut e = i;
            while e > open + 1 && matches!(bytes[e - 1], b' ' | b'\t' | b'\r') {
                e -= 1;
            }
            (e, e, false)
        }
    };
    lex.bump(consumed);
    BreakPattern {
        inner: Some(Span::new(base + open + 1, base + inner_end)),
        closed,
    }
}

impl fmt::Display for Token<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let text = match self {
            Token::Newline => "end of line",
            Token::Comment => "comment",
            Token::Number(_) => "number",
            Token::Ident(_) => "name",
            Token::If => "`if`",
            Token::EndIf => "`endif`",
            Token::While => "`while`",
            Token::EndWhile => "`endwhile`",
            Token::Check => "`check`",
            Token::Checkend => "`checkend`",
            Token::Priority => "`priority`",
            Token::Highest => "`highest`",
            Token::Break(_) => "`break`",
            Token::LParen => "`(`",
            Token::RParen => "`)`",
            Token::Comma => "`,`",
            Token::Colon => "`:`",
            Token::Assign => "`=`",
            Token::EqEq => "`==`",
            Token::NotEq => "`!=`",
            Token::Lt => "`<`",
            Token::Le => "`<=`",
            Token::Gt => "`>`",
            Token::Ge => "`>=`",
            Token::GeAlt => "`=>`",
            Token::Plus => "`+`",
            Token::Minus => "`-`",
            Token::Star => "`*`",
            Token::Slash => "`/`",
            Token::Error => "unreadable text",
        };
        f.write_str(text)
    }
}

/// The tokens of a file, with comments split off (the formatter and the language server
/// keep them; the parser never sees them).
pub struct Lexed<'s> {
    pub tokens: Vec<(Token<'s>, Span)>,
    pub comments: Vec<Span>,
}

pub fn lex(source: &str) -> Lexed<'_> {
    let mut tokens = Vec::with_capacity(source.len() / 3);
    let mut comments = Vec::new();
    let mut lexer = Token::lexer(source);
    while let Some(result) = lexer.next() {
        let span = Span::from(lexer.span());
        match result {
            Ok(Token::Comment) => comments.push(span),
            Ok(token) => tokens.push((token, span)),
            Err(()) => tokens.push((Token::Error, span)),
        }
    }
    Lexed { tokens, comments }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kinds(src: &str) -> Vec<Token<'_>> {
        lex(src).tokens.into_iter().map(|(t, _)| t).collect()
    }

    #[test]
    fn keywords_are_case_insensitive_and_names_keep_their_spelling() {
        assert_eq!(
            kinds("If(MyDoor) ENDIF"),
            vec![
                Token::If,
                Token::LParen,
                Token::Ident("MyDoor"),
                Token::RParen,
                Token::EndIf
            ]
        );
    }

    #[test]
    fn break_takes_its_pattern_as_raw_text() {
        let src = "break(turn(d=)) // stop turning";
        let lexed = lex(src);
        let Token::Break(p) = lexed.tokens[0].0 else {
            panic!("{:?}", lexed.tokens)
        };
        assert_eq!(p.inner.unwrap().slice(src), "turn(d=)");
        assert!(p.closed);
        assert_eq!(lexed.tokens.len(), 1);
        assert_eq!(lexed.comments.len(), 1);
    }

    #[test]
    fn bare_break_and_names_that_start_with_break() {
        assert!(matches!(
            kinds("break")[0],
            Token::Break(BreakPattern { inner: None, .. })
        ));
        assert_eq!(kinds("breakfast")[0], Token::Ident("breakfast"));
    }

    #[test]
    fn unclosed_break_pattern_runs_to_the_end_of_the_line() {
        let src = "break(while(c \nstop";
        let lexed = lex(src);
        let Token::Break(p) = lexed.tokens[0].0 else {
            panic!()
        };
        assert_eq!(p.inner.unwrap().slice(src), "while(c");
        assert!(!p.closed);
        assert_eq!(lexed.tokens[1].0, Token::Newline);
    }

    #[test]
    fn numbers_names_and_unicode() {
        assert_eq!(
            kinds("käännös = -0.4 + .5"),
            vec![
                Token::Ident("käännös"),
                Token::Assign,
                Token::Minus,
                Token::Number(0.4),
                Token::Plus,
                Token::Number(0.5)
            ]
        );
    }

    #[test]
    fn comparison_spellings_of_the_dissertation() {
        assert_eq!(
            kinds("a=>b a>=b a==b a=b"),
            vec![
                Token::Ident("a"),
                Token::GeAlt,
                Token::Ident("b"),
                Token::Ident("a"),
                Token::Ge,
                Token::Ident("b"),
                Token::Ident("a"),
                Token::EqEq,
                Token::Ident("b"),
                Token::Ident("a"),
                Token::Assign,
                Token::Ident("b")
            ]
        );
    }

    #[test]
    fn unreadable_text_becomes_error_tokens() {
        assert!(kinds("goahead(1) $ ?").contains(&Token::Error));
    }
}

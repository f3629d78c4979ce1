//! Tokens of ILMR. Lexing never fails: text it cannot read becomes an `Error` token so
//! that the parser can report it in place and go on.

use std::fmt;

use logos::Logos;

use crate::span::Span;

/// A token is only its kind: the text of a name or number is read from the source at
/// its span when needed. That keeps a token and its span to 12 bytes, which matters
/// when a large task has a million of them.
#[derive(Logos, Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[logos(skip r"[ \t\f\r]+")]
pub enum Token {
    /// A line break: statements are one per line and an empty line separates blocks.
    #[token("\n")]
    Newline,

    #[regex(r"//[^\n]*", allow_greedy = true)]
    Comment,

    #[regex(r"[0-9]+(\.[0-9]*)?|\.[0-9]+")]
    Number,

    #[regex(r"[\p{L}_][\p{L}\p{N}_]*")]
    Ident,

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
    /// `break` with its raw pattern (the token spans both; see [`break_pattern`]):
    /// section 4.5.5 matches the pattern as text against the commands' source, so
    /// `break(turn(d=))` must not be read as an expression.
    #[token("break", lex_break, ignore(case))]
    Break,

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

/// What follows `break` on its line: the length to take into the token (0 for a bare
/// `break`), the pattern's range relative to the text after `break`, and whether its
/// parenthesis closes.
fn scan_break(rest: &str) -> (usize, Option<(usize, usize)>, bool) {
    let bytes = rest.as_bytes();
    let mut i = 0;
    while i < bytes.len() && matches!(bytes[i], b' ' | b'\t') {
        i += 1;
    }
    if i >= bytes.len() || bytes[i] != b'(' {
        return (0, None, true);
    }
    let open = i;
    let mut depth = 0usize;
    while i < bytes.len() && bytes[i] != b'\n' {
        if bytes[i] == b'/' && bytes.get(i + 1) == Some(&b'/') {
            break;
        }
        match bytes[i] {
            b'(' => depth += 1,
            b')' => {
                depth -= 1;
                if depth == 0 {
                    return (i + 1, Some((open + 1, i)), true);
                }
            }
            _ => {}
        }
        i += 1;
    }
    // Unclosed: the pattern is the rest of the line, without trailing blanks.
    let mut end = i;
    while end > open + 1 && matches!(bytes[end - 1], b' ' | b'\t' | b'\r') {
        end -= 1;
    }
    (end, Some((open + 1, end)), false)
}

fn lex_break(lex: &mut logos::Lexer<'_, Token>) {
    let (consumed, _, _) = scan_break(lex.remainder());
    lex.bump(consumed);
}

/// The pattern of the `break` token at `span` of `source`.
pub fn break_pattern(source: &str, span: Span) -> BreakPattern {
    let after_keyword = span.start as usize + "break".len();
    let rest = &source[after_keyword..span.end as usize];
    let (_, inner, closed) = scan_break(rest);
    BreakPattern {
        inner: inner.map(|(a, b)| Span::new(after_keyword + a, after_keyword + b)),
        closed,
    }
}

/// The value of a `Number` token's text.
pub fn number(text: &str) -> f64 {
    short_number(text).unwrap_or_else(|| {
        // The token's pattern is digits with at most one point: always a valid f64.
        text.parse().unwrap_or(0.0)
    })
}

/// The value of a number of at most 15 digits, exactly as `str::parse` gives it,
/// without the general parser (4.4 M instructions on the 1x corpus's 33,000 numbers):
/// its digits make an integer below 2^53 and its point a power of ten below 10^16,
/// both exact as f64, and the division of two exact f64 is rounded once, correctly
/// (Clinger's fast path, which the standard parser takes for these too).
fn short_number(text: &str) -> Option<f64> {
    const POWERS: [f64; 16] = [
        1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
    ];
    if text.len() > 16 {
        return None;
    }
    let mut mantissa = 0u64;
    let mut digits = 0;
    let mut point = None;
    for (i, b) in text.bytes().enumerate() {
        match b {
            b'0'..=b'9' => {
                mantissa = mantissa * 10 + u64::from(b - b'0');
                digits += 1;
            }
            b'.' if point.is_none() => point = Some(i),
            _ => return None,
        }
    }
    if digits == 0 || digits > 15 {
        return None;
    }
    let decimals = point.map_or(0, |p| text.len() - p - 1);
    Some(mantissa as f64 / POWERS[decimals])
}

impl fmt::Display for Token {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let text = match self {
            Token::Newline => "end of line",
            Token::Comment => "comment",
            Token::Number => "number",
            Token::Ident => "name",
            Token::If => "`if`",
            Token::EndIf => "`endif`",
            Token::While => "`while`",
            Token::EndWhile => "`endwhile`",
            Token::Check => "`check`",
            Token::Checkend => "`checkend`",
            Token::Priority => "`priority`",
            Token::Highest => "`highest`",
            Token::Break => "`break`",
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
pub struct Lexed {
    pub tokens: Vec<(Token, Span)>,
    pub comments: Vec<Span>,
}

pub fn lex(source: &str) -> Lexed {
    let mut stream = Tokens::new(source);
    let mut tokens = Vec::with_capacity(source.len() / 3);
    tokens.extend(stream.by_ref());
    Lexed {
        tokens,
        comments: stream.comments,
    }
}

/// The tokens of a file one at a time, comments set aside in `comments`: the parser
/// reads a line's tokens as they come instead of holding the whole file's (12 bytes a
/// token, about five a line).
pub struct Tokens<'s> {
    lexer: logos::Lexer<'s, Token>,
    pub comments: Vec<Span>,
}

impl<'s> Tokens<'s> {
    pub fn new(source: &'s str) -> Self {
        Tokens {
            lexer: Token::lexer(source),
            comments: Vec::new(),
        }
    }
}

impl Iterator for Tokens<'_> {
    type Item = (Token, Span);

    fn next(&mut self) -> Option<(Token, Span)> {
        loop {
            let result = self.lexer.next()?;
            let span = Span::from(self.lexer.span());
            match result {
                Ok(Token::Comment) => self.comments.push(span),
                Ok(token) => return Some((token, span)),
                Err(()) => return Some((Token::Error, span)),
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn short_numbers_are_what_the_standard_parser_reads() {
        let mut fixed = vec![
            "0",
            "0.",
            ".5",
            "0.3",
            "3",
            "90",
            "0.1",
            "2.675",
            "123456789012345",
            "12345678901234.5",
            ".000000000000001",
            "999999999999999",
            "1234567890123456",
            "9007199254740993",
            "0.30000000000000004",
            "00000000000000001",
        ];
        let mut random = Vec::new();
        let mut rng = ilmr_geometry::SplitMix64::new(0x2545_f491_4f6c_dd1d);
        for _ in 0..200_000 {
            let x = rng.next_u64();
            let len = 1 + (x % 17) as usize;
            let mut t: String = (0..len)
                .map(|i| char::from(b'0' + ((x >> (i * 3 % 60)) % 10) as u8))
                .collect();
            if x & (1 << 62) != 0 {
                t.insert((x >> 40) as usize % (len + 1), '.');
            }
            random.push(t);
        }
        fixed.extend(random.iter().map(String::as_str));
        let mut short = 0;
        for t in fixed {
            let parsed: f64 = t.parse().unwrap();
            assert_eq!(number(t).to_bits(), parsed.to_bits(), "{t}");
            short += usize::from(short_number(t).is_some());
        }
        // Most of them took the short path, so the comparison above tested it.
        assert!(short > 100_000, "{short}");
    }

    fn kinds(src: &str) -> Vec<Token> {
        lex(src).tokens.into_iter().map(|(t, _)| t).collect()
    }

    #[test]
    fn keywords_are_case_insensitive_and_names_keep_their_spelling() {
        let src = "If(MyDoor) ENDIF";
        let lexed = lex(src);
        let kinds: Vec<Token> = lexed.tokens.iter().map(|(t, _)| *t).collect();
        assert_eq!(
            kinds,
            vec![
                Token::If,
                Token::LParen,
                Token::Ident,
                Token::RParen,
                Token::EndIf
            ]
        );
        assert_eq!(lexed.tokens[2].1.slice(src), "MyDoor");
    }

    #[test]
    fn break_takes_its_pattern_as_raw_text() {
        let src = "break(turn(d=)) // stop turning";
        let lexed = lex(src);
        assert_eq!(lexed.tokens[0].0, Token::Break);
        let p = break_pattern(src, lexed.tokens[0].1);
        assert_eq!(p.inner.unwrap().slice(src), "turn(d=)");
        assert!(p.closed);
        assert_eq!(lexed.tokens.len(), 1);
        assert_eq!(lexed.comments.len(), 1);
    }

    #[test]
    fn bare_break_and_names_that_start_with_break() {
        let lexed = lex("break");
        assert_eq!(lexed.tokens[0].0, Token::Break);
        assert_eq!(break_pattern("break", lexed.tokens[0].1).inner, None);
        assert_eq!(kinds("breakfast")[0], Token::Ident);
    }

    #[test]
    fn unclosed_break_pattern_runs_to_the_end_of_the_line() {
        let src = "break(while(c \nstop";
        let lexed = lex(src);
        let p = break_pattern(src, lexed.tokens[0].1);
        assert_eq!(p.inner.unwrap().slice(src), "while(c");
        assert!(!p.closed);
        assert_eq!(lexed.tokens[1].0, Token::Newline);
    }

    #[test]
    fn numbers_names_and_unicode() {
        let src = "käännös = -0.4 + .5";
        let lexed = lex(src);
        let kinds: Vec<Token> = lexed.tokens.iter().map(|(t, _)| *t).collect();
        assert_eq!(
            kinds,
            vec![
                Token::Ident,
                Token::Assign,
                Token::Minus,
                Token::Number,
                Token::Plus,
                Token::Number
            ]
        );
        assert_eq!(lexed.tokens[0].1.slice(src), "käännös");
        assert_eq!(number(lexed.tokens[3].1.slice(src)), 0.4);
        assert_eq!(number(lexed.tokens[5].1.slice(src)), 0.5);
    }

    #[test]
    fn comparison_spellings_of_the_dissertation() {
        assert_eq!(
            kinds("a=>b a>=b a==b a=b"),
            vec![
                Token::Ident,
                Token::GeAlt,
                Token::Ident,
                Token::Ident,
                Token::Ge,
                Token::Ident,
                Token::Ident,
                Token::EqEq,
                Token::Ident,
                Token::Ident,
                Token::Assign,
                Token::Ident
            ]
        );
    }

    #[test]
    fn unreadable_text_becomes_error_tokens() {
        assert!(kinds("goahead(1) $ ?").contains(&Token::Error));
    }
}

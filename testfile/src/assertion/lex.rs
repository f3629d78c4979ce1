//! The words of an assertion: names, numbers, command texts in backticks, and signs.

use std::ops::Range;

#[derive(Debug, Clone, PartialEq)]
pub enum Tok {
    /// A name or keyword (letters, digits, `_`), as written.
    Word(String),
    Number(f64),
    /// The text between backticks.
    Quoted(String),
    /// `(` `)` `,` `:` `.` `..` and the comparisons.
    Sign(&'static str),
}

impl Tok {
    pub fn describe(&self) -> String {
        match self {
            Tok::Word(w) => format!("`{w}`"),
            Tok::Number(n) => format!("the number {}", super::num(*n)),
            Tok::Quoted(q) => format!("`` `{q}` ``"),
            Tok::Sign(s) => format!("`{s}`"),
        }
    }
}

/// Longest first, so that `<=` is not read as `<` then `=`.
const SIGNS: [&str; 12] = [
    "..", "==", "!=", "<=", ">=", "<", ">", "(", ")", ",", ":", ".",
];

/// A token and its bytes in the assertion.
pub type Token = (Tok, Range<usize>);

/// The first character that starts no token, and what is wrong there.
pub type LexError = (Range<usize>, String);

/// The tokens of `text` with their byte ranges.
pub fn lex(text: &str) -> Result<Vec<Token>, LexError> {
    let mut out = Vec::new();
    let bytes = text.as_bytes();
    let mut i = 0;
    while i < text.len() {
        let rest = &text[i..];
        let c = rest.chars().next().unwrap_or(' ');
        if c.is_whitespace() {
            i += c.len_utf8();
            continue;
        }
        let starts_number =
            c.is_ascii_digit() || (c == '-' && bytes.get(i + 1).is_some_and(u8::is_ascii_digit));
        if starts_number {
            let mut end = i + 1;
            let mut dot = false;
            while let Some(&b) = bytes.get(end) {
                let decimal_point =
                    b == b'.' && !dot && bytes.get(end + 1).is_some_and(u8::is_ascii_digit);
                if b.is_ascii_digit() {
                    end += 1;
                } else if decimal_point {
                    dot = true;
                    end += 1;
                } else {
                    break;
                }
            }
            let value: f64 = text[i..end]
                .parse()
                .map_err(|_| (i..end, format!("`{}` is not a number", &text[i..end])))?;
            out.push((Tok::Number(value), i..end));
            i = end;
            continue;
        }
        if c.is_ascii_alphabetic() || c == '_' {
            let len = rest
                .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                .unwrap_or(rest.len());
            out.push((Tok::Word(rest[..len].to_string()), i..i + len));
            i += len;
            continue;
        }
        if c == '`' {
            let Some(close) = rest[1..].find('`') else {
                return Err((
                    i..text.len(),
                    "a command's text in backticks has no closing backtick".into(),
                ));
            };
            out.push((
                Tok::Quoted(rest[1..1 + close].to_string()),
                i..i + close + 2,
            ));
            i += close + 2;
            continue;
        }
        if let Some(sign) = SIGNS.iter().find(|s| rest.starts_with(**s)) {
            out.push((Tok::Sign(sign), i..i + sign.len()));
            i += sign.len();
            continue;
        }
        let mut message = format!("`{c}` starts no word of an assertion");
        if c == '"' || c == '\'' {
            message.push_str("; a command's text is written in backticks: `goahead(1.2)`");
        } else if c == '=' {
            message.push_str("; compare with `==`");
        }
        return Err((i..i + c.len_utf8(), message));
    }
    Ok(out)
}

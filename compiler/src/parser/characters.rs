//! Characters ILMR does not read but people paste: spaces that are not spaces, invisible
//! marks, typographic signs that stand for ASCII ones. Each is named by its code point
//! and Unicode name, and where it stands for something the line is read as if that had
//! been written, so one pasted space gives one diagnostic and nothing else.

use crate::diagnostic::{Code, Diagnostic, FileId};
use crate::lexer::Token;
use crate::span::Span;

/// What the reader does with an unusual character.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stands {
    /// A space of another width or that does not break: read as a space.
    ForSpace,
    /// Invisible: read as nothing.
    ForNothing,
    /// A sign for the ASCII one: read as that token.
    For(Token, &'static str),
    /// Nothing ILMR has; only named.
    Alone,
}

/// The unusual characters that are named, with what they stand for.
pub const UNUSUAL: &[(char, &str, Stands)] = &[
    ('\u{00A0}', "NO-BREAK SPACE", Stands::ForSpace),
    ('\u{2000}', "EN QUAD", Stands::ForSpace),
    ('\u{2001}', "EM QUAD", Stands::ForSpace),
    ('\u{2002}', "EN SPACE", Stands::ForSpace),
    ('\u{2003}', "EM SPACE", Stands::ForSpace),
    ('\u{2004}', "THREE-PER-EM SPACE", Stands::ForSpace),
    ('\u{2005}', "FOUR-PER-EM SPACE", Stands::ForSpace),
    ('\u{2006}', "SIX-PER-EM SPACE", Stands::ForSpace),
    ('\u{2007}', "FIGURE SPACE", Stands::ForSpace),
    ('\u{2008}', "PUNCTUATION SPACE", Stands::ForSpace),
    ('\u{2009}', "THIN SPACE", Stands::ForSpace),
    ('\u{200A}', "HAIR SPACE", Stands::ForSpace),
    ('\u{202F}', "NARROW NO-BREAK SPACE", Stands::ForSpace),
    ('\u{205F}', "MEDIUM MATHEMATICAL SPACE", Stands::ForSpace),
    ('\u{3000}', "IDEOGRAPHIC SPACE", Stands::ForSpace),
    ('\u{000B}', "LINE TABULATION", Stands::ForSpace),
    ('\u{200B}', "ZERO WIDTH SPACE", Stands::ForNothing),
    ('\u{200C}', "ZERO WIDTH NON-JOINER", Stands::ForNothing),
    ('\u{200D}', "ZERO WIDTH JOINER", Stands::ForNothing),
    ('\u{200E}', "LEFT-TO-RIGHT MARK", Stands::ForNothing),
    ('\u{200F}', "RIGHT-TO-LEFT MARK", Stands::ForNothing),
    ('\u{2060}', "WORD JOINER", Stands::ForNothing),
    (
        '\u{FEFF}',
        "ZERO WIDTH NO-BREAK SPACE (byte order mark)",
        Stands::ForNothing,
    ),
    ('\u{00AD}', "SOFT HYPHEN", Stands::ForNothing),
    ('\u{2212}', "MINUS SIGN", Stands::For(Token::Minus, "-")),
    ('\u{2010}', "HYPHEN", Stands::For(Token::Minus, "-")),
    (
        '\u{2011}',
        "NON-BREAKING HYPHEN",
        Stands::For(Token::Minus, "-"),
    ),
    ('\u{2013}', "EN DASH", Stands::For(Token::Minus, "-")),
    ('\u{2014}', "EM DASH", Stands::For(Token::Minus, "-")),
    (
        '\u{00D7}',
        "MULTIPLICATION SIGN",
        Stands::For(Token::Star, "*"),
    ),
    ('\u{22C5}', "DOT OPERATOR", Stands::For(Token::Star, "*")),
    ('\u{00F7}', "DIVISION SIGN", Stands::For(Token::Slash, "/")),
    ('\u{2215}', "DIVISION SLASH", Stands::For(Token::Slash, "/")),
    (
        '\u{2264}',
        "LESS-THAN OR EQUAL TO",
        Stands::For(Token::Le, "<="),
    ),
    (
        '\u{2265}',
        "GREATER-THAN OR EQUAL TO",
        Stands::For(Token::Ge, ">="),
    ),
    ('\u{2260}', "NOT EQUAL TO", Stands::For(Token::NotEq, "!=")),
    (
        '\u{FF08}',
        "FULLWIDTH LEFT PARENTHESIS",
        Stands::For(Token::LParen, "("),
    ),
    (
        '\u{FF09}',
        "FULLWIDTH RIGHT PARENTHESIS",
        Stands::For(Token::RParen, ")"),
    ),
    (
        '\u{FF0C}',
        "FULLWIDTH COMMA",
        Stands::For(Token::Comma, ","),
    ),
    (
        '\u{3001}',
        "IDEOGRAPHIC COMMA",
        Stands::For(Token::Comma, ","),
    ),
    (
        '\u{FF1A}',
        "FULLWIDTH COLON",
        Stands::For(Token::Colon, ":"),
    ),
    (
        '\u{FF1D}',
        "FULLWIDTH EQUALS SIGN",
        Stands::For(Token::Assign, "="),
    ),
    ('\u{00B0}', "DEGREE SIGN", Stands::Alone),
    ('\u{2018}', "LEFT SINGLE QUOTATION MARK", Stands::Alone),
    ('\u{2019}', "RIGHT SINGLE QUOTATION MARK", Stands::Alone),
    ('\u{201C}', "LEFT DOUBLE QUOTATION MARK", Stands::Alone),
    ('\u{201D}', "RIGHT DOUBLE QUOTATION MARK", Stands::Alone),
    ('\u{2026}', "HORIZONTAL ELLIPSIS", Stands::Alone),
];

fn lookup(c: char) -> Option<(&'static str, Stands)> {
    UNUSUAL
        .iter()
        .find(|(u, _, _)| *u == c)
        .map(|&(_, name, stands)| (name, stands))
}

/// "`$`", or "U+00A0 NO-BREAK SPACE" for a character that cannot be seen or told apart.
pub fn describe(c: char) -> String {
    match lookup(c) {
        Some((name, _)) => format!("U+{:04X} {name}", c as u32),
        None if c.is_ascii_graphic() => format!("`{c}`"),
        None if c.is_control() => format!("U+{:04X} (a control character)", c as u32),
        None => format!("`{c}` (U+{:04X})", c as u32),
    }
}

/// What to do about a character that stands for nothing ILMR has, where that is known.
pub fn advice(c: char) -> Option<&'static str> {
    match c {
        '"' | '\'' | '\u{2018}' | '\u{2019}' | '\u{201C}' | '\u{201D}' => {
            Some("ILMR has no quoted text: write the name without quotes")
        }
        '\u{00B0}' => {
            Some("values are plain numbers in the command's unit: write the number alone")
        }
        ';' => Some("statements are one per line: put what follows on a line of its own"),
        _ => None,
    }
}

/// What the line is read as, the diagnostic for its first unusual character that stands
/// for something (the others on the line as secondary labels), and `None` when it has
/// none. Characters that stand for nothing ILMR has stay error tokens for the grammar.
pub fn read_through(
    line: &mut Vec<(Token, Span)>,
    source: &str,
    file: FileId,
) -> Option<Diagnostic> {
    let mut found: Vec<(char, Span, Stands)> = Vec::new();
    line.retain_mut(|(token, span)| {
        if *token != Token::Error {
            return true;
        }
        let text = span.slice(source);
        let mut chars = text.chars();
        let (Some(c), None) = (chars.next(), chars.next()) else {
            return true;
        };
        match lookup(c) {
            Some((_, stands @ (Stands::ForSpace | Stands::ForNothing))) => {
                found.push((c, *span, stands));
                false
            }
            Some((_, stands @ Stands::For(replacement, _))) => {
                found.push((c, *span, stands));
                *token = replacement;
                true
            }
            _ => true,
        }
    });
    let (&(c, span, stands), rest) = found.split_first()?;
    let (help, replacement) = match stands {
        Stands::ForSpace => ("replace it with a plain space".to_string(), " "),
        Stands::ForNothing => ("delete it: it cannot be seen".to_string(), ""),
        Stands::For(_, ascii) => (format!("write `{ascii}`"), ascii),
        Stands::Alone => unreachable!("only characters that stand for something are found"),
    };
    let mut d = Diagnostic::new(
        Code::UnusualCharacter,
        file,
        span,
        format!("unusual character {}", describe(c)),
    )
    .with_label(match stands {
        Stands::ForSpace => "this looks like a space but is not one",
        Stands::ForNothing => "an invisible character is here",
        _ => "this looks like an ASCII sign but is not one",
    })
    .with_help(if rest.is_empty() {
        help
    } else {
        format!("{help} (and the same for the others on this line)")
    })
    .with_fix(help_title(stands), span, replacement);
    for &(c, span, _) in rest {
        d = d.with_secondary(file, span, format!("and {} here", describe(c)));
    }
    Some(d)
}

fn help_title(stands: Stands) -> String {
    match stands {
        Stands::ForSpace => "replace with a space".into(),
        Stands::ForNothing => "delete the invisible character".into(),
        Stands::For(_, ascii) => format!("replace with `{ascii}`"),
        Stands::Alone => String::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lexer::lex;

    fn read(src: &str) -> (Vec<Token>, Option<Diagnostic>) {
        let mut line = lex(src).tokens;
        let d = read_through(&mut line, src, FileId(0));
        (line.into_iter().map(|(t, _)| t).collect(), d)
    }

    #[test]
    fn a_pasted_space_is_named_and_read_as_a_space() {
        let (tokens, d) = read("x\u{00A0}= 1");
        assert_eq!(tokens, [Token::Ident, Token::Assign, Token::Number]);
        let d = d.unwrap();
        assert_eq!(d.message, "unusual character U+00A0 NO-BREAK SPACE");
        assert_eq!(d.fix.unwrap().replacement, " ");
    }

    #[test]
    fn typographic_signs_are_read_as_their_ascii_ones() {
        let (tokens, d) = read("if(a \u{2265} \u{2212}1)");
        assert_eq!(tokens[3], Token::Ge);
        assert_eq!(tokens[4], Token::Minus);
        let d = d.unwrap();
        assert_eq!(d.fix.as_ref().unwrap().replacement, ">=");
        assert_eq!(d.secondary.len(), 1);
    }

    #[test]
    fn other_characters_are_left_to_the_grammar() {
        let (tokens, d) = read("turn(d=90\u{00B0}) $");
        assert!(d.is_none());
        assert_eq!(tokens.iter().filter(|t| **t == Token::Error).count(), 2);
        assert_eq!(describe('\u{00B0}'), "U+00B0 DEGREE SIGN");
        assert_eq!(describe('$'), "`$`");
        assert_eq!(describe('\u{7}'), "U+0007 (a control character)");
    }

    #[test]
    fn every_named_character_is_one_the_lexer_cannot_read() {
        for &(c, _, _) in UNUSUAL {
            let text = c.to_string();
            assert_eq!(lex(&text).tokens[0].0, Token::Error, "U+{:04X}", c as u32);
        }
    }
}

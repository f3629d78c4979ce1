//! Mistakes people make on a line, recognised so that the message says what was meant
//! rather than which token was unexpected: a block end written as in another language
//! (`end if`), a unit after a number (`speed(30 km/h)`), two comparisons joined in a
//! condition (`if(x<2 and x>0)`). The grammar stays the judge of what is valid; these
//! only reword the lines it rejects (or, for block ends, read them as meant).

use ilmr_stdlib::Command;
use ilmr_stdlib::units::{self, round_for_people};

use crate::diagnostic::{Code, Diagnostic, FileId};
use crate::lexer::Token;
use crate::parser::lines::Line;
use crate::span::Span;

/// The block ends of ILMR, with the spellings that mean them once case, spaces, `_`
/// and `-` are dropped.
const BLOCK_ENDS: &[(&str, &[&str])] = &[
    ("endif", &["endif", "fi"]),
    ("endwhile", &["endwhile", "endloop", "wend"]),
    ("checkend", &["checkend", "endcheck"]),
];

/// Ends of blocks ILMR does not have: a skill ends where the next header begins.
const SKILL_ENDS: &[&str] = &["endsub", "endskill", "endfunction", "endproc", "endfunc"];

/// A line of at most this many tokens can be a block end written in another way.
const BLOCK_END_TOKENS: usize = 3;

/// A line meant as a block end (`end if`, `End_While`, `check end`): the block end it
/// means, read as such so that its block closes, and the diagnostic that says so.
pub fn block_end<'s>(
    line: &[(Token, Span)],
    source: &str,
    file: FileId,
) -> Option<(Line<'s>, Diagnostic)> {
    let first = line.first()?;
    if line.len() > BLOCK_END_TOKENS || !could_be_block_end(first, source) {
        return None;
    }
    let span = first.1.to(line[line.len() - 1].1);
    let mut joined = String::new();
    for &(token, span) in line {
        match token {
            Token::Ident | Token::If | Token::While | Token::Check | Token::Checkend => {
                joined.push_str(&span.slice(source).to_ascii_lowercase());
            }
            Token::Minus => {}
            _ => return None,
        }
    }
    let joined = joined.replace('_', "");
    let written = span.slice(source);
    if let Some(&(end, _)) = BLOCK_ENDS
        .iter()
        .find(|(end, spellings)| spellings.contains(&joined.as_str()) && written != *end)
    {
        let line = match end {
            "endif" => Line::EndIf,
            "endwhile" => Line::EndWhile,
            _ => Line::Checkend,
        };
        let d = Diagnostic::new(
            Code::Syntax,
            file,
            span,
            format!("`{written}` is written `{end}` in ILMR"),
        )
        .with_label(format!("did you mean `{end}`?"))
        .with_fix(format!("replace with `{end}`"), span, end);
        return Some((line, d));
    }
    if joined == "end" {
        let d = Diagnostic::new(
            Code::Syntax,
            file,
            span,
            format!("`{written}` alone ends no block in ILMR"),
        )
        .with_label("which block does this end?")
        .with_help(
            "an `if` ends with `endif`, a `while` with `endwhile`, a `check` with `checkend`",
        );
        return Some((Line::Stmt(crate::ast::StmtKind::Error), d));
    }
    if SKILL_ENDS.contains(&joined.as_str()) {
        let d = Diagnostic::new(
            Code::Syntax,
            file,
            span,
            format!("`{written}`: a skill has no end line"),
        )
        .with_label("not a statement of ILMR")
        .with_help("a skill ends where the next `NAME:` header begins, or at the end of the file")
        .with_fix("delete the line", span, "");
        return Some((Line::Stmt(crate::ast::StmtKind::Error), d));
    }
    None
}

fn could_be_block_end(&(token, span): &(Token, Span), source: &str) -> bool {
    let text = span.slice(source).as_bytes();
    let starts =
        |word: &[u8]| text.len() >= word.len() && text[..word.len()].eq_ignore_ascii_case(word);
    match token {
        Token::Ident => {
            starts(b"end")
                || starts(b"check")
                || starts(b"wend")
                || text.eq_ignore_ascii_case(b"fi")
        }
        Token::Check => true,
        _ => false,
    }
}

/// What a rejected line meant, as far as it can be told.
pub struct Explained {
    pub diagnostic: Diagnostic,
    /// The tokens to read the line as, so that what it binds and uses is still checked
    /// (a condition's first comparison); `None` leaves it a broken line.
    pub read_as: Option<Vec<(Token, Span)>>,
}

/// A better diagnostic for a line the grammar rejected at `error_at`, when the mistake
/// there is a known one.
pub fn explain(
    line: &[(Token, Span)],
    source: &str,
    file: FileId,
    error_at: Span,
) -> Option<Explained> {
    combined_condition(line, source, file, error_at).or_else(|| {
        unit_after_number(line, source, file, error_at).map(|diagnostic| Explained {
            diagnostic,
            read_as: None,
        })
    })
}

/// Where a condition's parentheses open and close on an `if(` or `while(` line.
fn condition_bounds(line: &[(Token, Span)]) -> Option<(usize, usize)> {
    let keyword = match line {
        [(Token::If | Token::While, _), ..] => 0,
        [(Token::Ident, _), (Token::Assign, _), (Token::While, _), ..] => 2,
        _ => return None,
    };
    let open = keyword + 1;
    if line.get(open)?.0 != Token::LParen {
        return None;
    }
    let mut depth = 0usize;
    for (i, &(token, _)) in line.iter().enumerate().skip(open) {
        match token {
            Token::LParen => depth += 1,
            Token::RParen => {
                depth -= 1;
                if depth == 0 {
                    return Some((open, i));
                }
            }
            _ => {}
        }
    }
    Some((open, line.len()))
}

fn combined_condition(
    line: &[(Token, Span)],
    source: &str,
    file: FileId,
    error_at: Span,
) -> Option<Explained> {
    let (open, close) = condition_bounds(line)?;
    let inside = &line[open + 1..close];
    let (at, &(_, joint)) = inside.iter().enumerate().find(|&(_, &(t, s))| {
        let text = s.slice(source);
        match t {
            Token::Ident => text.eq_ignore_ascii_case("and") || text.eq_ignore_ascii_case("or"),
            Token::Error => matches!(text, "&" | "|"),
            _ => false,
        }
    })?;
    if joint.start != error_at.start {
        return None;
    }
    // `&&` and `||` are two error tokens: the joint spans both.
    let joint = match inside.get(at + 1) {
        Some(&(Token::Error, next)) if next.slice(source) == joint.slice(source) => joint.to(next),
        _ => joint,
    };
    let word = joint.slice(source);
    let is_and = matches!(word.to_ascii_lowercase().as_str(), "and" | "&" | "&&");
    let text = |from: usize, to: usize| source[from..to].trim();
    let cond_start = line[open].1.end as usize;
    let cond_end = line
        .get(close)
        .map_or(line[line.len() - 1].1.end, |t| t.1.start) as usize;
    let left = text(cond_start, joint.start as usize);
    let right = text(joint.end as usize, cond_end);
    let keyword = if line[0].0 == Token::If {
        "if"
    } else {
        "while"
    };
    let help = match (keyword, is_and) {
        ("if", true) => {
            format!("nest one `if` inside the other:\nif({left})\nif({right})\n...\nendif\nendif")
        }
        ("if", false) => format!(
            "give each condition its own block:\nif({left})\n...\nendif\nif({right})\n...\nendif"
        ),
        _ => format!(
            "loop on one comparison and test the other inside the loop:\n{keyword}({left})\nif({right})\n...\nendif\nendwhile"
        ),
    };
    let diagnostic = Diagnostic::new(
        Code::CombinedCondition,
        file,
        joint,
        format!("a condition takes one comparison; `{word}` cannot join two"),
    )
    .with_label(format!("ILMR has no `{word}`"))
    .with_help(help);
    // Read as its first comparison, so the block still opens with what it uses.
    let joint_at = open + 1 + at;
    let read_as = line[..joint_at]
        .iter()
        .chain(&line[close.min(line.len())..])
        .copied()
        .collect();
    Some(Explained {
        diagnostic,
        read_as: Some(read_as),
    })
}

/// The command a line calls and where its arguments begin.
fn call_of(line: &[(Token, Span)], source: &str) -> Option<(Command, usize)> {
    let at = match line {
        [(Token::Ident, _), (Token::LParen, _), ..] => 0,
        [
            (Token::Ident, _),
            (Token::Assign, _),
            (Token::Ident, _),
            (Token::LParen, _),
            ..,
        ] => 2,
        _ => return None,
    };
    Some((Command::from_name(line[at].1.slice(source))?, at + 2))
}

fn unit_after_number(
    line: &[(Token, Span)],
    source: &str,
    file: FileId,
    error_at: Span,
) -> Option<Diagnostic> {
    let call = call_of(line, source);
    let args_from = call.map_or(0, |(_, from)| from);
    // Which argument each token is in: settings by key, the others by position.
    let mut depth = 0usize;
    let mut index = 0usize;
    let mut key: Option<&str> = None;
    let mut i = args_from;
    while i < line.len() {
        let (token, span) = line[i];
        match token {
            Token::LParen => depth += 1,
            Token::RParen => depth = depth.saturating_sub(1),
            // A setting's comma ends the setting; a positional one counts.
            Token::Comma if depth == 0 && key.take().is_none() => index += 1,
            Token::Ident if depth == 0 && line.get(i + 1).is_some_and(|t| t.0 == Token::Assign) => {
                key = Some(span.slice(source));
            }
            Token::Number => {
                let unit_end = line[i + 1..]
                    .iter()
                    .position(|&(t, _)| matches!(t, Token::Comma | Token::RParen | Token::LParen))
                    .map_or(line.len(), |p| i + 1 + p);
                if unit_end > i + 1 && line[i + 1].1.start == error_at.start {
                    let unit_span = line[i + 1].1.to(line[unit_end - 1].1);
                    let written: String = unit_span
                        .slice(source)
                        .chars()
                        .filter(|c| !c.is_whitespace())
                        .collect();
                    if let Some(unit) = units::written_unit(&written) {
                        let negative = i > 0 && line[i - 1].0 == Token::Minus;
                        let number_span = if negative {
                            line[i - 1].1.to(span)
                        } else {
                            span
                        };
                        let value = crate::lexer::number(span.slice(source))
                            * if negative { -1.0 } else { 1.0 };
                        let expected = call.and_then(|(c, _)| c.spec().unit_of(key, index));
                        return Some(unit_diagnostic(
                            file,
                            number_span.to(unit_span),
                            value,
                            &written,
                            unit,
                            call.map(|(c, _)| c),
                            expected,
                        ));
                    }
                }
            }
            _ => {}
        }
        i += 1;
    }
    None
}

fn unit_diagnostic(
    file: FileId,
    span: Span,
    value: f64,
    written: &str,
    unit: &units::WrittenUnit,
    command: Option<Command>,
    expected: Option<ilmr_stdlib::Unit>,
) -> Diagnostic {
    let number = round_for_people(value);
    let d = Diagnostic::new(
        Code::UnitAfterNumber,
        file,
        span,
        match (command, expected) {
            (Some(c), Some(u)) if u.dimension().is_some() => format!(
                "values are plain numbers: this argument of `{c}` is in {} ({})",
                u.words(),
                u.symbol()
            ),
            _ => "values are plain numbers, written without a unit".to_string(),
        },
    )
    .with_label(format!("`{written}` cannot follow the number"));
    match expected {
        Some(u) if u.dimension() == Some(unit.dimension) => {
            let meant = round_for_people(value * unit.factor);
            let help = if meant == number {
                format!("write the number alone: `{meant}`")
            } else {
                format!(
                    "{number} {written} is {meant} {}: write `{meant}`",
                    u.symbol()
                )
            };
            d.with_help(help)
                .with_fix(format!("replace with `{meant}`"), span, meant)
        }
        Some(u) if u.dimension().is_some() => d.with_help(format!(
            "`{written}` does not measure what this argument does: it takes {}",
            u.words()
        )),
        _ => d.with_help(format!("write the number alone: `{number}`")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lexer::lex;

    fn explained(src: &str) -> Option<Diagnostic> {
        let mut tokens = lex(src).tokens;
        tokens.push((Token::Newline, Span::empty(src.len())));
        let (_, errors) = crate::parser::lines::parse_lines(&tokens, src);
        let at = *errors.first()?.span();
        explain(&tokens[..tokens.len() - 1], src, FileId(0), at).map(|e| e.diagnostic)
    }

    fn ended(src: &str) -> Option<String> {
        block_end(&lex(src).tokens, src, FileId(0)).map(|(_, d)| d.fix.unwrap().replacement)
    }

    #[test]
    fn block_ends_of_other_languages_are_read_as_ilmr_ones() {
        assert_eq!(ended("end if").as_deref(), Some("endif"));
        assert_eq!(ended("End_While").as_deref(), Some("endwhile"));
        assert_eq!(ended("end-if").as_deref(), Some("endif"));
        assert_eq!(ended("check end").as_deref(), Some("checkend"));
        assert_eq!(ended("endcheck").as_deref(), Some("checkend"));
        assert_eq!(ended("end sub").as_deref(), Some(""));
        assert_eq!(ended("endif"), None);
        assert_eq!(ended("ENDIF"), None);
        assert_eq!(ended("fi").as_deref(), Some("endif"));
        assert_eq!(ended("end_if = 3"), None);
        // `end` alone could end any block: said so, with no fix to pick one.
        let (_, d) = block_end(&lex("end").tokens, "end", FileId(0)).expect("diagnosed");
        assert!(d.fix.is_none() && d.help.as_deref().is_some_and(|h| h.contains("endwhile")));
        assert_eq!(ended("endpoint(1)"), None);
    }

    #[test]
    fn a_unit_after_a_number_is_converted_into_the_arguments_unit() {
        let d = explained("speed(30 km/h)").unwrap();
        assert_eq!(d.code, Code::UnitAfterNumber);
        assert_eq!(d.fix.unwrap().replacement, "8.333");
        let d = explained("turn(d=1.57 rad,c=1)").unwrap();
        assert_eq!(d.fix.unwrap().replacement, "89.954");
        let d = explained("x = goahead(-50 cm)").unwrap();
        assert_eq!(d.fix.unwrap().replacement, "-0.5");
        let d = explained("gotoxy(1, 2 m)").unwrap();
        assert_eq!(d.fix.unwrap().replacement, "2");
        let d = explained("goahead(2 s)").unwrap();
        assert!(d.fix.is_none());
        assert!(d.help.unwrap().contains("metres"));
        assert!(explained("goahead(2 3)").is_none());
    }

    #[test]
    fn two_comparisons_in_a_condition_are_shown_nested() {
        let src = "if(x<2 and x>0) // in range";
        let tokens = lex(src).tokens;
        let e = explain(&tokens, src, FileId(0), tokens[5].1).unwrap();
        let kept: Vec<&str> = e.read_as.unwrap().iter().map(|t| t.1.slice(src)).collect();
        assert_eq!(kept, ["if", "(", "x", "<", "2", ")"]);
        let d = explained("if(x<2 and x>0)").unwrap();
        assert_eq!(d.code, Code::CombinedCondition);
        assert!(d.help.unwrap().contains("if(x<2)\nif(x>0)"));
        let d = explained("w = while(a>1 || b)").unwrap();
        assert_eq!(
            d.message,
            "a condition takes one comparison; `||` cannot join two"
        );
        assert!(explained("if(x<2 x>0)").is_none());
        // The grammar stops before the `or`: that is not the mistake to explain.
        assert!(explained("while (while--1 <= -d,or+.5)").is_none());
    }
}

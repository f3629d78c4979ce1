//! What an editor offers in a test file: at a place in an assertion, what the grammar
//! allows there (from the parser itself, [`crate::assertion::wants`]) with the test's
//! own lines, statements, variables and world objects; at a key's place, the keys;
//! and a few words on what is under the cursor. Plain values: the language server
//! turns them into LSP items.

use std::ops::Range;

use crate::assertion::{self, Field, Place, Want};
use crate::file::{KEYS, Outline};

/// Candidates of one kind in one list: a task of 10,000 lines has 10,000 line
/// references, which no one scrolls; past this the list is cut and marked incomplete,
/// and the editor asks again as more is typed.
pub const MAX_CANDIDATES: usize = 100;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum What {
    Keyword,
    Line,
    Text,
    Variable,
    Field,
    Object,
    Cmp,
    Key,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Candidate {
    pub label: String,
    pub what: What,
    /// A statement's text for a line, where an object is, what a key takes.
    pub detail: Option<String>,
    /// What replaces the word being typed.
    pub insert: String,
}

/// The candidates of a place, ranked, and whether some were left out.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Candidates {
    pub items: Vec<Candidate>,
    pub incomplete: bool,
}

/// Where in a test file the cursor is, for completion and hover.
#[derive(Debug, Clone)]
pub enum Spot<'a> {
    /// In the content of an `assert` string of `outline`: the content starts at `base`.
    Assertion {
        outline: &'a Outline,
        base: usize,
    },
    /// Where a key of a table is written (only a name so far on its line).
    Key,
    Elsewhere,
}

/// The place of byte `offset` of `text`.
pub fn spot<'a>(text: &str, outlines: &'a [Outline], offset: usize) -> Spot<'a> {
    for outline in outlines {
        for (span, base) in &outline.asserts {
            // The cursor may sit right before the closing quote.
            if let Some(base) = *base
                && base <= offset
                && offset < span.end
            {
                return Spot::Assertion { outline, base };
            }
        }
    }
    let line_start = text
        .get(..offset)
        .and_then(|t| t.rfind('\n'))
        .map_or(0, |i| i + 1);
    let before = text.get(line_start..offset).unwrap_or("");
    let word = before.trim_start();
    if word.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
        return Spot::Key;
    }
    Spot::Elsewhere
}

/// The start of the word that ends at `offset` of `text` (letters, digits, `_`).
pub fn word_start(text: &str, offset: usize) -> usize {
    let before = text.get(..offset).unwrap_or("");
    before
        .rfind(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .map_or(0, |i| i + 1)
}

/// What may be written at `offset` in an assertion whose content starts at `base`.
pub fn assertion(text: &str, outline: &Outline, base: usize, offset: usize) -> Candidates {
    let start = word_start(text, offset).max(base);
    let typed = text.get(start..offset).unwrap_or("");
    let Some(prefix) = text.get(base..start) else {
        return Candidates::default();
    };
    let ctx = outline.context();
    // Inside a backtick: the statement's text, without the backticks.
    let whole = text.get(base..offset).unwrap_or("");
    if whole.matches('`').count() % 2 == 1 {
        let open = whole.rfind('`').unwrap_or(0);
        let wanted = assertion::wants(&whole[..open], &ctx);
        if !wanted.contains(&Want::Text) {
            return Candidates::default();
        }
        return texts(outline, false, &whole[open + 1..]);
    }
    let mut out = Candidates::default();
    for want in assertion::wants(prefix, &ctx) {
        let items = match want {
            Want::Word(w) if w.chars().all(|c| c.is_ascii_alphabetic()) && w != "s" => {
                vec![keyword(w)]
            }
            Want::Word(_) => Vec::new(),
            Want::Line => {
                let part = ranked_by(
                    &outline.statements,
                    |(l, _)| l.to_string(),
                    |(l, t)| Candidate {
                        label: l.to_string(),
                        what: What::Line,
                        detail: Some(t.clone()),
                        insert: l.to_string(),
                    },
                    typed,
                );
                out.incomplete |= part.incomplete;
                out.items.extend(part.items);
                continue;
            }
            Want::Text => {
                let part = texts(outline, true, typed);
                out.incomplete |= part.incomplete;
                out.items.extend(part.items);
                continue;
            }
            Want::Variable => outline
                .variables
                .iter()
                .map(|v| Candidate {
                    label: v.clone(),
                    what: What::Variable,
                    detail: Some("a variable the task assigns".into()),
                    insert: v.clone(),
                })
                .collect(),
            Want::Field => Field::ALL
                .iter()
                .map(|(n, _)| Candidate {
                    label: (*n).to_string(),
                    what: What::Field,
                    detail: Some("a field of the variable's `var` events".into()),
                    insert: (*n).to_string(),
                })
                .collect(),
            Want::Object => outline
                .objects
                .iter()
                .flatten()
                .filter_map(|p| match p {
                    Place::Object { name, .. } => Some(Candidate {
                        label: name.clone(),
                        what: What::Object,
                        detail: Some(where_is(p)),
                        insert: name.clone(),
                    }),
                    Place::Point(..) => None,
                })
                .collect(),
            Want::Cmp => assertion::Cmp::ALL
                .iter()
                .map(|(s, _)| Candidate {
                    label: (*s).to_string(),
                    what: What::Cmp,
                    detail: None,
                    insert: (*s).to_string(),
                })
                .collect(),
        };
        let part = ranked(items, typed);
        out.incomplete |= part.incomplete;
        out.items.extend(part.items);
    }
    out
}

/// The keys of a test, with what each takes.
pub fn keys(text: &str, offset: usize) -> Candidates {
    let start = word_start(text, offset);
    let typed = text.get(start..offset).unwrap_or("");
    let items = KEYS
        .iter()
        .map(|(k, what)| Candidate {
            label: (*k).to_string(),
            what: What::Key,
            detail: Some((*what).to_string()),
            insert: format!("{k} = "),
        })
        .collect();
    ranked(items, typed)
}

fn keyword(w: &'static str) -> Candidate {
    // `at` begins only `at end:`.
    let insert = if w == "at" { "at end:" } else { w };
    Candidate {
        label: insert.to_string(),
        what: What::Keyword,
        detail: None,
        insert: insert.to_string(),
    }
}

fn texts(outline: &Outline, backticks: bool, typed: &str) -> Candidates {
    ranked_by(
        &outline.statements,
        |(_, t)| t.clone(),
        |(l, t)| Candidate {
            label: t.clone(),
            what: What::Text,
            detail: Some(format!("line {l}")),
            insert: if backticks {
                format!("`{t}`")
            } else {
                t.clone()
            },
        },
        typed,
    )
}

/// [`ranked`] over many items (a task's lines), making candidates only of those kept:
/// a 100,000-line task offers 100 of its lines, not 100,000 made and cut.
fn ranked_by<T>(
    items: &[T],
    label: impl Fn(&T) -> String,
    make: impl Fn(&T) -> Candidate,
    typed: &str,
) -> Candidates {
    let typed = typed.to_ascii_lowercase();
    let mut kept: Vec<&T> = Vec::new();
    let mut more = false;
    for first in [true, false] {
        for item in items {
            let l = label(item).to_ascii_lowercase();
            let fits = if first {
                l.starts_with(&typed)
            } else {
                !l.starts_with(&typed) && l.contains(&typed)
            };
            if fits {
                if kept.len() == MAX_CANDIDATES {
                    more = true;
                    break;
                }
                kept.push(item);
            }
        }
        if more {
            break;
        }
    }
    Candidates {
        items: kept.into_iter().map(make).collect(),
        incomplete: more,
    }
}

/// Those that begin with what is typed (ignoring case), then those that contain it, in
/// their order; at most [`MAX_CANDIDATES`].
fn ranked(items: Vec<Candidate>, typed: &str) -> Candidates {
    let typed = typed.to_ascii_lowercase();
    let (mut first, mut then) = (Vec::new(), Vec::new());
    for c in items {
        let label = c.label.to_ascii_lowercase();
        if label.starts_with(&typed) {
            first.push(c);
        } else if label.contains(&typed) {
            then.push(c);
        }
    }
    first.extend(then);
    let incomplete = first.len() > MAX_CANDIDATES;
    first.truncate(MAX_CANDIDATES);
    Candidates {
        items: first,
        incomplete,
    }
}

fn where_is(place: &Place) -> String {
    match place {
        Place::Object { from, to, .. } if from == to => {
            format!(
                "at ({}, {})",
                assertion::num(from.0),
                assertion::num(from.1)
            )
        }
        Place::Object { from, to, .. } => format!(
            "a wall from ({}, {}) to ({}, {})",
            assertion::num(from.0),
            assertion::num(from.1),
            assertion::num(to.0),
            assertion::num(to.1)
        ),
        Place::Point(x, y) => format!("({}, {})", assertion::num(*x), assertion::num(*y)),
    }
}

/// A few words (markdown) on what is at `offset` in an assertion whose content starts
/// at `base`: a line reference's statement, a statement text's lines, an object's
/// place, a variable; with the bytes it covers.
pub fn hover_assertion(
    text: &str,
    outline: &Outline,
    base: usize,
    end: usize,
    offset: usize,
) -> Option<(String, Range<usize>)> {
    // The string's closing quotes may be in `base..end` (a multi-line string's
    // three): an assertion never ends with a quote.
    let content = text.get(base..end)?.trim_end_matches(['"', '\'']);
    let toks = assertion::tokens(content)?;
    let at = offset.checked_sub(base)?;
    let i = toks.iter().position(|(_, r)| r.start <= at && at < r.end)?;
    let (tok, range) = &toks[i];
    let span = base + range.start..base + range.end;
    let said = match tok {
        assertion::Token::Number(n) => {
            let after_line = i > 0
                && matches!(&toks[i - 1].0, assertion::Token::Word(w) if w.eq_ignore_ascii_case("line"));
            if !after_line {
                return None;
            }
            let (l, t) = outline
                .statements
                .iter()
                .find(|(l, _)| f64::from(*l) == *n)?;
            format!("line {l} of the task: `{t}`")
        }
        assertion::Token::Quoted(q) => {
            let wanted = assertion::canonical(q);
            let lines: Vec<String> = outline
                .statements
                .iter()
                .filter(|(_, t)| assertion::names_statement(&wanted, t))
                .map(|(l, t)| format!("line {l}: `{t}`"))
                .collect();
            if lines.is_empty() {
                return None;
            }
            format!("the statement at\n\n{}", lines.join("\n\n"))
        }
        assertion::Token::Word(w) => {
            if let Some(p) =
                outline.objects.iter().flatten().find(
                    |p| matches!(p, Place::Object { name, .. } if name.eq_ignore_ascii_case(w)),
                )
            {
                format!("`{w}`: {} in the test's world", where_is(p))
            } else if let Some(v) = outline.variables.iter().find(|v| v.eq_ignore_ascii_case(w)) {
                let by: Vec<String> = outline
                    .statements
                    .iter()
                    .filter(|(_, t)| {
                        crate::file::assigns(t).is_some_and(|a| a.eq_ignore_ascii_case(v))
                    })
                    .map(|(l, t)| format!("line {l}: `{t}`"))
                    .collect();
                if by.is_empty() {
                    format!("variable `{v}`")
                } else {
                    format!("variable `{v}`, assigned at\n\n{}", by.join("\n\n"))
                }
            } else {
                return None;
            }
        }
        assertion::Token::Sign(_) => return None,
    };
    Some((said, span))
}

/// What a key of a test takes, when `offset` is on one (a key at a line's start).
pub fn hover_key(text: &str, offset: usize) -> Option<(String, Range<usize>)> {
    let start = word_start(text, offset);
    let len = text
        .get(start..)?
        .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .unwrap_or(text.len() - start);
    let word = text.get(start..start + len)?;
    let line_start = text[..start].rfind('\n').map_or(0, |i| i + 1);
    let rest = text[start + len..].trim_start();
    if !text[line_start..start].trim().is_empty() || !rest.starts_with('=') {
        return None;
    }
    let (key, what) = KEYS.iter().find(|(k, _)| *k == word)?;
    Some((format!("`{key}`: {what}"), start..start + len))
}

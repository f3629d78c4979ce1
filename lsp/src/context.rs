//! Where the cursor is, read from the text of its line up to the cursor. Statements
//! are one per line, so the line alone tells a statement's start from a command's
//! arguments, and a half-typed line never depends on the rest of the file parsing.

use ilmr_compiler::Span;
use ilmr_compiler::lexer::{Token, lex};
use ilmr_stdlib::{Command, CommandSpec, Form, Occurs, Param, ParamKind};

/// An argument written before the cursor, by its shape alone.
#[derive(Debug, Clone, PartialEq)]
pub enum ArgShape {
    Word(String),
    Number,
    Setting(String),
    Other,
}

#[derive(Debug, Clone, PartialEq)]
pub enum Context {
    /// At the start of a statement: commands, skills, block keywords, variables.
    Statement,
    /// After `v =`: a command, a skill, a while loop or an expression.
    AfterAssign,
    /// After `priority =`.
    Priority,
    /// In the condition of `if(` or `while(`.
    Condition,
    /// Inside `name(`; `previous` are the arguments before the one being written.
    Args {
        name: String,
        previous: Vec<ArgShape>,
        /// The key when the cursor is in the value of `key=`.
        setting: Option<String>,
        /// Where the argument list opens, for signature help's range.
        open: usize,
    },
    /// Elsewhere in an expression (`v = a + |`).
    Expression,
    /// In a comment, a break pattern or a skill header: nothing to offer.
    Nothing,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Cursor {
    pub context: Context,
    /// The partly typed name the cursor ends, which a completion replaces.
    pub word: Span,
}

/// `line_start..offset` is the line's text before the cursor.
pub fn at(text: &str, line_start: usize, offset: usize) -> Cursor {
    let prefix = &text[line_start..offset];
    let word_len: usize = prefix
        .chars()
        .rev()
        .take_while(|c| c.is_alphanumeric() || *c == '_')
        .map(char::len_utf8)
        .sum();
    let word = Span::new(offset - word_len, offset);
    let before = &prefix[..prefix.len() - word_len];
    Cursor {
        context: classify(before, line_start),
        word,
    }
}

fn classify(before: &str, base: usize) -> Context {
    let lexed = lex(before);
    if !lexed.comments.is_empty() {
        return Context::Nothing;
    }
    let tokens: Vec<(Token, Span)> = lexed.tokens;
    if tokens
        .iter()
        .any(|(t, _)| matches!(t, Token::Break | Token::Colon))
    {
        return Context::Nothing;
    }
    // Open parentheses with the token that precedes each.
    let mut open: Vec<usize> = Vec::new();
    for (i, (t, _)) in tokens.iter().enumerate() {
        match t {
            Token::LParen => open.push(i),
            Token::RParen => {
                open.pop();
            }
            _ => {}
        }
    }
    // Only the outermost parenthesis of a line opens arguments or a condition; inner ones
    // group arithmetic.
    if let Some(&first) = open.first() {
        let opener = first.checked_sub(1).map(|i| tokens[i]);
        let inner = &tokens[first + 1..];
        return match opener {
            Some((Token::If | Token::While, _)) => Context::Condition,
            Some((Token::Ident, name)) if open.len() == 1 => {
                args(name.slice(before), inner, before, tokens[first].1, base)
            }
            _ => Context::Expression,
        };
    }
    match tokens.as_slice() {
        [] => Context::Statement,
        [(Token::Ident, _), (Token::Assign, _)] => Context::AfterAssign,
        [(Token::Priority, _), (Token::Assign, _)] => Context::Priority,
        _ if tokens.iter().any(|(t, _)| *t == Token::Assign) => Context::Expression,
        _ => Context::Nothing,
    }
}

fn args(name: &str, inner: &[(Token, Span)], text: &str, open: Span, base: usize) -> Context {
    let mut previous = Vec::new();
    let mut current: Vec<(Token, &str)> = Vec::new();
    for (t, span) in inner {
        if *t == Token::Comma {
            previous.push(shape(&current));
            current.clear();
        } else {
            current.push((*t, span.slice(text)));
        }
    }
    let setting = match current.as_slice() {
        [(Token::Ident, key), (Token::Assign, _), ..] => Some(key.to_lowercase()),
        _ => None,
    };
    Context::Args {
        name: name.to_string(),
        previous,
        setting,
        open: base + open.start as usize,
    }
}

fn shape(tokens: &[(Token, &str)]) -> ArgShape {
    match tokens {
        [(Token::Ident, w)] => ArgShape::Word(w.to_lowercase()),
        [(Token::Number, _)] | [(Token::Minus, _), (Token::Number, _)] => ArgShape::Number,
        [(Token::Ident, k), (Token::Assign, _), ..] => ArgShape::Setting(k.to_lowercase()),
        _ => ArgShape::Other,
    }
}

/// A parameter the argument at the cursor may fill, in the form it belongs to.
#[derive(Debug, Clone, Copy)]
pub struct Slot {
    pub form: usize,
    /// Index into the form's `params`.
    pub param: usize,
}

impl Slot {
    pub fn param(self, spec: &'static CommandSpec) -> &'static Param {
        &spec.forms[self.form].params[self.param]
    }
}

/// What the next argument may be, over every form the arguments so far still fit: the
/// positional parameter(s) it could fill and the settings not given yet.
pub fn slots(spec: &'static CommandSpec, previous: &[ArgShape]) -> Vec<Slot> {
    let mut out = Vec::new();
    for (f, form) in spec.forms.iter().enumerate() {
        if let Some(params) = next_params(spec, form, previous) {
            out.extend(params.into_iter().map(|param| Slot { form: f, param }));
        }
    }
    out
}

/// The forms the arguments so far fit, best first (for signature help).
pub fn fitting_forms(spec: &'static CommandSpec, previous: &[ArgShape]) -> Vec<usize> {
    (0..spec.forms.len())
        .filter(|&f| next_params(spec, &spec.forms[f], previous).is_some())
        .collect()
}

fn next_params(spec: &CommandSpec, form: &Form, previous: &[ArgShape]) -> Option<Vec<usize>> {
    let given: Vec<&str> = previous
        .iter()
        .filter_map(|a| match a {
            ArgShape::Setting(k) => Some(k.as_str()),
            _ => None,
        })
        .collect();
    let setting_index = |key: &str| {
        form.params
            .iter()
            .position(|p| matches!(p.kind, ParamKind::Setting { key: k, .. } if k == key))
    };
    if given.iter().any(|k| setting_index(k).is_none()) {
        return None;
    }
    let positional: Vec<usize> = (0..form.params.len())
        .filter(|&i| !matches!(form.params[i].kind, ParamKind::Setting { .. }))
        .collect();
    let mut p = 0;
    for arg in previous
        .iter()
        .filter(|a| !matches!(a, ArgShape::Setting(_)))
    {
        loop {
            let &i = positional.get(p)?;
            let param = &form.params[i];
            let fits = fits(spec, &param.kind, arg);
            match param.occurs {
                Occurs::One if fits => {
                    p += 1;
                    break;
                }
                Occurs::One => return None,
                Occurs::Optional if fits => {
                    p += 1;
                    break;
                }
                Occurs::Optional => p += 1,
                Occurs::Many | Occurs::Pairs => break,
            }
        }
    }
    let mut next = Vec::new();
    for &i in &positional[p.min(positional.len())..] {
        next.push(i);
        if form.params[i].occurs != Occurs::Optional {
            break;
        }
    }
    for (i, param) in form.params.iter().enumerate() {
        if let ParamKind::Setting { key, .. } = param.kind
            && !given.contains(&key)
        {
            next.push(i);
        }
    }
    Some(next)
}

/// Whether an argument of this shape may fill a parameter: keywords must be the
/// parameter's own; names and numbers are judged loosely, as the checker will say more.
fn fits(spec: &CommandSpec, kind: &ParamKind, arg: &ArgShape) -> bool {
    match (kind, arg) {
        (ParamKind::Keyword { words } | ParamKind::Mode { words, .. }, ArgShape::Word(w)) => {
            words.iter().any(|k| k.eq_ignore_ascii_case(w))
        }
        (ParamKind::Keyword { .. } | ParamKind::Mode { .. }, _) => false,
        (ParamKind::OneOf { kinds }, _) => kinds.iter().any(|k| fits(spec, k, arg)),
        (_, ArgShape::Word(w)) => !spec.has_keyword(w),
        (ParamKind::Value { .. }, _) => true,
        (ParamKind::Model { .. }, ArgShape::Number) => true,
        _ => false,
    }
}

/// The command named by an argument list's opener, if it is one of the catalogue's.
pub fn command(name: &str) -> Option<&'static CommandSpec> {
    Command::from_name(name).map(Command::spec)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn context(line: &str) -> Context {
        at(line, 0, line.len()).context
    }

    fn slot_names(line: &str) -> Vec<&'static str> {
        let Context::Args { name, previous, .. } = context(line) else {
            panic!("not in arguments: {line}");
        };
        let spec = command(&name).unwrap();
        let mut names: Vec<&'static str> = Vec::new();
        for s in slots(spec, &previous) {
            if !names.contains(&s.param(spec).name) {
                names.push(s.param(spec).name);
            }
        }
        names
    }

    #[test]
    fn statement_positions() {
        assert_eq!(context("    goa"), Context::Statement);
        assert_eq!(context("t = tu"), Context::AfterAssign);
        assert_eq!(context("priority = hi"), Context::Priority);
        assert_eq!(context("x = a + "), Context::Expression);
        assert_eq!(context("if(bat"), Context::Condition);
        assert_eq!(context("while(c < (ma"), Context::Condition);
        assert_eq!(context("// turn("), Context::Nothing);
        assert_eq!(context("break(tur"), Context::Nothing);
        assert_eq!(context("speed(1) "), Context::Nothing);
    }

    #[test]
    fn the_word_is_unicode() {
        let line = "x = ovi_ö";
        let c = at(line, 0, line.len());
        assert_eq!(c.word.slice(line), "ovi_ö");
    }

    #[test]
    fn arguments_follow_the_grammar() {
        assert_eq!(slot_names("t = turn("), ["d", "c", "direction", "target"]);
        assert_eq!(slot_names("turn(d=90,"), ["c"]);
        assert_eq!(slot_names("followwall("), ["side"]);
        assert_eq!(slot_names("followwall(left,"), ["distance"]);
        assert_eq!(slot_names("s=sensor("), ["sensor"]);
        assert_eq!(
            slot_names("sensor(scanner,"),
            ["object", "which", "forever"]
        );
        assert_eq!(slot_names("sensor(scanner,door,"), ["side", "forever"]);
        assert_eq!(slot_names("sensor(battery,left,"), ["forever"]);
    }

    #[test]
    fn setting_values_are_known() {
        let Context::Args { setting, .. } = context("turn(d=9") else {
            panic!()
        };
        assert_eq!(setting.as_deref(), Some("d"));
    }
}

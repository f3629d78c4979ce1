//! Semantic tokens: the lexer gives keywords, numbers, operators and comments; the
//! checker's resolutions tell commands, skills, variables, grammar keywords, model
//! names and paths apart, which no TextMate grammar can.

use std::collections::HashSet;

use ilmr_compiler::Span;
use ilmr_compiler::check::Resolved;
use ilmr_compiler::diagnostic::FileId;
use ilmr_compiler::lexer::{Token, lex};
use tower_lsp_server::ls_types::{
    SemanticToken, SemanticTokenModifier, SemanticTokenType, SemanticTokensLegend,
};

use crate::analysis::Program;
use crate::line_index::LineIndex;

/// Indexes into `legend().token_types`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u32)]
enum Kind {
    Keyword,
    Function,
    Method,
    Variable,
    EnumMember,
    Property,
    Namespace,
    Number,
    Comment,
    Operator,
    String,
}

const DECLARATION: u32 = 1;
const READONLY: u32 = 2;
const DEFAULT_LIBRARY: u32 = 4;

pub fn legend() -> SemanticTokensLegend {
    SemanticTokensLegend {
        token_types: vec![
            SemanticTokenType::KEYWORD,
            SemanticTokenType::FUNCTION,
            SemanticTokenType::METHOD,
            SemanticTokenType::VARIABLE,
            SemanticTokenType::ENUM_MEMBER,
            SemanticTokenType::PROPERTY,
            SemanticTokenType::NAMESPACE,
            SemanticTokenType::NUMBER,
            SemanticTokenType::COMMENT,
            SemanticTokenType::OPERATOR,
            SemanticTokenType::STRING,
        ],
        token_modifiers: vec![
            SemanticTokenModifier::DECLARATION,
            SemanticTokenModifier::READONLY,
            SemanticTokenModifier::DEFAULT_LIBRARY,
        ],
    }
}

/// The tokens of `file` that lie within `within` (the whole file for
/// `semanticTokens/full`, the lines an editor shows for `semanticTokens/range`).
pub fn tokens(
    program: &Program,
    file: FileId,
    index: &LineIndex,
    within: Span,
) -> Vec<SemanticToken> {
    let text = program.text(file);
    let mut marks = Marks {
        all: Vec::new(),
        within,
    };
    let lexed = lex(text);
    for (token, span) in &lexed.tokens {
        let kind = match token {
            Token::If
            | Token::EndIf
            | Token::While
            | Token::EndWhile
            | Token::Check
            | Token::Checkend
            | Token::Priority
            | Token::Highest => Kind::Keyword,
            Token::Break => {
                let word = Span::new(span.start as usize, span.start as usize + 5);
                marks.put(word, Kind::Keyword, 0);
                let p = ilmr_compiler::lexer::break_pattern(text, *span);
                if let Some(inner) = p.inner.filter(|s| !s.is_empty()) {
                    marks.put(inner, Kind::String, 0);
                }
                continue;
            }
            Token::Number => Kind::Number,
            Token::Assign
            | Token::EqEq
            | Token::NotEq
            | Token::Lt
            | Token::Le
            | Token::Gt
            | Token::Ge
            | Token::GeAlt
            | Token::Plus
            | Token::Minus
            | Token::Star
            | Token::Slash => Kind::Operator,
            _ => continue,
        };
        marks.put(*span, kind, 0);
    }
    for c in &lexed.comments {
        marks.put(*c, Kind::Comment, 0);
    }
    for unit in program.units_of(file) {
        // A set, not a search per reference: a name bound on every line of a long file
        // would make that quadratic.
        let defs: HashSet<Span> = unit
            .vars
            .iter()
            .flat_map(|(_, var)| var.defs.iter())
            .filter(|(f, _)| *f == file)
            .map(|(_, s)| *s)
            .collect();
        for &(span, resolved) in &unit.refs {
            let (kind, mods) = match resolved {
                Resolved::Command(_) => (Kind::Function, DEFAULT_LIBRARY),
                Resolved::Skill(_) => (Kind::Method, 0),
                Resolved::Variable(_) => {
                    let def = defs.contains(&span);
                    (Kind::Variable, if def { DECLARATION } else { 0 })
                }
                Resolved::Keyword => (Kind::EnumMember, 0),
                Resolved::Model => (Kind::Property, READONLY),
                Resolved::Path => (Kind::Namespace, 0),
            };
            marks.put(span, kind, mods);
        }
    }
    for skill in &program.tree(file).skills {
        let span = skill.name.span;
        marks.put(span, Kind::Method, DECLARATION);
    }
    encode(marks.in_order(), text, index)
}

/// What each span of the file is, as the lexer and then the checker saw it.
struct Marks {
    all: Vec<(Span, Kind, u32)>,
    within: Span,
}

impl Marks {
    fn put(&mut self, span: Span, kind: Kind, mods: u32) {
        if span.start >= self.within.start && span.end <= self.within.end {
            self.all.push((span, kind, mods));
        }
    }

    /// By start offset, the last put at each start: a name the checker resolved
    /// replaces what the lexer saw there. A sorted vector rather than an ordered map,
    /// which costs an allocation per token where a file has millions.
    fn in_order(mut self) -> impl Iterator<Item = (Span, Kind, u32)> {
        // Stable, so marks at one start stay in the order they were put.
        self.all.sort_by_key(|(span, ..)| span.start);
        let mut all = self.all.into_iter().peekable();
        std::iter::from_fn(move || {
            loop {
                let mark = all.next()?;
                if all.peek().is_none_or(|next| next.0.start != mark.0.start) {
                    return Some(mark);
                }
            }
        })
    }
}

fn encode(
    marks: impl Iterator<Item = (Span, Kind, u32)>,
    text: &str,
    index: &LineIndex,
) -> Vec<SemanticToken> {
    let mut out = Vec::new();
    let (mut line, mut col) = (0, 0);
    let mut covered = 0;
    let mut walk = index.walk(text);
    for (span, kind, mods) in marks {
        // Overlaps (a ref inside a comment cannot happen, but a pattern could be lexed
        // oddly) keep the first token.
        if span.start < covered || span.is_empty() {
            continue;
        }
        covered = span.end;
        let start = walk.position(span.start as usize);
        let end = walk.position(span.end as usize);
        if end.line != start.line {
            continue;
        }
        let delta_line = start.line - line;
        let delta_start = if delta_line == 0 {
            start.character - col
        } else {
            start.character
        };
        out.push(SemanticToken {
            delta_line,
            delta_start,
            length: end.character - start.character,
            token_type: kind as u32,
            token_modifiers_bitset: mods,
        });
        line = start.line;
        col = start.character;
    }
    out
}

//! Hover: a command's documentation with the robot's ranges, a variable's kind and the
//! statement that binds it, a model name's value in ROBO.INI, a skill's definition.

use ilmr_compiler::Span;
use ilmr_compiler::ast::{Arg, StmtKind};
use ilmr_compiler::check::{Resolved, SkillId, Target};
use ilmr_compiler::diagnostic::FileId;
use ilmr_compiler::lexer::{Token, lex};
use ilmr_model::RobotModel;
use ilmr_stdlib::{Command, CommandSpec, ParamKind};

use crate::analysis::{Program, Symbol, stmt_containing};
use crate::{docs, lens};

/// Markdown and the span it describes.
pub fn hover(
    program: &Program,
    model: &RobotModel,
    file: FileId,
    offset: usize,
) -> Option<(String, Span)> {
    if let Some(id) = program.skill_header_at(file, offset) {
        let info = program.analysis().skills.get(id);
        let span = program.tree(file).skills[info.index].name.span;
        return Some((skill(program, id), span));
    }
    let Some((span, resolved, unit)) = program.resolved_at(file, offset) else {
        return structural(program, model, file, offset);
    };
    let text = match resolved {
        Resolved::Command(c) => docs::command(c.spec(), model),
        Resolved::Skill(id) => {
            let mut text = skill(program, id);
            // A call of a skill with parameters runs its specialization for the call's
            // arguments.
            if let Some(&i) = unit
                .specials
                .iter()
                .find(|(stmt, _)| stmt.contains(span.start as usize))
                .map(|(_, i)| i)
            {
                let label = &program.analysis().specials[i as usize].label;
                text.push_str(&format!(
                    "\n\nThis call runs `{label}`: the skill's body with these arguments in place of its parameters."
                ));
            }
            text
        }
        Resolved::Variable(id) => variable(
            program,
            &unit.vars.get(id).spelling.to_lowercase(),
            unit.vars.get(id).kind,
        ),
        Resolved::Model => {
            let name = span.slice(program.text(file));
            match model.lookup(name) {
                Some(m) => docs::model_name(m, model),
                None => docs::default_parameter(name, model)?,
            }
        }
        Resolved::Keyword => keyword(program, model, file, span)?,
        Resolved::Path => {
            let name = span.slice(program.text(file));
            let uses = program
                .occurrences(&Symbol::Path(name.to_lowercase()))
                .len();
            format!(
                "**{name}** — a path (`record`, `createpath`, `followpath`), named {uses} time(s)"
            )
        }
    };
    Some((text, span))
}

fn skill(program: &Program, id: SkillId) -> String {
    let info = program.analysis().skills.get(id);
    let tree = program.tree(info.file);
    let body = tree.skills[info.index].span.to(info.header);
    let source = body.slice(program.text(info.file)).trim_end();
    let place = match program.uri(info.file) {
        Some(uri) => format!("defined in `{}`", uri.rsplit('/').next().unwrap_or(uri)),
        None => "a built-in skill".to_string(),
    };
    let mut text = format!(
        "**{}** — skill, {place}\n\n```ilmr\n{source}\n```",
        info.name
    );
    if !info.params.is_empty() {
        let params: Vec<String> = info
            .params
            .iter()
            .map(|p| {
                if p.words.is_empty() {
                    format!("`{}`: a number", p.name)
                } else {
                    let words: Vec<String> = p.words.iter().map(|w| format!("`{w}`")).collect();
                    format!("`{}`: one of {}", p.name, words.join(", "))
                }
            })
            .collect();
        text.push_str(&format!(
            "\n\nParameters, given in this order: {}.",
            params.join("; ")
        ));
    }
    text
}

fn variable(program: &Program, name: &str, kind: ilmr_stdlib::VarKind) -> String {
    let fields: Vec<&str> = kind.fields().iter().map(|f| f.name()).collect();
    let mut out = format!(
        "**{name}** — variable holding {}\n\nfields: `{}`",
        kind.describe(),
        fields.join("`, `")
    );
    let defs = program.variable_defs(name);
    if !defs.is_empty() {
        out.push_str("\n\nbound by:");
    }
    for (file, span) in defs.iter().take(5) {
        let text = program.text(*file);
        let tree = program.tree(*file);
        let line = text[..span.start as usize].matches('\n').count() + 1;
        let Some(stmt) = stmt_containing(tree, *span) else {
            continue;
        };
        let what = program
            .units_of(*file)
            .find_map(|u| u.targets.get(&stmt.span))
            .map(|t| match t {
                Target::Command { command, form } => {
                    format!(
                        "`{}` ({})",
                        command.name(),
                        command.spec().forms[*form].label
                    )
                }
                Target::Skill(id) => format!("skill `{}`", program.analysis().skills.get(*id).name),
                Target::Copy(_) => "a copy of another variable".to_string(),
            })
            .unwrap_or_else(|| match stmt.kind {
                StmtKind::While { .. } => "`while`".to_string(),
                StmtKind::Assign { .. } => "arithmetic".to_string(),
                _ => "a statement".to_string(),
            });
        let file_name = program
            .uri(*file)
            .map_or("", |u| u.rsplit('/').next().unwrap_or(u));
        out.push_str(&format!(
            "\n- {what} at {file_name}:{line}: `{}`",
            stmt.span.slice(text).trim()
        ));
    }
    if defs.len() > 5 {
        out.push_str(&format!("\n- … and {} more", defs.len() - 5));
    }
    out
}

/// A keyword or setting key of a command's grammar: the parameter it belongs to.
fn keyword(program: &Program, model: &RobotModel, file: FileId, span: Span) -> Option<String> {
    let text = program.text(file);
    let word = span.slice(text);
    let stmt = stmt_containing(program.tree(file), span)?;
    let call = match &stmt.kind {
        StmtKind::Call { call, .. } => call,
        _ => return None,
    };
    let spec = Command::from_name(call.name.text)?.spec();
    let is_key = call.args.as_ref().is_some_and(|a| {
        a.items
            .iter()
            .any(|arg| matches!(arg, Arg::Setting { key, .. } if key.span == span))
    });
    let param = spec.forms.iter().flat_map(|f| f.params.iter()).find(|p| {
        if is_key {
            matches!(p.kind, ParamKind::Setting { key, .. } if key.eq_ignore_ascii_case(word))
        } else {
            has_word(&p.kind, word)
        }
    })?;
    Some(format!(
        "**{}** — {} of `{}`\n\n{}",
        word.to_lowercase(),
        if is_key { "setting" } else { "keyword" },
        spec.name,
        docs::param(param, model)
    ))
}

fn has_word(kind: &ParamKind, word: &str) -> bool {
    match kind {
        ParamKind::Keyword { words } | ParamKind::Mode { words, .. } => {
            words.iter().any(|w| w.eq_ignore_ascii_case(word))
        }
        ParamKind::OneOf { kinds } => kinds.iter().any(|k| has_word(k, word)),
        _ => false,
    }
}

/// The words the checker does not resolve: `if`, `while`, `break` and the block closers.
fn structural(
    program: &Program,
    model: &RobotModel,
    file: FileId,
    offset: usize,
) -> Option<(String, Span)> {
    let stmt = program.stmt_at(file, offset);
    // Anywhere on `break(pattern)`, the pattern's words included: what it ends.
    if let Some(s) = stmt
        && matches!(s.kind, StmtKind::Break { pattern: Some(_) })
    {
        let doc = docs::command(Command::Break.spec(), model) + &ends(program, stmt)?;
        return Some((doc, s.span));
    }
    let text = program.text(file);
    let line_start = text[..offset].rfind('\n').map_or(0, |i| i + 1);
    let line_end = text[offset..].find('\n').map_or(text.len(), |i| offset + i);
    let line = &text[line_start..line_end];
    let (token, span) = lex(line)
        .tokens
        .into_iter()
        .find(|(_, s)| s.contains(offset - line_start))?;
    let command = match token {
        Token::If | Token::EndIf => Command::If,
        Token::While | Token::EndWhile => Command::While,
        Token::Check | Token::Checkend => Command::Check,
        Token::Break => Command::Break,
        Token::Priority | Token::Highest => {
            let doc = "**priority = highest** — first in a block: when the block starts, every other command of the task ends (section 4.3).";
            return Some((doc.to_string(), shift(span, line_start)));
        }
        Token::Number => return number(program, model, file, stmt, shift(span, line_start)),
        _ => return None,
    };
    let spec: &CommandSpec = command.spec();
    let span = match token {
        Token::Break => Span::new(span.start as usize, span.start as usize + 5),
        _ => span,
    };
    Some((docs::command(spec, model), shift(span, line_start)))
}

/// A number argument: the parameter it sets in the form the checker matched, with
/// unit and range.
fn number(
    program: &Program,
    model: &RobotModel,
    file: FileId,
    stmt: Option<&ilmr_compiler::ast::Stmt<'_>>,
    span: Span,
) -> Option<(String, Span)> {
    let stmt = stmt?;
    let StmtKind::Call { call, .. } = &stmt.kind else {
        return None;
    };
    let args = call.args.as_ref()?;
    let Target::Command { command, form } = program
        .units_of(file)
        .find_map(|u| u.targets.get(&stmt.span))
        .copied()?
    else {
        return None;
    };
    let form = &command.spec().forms[form];
    for (arg, param) in crate::units::params(form, args) {
        if arg.span().contains(span.start as usize) {
            return Some((docs::param(param?, model), span));
        }
    }
    None
}

/// What a `break(pattern)` ends: every statement whose text contains its needle, and
/// what stands inside a matched `if` or `while`.
fn ends(program: &Program, stmt: Option<&ilmr_compiler::ast::Stmt<'_>>) -> Option<String> {
    let StmtKind::Break { pattern: Some(p) } = &stmt?.kind else {
        return None;
    };
    let needle = ilmr_compiler::check::needle(p);
    let ended = lens::ended_by(program, needle);
    if ended.is_empty() {
        return Some(format!(
            "\n\n---\n\nEnds nothing: no statement contains `{needle}`."
        ));
    }
    let mut out = format!(
        "\n\n---\n\nEnds, if they are running when it is issued ({} statement{}):\n",
        ended.len(),
        if ended.len() == 1 { "" } else { "s" }
    );
    for &(file, span, inside) in ended.iter().take(lens::ENDED_LISTED) {
        let text = program.text(file);
        let line = text[..span.start as usize].matches('\n').count() + 1;
        let uri = program.uri(file).unwrap_or("");
        let name = uri.rsplit('/').next().unwrap_or(uri);
        let quoted = span.slice(text).trim();
        let through = if inside {
            " (inside a matched block)"
        } else {
            ""
        };
        out.push_str(&format!("\n- {name}:{line} `{quoted}`{through}"));
    }
    if ended.len() > lens::ENDED_LISTED {
        out.push_str(&format!(
            "\n- and {} more",
            ended.len() - lens::ENDED_LISTED
        ));
    }
    Some(out)
}

fn shift(span: Span, by: usize) -> Span {
    Span::new(span.start as usize + by, span.end as usize + by)
}

//! `ilmrc fmt`: the canonical form of a file. Lower-case commands and keywords, `==`
//! and `>=`, four spaces per nesting level, every variable and skill spelt as it was
//! first bound or defined, other names as written, comments kept, runs of empty lines
//! reduced to one (one is what separates blocks). Files that do not parse are not
//! formatted.

use std::collections::HashMap;

use ilmr_model::RobotModel;
use ilmr_stdlib::Command;

use crate::ast::{Arg, Block, Call, Expr, ExprKind, Name, Stmt, StmtKind};
use crate::check::{Resolved, Source, analyze};
use crate::diagnostic::{Code, Diagnostic};
use crate::span::{LineIndex, Span};

const INDENT: &str = "    ";

/// The formatted text, or the syntax errors that prevent formatting. The robot model
/// only tells object and sensor names from variables of the same spelling.
pub fn format(source: &str, model: &RobotModel) -> Result<String, Vec<Diagnostic>> {
    let sources = [Source::new("", source)];
    let analysis = analyze(&sources, model);
    let entry = &analysis.files[0];
    if entry.syntax_errors > 0 {
        // The note that counts what the limit left out goes with them: the analysis
        // may have kept none of the syntax errors.
        let syntax = analysis.diagnostics.iter().filter(|d| {
            matches!(&d.code.as_str()[..3], "E01" | "E02")
                || matches!(d.code, Code::TooManyErrors | Code::TooManyWarnings)
        });
        return Err(syntax.cloned().collect());
    }
    let mut spellings: HashMap<Span, String> = HashMap::new();
    for unit in analysis.units.iter().filter(|u| u.file.0 == 0) {
        for (span, resolved) in &unit.refs {
            let spelling = match resolved {
                Resolved::Variable(id) => unit.vars.get(*id).spelling.clone(),
                Resolved::Skill(id) => analysis.skills.get(*id).name.clone(),
                _ => continue,
            };
            spellings.insert(*span, spelling);
        }
    }
    let file = &entry.tree;
    let index = LineIndex::new(source);
    let mut f = Formatter {
        source,
        index: &index,
        spellings,
        lines: vec![None; index.line_count()],
    };
    for skill in &file.skills {
        let head = f.header(skill);
        f.put(skill.header, 0, head);
    }
    f.blocks(&file.blocks, 0);
    for skill in &file.skills {
        f.blocks(&skill.blocks, 0);
    }
    Ok(f.assemble(&file.comments))
}

struct Formatter<'a, 's> {
    source: &'s str,
    index: &'a LineIndex,
    /// Where a name means a variable or a skill: how it was first spelt.
    spellings: HashMap<Span, String>,
    /// 0-based line -> (depth, canonical text).
    lines: Vec<Option<(usize, String)>>,
}

impl<'s> Formatter<'_, 's> {
    fn put(&mut self, span: Span, depth: usize, text: String) {
        let line = self.index.line_of(span.start as usize);
        self.lines[line] = Some((depth, text));
    }

    fn spelling<'n>(&'n self, name: &Name<'n>) -> &'n str {
        self.spellings
            .get(&name.span)
            .map_or(name.text, String::as_str)
    }

    fn blocks(&mut self, blocks: &[Block<'s>], depth: usize) {
        for block in blocks {
            for stmt in &block.stmts {
                self.stmt(stmt, depth);
            }
        }
    }

    fn stmt(&mut self, stmt: &Stmt<'s>, depth: usize) {
        let text = match &stmt.kind {
            StmtKind::Call { bind, call } => {
                let call = self.call(call);
                match bind {
                    Some(b) => format!("{} = {call}", self.spelling(b)),
                    None => call,
                }
            }
            StmtKind::Assign { target, value } => {
                format!("{} = {}", self.spelling(target), self.expr(value, None))
            }
            StmtKind::If(c) => {
                self.put(
                    stmt.span,
                    depth,
                    format!("if({})", self.expr(&c.cond, None)),
                );
                self.blocks(&c.body, depth + 1);
                if let Some(end) = c.end {
                    self.put(end, depth, "endif".into());
                }
                return;
            }
            StmtKind::While { bind, body } => {
                let head = format!("while({})", self.expr(&body.cond, None));
                let head = match bind {
                    Some(b) => format!("{} = {head}", self.spelling(b)),
                    None => head,
                };
                self.put(stmt.span, depth, head);
                self.blocks(&body.body, depth + 1);
                if let Some(end) = body.end {
                    self.put(end, depth, "endwhile".into());
                }
                return;
            }
            StmtKind::Check { body, end } => {
                self.put(stmt.span, depth, "check".into());
                self.blocks(body, depth + 1);
                if let Some(end) = end {
                    self.put(*end, depth, "checkend".into());
                }
                return;
            }
            StmtKind::Break { pattern } => match pattern {
                Some(p) => format!("break({})", p.text.trim()),
                None => "break".into(),
            },
            StmtKind::Priority => "priority = highest".into(),
            StmtKind::Error => stmt.span.slice(self.source).to_string(),
        };
        self.put(stmt.span, depth, text);
    }

    /// `NAME:`, or `NAME(d,side=left/right):` with a word list written as declared.
    fn header(&self, skill: &crate::ast::Skill<'s>) -> String {
        let name = self.spelling(&skill.name);
        let Some(params) = &skill.params else {
            return format!("{name}:");
        };
        let items: Vec<String> = params
            .items
            .iter()
            .map(|a| match a {
                Arg::Setting { key, value } => format!("{}={}", key.text, self.words(value)),
                Arg::Positional(e) => self.expr(e, None),
            })
            .collect();
        format!("{name}({}):", items.join(","))
    }

    /// `left/right`: the words of a parameter, without the spaces of a division.
    fn words(&self, e: &Expr<'s>) -> String {
        match &e.kind {
            ExprKind::Binary {
                op: crate::ast::BinOp::Div,
                lhs,
                rhs,
            } => format!("{}/{}", self.words(lhs), self.words(rhs)),
            _ => self.expr(e, None),
        }
    }

    fn call(&self, call: &Call<'s>) -> String {
        let command = Command::from_name(call.name.text);
        let name = match command {
            Some(c) => c.name().to_string(),
            None => self.spelling(&call.name).to_string(),
        };
        let Some(args) = &call.args else {
            return name;
        };
        let items: Vec<String> = args
            .items
            .iter()
            .map(|a| match a {
                Arg::Positional(e) => self.expr(e, command),
                Arg::Setting { key, value } => {
                    format!("{}={}", key.text.to_lowercase(), self.expr(value, command))
                }
            })
            .collect();
        format!("{name}({})", items.join(","))
    }

    /// `command` tells which words are keywords (written in lower case).
    fn expr(&self, e: &Expr<'s>, command: Option<Command>) -> String {
        match &e.kind {
            ExprKind::Number(_) => e.span.slice(self.source).to_string(),
            ExprKind::Name(n) => {
                if command.is_some_and(|c| c.spec().has_keyword(n.text)) {
                    n.text.to_lowercase()
                } else {
                    self.spelling(n).to_string()
                }
            }
            ExprKind::Neg(inner) => format!("-{}", self.operand(inner, command, 3)),
            ExprKind::Binary { op, lhs, rhs } => {
                let p = precedence(e);
                // Left-associative: the right operand needs parentheses at equal precedence.
                format!(
                    "{} {} {}",
                    self.operand(lhs, command, p),
                    op.symbol(),
                    self.operand(rhs, command, p + 1)
                )
            }
            ExprKind::Compare { op, lhs, rhs, .. } => format!(
                "{} {} {}",
                self.expr(lhs, command),
                op.symbol(),
                self.expr(rhs, command)
            ),
            ExprKind::Error => e.span.slice(self.source).to_string(),
        }
    }

    fn operand(&self, e: &Expr<'s>, command: Option<Command>, min: u8) -> String {
        let text = self.expr(e, command);
        if precedence(e) < min {
            format!("({text})")
        } else {
            text
        }
    }

    fn assemble(&self, comments: &[Span]) -> String {
        let comment_on: HashMap<usize, Span> = comments
            .iter()
            .map(|c| (self.index.line_of(c.start as usize), *c))
            .collect();
        let count = self.index.line_count();
        let mut out: Vec<String> = Vec::with_capacity(count);
        // A comment-only line takes the depth of the statement that follows it.
        let mut next_depth = vec![0; count + 1];
        for line in (0..count).rev() {
            next_depth[line] = self.lines[line]
                .as_ref()
                .map_or(next_depth[line + 1], |l| l.0);
        }
        for (line, &next) in next_depth.iter().enumerate().take(count) {
            let comment = comment_on
                .get(&line)
                .map(|c| c.slice(self.source).trim_end());
            let text = match (&self.lines[line], comment) {
                (Some((depth, text)), Some(c)) => format!("{}{text} {c}", INDENT.repeat(*depth)),
                (Some((depth, text)), None) => format!("{}{text}", INDENT.repeat(*depth)),
                (None, Some(c)) => format!("{}{c}", INDENT.repeat(next)),
                (None, None) => String::new(),
            };
            if text.is_empty() && out.last().is_none_or(String::is_empty) {
                continue;
            }
            out.push(text);
        }
        while out.last().is_some_and(String::is_empty) {
            out.pop();
        }
        let mut text = out.join("\n");
        text.push('\n');
        text
    }
}

fn precedence(e: &Expr<'_>) -> u8 {
    match &e.kind {
        ExprKind::Compare { .. } => 0,
        ExprKind::Binary { op, .. } => match op {
            crate::ast::BinOp::Add | crate::ast::BinOp::Sub => 1,
            crate::ast::BinOp::Mul | crate::ast::BinOp::Div => 2,
        },
        _ => 3,
    }
}

#[cfg(test)]
mod tests {
    use ilmr_model::RobotModel;

    fn format(src: &str) -> Result<String, Vec<crate::Diagnostic>> {
        super::format(src, &RobotModel::builtin("moro").unwrap())
    }

    #[test]
    fn canonical_form() {
        let src = "Turns = 0\nWhile(Turns<2) // loop\n  Door=sensor(scanner,door,LEFT)\n  If(door = 1)\n// found\n   turns = turns+1*(2-1)\n  EndIf\n\n\n\nEndWhile\nx = (1+2)*3 - -4\nif(x=>2)\nendif\n";
        let expected = "Turns = 0\nwhile(Turns < 2) // loop\n    Door = sensor(scanner,door,left)\n    if(Door == 1)\n        // found\n        Turns = Turns + 1 * (2 - 1)\n    endif\n\nendwhile\nx = (1 + 2) * 3 - -4\nif(x >= 2)\nendif\n";
        let out = format(src).unwrap();
        assert_eq!(out, expected);
        assert_eq!(format(&out).unwrap(), out, "formatting is idempotent");
    }

    #[test]
    fn files_with_syntax_errors_are_refused() {
        assert!(format("goahead(1\n").is_err());
    }

    #[test]
    fn skills_keep_their_headers_and_break_patterns_their_text() {
        let src = "turn1:\nSpeed(-0.4)\nT1=Turn(D=90,C=0.25)\nBreak( turn(d=) )\n";
        assert_eq!(
            format(src).unwrap(),
            "turn1:\nspeed(-0.4)\nT1 = turn(d=90,c=0.25)\nbreak(turn(d=))\n"
        );
    }

    #[test]
    fn a_header_keeps_its_parameters_and_word_lists() {
        let src = "Corner( d , side = left/ right ):\nTurn(side)\ngoahead( d )\n";
        assert_eq!(
            format(src).unwrap(),
            "Corner(d,side=left/right):\nturn(side)\ngoahead(d)\n"
        );
    }
}

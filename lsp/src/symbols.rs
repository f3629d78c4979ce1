//! Workspace symbols (skills, variables and paths of every task and skill file, by a
//! query) and document highlights (a symbol's occurrences in one file, its bindings
//! told apart from its uses). Both read the program's resolutions, as references do.

use std::collections::HashSet;

use ilmr_compiler::Span;
use ilmr_compiler::check::Resolved;
use ilmr_compiler::diagnostic::FileId;
use tower_lsp_server::ls_types::SymbolKind;

use crate::analysis::{Program, Symbol};

/// Workspace symbols answered at most; the client narrows by typing, and a
/// 100,000-line workspace has tens of thousands of variables.
pub const MAX_WORKSPACE_SYMBOLS: usize = 256;

/// A symbol found by a query, at the place that defines it.
#[derive(Debug, Clone, PartialEq)]
pub struct Found {
    pub name: String,
    pub kind: SymbolKind,
    pub file: FileId,
    pub span: Span,
    /// Where it lives: the skill's file, "variable", "path".
    pub detail: &'static str,
}

/// Whether `name` holds the query's characters in order, ignoring case (`tkb` finds
/// `Takebox`), as editors' symbol pickers expect.
pub fn fuzzy(name: &str, query: &str) -> bool {
    let mut wanted = query.chars().flat_map(char::to_lowercase).peekable();
    for c in name.chars().flat_map(char::to_lowercase) {
        if wanted.peek() == Some(&c) {
            wanted.next();
        }
    }
    wanted.peek().is_none()
}

/// Skills first, then variables, then paths, each in program order, at most
/// [`MAX_WORKSPACE_SYMBOLS`]; whether any were left out.
pub fn workspace(program: &Program, query: &str) -> (Vec<Found>, bool) {
    let analysis = program.analysis();
    let mut out = Vec::new();
    let mut more = false;
    let mut push = |found: Found, out: &mut Vec<Found>| {
        if out.len() < MAX_WORKSPACE_SYMBOLS {
            out.push(found);
        } else {
            more = true;
        }
    };
    for (_, info) in analysis.skills.iter() {
        if program.uri(info.file).is_none() {
            continue;
        }
        let name = &program.tree(info.file).skills[info.index].name;
        if fuzzy(name.text, query) {
            push(
                Found {
                    name: name.text.to_string(),
                    kind: SymbolKind::FUNCTION,
                    file: info.file,
                    span: name.span,
                    detail: "skill",
                },
                &mut out,
            );
        }
    }
    let mut seen: HashSet<String> = HashSet::new();
    for unit in &analysis.units {
        for (_, var) in unit.vars.iter() {
            let Some(&(file, span)) = var.defs.first() else {
                continue;
            };
            if program.uri(file).is_none() || !fuzzy(&var.spelling, query) {
                continue;
            }
            if seen.insert(var.spelling.to_lowercase()) {
                push(
                    Found {
                        name: var.spelling.to_string(),
                        kind: SymbolKind::VARIABLE,
                        file,
                        span,
                        detail: "variable",
                    },
                    &mut out,
                );
            }
        }
    }
    let mut paths: HashSet<String> = HashSet::new();
    for unit in &analysis.units {
        if program.uri(unit.file).is_none() {
            continue;
        }
        let text = program.text(unit.file);
        for &(span, resolved) in &unit.refs {
            if resolved != Resolved::Path {
                continue;
            }
            let name = span.slice(text);
            if fuzzy(name, query) && paths.insert(name.to_lowercase()) {
                push(
                    Found {
                        name: name.to_string(),
                        kind: SymbolKind::KEY,
                        file: unit.file,
                        span,
                        detail: "path",
                    },
                    &mut out,
                );
            }
        }
    }
    (out, more)
}

/// The occurrences in `file` of the symbol at `offset`, each with whether it binds
/// (a variable's binding statement, a skill's header, a path's `record`).
pub fn highlights(program: &Program, file: FileId, offset: usize) -> Vec<(Span, bool)> {
    let Some((_, symbol)) = program.symbol_at(file, offset) else {
        return Vec::new();
    };
    let binds: HashSet<Span> = match &symbol {
        Symbol::Variable(name) => program
            .variable_defs(name)
            .into_iter()
            .filter(|(f, _)| *f == file)
            .map(|(_, s)| s)
            .collect(),
        Symbol::Skill(id) => {
            let info = program.analysis().skills.get(*id);
            let header = program.tree(info.file).skills[info.index].name.span;
            (info.file == file).then_some(header).into_iter().collect()
        }
        Symbol::Path(_) => HashSet::new(),
    };
    program
        .occurrences(&symbol)
        .into_iter()
        .filter(|(f, _)| *f == file)
        .map(|(_, span)| (span, binds.contains(&span)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_query_is_a_subsequence_in_any_case() {
        assert!(fuzzy("Takebox", "tkb"));
        assert!(fuzzy("Takebox", ""));
        assert!(fuzzy("käännös", "ÄÄN"));
        assert!(!fuzzy("Takebox", "bt"));
    }
}

//! `break(pattern)` matches statements by their text (section 4.5.5). The checker warns
//! when a pattern can end nothing, or more than one statement.

use crate::ast::{Pattern, Stmt, StmtKind};
use crate::check::FileEntry;
use crate::check::skills::Skills;
use crate::diagnostic::{Code, Diagnostic, FileId, MAX_PLACES_SHOWN};
use crate::kept::Kept;
use crate::limits;
use crate::span::Span;
use ilmr_stdlib::pattern::Needles;

/// The text a pattern is searched for. The dissertation's own examples, `break(turn(d=))`
/// and `break(while(c))`, only match the statements they mean (`turn(d=90,c=0.5)`,
/// `while(cnt<5)`) when the pattern ends at its first `)`, which is how the original
/// interpreter read it; this toolchain does the same.
pub fn needle<'s>(pattern: &Pattern<'s>) -> &'s str {
    let text = pattern.text;
    text.find(')').map_or(text, |i| &text[..i]).trim()
}

pub use ilmr_stdlib::pattern::matches;

/// The statements a `break(pattern)` may end, with their text: every statement but
/// breaks, of task files and of the library files a task calls into, leaving out what
/// stands between `check` and `checkend` (which never runs). The checker's W0701/W0702
/// and the language server's lens both match patterns against this list.
pub fn breakable<'s>(files: &[FileEntry<'s>], skills: &Skills) -> Vec<(FileId, Span, &'s str)> {
    let mut statements: Vec<(FileId, Span, &'s str)> = Vec::new();
    for (i, entry) in files.iter().enumerate() {
        let file = FileId(i as u32);
        if !runs(entry, file, skills) {
            continue;
        }
        let text = entry.text;
        let from = statements.len();
        entry
            .tree
            .for_each_stmt(&mut |stmt: &Stmt<'_>| match &stmt.kind {
                StmtKind::Break { .. } | StmtKind::Error => {}
                _ => statements.push((file, stmt.span, stmt.span.slice(text))),
            });
        // What stands between `check` and `checkend` never runs, so no break can end it.
        let mut inside_check = Vec::new();
        entry.tree.for_each_stmt(&mut |stmt: &Stmt<'_>| {
            if let StmtKind::Check { body, .. } = &stmt.kind {
                inside_check.extend(body.iter().map(|b| b.span));
            }
        });
        if !inside_check.is_empty() {
            let mut k = from;
            for j in from..statements.len() {
                let span = statements[j].1;
                if !inside_check
                    .iter()
                    .any(|b| b.start <= span.start && span.end <= b.end)
                {
                    statements[k] = statements[j];
                    k += 1;
                }
            }
            statements.truncate(k);
        }
    }
    statements
}

/// Whether a file's statements can run: a task file, or a library a task calls into.
fn runs(entry: &FileEntry<'_>, file: FileId, skills: &Skills) -> bool {
    !entry.library
        || skills
            .iter()
            .any(|(id, s)| s.file == file && skills.is_called(id))
}

pub fn check_patterns(files: &[FileEntry<'_>], skills: &Skills, diags: &mut Kept) {
    let mut any = false;
    for entry in files.iter().filter(|f| f.break_patterns) {
        entry.tree.for_each_stmt(&mut |stmt: &Stmt<'_>| {
            any |= matches!(stmt.kind, StmtKind::Break { pattern: Some(_) });
        });
    }
    if !any {
        return;
    }
    let statements = breakable(files, skills);
    let mut patterns: Vec<(FileId, Pattern<'_>)> = Vec::new();
    for (i, entry) in files.iter().enumerate() {
        let file = FileId(i as u32);
        if !runs(entry, file, skills) {
            continue;
        }
        entry.tree.for_each_stmt(&mut |stmt: &Stmt<'_>| {
            if let StmtKind::Break { pattern: Some(p) } = &stmt.kind {
                patterns.push((file, *p));
            }
        });
    }
    let needles = Needles::new(
        patterns.iter().map(|(_, p)| needle(p)),
        limits::PATTERN_MATCHES,
    );
    // For each distinct needle, how many statements contain it and the first few.
    let mut hits: Vec<(usize, Vec<(FileId, Span)>)> = vec![(0, Vec::new()); needles.distinct()];
    let mut seen = Vec::new();
    for &(file, span, text) in &statements {
        let found = needles.each_in(text, &mut seen, |id| {
            let (n, first) = &mut hits[id as usize];
            *n += 1;
            // The count is in the message, so the places need no count of their own.
            if first.len() < MAX_PLACES_SHOWN {
                first.push((file, span));
            }
        });
        // Past the limit nothing is known for certain: say nothing rather than wrong.
        if found.is_none() {
            return;
        }
    }
    for (i, (file, pattern)) in patterns.iter().enumerate() {
        let needle = needle(pattern);
        let (n, first) = needles.id(i).map_or((0, &[][..]), |id| {
            let (n, first) = &hits[id as usize];
            (*n, &first[..])
        });
        match n {
            0 => diags.push(
                Diagnostic::new(
                    Code::PatternMatchesNothing,
                    *file,
                    pattern.span,
                    format!("no statement contains `{needle}`"),
                )
                .with_label("this break can end nothing"),
            ),
            1 => {}
            n => {
                let mut d = Diagnostic::new(
                    Code::PatternMatchesSeveral,
                    *file,
                    pattern.span,
                    format!("`{needle}` is found in {n} statements; the break ends every one that is running"),
                )
                .with_label("matches several statements");
                for &(f, span) in first {
                    d = d.with_secondary(f, span, "matches");
                }
                diags.push(d);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn patterns_end_at_their_first_closing_parenthesis() {
        let p = |text| Pattern {
            text,
            span: Span::default(),
            closed: true,
        };
        assert_eq!(needle(&p("turn(d=)")), "turn(d=");
        assert_eq!(needle(&p("while(c)")), "while(c");
        assert_eq!(needle(&p("followw")), "followw");
        assert!(matches("Turn(d=90,c=0.5)", "turn(d="));
        assert!(matches("while(cnt<5)", "while(c"));
        assert!(!matches("while(claps<2)", "while(cn"));
        assert!(matches("käännös=turn(left)", "KÄÄNNÖS"));
    }
}

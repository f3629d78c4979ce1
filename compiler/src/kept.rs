//! Diagnostics kept within [`limits::MAX_DIAGNOSTICS`]: the first ones in source order,
//! and a count of those past the limit. An 8 MiB file of four million broken lines
//! would otherwise make four million diagnostics, and the tree, the diagnostics and
//! their rendering together passed the 2 GB a tool may take (docs/reliability.md).
//!
//! The list grows to twice the limit, then is sorted and cut back to the limit: a
//! diagnostic past the cut is counted and forgotten, so memory stays bounded whatever
//! order the passes report in, and each push costs a logarithm on average. Once a cut
//! has been made, [`Kept::admits`] tells a pass that a diagnostic at a later place
//! would be dropped, so it can skip composing it (a suggestion is an edit-distance
//! search over every known name).

use crate::check::suggest::Budget;
use crate::diagnostic::{Code, Diagnostic, FileId, Severity};
use crate::limits::MAX_DIAGNOSTICS;
use crate::span::Span;

/// Where a diagnostic sorts: file, place, code (the order every tool reports in).
type Place = (FileId, u32, Code);

fn place(d: &Diagnostic) -> Place {
    (d.file, d.span.start, d.code)
}

/// How many diagnostics were dropped past the limit, by severity.
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq)]
pub struct Past {
    pub errors: usize,
    pub warnings: usize,
}

impl Past {
    pub fn add(&mut self, other: Past) {
        self.errors += other.errors;
        self.warnings += other.warnings;
    }

    fn count(&mut self, code: Code) {
        if code.severity() == Severity::Error {
            self.errors += 1;
        } else {
            self.warnings += 1;
        }
    }

    pub fn is_empty(&self) -> bool {
        self.errors == 0 && self.warnings == 0
    }
}

#[derive(Debug)]
pub struct Kept {
    list: Vec<Diagnostic>,
    limit: usize,
    past: Past,
    /// The last place kept at the latest cut: anything after it is past the limit.
    cut: Option<Place>,
    /// What "did you mean" may still spend on this program's diagnostics.
    pub suggestions: Budget,
}

impl Default for Kept {
    fn default() -> Kept {
        Kept::with_limit(MAX_DIAGNOSTICS)
    }
}

impl Kept {
    pub fn new() -> Kept {
        Kept::default()
    }

    pub fn with_limit(limit: usize) -> Kept {
        Kept {
            list: Vec::new(),
            limit: limit.max(1),
            past: Past::default(),
            cut: None,
            suggestions: Budget::default(),
        }
    }

    pub fn push(&mut self, d: Diagnostic) {
        if self.cut.is_some_and(|cut| place(&d) > cut) {
            self.past.count(d.code);
            return;
        }
        self.list.push(d);
        if self.list.len() >= 2 * self.limit {
            self.cut_back();
        }
    }

    /// Whether a diagnostic at `span` of `file` (of any code) could still be kept.
    pub fn admits(&self, file: FileId, span: Span) -> bool {
        self.cut
            .is_none_or(|(f, start, _)| (file, span.start) <= (f, start))
    }

    /// Whether as many diagnostics as the limit have come: from there on, which are
    /// kept depends on the order they come in (`check/stream.rs` needs it not to).
    pub fn near_limit(&self) -> bool {
        self.cut.is_some() || self.list.len() >= self.limit || !self.past.is_empty()
    }

    /// Counts a diagnostic of `code` that [`Kept::admits`] said would be dropped,
    /// without composing it.
    pub fn count_dropped(&mut self, code: Code) {
        self.past.count(code);
    }

    pub fn append(&mut self, more: &mut Vec<Diagnostic>) {
        more.drain(..).for_each(|d| self.push(d));
    }

    /// Diagnostics another collector dropped, counted here.
    pub fn add_past(&mut self, past: Past) {
        self.past.add(past);
    }

    pub fn contains(&self, d: &Diagnostic) -> bool {
        self.list.contains(d)
    }

    pub fn is_empty(&self) -> bool {
        self.list.is_empty() && self.past.is_empty()
    }

    pub fn iter(&self) -> impl Iterator<Item = &Diagnostic> {
        self.list.iter()
    }

    fn cut_back(&mut self) {
        self.list.sort_by_key(place);
        self.list.dedup();
        if self.list.len() > self.limit {
            for d in &self.list[self.limit..] {
                self.past.count(d.code);
            }
            self.list.truncate(self.limit);
            self.cut = self.list.last().map(place);
        }
    }

    /// The kept diagnostics in source order, without duplicates, and what was dropped.
    pub fn finish(mut self) -> (Vec<Diagnostic>, Past) {
        self.cut_back();
        (self.list, self.past)
    }

    /// As [`Kept::finish`], with one more diagnostic after the last kept one that says
    /// how many were dropped: an error (E0003) when any dropped one was, so a program
    /// whose errors all fell past the limit is still refused.
    pub fn into_reported(self) -> Vec<Diagnostic> {
        let (mut list, past) = self.finish();
        if past.is_empty() {
            return list;
        }
        let code = if past.errors > 0 {
            Code::TooManyErrors
        } else {
            Code::TooManyWarnings
        };
        let (file, at) = list
            .last()
            .map_or((FileId(0), 0), |d| (d.file, d.span.start as usize));
        list.push(
            Diagnostic::new(
                code,
                file,
                Span::empty(at),
                format!(
                    "{} more problems after this place are not shown ({} errors, {} warnings): \
                     at most {MAX_DIAGNOSTICS} diagnostics are kept",
                    past.errors + past.warnings,
                    past.errors,
                    past.warnings
                ),
            )
            .with_label("the diagnostics shown end here")
            .with_help(
                "fix the first ones and check again; past the limit lines are read less \
                 closely, so the count is a floor",
            ),
        );
        list
    }
}

impl Extend<Diagnostic> for Kept {
    fn extend<I: IntoIterator<Item = Diagnostic>>(&mut self, items: I) {
        items.into_iter().for_each(|d| self.push(d));
    }
}

impl FromIterator<Diagnostic> for Kept {
    fn from_iter<I: IntoIterator<Item = Diagnostic>>(items: I) -> Kept {
        let mut kept = Kept::new();
        kept.extend(items);
        kept
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(start: usize, code: Code) -> Diagnostic {
        Diagnostic::new(code, FileId(0), Span::new(start, start + 1), "x")
    }

    #[test]
    fn the_first_ones_in_source_order_are_kept_whatever_order_they_come_in() {
        let mut kept = Kept::with_limit(3);
        for start in [9, 8, 7, 6, 5, 4, 3, 2, 1, 0] {
            kept.push(at(start, Code::Syntax));
        }
        let (list, past) = kept.finish();
        let starts: Vec<u32> = list.iter().map(|d| d.span.start).collect();
        assert_eq!(starts, [0, 1, 2]);
        assert_eq!(
            past,
            Past {
                errors: 7,
                warnings: 0
            }
        );
    }

    #[test]
    fn memory_stays_within_twice_the_limit() {
        let mut kept = Kept::with_limit(10);
        for start in 0..100_000 {
            kept.push(at(start, Code::Syntax));
            assert!(kept.list.len() < 20);
        }
        assert!(!kept.admits(FileId(0), Span::empty(50)));
        assert!(kept.admits(FileId(0), Span::empty(5)));
        assert_eq!(kept.finish().1.errors, 100_000 - 10);
    }

    #[test]
    fn duplicates_take_no_place_and_are_not_counted() {
        let mut kept = Kept::with_limit(2);
        for _ in 0..5 {
            kept.push(at(1, Code::Syntax));
        }
        kept.push(at(2, Code::Syntax));
        let (list, past) = kept.finish();
        assert_eq!(list.len(), 2);
        assert!(past.is_empty());
    }

    #[test]
    fn an_error_past_the_limit_keeps_the_program_refused() {
        let mut kept = Kept::with_limit(2);
        kept.push(at(0, Code::UnusedVariable));
        kept.push(at(1, Code::UnusedVariable));
        kept.push(at(2, Code::Syntax));
        let list = kept.into_reported();
        let last = list.last().unwrap();
        assert_eq!(last.code, Code::TooManyErrors);
        assert!(last.is_error());
        assert_eq!(last.span.start, 1);
        assert!(list.iter().any(Diagnostic::is_error));
    }

    #[test]
    fn only_warnings_past_the_limit_leave_a_warning() {
        let mut kept = Kept::with_limit(1);
        kept.push(at(0, Code::UnusedVariable));
        kept.push(at(1, Code::UnusedVariable));
        let list = kept.into_reported();
        assert_eq!(list.last().unwrap().code, Code::TooManyWarnings);
        assert!(!list.iter().any(Diagnostic::is_error));
    }
}

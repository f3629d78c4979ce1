//! Test files (`*.test.toml`, `ilmrc test`): read and checked by `ilmr_testfile`, the
//! reader `ilmrc test` uses, so the editor shows the problems `ilmrc test` would report
//! (same spans, same codes); completion and hover inside assertions come from the same
//! parser and the test's task and world. Test files are not part of the ILMR program:
//! they are kept here, apart from the workspace's task and skill files.

use std::collections::{BTreeSet, HashMap};
use std::path::PathBuf;

use ilmr_compiler::Span;
use ilmr_testfile::codes::Code;
use ilmr_testfile::complete::{self, Candidate, Candidates, Spot, What};
use ilmr_testfile::file::Outline;
use ilmr_testfile::problem::Problem;
use tower_lsp_server::ls_types::{
    CompletionItem, CompletionItemKind, CompletionList, CompletionTextEdit, Diagnostic,
    DiagnosticSeverity, Hover, HoverContents, MarkupContent, MarkupKind, NumberOrString, Position,
    Range, TextDocumentContentChangeEvent, TextEdit, Uri,
};

use crate::diagnostics::{SOURCE, TOO_LARGE};
use crate::engine::Publish;
use crate::line_index::LineIndex;

/// Whether a document is a test file, by its name as `ilmrc test` finds them.
pub fn is_test(uri: &Uri) -> bool {
    uri.as_str().ends_with(ilmr_testfile::SUFFIX)
}

struct TestDoc {
    uri: Uri,
    version: i32,
    text: String,
    index: LineIndex,
    problems: Vec<Problem>,
    outlines: Vec<Outline>,
    /// The text is larger than `ilmrc test` reads a test file.
    too_large: bool,
}

impl TestDoc {
    fn path(&self) -> PathBuf {
        // A document not saved anywhere is read as if in the working directory.
        self.uri
            .to_file_path()
            .map(|p| p.into_owned())
            .unwrap_or_else(|| PathBuf::from(ilmr_testfile::SUFFIX))
    }

    fn check(&mut self) {
        self.too_large = self.text.len() as u64 > ilmr_files::Kind::Scenario.limit();
        if self.too_large {
            self.problems.clear();
            self.outlines.clear();
            return;
        }
        let read = ilmr_testfile::file::check(&self.path(), self.text.clone());
        self.problems = read.file.err().unwrap_or_default();
        self.outlines = read.outlines;
    }

    /// While an assertion is typed its string is often not closed yet, and the file is
    /// no TOML: the text as it would be with the string (and the array) closed at the
    /// cursor, and its outlines, when that makes the cursor's place an assertion.
    fn closed_at(&self, offset: usize) -> Option<(String, Vec<Outline>)> {
        let not_toml = self.problems.iter().any(|p| p.code == Code::NotToml);
        if !not_toml || !self.text.is_char_boundary(offset) {
            return None;
        }
        for closer in ["\"", "\"]"] {
            let mut text = self.text.clone();
            text.insert_str(offset, closer);
            let read = ilmr_testfile::file::check(&self.path(), text.clone());
            if matches!(
                complete::spot(&text, &read.outlines, offset),
                Spot::Assertion { .. }
            ) {
                return Some((text, read.outlines));
            }
        }
        None
    }

    fn diagnostics(&self) -> Vec<Diagnostic> {
        if self.too_large {
            let why = ilmr_files::ReadError {
                kind: ilmr_files::Kind::Scenario,
                problem: ilmr_files::Problem::TooLarge,
            };
            return vec![Diagnostic {
                severity: Some(DiagnosticSeverity::ERROR),
                code: Some(NumberOrString::String(TOO_LARGE.to_string())),
                source: Some(SOURCE.to_string()),
                message: format!("this test file is not read: {why}"),
                ..Default::default()
            }];
        }
        self.problems.iter().map(|p| self.diagnostic(p)).collect()
    }

    /// As `ilmrc test` reports it: the code's title, then what is wrong there, then the
    /// help.
    fn diagnostic(&self, p: &Problem) -> Diagnostic {
        let mut message = format!("{}\n{}", p.code.title(), p.message);
        if let Some(help) = &p.help {
            message.push_str("\nhelp: ");
            message.push_str(help);
        }
        let start = p.span.start.min(self.text.len());
        let end = p.span.end.clamp(start, self.text.len());
        Diagnostic {
            range: self.index.range(&self.text, Span::new(start, end)),
            severity: Some(DiagnosticSeverity::ERROR),
            code: Some(NumberOrString::String(p.code.as_str().to_string())),
            source: Some(SOURCE.to_string()),
            message,
            ..Default::default()
        }
    }

    fn publish(&self) -> Publish {
        Publish {
            uri: self.uri.clone(),
            version: Some(self.version),
            diagnostics: self.diagnostics(),
        }
    }
}

/// The open test files.
#[derive(Default)]
pub struct TestFiles {
    docs: HashMap<String, TestDoc>,
    /// Edited since their last check.
    stale: BTreeSet<String>,
}

impl TestFiles {
    pub fn open(&mut self, uri: Uri, version: i32, text: String) -> Vec<Publish> {
        let mut doc = TestDoc {
            index: LineIndex::new(&text),
            uri,
            version,
            text,
            problems: Vec::new(),
            outlines: Vec::new(),
            too_large: false,
        };
        doc.check();
        let out = vec![doc.publish()];
        self.stale.remove(doc.uri.as_str());
        self.docs.insert(doc.uri.as_str().to_string(), doc);
        out
    }

    /// Applies edits without checking; [`TestFiles::refresh`] checks.
    pub fn change(
        &mut self,
        uri: &Uri,
        version: i32,
        changes: Vec<TextDocumentContentChangeEvent>,
    ) {
        let Some(doc) = self.docs.get_mut(uri.as_str()) else {
            return;
        };
        doc.index.apply(&mut doc.text, changes);
        doc.version = version;
        self.stale.insert(uri.as_str().to_string());
    }

    /// Checks the documents edited since their last check: what to publish.
    pub fn refresh(&mut self) -> Option<Vec<Publish>> {
        if self.stale.is_empty() {
            return None;
        }
        let mut out = Vec::new();
        for uri in std::mem::take(&mut self.stale) {
            if let Some(doc) = self.docs.get_mut(&uri) {
                doc.check();
                out.push(doc.publish());
            }
        }
        Some(out)
    }

    /// Checks every open test file again: a task, skill, world or model file they name
    /// changed on disk.
    pub fn recheck(&mut self) -> Vec<Publish> {
        self.stale.clear();
        self.docs
            .values_mut()
            .map(|doc| {
                doc.check();
                doc.publish()
            })
            .collect()
    }

    /// The editor let go of a test file: its diagnostics are cleared.
    pub fn close(&mut self, uri: &Uri) -> Vec<Publish> {
        self.stale.remove(uri.as_str());
        match self.docs.remove(uri.as_str()) {
            Some(_) => vec![Publish {
                uri: uri.clone(),
                version: None,
                diagnostics: Vec::new(),
            }],
            None => Vec::new(),
        }
    }

    pub fn diagnostics(&self, uri: &Uri) -> Vec<Diagnostic> {
        self.docs
            .get(uri.as_str())
            .map(TestDoc::diagnostics)
            .unwrap_or_default()
    }

    pub fn completion(&self, uri: &Uri, position: Position) -> CompletionList {
        let Some(doc) = self.docs.get(uri.as_str()) else {
            return CompletionList::default();
        };
        let offset = doc.index.offset(&doc.text, position);
        let closed = doc.closed_at(offset);
        let (text, outlines) = match &closed {
            Some((text, outlines)) => (text.as_str(), outlines.as_slice()),
            None => (doc.text.as_str(), doc.outlines.as_slice()),
        };
        let (candidates, start) = match complete::spot(text, outlines, offset) {
            Spot::Assertion { outline, base } => {
                let start = in_backticks(text, base, offset)
                    .unwrap_or_else(|| complete::word_start(text, offset).max(base));
                (complete::assertion(text, outline, base, offset), start)
            }
            Spot::Key => (
                complete::keys(&doc.text, offset),
                complete::word_start(&doc.text, offset),
            ),
            Spot::Elsewhere => return CompletionList::default(),
        };
        let range = doc.index.range(&doc.text, Span::new(start, offset));
        CompletionList {
            is_incomplete: candidates.incomplete,
            items: items(candidates, range),
        }
    }

    pub fn hover(&self, uri: &Uri, position: Position) -> Option<Hover> {
        let doc = self.docs.get(uri.as_str())?;
        let offset = doc.index.offset(&doc.text, position);
        let (value, span) = match complete::spot(&doc.text, &doc.outlines, offset) {
            Spot::Assertion { outline, base } => {
                let end = outline
                    .asserts
                    .iter()
                    .find(|(_, b)| *b == Some(base))
                    .map(|(s, _)| s.end.saturating_sub(1))?;
                complete::hover_assertion(&doc.text, outline, base, end, offset)?
            }
            _ => complete::hover_key(&doc.text, offset)?,
        };
        Some(Hover {
            contents: HoverContents::Markup(MarkupContent {
                kind: MarkupKind::Markdown,
                value,
            }),
            range: Some(doc.index.range(&doc.text, Span::new(span.start, span.end))),
        })
    }
}

/// Where a statement's text being typed in backticks starts (after the open backtick).
fn in_backticks(text: &str, base: usize, offset: usize) -> Option<usize> {
    let prefix = text.get(base..offset)?;
    (prefix.matches('`').count() % 2 == 1).then(|| base + prefix.rfind('`').unwrap_or(0) + 1)
}

/// LSP items, in the candidates' rank, each replacing the word being typed.
fn items(candidates: Candidates, range: Range) -> Vec<CompletionItem> {
    candidates
        .items
        .into_iter()
        .enumerate()
        .map(|(i, c)| item(i, c, range))
        .collect()
}

fn item(rank: usize, c: Candidate, range: Range) -> CompletionItem {
    let kind = match c.what {
        What::Keyword => CompletionItemKind::KEYWORD,
        What::Line => CompletionItemKind::REFERENCE,
        What::Text => CompletionItemKind::TEXT,
        What::Variable => CompletionItemKind::VARIABLE,
        What::Field => CompletionItemKind::FIELD,
        What::Object => CompletionItemKind::CONSTANT,
        What::Cmp => CompletionItemKind::OPERATOR,
        What::Key => CompletionItemKind::PROPERTY,
    };
    CompletionItem {
        // Line numbers filter by their digits, and the client keeps this order.
        filter_text: Some(c.label.clone()),
        sort_text: Some(format!("{rank:04}")),
        label: c.label,
        kind: Some(kind),
        detail: c.detail,
        text_edit: Some(CompletionTextEdit::Edit(TextEdit::new(range, c.insert))),
        ..Default::default()
    }
}

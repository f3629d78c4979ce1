//! The one place diagnostics become text: ariadne reports for people, JSON for tools.
//! Spans are bytes, so ariadne is told to index bytes.

use ariadne::{CharSet, Color, Config, IndexType, Label, Report, ReportKind};
use serde::Serialize;

use crate::diagnostic::{Diagnostic, Severity};
use crate::span::LineIndex;

/// A file a diagnostic may point into.
pub struct RenderFile<'a> {
    pub path: &'a str,
    pub text: &'a str,
}

#[derive(Debug, Clone, Copy)]
pub struct Style {
    pub color: bool,
    /// Box-drawing characters; plain ASCII when false.
    pub unicode: bool,
}

impl Style {
    /// What snapshots use: no colour, plain ASCII.
    pub const PLAIN: Style = Style {
        color: false,
        unicode: false,
    };
}

pub fn human(diagnostics: &[Diagnostic], files: &[RenderFile<'_>], style: Style) -> String {
    let mut out = Vec::new();
    if diagnostics.is_empty() {
        return String::new();
    }
    let config = Config::default()
        .with_index_type(IndexType::Byte)
        .with_color(style.color)
        .with_char_set(if style.unicode {
            CharSet::Unicode
        } else {
            CharSet::Ascii
        });
    // Only the files a diagnostic points into: ariadne indexes the lines of each.
    let mut used: Vec<usize> = diagnostics
        .iter()
        .flat_map(|d| std::iter::once(d.file).chain(d.secondary.iter().map(|s| s.file)))
        .map(|f| f.0 as usize)
        .collect();
    used.sort_unstable();
    used.dedup();
    let mut cache = ariadne::sources(
        used.iter()
            .map(|&i| (files[i].path.to_string(), files[i].text.to_string())),
    );
    for d in diagnostics {
        let path = |file: crate::FileId| files[file.0 as usize].path.to_string();
        let (kind, color) = match d.severity() {
            Severity::Error => (ReportKind::Error, Color::Red),
            Severity::Warning => (ReportKind::Warning, Color::Yellow),
        };
        let label = if d.label.is_empty() {
            &d.message
        } else {
            &d.label
        };
        let mut report = Report::build(kind, (path(d.file), d.span.range()))
            .with_config(config)
            .with_code(d.code.as_str())
            .with_message(&d.message)
            .with_label(
                Label::new((path(d.file), d.span.range()))
                    .with_message(label)
                    .with_color(color),
            );
        for s in &d.secondary {
            report = report.with_label(
                Label::new((path(s.file), s.span.range()))
                    .with_message(&s.message)
                    .with_color(Color::Blue),
            );
        }
        if let Some(help) = &d.help {
            report = report.with_help(help);
        }
        // Writing into a Vec cannot fail.
        let _ = report.finish().write(&mut cache, &mut out);
    }
    String::from_utf8_lossy(&out).into_owned()
}

#[derive(Debug, Serialize)]
pub struct JsonDiagnostic<'a> {
    pub code: &'static str,
    pub severity: Severity,
    pub message: &'a str,
    pub file: &'a str,
    pub line: usize,
    pub column: usize,
    pub end_line: usize,
    pub end_column: usize,
    #[serde(skip_serializing_if = "str::is_empty")]
    pub label: &'a str,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub help: Option<&'a str>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub related: Vec<JsonLabel<'a>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fix: Option<JsonFix<'a>>,
}

#[derive(Debug, Serialize)]
pub struct JsonLabel<'a> {
    pub file: &'a str,
    pub line: usize,
    pub column: usize,
    pub end_line: usize,
    pub end_column: usize,
    pub message: &'a str,
}

#[derive(Debug, Serialize)]
pub struct JsonFix<'a> {
    pub title: &'a str,
    pub line: usize,
    pub column: usize,
    pub end_line: usize,
    pub end_column: usize,
    pub replacement: &'a str,
}

/// Diagnostics as JSON values with 1-based lines and character columns.
pub fn json<'a>(
    diagnostics: &'a [Diagnostic],
    files: &[RenderFile<'a>],
) -> Vec<JsonDiagnostic<'a>> {
    let indexes: Vec<LineIndex> = files.iter().map(|f| LineIndex::new(f.text)).collect();
    let pos = |file: crate::FileId, offset: u32| {
        let i = file.0 as usize;
        indexes[i].line_col(files[i].text, offset as usize)
    };
    diagnostics
        .iter()
        .map(|d| {
            let (line, column) = pos(d.file, d.span.start);
            let (end_line, end_column) = pos(d.file, d.span.end);
            JsonDiagnostic {
                code: d.code.as_str(),
                severity: d.severity(),
                message: &d.message,
                file: files[d.file.0 as usize].path,
                line,
                column,
                end_line,
                end_column,
                label: &d.label,
                help: d.help.as_deref(),
                related: d
                    .secondary
                    .iter()
                    .map(|s| {
                        let (line, column) = pos(s.file, s.span.start);
                        let (end_line, end_column) = pos(s.file, s.span.end);
                        JsonLabel {
                            file: files[s.file.0 as usize].path,
                            line,
                            column,
                            end_line,
                            end_column,
                            message: &s.message,
                        }
                    })
                    .collect(),
                fix: d.fix.as_ref().map(|f| {
                    let (line, column) = pos(d.file, f.span.start);
                    let (end_line, end_column) = pos(d.file, f.span.end);
                    JsonFix {
                        title: &f.title,
                        line,
                        column,
                        end_line,
                        end_column,
                        replacement: &f.replacement,
                    }
                }),
            }
        })
        .collect()
}

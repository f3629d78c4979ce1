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
    let mut shown: Vec<Option<Shown>> = (0..files.len()).map(|_| None).collect();
    for &i in &used {
        let labels = diagnostics.iter().flat_map(|d| {
            std::iter::once((d.file, d.span))
                .chain(d.secondary.iter().map(|s| (s.file, s.span)))
                .filter(move |(f, _)| f.0 as usize == i)
                .map(|(_, span)| span)
        });
        shown[i] = Some(Shown::new(files[i].text, labels));
    }
    let mut cache = ariadne::sources(used.iter().map(|&i| {
        let text = shown[i].as_ref().map_or(String::new(), |s| s.text.clone());
        (files[i].path.to_string(), text)
    }));
    for d in diagnostics {
        let path = |file: crate::FileId| files[file.0 as usize].path.to_string();
        let range = |file: crate::FileId, span: crate::Span| {
            let s = shown[file.0 as usize].as_ref();
            let at = |o: u32| s.map_or(o as usize, |s| s.offset(o));
            at(span.start)..at(span.end)
        };
        let (kind, color) = match d.severity() {
            Severity::Error => (ReportKind::Error, Color::Red),
            Severity::Warning => (ReportKind::Warning, Color::Yellow),
        };
        let label = if d.label.is_empty() {
            &d.message
        } else {
            &d.label
        };
        let mut report = Report::build(kind, (path(d.file), range(d.file, d.span)))
            .with_config(config)
            .with_code(d.code.as_str())
            .with_message(&d.message)
            .with_label(
                Label::new((path(d.file), range(d.file, d.span)))
                    .with_message(label)
                    .with_color(color),
            );
        for s in &d.secondary {
            report = report.with_label(
                Label::new((path(s.file), range(s.file, s.span)))
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

/// Lines longer than this are cut short where people read them: a generated or hostile
/// line of a megabyte would otherwise be echoed whole.
const LONG_LINE: usize = 200;
/// What is kept of a long line past the furthest label on it.
const AFTER_LABEL: usize = 40;
const CUT_MARK: &str = " ...";

/// A file as shown to people: long lines cut short at the right, so that every column
/// ariadne counts stays where it was, with the offsets of the text after each cut.
struct Shown {
    text: String,
    /// Each cut: the original bytes `from..to` became `CUT_MARK`, and the original
    /// offsets after it are `shift` bytes further on in `text` (less, as a rule).
    cuts: Vec<(usize, usize, isize)>,
}

impl Shown {
    fn new(text: &str, labels: impl Iterator<Item = crate::Span>) -> Shown {
        let mut ends: Vec<usize> = labels.map(|s| s.end as usize).collect();
        ends.sort_unstable();
        let mut shown = Shown {
            text: String::with_capacity(text.len().min(1 << 16)),
            cuts: Vec::new(),
        };
        let mut shift = 0isize;
        let mut start = 0;
        for line in text.split_inclusive('\n') {
            let content = line.trim_end_matches(['\n', '\r']);
            let end = start + content.len();
            // The furthest label end on this line, if any.
            let furthest = ends[ends.partition_point(|&e| e < start)..]
                .iter()
                .take_while(|&&e| e <= end)
                .last()
                .map_or(0, |&e| e - start + AFTER_LABEL);
            let mut keep = LONG_LINE.max(furthest).min(content.len());
            while !content.is_char_boundary(keep) {
                keep -= 1;
            }
            if keep + CUT_MARK.len() < content.len() {
                shown.text.push_str(&content[..keep]);
                shown.text.push_str(CUT_MARK);
                shown.text.push_str(&line[content.len()..]);
                shift += CUT_MARK.len() as isize - (content.len() - keep) as isize;
                shown.cuts.push((start + keep, end, shift));
            } else {
                shown.text.push_str(line);
            }
            start += line.len();
        }
        shown
    }

    /// Where an offset of the original text is in the shown one.
    fn offset(&self, original: u32) -> usize {
        let o = original as usize;
        let i = self.cuts.partition_point(|&(from, _, _)| from <= o);
        let Some(&(from, to, shift)) = i.checked_sub(1).map(|i| &self.cuts[i]) else {
            return o;
        };
        if o < to {
            // Inside a cut: where the cut stands.
            let before = shift + (to - from) as isize - CUT_MARK.len() as isize;
            return (from as isize + before) as usize;
        }
        (o as isize + shift) as usize
    }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnostic::{Code, FileId};
    use crate::span::Span;

    fn render(text: &str, spans: &[Span]) -> String {
        let diagnostics: Vec<Diagnostic> = spans
            .iter()
            .map(|&s| Diagnostic::new(Code::Syntax, FileId(0), s, "here").with_label("this"))
            .collect();
        let files = [RenderFile {
            path: "f.ilmr",
            text,
        }];
        human(&diagnostics, &files, Style::PLAIN)
    }

    #[test]
    fn a_megabyte_line_is_cut_short_and_columns_stay_true() {
        let line = format!("x = {}", "(".repeat(1 << 20));
        let text = format!("a = 1\n{line}\nb = 2\n");
        let at = 6 + 300;
        let out = render(
            &text,
            &[
                Span::new(at, at + 1),
                Span::new(text.len() - 6, text.len() - 1),
            ],
        );
        assert!(out.len() < 4_000, "{} bytes", out.len());
        assert!(out.contains("f.ilmr:2:301"), "{out}");
        assert!(out.contains(" ..."), "{out}");
        // The line after the cut is found where it is.
        assert!(out.contains("f.ilmr:3:1"), "{out}");
        assert!(out.contains("b = 2"), "{out}");
    }

    #[test]
    fn a_label_inside_what_is_cut_points_at_the_cut() {
        let text = format!("{}\n", "y".repeat(10_000));
        let shown = Shown::new(&text, std::iter::empty());
        assert_eq!(shown.offset(5), 5);
        assert_eq!(shown.offset(5_000), LONG_LINE);
        assert_eq!(shown.offset(10_000), LONG_LINE + CUT_MARK.len());
        assert_eq!(&shown.text[LONG_LINE..], " ...\n");
    }

    #[test]
    fn short_lines_are_shown_whole() {
        let text = "speed(0.4)\nturn(left)\n";
        let shown = Shown::new(text, std::iter::empty());
        assert_eq!(shown.text, text);
        assert!(shown.cuts.is_empty());
    }
}

//! The one place diagnostics become text: ariadne reports for people, JSON for tools.
//! Spans are bytes, so ariadne is told to index bytes.

use std::borrow::Cow;

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

    /// Colour (unless `NO_COLOR` is set) and box drawing on a terminal, plain ASCII
    /// elsewhere.
    pub fn on_terminal(terminal: bool) -> Style {
        Style {
            color: terminal && std::env::var_os("NO_COLOR").is_none(),
            unicode: terminal,
        }
    }

    /// ariadne's configuration in this style, spans in bytes.
    pub fn config(self) -> Config {
        Config::default()
            .with_index_type(IndexType::Byte)
            .with_color(self.color)
            .with_char_set(if self.unicode {
                CharSet::Unicode
            } else {
                CharSet::Ascii
            })
    }
}

/// `200000` as `200,000`: a count as messages and docs write it.
pub fn thousands(n: impl Into<u64>) -> String {
    let digits = n.into().to_string();
    let mut out = String::new();
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

pub fn human(diagnostics: &[Diagnostic], files: &[RenderFile<'_>], style: Style) -> String {
    let mut out = String::new();
    if diagnostics.is_empty() {
        return String::new();
    }
    let config = style.config();
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
    // The line starts of the files cut short, original and shown, made once.
    let mut indexes: Vec<Option<(LineIndex, LineIndex)>> = (0..files.len()).map(|_| None).collect();
    for d in diagnostics {
        let path = |file: crate::FileId| files[file.0 as usize].path.to_string();
        let range = |file: crate::FileId, span: crate::Span| {
            let s = shown[file.0 as usize].as_ref();
            let at = |o: u32| s.map_or(o as usize, |s| s.offset(o));
            at(span.start)..at(span.end)
        };
        let (kind, color) = look(d.severity());
        let label = short(if d.label.is_empty() {
            &d.message
        } else {
            &d.label
        });
        let mut report = Report::build(kind, (path(d.file), range(d.file, d.span)))
            .with_config(config)
            .with_code(d.code.as_str())
            .with_message(short(&d.message))
            .with_label(
                Label::new((path(d.file), range(d.file, d.span)))
                    .with_message(label)
                    .with_color(color),
            );
        for s in &d.secondary {
            report = report.with_label(
                Label::new((path(s.file), range(s.file, s.span)))
                    .with_message(short(&s.message))
                    .with_color(Color::Blue),
            );
        }
        if let Some(help) = &d.help {
            report = report.with_help(short(help));
        }
        let mut one = Vec::new();
        // Writing into a Vec cannot fail.
        let _ = report.finish().write(&mut cache, &mut one);
        let mut one = String::from_utf8_lossy(&one).into_owned();
        let starts = std::iter::once((d.file, d.span.start))
            .chain(d.secondary.iter().map(|s| (s.file, s.span.start)));
        for (file, at) in starts {
            let i = file.0 as usize;
            if let Some(s) = shown[i].as_ref().filter(|s| !s.cuts.is_empty()) {
                let lines = indexes[i].get_or_insert_with(|| {
                    (LineIndex::new(files[i].text), LineIndex::new(&s.text))
                });
                true_column(&mut one, &files[i], s, lines, at);
            }
        }
        out.push_str(&one);
    }
    out
}

/// A report on one span of a file that is not a program (a test file): what it says.
pub struct Single<'a> {
    pub severity: Severity,
    pub code: &'a str,
    pub message: &'a str,
    pub span: crate::Span,
    pub label: &'a str,
    pub help: Option<&'a str>,
}

/// One report against `file`, its long lines cut and its texts shortened as [`human`]
/// does a program's: the rule for what people are shown of a long line is this one.
pub fn single(file: &RenderFile<'_>, r: &Single<'_>, style: Style) -> String {
    let shown = Shown::new(file.text, std::iter::once(r.span));
    let range = shown.offset(r.span.start)..shown.offset(r.span.end);
    let (kind, color) = look(r.severity);
    let path = file.path.to_string();
    let mut report = Report::build(kind, (path.clone(), range.clone()))
        .with_config(style.config())
        .with_code(r.code)
        .with_message(short(r.message))
        .with_label(
            Label::new((path.clone(), range))
                .with_message(short(r.label))
                .with_color(color),
        );
    if let Some(help) = r.help {
        report = report.with_help(short(help));
    }
    let mut out = Vec::new();
    // Writing into a Vec cannot fail.
    let _ = report
        .finish()
        .write((path, ariadne::Source::from(shown.text.as_str())), &mut out);
    let mut out = String::from_utf8_lossy(&out).into_owned();
    if !shown.cuts.is_empty() {
        let lines = (LineIndex::new(file.text), LineIndex::new(&shown.text));
        true_column(&mut out, file, &shown, &lines, r.span.start);
    }
    out
}

/// How a report of each severity looks: its heading and its label's colour.
fn look(severity: Severity) -> (ReportKind<'static>, Color) {
    match severity {
        Severity::Error => (ReportKind::Error, Color::Red),
        Severity::Warning => (ReportKind::Warning, Color::Yellow),
    }
}

/// Puts the true column of `at` back in a report's `path:line:column` header when a
/// cut before it on its line moved it in the shown text.
fn true_column(
    report: &mut String,
    file: &RenderFile<'_>,
    shown: &Shown,
    (lines, shown_lines): &(LineIndex, LineIndex),
    at: u32,
) {
    let (line, column) = lines.line_col(file.text, at as usize);
    let (shown_line, shown_column) = shown_lines.line_col(&shown.text, shown.offset(at));
    if (line, column) == (shown_line, shown_column) {
        return;
    }
    let wrong = format!("{}:{shown_line}:{shown_column} ", file.path);
    if let Some(i) = report.find(&wrong) {
        report.replace_range(
            i..i + wrong.len(),
            &format!("{}:{line}:{column} ", file.path),
        );
    }
}

/// Characters of a message (or label, or help) kept: a message that quotes a token
/// (`unexpected name ...`) quotes all of it, and a token can be a megabyte long.
pub const LONG_MESSAGE: usize = 300;
/// What is kept of a long message's end: the close of its quote and what follows.
const MESSAGE_TAIL: usize = 60;

/// A message of at most [`LONG_MESSAGE`] characters: a longer one keeps its start and
/// its end, with [`CUT_MARK`] between.
fn short(message: &str) -> Cow<'_, str> {
    let chars = message.chars().count();
    if chars <= LONG_MESSAGE {
        return Cow::Borrowed(message);
    }
    let head = LONG_MESSAGE - MESSAGE_TAIL - CUT_MARK.len();
    let mut out: String = message.chars().take(head).collect();
    out.push_str(CUT_MARK);
    out.extend(message.chars().skip(chars - MESSAGE_TAIL));
    Cow::Owned(out)
}

/// Lines longer than this are cut short where people read them: a generated or hostile
/// line of a megabyte would otherwise be echoed whole.
pub const LONG_LINE: usize = 200;
/// What is kept of a long line on each side of a label's start and end: a label of up
/// to twice this shows whole, in one window of at most four times this.
pub const AROUND_LABEL: usize = 60;
/// Windows kept on one long line; labels past the last point at its cut.
pub const MAX_WINDOWS: usize = 4;
/// Where the text was cut: before the first window, between two, after the last.
const LEAD_MARK: &str = "... ";
const CUT_MARK: &str = " ... ";
const TAIL_MARK: &str = " ...";

/// A cut: the original bytes `from..to` became a mark at `mark_at` in the shown text;
/// the original offsets from `to` on are `shift` bytes further on there.
#[derive(Debug, Clone, Copy)]
struct Cut {
    from: usize,
    to: usize,
    mark_at: usize,
    shift: isize,
}

/// A file as shown to people: each long line cut down to windows round the labels on it
/// (its start when it has none), with a mark where text was left out, and the offsets
/// of the text after each cut. Lines are never joined or split, so line numbers stay
/// true; a column after a cut at a line's start does not, and [`human`] puts the true
/// one back in the report's header.
struct Shown {
    text: String,
    cuts: Vec<Cut>,
}

impl Shown {
    fn new(text: &str, labels: impl Iterator<Item = crate::Span>) -> Shown {
        let mut points: Vec<usize> = labels
            .flat_map(|s| [s.start as usize, s.end as usize])
            .collect();
        points.sort_unstable();
        points.dedup();
        let mut shown = Shown {
            text: String::with_capacity(text.len().min(1 << 16)),
            cuts: Vec::new(),
        };
        let mut start = 0;
        for line in text.split_inclusive('\n') {
            let content = line.trim_end_matches(['\n', '\r']);
            let end = start + content.len();
            if content.len() <= LONG_LINE {
                shown.text.push_str(line);
            } else {
                let at = &points[points.partition_point(|&p| p < start)..];
                let on_line = at.iter().take_while(|&&p| p <= end).map(|&p| p - start);
                let windows = windows(content, on_line);
                shown.push_windows(start, content, &windows);
                shown.text.push_str(&line[content.len()..]);
            }
            start += line.len();
        }
        shown
    }

    /// One long line, `content` starting at original offset `start`, as its windows.
    fn push_windows(&mut self, start: usize, content: &str, windows: &[(usize, usize)]) {
        let mut kept_to = 0;
        for (i, &(a, b)) in windows.iter().enumerate() {
            if a > kept_to {
                let mark = if i == 0 { LEAD_MARK } else { CUT_MARK };
                self.cut(start + kept_to, start + a, mark);
            }
            self.text.push_str(&content[a..b]);
            kept_to = b;
        }
        if kept_to < content.len() {
            self.cut(start + kept_to, start + content.len(), TAIL_MARK);
        }
    }

    fn cut(&mut self, from: usize, to: usize, mark: &str) {
        let mark_at = self.text.len();
        self.text.push_str(mark);
        let shift = self.text.len() as isize - to as isize;
        self.cuts.push(Cut {
            from,
            to,
            mark_at,
            shift,
        });
    }

    /// Where an offset of the original text is in the shown one.
    fn offset(&self, original: u32) -> usize {
        let o = original as usize;
        let i = self.cuts.partition_point(|c| c.from <= o);
        let Some(c) = i.checked_sub(1).map(|i| &self.cuts[i]) else {
            return o;
        };
        if o < c.to {
            // Inside a cut: where its mark stands.
            return c.mark_at;
        }
        (o as isize + c.shift) as usize
    }
}

/// The byte ranges of a long line to keep: round each label point (`points`, sorted,
/// relative to the line), merged where they touch, at most [`MAX_WINDOWS`]; the line's
/// start when no label is on it. On character boundaries.
fn windows(content: &str, points: impl Iterator<Item = usize>) -> Vec<(usize, usize)> {
    let floor = |mut i: usize| {
        i = i.min(content.len());
        while !content.is_char_boundary(i) {
            i -= 1;
        }
        i
    };
    let mut out: Vec<(usize, usize)> = Vec::new();
    for p in points {
        let (a, b) = (
            floor(p.saturating_sub(AROUND_LABEL)),
            floor(p + AROUND_LABEL),
        );
        let full = out.len() == MAX_WINDOWS;
        match out.last_mut() {
            // Touching, or so near that a mark would hide less than it takes.
            Some(last) if a <= last.1 + CUT_MARK.len() => last.1 = last.1.max(b),
            _ if full => break,
            _ => out.push((a, b)),
        }
    }
    if out.is_empty() {
        out.push((0, floor(LONG_LINE)));
    }
    // A start left out by less than its mark is kept.
    if out[0].0 <= LEAD_MARK.len() {
        out[0].0 = 0;
    }
    out
}

#[derive(Debug, Serialize)]
pub struct JsonDiagnostic<'a> {
    pub code: &'static str,
    pub severity: Severity,
    pub message: Cow<'a, str>,
    pub file: &'a str,
    pub line: usize,
    pub column: usize,
    pub end_line: usize,
    pub end_column: usize,
    #[serde(skip_serializing_if = "str::is_empty")]
    pub label: Cow<'a, str>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub help: Option<Cow<'a, str>>,
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
    pub message: Cow<'a, str>,
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
                message: short(&d.message),
                file: files[d.file.0 as usize].path,
                line,
                column,
                end_line,
                end_column,
                label: short(&d.label),
                help: d.help.as_deref().map(short),
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
                            message: short(&s.message),
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
        assert_eq!(shown.offset(10_000), LONG_LINE + TAIL_MARK.len());
        assert_eq!(&shown.text[LONG_LINE..], " ...\n");
    }

    /// The longest line a report shows: what each diagnostic prints of a source line.
    fn longest_line(out: &str) -> usize {
        out.lines().map(|l| l.chars().count()).max().unwrap_or(0)
    }

    #[test]
    fn a_label_far_into_a_long_line_is_shown_with_a_window_round_it() {
        for len in [6_000, 1 << 20] {
            let at = len - 1_000;
            let mut line = "a".repeat(len);
            line.replace_range(at..at + 5, "WRONG");
            let text = format!("x = 1\n{line}\ny = 2\n");
            let start = 6 + at;
            let out = render(&text, &[Span::new(start, start + 5)]);
            assert!(
                longest_line(&out) < 3 * AROUND_LABEL + 40,
                "{len}: a line of {} characters:\n{out}",
                longest_line(&out)
            );
            assert!(out.len() < 2_000, "{len}: {} bytes", out.len());
            assert!(
                out.contains(&format!("f.ilmr:2:{} ", at + 1)),
                "{len}: the true column:\n{out}"
            );
            assert!(
                out.contains(&format!(
                    "... {}WRONG{} ...",
                    "a".repeat(60),
                    "a".repeat(60)
                )),
                "{len}:\n{out}"
            );
            // The label's caret stands under the label.
            let shown = out.lines().find(|l| l.contains("WRONG")).expect("the line");
            let marks = out.lines().find(|l| l.contains("^^|^^")).expect(&out);
            assert_eq!(shown.find("WRONG"), marks.find("^^|^^"), "\n{out}");
        }
    }

    #[test]
    fn labels_far_apart_on_one_line_get_a_window_each() {
        let mut line = "b".repeat(100_000);
        line.replace_range(500..503, "ONE");
        line.replace_range(90_000..90_003, "TWO");
        let text = format!("{line}\n");
        let out = render(&text, &[Span::new(500, 503), Span::new(90_000, 90_003)]);
        assert!(longest_line(&out) < 5 * AROUND_LABEL + 60, "\n{out}");
        let cut = out.lines().find(|l| l.contains("ONE")).expect("the line");
        assert!(
            cut.contains("ONE") && cut.contains(" ... ") && cut.contains("TWO"),
            "{cut}"
        );
        assert!(out.contains("f.ilmr:1:501 "), "\n{out}");
        assert!(out.contains("f.ilmr:1:90001 "), "\n{out}");
    }

    #[test]
    fn a_long_line_of_many_characters_is_cut_on_their_boundaries() {
        let line = "é".repeat(5_000);
        let text = format!("{line}\n");
        let at = 2 * 3_000;
        let out = render(&text, &[Span::new(at, at + 2)]);
        assert!(longest_line(&out) < 3 * AROUND_LABEL + 40, "\n{out}");
        assert!(out.contains("f.ilmr:1:3001 "), "\n{out}");
    }

    #[test]
    fn a_message_quoting_a_long_token_keeps_its_ends() {
        let token = "n".repeat(1 << 20);
        let message = format!("unexpected name `{token}`");
        let cut = short(&message);
        assert_eq!(cut.chars().count(), LONG_MESSAGE);
        assert!(cut.starts_with("unexpected name `nnn"), "{cut}");
        assert!(cut.ends_with("nnn`"), "{cut}");
        assert!(cut.contains(CUT_MARK), "{cut}");
        let d = Diagnostic::new(Code::Syntax, FileId(0), Span::new(0, 1), message);
        let files = [RenderFile {
            path: "f.ilmr",
            text: "x\n",
        }];
        let json = serde_json::to_string(&json(std::slice::from_ref(&d), &files)).unwrap();
        assert!(json.len() < 1_000, "{} bytes of JSON", json.len());
        let out = human(&[d], &files, Style::PLAIN);
        assert!(out.len() < 1_500, "{} bytes:\n{out}", out.len());
        assert_eq!(short("speed(0.4) is refused"), "speed(0.4) is refused");
    }

    #[test]
    fn short_lines_are_shown_whole() {
        let text = "speed(0.4)\nturn(left)\n";
        let shown = Shown::new(text, std::iter::empty());
        assert_eq!(shown.text, text);
        assert!(shown.cuts.is_empty());
    }
}

//! Problems and failures as people read them: ariadne reports against the test file.

use std::ops::Range;

use ariadne::{Color, Label, Report, ReportKind, Source};
use ilmr_compiler::render::{AROUND_LABEL, LONG_LINE};

use super::problem::Problem;

pub use ilmr_compiler::render::Style;

/// One report: the problem's code and `head` at its top, its message as the label at
/// its span of the file, and its help.
pub fn report(path: &str, text: &str, head: &str, p: &Problem, style: Style) -> String {
    let config = style.config();
    let span = p.span.start.min(text.len())..p.span.end.min(text.len());
    let window = windowed(text, span.clone());
    let (text, span) = match &window {
        Some((shown, span)) => (shown.as_str(), span.clone()),
        None => (text, span),
    };
    let path = path.to_string();
    let mut report = Report::build(ReportKind::Error, (path.clone(), span.clone()))
        .with_config(config)
        .with_code(p.code.as_str())
        .with_message(head)
        .with_label(
            Label::new((path.clone(), span))
                .with_message(&p.message)
                .with_color(Color::Red),
        );
    if let Some(help) = &p.help {
        report = report.with_help(help);
    }
    let mut out = Vec::new();
    // Writing into a Vec cannot fail.
    let _ = report.finish().write((path, Source::from(text)), &mut out);
    String::from_utf8_lossy(&out).into_owned()
}

/// When a line the problem touches is longer than the compiler's `LONG_LINE` (a test
/// file's line can be megabytes, and every problem on it printed it whole): the file
/// as shown instead, its lines before the problem's empty so that line numbers stay
/// true, and of the problem's first line only `AROUND_LABEL` characters each side of
/// the problem (itself cut to twice that), with `...` where text was left out.
fn windowed(text: &str, span: Range<usize>) -> Option<(String, Range<usize>)> {
    let start = floor(text, span.start);
    let line_start = text[..start].rfind('\n').map_or(0, |i| i + 1);
    let line_end = text[start..].find('\n').map_or(text.len(), |i| start + i);
    let last_end = text[span.end.max(start)..]
        .find('\n')
        .map_or(text.len(), |i| span.end.max(start) + i);
    let longest = text[line_start..last_end]
        .split('\n')
        .map(str::len)
        .max()
        .unwrap_or(0);
    if longest <= LONG_LINE {
        return None;
    }
    let end = floor(
        text,
        span.end
            .clamp(start, line_end)
            .min(start + 2 * AROUND_LABEL),
    );
    let from = floor(text, start.saturating_sub(AROUND_LABEL).max(line_start));
    let to = floor(text, (end + AROUND_LABEL).min(line_end));
    let mut shown = "\n".repeat(text[..line_start].matches('\n').count());
    if from > line_start {
        shown.push_str("... ");
    }
    let at = shown.len();
    shown.push_str(&text[from..to]);
    if to < line_end {
        shown.push_str(" ...");
    }
    shown.push('\n');
    Some((shown, at + start - from..at + end - from))
}

/// The last character boundary of `text` at or before `at`.
fn floor(text: &str, at: usize) -> usize {
    let mut at = at.min(text.len());
    while !text.is_char_boundary(at) {
        at -= 1;
    }
    at
}

/// A problem of a test file, its code's title at the top.
pub fn problem(path: &str, text: &str, p: &Problem, style: Style) -> String {
    report(path, text, p.code.title(), p, style)
}

/// Text without the escape sequences of colours (for JUnit XML).
pub fn strip_ansi(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut chars = text.chars();
    while let Some(c) = chars.next() {
        if c == '\u{1b}' {
            // CSI: ESC [ parameters final-byte.
            if chars.next() == Some('[') {
                for d in chars.by_ref() {
                    if ('@'..='~').contains(&d) {
                        break;
                    }
                }
            }
            continue;
        }
        out.push(c);
    }
    out
}

#[cfg(test)]
mod window_tests {
    use super::*;
    use ilmr_testfile::codes::Code;

    /// Each problem on a line of megabytes printed the line whole: a file of one such
    /// line and a hundred problems on it printed hundreds of megabytes.
    #[test]
    fn a_problem_on_a_long_line_shows_a_window_of_it() {
        let text = format!(
            "a = 1\nb = {}x{}\n",
            "y".repeat(1 << 20),
            "z".repeat(1 << 20)
        );
        let at = text.find('x').unwrap();
        let p = Problem::new(Code::BadValue, at..at + 1, "here");
        let shown = problem("f.test.toml", &text, &p, Style::PLAIN);
        assert!(shown.len() < 2_000, "{} bytes", shown.len());
        assert!(
            shown.contains("yyyx") && shown.contains("xzzz") && shown.contains("..."),
            "{shown}"
        );
        assert!(
            shown.contains(" 2 │") || shown.contains(" 2 |"),
            "the true line number: {shown}"
        );
        let short = Problem::new(Code::BadValue, 0..1, "here");
        assert_eq!(windowed("a = 1\n", short.span), None);
    }
}

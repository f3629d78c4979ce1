//! Problems and failures as people read them: ariadne reports against the test file.

use ariadne::{Color, Label, Report, ReportKind, Source};

use super::problem::Problem;

pub use ilmr_compiler::render::Style;

/// One report: the problem's code and `head` at its top, its message as the label at
/// its span of the file, and its help.
pub fn report(path: &str, text: &str, head: &str, p: &Problem, style: Style) -> String {
    let config = style.config();
    let span = p.span.start.min(text.len())..p.span.end.min(text.len());
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

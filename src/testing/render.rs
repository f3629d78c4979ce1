//! Problems and failures as people read them: ariadne reports against the test file.

use ilmr_compiler::Span;
use ilmr_compiler::diagnostic::Severity;
use ilmr_compiler::render::{RenderFile, Single, single};

use super::problem::Problem;

pub use ilmr_compiler::render::Style;

/// One report: the problem's code and `head` at its top, its message as the label at
/// its span of the file, and its help; long lines cut as the compiler cuts a program's.
pub fn report(path: &str, text: &str, head: &str, p: &Problem, style: Style) -> String {
    let span = Span::new(p.span.start.min(text.len()), p.span.end.min(text.len()));
    let file = RenderFile { path, text };
    let one = Single {
        severity: Severity::Error,
        code: p.code.as_str(),
        message: head,
        span,
        label: &p.message,
        help: p.help.as_deref(),
    };
    single(&file, &one, style)
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
        let whole = problem("f.test.toml", "a = 1\n", &short, Style::PLAIN);
        assert!(whole.contains("a = 1") && !whole.contains("..."), "{whole}");
    }
}

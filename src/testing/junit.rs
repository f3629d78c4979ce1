//! JUnit XML, as CI servers read it: one `testsuite` per test file, one `testcase` per
//! test, a `failure` with the report of a test that failed.

use std::fmt::Write as _;

/// One test's result for the XML.
pub struct Case<'a> {
    pub file: &'a str,
    pub name: &'a str,
    pub seconds: f64,
    /// The one-line reason and the whole report, when it failed.
    pub failure: Option<(String, String)>,
}

pub fn write(cases: &[Case<'_>], seconds: f64) -> String {
    let failures = cases.iter().filter(|c| c.failure.is_some()).count();
    let mut x = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    let _ = writeln!(
        x,
        "<testsuites name=\"ilmrc test\" tests=\"{}\" failures=\"{failures}\" errors=\"0\" time=\"{seconds:.3}\">",
        cases.len()
    );
    let mut files: Vec<&str> = cases.iter().map(|c| c.file).collect();
    files.dedup();
    for file in files {
        let mine: Vec<&Case> = cases.iter().filter(|c| c.file == file).collect();
        let failed = mine.iter().filter(|c| c.failure.is_some()).count();
        let time: f64 = mine.iter().map(|c| c.seconds).sum();
        let _ = writeln!(
            x,
            "  <testsuite name=\"{}\" tests=\"{}\" failures=\"{failed}\" errors=\"0\" time=\"{time:.3}\">",
            escape(file),
            mine.len()
        );
        for c in mine {
            let _ = write!(
                x,
                "    <testcase classname=\"{}\" name=\"{}\" time=\"{:.3}\"",
                escape(file),
                escape(c.name),
                c.seconds
            );
            match &c.failure {
                None => x.push_str("/>\n"),
                Some((message, report)) => {
                    let _ = writeln!(
                        x,
                        ">\n      <failure message=\"{}\">{}</failure>\n    </testcase>",
                        escape(message),
                        escape(report)
                    );
                }
            }
        }
        x.push_str("  </testsuite>\n");
    }
    x.push_str("</testsuites>\n");
    x
}

/// Text as XML character data or an attribute value. Characters XML 1.0 does not
/// allow (most control characters) are written as U+FFFD.
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            '\n' | '\t' | '\r' => out.push(c),
            c if (c as u32) < 0x20 || c == '\u{FFFE}' || c == '\u{FFFF}' => out.push('\u{FFFD}'),
            c => out.push(c),
        }
    }
    out
}

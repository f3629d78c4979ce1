//! The checker's diagnostics as LSP diagnostics. The message's first line is the one
//! `ilmrc check` prints; the label and the help follow on lines of their own, as the
//! command line's report shows them. Secondary labels become related information.

use ilmr_compiler::diagnostic::{Diagnostic, FileId, Severity};
use ilmr_compiler::{Code, Span};
use ilmr_model::ModelWarning;
use tower_lsp_server::ls_types::{
    self as lsp, DiagnosticRelatedInformation, DiagnosticSeverity, Location, NumberOrString,
    Position, Range, Uri,
};

use crate::line_index::LineIndex;

pub const SOURCE: &str = "ilmr";

/// The language server's own code for a file whose analysis failed: a bug in the
/// checker, isolated to the file. The compiler's codes are `E`/`W` and four digits.
pub const ANALYSIS_FAILED: &str = "L0001";

/// What a file the checker failed on shows instead of its diagnostics, at its start.
pub const ANALYSIS_FAILED_MESSAGE: &str = "ilmr-lsp could not analyse this file: \
    the checker failed on it (an internal error, reported in the server's log). \
    The other files are analysed without it.";

/// The language server's own code for an open document larger than `ilmrc` reads a
/// task or skill file (`ilmr_files::MAX_SOURCE_BYTES`): it is not analysed, so the
/// editor and `ilmrc check` agree, and a keystroke in it costs nothing.
pub const TOO_LARGE: &str = "L0002";

pub fn too_large() -> lsp::Diagnostic {
    let why = ilmr_files::ReadError {
        kind: ilmr_files::Kind::Source,
        problem: ilmr_files::Problem::TooLarge,
    };
    lsp::Diagnostic {
        range: Range::default(),
        severity: Some(DiagnosticSeverity::ERROR),
        code: Some(NumberOrString::String(TOO_LARGE.to_string())),
        source: Some(SOURCE.to_string()),
        message: format!("this file is not analysed: {why}"),
        ..Default::default()
    }
}

pub fn analysis_failed() -> lsp::Diagnostic {
    lsp::Diagnostic {
        range: Range::default(),
        severity: Some(DiagnosticSeverity::ERROR),
        code: Some(NumberOrString::String(ANALYSIS_FAILED.to_string())),
        source: Some(SOURCE.to_string()),
        message: ANALYSIS_FAILED_MESSAGE.to_string(),
        ..Default::default()
    }
}

/// Turns a file's span into a location; `None` for files no editor can open.
pub trait Locate {
    fn locate(&self, file: FileId, span: Span) -> Option<(Uri, Range)>;
}

pub fn to_lsp(d: &Diagnostic, range: Range, files: &impl Locate) -> lsp::Diagnostic {
    let mut message = d.message.clone();
    if !d.label.is_empty() && d.label != d.message {
        message.push('\n');
        message.push_str(&d.label);
    }
    if let Some(help) = &d.help {
        message.push_str("\nhelp: ");
        message.push_str(help);
    }
    let related: Vec<DiagnosticRelatedInformation> = d
        .secondary
        .iter()
        .filter_map(|l| {
            let (uri, range) = files.locate(l.file, l.span)?;
            Some(DiagnosticRelatedInformation {
                location: Location::new(uri, range),
                message: l.message.clone(),
            })
        })
        .collect();
    lsp::Diagnostic {
        range,
        severity: Some(severity(d.severity())),
        code: Some(NumberOrString::String(d.code.as_str().to_string())),
        code_description: None,
        source: Some(SOURCE.to_string()),
        message,
        related_information: (!related.is_empty()).then_some(related),
        tags: None,
        data: None,
    }
}

fn severity(s: Severity) -> DiagnosticSeverity {
    match s {
        Severity::Error => DiagnosticSeverity::ERROR,
        Severity::Warning => DiagnosticSeverity::WARNING,
    }
}

/// A robot-model warning on the line it names (the whole file when it names none).
pub fn model_warning(w: &ModelWarning, text: Option<(&str, &LineIndex)>) -> lsp::Diagnostic {
    let range = match (w.line, text) {
        (Some(line), Some((text, index))) if line > 0 => {
            index.range(text, index.line_span(text, line as usize - 1))
        }
        (Some(line), None) if line > 0 => {
            Range::new(Position::new(line - 1, 0), Position::new(line, 0))
        }
        _ => Range::default(),
    };
    lsp::Diagnostic {
        range,
        severity: Some(severity(Code::RobotModel.severity())),
        code: Some(NumberOrString::String(
            Code::RobotModel.as_str().to_string(),
        )),
        source: Some(SOURCE.to_string()),
        message: w.message.clone(),
        ..Default::default()
    }
}

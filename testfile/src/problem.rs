//! A problem found in a test file: a code, the bytes it points at, what is wrong, and
//! where one exists a suggestion.

use std::ops::Range;

use super::codes::Code;

#[derive(Debug, Clone, PartialEq)]
pub struct Problem {
    pub code: Code,
    /// Bytes of the test file.
    pub span: Range<usize>,
    pub message: String,
    pub help: Option<String>,
}

impl Problem {
    pub fn new(code: Code, span: Range<usize>, message: impl Into<String>) -> Problem {
        Problem {
            code,
            span,
            message: message.into(),
            help: None,
        }
    }

    pub fn help(mut self, help: impl Into<String>) -> Problem {
        self.help = Some(help.into());
        self
    }

    /// "did you mean `x`?" when one of `candidates` is close to `word`.
    pub fn suggest<'a>(self, word: &str, candidates: impl IntoIterator<Item = &'a str>) -> Problem {
        match ilmr_compiler::check::suggest::closest(word, candidates) {
            Some(near) => self.help(format!("did you mean `{near}`?")),
            None => self,
        }
    }
}

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

/// Characters of a message or help kept, as the compiler keeps of its diagnostics'
/// (`ilmr_compiler::render::LONG_MESSAGE`): a message that quotes a key, a name, a
/// path or a value quotes all of it, and any of those can be megabytes long.
pub const MAX_MESSAGE: usize = ilmr_compiler::render::LONG_MESSAGE;
/// What is kept of a long message's end: the close of its quote and what follows.
const MESSAGE_TAIL: usize = 60;
const CUT_MARK: &str = " ... ";

/// `message` in at most [`MAX_MESSAGE`] characters: a longer one keeps its start and
/// its end, with ` ... ` between.
pub fn clip(message: String) -> String {
    let chars = message.chars().count();
    if chars <= MAX_MESSAGE {
        return message;
    }
    let head = MAX_MESSAGE - MESSAGE_TAIL - CUT_MARK.len();
    let mut out: String = message.chars().take(head).collect();
    out.push_str(CUT_MARK);
    out.extend(message.chars().skip(chars - MESSAGE_TAIL));
    out
}

impl Problem {
    pub fn new(code: Code, span: Range<usize>, message: impl Into<String>) -> Problem {
        Problem {
            code,
            span,
            message: clip(message.into()),
            help: None,
        }
    }

    pub fn help(mut self, help: impl Into<String>) -> Problem {
        self.help = Some(clip(help.into()));
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A key of a megabyte was quoted whole in `unknown key` (and a name, a path or a
    /// value in the others), and `ilmrc test` printed it.
    #[test]
    fn a_message_quoting_a_long_word_is_cut_to_its_ends() {
        let key = "k".repeat(1 << 20);
        let p = Problem::new(Code::UnknownKey, 0..1, format!("unknown key `{key}`"))
            .help(format!("did you mean `{key}`?"));
        assert_eq!(p.message.chars().count(), MAX_MESSAGE);
        assert!(p.message.starts_with("unknown key `kkk"), "{}", p.message);
        assert!(
            p.message.ends_with("kkk`") && p.message.contains(" ... "),
            "{}",
            p.message
        );
        assert_eq!(
            p.help.as_deref().map(|h| h.chars().count()),
            Some(MAX_MESSAGE)
        );
        let short = Problem::new(Code::UnknownKey, 0..1, "unknown key `x`");
        assert_eq!(short.message, "unknown key `x`");
    }
}

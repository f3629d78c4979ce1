//! What a typed line means: a shell command (`:status`), ILMR text to join, a block
//! still being typed (`if(..)` until its `endif`), or a `check` ... `checkend` block to
//! validate. Pure: the loop in `mod.rs` acts on what [`Collector::take`] returns.

/// A command to the shell itself. They start with `:` so that none can clash with
/// ILMR, whose statements never do.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ShellCommand {
    Status,
    /// Echo the start and end of every command (toggles).
    Watch,
    Help,
    Quit,
}

#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Input {
    Shell(ShellCommand),
    /// ILMR text to check and join: one line, or a block typed over several.
    Join(String),
    /// The text between `check` and `checkend`, to check and not join.
    Check(String),
    /// Part of a block or a check: wait for more lines.
    More,
    /// A blank or comment line outside a block.
    Nothing,
    /// Something to tell the person (an unknown shell command, a stray `checkend`).
    Note(String),
}

#[derive(Debug, Clone, PartialEq, Eq, Default)]
enum Mode {
    #[default]
    Line,
    /// Inside `if`/`while` blocks `depth` deep.
    Block {
        depth: u32,
        text: String,
    },
    Check {
        text: String,
    },
}

/// Collects typed lines into what they mean.
#[derive(Debug, Default)]
pub struct Collector {
    mode: Mode,
}

pub const SHELL_COMMANDS: [&str; 6] = [":status", ":watch", ":help", ":quit", ":exit", ":q"];

impl Collector {
    pub fn prompt(&self) -> &'static str {
        match self.mode {
            Mode::Line => "ilmr> ",
            Mode::Block { .. } => "...> ",
            Mode::Check { .. } => "check> ",
        }
    }

    /// Drops a block or check being typed (Ctrl-C); returns whether there was one.
    pub fn cancel(&mut self) -> bool {
        std::mem::take(&mut self.mode) != Mode::Line
    }

    pub fn take(&mut self, line: &str) -> Input {
        let bare = statement(line);
        if let Some(command) = bare.strip_prefix(':') {
            return shell_command(command);
        }
        match &mut self.mode {
            Mode::Line => {
                if bare.is_empty() {
                    return Input::Nothing;
                }
                if is_word(bare, "exit") || is_word(bare, "quit") {
                    return Input::Shell(ShellCommand::Quit);
                }
                if is_word(bare, "check") {
                    self.mode = Mode::Check {
                        text: String::new(),
                    };
                    return Input::More;
                }
                if is_word(bare, "checkend") {
                    return Input::Note("`checkend` without `check`: nothing to check".into());
                }
                match block_delta(bare) {
                    d if d > 0 => {
                        self.mode = Mode::Block {
                            depth: d.unsigned_abs(),
                            text: format!("{line}\n"),
                        };
                        Input::More
                    }
                    _ => Input::Join(line.to_string()),
                }
            }
            Mode::Block { depth, text } => {
                text.push_str(line);
                text.push('\n');
                let d = i64::from(*depth) + i64::from(block_delta(bare));
                if d > 0 {
                    *depth = u32::try_from(d).unwrap_or(u32::MAX);
                    return Input::More;
                }
                let Mode::Block { text, .. } = std::mem::take(&mut self.mode) else {
                    return Input::More;
                };
                Input::Join(text)
            }
            Mode::Check { text } => {
                if is_word(bare, "checkend") {
                    let Mode::Check { text } = std::mem::take(&mut self.mode) else {
                        return Input::More;
                    };
                    return Input::Check(text);
                }
                if is_word(bare, "check") {
                    return Input::Note("already checking: `checkend` ends the check".into());
                }
                text.push_str(line);
                text.push('\n');
                Input::More
            }
        }
    }
}

fn shell_command(name: &str) -> Input {
    let name = name.trim().to_ascii_lowercase();
    match name.as_str() {
        "status" | "s" => Input::Shell(ShellCommand::Status),
        "watch" | "w" => Input::Shell(ShellCommand::Watch),
        "help" | "h" | "?" => Input::Shell(ShellCommand::Help),
        "quit" | "exit" | "q" => Input::Shell(ShellCommand::Quit),
        _ => Input::Note(format!(
            "unknown shell command `:{name}`; the shell's commands are {}",
            SHELL_COMMANDS[..4].join(", ")
        )),
    }
}

/// The statement on a line: without its comment and surrounding blanks.
fn statement(line: &str) -> &str {
    line.split("//").next().unwrap_or("").trim()
}

/// `word` alone, in any letter case, with or without an empty `()`.
fn is_word(statement: &str, word: &str) -> bool {
    let s = statement.strip_suffix("()").unwrap_or(statement).trim_end();
    s.eq_ignore_ascii_case(word)
}

/// +1 for a line that opens an `if` or `while` block, -1 for one that closes it.
fn block_delta(statement: &str) -> i32 {
    let s: String = statement
        .chars()
        .filter(|c| !c.is_whitespace())
        .collect::<String>()
        .to_ascii_lowercase();
    if s == "endif" || s == "endwhile" {
        return -1;
    }
    // `v = while(..)` binds the loop; its name is an identifier.
    let after_bind = match s.split_once('=') {
        Some((name, rest))
            if !name.is_empty()
                && name.chars().all(|c| c.is_alphanumeric() || c == '_')
                && !rest.starts_with('=') =>
        {
            rest
        }
        _ => s.as_str(),
    };
    if s.starts_with("if(") || after_bind.starts_with("while(") {
        1
    } else {
        0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn feed(lines: &[&str]) -> Vec<Input> {
        let mut c = Collector::default();
        lines.iter().map(|l| c.take(l)).collect()
    }

    #[test]
    fn a_line_joins_and_shell_commands_are_recognised() {
        assert_eq!(
            feed(&[
                "goahead(1)",
                "  ",
                "// a note",
                ":status",
                ":Q",
                "exit",
                ":fly"
            ]),
            vec![
                Input::Join("goahead(1)".into()),
                Input::Nothing,
                Input::Nothing,
                Input::Shell(ShellCommand::Status),
                Input::Shell(ShellCommand::Quit),
                Input::Shell(ShellCommand::Quit),
                Input::Note(
                    "unknown shell command `:fly`; the shell's commands are :status, :watch, \
                     :help, :quit"
                        .into()
                ),
            ]
        );
    }

    #[test]
    fn a_block_is_collected_until_it_closes() {
        let got = feed(&[
            "If(x < 1) // guard",
            "  n = while(x < 3)",
            "    x = x + 1",
            "  endwhile",
            "EndIf",
            "goahead(1)",
        ]);
        assert_eq!(
            got[..4],
            [Input::More, Input::More, Input::More, Input::More]
        );
        assert_eq!(
            got[4],
            Input::Join(
                "If(x < 1) // guard\n  n = while(x < 3)\n    x = x + 1\n  endwhile\nEndIf\n".into()
            )
        );
        assert_eq!(got[5], Input::Join("goahead(1)".into()));
    }

    #[test]
    fn a_comparison_is_not_a_bound_loop() {
        assert_eq!(block_delta("x == while(1)"), 0);
        assert_eq!(block_delta("w=while(a<2)"), 1);
        assert_eq!(block_delta("iffy(3)"), 0);
        assert_eq!(block_delta("end if"), -1);
    }

    #[test]
    fn check_collects_until_checkend_and_joins_nothing() {
        let mut c = Collector::default();
        assert_eq!(c.take("CHECK"), Input::More);
        assert_eq!(c.prompt(), "check> ");
        assert_eq!(c.take("speed(0.3)"), Input::More);
        assert!(matches!(c.take("check"), Input::Note(_)));
        assert_eq!(c.take(":status"), Input::Shell(ShellCommand::Status));
        assert_eq!(c.take("if(a)"), Input::More);
        assert_eq!(
            c.take("checkend"),
            Input::Check("speed(0.3)\nif(a)\n".into())
        );
        assert_eq!(c.prompt(), "ilmr> ");
        assert!(matches!(c.take("checkend"), Input::Note(_)));
    }

    #[test]
    fn cancel_drops_what_was_being_typed() {
        let mut c = Collector::default();
        assert!(!c.cancel());
        assert_eq!(c.take("while(1)"), Input::More);
        assert!(c.cancel());
        assert_eq!(c.take("goahead(1)"), Input::Join("goahead(1)".into()));
    }
}

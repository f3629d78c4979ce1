//! Tab completion: the catalogue's commands and keywords, the reserved words, the
//! robot model's names, the shell's own commands, and the running task's variables and
//! skills (refreshed after every line that joins).

use std::sync::{Arc, Mutex};

use ilmr_model::RobotModel;
use rustyline::Context;
use rustyline::completion::{Completer, Pair};
use rustyline::highlight::Highlighter;
use rustyline::hint::Hinter;
use rustyline::validate::Validator;

use super::input::SHELL_COMMANDS;

/// Every word that can be completed, sorted by lower case and without repeats.
#[derive(Debug, Clone, Default)]
pub struct Words {
    fixed: Vec<String>,
    task: Vec<String>,
}

impl Words {
    pub fn new(model: &RobotModel) -> Words {
        let mut fixed: Vec<String> = ilmr_stdlib::CATALOGUE
            .iter()
            .map(|s| s.name.to_string())
            .chain(ilmr_stdlib::all_keywords().into_iter().map(str::to_string))
            .chain(ilmr_stdlib::RESERVED.iter().map(|w| w.to_string()))
            .chain(model.names().map(|(name, _)| name.to_string()))
            .collect();
        sort(&mut fixed);
        Words {
            fixed,
            task: Vec::new(),
        }
    }

    /// The running task's variables and skills.
    pub fn set_task(&mut self, names: impl IntoIterator<Item = String>) {
        self.task = names.into_iter().collect();
        sort(&mut self.task);
    }

    /// Words that start with `prefix` in any letter case, in order.
    pub fn starting(&self, prefix: &str) -> Vec<String> {
        let p = prefix.to_lowercase();
        let mut out: Vec<String> = self
            .fixed
            .iter()
            .chain(&self.task)
            .filter(|w| w.to_lowercase().starts_with(&p))
            .cloned()
            .collect();
        sort(&mut out);
        out
    }
}

fn sort(words: &mut Vec<String>) {
    words.sort_by_key(|w| (w.to_lowercase(), w.clone()));
    words.dedup_by(|a, b| a.eq_ignore_ascii_case(b));
}

/// The word the cursor is in, up to the cursor: its start and text. A `:` at the start
/// of the line belongs to the word (a shell command).
fn word_before(line: &str, pos: usize) -> (usize, &str) {
    let head = line.get(..pos).unwrap_or(line);
    let start = head
        .char_indices()
        .rev()
        .find(|(_, c)| !(c.is_alphanumeric() || *c == '_'))
        .map_or(0, |(i, c)| i + c.len_utf8());
    let start = if start == 1 && head.starts_with(':') {
        0
    } else {
        start
    };
    (start, &head[start..])
}

/// rustyline's helper: completion only (no hints, highlighting or validation).
pub struct ShellHelper {
    pub words: Arc<Mutex<Words>>,
}

impl ShellHelper {
    pub fn candidates(&self, line: &str, pos: usize) -> (usize, Vec<String>) {
        let (start, word) = word_before(line, pos);
        if word.is_empty() {
            return (start, Vec::new());
        }
        if word.starts_with(':') {
            let shell = SHELL_COMMANDS
                .iter()
                .filter(|c| c.starts_with(&word.to_lowercase()))
                .map(|c| c.to_string())
                .collect();
            return (start, shell);
        }
        let words = match self.words.lock() {
            Ok(w) => w.starting(word),
            Err(poisoned) => poisoned.into_inner().starting(word),
        };
        (start, words)
    }
}

impl Completer for ShellHelper {
    type Candidate = Pair;

    fn complete(
        &self,
        line: &str,
        pos: usize,
        _ctx: &Context<'_>,
    ) -> rustyline::Result<(usize, Vec<Pair>)> {
        let (start, words) = self.candidates(line, pos);
        let pairs = words
            .into_iter()
            .map(|w| Pair {
                display: w.clone(),
                replacement: w,
            })
            .collect();
        Ok((start, pairs))
    }
}

impl Hinter for ShellHelper {
    type Hint = String;
}

impl Highlighter for ShellHelper {}

impl Validator for ShellHelper {}

impl rustyline::Helper for ShellHelper {}

#[cfg(test)]
mod tests {
    use super::*;

    fn helper() -> ShellHelper {
        let model = RobotModel::builtin("moro").expect("shipped model");
        let mut words = Words::new(&model);
        words.set_task(["MyDoor".to_string(), "Takebox".to_string()]);
        ShellHelper {
            words: Arc::new(Mutex::new(words)),
        }
    }

    #[test]
    fn commands_keywords_and_names_complete_in_any_case() {
        let h = helper();
        let goa = vec!["goahead".to_string(), "goalpos".to_string()];
        assert_eq!(h.candidates("goa", 3), (0, goa));
        assert_eq!(
            h.candidates("x = GOAH", 8),
            (4, vec!["goahead".to_string()])
        );
        let (start, words) = h.candidates("turn(lef", 8);
        assert_eq!((start, words), (5, vec!["left".to_string()]));
        assert_eq!(h.candidates("wait(myd", 8).1, vec!["MyDoor".to_string()]);
        assert_eq!(h.candidates("takeb", 5).1, vec!["Takebox".to_string()]);
        assert!(h.candidates("endw", 4).1.contains(&"endwhile".to_string()));
        assert_eq!(h.candidates("goahead(", 8).1, Vec::<String>::new());
    }

    #[test]
    fn the_model_names_are_offered() {
        let model = RobotModel::builtin("moro").expect("shipped model");
        let h = helper();
        let (name, _) = model.names().next().expect("MoRo's model names something");
        let prefix: String = name.chars().take(3).collect();
        assert!(
            h.candidates(&prefix, prefix.len())
                .1
                .iter()
                .any(|w| w == name),
            "{name}"
        );
    }

    #[test]
    fn shell_commands_complete_after_a_colon() {
        let h = helper();
        assert_eq!(h.candidates(":st", 3), (0, vec![":status".to_string()]));
        assert_eq!(
            h.candidates(":q", 2).1,
            vec![":quit".to_string(), ":q".to_string()]
        );
    }
}

//! Skill files, checked in full (named on the command line) and as a `--skills`
//! library, called from a task that calls every skill the file heads.

use ilmr_compiler::check::Source;
use ilmr_model::RobotModel;

use super::corpus::{self, ROBOTS};
use crate::engine::{self, Budget, Stats};
use crate::{mutate, pipeline};

/// A task calling every `NAME:` header of a skill file, one block each.
fn caller(skills: &str) -> String {
    let calls: Vec<String> = skills
        .lines()
        .filter_map(|l| l.trim().strip_suffix(':'))
        .filter(|name| !name.is_empty() && !name.contains(char::is_whitespace))
        .map(|name| format!("{name}\n"))
        .collect();
    calls.join("\n")
}

/// The target, shared by this loop and the AFL++ binary (`fuzz/src/bin/skills.rs`).
pub struct Skills {
    models: Vec<RobotModel>,
}

impl Skills {
    pub fn load() -> Skills {
        Skills {
            models: ROBOTS.iter().map(|r| corpus::model(r)).collect(),
        }
    }

    pub fn feed(&self, input: &[u8]) {
        let text = String::from_utf8_lossy(input);
        let task = caller(&text);
        for model in &self.models {
            let checked = [
                Source::new("task.ilmr", task.as_str()),
                Source::new("fuzz.ilms", text.as_ref()),
            ];
            if let Some(module) = pipeline::compile(&checked, model) {
                pipeline::run(module, model, None);
            }
            let library = [
                Source::new("task.ilmr", task.as_str()),
                Source::library("fuzz.ilms", text.as_ref()),
            ];
            let _ = pipeline::compile(&library, model);
        }
    }
}

pub fn fuzz(budget: Budget) -> Stats {
    let corpus = corpus::skill_files();
    let dictionary = mutate::ilmr_dictionary();
    let target = Skills::load();
    engine::run(
        "skills",
        &corpus,
        budget,
        |base, rng| mutate::text(base, rng, &corpus, &dictionary),
        |input| target.feed(input),
    )
}

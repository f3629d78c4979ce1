//! Skill files, checked in full (named on the command line) and as a `--skills`
//! library, called from a task that calls every skill the file heads.

use ilmr_compiler::check::Source;

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

pub fn fuzz(budget: Budget) -> Stats {
    let corpus = corpus::skill_files();
    let dictionary = mutate::ilmr_dictionary();
    let models: Vec<_> = ROBOTS.iter().map(|r| corpus::model(r)).collect();
    engine::run(
        "skills",
        &corpus,
        budget,
        |base, rng| mutate::text(base, rng, &corpus, &dictionary),
        |input| {
            let text = String::from_utf8_lossy(input);
            let task = caller(&text);
            for model in &models {
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
        },
    )
}

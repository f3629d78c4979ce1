//! Task files through check, render, lowering, encoding, a short run, and the same
//! text as an interactive line joining a running program.

use ilmr_compiler::check::Source;
use ilmr_model::RobotModel;

use super::corpus::{self, ROBOTS};
use crate::engine::{self, Budget, Stats};
use crate::{mutate, pipeline};

/// The target, shared by this loop and the AFL++ binary (`fuzz/src/bin/task.rs`).
pub struct Tasks {
    models: Vec<RobotModel>,
}

impl Tasks {
    /// Loads the models and builds the live programs once, before the first input
    /// (under AFL++, before the fork server forks, so that no input pays for them).
    pub fn load() -> Tasks {
        for robot in ROBOTS {
            corpus::live_module(robot);
        }
        Tasks {
            models: ROBOTS.iter().map(|r| corpus::model(r)).collect(),
        }
    }

    pub fn feed(&self, input: &[u8]) {
        let text = String::from_utf8_lossy(input);
        let mut sources = vec![Source::new("fuzz.ilmr", text.as_ref())];
        sources.extend(corpus::library().iter().cloned());
        for (robot, model) in ROBOTS.iter().zip(&self.models) {
            if let Some(module) = pipeline::compile(&sources, model) {
                pipeline::run(module, model, None);
            }
            pipeline::run(corpus::live_module(robot), model, Some(&text));
        }
    }
}

pub fn fuzz(budget: Budget) -> Stats {
    let corpus = corpus::tasks();
    let dictionary = mutate::ilmr_dictionary();
    let target = Tasks::load();
    engine::run(
        "task",
        corpus,
        budget,
        |base, rng| mutate::text(base, rng, corpus, &dictionary),
        |input| target.feed(input),
    )
}

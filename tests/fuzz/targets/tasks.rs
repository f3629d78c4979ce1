//! Task files through check, render, lowering, encoding, a short run, and the same
//! text as an interactive line joining a running program.

use ilmr_compiler::check::Source;

use super::corpus::{self, ROBOTS};
use crate::engine::{self, Budget, Stats};
use crate::{mutate, pipeline};

pub fn fuzz(budget: Budget) -> Stats {
    let corpus = corpus::tasks();
    let dictionary = mutate::ilmr_dictionary();
    let models: Vec<_> = ROBOTS.iter().map(|r| corpus::model(r)).collect();
    engine::run(
        "task",
        corpus,
        budget,
        |base, rng| mutate::text(base, rng, corpus, &dictionary),
        |input| {
            let text = String::from_utf8_lossy(input);
            let mut sources = vec![Source::new("fuzz.ilmr", text.as_ref())];
            sources.extend(corpus::library().iter().cloned());
            for (robot, model) in ROBOTS.iter().zip(&models) {
                if let Some(module) = pipeline::compile(&sources, model) {
                    pipeline::run(module, model, None);
                }
                pipeline::run(corpus::live_module(robot), model, Some(&text));
            }
        },
    )
}

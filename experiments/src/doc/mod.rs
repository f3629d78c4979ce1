//! `docs/experiments.md`: for each test the dissertation's figures beside the ones
//! measured here, the bars the tests assert, and its picture. The numbers come from
//! the runs; the sections the generator does not write are kept (see [`merge`]).

mod controller;
mod fig20;
mod fmt;
mod intro;
pub mod merge;
mod predictions;
mod test1;
mod test2;
mod test3;
mod test4;
mod test5;
mod test6;
mod test7;

use crate::{Experiments, PICTURES};
use merge::Generated;

/// How each generated section's heading starts, in the order of the report.
const KEYS: [&str; 10] = [
    "## Test 1:",
    "## Predictions of the calibrated model",
    "## What the controller adds",
    "## Test 2:",
    "## Test 3:",
    "## Test 4:",
    "## Test 5:",
    "## Test 6:",
    "## Test 7:",
    "## Figure 20 ",
];

/// The command that writes the report, as the report names it.
pub const COMMAND: &str = "cargo run --release -p ilmr-experiments";

/// The report from `results`, keeping the sections of `existing` (the file as it is)
/// that are not generated.
pub fn render(results: &Experiments, existing: &str) -> String {
    let sections = [
        test1::section(&results.test1),
        predictions::section(&results.predictions),
        controller::section(&results.controller),
        test2::section(&results.test2),
        test3::section(&results.test3),
        test4::section(&results.test4),
        test5::section(&results.test5),
        test6::section(&results.test6),
        test7::section(&results.test7),
        fig20::section(&results.fig20),
    ];
    let generated: Vec<Generated> = KEYS
        .iter()
        .zip(sections)
        .map(|(key, text)| Generated {
            key: key.to_string(),
            text,
        })
        .collect();
    merge::merge(&intro::intro(&results.settings), &generated, existing)
}

/// The markdown that shows the `n`th experiment's picture (1-based, as [`PICTURES`]).
fn picture(n: usize, alt: &str) -> String {
    format!("![{alt}](experiments/{})\n", PICTURES[n - 1])
}

//! Seed corpora: the repository's own files (examples/, the dissertation fixtures in
//! tests/check and tests/run, the shipped ROBO.INI models) and generated valid tasks.

use std::sync::OnceLock;

use ilmr_compiler::check::Source;
use ilmr_model::RobotModel;
use ilmr_vm::Module;

use crate::engine::{files, root};
use crate::pipeline;
use crate::taskgen::{Generator, Shape};

pub const ROBOTS: [&str; 2] = ["moro", "workpartner"];

/// Generated tasks in the corpus: valid programs that use every command family.
const GENERATED: u64 = 12;

pub fn model(name: &str) -> RobotModel {
    match RobotModel::builtin(name) {
        Some(m) => m,
        None => panic!("{name} is a shipped model"),
    }
}

/// Task files: the dissertation's programs, the broken fixtures, the run fixtures and
/// generated tasks for both robots.
pub fn tasks() -> &'static [Vec<u8>] {
    static TASKS: OnceLock<Vec<Vec<u8>>> = OnceLock::new();
    TASKS.get_or_init(|| {
        let mut out: Vec<Vec<u8>> = ["examples", "tests/check", "tests/run", "tests/sim_run"]
            .iter()
            .flat_map(|d| files(d, &["ilmr"]))
            .map(|(_, bytes)| bytes)
            .collect();
        for robot in ROBOTS {
            let m = model(robot);
            let generator = Generator::new(&[&m], Shape::default());
            for seed in 0..GENERATED {
                out.push(generator.generate(seed).task.into_bytes());
            }
        }
        out
    })
}

/// Skill files: the example library and the broken skill fixtures.
pub fn skill_files() -> Vec<Vec<u8>> {
    ["examples", "tests/check"]
        .iter()
        .flat_map(|d| files(d, &["ilms"]))
        .map(|(_, bytes)| bytes)
        .collect()
}

/// The example skill library as `--skills examples/skills` passes it.
pub fn library() -> &'static [Source] {
    static LIBRARY: OnceLock<Vec<Source>> = OnceLock::new();
    LIBRARY.get_or_init(|| {
        files("examples/skills", &["ilms"])
            .into_iter()
            .map(|(path, bytes)| Source::library(path, String::from_utf8_lossy(&bytes)))
            .collect()
    })
}

pub fn ini_files() -> Vec<Vec<u8>> {
    files("robots/model/models", &["ini"])
        .into_iter()
        .map(|(_, bytes)| bytes)
        .collect()
}

/// The live program fuzzed interactive lines join: the first of these tasks that
/// lowers for the robot (Figure 52 for MoRo, Figure 20 for Workpartner), with the
/// example skills.
const LIVE_TASKS: &[&str] = &["examples/short_task.ilmr", "examples/fetch_boxes.ilmr"];

pub fn live_module(robot: &str) -> Module {
    static LIVE: OnceLock<Vec<Module>> = OnceLock::new();
    let modules = LIVE.get_or_init(|| {
        ROBOTS
            .iter()
            .map(|r| {
                let m = model(r);
                LIVE_TASKS
                    .iter()
                    .find_map(|path| {
                        let text = std::fs::read_to_string(root().join(path)).ok()?;
                        let mut sources = vec![Source::new(*path, text)];
                        sources.extend(library().iter().cloned());
                        pipeline::compile(&sources, &m).filter(|m| !m.code.is_empty())
                    })
                    .unwrap_or_else(|| panic!("no example task lowers for {r}"))
            })
            .collect()
    });
    let i = ROBOTS.iter().position(|r| *r == robot).unwrap_or(0);
    modules[i].clone()
}

//! World files, as `ilmrc run --world FILE` reads them: the loader and its validation,
//! and, for a world it accepts, the scene built from it and a simulated MoRo running
//! Figure 52 in it under the VM, as `run` sets them up. A world the loader accepts
//! must be one the simulator can run, unless its start puts MoRo's footprint into
//! something (the simulator refuses that with the contact, and `run` says so); one the
//! loader refuses gets its line and what is wrong.

use std::sync::OnceLock;

use ilmr_compiler::check::Source;
use ilmr_model::RobotModel;
use ilmr_sim::{SimError, SimRobot, World};

use super::{corpus, models};
use crate::engine::{self, Budget, Rng, Stats};
use crate::{mutate, pipeline};

/// The shipped worlds and the simulator's test worlds.
pub fn seeds() -> Vec<Vec<u8>> {
    engine::files("robots/worlds", &["toml"])
        .into_iter()
        .chain(engine::files("robots/sim/tests/worlds", &["toml"]))
        .map(|(_, bytes)| bytes)
        .collect()
}

/// Keys, tables and values of the world format.
pub fn dictionary() -> Vec<String> {
    let words: Vec<String> = [
        "[[wall]]",
        "[[door]]",
        "[[obstacle]]",
        "[[pickup_box]]",
        "[[target]]",
        "[charger]",
        "[[plate]]",
        "[[fault]]",
        "name = ",
        "description = ",
        "bounds = { min = [-1.0, -1.0], max = [20.0, 15.0] }",
        "start = { x = 2.0, y = 1.2, heading = 0.0 }",
        "id = ",
        "from = [0.0, 0.0]",
        "to = [16.0, 0.0]",
        "thickness = ",
        "wall = ",
        "at = ",
        "width = ",
        "shape = \"circle\"",
        "shape = \"box\"",
        "center = [3.0, 1.0]",
        "radius = ",
        "size = [0.4, 0.3]",
        "heading = ",
        "colour = \"yellow\"",
        "position = [5.0, 5.0]",
        "speed = ",
        "waypoints = [[1.0, 1.0], [4.0, 1.0]]",
        "path = \"loop\"",
        "path = \"once\"",
        "[",
        "]",
        "{",
        "}",
        "=",
        ",",
        "\"",
    ]
    .iter()
    .map(|w| w.to_string())
    .collect();
    mutate::with_numbers_and_spacing(words)
}

/// The target, shared by this loop and the AFL++ binary (`fuzz/src/bin/world.rs`).
pub fn feed(input: &[u8]) {
    // `ilmr_files::read_text` refuses other bytes before the loader sees them.
    let Ok(text) = std::str::from_utf8(input) else {
        return;
    };
    match World::from_toml(text, "fuzz.toml") {
        Ok(world) => {
            let _ = world.scene();
            match SimRobot::moro(world.clone(), 1) {
                Ok(_) => {}
                Err(SimError::StartInCollision(_)) => return,
                Err(e) => panic!("an accepted world the simulator refuses: {e}"),
            }
            let (module, model) = figure_52();
            models::simulate(module.clone(), model, &world);
        }
        Err(e) => {
            assert!(!e.message.is_empty(), "an error says why: {e:?}");
            // The end of a file that ends in a newline is the line after its last.
            let lines = text.matches('\n').count() + 1;
            assert!(
                e.line <= lines,
                "line {} of a file of {lines} lines: {e:?}",
                e.line,
            );
        }
    }
}

/// Figure 52 lowered for MoRo, once (under AFL++, before the fork server forks).
fn figure_52() -> &'static (ilmr_vm::Module, RobotModel) {
    static TASK: OnceLock<(ilmr_vm::Module, RobotModel)> = OnceLock::new();
    TASK.get_or_init(|| {
        let model = corpus::model("moro");
        let text = std::fs::read_to_string(engine::root().join("examples/short_task.ilmr"))
            .expect("examples/short_task.ilmr is read");
        let mut sources = vec![Source::new("short_task.ilmr", text)];
        sources.extend(corpus::library().iter().cloned());
        let module = pipeline::compile(&sources, &model).expect("Figure 52 lowers for MoRo");
        (module, model)
    })
}

/// Lowers the task before the first input (under AFL++, before the fork server forks).
pub fn load() {
    figure_52();
}

pub fn fuzz(budget: Budget) -> Stats {
    load();
    let corpus = seeds();
    let words = dictionary();
    engine::run(
        "world",
        &corpus,
        budget,
        |base, rng: &mut Rng| mutate::text(base, rng, &corpus, &words),
        feed,
    )
}

//! ROBO.INI text through the model loader, its writer, the checker (every example
//! task against the fuzzed model), the lowering, and a simulated robot built from
//! the model with the VM configured from it, as `ilmrc run --robot FILE.ini` does.

use ilmr_compiler::check::Source;
use ilmr_model::RobotModel;
use ilmr_sim::{RobotKind, SimRobot, World};
use ilmr_vm::{Config, SimClock, TraceLevel, Vm};

use super::corpus;
use crate::engine::{self, Budget, Stats};
use crate::{mutate, pipeline};

/// The example tasks each fuzzed model is checked with (the first lines of each, to
/// keep an iteration short).
const TASKS: &[&str] = &[
    "examples/short_task.ilmr",
    "examples/fetch_boxes.ilmr",
    "tests/check/dissertation/action_commands.ilmr",
    "tests/check/dissertation/define_commands.ilmr",
    "tests/check/dissertation/movement_commands.ilmr",
];

const TICKS: u32 = 20;

/// The target, shared by this loop and the AFL++ binary (`fuzz/src/bin/model.rs`).
pub struct Models {
    tasks: Vec<String>,
    world: World,
}

impl Models {
    pub fn load() -> Models {
        let tasks = TASKS
            .iter()
            .map(|p| std::fs::read_to_string(engine::root().join(p)).unwrap_or_default())
            .collect();
        let world = match ilmr_sim::world::shipped("empty") {
            Some(Ok(w)) => w,
            _ => panic!("the empty world is shipped"),
        };
        // Parsed once, before the first input (under AFL++, before the fork server forks).
        corpus::library();
        Models { tasks, world }
    }

    pub fn feed(&self, input: &[u8]) {
        let text = String::from_utf8_lossy(input);
        let (model, warnings) = RobotModel::parse(&text, "fuzz");
        for w in &warnings {
            assert!(!w.message.is_empty(), "a warning says what was wrong");
        }
        writes_back(&model);
        for task in &self.tasks {
            let mut sources = vec![Source::new("task.ilmr", task.as_str())];
            sources.extend(corpus::library().iter().cloned());
            if let Some(module) = pipeline::compile(&sources, &model) {
                simulate(module, &model, &self.world);
            }
        }
    }
}

pub fn fuzz(budget: Budget) -> Stats {
    let corpus = corpus::ini_files();
    let dictionary = mutate::ini_dictionary();
    let target = Models::load();
    engine::run(
        "model",
        &corpus,
        budget,
        |base, rng| mutate::text(base, rng, &corpus, &dictionary),
        |input| target.feed(input),
    )
}

/// `to_ini` promises that parsing its text gives the same entries back.
fn writes_back(model: &RobotModel) {
    let text = model.to_ini();
    let (again, _) = RobotModel::parse(&text, &model.name);
    assert_eq!(
        entries(&again),
        entries(model),
        "to_ini does not read back:\n{text}"
    );
}

/// The model's entries without line numbers or source, as comparable JSON (so that a
/// NaN compares equal to itself).
fn entries(model: &RobotModel) -> serde_json::Value {
    let mut m = model.clone();
    m.source = None;
    m.devices.iter_mut().for_each(|d| d.line = 0);
    m.objects.iter_mut().for_each(|o| o.line = 0);
    for list in [&mut m.colors, &mut m.identifiers, &mut m.parameters] {
        list.iter_mut().for_each(|v| v.line = 0);
    }
    serde_json::to_value(&m).unwrap_or_default()
}

/// The simulated body and the VM as `ilmrc run` sets them up from a model
/// (`Config::for_robot`, as `src/run/setup.rs` calls it).
pub fn simulate(module: ilmr_vm::Module, model: &RobotModel, world: &World) {
    let kind = if model.nav_rate().is_some() {
        RobotKind::Workpartner
    } else {
        RobotKind::Moro
    };
    let Ok(robot) = SimRobot::new(model.clone(), kind, world.clone(), 1) else {
        return;
    };
    let body = robot.sim().config().offsets();
    let config = Config {
        budget_ops: 500,
        trace: TraceLevel::Commands,
        ..Config::for_robot(model, Some(body))
    };
    let Ok(mut vm) = Vm::new(module, robot, SimClock, config) else {
        panic!("Vm::new refused a lowered module");
    };
    for _ in 0..TICKS {
        vm.tick();
    }
}

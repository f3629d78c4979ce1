//! Issue 7's soak test: random valid tasks (from the catalogue's grammars, see
//! `support/taskgen.rs`) run on both simulated robots while random faults are
//! injected, and no run may panic, touch a wall or an obstacle, drive faster
//! than the model's top speed, or change its speed setpoint faster than the
//! model's acceleration and deceleration. The figures it prints are the ones
//! in docs/reliability.md.
//!
//! `ILMR_SOAK_RUNS=N` sets the number of runs (default below), `ILMR_SOAK_SEED=S`
//! the first seed: `ILMR_SOAK_RUNS=20000 cargo test --release --test soak -- --nocapture`
//! soaks for longer.

mod support;

use std::panic::{AssertUnwindSafe, catch_unwind};

use ilmr_compiler::FileId;
use ilmr_compiler::check::{Source, analyze};
use ilmr_compiler::lower::lower;
use ilmr_hal::Recorded;
use ilmr_model::RobotModel;
use ilmr_sim::faults::random_plan;
use ilmr_sim::{RobotKind, SimRobot, World};
use ilmr_vm::{SimClock, TraceLevel, Vm};
use support::taskgen::{Generator, Shape};

/// Runs in CI: enough to meet every fault kind on both robots many times, in
/// about a minute of a debug build on two cores.
const DEFAULT_RUNS: u64 = 2_000;
/// Simulated seconds a run may take; generated tasks are short.
const MAX_TIME: f64 = 12.0;
/// Faults per run, spread over its first `MAX_TIME` seconds.
const FAULTS: usize = 2;

struct Robot {
    name: &'static str,
    kind: RobotKind,
    model: RobotModel,
    world: World,
    generator: Generator,
}

impl Robot {
    fn new(name: &'static str, kind: RobotKind, world: &str) -> Robot {
        let model = RobotModel::builtin(name).expect("the model ships");
        let world = ilmr_sim::world::shipped(world)
            .expect("the world ships")
            .expect("the world is valid");
        let shape = Shape {
            origin: (world.start.x, world.start.y),
            // Searches run until they find something; a soak run must end.
            searches: false,
            max_wait: 1.5,
            ..Shape::default()
        };
        let generator = Generator::new(&[&model], shape);
        Robot {
            name,
            kind,
            model,
            world,
            generator,
        }
    }
}

#[derive(Debug, Default)]
struct Tally {
    runs: u64,
    faults: u64,
    finished: u64,
    ticks: u64,
    refused: u64,
    supervisor_events: u64,
    failures: Vec<String>,
}

/// One run: the task of `seed` on `robot` with random faults. Returns what
/// went wrong, if anything.
fn run(robot: &Robot, seed: u64, tally: &mut Tally) -> Result<(), String> {
    let task = robot.generator.generate(seed);
    let mut sources = vec![Source::new("soak.ilmr", &task.task)];
    if let Some(skills) = &task.skills {
        sources.push(Source::library("soak.ilms", skills));
    }
    let analysis = analyze(&sources, &robot.model);
    let module = lower(&analysis, &robot.model, FileId(0))
        .map_err(|d| format!("a generated task does not compile: {d:?}\n{}", task.task))?;
    let mut world = robot.world.clone();
    world.faults = random_plan(seed, MAX_TIME, FAULTS, robot.kind);
    tally.faults += world.faults.len() as u64;
    let faults: Vec<String> = world.faults.iter().map(|f| format!("{f:?}")).collect();
    let context = |why: String| {
        format!(
            "{why}\n  faults: {}\n  task:\n{}",
            faults.join(" "),
            task.task
        )
    };
    drive(robot, seed, world, module, tally).map_err(context)
}

fn drive(
    robot: &Robot,
    seed: u64,
    world: World,
    module: ilmr_vm::Module,
    tally: &mut Tally,
) -> Result<(), String> {
    let sim = match robot.kind {
        RobotKind::Moro => SimRobot::moro(world, seed),
        RobotKind::Workpartner => SimRobot::workpartner(world, seed),
    }
    .map_err(|e| format!("the robot does not start: {e}"))?;
    let mut config = ilmr_vm::Config::for_robot(&robot.model, Some(sim.sim().config().offsets()));
    config.trace = TraceLevel::Commands;
    let max_speed = config.safety.max_speed;
    let mut vm = Vm::new(module, Recorded::new(sim), SimClock, config)
        .map_err(|e| format!("the VM refuses a lowered module: {e}"))?;
    let ticks = (MAX_TIME / config.period).round() as u64;
    for _ in 0..ticks {
        // Done when the task is and the robot stands: a robot still rolling
        // after its task has ended is watched on.
        if vm.finished() && vm.hal().inner.sim().true_speed().abs() < 1e-3 {
            tally.finished += 1;
            break;
        }
        vm.tick();
        tally.ticks += 1;
        let sim = vm.hal().inner.sim();
        if sim.contact_count() > 0 {
            let trace = ilmr_vm::to_jsonl(vm.module(), vm.events());
            let tail: Vec<&str> = trace.lines().rev().take(12).collect();
            return Err(format!(
                "contact at t = {:.2} s, true pose {:?}; the trace ends:\n{}",
                sim.time(),
                sim.true_pose(),
                tail.into_iter().rev().collect::<Vec<_>>().join("\n")
            ));
        }
    }
    if let Some(&(t, v)) = vm
        .hal()
        .setpoints()
        .iter()
        .find(|(_, v)| v.abs() > max_speed + 1e-9)
    {
        return Err(format!(
            "speed setpoint {v} m/s beyond {max_speed} at t = {t:.2} s"
        ));
    }
    if let Some(jump) = vm
        .hal()
        .first_jump(config.period, config.acceleration, config.deceleration)
    {
        return Err(jump);
    }
    for e in vm.events() {
        match &e.kind {
            ilmr_vm::EventKind::Fault { .. } => tally.supervisor_events += 1,
            ilmr_vm::EventKind::End {
                how: ilmr_vm::How::Refused,
                ..
            } => tally.refused += 1,
            _ => {}
        }
    }
    Ok(())
}

fn env_u64(name: &str, default: u64) -> u64 {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

/// Each robot soaks in its own test, so that the two run on two cores.
#[test]
fn random_tasks_on_moro_with_random_faults_never_collide_panic_or_jump() {
    soak(&Robot::new("moro", RobotKind::Moro, "office"));
}

#[test]
fn random_tasks_on_workpartner_with_random_faults_never_collide_panic_or_jump() {
    soak(&Robot::new("workpartner", RobotKind::Workpartner, "yard"));
}

fn soak(robot: &Robot) {
    let runs = env_u64("ILMR_SOAK_RUNS", DEFAULT_RUNS) / 2;
    let first = env_u64("ILMR_SOAK_SEED", 1);
    let mut tally = Tally::default();
    let mut panics = 0;
    for seed in first..first + runs {
        tally.runs += 1;
        let outcome = catch_unwind(AssertUnwindSafe(|| run(robot, seed, &mut tally)));
        let failure = match outcome {
            Ok(Ok(())) => continue,
            Ok(Err(why)) => why,
            Err(panic) => {
                panics += 1;
                panic
                    .downcast_ref::<String>()
                    .cloned()
                    .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()))
                    .unwrap_or_else(|| "a panic".into())
            }
        };
        tally
            .failures
            .push(format!("seed {seed} on {}: {failure}", robot.name));
    }
    println!(
        "soak on {}: {} runs, {} faults injected, {} finished within {MAX_TIME} s, {} ticks, \
         {} commands refused, {} supervisor faults raised, {} failures ({panics} panics)",
        robot.name,
        tally.runs,
        tally.faults,
        tally.finished,
        tally.ticks,
        tally.refused,
        tally.supervisor_events,
        tally.failures.len()
    );
    assert!(
        tally.failures.is_empty(),
        "{} of {} runs failed:\n{}",
        tally.failures.len(),
        tally.runs,
        tally.failures.join("\n")
    );
    // The soak must have exercised what it claims to.
    if runs >= 100 {
        assert!(tally.faults >= runs);
        assert!(tally.supervisor_events > 0 && tally.refused > 0);
    }
}

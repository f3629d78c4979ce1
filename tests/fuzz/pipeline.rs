//! What `ilmrc check`, `build` and `run` do with a program, in process: check, render
//! the diagnostics both ways, lower, encode and decode the module, run it a little.
//! Each step asserts the invariant the next one relies on.

use ilmr_compiler::check::{Source, analyze};
use ilmr_compiler::lower::{LineOptions, lower, lower_line_into};
use ilmr_compiler::render::{self, RenderFile, Style};
use ilmr_compiler::{Diagnostic, FileId};
use ilmr_hal::{Limits, ScriptedRobot};
use ilmr_model::RobotModel;
use ilmr_vm::{Config, Module, SimClock, TraceLevel, Vm};

/// Ticks a fuzzed program runs for: enough to issue every block and step the
/// movement a few times, cheap enough for thousands of inputs.
pub const TICKS: u32 = 40;

/// Checks `sources` (the task is file 0) against `model`, renders the diagnostics,
/// and lowers the task when it has no errors. A lowered module must validate and
/// survive its own encoding.
pub fn compile(sources: &[Source], model: &RobotModel) -> Option<Module> {
    let analysis = analyze(sources, model);
    let files: Vec<RenderFile<'_>> = analysis
        .files
        .iter()
        .map(|f| RenderFile {
            path: f.path,
            text: f.text,
        })
        .collect();
    for d in &analysis.diagnostics {
        spans_inside(d, &files);
    }
    let human = render::human(&analysis.diagnostics, &files, Style::PLAIN);
    assert_eq!(
        human.is_empty(),
        analysis.diagnostics.is_empty(),
        "every diagnostic is rendered"
    );
    let json = render::json(&analysis.diagnostics, &files);
    assert_eq!(json.len(), analysis.diagnostics.len());
    assert!(serde_json::to_string(&json).is_ok());
    let module = match lower(&analysis, model, FileId(0)) {
        Ok(m) => m,
        Err(problems) => {
            assert!(
                problems.iter().any(Diagnostic::is_error),
                "a refused lowering says why"
            );
            return None;
        }
    };
    assert!(!analysis.has_errors(), "a program with errors was lowered");
    if let Err(e) = module.validate() {
        panic!("the lowering produced an invalid module: {e}");
    }
    let bytes = module.to_bytes();
    match Module::from_bytes(&bytes) {
        Ok(back) => assert_eq!(back.code, module.code, "the encoding keeps the code"),
        Err(e) => panic!("a lowered module does not load back: {e}"),
    }
    Some(module)
}

fn spans_inside(d: &Diagnostic, files: &[RenderFile<'_>]) {
    let Some(file) = files.get(d.file.0 as usize) else {
        panic!("{d:?} names a file the analysis does not have");
    };
    assert!(
        file.text.get(d.span.range()).is_some(),
        "{d:?} lies outside its file or splits a character"
    );
}

/// A VM on a scripted robot with a small tick budget, so that a loop of arithmetic
/// costs a fuzzing iteration microseconds, not the 200 000 operations of a real tick.
pub fn vm(module: Module) -> Option<Vm<ScriptedRobot, SimClock>> {
    let config = Config {
        budget_ops: 500,
        trace: TraceLevel::Full,
        ..Config::default()
    };
    Vm::new(
        module,
        ScriptedRobot::new(Limits::default()),
        SimClock,
        config,
    )
    .ok()
}

/// Runs a module for [`TICKS`] ticks, then offers `line` as an interactive line
/// (what `ilmrc serve` and a run scenario do) and runs on.
pub fn run(module: Module, model: &RobotModel, line: Option<&str>) {
    let Some(mut vm) = vm(module) else {
        panic!("Vm::new refused a module that validated");
    };
    for _ in 0..TICKS {
        vm.tick();
    }
    if let Some(text) = line {
        let _ = vm.add_line(|b| lower_line_into(text, b, model, LineOptions::default()));
        for _ in 0..TICKS / 2 {
            vm.tick();
        }
    }
    trace_is_json(&mut vm);
}

/// Every event renders to one JSON line: what the trace file and `serve` send.
pub fn trace_is_json(vm: &mut Vm<ScriptedRobot, SimClock>) {
    let events = vm.take_events();
    let trace = ilmr_vm::to_jsonl(vm.module(), &events);
    for line in trace.lines() {
        if let Err(e) = serde_json::from_str::<serde_json::Value>(line) {
            panic!("a trace line is not JSON ({e}): {line}");
        }
    }
}

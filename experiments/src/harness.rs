//! What every experiment is built from: the VM configured as `ilmrc run` configures it
//! for a simulated robot, tasks compiled from the repository's examples or assembled
//! statement by statement over the VM's `ModuleBuilder`, runs that record the true
//! path, and the measures taken on them. `ilmr-sim`'s own tests use it too.

use std::path::{Path, PathBuf};

use ilmr_model::RobotModel;
use ilmr_sim::{SimRobot, World};
use ilmr_stdlib::{Command, VarKind};
use ilmr_vm::bytecode::{Arg, FileId, Instr, Op};
use ilmr_vm::{Config, Module, ModuleBuilder, SimClock, TraceLevel, Vm};

/// The VM configured as `ilmrc run` configures it for a simulated robot,
/// tracing everything and the pose every 10 ticks.
pub fn vm_config(model: &RobotModel, sim: &ilmr_sim::RobotConfig) -> Config {
    Config {
        trace: TraceLevel::Full,
        pose_every: 10,
        ..Config::for_robot(model, Some(sim.offsets()))
    }
}

pub type SimVm = Vm<SimRobot, SimClock>;

/// The repository's root.
pub fn repo() -> PathBuf {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    root.canonicalize().unwrap_or(root)
}

/// The repository's `examples/` directory.
pub fn examples() -> PathBuf {
    repo().join("examples")
}

/// Where the worlds of tests 2-4, 6 and 7 are (`ilmr-sim`'s test worlds).
pub fn worlds() -> PathBuf {
    repo().join("robots/sim/tests/worlds")
}

fn read(path: &Path) -> Result<String, String> {
    std::fs::read_to_string(path).map_err(|e| format!("cannot read `{}`: {e}", path.display()))
}

/// An example task file compiled for `model` as `ilmrc run` compiles it,
/// with every skill file of `examples/skills` as its library.
pub fn compile_example(file: &str, model: &RobotModel) -> Result<Module, String> {
    let text = read(&examples().join(file))?;
    compile(&format!("examples/{file}"), &text, model)
}

/// ILMR source compiled for `model`, with `examples/skills` as its library.
pub fn compile(name: &str, text: &str, model: &RobotModel) -> Result<Module, String> {
    compile_with(name, text, "skills", model)
}

/// ILMR source compiled for `model` with every skill file of `examples/<skills>` as
/// its library, as `ilmrc run --skills examples/<skills>` compiles it (a robot's own
/// skills: MoRo's `Takebox` is in `examples/skills_moro`).
pub fn compile_with(
    name: &str,
    text: &str,
    skills: &str,
    model: &RobotModel,
) -> Result<Module, String> {
    use ilmr_compiler::check::{Source, analyze};
    let dir = examples().join(skills);
    let mut sources = vec![Source::new(name, text)];
    let mut files = Vec::new();
    for entry in
        std::fs::read_dir(&dir).map_err(|e| format!("cannot list `{}`: {e}", dir.display()))?
    {
        files.push(
            entry
                .map_err(|e| format!("cannot list `{}`: {e}", dir.display()))?
                .path(),
        );
    }
    files.sort();
    for p in files {
        let file = p
            .file_name()
            .unwrap_or_default()
            .to_string_lossy()
            .into_owned();
        sources.push(Source::library(
            format!("examples/{skills}/{file}"),
            read(&p)?,
        ));
    }
    let analysis = analyze(&sources, model);
    ilmr_compiler::lower::lower(&analysis, model, ilmr_compiler::FileId(0))
        .map_err(|d| format!("{name} does not compile: {d:?}"))
}

/// A world of `worlds()` by file name.
pub fn world(file: &str) -> Result<World, String> {
    let path = worlds().join(file);
    World::from_path(&path).map_err(|e| format!("world `{}`: {e}", path.display()))
}

/// A world shipped with `ilmr-sim` (`empty`, `office`, `yard`).
pub fn shipped(name: &str) -> Result<World, String> {
    match ilmr_sim::world::shipped(name) {
        Some(w) => w.map_err(|e| format!("shipped world `{name}`: {e}")),
        None => Err(format!("no shipped world `{name}`")),
    }
}

pub fn moro(world: World, seed: u64) -> Result<SimRobot, String> {
    SimRobot::moro(world, seed).map_err(|e| format!("MoRo does not start: {e}"))
}

/// MoRo with its shipped model and `profile`'s errors.
pub fn moro_with(
    world: World,
    seed: u64,
    profile: ilmr_sim::SimProfile,
) -> Result<SimRobot, String> {
    let model = RobotModel::builtin("moro").ok_or("no built-in model moro")?;
    SimRobot::with_profile(model, ilmr_sim::RobotKind::Moro, profile, world, seed)
        .map_err(|e| format!("MoRo does not start: {e}"))
}

pub fn workpartner(world: World, seed: u64) -> Result<SimRobot, String> {
    SimRobot::workpartner(world, seed).map_err(|e| format!("Workpartner does not start: {e}"))
}

/// Workpartner with its shipped model and `profile`'s errors.
pub fn workpartner_with(
    world: World,
    seed: u64,
    profile: ilmr_sim::SimProfile,
) -> Result<SimRobot, String> {
    let model = RobotModel::builtin("workpartner").ok_or("no built-in model workpartner")?;
    SimRobot::with_profile(
        model,
        ilmr_sim::RobotKind::Workpartner,
        profile,
        world,
        seed,
    )
    .map_err(|e| format!("Workpartner does not start: {e}"))
}

pub fn vm(module: Module, robot: SimRobot) -> Result<SimVm, String> {
    vm_with(module, robot, ilmr_vm::Controller::PROJECT)
}

/// As [`vm`], with the position controller's `controller` variant.
pub fn vm_with(
    module: Module,
    robot: SimRobot,
    controller: ilmr_vm::Controller,
) -> Result<SimVm, String> {
    let cfg = Config {
        controller,
        ..vm_config(robot.model(), robot.sim().config())
    };
    Vm::new(module, robot, SimClock, cfg).map_err(|e| format!("the VM refuses the task: {e:?}"))
}

/// An argument as written in ILMR.
#[derive(Clone, Copy)]
pub enum A<'a> {
    N(f64),
    W(&'a str),
    S(&'a str, f64),
    V(&'a str),
}

/// A task assembled statement by statement, one line each.
///
/// The tasks are the experiments' own few fixed lines, far inside the builder's
/// limits, so a builder error is a mistake in an experiment and panics.
pub struct Task {
    b: ModuleBuilder,
    file: FileId,
    line: u32,
    offset: u32,
    code: Vec<Instr>,
}

impl Default for Task {
    fn default() -> Task {
        Task::new()
    }
}

impl Task {
    pub fn new() -> Task {
        let mut b = ModuleBuilder::new();
        let file = b.file("experiment.ilmr").expect("file");
        Task {
            b,
            file,
            line: 0,
            offset: 0,
            code: Vec::new(),
        }
    }

    fn stmt(&mut self, text: &str) -> ilmr_vm::bytecode::StmtId {
        self.line += 1;
        let start = self.offset;
        self.offset += text.len() as u32 + 1;
        self.b
            .stmt(
                self.file,
                self.line,
                (start, start + text.len() as u32),
                text,
            )
            .expect("stmt")
    }

    /// A command; `bind` names the variable it is bound to.
    pub fn cmd(mut self, text: &str, command: Command, args: &[A], bind: Option<&str>) -> Task {
        let stmt = self.stmt(text);
        let mut list = Vec::new();
        for a in args {
            list.push(match *a {
                A::N(n) => Arg::Num(self.b.num(n).expect("num")),
                A::W(w) => Arg::Word(self.b.name(w).expect("name")),
                A::S(k, v) => Arg::Setting {
                    key: self.b.name(k).expect("name"),
                    value: self.b.num(v).expect("num"),
                },
                A::V(name) => {
                    Arg::Var(self.b.find_global(name).expect("variable bound before use"))
                }
            });
        }
        let args = self.b.args(&list).expect("args");
        let bind = bind.map(|name| {
            let kind = command
                .spec()
                .forms
                .first()
                .map_or(VarKind::Status, |f| f.produces);
            self.b.global(name, kind).expect("one kind per variable")
        });
        self.code.push(Instr::new(
            Op::Issue {
                command,
                args,
                bind,
            },
            stmt,
        ));
        self
    }

    pub fn wait_var(mut self, text: &str, var: &str) -> Task {
        let stmt = self.stmt(text);
        let var = self.b.find_global(var).expect("bound variable");
        self.code
            .push(Instr::new(Op::WaitVar { var, bind: None }, stmt));
        self
    }

    /// The task as one top-level block.
    pub fn finish(mut self) -> Module {
        let block = self.b.block(&self.code).expect("block");
        let main = self.b.declare_unit("task", false).expect("unit");
        self.b.define_unit(main, &[block]);
        self.b.set_main(main);
        self.b.finish().expect("valid module")
    }
}

pub fn speed(t: Task, v: f64) -> Task {
    t.cmd(&format!("speed({v})"), Command::Speed, &[A::N(v)], None)
}

/// The true pose, speed and curvature after every tick of a run, and whether the
/// task ended.
pub struct Run {
    pub trace: Vec<ilmr_hal::Pose>,
    pub speeds: Vec<f64>,
    pub curvatures: Vec<f64>,
    pub finished: bool,
}

/// Ticks until the task ends or `seconds` pass.
pub fn run(vm: &mut SimVm, seconds: f64) -> Run {
    run_watched(vm, seconds, |_| {})
}

/// As [`run`], showing the VM to `watch` after every tick (to collect marks and
/// scans for a picture).
pub fn run_watched(vm: &mut SimVm, seconds: f64, watch: impl FnMut(&SimVm)) -> Run {
    run_until(vm, seconds, |vm| vm.finished(), watch)
}

/// As [`run_watched`], but the run also ends as `ilmrc run` ends it: when nothing is
/// left but `if` guards with the robot at rest (a task that watches its battery to
/// the end never finishes otherwise). `finished` says it ended either way.
pub fn run_to_rest(vm: &mut SimVm, seconds: f64, watch: impl FnMut(&SimVm)) -> Run {
    run_until(
        vm,
        seconds,
        |vm| vm.finished() || vm.only_guards_waiting(),
        watch,
    )
}

fn run_until(
    vm: &mut SimVm,
    seconds: f64,
    ended: impl Fn(&SimVm) -> bool,
    mut watch: impl FnMut(&SimVm),
) -> Run {
    let mut out = Run {
        trace: Vec::new(),
        speeds: Vec::new(),
        curvatures: Vec::new(),
        finished: false,
    };
    let ticks = (seconds / vm.config().period).round() as u64;
    for _ in 0..ticks {
        if ended(vm) {
            out.finished = true;
            break;
        }
        tick(vm);
        out.trace.push(vm.hal().true_pose());
        out.speeds.push(vm.hal().sim().true_speed());
        out.curvatures.push(vm.hal().sim().true_curvature());
        watch(vm);
    }
    out.finished |= ended(vm);
    out
}

/// One tick of the VM, counted towards the simulated time [`crate::cost`] reports.
pub fn tick(vm: &mut SimVm) {
    vm.tick();
    crate::cost::ticked(vm.config().period);
}

/// `how` of the end event of the statement with `text`.
pub fn ended(vm: &SimVm, text: &str) -> Option<String> {
    vm.events().iter().find_map(|e| {
        let s = e.stmt.and_then(|s| vm.module().stmt(s))?;
        match &e.kind {
            ilmr_vm::EventKind::End { how, .. } if s.text == text => Some(how.name().to_string()),
            _ => None,
        }
    })
}

pub fn linked_ends(vm: &SimVm) -> usize {
    vm.events()
        .iter()
        .filter(|e| matches!(e.kind, ilmr_vm::EventKind::End { linked: true, .. }))
        .count()
}

/// Mean, and sample standard deviation.
pub fn mean_std(xs: &[f64]) -> (f64, f64) {
    let n = xs.len() as f64;
    let mean = xs.iter().sum::<f64>() / n;
    let var = xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0).max(1.0);
    (mean, var.sqrt())
}

/// Length of a driven trace, metres.
pub fn length(trace: &[ilmr_hal::Pose]) -> f64 {
    trace
        .windows(2)
        .map(|w| (w[1].x - w[0].x).hypot(w[1].y - w[0].y))
        .sum()
}

/// Distance from `p` to the nearest leg of the polyline `pts`.
pub fn distance_to_polyline(pts: &[(f64, f64)], p: (f64, f64)) -> f64 {
    pts.windows(2)
        .map(|w| ilmr_hal::segment_distance(p, w[0], w[1]))
        .fold(f64::INFINITY, f64::min)
}

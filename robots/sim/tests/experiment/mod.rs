//! Shared by the experiment tests (the VM on `SimRobot`): the VM configured from a robot model,
//! a small assembler of tasks over the VM's `ModuleBuilder`, and traces.
#![allow(dead_code)]

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
        ..ilmr_sim::vm_config(model, Some(sim))
    }
}

pub type SimVm = Vm<SimRobot, SimClock>;

/// The repository's `examples/` directory.
pub fn examples() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

/// An example task file compiled for `model` as `ilmrc run` compiles it,
/// with every skill file of `examples/skills` as its library.
pub fn compile_example(file: &str, model: &RobotModel) -> Module {
    let text = std::fs::read_to_string(examples().join(file)).expect("example readable");
    compile(&format!("examples/{file}"), &text, model)
}

/// ILMR source compiled for `model`, with `examples/skills` as its library.
pub fn compile(name: &str, text: &str, model: &RobotModel) -> Module {
    use ilmr_compiler::check::{Source, analyze};
    let dir = examples().join("skills");
    let mut sources = vec![Source::new(name, text)];
    let mut skills: Vec<_> = std::fs::read_dir(&dir)
        .expect("examples/skills")
        .map(|e| e.expect("entry").path())
        .collect();
    skills.sort();
    for p in skills {
        let file = p.file_name().expect("file").to_string_lossy().into_owned();
        let text = std::fs::read_to_string(&p).expect("skill file readable");
        sources.push(Source::library(format!("examples/skills/{file}"), text));
    }
    let analysis = analyze(&sources, model);
    ilmr_compiler::lower::lower(&analysis, model, ilmr_compiler::FileId(0))
        .unwrap_or_else(|d| panic!("{name} does not compile: {d:?}"))
}

pub fn world(file: &str) -> World {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/worlds")
        .join(file);
    World::from_path(&path).expect("test world loads")
}

pub fn shipped(name: &str) -> World {
    ilmr_sim::world::shipped(name)
        .expect("shipped world exists")
        .expect("shipped world is valid")
}

pub fn moro(world: World, seed: u64) -> SimRobot {
    SimRobot::moro(world, seed).expect("robot starts free")
}

pub fn workpartner(world: World, seed: u64) -> SimRobot {
    SimRobot::workpartner(world, seed).expect("robot starts free")
}

pub fn vm(module: Module, robot: SimRobot) -> SimVm {
    let cfg = vm_config(robot.model(), robot.sim().config());
    Vm::new(module, robot, SimClock, cfg).expect("valid module")
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
pub struct Task {
    b: ModuleBuilder,
    file: FileId,
    line: u32,
    offset: u32,
    code: Vec<Instr>,
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

/// Ticks until the task ends or `seconds` pass, recording the true pose and
/// the drive's speed after every tick.
pub struct Run {
    pub trace: Vec<ilmr_hal::Pose>,
    pub speeds: Vec<f64>,
    pub finished: bool,
}

pub fn run(vm: &mut SimVm, seconds: f64) -> Run {
    let mut out = Run {
        trace: Vec::new(),
        speeds: Vec::new(),
        finished: false,
    };
    let ticks = (seconds / vm.config().period).round() as u64;
    for _ in 0..ticks {
        if vm.finished() {
            out.finished = true;
            break;
        }
        vm.tick();
        out.trace.push(vm.hal().true_pose());
        out.speeds.push(vm.hal().sim().true_speed());
    }
    out.finished |= vm.finished();
    out
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

pub fn mpose(p: ilmr_hal::Pose) -> ilmr_motion::Pose {
    ilmr_motion::Pose::new(p.x, p.y, p.h)
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

//! Shared by the experiment tests (the VM on `SimRobot`): the VM configured from a robot model,
//! a small assembler of tasks over the VM's `ModuleBuilder`, and traces.
#![allow(dead_code)]

use ilmr_model::RobotModel;
use ilmr_sim::{SimRobot, World};
use ilmr_stdlib::{Command, VarKind};
use ilmr_vm::bytecode::{Arg, FileId, Instr, Op};
use ilmr_vm::{Config, Module, ModuleBuilder, SimClock, TraceLevel, Vm};

/// The VM's physical tunables from a ROBO.INI model (what `ilmrc run` does
/// for a simulated or real robot).
pub fn vm_config(model: &RobotModel, sim: &ilmr_sim::RobotConfig) -> Config {
    Config {
        default_speed: model.default_speed(),
        max_curvature: model.max_curvature(),
        curinc: model.curinc(),
        // turn(left|right): a comfortable three quarters of full lock.
        turn_curvature: 0.75 * model.max_curvature(),
        acceleration: model.max_acceleration(),
        deceleration: model.max_deceleration(),
        robot_width: model.robot_width(),
        robot_length: model.robot_length(),
        front_offset: sim.body.length - sim.body.rear_overhang,
        scanner_offset: sim.scanner.mount.x,
        followwall_d: model.followwall_d(),
        obstacle_curvature: model.omax_curvature(),
        security_wait: model.bs_security(),
        trace: TraceLevel::Full,
        pose_every: 10,
        ..Config::default()
    }
}

pub type SimVm = Vm<SimRobot, SimClock>;

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

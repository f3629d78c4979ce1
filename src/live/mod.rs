//! A robot (simulated or ROS 2) running in real time on its own thread, driven by jobs: what
//! `ilmrc serve` (for planners over TCP) and `ilmrc shell` (for a person at a prompt)
//! both put in front of the dissertation's language process.

pub mod engine;
pub mod guard;
mod lines;
pub mod reply;
mod robot;
pub mod stop;

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::mpsc::{self, Sender};

use ilmr_compiler::FileId;
use ilmr_compiler::check::{Source, analyze};
use ilmr_model::RobotModel;
use ilmr_vm::{SimClock, Vm};

use crate::build::{Compiled, compile, render_diagnostics};
use engine::{Engine, Job};

/// The robot and task options `serve` and `shell` share.
#[derive(clap::Args, Debug)]
pub struct RobotArgs {
    /// The robot: `moro`, `workpartner` or a ROBO.INI path (simulated), or `ros2` (a
    /// ROS 2 robot over DDS, checked against `--model`).
    #[arg(long, default_value = "moro")]
    pub robot: String,
    /// With `--robot ros2`: the model the lines are checked against and whose limits
    /// bound the robot (default moro).
    #[arg(long)]
    pub model: Option<String>,
    /// The simulated robot's world: `office`, `yard`, `empty` or a world file (default:
    /// office for MoRo, yard for Workpartner).
    #[arg(long)]
    pub world: Option<String>,
    /// Where the simulated robot starts, `X,Y,HEADING` in metres and degrees (default:
    /// as `ilmrc run`).
    #[arg(long, allow_hyphen_values = true)]
    pub start: Option<String>,
    /// Seed of the simulated robot's noise.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// A directory of skill files (`*.ilms`) lines may call.
    #[arg(long)]
    pub skills: Option<PathBuf>,
    /// A task to start with (checked as `ilmrc check` does); without one the robot
    /// waits for lines.
    #[arg(long)]
    pub task: Option<PathBuf>,
    #[command(flatten)]
    pub ros2: crate::ros2::Ros2Args,
    #[command(flatten)]
    pub view: crate::view::live::FoxgloveArgs,
}

/// The longest line `serve` takes as one request and `shell` as one typed line, bytes;
/// a longer one is refused (`serve` closes the connection, `shell` skips to the next
/// line), so that a client cannot make either hold unbounded input.
pub const MAX_LINE_BYTES: usize = 1 << 20;

/// Statements lines may add to the running task, all lines together: every joined
/// line stays in the module for good (a running command may still point into it), so
/// past this (some 400 MB) lines are refused and the robot goes on with what it has.
pub const MAX_LINE_STATEMENTS: u32 = 1_000_000;
/// Bytes of text lines may join, all lines together, for the same reason (the module
/// keeps each statement's text, and the VM a lower-case copy).
pub const MAX_LINE_TEXT_BYTES: u64 = 128 << 20;

/// A robot whose VM runs on its own thread, with a second thread that compiles the
/// lines it is sent; both run for as long as the process does.
pub struct Live {
    /// The VM thread's queue.
    pub jobs: Sender<Job>,
    /// The emergency stop, which does not queue behind `jobs`.
    pub stop: Arc<stop::EmergencyStop>,
    pub model: RobotModel,
    /// The world's name or file.
    pub world: String,
}

/// Opens the robot, compiles the task (or an empty one) and starts the VM's thread;
/// `None` when the task has errors (they were printed).
pub fn start(args: &RobotArgs) -> Result<Option<Live>, String> {
    start_named(args, None)
}

/// As [`start`], for a robot of a fleet: `name` is put in every event it sends.
pub fn start_named(args: &RobotArgs, name: Option<&str>) -> Result<Option<Live>, String> {
    let opened = robot::open(args)?;
    let module = guard::on_compiler_stack("compiling the task", || match &args.task {
        Some(task) => compile(task, &opened.spec, args.skills.as_deref(), |_| Vec::new()),
        None => no_task(&opened.spec, args.skills.as_deref()),
    })??;
    let module = match module {
        Compiled::Module(m) => *m,
        Compiled::Rejected => return Ok(None),
    };
    let copy = module.clone();
    let vm = Vm::new(module, opened.robot, SimClock, opened.config).map_err(|e| e.to_string())?;
    let (jobs, queue) = mpsc::channel();
    let (work, to_compile) = mpsc::channel();
    let (news, heard) = mpsc::channel();
    let stop = Arc::new(stop::EmergencyStop::default());
    let library = match &args.skills {
        Some(dir) => crate::inputs::read_skill_dir(dir)?,
        None => Vec::new(),
    };
    let compiler = lines::Compiler::new(copy, opened.model.clone(), jobs.clone(), heard)
        .limited_to(MAX_LINE_STATEMENTS, MAX_LINE_TEXT_BYTES)
        .with_library(library);
    // The compiler's thread has the stack the compiler's nesting limits need; the
    // engine's too, for the one line it compiles itself (`stop`) and for lines when
    // it has no compiler (its unit tests).
    std::thread::Builder::new()
        .name("ilmr-lines".into())
        .stack_size(ilmr_compiler::limits::COMPILER_STACK)
        .spawn(move || compiler.run(to_compile))
        .map_err(|e| format!("cannot start the line compiler's thread: {e}"))?;
    let task = args
        .task
        .as_ref()
        .map_or_else(|| "<live>".to_string(), |t| t.display().to_string());
    let view = args.view.open(&task, opened.scene.as_ref())?;
    let engine = Engine::new(vm, opened.model.clone())
        .with_compiler(work, news, Arc::clone(&stop))
        .with_view(view);
    let engine = match name {
        Some(n) => engine.tagged(n),
        None => engine,
    };
    std::thread::Builder::new()
        .name("ilmr-vm".into())
        .stack_size(ilmr_compiler::limits::COMPILER_STACK)
        .spawn(move || engine.run(queue))
        .map_err(|e| format!("cannot start the robot's thread: {e}"))?;
    Ok(Some(Live {
        jobs,
        stop,
        model: opened.model,
        world: opened.world,
    }))
}

/// The module of an empty task, with the skills lines may call.
fn no_task(robot: &str, skills: Option<&Path>) -> Result<Compiled, String> {
    let model = crate::inputs::load_robot_model(robot)?;
    let mut sources = vec![Source::new("<live>", "")];
    if let Some(dir) = skills {
        sources.extend(crate::inputs::read_skill_dir(dir)?);
    }
    let analysis = analyze(&sources, &model);
    match ilmr_compiler::lower::lower(&analysis, &model, FileId(0)) {
        Ok(module) => Ok(Compiled::Module(Box::new(module))),
        Err(problems) => {
            print!("{}", render_diagnostics(&analysis, &problems));
            Ok(Compiled::Rejected)
        }
    }
}

/// The robots a server drives, by name: one, or the robots of a fleet.
pub struct Robots {
    members: Vec<(String, Live)>,
    /// A fleet's robots are addressed by name and name themselves in what they send.
    fleet: bool,
}

impl Robots {
    pub fn one(live: Live) -> Robots {
        Robots {
            members: vec![(String::new(), live)],
            fleet: false,
        }
    }

    pub fn fleet(members: Vec<(String, Live)>) -> Robots {
        Robots {
            members,
            fleet: true,
        }
    }

    pub fn is_fleet(&self) -> bool {
        self.fleet
    }

    pub fn names(&self) -> impl Iterator<Item = &str> {
        self.members.iter().map(|(n, _)| n.as_str())
    }

    pub fn all(&self) -> impl Iterator<Item = (&str, &Live)> {
        self.members.iter().map(|(n, l)| (n.as_str(), l))
    }

    /// The robot a request is for: the one named, or the only one.
    pub fn route(&self, name: Option<&str>) -> Result<&Live, String> {
        match (name, &self.members[..]) {
            (None, [(_, only)]) if !self.fleet => Ok(only),
            (Some(_), [_]) if !self.fleet => {
                Err("this server drives one robot: send requests without \"robot\"".into())
            }
            (None, _) => Err(format!(
                "this server drives a fleet: name the robot with \"robot\" ({})",
                self.listed()
            )),
            (Some(n), members) => members
                .iter()
                .find(|(m, _)| m == n)
                .map(|(_, l)| l)
                .ok_or_else(|| {
                    format!(
                        "no robot `{}` in this fleet ({})",
                        n.chars().take(64).collect::<String>(),
                        self.listed()
                    )
                }),
        }
    }

    /// Every robot's status, asked of all at once and waited for up to `wait` each:
    /// `Err` says why a robot gave none.
    pub fn statuses(
        &self,
        wait: std::time::Duration,
    ) -> Vec<(&str, Result<engine::Status, &'static str>)> {
        let asked: Vec<_> = self
            .all()
            .map(|(name, live)| {
                let (reply, answer) = mpsc::channel();
                let sent = live
                    .jobs
                    .send(Job::Status {
                        reply: reply.into(),
                    })
                    .is_ok();
                (name, sent.then_some(answer))
            })
            .collect();
        asked
            .into_iter()
            .map(|(name, answer)| {
                let status = match answer {
                    None => Err("the robot has stopped"),
                    Some(a) => a.recv_timeout(wait).map_err(|_| "the robot did not answer"),
                };
                (name, status)
            })
            .collect()
    }

    fn listed(&self) -> String {
        self.names().collect::<Vec<_>>().join(", ")
    }
}

//! Fleets: several robots driven at once, each with its own VM thread, simulated here
//! or a ROS 2 robot in its own namespace (docs/fleet.md). `ilmrc fleet FILE` starts
//! one, starting `ilmrc sim --ros2` for the robots that ask for it, and shows each
//! robot's state until every task has finished; `ilmrc serve --fleet FILE` serves one
//! to planners, who name the robot in each request.

pub mod file;

use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, ExitCode, Stdio};
use std::sync::Arc;
use std::sync::mpsc;
use std::time::{Duration, Instant};

use crate::live::engine::Status;
use crate::live::{RobotArgs, Robots};
use crate::ros2::Ros2Args;

/// How long a launched simulator may take to create its endpoints.
const LAUNCH_WAIT: Duration = Duration::from_secs(30);

#[derive(clap::Args)]
pub struct FleetArgs {
    /// The fleet file (TOML; docs/fleet.md).
    pub file: PathBuf,
    /// Also take planners' requests over TCP here, as `serve --fleet` does (a loopback
    /// address and port).
    #[arg(long)]
    pub listen: Option<String>,
    #[command(flatten)]
    pub security: crate::serve::SecurityArgs,
    /// Seconds between the robots' state tables on stdout.
    #[arg(long, default_value_t = 1.0)]
    pub every: f64,
    /// Stop after this many seconds.
    #[arg(long, default_value_t = 600.0)]
    pub max_time: f64,
    /// Keep the fleet running when every task has finished (for planners' requests).
    #[arg(long)]
    pub stay: bool,
}

/// A fleet's robots, and the simulators started for them (stopped when it is dropped).
pub struct Fleet {
    pub robots: Arc<Robots>,
    _launched: Launched,
}

/// One robot of a fleet: its name, `serve`'s options for it, and the simulator to
/// start for it.
struct Member {
    name: String,
    args: RobotArgs,
    launch: Option<file::Launch>,
}

impl Member {
    fn of(m: file::Member) -> Member {
        let ros2 = match m.ros2 {
            Some(r) => Ros2Args {
                ros_namespace: Some(r.namespace),
                ros_domain: r.domain,
                ros_wait: None,
                ros_loopback: r.loopback,
            },
            None => Ros2Args::default(),
        };
        Member {
            args: RobotArgs {
                robot: m.robot,
                model: m.model,
                world: m.world,
                start: m.start,
                seed: m.seed,
                skills: m.skills,
                task: m.task,
                ros2,
                view: Default::default(),
            },
            name: m.name,
            launch: m.launch,
        }
    }
}

/// Starts the simulators the file asks for, then every robot's VM; `None` when a task
/// has errors (they were printed).
pub fn open(path: &Path) -> Result<Option<Fleet>, String> {
    let members: Vec<Member> = file::load(path)?.into_iter().map(Member::of).collect();
    let launched = launch(&members)?;
    let mut lives = Vec::with_capacity(members.len());
    for m in &members {
        let started = crate::live::start_named(&m.args, Some(&m.name))
            .map_err(|e| format!("robot `{}`: {e}", m.name))?;
        match started {
            Some(live) => lives.push((m.name.clone(), live)),
            None => return Ok(None),
        }
    }
    Ok(Some(Fleet {
        robots: Arc::new(Robots::fleet(lives)),
        _launched: launched,
    }))
}

pub fn run(args: FleetArgs) -> ExitCode {
    match execute(&args) {
        Ok(code) => code,
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::from(crate::EXIT_USAGE)
        }
    }
}

fn execute(args: &FleetArgs) -> Result<ExitCode, String> {
    for (flag, v) in [("--every", args.every), ("--max-time", args.max_time)] {
        if !(v.is_finite() && v > 0.0) {
            return Err(format!("{flag} {v} is not a time"));
        }
    }
    let listener = match &args.listen {
        Some(a) => Some(crate::serve::listen(a, &args.security)?),
        None => None,
    };
    let Some(fleet) = open(&args.file)? else {
        return Ok(ExitCode::from(crate::EXIT_ERRORS));
    };
    if let Some((l, security)) = listener {
        let local = l.local_addr().map_err(|e| e.to_string())?;
        println!("listening on {local}");
        let robots = Arc::clone(&fleet.robots);
        std::thread::Builder::new()
            .name("ilmr-fleet-serve".into())
            .spawn(move || crate::serve::accept(&l, &robots, security))
            .map_err(|e| format!("cannot start serving: {e}"))?;
    }
    let start = Instant::now();
    let every = Duration::from_secs_f64(args.every);
    loop {
        std::thread::sleep(every);
        let statuses = fleet.robots.statuses(Duration::from_secs(10));
        let done = statuses.iter().all(|(_, s)| s.as_ref().is_ok_and(at_rest));
        let out_of_time = start.elapsed().as_secs_f64() >= args.max_time;
        print!("{}", table(&statuses));
        let _ = std::io::stdout().flush();
        if done && !args.stay {
            println!("fleet: every task has finished");
            return Ok(ExitCode::SUCCESS);
        }
        if out_of_time {
            println!("fleet: max-time: stopped at --max-time {}", args.max_time);
            return Ok(ExitCode::SUCCESS);
        }
    }
}

/// A task that has nothing left to do, on a robot that has stopped.
fn at_rest(s: &Status) -> bool {
    s.finished && s.speed.abs() < 1e-3
}

fn table(statuses: &[(&str, Result<Status, &str>)]) -> String {
    let mut out = String::from("robot        t s      x m     y m   h deg   v m/s  live  state\n");
    for (name, s) in statuses {
        match s {
            Ok(s) => out.push_str(&format!(
                "{name:<10} {:>5.1} {:>7.2} {:>7.2} {:>7.1} {:>7.2} {:>5}  {}\n",
                s.t,
                s.pose.x,
                s.pose.y,
                s.pose.h.to_degrees(),
                s.speed,
                s.live.len(),
                if at_rest(s) { "finished" } else { "running" }
            )),
            Err(why) => out.push_str(&format!("{name:<10} (no status: {why})\n")),
        }
    }
    out
}

/// Simulators started for a fleet: stopped, and waited for, when the fleet ends.
#[derive(Default)]
struct Launched(Vec<Child>);

impl Drop for Launched {
    fn drop(&mut self) {
        for child in &mut self.0 {
            let _ = child.kill();
            let _ = child.wait();
        }
    }
}

/// Starts `ilmrc sim --ros2` for every robot that asks for it, and waits until each
/// has its endpoints.
fn launch(members: &[Member]) -> Result<Launched, String> {
    let exe = std::env::current_exe().map_err(|e| format!("cannot find ilmrc itself: {e}"))?;
    let mut launched = Launched::default();
    for m in members {
        let Some(l) = &m.launch else { continue };
        let a = &m.args;
        let mut cmd = Command::new(&exe);
        cmd.args(["sim", "--ros2", "--stdin-lifeline", "--robot"])
            .arg(a.model.as_deref().unwrap_or("moro"))
            .args(["--seed", &a.seed.to_string()])
            .args([
                "--ros-namespace",
                a.ros2.ros_namespace.as_deref().unwrap_or("/"),
            ]);
        if let Some(w) = &l.world {
            cmd.args(["--world", w]);
        }
        if let Some(s) = &l.start {
            cmd.arg(format!("--start={s}"));
        }
        if let Some(d) = a.ros2.ros_domain {
            cmd.args(["--ros-domain", &d.to_string()]);
        }
        if a.ros2.ros_loopback {
            cmd.arg("--ros-loopback");
        }
        let mut child = cmd
            // The simulator's lifeline: it stops when this end closes, with this
            // process, however this process ends.
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .spawn()
            .map_err(|e| format!("robot `{}`: cannot start its simulator: {e}", m.name))?;
        let stdout = child.stdout.take().expect("piped");
        launched.0.push(child);
        let (ready, said) = mpsc::channel();
        std::thread::spawn(move || {
            let mut lines = BufReader::new(stdout).lines();
            let _ = ready.send(lines.next().and_then(Result::ok));
            // The rest (its summary) is read so that the simulator never blocks on it.
            for _ in lines {}
        });
        match said.recv_timeout(LAUNCH_WAIT) {
            Ok(Some(line)) if line.starts_with("ilmrc sim:") => {}
            _ => {
                return Err(format!(
                    "robot `{}`: its simulator did not start within {} s",
                    m.name,
                    LAUNCH_WAIT.as_secs()
                ));
            }
        }
    }
    Ok(launched)
}

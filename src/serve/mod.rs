//! `ilmrc serve`: the intermediate process of the dissertation's section 4.2.1 for
//! today's planners. A simulated robot runs in real time (10 ms ticks); clients on
//! TCP send ILMR text as JSON lines and are answered at once with success or the
//! diagnostics; they may subscribe to the trace's events. Protocol: docs/serve.md.

mod conn;
mod engine;
mod protocol;
mod robot;

use std::io::Write;
use std::net::{SocketAddr, TcpListener};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::mpsc;
use std::time::Duration;

use ilmr_compiler::FileId;
use ilmr_compiler::check::{Source, analyze};
use ilmr_vm::{SimClock, Vm};

use crate::build::{Compiled, compile, render_diagnostics};
use engine::Engine;

/// Connections served at once; one more is told so and closed.
const MAX_CLIENTS: usize = 64;

#[derive(clap::Args)]
pub struct ServeArgs {
    /// The simulated robot: `moro`, `workpartner` or a ROBO.INI path.
    #[arg(long, default_value = "moro")]
    pub robot: String,
    /// The robot's world: `office`, `yard`, `empty` or a world file (default: office
    /// for MoRo, yard for Workpartner).
    #[arg(long)]
    pub world: Option<String>,
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
    /// Where to listen: a loopback address and port, e.g. 127.0.0.1:7878 (port 0 picks
    /// a free one; the address is printed on stdout).
    #[arg(long)]
    pub listen: String,
}

pub fn run(args: ServeArgs) -> ExitCode {
    match execute(&args) {
        Ok(code) => code,
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::from(crate::EXIT_USAGE)
        }
    }
}

fn execute(args: &ServeArgs) -> Result<ExitCode, String> {
    // The address first: a port in use should fail before the task is compiled.
    let listener = listen(&args.listen)?;
    let opened = robot::open(&args.robot, args.world.as_deref(), args.seed)?;
    let module = match &args.task {
        Some(task) => compile(task, &opened.spec, args.skills.as_deref(), |_| Vec::new())?,
        None => no_task(&opened.spec, args.skills.as_deref())?,
    };
    let module = match module {
        Compiled::Module(m) => *m,
        Compiled::Rejected => return Ok(ExitCode::from(crate::EXIT_ERRORS)),
    };
    let vm = Vm::new(module, opened.robot, SimClock, opened.config).map_err(|e| e.to_string())?;
    let local = listener
        .local_addr()
        .map_err(|e| format!("cannot read the bound address: {e}"))?;
    let (jobs, queue) = mpsc::channel();
    let engine = Engine::new(vm, opened.model);
    std::thread::Builder::new()
        .name("ilmr-vm".into())
        .spawn(move || engine.run(queue))
        .map_err(|e| format!("cannot start the robot's thread: {e}"))?;
    // Clients (and the test) read this line to learn the port.
    println!(
        "listening on {local} (robot {}, world {})",
        args.robot, opened.world
    );
    let _ = std::io::stdout().flush();
    accept(&listener, &jobs);
    Ok(ExitCode::SUCCESS)
}

/// Binds a loopback address. The protocol has no authentication: whoever connects
/// drives the robot, so the server does not listen beyond this machine.
fn listen(text: &str) -> Result<TcpListener, String> {
    let addr: SocketAddr = text.parse().map_err(|_| {
        format!("--listen `{text}`: expected a loopback address and port, e.g. 127.0.0.1:7878")
    })?;
    if !addr.ip().is_loopback() {
        return Err(format!(
            "--listen `{text}`: only loopback addresses (127.0.0.1, [::1]) are served, since \
             the protocol has no authentication"
        ));
    }
    TcpListener::bind(addr).map_err(|e| match e.kind() {
        std::io::ErrorKind::AddrInUse => format!("cannot listen on {addr}: the port is in use"),
        _ => format!("cannot listen on {addr}: {e}"),
    })
}

/// Serves connections, each on its own thread, for as long as the process runs.
fn accept(listener: &TcpListener, jobs: &mpsc::Sender<engine::Job>) {
    let clients = Arc::new(AtomicUsize::new(0));
    let mut next_conn: u64 = 0;
    for stream in listener.incoming() {
        let mut stream = match stream {
            Ok(s) => s,
            Err(e) => {
                // Out of descriptors and the like: say so, and do not spin on it.
                eprintln!("warning: accepting a connection failed: {e}");
                std::thread::sleep(Duration::from_millis(50));
                continue;
            }
        };
        if clients.load(Ordering::SeqCst) >= MAX_CLIENTS {
            let refusal = protocol::answer(
                protocol::error(&format!("the server has {MAX_CLIENTS} clients already")),
                None,
            );
            let _ = writeln!(stream, "{refusal}");
            continue;
        }
        next_conn += 1;
        let conn = next_conn;
        let jobs = jobs.clone();
        let count = Arc::clone(&clients);
        count.fetch_add(1, Ordering::SeqCst);
        let spawned = std::thread::Builder::new()
            .name(format!("ilmr-client-{conn}"))
            .spawn(move || {
                conn::serve(stream, conn, jobs);
                count.fetch_sub(1, Ordering::SeqCst);
            });
        if let Err(e) = spawned {
            clients.fetch_sub(1, Ordering::SeqCst);
            eprintln!("warning: cannot serve a connection: {e}");
        }
    }
}

/// The module of an empty task, with the skills lines may call.
fn no_task(robot: &str, skills: Option<&Path>) -> Result<Compiled, String> {
    let model = crate::inputs::load_robot(robot)?.model;
    let mut sources = vec![Source::new("<serve>", "")];
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

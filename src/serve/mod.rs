//! `ilmrc serve`: the intermediate process of the dissertation's section 4.2.1 for
//! today's planners. A simulated robot runs in real time (10 ms ticks); clients on
//! TCP send ILMR text as JSON lines and are answered at once with success or the
//! diagnostics; they may subscribe to the trace's events. Protocol: docs/serve.md.

mod conn;
mod protocol;
mod reply;

use std::io::Write;
use std::net::{SocketAddr, TcpListener};
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Duration;

use crate::live::{RobotArgs, Robots};

/// Connections served at once; one more is told so and closed.
const MAX_CLIENTS: usize = 64;

#[derive(clap::Args)]
pub struct ServeArgs {
    #[command(flatten)]
    pub live: RobotArgs,
    /// Drive the robots of a fleet file instead of one (docs/fleet.md); requests name
    /// the robot with "robot".
    #[arg(long, conflicts_with_all = ["robot", "model", "world", "start", "task", "skills"])]
    pub fleet: Option<std::path::PathBuf>,
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
    if let Some(path) = &args.fleet {
        let Some(fleet) = crate::fleet::open(path)? else {
            return Ok(ExitCode::from(crate::EXIT_ERRORS));
        };
        let local = listener
            .local_addr()
            .map_err(|e| format!("cannot read the bound address: {e}"))?;
        let names: Vec<&str> = fleet.robots.names().collect();
        println!("listening on {local} (fleet: {})", names.join(", "));
        let _ = std::io::stdout().flush();
        accept(&listener, &fleet.robots);
        return Ok(ExitCode::SUCCESS);
    }
    let Some(live) = crate::live::start(&args.live)? else {
        return Ok(ExitCode::from(crate::EXIT_ERRORS));
    };
    let local = listener
        .local_addr()
        .map_err(|e| format!("cannot read the bound address: {e}"))?;
    // Clients (and the test) read this line to learn the port.
    println!(
        "listening on {local} (robot {}, world {})",
        args.live.robot, live.world
    );
    let _ = std::io::stdout().flush();
    accept(&listener, &Arc::new(Robots::one(live)));
    Ok(ExitCode::SUCCESS)
}

/// Binds a loopback address. The protocol has no authentication: whoever connects
/// drives the robot, so the server does not listen beyond this machine.
pub fn listen(text: &str) -> Result<TcpListener, String> {
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
pub fn accept(listener: &TcpListener, robots: &Arc<Robots>) {
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
        let robots = Arc::clone(robots);
        let count = Arc::clone(&clients);
        count.fetch_add(1, Ordering::SeqCst);
        let spawned = std::thread::Builder::new()
            .name(format!("ilmr-client-{conn}"))
            .spawn(move || {
                conn::serve(stream, conn, robots);
                count.fetch_sub(1, Ordering::SeqCst);
            });
        if let Err(e) = spawned {
            clients.fetch_sub(1, Ordering::SeqCst);
            eprintln!("warning: cannot serve a connection: {e}");
        }
    }
}

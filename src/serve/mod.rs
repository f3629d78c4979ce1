//! `ilmrc serve`: the intermediate process of the dissertation's section 4.2.1 for
//! today's planners. A simulated robot runs in real time (10 ms ticks); clients on
//! TCP send ILMR text as JSON lines and are answered at once with success or the
//! diagnostics; they may subscribe to the trace's events. Protocol: docs/serve.md.

mod access;
mod admit;
mod audit;
mod client;
mod conn;
mod credentials;
mod lease;
mod outbox;
mod protocol;
mod reply;
mod security;
mod tls;

use std::io::Write;
use std::net::{SocketAddr, TcpListener};
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Arc;
use std::time::Duration;

use tokio_rustls::TlsAcceptor;

use crate::live::{RobotArgs, Robots};
use access::{Access, Identity};
use audit::Audit;
use lease::Leases;
pub use security::{Security, SecurityArgs};

pub use admit::{MAX_CLIENTS, RESERVED_PLACES};

/// A client's first request must end this long after it connected, and every request
/// line this long after its first byte.
pub const REQUEST_TIMEOUT: Duration = Duration::from_secs(10);
/// A client with no request and nothing written to it for this long is closed.
pub const IDLE_TIMEOUT: Duration = Duration::from_secs(120);
/// The kernel's send and receive buffers of a client's socket (it doubles them):
/// fixed, so that a client that does not read holds this much of the kernel's memory
/// rather than the megabytes autotuning would give it.
const SOCKET_BUFFER_BYTES: usize = 64 << 10;
/// The longest `--request-timeout` or `--idle-timeout`: a day.
const MAX_TIMEOUT_SECS: f64 = 86_400.0;

/// How long a client may take.
#[derive(Debug, Clone, Copy)]
pub struct Timeouts {
    pub request: Duration,
    pub idle: Duration,
}

impl Default for Timeouts {
    fn default() -> Timeouts {
        Timeouts {
            request: REQUEST_TIMEOUT,
            idle: IDLE_TIMEOUT,
        }
    }
}

/// What every connection shares.
pub struct Server {
    pub robots: Arc<Robots>,
    pub timeouts: Timeouts,
    /// `None`: a loopback server that asks nobody who they are.
    pub access: Option<Access>,
    pub leases: Leases,
    pub audit: Option<Audit>,
}

#[derive(clap::Args)]
pub struct ServeArgs {
    #[command(flatten)]
    pub live: RobotArgs,
    /// Drive the robots of a fleet file instead of one (docs/fleet.md); requests name
    /// the robot with "robot".
    #[arg(long, conflicts_with_all = ["robot", "model", "world", "start", "task", "skills"])]
    pub fleet: Option<std::path::PathBuf>,
    /// Where to listen: an address and port, e.g. 0.0.0.0:7878 with --credentials, or
    /// 127.0.0.1:7878 with --no-tls (port 0 picks a free one; the address is printed
    /// on stdout).
    #[arg(long, required_unless_present = "init_credentials")]
    pub listen: Option<String>,
    #[command(flatten)]
    pub security: SecurityArgs,
    /// Make a CA, a server certificate, client credentials and an access file in DIR
    /// (for --credentials DIR), then exit.
    #[arg(long, value_name = "DIR", conflicts_with_all = ["listen", "credentials", "no_tls"])]
    pub init_credentials: Option<PathBuf>,
    /// A host name or address the server's certificate also names (repeat for more;
    /// localhost, 127.0.0.1 and ::1 are always named).
    #[arg(long, value_name = "NAME", requires = "init_credentials")]
    pub san: Vec<String>,
    /// Seconds a client has to finish its first request after connecting, and any
    /// request line after its first byte (default 10).
    #[arg(long, value_name = "SECONDS")]
    pub request_timeout: Option<f64>,
    /// Seconds after which a client that sent no request and was sent nothing is
    /// closed (default 120).
    #[arg(long, value_name = "SECONDS")]
    pub idle_timeout: Option<f64>,
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

fn timeouts(args: &ServeArgs) -> Result<Timeouts, String> {
    let pick = |flag: &str, given: Option<f64>, default: Duration| match given {
        None => Ok(default),
        Some(s) if s.is_finite() && s > 0.0 && s <= MAX_TIMEOUT_SECS => {
            Ok(Duration::from_secs_f64(s))
        }
        Some(s) => Err(format!(
            "{flag} {s}: expected seconds above 0, at most {MAX_TIMEOUT_SECS}"
        )),
    };
    Ok(Timeouts {
        request: pick("--request-timeout", args.request_timeout, REQUEST_TIMEOUT)?,
        idle: pick("--idle-timeout", args.idle_timeout, IDLE_TIMEOUT)?,
    })
}

fn execute(args: &ServeArgs) -> Result<ExitCode, String> {
    if let Some(dir) = &args.init_credentials {
        let written = credentials::init(dir, &args.san)?;
        for path in &written {
            println!("wrote {}", path.display());
        }
        println!(
            "serve with: ilmrc serve --credentials {} --listen ADDRESS:PORT",
            dir.display()
        );
        return Ok(ExitCode::SUCCESS);
    }
    let timeouts = timeouts(args)?;
    let Some(address) = &args.listen else {
        return Err("--listen ADDRESS:PORT is needed".into());
    };
    // The address first: a port in use should fail before the task is compiled.
    let (listener, security) = listen(address, &args.security)?;
    if let Some(path) = &args.fleet {
        let Some(fleet) = crate::fleet::open(path)? else {
            return Ok(ExitCode::from(crate::EXIT_ERRORS));
        };
        let local = listener
            .local_addr()
            .map_err(|e| format!("cannot read the bound address: {e}"))?;
        let names: Vec<&str> = fleet.robots.names().collect();
        println!(
            "listening on {local} ({}; fleet: {})",
            security.describe(),
            names.join(", ")
        );
        let _ = std::io::stdout().flush();
        serve(listener, server(&fleet.robots, timeouts, security))?;
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
        "listening on {local} ({}; robot {}, world {})",
        security.describe(),
        args.live.robot,
        live.world
    );
    let _ = std::io::stdout().flush();
    serve(
        listener,
        server(&Arc::new(Robots::one(live)), timeouts, security),
    )?;
    Ok(ExitCode::SUCCESS)
}

/// What the connections share, and the TLS acceptor they go through when there is one.
fn server(
    robots: &Arc<Robots>,
    timeouts: Timeouts,
    security: Security,
) -> (Server, Option<TlsAcceptor>) {
    let server = Server {
        robots: Arc::clone(robots),
        timeouts,
        access: security.access,
        leases: Leases::default(),
        audit: security.audit,
    };
    (server, security.tls)
}

/// Binds the address with what the flags say of TLS and clients: beyond loopback
/// only with credentials, and plain TCP only when asked for.
pub fn listen(text: &str, args: &SecurityArgs) -> Result<(TcpListener, Security), String> {
    let addr: SocketAddr = text.parse().map_err(|_| {
        format!("--listen `{text}`: expected an address and port, e.g. 127.0.0.1:7878")
    })?;
    let security = Security::from_args(args, &addr)?;
    let listener = TcpListener::bind(addr).map_err(|e| match e.kind() {
        std::io::ErrorKind::AddrInUse => format!("cannot listen on {addr}: the port is in use"),
        _ => format!("cannot listen on {addr}: {e}"),
    })?;
    Ok((listener, security))
}

/// Serves connections with the default timeouts for as long as the process runs
/// (`ilmrc fleet --listen`).
pub fn accept(listener: &TcpListener, robots: &Arc<Robots>, security: Security) {
    let served = listener
        .try_clone()
        .map_err(|e| format!("cannot serve the listener: {e}"))
        .and_then(|l| serve(l, server(robots, Timeouts::default(), security)));
    if let Err(e) = served {
        eprintln!("error: {e}");
    }
}

/// Serves connections, each a task on two network threads, for as long as the
/// process runs.
fn serve(listener: TcpListener, server: (Server, Option<TlsAcceptor>)) -> Result<(), String> {
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .thread_name("ilmr-net")
        .enable_io()
        .enable_time()
        .build()
        .map_err(|e| format!("cannot start the network threads: {e}"))?;
    listener
        .set_nonblocking(true)
        .map_err(|e| format!("cannot serve the listener: {e}"))?;
    runtime.block_on(async {
        let listener = tokio::net::TcpListener::from_std(listener)
            .map_err(|e| format!("cannot serve the listener: {e}"))?;
        accept_all(listener, Arc::new(server.0), server.1).await;
        Ok(())
    })
}

async fn accept_all(
    listener: tokio::net::TcpListener,
    server: Arc<Server>,
    tls: Option<TlsAcceptor>,
) {
    let registry = Arc::new(admit::Registry::default());
    let mut next_conn: u64 = 0;
    loop {
        let (stream, peer) = match listener.accept().await {
            Ok(accepted) => accepted,
            Err(e) => {
                // Out of descriptors and the like: say so, and do not spin on it.
                eprintln!("warning: accepting a connection failed: {e}");
                tokio::time::sleep(Duration::from_millis(50)).await;
                continue;
            }
        };
        next_conn += 1;
        let Some(place) = registry.admit(next_conn) else {
            let refusal = protocol::answer(
                protocol::error(&format!(
                    "the server has {} clients already, all of them busy",
                    MAX_CLIENTS + RESERVED_PLACES
                )),
                None,
            );
            let _ = stream.try_write(format!("{refusal}\n").as_bytes());
            continue;
        };
        let _ = stream.set_nodelay(true);
        let socket = socket2::SockRef::from(&stream);
        let _ = socket.set_send_buffer_size(SOCKET_BUFFER_BYTES);
        let _ = socket.set_recv_buffer_size(SOCKET_BUFFER_BYTES);
        let server = Arc::clone(&server);
        let registry = Arc::clone(&registry);
        let tls = tls.clone();
        tokio::spawn(async move {
            let conn = place.conn;
            match tls {
                None => {
                    if server.access.is_none() {
                        let _ = place.identify(Identity::anonymous(conn));
                    }
                    conn::serve(stream, place, server, Some(peer)).await;
                }
                Some(tls) => security::handshake(stream, peer, place, server, &tls).await,
            }
            registry.leave(conn);
        });
    }
}

#[cfg(test)]
mod tests {
    use super::admit::EVICT_AFTER;
    use super::outbox::EVENT_BUDGET_BYTES;
    use super::*;

    /// The limits tables of docs/reliability.md and docs/serve.md quote the constants.
    #[test]
    fn the_docs_quote_the_limits() {
        let reliability = include_str!("../../docs/reliability.md");
        let serve = include_str!("../../docs/serve.md");
        let row = |name: &str| {
            reliability
                .lines()
                .find(|l| l.starts_with('|') && l.contains(name))
                .unwrap_or_else(|| panic!("no row of docs/reliability.md names {name}"))
        };
        let quoted = [
            ("MAX_CLIENTS", format!("{MAX_CLIENTS} clients")),
            ("RESERVED_PLACES", format!("{RESERVED_PLACES} places")),
            ("EVICT_AFTER", format!("silent {} s", EVICT_AFTER.as_secs())),
            (
                "REQUEST_TIMEOUT",
                format!("{} s", REQUEST_TIMEOUT.as_secs()),
            ),
            ("IDLE_TIMEOUT", format!("{} s", IDLE_TIMEOUT.as_secs())),
            ("LEASE_TIME", format!("{} s", lease::LEASE_TIME.as_secs())),
            (
                "MAX_AUDIT_BYTES",
                format!("{} MiB", audit::MAX_AUDIT_BYTES >> 20),
            ),
            (
                "EVENT_BUDGET_BYTES",
                format!("{} KiB", EVENT_BUDGET_BYTES >> 10),
            ),
            (
                "MAX_LINE_STATEMENTS",
                format!(
                    "{} statements",
                    ilmr_compiler::render::thousands(crate::live::MAX_LINE_STATEMENTS)
                ),
            ),
            (
                "MAX_LINE_TEXT_BYTES",
                format!("{} MiB", crate::live::MAX_LINE_TEXT_BYTES >> 20),
            ),
        ];
        for (name, value) in quoted {
            assert!(
                row(name).contains(&value),
                "the row of {name} does not say {value}"
            );
            assert!(
                serve.contains(&value),
                "docs/serve.md does not say {value} ({name})"
            );
        }
    }

    #[test]
    fn timeouts_must_be_positive_and_finite() {
        let args = |request: Option<f64>, idle: Option<f64>| ServeArgs {
            live: RobotArgs {
                robot: "moro".into(),
                model: None,
                world: None,
                start: None,
                seed: 0,
                skills: None,
                task: None,
                ros2: crate::ros2::Ros2Args::default(),
                view: Default::default(),
            },
            fleet: None,
            listen: Some("127.0.0.1:0".into()),
            security: SecurityArgs::default(),
            init_credentials: None,
            san: Vec::new(),
            request_timeout: request,
            idle_timeout: idle,
        };
        let t = timeouts(&args(None, Some(2.5))).expect("valid");
        assert_eq!(
            (t.request, t.idle),
            (REQUEST_TIMEOUT, Duration::from_millis(2500))
        );
        for bad in [0.0, -1.0, f64::NAN, f64::INFINITY, 1e9] {
            assert!(timeouts(&args(Some(bad), None)).is_err(), "{bad}");
            assert!(timeouts(&args(None, Some(bad))).is_err(), "{bad}");
        }
    }
}

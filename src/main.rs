//! `ilmrc`: the ILMR toolchain's command line.

mod build;
mod check;
mod diff;
mod fleet;
mod fmt;
mod inputs;
mod live;
mod notice;
mod replay;
mod ros2;
mod run;
mod serve;
mod shell;
mod sim;
mod status_line;
mod tape;
mod testing;
mod view;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// Checking a large task allocates a node per statement and argument; mimalloc does
/// that in about half the time of the system allocator.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

#[derive(Parser)]
#[command(
    name = "ilmrc",
    version,
    about = "Check, build and run ILMR robot tasks"
)]
struct Cli {
    #[command(subcommand)]
    command: Cmd,
}

#[derive(Subcommand)]
enum Cmd {
    /// Check task and skill files against a robot model (replaces `check`/`checkend`).
    Check(check::CheckArgs),
    /// Rewrite files in canonical form (lower-case commands, `==` and `>=`, indented blocks).
    Fmt(fmt::FmtArgs),
    /// Check a task and write it as a bytecode module (`.ilmb`).
    Build(build::BuildArgs),
    /// List a module's instructions with their source lines.
    Disasm(build::DisasmArgs),
    /// Run a task on a robot backend and write its trace.
    Run(Box<run::RunArgs>),
    /// Run a simulated robot in real time and take ILMR lines from clients over TCP.
    Serve(serve::ServeArgs),
    /// Run a simulated robot in real time and type ILMR lines into it.
    Shell(shell::ShellArgs),
    /// Run a simulated robot in real time as a ROS 2 robot (`--ros2`), for any ROS 2
    /// node or `run --robot ros2` to drive.
    Sim(Box<sim::SimArgs>),
    /// Start a fleet of robots (a fleet file) and show each robot's state.
    Fleet(fleet::FleetArgs),
    /// Run the tests of test files (`*.test.toml`): tasks run on simulated robots, with
    /// assertions on what they did.
    Test(testing::TestArgs),
    /// Redraw a finished run from its trace, without running it.
    Replay(replay::ReplayArgs),
    /// Where two traces of a task part ways: the first event that differs, the
    /// commands whose end changed, the largest pose difference.
    Diff(diff::DiffArgs),
    /// Print the syntax tree of a file, one node per line.
    Parse {
        /// The file to parse.
        file: std::path::PathBuf,
    },
}

impl Cmd {
    /// Whether the command does its job and ends, writing what it found to stdout:
    /// unlike the robots that run until stopped (`serve`, `shell`, `sim`, `fleet`) and a
    /// run with a live view, which talk to clients and children over pipes and sockets
    /// (a vectored write to a closed socket raises SIGPIPE too).
    fn ends_by_itself(&self) -> bool {
        match self {
            Cmd::Serve(_) | Cmd::Shell(_) | Cmd::Sim(_) | Cmd::Fleet(_) => false,
            Cmd::Run(args) => args.view.foxglove.is_none(),
            _ => true,
        }
    }
}

/// Lets a closed stdout end the process as it ends `cat` or `grep` (`ilmrc parse BIG |
/// head`), by the signal, silently. Rust ignores SIGPIPE, so a write to a closed pipe is
/// an error, and `print!` panics on it (exit 101).
#[cfg(unix)]
fn default_sigpipe() {
    // SAFETY: sets the process's disposition of one signal before any thread is
    // started; no pointer is passed. std's sockets send with MSG_NOSIGNAL, so they
    // still get EPIPE as an error rather than the signal.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}

#[cfg(not(unix))]
fn default_sigpipe() {}

/// Exit codes: 0 clean (warnings allowed), 1 errors in the input, 2 usage or I/O errors;
/// a run also 3, 4 or 5 (docs/run.md).
pub const EXIT_ERRORS: u8 = 1;
pub const EXIT_USAGE: u8 = 2;
/// A run ended, but commands were refused or runtime errors happened.
pub const EXIT_TROUBLE: u8 = 3;
/// A run ended on a supervisor hold that did not clear.
pub const EXIT_HELD: u8 = 4;
/// A run stopped at `--max-time` with commands still live.
pub const EXIT_MAX_TIME: u8 = 5;

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            let code = if e.use_stderr() { EXIT_USAGE } else { 0 };
            let _ = e.print();
            return ExitCode::from(code);
        }
    };
    if cli.command.ends_by_itself() {
        default_sigpipe();
    }
    match cli.command {
        Cmd::Check(args) => check::run(args),
        Cmd::Fmt(args) => fmt::run(args),
        Cmd::Build(args) => build::build(args),
        Cmd::Disasm(args) => build::disasm(args),
        Cmd::Run(args) => run::run(*args),
        Cmd::Sim(args) => sim::run(*args),
        Cmd::Fleet(args) => fleet::run(args),
        Cmd::Test(args) => testing::run(args),
        Cmd::Replay(args) => replay::run(args),
        Cmd::Diff(args) => diff::run(args),
        Cmd::Serve(args) => serve::run(args),
        Cmd::Shell(args) => shell::run(args),
        Cmd::Parse { file } => match inputs::read_source(&file) {
            Ok(source) => {
                let parsed = ilmr_compiler::parser::parse(&source.text, ilmr_compiler::FileId(0));
                print!("{}", ilmr_compiler::tree::render(&parsed.file));
                ExitCode::SUCCESS
            }
            Err(message) => {
                eprintln!("error: {message}");
                ExitCode::from(EXIT_USAGE)
            }
        },
    }
}

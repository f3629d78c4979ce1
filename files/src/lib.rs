//! The one way the ILMR tools read a file they are given: task and skill sources,
//! robot models, worlds, compiled modules, traces, scenarios, the shell's history and
//! fleet files.
//!
//! A tool that reads `/dev/zero`, a FIFO or a file that keeps growing must not grow
//! with it, and a directory or a device must get a clear message rather than an OS
//! error that differs from one command to the next. So every read here:
//!
//! - takes regular files only (symbolic links are followed), and says what else the
//!   path is: a directory, a FIFO, a character or block device, a socket;
//! - refuses a file whose size is above its kind's limit before reading it, and reads
//!   at most `limit + 1` bytes whatever the size said, so that a file that grows while
//!   it is read (or a `/proc` file that claims size 0) cannot exceed the limit either;
//! - opens without blocking, so a FIFO put in the file's place between the check and
//!   the open cannot hang the reader.
//!
//! The limits, one per [`Kind`], are the `MAX_*_BYTES` constants below.

use std::fmt;
use std::fs::{File, Metadata, OpenOptions};
use std::io::{self, Read};
use std::path::Path;

const MIB: u64 = 1 << 20;

/// A task (`.ilmr`) or skill (`.ilms`) file: 64 times the largest program the
/// compiler's benchmarks check (the 100,000-line corpus is 2.6 MB), far beyond any
/// hand-written task, and small enough that checking it stays within a few hundred MB.
pub const MAX_SOURCE_BYTES: u64 = 8 * MIB;
/// A ROBO.INI robot model: the shipped models are under 4 KB.
pub const MAX_ROBOT_MODEL_BYTES: u64 = MIB;
/// A world file (TOML): room for the largest world the simulator's limits allow.
pub const MAX_WORLD_BYTES: u64 = 16 * MIB;
/// A compiled module (`.ilmb`): a module is a few times the size of its source.
pub const MAX_MODULE_BYTES: u64 = 64 * MIB;
/// A trace of `ilmrc run` (JSON Lines), read back by `ilmrc replay`: hours of
/// simulated time with pose samples and scans.
pub const MAX_TRACE_BYTES: u64 = 256 * MIB;
/// An `--mcap` file `ilmrc run` writes (never read here): it stops growing there, with
/// a last log message that says so, as a trace stops at [`MAX_TRACE_BYTES`]. Four
/// times the trace's room, for every scan is in it.
pub const MAX_MCAP_BYTES: u64 = 1024 * MIB;
/// A `--scenario` file (JSON): taught paths and timed lines.
pub const MAX_SCENARIO_BYTES: u64 = 16 * MIB;
/// The shell's `--history` file: rustyline keeps the last 100 lines.
pub const MAX_HISTORY_BYTES: u64 = MIB;
/// A fleet file (TOML): a few lines per robot, for at most a few dozen robots.
pub const MAX_FLEET_BYTES: u64 = MIB;

/// What a file holds, which sets its size limit and names it in messages.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    Source,
    RobotModel,
    World,
    Module,
    Trace,
    Scenario,
    History,
    Fleet,
    /// An MCAP recording (`ilmrc replay --inputs RUN.mcap`).
    Recording,
}

impl Kind {
    pub const ALL: [Kind; 9] = [
        Kind::Source,
        Kind::RobotModel,
        Kind::World,
        Kind::Module,
        Kind::Trace,
        Kind::Scenario,
        Kind::History,
        Kind::Fleet,
        Kind::Recording,
    ];

    /// The largest file of this kind, bytes.
    pub const fn limit(self) -> u64 {
        match self {
            Kind::Source => MAX_SOURCE_BYTES,
            Kind::RobotModel => MAX_ROBOT_MODEL_BYTES,
            Kind::World => MAX_WORLD_BYTES,
            Kind::Module => MAX_MODULE_BYTES,
            Kind::Trace => MAX_TRACE_BYTES,
            Kind::Scenario => MAX_SCENARIO_BYTES,
            Kind::History => MAX_HISTORY_BYTES,
            Kind::Fleet => MAX_FLEET_BYTES,
            Kind::Recording => MAX_MCAP_BYTES,
        }
    }

    /// The name of the constant that holds [`Kind::limit`], for messages and docs.
    pub const fn limit_name(self) -> &'static str {
        match self {
            Kind::Source => "MAX_SOURCE_BYTES",
            Kind::RobotModel => "MAX_ROBOT_MODEL_BYTES",
            Kind::World => "MAX_WORLD_BYTES",
            Kind::Module => "MAX_MODULE_BYTES",
            Kind::Trace => "MAX_TRACE_BYTES",
            Kind::Scenario => "MAX_SCENARIO_BYTES",
            Kind::History => "MAX_HISTORY_BYTES",
            Kind::Fleet => "MAX_FLEET_BYTES",
            Kind::Recording => "MAX_MCAP_BYTES",
        }
    }

    /// What a file of this kind is called in messages.
    pub const fn noun(self) -> &'static str {
        match self {
            Kind::Source => "task or skill file",
            Kind::RobotModel => "robot model",
            Kind::World => "world file",
            Kind::Module => "compiled module",
            Kind::Trace => "trace",
            Kind::Scenario => "scenario",
            Kind::History => "shell history",
            Kind::Fleet => "fleet file",
            Kind::Recording => "MCAP recording",
        }
    }
}

/// Why a file was not read.
#[derive(Debug)]
pub enum Problem {
    NotFound,
    Directory,
    /// Not a regular file: what it is instead.
    Special(&'static str),
    /// Larger than its kind's limit.
    TooLarge,
    /// [`read_text`] only: the first byte that is not UTF-8, and where it stands
    /// (1-based line, and column in characters).
    NotUtf8 {
        offset: usize,
        line: usize,
        column: usize,
    },
    Io(io::Error),
}

/// A file that was not read, of a kind. Its message says why and is written to
/// follow "cannot read `PATH`: ".
#[derive(Debug)]
pub struct ReadError {
    pub kind: Kind,
    pub problem: Problem,
}

impl ReadError {
    pub fn is_not_found(&self) -> bool {
        matches!(self.problem, Problem::NotFound)
    }
}

impl fmt::Display for ReadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.problem {
            Problem::NotFound => write!(f, "no such file"),
            Problem::Directory => write!(f, "it is a directory, not a file"),
            Problem::Special(what) => write!(f, "it is a {what}, not a regular file"),
            Problem::TooLarge => write!(
                f,
                "it is larger than {}, the limit for a {} ({})",
                size(self.kind.limit()),
                self.kind.noun(),
                self.kind.limit_name()
            ),
            Problem::NotUtf8 { line, column, .. } => write!(
                f,
                "it is not UTF-8 text (invalid byte at line {line}, column {column})"
            ),
            Problem::Io(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for ReadError {}

/// For callers whose errors are `io::Error`s; the message stays the same.
impl From<ReadError> for io::Error {
    fn from(e: ReadError) -> io::Error {
        let kind = match &e.problem {
            Problem::NotFound => io::ErrorKind::NotFound,
            Problem::Directory => io::ErrorKind::IsADirectory,
            Problem::Special(_) => io::ErrorKind::InvalidInput,
            Problem::TooLarge => io::ErrorKind::FileTooLarge,
            Problem::NotUtf8 { .. } => io::ErrorKind::InvalidData,
            Problem::Io(inner) => inner.kind(),
        };
        io::Error::new(kind, e.to_string())
    }
}

/// `8 MiB`, or the exact bytes when the limit is not whole mebibytes.
fn size(bytes: u64) -> String {
    if bytes.is_multiple_of(MIB) {
        format!("{} MiB", bytes / MIB)
    } else {
        format!("{bytes} bytes")
    }
}

/// The bytes of a regular file of `kind`, at most its limit.
pub fn read(path: &Path, kind: Kind) -> Result<Vec<u8>, ReadError> {
    read_limited(path, kind.limit()).map_err(|problem| ReadError { kind, problem })
}

/// The text of a regular file of `kind`, at most its limit; text that is not UTF-8 is
/// an error.
pub fn read_text(path: &Path, kind: Kind) -> Result<String, ReadError> {
    let bytes = read(path, kind)?;
    String::from_utf8(bytes).map_err(|e| {
        let offset = e.utf8_error().valid_up_to();
        let (line, column) = line_column(&e.as_bytes()[..offset]);
        ReadError {
            kind,
            problem: Problem::NotUtf8 {
                offset,
                line,
                column,
            },
        }
    })
}

/// 1-based line of a byte offset of `text` (past the end: its last line), for readers
/// that name the line of what they refuse.
pub fn line_of(text: &str, offset: usize) -> usize {
    let end = offset.min(text.len());
    text.as_bytes()[..end]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
        + 1
}

/// Where the byte after `valid` (UTF-8 text) stands: 1-based line, and column in
/// characters.
pub fn line_column(valid: &[u8]) -> (usize, usize) {
    let line_start = valid.iter().rposition(|b| *b == b'\n').map_or(0, |i| i + 1);
    let line = valid.iter().filter(|b| **b == b'\n').count() + 1;
    let column = std::str::from_utf8(&valid[line_start..]).map_or(0, |t| t.chars().count()) + 1;
    (line, column)
}

fn read_limited(path: &Path, limit: u64) -> Result<Vec<u8>, Problem> {
    let before = std::fs::metadata(path).map_err(problem)?;
    regular(&before)?;
    if before.len() > limit {
        return Err(Problem::TooLarge);
    }
    let file = open(path)?;
    // The path may name another file by now; what is read is what this says.
    let opened = file.metadata().map_err(problem)?;
    regular(&opened)?;
    let expected = opened.len().min(limit);
    let mut bytes = Vec::with_capacity(usize::try_from(expected).unwrap_or(0));
    file.take(limit.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(problem)?;
    if bytes.len() as u64 > limit {
        return Err(Problem::TooLarge);
    }
    Ok(bytes)
}

#[cfg(unix)]
fn open(path: &Path) -> Result<File, Problem> {
    use std::os::unix::fs::OpenOptionsExt;
    // Without O_NONBLOCK, opening a FIFO waits for a writer; on a regular file the
    // flag changes nothing.
    OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NONBLOCK)
        .open(path)
        .map_err(problem)
}

#[cfg(not(unix))]
fn open(path: &Path) -> Result<File, Problem> {
    OpenOptions::new().read(true).open(path).map_err(problem)
}

fn problem(e: io::Error) -> Problem {
    match e.kind() {
        io::ErrorKind::NotFound => Problem::NotFound,
        io::ErrorKind::IsADirectory => Problem::Directory,
        _ => Problem::Io(e),
    }
}

fn regular(meta: &Metadata) -> Result<(), Problem> {
    let t = meta.file_type();
    if t.is_file() {
        return Ok(());
    }
    if t.is_dir() {
        return Err(Problem::Directory);
    }
    Err(Problem::Special(special_name(&t)))
}

#[cfg(unix)]
fn special_name(t: &std::fs::FileType) -> &'static str {
    use std::os::unix::fs::FileTypeExt;
    if t.is_fifo() {
        "FIFO (named pipe)"
    } else if t.is_char_device() {
        "character device"
    } else if t.is_block_device() {
        "block device"
    } else if t.is_socket() {
        "socket"
    } else {
        "special file"
    }
}

#[cfg(not(unix))]
fn special_name(_: &std::fs::FileType) -> &'static str {
    "special file"
}

#[cfg(test)]
mod tests;

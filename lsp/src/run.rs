//! "Run in simulator": the code lens's command runs the task with `ilmrc run`, a
//! process of its own (the server does not link the toolchain's top crate), keeps its
//! summary, and reads the run's trace (`ilmr-trace`'s typed schema) for each line's
//! start and end times, shown as inlay hints until the text changes.

use std::collections::BTreeMap;
use std::hash::{Hash, Hasher};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

use ilmr_trace::{Event, records};

/// The code lens's command.
pub const RUN_COMMAND: &str = "ilmr.run";

/// A run that takes longer than this on the wall clock is ended: `ilmrc run` stops at
/// its own `--max-time` of logical time, which a simulated robot covers many times
/// faster, so this is a run that went wrong.
pub const RUN_TIMEOUT: Duration = Duration::from_secs(120);

/// What one task's last run left.
#[derive(Debug, Clone, PartialEq)]
pub struct LastRun {
    /// The text that ran: the times are shown only while the document still reads so.
    pub text: u64,
    /// `ilmrc run`'s summary (stdout), or why there is none.
    pub summary: String,
    pub exit: Option<i32>,
    /// By line (from 1) of the task file.
    pub times: BTreeMap<u32, Times>,
}

impl LastRun {
    /// The summary's first line: how the run ended.
    pub fn headline(&self) -> &str {
        self.summary.lines().next().unwrap_or("").trim()
    }
}

/// When one statement ran in the trace.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Times {
    /// Its first `issue`, and how many.
    pub issued: Option<f64>,
    pub issues: u32,
    /// Its first `start` (a queued movement given the reservation, a guard's body, a
    /// loop's iteration), and how many.
    pub started: Option<f64>,
    pub starts: u32,
    /// Its last end, if it ended.
    pub end: Option<f64>,
}

impl Times {
    /// When it began to act: its first start, else its first issue.
    pub fn start(&self) -> f64 {
        self.started.or(self.issued).unwrap_or(0.0)
    }

    pub fn label(&self) -> String {
        let start = secs(self.start());
        let mut s = match self.end {
            Some(end) => format!("ran t={start}–{} s", secs(end)),
            // Ended at issue (a setting), or still live when the run stopped: the
            // trace tells only when it began.
            None if self.started.is_some() => format!("started t={start} s"),
            None => format!("issued t={start} s"),
        };
        let times = if self.started.is_some() {
            self.starts
        } else {
            self.issues
        };
        if times > 1 {
            s.push_str(&format!(" ({times}×)"));
        }
        s
    }
}

fn secs(t: f64) -> String {
    format!("{t:.2}")
}

/// A text's fingerprint, to tell whether a document still reads as it ran.
pub fn fingerprint(text: &str) -> u64 {
    let mut h = std::collections::hash_map::DefaultHasher::new();
    text.hash(&mut h);
    h.finish()
}

/// Each line's times from a trace, keeping only the task's own statements (a skill's
/// or a typed line's name their file) whose text is still that line's text in `task`.
pub fn times(trace: &str, task: &str) -> Result<BTreeMap<u32, Times>, String> {
    let lines: Vec<&str> = task.lines().map(str::trim).collect();
    let ours = |line: u32, text: &str| {
        lines
            .get((line as usize).wrapping_sub(1))
            .is_some_and(|l| *l == text.trim())
    };
    let mut out: BTreeMap<u32, Times> = BTreeMap::new();
    for record in records(trace) {
        let record = record.map_err(|e| e.to_string())?;
        let t = record.t.0;
        let stmt = match &record.event {
            Event::Issue(i) => i.stmt.as_ref(),
            Event::Start(s) => s.stmt.as_ref(),
            Event::End(e) => e.stmt.as_ref(),
            _ => continue,
        };
        let Some(stmt) = stmt.filter(|s| s.file.is_none() && ours(s.line, &s.text)) else {
            continue;
        };
        let entry = out.entry(stmt.line).or_default();
        match &record.event {
            Event::Issue(_) => {
                entry.issued.get_or_insert(t);
                entry.issues += 1;
            }
            Event::Start(_) => {
                entry.started.get_or_insert(t);
                entry.starts += 1;
            }
            _ => entry.end = Some(t),
        }
    }
    Ok(out)
}

/// How to run a task.
#[derive(Debug, Clone)]
pub struct Invocation {
    pub ilmrc: PathBuf,
    pub task: PathBuf,
    /// `--robot`: a name or a ROBO.INI path.
    pub robot: String,
    /// `--skills`: a skill file or a directory of them.
    pub skills: Option<PathBuf>,
}

/// Runs `ilmrc run` with a trace into a file of its own; the last run's summary and
/// times. Never fails: a run that cannot start says why in its summary.
pub fn run(inv: &Invocation, text: &str) -> LastRun {
    // Runs may overlap (the lens clicked twice): each writes a trace of its own.
    static RUNS: AtomicU64 = AtomicU64::new(0);
    let trace = std::env::temp_dir().join(format!(
        "ilmr-lsp-{}-{}.jsonl",
        std::process::id(),
        RUNS.fetch_add(1, Ordering::Relaxed)
    ));
    let mut last = LastRun {
        text: fingerprint(text),
        summary: String::new(),
        exit: None,
        times: BTreeMap::new(),
    };
    let mut command = Command::new(&inv.ilmrc);
    command
        .arg("run")
        .arg(&inv.task)
        .arg("--robot")
        .arg(&inv.robot)
        .arg("--trace")
        .arg(&trace)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    if let Some(skills) = &inv.skills {
        command.arg("--skills").arg(skills);
    }
    let output = match wait(command) {
        Ok(o) => o,
        Err(e) => {
            last.summary = format!("cannot run `{}`: {e}", inv.ilmrc.display());
            return last;
        }
    };
    last.exit = output.status.code();
    last.summary = summary(&String::from_utf8_lossy(&output.stdout), &inv.task);
    if last.summary.is_empty() {
        // A task that fails its check prints its diagnostics on stderr and no summary.
        let stderr = String::from_utf8_lossy(&output.stderr);
        last.summary = format!(
            "ilmrc run ended with exit {}: {}",
            last.exit.map_or("(killed)".to_string(), |c| c.to_string()),
            stderr.trim()
        );
    }
    match std::fs::read_to_string(&trace) {
        Ok(t) => match times(&t, text) {
            Ok(times) => last.times = times,
            Err(e) => last
                .summary
                .push_str(&format!("\n(the trace could not be read: {e})")),
        },
        Err(e) => last.summary.push_str(&format!("\n(no trace: {e})")),
    }
    let _ = std::fs::remove_file(&trace);
    last
}

/// `ilmrc run`'s stdout from its summary's first line (`TASK: finished: ...`) on: the
/// check's diagnostics printed before it are the editor's diagnostics already.
fn summary(stdout: &str, task: &Path) -> String {
    let head = format!("{}: ", task.display());
    let from = stdout
        .match_indices(&head)
        .map(|(i, _)| i)
        .find(|&i| i == 0 || stdout.as_bytes()[i - 1] == b'\n')
        .unwrap_or(0);
    stdout[from..].trim_end().to_string()
}

/// The process's output, or an error when it cannot start or outlives
/// [`RUN_TIMEOUT`] (then it is killed).
fn wait(mut command: Command) -> std::io::Result<std::process::Output> {
    let mut child = command.spawn()?;
    // Pipes are drained on threads of their own so that a chatty run cannot block on
    // a full pipe while this waits for it.
    let drain = |pipe: Option<Box<dyn std::io::Read + Send>>| {
        std::thread::spawn(move || {
            let mut buf = Vec::new();
            if let Some(mut p) = pipe {
                let _ = p.read_to_end(&mut buf);
            }
            buf
        })
    };
    let out = drain(child.stdout.take().map(|p| Box::new(p) as _));
    let err = drain(child.stderr.take().map(|p| Box::new(p) as _));
    let began = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait()? {
            break status;
        }
        if began.elapsed() > RUN_TIMEOUT {
            let _ = child.kill();
            let _ = child.wait();
            return Err(std::io::Error::new(
                std::io::ErrorKind::TimedOut,
                format!(
                    "the run took longer than {} s and was ended",
                    RUN_TIMEOUT.as_secs()
                ),
            ));
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    Ok(std::process::Output {
        status,
        stdout: out.join().unwrap_or_default(),
        stderr: err.join().unwrap_or_default(),
    })
}

/// `ilmrc`: the configured path, else beside this server's executable (where cargo
/// and `cargo install` put both), else on `PATH`.
pub fn find_ilmrc(configured: Option<&str>) -> PathBuf {
    if let Some(c) = configured.filter(|c| !c.trim().is_empty()) {
        return PathBuf::from(c);
    }
    let beside = std::env::current_exe().ok().and_then(|exe| {
        exe.parent()
            .map(|d| d.join(format!("ilmrc{}", std::env::consts::EXE_SUFFIX)))
    });
    match beside {
        Some(p) if p.is_file() => p,
        _ => PathBuf::from("ilmrc"),
    }
}

/// The `--skills` argument for a workspace's skill files: the one file, or the one
/// directory that holds them all and no task file; `None` with a note otherwise.
pub fn skills_argument(
    skill_files: &[PathBuf],
    task_files: &[PathBuf],
) -> Result<Option<PathBuf>, String> {
    match skill_files {
        [] => Ok(None),
        [one] => Ok(Some(one.clone())),
        many => {
            let dir = many[0].parent().map(Path::to_path_buf);
            let same = many
                .iter()
                .all(|f| f.parent().map(Path::to_path_buf) == dir);
            let tasks_there = task_files
                .iter()
                .any(|t| t.parent().map(Path::to_path_buf) == dir);
            match dir {
                Some(d) if same && !tasks_there => Ok(Some(d)),
                _ => Err(format!(
                    "the workspace's {} skill files are not alone in one directory, which `ilmrc run --skills` takes; the task ran without them",
                    many.len()
                )),
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const TRACE: &str = r#"{"t":0,"event":"trace","version":1}
{"t":0,"event":"issue","line":1,"text":"goahead(1)"}
{"t":0,"event":"issue","line":2,"text":"turn(left)"}
{"t":2.5,"event":"end","line":1,"text":"goahead(1)","how":"completed"}
{"t":2.5,"event":"start","line":2,"text":"turn(left)"}
{"t":6.25,"event":"end","line":2,"text":"turn(left)","how":"completed"}
{"t":0.01,"event":"issue","line":1,"text":"speed(0.3)"}
{"t":7,"event":"end","line":2,"text":"turn(left)","file":"skills/turns.ilms","how":"completed"}
"#;

    #[test]
    fn times_by_line_from_the_trace_of_this_text() {
        let times = times(TRACE, "goahead(1)\nturn(left)\n").unwrap();
        assert_eq!(times.len(), 2, "{times:?}");
        assert_eq!(times[&1].label(), "ran t=0.00–2.50 s");
        // Issued at 0, started at 2.5 when the reservation came; the skill's
        // `turn(left)` on its own line 2 ended later, which is not this line's end.
        assert_eq!(times[&2].label(), "ran t=2.50–6.25 s");
    }

    #[test]
    fn the_summary_starts_at_its_first_line_after_the_checks_diagnostics() {
        let out = "[W0502] Warning: `f` is bound but never used\n/w/t.ilmr:6:1\n1 file(s) checked\n/w/t.ilmr: finished: no command left\n  exit            0\n";
        let s = summary(out, Path::new("/w/t.ilmr"));
        assert_eq!(
            s,
            "/w/t.ilmr: finished: no command left\n  exit            0"
        );
        assert_eq!(
            summary("no summary\n", Path::new("/w/t.ilmr")),
            "no summary"
        );
    }

    #[test]
    fn an_ilmrc_that_cannot_start_is_said_in_the_summary() {
        let inv = Invocation {
            ilmrc: PathBuf::from("/nonexistent/ilmrc"),
            task: PathBuf::from("/nonexistent/task.ilmr"),
            robot: "moro".into(),
            skills: None,
        };
        let last = run(&inv, "goahead(1)\n");
        assert!(
            last.summary
                .starts_with("cannot run `/nonexistent/ilmrc`: "),
            "{}",
            last.summary
        );
        assert_eq!(last.exit, None);
        assert!(last.times.is_empty());
    }

    #[test]
    fn a_trace_without_its_version_line_is_an_error() {
        assert!(
            times(
                "{\"t\":0,\"event\":\"issue\",\"line\":1,\"text\":\"x\"}\n",
                "x"
            )
            .is_err()
        );
    }

    #[test]
    fn skills_are_one_file_or_one_directory_of_skill_files_only() {
        let p = |s: &str| PathBuf::from(s);
        assert_eq!(skills_argument(&[], &[p("/w/t.ilmr")]), Ok(None));
        assert_eq!(
            skills_argument(&[p("/w/s.ilms")], &[p("/w/t.ilmr")]),
            Ok(Some(p("/w/s.ilms")))
        );
        assert_eq!(
            skills_argument(&[p("/w/s/a.ilms"), p("/w/s/b.ilms")], &[p("/w/t.ilmr")]),
            Ok(Some(p("/w/s")))
        );
        assert!(skills_argument(&[p("/w/a.ilms"), p("/w/b.ilms")], &[p("/w/t.ilmr")]).is_err());
    }
}

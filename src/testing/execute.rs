//! One test at one seed: the task run in-process by `ilmrc run`'s own pipeline, its
//! trace read back with `ilmr_trace`, and the assertions evaluated on it.

use std::path::Path;

use clap::Parser;

use super::eval::{Failure, Run};
use super::file::Test;
use crate::run::console::Console;
use crate::run::{Ran, Reached, RunArgs, execute};

/// How one run of a test went.
#[derive(Debug)]
pub enum Verdict {
    Passed,
    /// The assertions that did not hold, by index, and why; how the trace differs from
    /// its snapshot.
    Failed {
        failures: Vec<(usize, Failure)>,
        snapshot: Option<String>,
    },
    /// The task does not check; the log holds the check's diagnostics.
    Rejected,
    /// The run did not start, or its trace could not be read: why.
    Broke(String),
}

pub struct Outcome {
    pub seed: u64,
    pub verdict: Verdict,
    /// What the run said: the check's diagnostics, notices, its summary.
    pub log: String,
}

/// Seconds between the scans kept in a test's trace when an assertion reads them:
/// every scan of the simulated scanner (4 Hz).
const SCAN_EVERY: f64 = 0.25;
/// Otherwise: scans are left out (one at the start is all a run then writes).
const NO_SCANS: f64 = 1e9;

#[derive(Parser)]
#[command(no_binary_name = true)]
struct Argv {
    #[command(flatten)]
    run: RunArgs,
}

/// Runs `test` at `seed`, its trace written to `trace` (removed afterwards).
pub fn run(test: &Test, seed: u64, trace: &Path) -> Outcome {
    let mut console = Console::Kept(String::new());
    let verdict = verdict(test, seed, trace, &mut console);
    let _ = std::fs::remove_file(trace);
    let log = match console {
        Console::Kept(s) => s,
        Console::Terminal => String::new(),
    };
    Outcome { seed, verdict, log }
}

fn verdict(test: &Test, seed: u64, trace: &Path, console: &mut Console) -> Verdict {
    let scans = test
        .assertions
        .iter()
        .any(super::assertion::Assertion::reads_scans);
    let mut argv: Vec<String> = test.argv.clone();
    argv.extend([
        "--seed".into(),
        seed.to_string(),
        // Every tick's pose: a bound on speed or place holds at every sample.
        "--pose-every".into(),
        "1".into(),
        "--scan-every".into(),
        (if scans { SCAN_EVERY } else { NO_SCANS }).to_string(),
        "--trace".into(),
        trace.display().to_string(),
    ]);
    let mut args = match Argv::try_parse_from(&argv) {
        Ok(a) => a.run,
        Err(e) => return Verdict::Broke(e.to_string()),
    };
    args.lines = test.lines.clone();
    let mut reached = Reached::default();
    match execute(&args, &mut reached, console) {
        Ok(Ran::Ended(_)) => {}
        Ok(Ran::Rejected) => return Verdict::Rejected,
        Err(e) => return Verdict::Broke(e),
    }
    let text = match ilmr_files::read_text(trace, ilmr_files::Kind::Trace) {
        Ok(t) => t,
        Err(e) => return Verdict::Broke(format!("cannot read the run's trace: {e}")),
    };
    let records = match ilmr_trace::records(&text).collect::<Result<Vec<_>, _>>() {
        Ok(r) => r,
        Err(e) => return Verdict::Broke(format!("the run's trace: {e}")),
    };
    if let Some(r) = records
        .iter()
        .find(|r| matches!(r.event, ilmr_trace::Event::Truncated(_)))
    {
        return Verdict::Broke(format!(
            "the trace reached its limit at t={}: a shorter `max_time` lets the test see the whole run",
            ilmr_trace::fmt_num(r.t.0)
        ));
    }
    let run = Run::new(&records);
    let failures: Vec<(usize, Failure)> = test
        .assertions
        .iter()
        .enumerate()
        .filter_map(|(i, a)| run.check(a).err().map(|f| (i, f)))
        .collect();
    let snapshot = test.snapshot.as_ref().and_then(|s| {
        super::snapshot::compare(&s.path(seed), &super::snapshot::text(&records, s)).err()
    });
    if failures.is_empty() && snapshot.is_none() {
        Verdict::Passed
    } else {
        Verdict::Failed { failures, snapshot }
    }
}

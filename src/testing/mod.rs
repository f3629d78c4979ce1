//! `ilmrc test`: tests of robot tasks written as TOML files beside them
//! (docs/testing.md). Each test runs its task in-process through `ilmrc run`'s
//! pipeline, once per seed, on the machine's cores; its assertions are evaluated on the
//! run's trace.

mod eval;
mod execute;
mod junit;
mod progress;
mod render;
mod snapshot;
#[cfg(test)]
mod tests;

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use execute::{Outcome, Verdict};
use ilmr_testfile::file::{self, Note, TestFile};
use ilmr_testfile::{assertion, codes, problem};
use render::Style;

use crate::{EXIT_ERRORS, EXIT_USAGE};
use codes::Code;
use problem::Problem;

/// Prints to stdout; a closed stdout (`ilmrc test | head`) is no reason to panic, and
/// the tests go on to their exit code and JUnit file.
macro_rules! say_raw {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = write!(std::io::stdout().lock(), $($arg)*);
    }};
}

macro_rules! say {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stdout().lock(), $($arg)*);
    }};
}

/// The suffix that makes a file a test file when a folder is searched.
pub use ilmr_testfile::SUFFIX;
/// Failing seeds of one test reported in full; the others are counted.
const SEEDS_SHOWN: usize = 3;

#[derive(clap::Args)]
pub struct TestArgs {
    /// Test files, or folders searched for `*.test.toml` files.
    #[arg(required = true)]
    pub paths: Vec<PathBuf>,
    /// Write the results as JUnit XML here.
    #[arg(long, value_name = "OUT.xml")]
    pub junit: Option<PathBuf>,
    /// Show how each pending snapshot of the test files differs from the stored one,
    /// without running the tests.
    #[arg(long, conflicts_with_all = ["accept", "junit"])]
    pub review: bool,
    /// Store each pending snapshot of the test files, without running the tests.
    #[arg(long, conflicts_with = "junit")]
    pub accept: bool,
    /// Runs at once (default: the machine's cores).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=1024))]
    pub jobs: Option<u32>,
}

pub fn run(args: TestArgs) -> ExitCode {
    let started = Instant::now();
    let style = Style::on_terminal(std::io::IsTerminal::is_terminal(&std::io::stdout()));
    let paths = match find(&args.paths) {
        Ok(p) => p,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(EXIT_USAGE);
        }
    };
    let mut files = Vec::new();
    let mut problems = 0;
    for path in &paths {
        let text = match ilmr_files::read_text(path, ilmr_files::Kind::Scenario) {
            Ok(t) => t,
            Err(e) => {
                eprintln!("error: cannot read test file `{}`: {e}", path.display());
                problems += 1;
                continue;
            }
        };
        let read = file::check(path, text.clone());
        for note in &read.notes {
            match note {
                Note::Model { spec, warnings } => crate::inputs::warn_about(spec, warnings),
                Note::SkillsIgnored { dir, files } => crate::inputs::note_ignored(dir, files),
            }
        }
        match read.file {
            Ok(f) => files.push(f),
            Err(ps) => {
                problems += ps.len();
                let shown = path.display().to_string();
                for p in &ps {
                    say_raw!("{}", render::problem(&shown, &text, p, style));
                }
            }
        }
    }
    if problems > 0 {
        say!("{problems} problem(s) in the test files; no test was run");
        return ExitCode::from(EXIT_USAGE);
    }
    if args.review || args.accept {
        return snapshots(&files, args.accept);
    }
    let jobs = args.jobs.map_or_else(
        || std::thread::available_parallelism().map_or(1, |n| n.get()),
        |j| j as usize,
    );
    let results = run_all(&files, jobs, style);
    let elapsed = started.elapsed().as_secs_f64();
    let failed = results.iter().filter(|r| r.failure.is_some()).count();
    let runs: usize = files
        .iter()
        .flat_map(|f| &f.tests)
        .map(|t| t.seeds.len())
        .sum();
    say!(
        "\ntest result: {}. {} passed; {failed} failed; {runs} run(s) in {elapsed:.2} s",
        if failed == 0 { "ok" } else { "FAILED" },
        results.len() - failed,
    );
    if let Some(out) = &args.junit {
        let cases: Vec<junit::Case> = results
            .iter()
            .map(|r| junit::Case {
                file: &r.file,
                name: &r.name,
                seconds: r.seconds,
                failure: r.failure.clone(),
            })
            .collect();
        if let Err(e) = std::fs::write(out, junit::write(&cases, elapsed)) {
            eprintln!("error: cannot write `{}`: {e}", out.display());
            return ExitCode::from(EXIT_USAGE);
        }
    }
    ExitCode::from(if failed == 0 { 0 } else { EXIT_ERRORS })
}

/// `--review` and `--accept`: each pending snapshot of the files shown, or stored.
fn snapshots(files: &[TestFile], accept: bool) -> ExitCode {
    let mut count = 0;
    for f in files {
        let pending = match snapshot::pending(&f.path) {
            Ok(p) => p,
            Err(e) => {
                eprintln!("error: {e}");
                return ExitCode::from(EXIT_USAGE);
            }
        };
        for p in pending {
            count += 1;
            if !accept {
                say_raw!("{}", snapshot::review(&p));
                continue;
            }
            match snapshot::accept(&p) {
                Ok(stored) => say!("stored {}", stored.display()),
                Err(e) => {
                    eprintln!("error: {e}");
                    return ExitCode::from(EXIT_USAGE);
                }
            }
        }
    }
    say!(
        "{count} pending snapshot(s){}",
        if accept { " stored" } else { "" }
    );
    ExitCode::SUCCESS
}

/// The test files named, folders searched (in name order) for [`SUFFIX`].
fn find(paths: &[PathBuf]) -> Result<Vec<PathBuf>, String> {
    let mut out = Vec::new();
    for p in paths {
        if p.is_dir() {
            let before = out.len();
            walk(p, &mut out).map_err(|e| format!("cannot read `{}`: {e}", p.display()))?;
            if out.len() == before {
                return Err(format!("no `*{SUFFIX}` file under `{}`", p.display()));
            }
        } else if p.exists() {
            out.push(p.clone());
        } else {
            return Err(format!("no file or folder `{}`", p.display()));
        }
    }
    Ok(out)
}

fn walk(dir: &Path, out: &mut Vec<PathBuf>) -> std::io::Result<()> {
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)?
        .map(|e| e.map(|e| e.path()))
        .collect::<Result<_, _>>()?;
    entries.sort();
    for p in entries {
        let name = p.file_name().map(|n| n.to_string_lossy().into_owned());
        if p.is_dir() {
            // Links to folders are not followed: a loop of links would never end.
            if !std::fs::symlink_metadata(&p).is_ok_and(|m| m.file_type().is_symlink()) {
                walk(&p, out)?;
            }
        } else if name.is_some_and(|n| n.ends_with(SUFFIX)) {
            out.push(p);
        }
    }
    Ok(())
}

/// One test's result, for the summary and the XML.
struct TestResult {
    file: String,
    name: String,
    seconds: f64,
    /// One line saying why, and the whole report.
    failure: Option<(String, String)>,
}

/// One run: which test (by file, by its place in the file, and in the order the
/// tests are printed), which seed.
struct Job {
    file: usize,
    test: usize,
    order: usize,
    seed: u64,
}

/// Runs every test's seeds on `jobs` threads; prints each test's line (and the report
/// of one that failed) in file order as soon as its runs are done.
fn run_all(files: &[TestFile], jobs: usize, style: Style) -> Vec<TestResult> {
    let mut queue = Vec::new();
    let mut order = Vec::new();
    for (fi, f) in files.iter().enumerate() {
        for (ti, t) in f.tests.iter().enumerate() {
            for &seed in &t.seeds {
                queue.push(Job {
                    file: fi,
                    test: ti,
                    order: order.len(),
                    seed,
                });
            }
            order.push((fi, ti));
        }
    }
    let scratch = std::env::temp_dir().join(format!("ilmrc-test-{}", std::process::id()));
    if let Err(e) = std::fs::create_dir_all(&scratch) {
        eprintln!("error: cannot make `{}`: {e}", scratch.display());
    }
    let next = AtomicUsize::new(0);
    let (tx, rx) = mpsc::channel::<(usize, Outcome, Duration)>();
    let mut done: Vec<Vec<(Outcome, Duration)>> = order.iter().map(|_| Vec::new()).collect();
    let mut results = Vec::new();
    std::thread::scope(|s| {
        for _ in 0..jobs.min(queue.len()).max(1) {
            let tx = tx.clone();
            let (queue, next, scratch) = (&queue, &next, &scratch);
            s.spawn(move || {
                loop {
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    let Some(job) = queue.get(i) else { break };
                    let test = &files[job.file].tests[job.test];
                    let trace = scratch.join(format!("{i}.jsonl"));
                    let t0 = Instant::now();
                    let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                        execute::run(test, job.seed, &trace)
                    }))
                    .unwrap_or_else(|_| Outcome {
                        seed: job.seed,
                        verdict: Verdict::Broke(
                            "the run panicked (a bug of ilmrc; please report it)".into(),
                        ),
                        log: String::new(),
                    });
                    if tx.send((i, outcome, t0.elapsed())).is_err() {
                        break;
                    }
                }
            });
        }
        drop(tx);
        let mut printed = 0;
        let mut finished = 0;
        let mut progress = progress::Progress::on_terminal();
        loop {
            let (i, outcome, took) = match rx.recv_timeout(progress::EVERY) {
                Ok(got) => got,
                Err(mpsc::RecvTimeoutError::Timeout) => {
                    progress.show(finished, queue.len());
                    continue;
                }
                Err(mpsc::RecvTimeoutError::Disconnected) => break,
            };
            finished += 1;
            done[queue[i].order].push((outcome, took));
            while let Some(&(fi, ti)) = order.get(printed) {
                let test = &files[fi].tests[ti];
                if done[printed].len() < test.seeds.len() {
                    break;
                }
                let mut outcomes = std::mem::take(&mut done[printed]);
                outcomes.sort_by_key(|(o, _)| test.seeds.iter().position(|&s| s == o.seed));
                progress.clear();
                results.push(report(&files[fi], test, &outcomes, style));
                printed += 1;
            }
            progress.show(finished, queue.len());
        }
        progress.clear();
    });
    let _ = std::fs::remove_dir_all(&scratch);
    results
}

/// Prints a test's line, and the report of its failing seeds; returns its result.
fn report(
    file: &TestFile,
    test: &file::Test,
    outcomes: &[(Outcome, Duration)],
    style: Style,
) -> TestResult {
    let seconds: f64 = outcomes.iter().map(|(_, d)| d.as_secs_f64()).sum();
    let path = file.path.display().to_string();
    let failing: Vec<&Outcome> = outcomes
        .iter()
        .map(|(o, _)| o)
        .filter(|o| !matches!(o.verdict, Verdict::Passed))
        .collect();
    let seeds = match test.seeds.as_slice() {
        [one] => format!("seed {one}"),
        many => format!("{} seeds", many.len()),
    };
    let status = if failing.is_empty() {
        "ok    "
    } else {
        "FAILED"
    };
    say!("{status} {path}: {} ({seeds}) {seconds:.2} s", test.name);
    if failing.is_empty() {
        return TestResult {
            file: path,
            name: test.name.clone(),
            seconds,
            failure: None,
        };
    }
    let mut text = String::new();
    for o in failing.iter().take(SEEDS_SHOWN) {
        text.push_str(&failure(file, test, o, style));
    }
    if failing.len() > SEEDS_SHOWN {
        text.push_str(&format!(
            "... and {} more failing seed(s): {}\n",
            failing.len() - SEEDS_SHOWN,
            failing[SEEDS_SHOWN..]
                .iter()
                .map(|o| o.seed.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    say_raw!("{text}");
    let first = failing[0];
    let why = match &first.verdict {
        Verdict::Failed { failures, snapshot } => match (failures.first(), snapshot) {
            (Some((i, fail)), _) => format!(
                "{} (seed {}): {}",
                test.assertions[*i].text, first.seed, fail.message
            ),
            (None, Some(miss)) => format!("seed {}: {miss}", first.seed),
            (None, None) => String::new(),
        },
        Verdict::Rejected => "the task does not check".to_string(),
        Verdict::Broke(m) => m.clone(),
        Verdict::Passed => String::new(),
    };
    TestResult {
        file: path,
        name: test.name.clone(),
        seconds,
        failure: Some((
            format!(
                "{} of {} seed(s) failed: {why}",
                failing.len(),
                outcomes.len()
            ),
            render::strip_ansi(&text),
        )),
    }
}

/// The report of one failing seed: each assertion that failed against the test file,
/// then what the run said.
fn failure(file: &TestFile, test: &file::Test, o: &Outcome, style: Style) -> String {
    let path = file.path.display().to_string();
    let mut out = String::new();
    let at_name = |code: Code, head: &str, label: &str| {
        let p = Problem::new(code, test.span.clone(), label);
        render::report(&path, &file.text, head, &p, style)
    };
    match &o.verdict {
        Verdict::Passed => return out,
        Verdict::Failed { failures, snapshot } => {
            if let (Some(miss), Some(s)) = (snapshot, &test.snapshot) {
                let p = Problem::new(Code::SnapshotDiffers, s.span.clone(), miss.clone()).help(
                    format!(
                        "see the difference with `ilmrc test --review {0}`, keep the run's with `ilmrc test --accept {0}`",
                        file.path.display()
                    ),
                );
                let head = format!("the trace is not its snapshot (seed {})", o.seed);
                out.push_str(&render::report(&path, &file.text, &head, &p, style));
            }
            for (i, f) in failures {
                let a = &test.assertions[*i];
                let head = format!(
                    "assertion failed at t={} s (seed {})",
                    ilmr_trace::fmt_num(f.t),
                    o.seed
                );
                let p = Problem::new(Code::Failed, a.span.clone(), f.message.clone());
                out.push_str(&render::report(&path, &file.text, &head, &p, style));
            }
        }
        Verdict::Rejected => out.push_str(&at_name(
            Code::TaskRejected,
            &format!("the task does not check (seed {})", o.seed),
            "the check's diagnostics follow",
        )),
        Verdict::Broke(why) => out.push_str(&at_name(
            Code::RunFailed,
            &format!("the run did not go through (seed {})", o.seed),
            why,
        )),
    }
    if !o.log.is_empty() {
        out.push_str(&format!("  --- what the run said (seed {}) ---\n", o.seed));
        for line in o.log.lines() {
            out.push_str("  ");
            out.push_str(line);
            out.push('\n');
        }
    }
    out
}

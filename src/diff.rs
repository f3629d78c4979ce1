//! `ilmrc diff A.jsonl B.jsonl`: where two traces of a task part ways, and what that
//! changed. The first event that differs (its time, both lines and the statement),
//! then the commands whose end moved or whose outcome changed, and the largest
//! distance between the two robots at a pose sample both traces have. Exit 0 when the
//! runs are the same event for event, 1 when they differ, 2 when a file is not a trace.
//!
//! The traces' `run` lines (task, robot, world, seed) are compared apart: two seeds of
//! one task are the usual question, and their headers always differ.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use ilmr_trace::{Event, How, Record, Stmt, fmt_num, to_line};

#[derive(clap::Args)]
pub struct DiffArgs {
    /// A trace written by `ilmrc run --trace` (or `ilmrc test`'s snapshots).
    pub a: PathBuf,
    /// The trace to compare it with.
    pub b: PathBuf,
    /// Draw both trajectories over A's world, with speed and curvature below (SVG).
    #[arg(long)]
    pub plot: Option<PathBuf>,
}

pub fn run(args: DiffArgs) -> ExitCode {
    let texts = [read(&args.a), read(&args.b)];
    let [a, b] = match texts {
        [Ok(a), Ok(b)] => [a, b],
        [a, b] => {
            for e in [a.err(), b.err()].into_iter().flatten() {
                eprintln!("error: {e}");
            }
            return ExitCode::from(crate::EXIT_USAGE);
        }
    };
    let (ra, rb) = match (records(&args.a, &a), records(&args.b, &b)) {
        (Ok(ra), Ok(rb)) => (ra, rb),
        (ra, rb) => {
            for e in [ra.err(), rb.err()].into_iter().flatten() {
                eprintln!("error: {e}");
            }
            return ExitCode::from(crate::EXIT_USAGE);
        }
    };
    let report = compare(&ra, &rb);
    print!("{}", report.render(&args.a, &args.b));
    if let Some(out) = &args.plot {
        if let Err(e) = plot_both([(&args.a, &a), (&args.b, &b)], out) {
            eprintln!("error: {e}");
            return ExitCode::from(crate::EXIT_USAGE);
        }
        println!("drew both runs: {}", out.display());
    }
    if report.same() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(crate::EXIT_ERRORS)
    }
}

/// Both runs' trajectories, A's in the palette's first colour and B's in its second,
/// over A's world, with both runs' speed and curvature below.
fn plot_both(runs: [(&Path, &str); 2], out: &Path) -> Result<(), String> {
    use ilmr_plot::{Colour, Corner, Figure, RunRecord, Scenery, Track};
    let [(a, _), (b, _)] = runs;
    let mut figure = Figure::new(format!("{} (A) and {} (B)", a.display(), b.display()));
    for (i, (path, text)) in runs.into_iter().enumerate() {
        let record = RunRecord::from_jsonl(text)
            .map_err(|e| format!("`{}` is not a trace of ilmrc run: {e}", path.display()))?;
        if i == 0 {
            figure
                .scenery
                .extend(record.world()?.map(|world| Scenery { world, tint: None }));
        }
        figure.tracks.push(Track {
            label: Some(format!("{} {}", ["A", "B"][i], path.display())),
            colour: Colour::palette(i),
            samples: record.poses,
        });
    }
    if figure.tracks.iter().all(|t| t.samples.is_empty()) {
        return Err(
            "neither trace has pose samples to draw (a run with --robot none has none)".into(),
        );
    }
    figure.time_series = true;
    figure.legend = Corner::Quietest;
    figure.write_svg(out)
}

fn read(path: &Path) -> Result<String, String> {
    ilmr_files::read_text(path, ilmr_files::Kind::Trace)
        .map_err(|e| format!("cannot read trace `{}`: {e}", path.display()))
}

fn records<'a>(path: &Path, text: &'a str) -> Result<Vec<Record<'a>>, String> {
    ilmr_trace::records(text)
        .collect::<Result<_, _>>()
        .map_err(|e| format!("`{}` is not a trace of ilmrc run: {e}", path.display()))
}

/// How two traces differ.
#[derive(Debug, Default)]
pub struct Report {
    /// The header lines, when they differ.
    headers: Option<(String, String)>,
    first: Option<Parting>,
    ends: Vec<Moved>,
    pose: Option<Apart>,
    poses_compared: usize,
    events: (usize, usize),
}

/// Characters of a trace line shown: a scan's line runs to kilobytes.
pub const SHOWN: usize = 240;

fn shortened(line: &str) -> String {
    match line.char_indices().nth(SHOWN) {
        Some((cut, _)) => format!(
            "{}... ({} more characters)",
            &line[..cut],
            line[cut..].chars().count()
        ),
        None => line.to_string(),
    }
}

/// The first pair of events that differ (headers left out).
#[derive(Debug)]
struct Parting {
    /// 1-based, among the events.
    index: usize,
    /// Each side's line; `None` on the side whose trace ended first.
    a: Option<String>,
    b: Option<String>,
    t: f64,
    stmt: Option<String>,
}

/// How and when a command ended, if it did.
type Ended = Option<(How, f64)>;

/// A command whose end changed.
#[derive(Debug)]
struct Moved {
    what: String,
    a: Ended,
    b: Ended,
}

/// The largest distance between the robots at a sample time both traces have.
#[derive(Debug, Clone, Copy)]
struct Apart {
    metres: f64,
    t: f64,
    a: (f64, f64),
    b: (f64, f64),
}

/// Lines that say how the run was set up or what it received rather than what the
/// task did: the header, and the inputs of a run that recorded them.
fn is_header(r: &Record<'_>) -> bool {
    matches!(
        r.event,
        Event::Trace(_) | Event::Run(_) | Event::Tape(_) | Event::Input(_)
    )
}

fn stmt_of<'r>(e: &'r Event<'_>) -> Option<&'r Stmt<'r>> {
    match e {
        Event::Issue(x) => x.stmt.as_ref(),
        Event::Start(x) => x.stmt.as_ref(),
        Event::End(x) => x.stmt.as_ref(),
        Event::Var(x) => x.stmt.as_ref(),
        Event::Path(x) => x.stmt.as_ref(),
        Event::Avoid(x) => x.stmt.as_ref(),
        Event::Fault(x) => x.stmt.as_ref(),
        Event::Recovered(x) => x.stmt.as_ref(),
        Event::Overrun(x) => x.stmt.as_ref(),
        Event::Error(x) => x.stmt.as_ref(),
        _ => None,
    }
}

fn describe(s: &Stmt<'_>) -> String {
    match &s.file {
        Some(file) => format!("line {} of {file} `{}`", s.line, s.text),
        None => format!("line {} `{}`", s.line, s.text),
    }
}

/// A command: its file (none for the task's), line and text.
type Command = (Option<String>, u32, String);

/// Each command's ends in order: the command and its n-th end, to how and when. The
/// task's commands sort first, by line.
fn ends(records: &[Record<'_>]) -> BTreeMap<(Command, usize), (How, f64)> {
    let mut seen: BTreeMap<Command, usize> = BTreeMap::new();
    let mut out = BTreeMap::new();
    for r in records {
        if let Event::End(e) = &r.event
            && let Some(s) = &e.stmt
        {
            let key = (
                s.file.as_ref().map(|f| f.to_string()),
                s.line,
                s.text.to_string(),
            );
            let n = seen.entry(key.clone()).or_default();
            out.insert((key, *n), (e.how, r.t.0));
            *n += 1;
        }
    }
    out
}

/// Pose samples by time, in ten-thousandths of a second (the trace's precision).
fn poses(records: &[Record<'_>]) -> BTreeMap<i64, (f64, f64)> {
    records
        .iter()
        .filter_map(|r| match &r.event {
            Event::Pose(p) => Some(((r.t.0 * 1e4).round() as i64, (p.x.0, p.y.0))),
            _ => None,
        })
        .collect()
}

pub fn compare(a: &[Record<'_>], b: &[Record<'_>]) -> Report {
    let header = |rs: &[Record<'_>]| {
        rs.iter()
            .filter(|r| matches!(r.event, Event::Run(_)))
            .map(to_line)
            .next()
            .unwrap_or_default()
    };
    let (ha, hb) = (header(a), header(b));
    let ea: Vec<&Record<'_>> = a.iter().filter(|r| !is_header(r)).collect();
    let eb: Vec<&Record<'_>> = b.iter().filter(|r| !is_header(r)).collect();
    let mut report = Report {
        headers: (ha != hb).then_some((ha, hb)),
        events: (ea.len(), eb.len()),
        ..Report::default()
    };
    let first = (0..ea.len().max(eb.len())).find(|&i| ea.get(i) != eb.get(i));
    if let Some(i) = first {
        let (x, y) = (ea.get(i), eb.get(i));
        let t = x.or(y).map_or(0.0, |r| r.t.0);
        let stmt = x
            .and_then(|r| stmt_of(&r.event))
            .or_else(|| y.and_then(|r| stmt_of(&r.event)))
            .map(describe);
        report.first = Some(Parting {
            index: i + 1,
            a: x.map(|r| to_line(r)),
            b: y.map(|r| to_line(r)),
            t,
            stmt,
        });
    }
    let (na, nb) = (ends(a), ends(b));
    let keys: std::collections::BTreeSet<_> = na.keys().chain(nb.keys()).cloned().collect();
    for key in keys {
        let (x, y) = (na.get(&key).copied(), nb.get(&key).copied());
        let moved = match (x, y) {
            (Some((h1, t1)), Some((h2, t2))) => h1 != h2 || (t1 - t2).abs() > 1e-9,
            _ => true,
        };
        if moved {
            let ((file, line, text), n) = key;
            let what = describe(&Stmt {
                line,
                text: text.into(),
                file: file.map(Into::into),
            });
            let what = if n > 0 {
                format!("{what} (end {})", n + 1)
            } else {
                what
            };
            report.ends.push(Moved { what, a: x, b: y });
        }
    }
    let (pa, pb) = (poses(a), poses(b));
    for (k, &(x1, y1)) in &pa {
        if let Some(&(x2, y2)) = pb.get(k) {
            report.poses_compared += 1;
            let d = (x1 - x2).hypot(y1 - y2);
            if report.pose.is_none_or(|best| d > best.metres) {
                report.pose = Some(Apart {
                    metres: d,
                    t: *k as f64 / 1e4,
                    a: (x1, y1),
                    b: (x2, y2),
                });
            }
        }
    }
    report
}

impl Report {
    pub fn same(&self) -> bool {
        self.first.is_none()
    }

    pub fn render(&self, a: &Path, b: &Path) -> String {
        let (an, bn) = (a.display(), b.display());
        let mut s = String::new();
        if let Some((ha, hb)) = &self.headers {
            s.push_str(&format!(
                "the runs differ:\n  A: {}\n  B: {}\n",
                shortened(ha),
                shortened(hb)
            ));
        }
        let Some(Parting {
            index: i,
            a: x,
            b: y,
            t,
            stmt,
        }) = &self.first
        else {
            s.push_str(&format!(
                "A ({an}) and B ({bn}) are the same run: {} events\n",
                self.events.0
            ));
            return s;
        };
        s.push_str(&format!(
            "A ({an}) and B ({bn}) part ways at t={} (event {i} of {} and {}):\n",
            fmt_num(*t),
            self.events.0,
            self.events.1
        ));
        let side = |r: &Option<String>| {
            r.as_deref()
                .map_or_else(|| "(its trace has ended)".into(), shortened)
        };
        s.push_str(&format!("  A: {}\n  B: {}\n", side(x), side(y)));
        if let Some(stmt) = stmt {
            s.push_str(&format!("  statement: {stmt}\n"));
        }
        let end = |e: &Ended| match e {
            Some((how, t)) => format!("{} at t={}", how.name(), fmt_num(*t)),
            None => "never ended".to_string(),
        };
        if self.ends.is_empty() {
            s.push_str("every command ended the same way at the same time\n");
        } else {
            s.push_str(&format!(
                "commands whose end changed ({}):\n",
                self.ends.len()
            ));
            for m in &self.ends {
                s.push_str(&format!("  {}: A {}, B {}\n", m.what, end(&m.a), end(&m.b)));
            }
        }
        match self.pose {
            Some(p) => s.push_str(&format!(
                "largest pose difference: {} m at t={} (A at {}, {}; B at {}, {}), of {} samples both have\n",
                fmt_num(p.metres),
                fmt_num(p.t),
                fmt_num(p.a.0),
                fmt_num(p.a.1),
                fmt_num(p.b.0),
                fmt_num(p.b.1),
                self.poses_compared
            )),
            None => s.push_str("no pose sample at a time both traces have\n"),
        }
        s
    }
}

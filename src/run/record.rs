//! The run's own trace events, beside the VM's, for a simulated robot: a `run` header
//! (robot, world, seed, start), `mark`s (the true pose where a movement command started
//! and ended) and `scan`s (scanner hits in the world frame). With them a trace holds
//! everything `ilmrc replay` needs to draw the run again.
//!
//! ```json
//! {"t":0,"event":"run","task":"examples/short_task.ilmr","robot":"moro","world":"office","seed":0,"start":{"x":19.5,"y":5.5,"h":0}}
//! {"t":0.01,"event":"mark","line":4,"text":"goahead(1.2)","at":"start","x":19.5,"y":5.5,"h":0}
//! {"t":1,"event":"scan","x":20.2,"y":5.5,"h":0,"hits":[[20.5,4.08],[20.51,4.08]]}
//! ```
//!
//! Headings are radians, as in the VM's `pose` events. A world read from a file is
//! carried whole (`world_toml`); a shipped one by its name.
//!
//! A trace file stops growing at [`MAX_TRACE_BYTES`], what `ilmrc replay` reads: its
//! last line is then a `truncated` event, and stderr says so once. The run goes on
//! (a robot is not stopped because its log is full).

use std::borrow::Cow;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, PoisonError};

use ilmr_files::MAX_TRACE_BYTES;
use ilmr_hal::Pose;
use ilmr_trace::{At, Event as Line, Failed, Mark, Moment, Num, Record, Scan, Truncated};
use ilmr_vm::{Event, EventKind, Module};

use super::RunArgs;
use super::backend::WorldScan;
use super::setup::{Backend, Setup};
use ilmr_plot::RunRecord;

/// Where the trace lines go: the `--trace` file, and the record the plot is drawn
/// from (built from the very lines `ilmrc replay` reads, so both draw the same).
pub struct Sink {
    file: Option<TraceFile>,
    record: Option<RunRecord>,
    /// The line being written, kept from line to line so that writing one allocates
    /// nothing.
    buf: Vec<u8>,
}

/// Room kept under the cap for the `truncated` line, so that the whole file stays
/// within it.
const TRUNCATED_ROOM: u64 = 256;

struct TraceFile {
    path: PathBuf,
    out: Box<dyn Write + Send>,
    written: u64,
    cap: u64,
    /// The cap was reached: nothing more is written.
    full: bool,
}

impl TraceFile {
    /// Writes one line (`line`, without its newline), of time `t`.
    fn line(&mut self, line: &[u8], t: f64) -> Result<(), String> {
        if self.full {
            return Ok(());
        }
        let len = line.len() as u64 + 1;
        let fail = |e: std::io::Error, path: &Path| {
            format!("cannot write trace `{}`: {e}", path.display())
        };
        if self.written + len + TRUNCATED_ROOM > self.cap {
            self.full = true;
            let note = ilmr_trace::to_line(&truncated(t, self.cap));
            writeln!(self.out, "{note}").map_err(|e| fail(e, &self.path))?;
            self.written += note.len() as u64 + 1;
            eprintln!(
                "warning: the trace `{}` reached {}, its limit (MAX_TRACE_BYTES); the rest of the run is not in it",
                self.path.display(),
                size(self.cap)
            );
            return Ok(());
        }
        self.out
            .write_all(line)
            .and_then(|()| self.out.write_all(b"\n"))
            .map_err(|e| fail(e, &self.path))?;
        self.written += len;
        Ok(())
    }
}

/// The `truncated` event that ends a trace cut at its cap.
fn truncated(t: f64, cap: u64) -> Record<'static> {
    Record::new(
        t,
        Line::Truncated(Truncated {
            limit: cap,
            message: format!(
                "the trace reached {}, its limit (MAX_TRACE_BYTES); the rest of the run is not in it",
                size(cap)
            )
            .into(),
        }),
    )
}

fn size(bytes: u64) -> String {
    if bytes >= 1 << 20 && bytes.is_multiple_of(1 << 20) {
        format!("{} MiB", bytes >> 20)
    } else {
        format!("{bytes} bytes")
    }
}

fn create(path: &Path, what: &str) -> Result<File, String> {
    File::create(path).map_err(|e| format!("cannot write {what} `{}`: {e}", path.display()))
}

impl Sink {
    /// Opens the outputs and writes the trace's version line.
    pub fn open(trace: Option<&Path>, plot: Option<&Path>) -> Result<Sink, String> {
        Sink::capped(trace, plot, MAX_TRACE_BYTES)
    }

    fn capped(trace: Option<&Path>, plot: Option<&Path>, cap: u64) -> Result<Sink, String> {
        let file = match trace {
            Some(p) => Some(TraceFile {
                path: p.to_path_buf(),
                out: Box::new(BufWriter::new(create(p, "trace")?)),
                written: 0,
                cap,
                full: false,
            }),
            None => None,
        };
        Sink::with(file, plot)
    }

    /// A sink whose trace goes into `kept` rather than a file (a replay compares it
    /// with the recording before it writes it anywhere).
    pub fn in_memory(kept: Kept, plot: Option<&Path>) -> Result<Sink, String> {
        let file = TraceFile {
            path: PathBuf::from("(the replayed trace)"),
            out: Box::new(kept),
            written: 0,
            cap: MAX_TRACE_BYTES,
            full: false,
        };
        Sink::with(Some(file), plot)
    }

    fn with(file: Option<TraceFile>, plot: Option<&Path>) -> Result<Sink, String> {
        if let Some(p) = plot {
            create(p, "plot")?;
        }
        let mut sink = Sink {
            file,
            record: plot.map(|_| RunRecord::default()),
            buf: Vec::with_capacity(256),
        };
        sink.put(&Record::header())?;
        Ok(sink)
    }

    pub fn wants_poses(&self) -> bool {
        self.file.is_some() || self.record.is_some()
    }

    /// Writes one line to the trace and the plot's record.
    pub fn put(&mut self, record: &Record<'_>) -> Result<(), String> {
        let Sink {
            file,
            record: plot,
            buf,
        } = self;
        buf.clear();
        ilmr_trace::write_line(&mut *buf, record)
            .map_err(|e| format!("cannot write a trace line: {e}"))?;
        if let Some(f) = file.as_mut() {
            f.line(buf, record.t.0)?;
        }
        if let Some(r) = plot.as_mut() {
            // serde_json writes UTF-8.
            let line = std::str::from_utf8(buf).unwrap_or_default();
            r.absorb(line)
                .map_err(|e| format!("the trace for the plot: {e}"))?;
        }
        Ok(())
    }

    /// Flushes the trace; returns the record for the plot.
    pub fn finish(self) -> Result<Option<RunRecord>, String> {
        if let Some(mut f) = self.file {
            f.out
                .flush()
                .map_err(|e| format!("cannot write trace `{}`: {e}", f.path.display()))?;
        }
        Ok(self.record)
    }
}

/// A trace kept in memory, shared by the sink that writes it and whoever reads it
/// once the run is over.
#[derive(Clone, Default)]
pub struct Kept(Arc<Mutex<Vec<u8>>>);

impl Kept {
    pub fn take(&self) -> Vec<u8> {
        std::mem::take(&mut *self.0.lock().unwrap_or_else(PoisonError::into_inner))
    }
}

impl Write for Kept {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.0
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .extend_from_slice(buf);
        Ok(buf.len())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

/// The `run` header of a simulated run; `None` for the other backends, whose traces
/// stay as they were.
pub fn header(setup: &Setup, args: &RunArgs) -> Option<Record<'static>> {
    let Backend::Sim(_) = setup.backend else {
        return None;
    };
    let world = setup.world.as_ref()?;
    let shipped = ilmr_sim::world::SHIPPED
        .iter()
        .any(|(n, _)| *n == world.name);
    Some(Record::new(
        0.0,
        Line::Run(ilmr_trace::Run {
            task: args.task.display().to_string().into(),
            robot: setup.model_spec.clone().into(),
            world: world.name.clone().into(),
            seed: args.seed,
            profile: (setup.profile != ilmr_sim::SimProfile::Basic)
                .then(|| setup.profile.name().into()),
            start: At {
                x: Num(world.world.start.x),
                y: Num(world.world.start.y),
                h: Num(world.world.start.h),
            },
            world_toml: (!shipped).then(|| world.text.clone().into()),
        }),
    ))
}

/// The whole trace of a run that failed before it started: the version line, its
/// `run` line when the robot and world were known, then a `failed` event with the
/// reason and exit code.
pub fn write_failure(
    path: &Path,
    header: Option<&Record<'_>>,
    reason: &str,
    exit: u8,
) -> Result<(), String> {
    let failed = Record::new(
        0.0,
        Line::Failed(Failed {
            reason: reason.into(),
            exit,
        }),
    );
    let mut text = String::new();
    for line in [Some(&Record::header()), header, Some(&failed)]
        .into_iter()
        .flatten()
    {
        text.push_str(&ilmr_trace::to_line(line));
        text.push('\n');
    }
    std::fs::write(path, text).map_err(|e| format!("cannot write trace `{}`: {e}", path.display()))
}

/// Produces `mark` and `scan` lines tick by tick.
pub struct Extra {
    /// Per statement: whether it issues a movement command.
    movement: Vec<bool>,
    scan_every: f64,
    next_scan: f64,
}

impl Extra {
    pub fn new(module: &Module, scan_every: f64) -> Extra {
        let mut extra = Extra {
            movement: Vec::new(),
            scan_every,
            next_scan: 0.0,
        };
        extra.learn(module);
        extra
    }

    /// Per statement: whether it issues a movement command.
    pub fn movement(&self) -> &[bool] {
        &self.movement
    }

    /// Learns the statements an interactive line added.
    pub fn learn(&mut self, module: &Module) {
        self.movement = module.movement_statements();
    }

    /// The tick's lines, after the VM's events of the same tick. Nothing without a
    /// true pose (a robot with no world).
    pub fn lines<'m>(
        &mut self,
        module: &'m Module,
        events: &[Event],
        pose: Option<Pose>,
        scan: Option<&WorldScan>,
    ) -> Vec<Record<'m>> {
        let Some(p) = pose else {
            return Vec::new();
        };
        let mut out = Vec::new();
        for e in events {
            let Some(stmt) = e.stmt else { continue };
            if !self.movement.get(stmt.index()).copied().unwrap_or(false) {
                continue;
            }
            let (at, how) = match &e.kind {
                EventKind::Start { .. } => (Moment::Start, None),
                EventKind::End { how, .. } => (Moment::End, Some(*how)),
                _ => continue,
            };
            let Some(s) = module.stmt(stmt) else { continue };
            out.push(Record::new(
                e.t,
                Line::Mark(Mark {
                    line: s.line,
                    text: Cow::Borrowed(&s.text),
                    at,
                    x: Num(p.x),
                    y: Num(p.y),
                    h: Num(p.h),
                    how,
                }),
            ));
        }
        if let Some(scan) = scan.filter(|s| s.t >= self.next_scan - 1e-9) {
            self.next_scan = (scan.t / self.scan_every).floor() * self.scan_every + self.scan_every;
            out.push(scan_line(scan));
        }
        out
    }
}

/// Hits to the centimetre: what a plot can show, and a fifth of the digits.
fn scan_line(scan: &WorldScan) -> Record<'static> {
    let cm = |v: f64| (v * 100.0).round() / 100.0;
    let hits: Vec<(f64, f64)> = scan.hits().map(|(x, y)| (cm(x), cm(y))).collect();
    Record::new(
        scan.t,
        Line::Scan(Scan {
            x: Num(scan.origin.x),
            y: Num(scan.origin.y),
            h: Num(scan.origin.h),
            hits: hits.into(),
        }),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_trace_stops_at_its_cap_with_a_truncated_line() {
        let dir = std::env::temp_dir().join(format!("ilmr-trace-cap-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        let path = dir.join("t.jsonl");
        let cap = 4096;
        let mut sink = Sink::capped(Some(&path), None, cap).expect("open");
        for i in 0..1000 {
            let issue = Line::Issue(ilmr_trace::Issue {
                stmt: Some(ilmr_trace::Stmt {
                    line: i,
                    text: "x=1".into(),
                    file: None,
                }),
                count: 1,
            });
            sink.put(&Record::new(f64::from(i) + 0.5, issue))
                .expect("a full trace is no error");
        }
        sink.finish().expect("finish");
        let text = std::fs::read_to_string(&path).expect("read back");
        let _ = std::fs::remove_dir_all(&dir);
        assert!(text.len() as u64 <= cap, "{} bytes", text.len());
        assert!(
            text.len() as u64 > cap - TRUNCATED_ROOM - 64,
            "{} bytes",
            text.len()
        );
        let lines: Vec<&str> = text.lines().collect();
        let last = lines.last().expect("lines");
        let kept = lines.len() - 2;
        assert_eq!(lines[0], r#"{"t":0,"event":"trace","version":1}"#);
        assert_eq!(
            *last,
            format!(
                "{{\"t\":{kept}.5,\"event\":\"truncated\",\"limit\":4096,\"message\":\"the trace reached 4096 bytes, its limit (MAX_TRACE_BYTES); the rest of the run is not in it\"}}"
            )
        );
        assert!(lines[1..=kept].iter().all(|l| l.contains("\"issue\"")));
        let v: serde_json::Value = serde_json::from_str(last).expect("JSON");
        assert_eq!(v["event"], "truncated");
    }
}

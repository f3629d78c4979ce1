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

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use ilmr_files::MAX_TRACE_BYTES;
use ilmr_hal::Pose;
use ilmr_vm::runtime::trace::fmt_num;
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
}

/// Room kept under the cap for the `truncated` line, so that the whole file stays
/// within it.
const TRUNCATED_ROOM: u64 = 256;

struct TraceFile {
    path: PathBuf,
    out: BufWriter<File>,
    written: u64,
    cap: u64,
    /// The cap was reached: nothing more is written.
    full: bool,
}

impl TraceFile {
    fn line(&mut self, line: &str) -> Result<(), String> {
        if self.full {
            return Ok(());
        }
        let len = line.len() as u64 + 1;
        let fail = |e: std::io::Error, path: &Path| {
            format!("cannot write trace `{}`: {e}", path.display())
        };
        if self.written + len + TRUNCATED_ROOM > self.cap {
            self.full = true;
            let note = truncated_line(line_time(line), self.cap);
            writeln!(self.out, "{note}").map_err(|e| fail(e, &self.path))?;
            self.written += note.len() as u64 + 1;
            eprintln!(
                "warning: the trace `{}` reached {}, its limit (MAX_TRACE_BYTES); the rest of the run is not in it",
                self.path.display(),
                size(self.cap)
            );
            return Ok(());
        }
        writeln!(self.out, "{line}").map_err(|e| fail(e, &self.path))?;
        self.written += len;
        Ok(())
    }
}

/// The `truncated` event that ends a trace cut at its cap.
fn truncated_line(t: &str, cap: u64) -> String {
    format!(
        "{{\"t\":{t},\"event\":\"truncated\",\"limit\":{cap},\"message\":\"the trace reached {}, its limit (MAX_TRACE_BYTES); the rest of the run is not in it\"}}",
        size(cap)
    )
}

fn size(bytes: u64) -> String {
    if bytes >= 1 << 20 && bytes.is_multiple_of(1 << 20) {
        format!("{} MiB", bytes >> 20)
    } else {
        format!("{bytes} bytes")
    }
}

/// The time of a trace line: every line starts `{"t":` and a number.
fn line_time(line: &str) -> &str {
    line.strip_prefix("{\"t\":")
        .and_then(|rest| rest.split(',').next())
        .filter(|t| {
            !t.is_empty()
                && t.bytes()
                    .all(|b| b.is_ascii_digit() || b == b'.' || b == b'-' || b == b'e')
        })
        .unwrap_or("0")
}

fn create(path: &Path, what: &str) -> Result<File, String> {
    File::create(path).map_err(|e| format!("cannot write {what} `{}`: {e}", path.display()))
}

impl Sink {
    pub fn open(trace: Option<&Path>, plot: Option<&Path>) -> Result<Sink, String> {
        Sink::capped(trace, plot, MAX_TRACE_BYTES)
    }

    fn capped(trace: Option<&Path>, plot: Option<&Path>, cap: u64) -> Result<Sink, String> {
        let file = match trace {
            Some(p) => Some(TraceFile {
                path: p.to_path_buf(),
                out: BufWriter::new(create(p, "trace")?),
                written: 0,
                cap,
                full: false,
            }),
            None => None,
        };
        if let Some(p) = plot {
            create(p, "plot")?;
        }
        Ok(Sink {
            file,
            record: plot.map(|_| RunRecord::default()),
        })
    }

    pub fn wants_poses(&self) -> bool {
        self.file.is_some() || self.record.is_some()
    }

    pub fn line(&mut self, line: &str) -> Result<(), String> {
        if let Some(f) = self.file.as_mut() {
            f.line(line)?;
        }
        if let Some(r) = self.record.as_mut() {
            r.absorb(line)?;
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

/// The `run` header of a simulated run; `None` for the other backends, whose traces
/// stay as they were.
pub fn header(setup: &Setup, args: &RunArgs) -> Option<String> {
    let Backend::Sim(_) = setup.backend else {
        return None;
    };
    let world = setup.world.as_ref()?;
    let s = world.world.start;
    let mut line = format!(
        "{{\"t\":0,\"event\":\"run\",\"task\":{},\"robot\":{},\"world\":{},\"seed\":{},\"start\":{{\"x\":{},\"y\":{},\"h\":{}}}",
        json(&args.task.display().to_string()),
        json(&setup.model_spec),
        json(&world.name),
        args.seed,
        fmt_num(s.x),
        fmt_num(s.y),
        fmt_num(s.h)
    );
    let shipped = ilmr_sim::world::SHIPPED
        .iter()
        .any(|(n, _)| *n == world.name);
    if !shipped {
        line.push_str(&format!(",\"world_toml\":{}", json(&world.text)));
    }
    line.push('}');
    Some(line)
}

/// The whole trace of a run that failed before it started: its `run` line when the
/// robot and world were known, then a `failed` event with the reason and exit code.
pub fn write_failure(
    path: &Path,
    header: Option<&str>,
    reason: &str,
    exit: u8,
) -> Result<(), String> {
    let mut text = String::new();
    if let Some(h) = header {
        text.push_str(h);
        text.push('\n');
    }
    text.push_str(&format!(
        "{{\"t\":0,\"event\":\"failed\",\"reason\":{},\"exit\":{exit}}}\n",
        json(reason)
    ));
    std::fs::write(path, text).map_err(|e| format!("cannot write trace `{}`: {e}", path.display()))
}

fn json(s: &str) -> String {
    serde_json::to_string(s).unwrap_or_else(|_| "\"\"".into())
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
    pub fn lines(
        &mut self,
        module: &Module,
        events: &[Event],
        pose: Option<Pose>,
        scan: Option<&WorldScan>,
    ) -> Vec<String> {
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
                EventKind::Start { .. } => ("start", None),
                EventKind::End { how, .. } => ("end", Some(how.name())),
                _ => continue,
            };
            let Some(s) = module.stmt(stmt) else { continue };
            let mut line = format!(
                "{{\"t\":{},\"event\":\"mark\",\"line\":{},\"text\":{},\"at\":\"{at}\",\"x\":{},\"y\":{},\"h\":{}",
                fmt_num(e.t),
                s.line,
                json(&s.text),
                fmt_num(p.x),
                fmt_num(p.y),
                fmt_num(p.h)
            );
            if let Some(how) = how {
                line.push_str(&format!(",\"how\":\"{how}\""));
            }
            line.push('}');
            out.push(line);
        }
        if let Some(scan) = scan.filter(|s| s.t >= self.next_scan - 1e-9) {
            self.next_scan = (scan.t / self.scan_every).floor() * self.scan_every + self.scan_every;
            out.push(scan_line(scan));
        }
        out
    }
}

/// Hits to the centimetre: what a plot can show, and a fifth of the digits.
fn scan_line(scan: &WorldScan) -> String {
    let mut hits = String::new();
    for (i, (x, y)) in scan.hits().enumerate() {
        if i > 0 {
            hits.push(',');
        }
        hits.push_str(&format!(
            "[{},{}]",
            fmt_num((x * 100.0).round() / 100.0),
            fmt_num((y * 100.0).round() / 100.0)
        ));
    }
    let o = scan.origin;
    format!(
        "{{\"t\":{},\"event\":\"scan\",\"x\":{},\"y\":{},\"h\":{},\"hits\":[{hits}]}}",
        fmt_num(scan.t),
        fmt_num(o.x),
        fmt_num(o.y),
        fmt_num(o.h)
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
            let line = format!("{{\"t\":{}.5,\"event\":\"issue\",\"line\":{i}}}", i);
            sink.line(&line).expect("a full trace is no error");
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
        let kept = lines.len() - 1;
        assert_eq!(
            *last,
            format!(
                "{{\"t\":{kept}.5,\"event\":\"truncated\",\"limit\":4096,\"message\":\"the trace reached 4096 bytes, its limit (MAX_TRACE_BYTES); the rest of the run is not in it\"}}"
            )
        );
        assert!(lines[..kept].iter().all(|l| l.contains("\"issue\"")));
        let v: serde_json::Value = serde_json::from_str(last).expect("JSON");
        assert_eq!(v["event"], "truncated");
    }

    #[test]
    fn the_time_of_a_line_is_its_first_key() {
        assert_eq!(line_time(r#"{"t":12.34,"event":"pose"}"#), "12.34");
        assert_eq!(line_time(r#"{"t":0,"event":"run"}"#), "0");
        assert_eq!(line_time("not a trace line"), "0");
    }
}

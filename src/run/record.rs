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

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

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
    file: Option<(PathBuf, BufWriter<File>)>,
    record: Option<RunRecord>,
}

fn create(path: &Path, what: &str) -> Result<File, String> {
    File::create(path).map_err(|e| format!("cannot write {what} `{}`: {e}", path.display()))
}

impl Sink {
    pub fn open(trace: Option<&Path>, plot: Option<&Path>) -> Result<Sink, String> {
        let file = match trace {
            Some(p) => Some((p.to_path_buf(), BufWriter::new(create(p, "trace")?))),
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
        if let Some((path, w)) = self.file.as_mut() {
            writeln!(w, "{line}")
                .map_err(|e| format!("cannot write trace `{}`: {e}", path.display()))?;
        }
        if let Some(r) = self.record.as_mut() {
            r.absorb(line)?;
        }
        Ok(())
    }

    /// Flushes the trace; returns the record for the plot.
    pub fn finish(self) -> Result<Option<RunRecord>, String> {
        if let Some((path, mut w)) = self.file {
            w.flush()
                .map_err(|e| format!("cannot write trace `{}`: {e}", path.display()))?;
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

//! What a run's plot is drawn from, read back from trace lines with the trace's own
//! types (`ilmr_trace`): the `run` header, `pose` samples, `scan` hits, `mark`s and
//! reference paths (the VM's `path` events). Other events are read and passed over, so
//! any trace of `ilmrc run` reads; one of a robot without a world draws without one.

use ilmr_sim::World;
use ilmr_trace::{Event, How, Moment, Reader, TraceError};

#[derive(Debug, Clone, Default, PartialEq)]
pub struct RunRecord {
    pub header: Option<Header>,
    pub poses: Vec<Sample>,
    pub hits: Vec<(f64, f64)>,
    pub marks: Vec<Mark>,
    pub refs: Vec<RefPath>,
    /// Checks the schema version and counts lines.
    reader: Reader,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Header {
    pub task: String,
    pub robot: String,
    pub world: String,
    /// The world's text, when it came from a file.
    pub world_toml: Option<String>,
    pub seed: u64,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    pub t: f64,
    pub x: f64,
    pub y: f64,
    /// Heading, radians.
    pub h: f64,
    pub v: f64,
    pub c: f64,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum At {
    Start,
    End,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Mark {
    pub t: f64,
    pub line: u32,
    pub text: String,
    pub at: At,
    pub x: f64,
    pub y: f64,
    /// Heading, radians.
    pub h: f64,
    /// How an ended command ended.
    pub how: Option<How>,
}

#[derive(Debug, Clone, PartialEq)]
pub struct RefPath {
    pub line: u32,
    pub points: Vec<(f64, f64)>,
}

impl RunRecord {
    /// Takes the next trace line (the first must be the trace's version line).
    pub fn absorb(&mut self, line: &str) -> Result<(), TraceError> {
        let Some(record) = self.reader.read(line)? else {
            return Ok(());
        };
        let t = record.t.0;
        match record.event {
            Event::Run(run) => {
                self.header = Some(Header {
                    task: run.task.into_owned(),
                    robot: run.robot.into_owned(),
                    world: run.world.into_owned(),
                    world_toml: run.world_toml.map(|w| w.into_owned()),
                    seed: run.seed,
                })
            }
            Event::Pose(p) => self.poses.push(Sample {
                t,
                x: p.x.0,
                y: p.y.0,
                h: p.h.0,
                v: p.v.0,
                c: p.c.0,
            }),
            Event::Scan(scan) => self.hits.extend(scan.hits.0.iter().copied()),
            Event::Mark(m) => self.marks.push(Mark {
                t,
                line: m.line,
                text: m.text.into_owned(),
                at: match m.at {
                    Moment::Start => At::Start,
                    Moment::End => At::End,
                },
                x: m.x.0,
                y: m.y.0,
                h: m.h.0,
                how: m.how,
            }),
            // A path outside any statement is drawn under line 0.
            Event::Path(p) => self.refs.push(RefPath {
                line: p.stmt.map_or(0, |s| s.line),
                points: p.points.0.into_owned(),
            }),
            _ => {}
        }
        Ok(())
    }

    /// A whole trace; an error names the line and its code.
    pub fn from_jsonl(text: &str) -> Result<RunRecord, TraceError> {
        let mut record = RunRecord::default();
        for line in text.lines() {
            record.absorb(line)?;
        }
        Ok(record)
    }

    /// The world the run was in, when the trace names one.
    pub fn world(&self) -> Result<Option<World>, String> {
        let Some(h) = &self.header else {
            return Ok(None);
        };
        if let Some(toml) = &h.world_toml {
            return World::from_toml(toml, &h.world)
                .map(Some)
                .map_err(|e| format!("the trace's world: {e}"));
        }
        match ilmr_sim::world::shipped(&h.world) {
            Some(w) => w.map(Some).map_err(|e| e.to_string()),
            None => Err(format!(
                "the trace names a world `{}` that is not shipped",
                h.world
            )),
        }
    }
}

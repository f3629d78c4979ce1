//! What a run's plot is drawn from, read back from trace lines: the `run` header, `pose`
//! samples, `scan` hits, `mark`s and reference paths (the VM's `path` events). Other events are skipped,
//! so any trace of `ilmrc run` reads; one of a robot without a world draws without one.

use ilmr_sim::World;
use serde_json::Value;

#[derive(Debug, Clone, Default, PartialEq)]
pub struct RunRecord {
    pub header: Option<Header>,
    pub poses: Vec<Sample>,
    pub hits: Vec<(f64, f64)>,
    pub marks: Vec<Mark>,
    pub refs: Vec<RefPath>,
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
    /// How an ended command ended (`completed`, `broken`, `refused`).
    pub how: Option<String>,
}

#[derive(Debug, Clone, PartialEq)]
pub struct RefPath {
    pub line: u32,
    pub points: Vec<(f64, f64)>,
}

fn num(v: &Value, key: &str) -> Result<f64, String> {
    v[key]
        .as_f64()
        .ok_or_else(|| format!("`{key}` is not a number"))
}

fn text(v: &Value, key: &str) -> Result<String, String> {
    v[key]
        .as_str()
        .map(str::to_string)
        .ok_or_else(|| format!("`{key}` is not a string"))
}

fn points(v: &Value, key: &str) -> Result<Vec<(f64, f64)>, String> {
    let list = v[key]
        .as_array()
        .ok_or_else(|| format!("`{key}` is not a list"))?;
    list.iter()
        .map(|p| match (p[0].as_f64(), p[1].as_f64()) {
            (Some(x), Some(y)) => Ok((x, y)),
            _ => Err(format!("`{key}` holds something other than [x, y]")),
        })
        .collect()
}

impl RunRecord {
    /// Takes one trace line.
    pub fn absorb(&mut self, line: &str) -> Result<(), String> {
        let v: Value = serde_json::from_str(line).map_err(|e| format!("not JSON: {e}"))?;
        let event = v["event"]
            .as_str()
            .ok_or("not a trace event: it has no `event`")?;
        match event {
            "run" => {
                self.header = Some(Header {
                    task: text(&v, "task")?,
                    robot: text(&v, "robot")?,
                    world: text(&v, "world")?,
                    world_toml: v["world_toml"].as_str().map(str::to_string),
                    seed: v["seed"].as_u64().ok_or("`seed` is not a number")?,
                })
            }
            "pose" => self.poses.push(Sample {
                t: num(&v, "t")?,
                x: num(&v, "x")?,
                y: num(&v, "y")?,
                h: num(&v, "h")?,
                v: num(&v, "v")?,
                c: num(&v, "c")?,
            }),
            "scan" => self.hits.extend(points(&v, "hits")?),
            "mark" => self.marks.push(Mark {
                t: num(&v, "t")?,
                line: num(&v, "line")? as u32,
                text: text(&v, "text")?,
                at: match v["at"].as_str() {
                    Some("start") => At::Start,
                    Some("end") => At::End,
                    _ => return Err("`at` is neither start nor end".into()),
                },
                x: num(&v, "x")?,
                y: num(&v, "y")?,
                h: num(&v, "h")?,
                how: v["how"].as_str().map(str::to_string),
            }),
            "path" => self.refs.push(RefPath {
                line: num(&v, "line")? as u32,
                points: points(&v, "points")?,
            }),
            _ => {}
        }
        Ok(())
    }

    /// A whole trace; errors name the line.
    pub fn from_jsonl(text: &str) -> Result<RunRecord, String> {
        let mut record = RunRecord::default();
        for (i, line) in text.lines().enumerate() {
            if line.trim().is_empty() {
                continue;
            }
            record
                .absorb(line)
                .map_err(|e| format!("line {}: {e}", i + 1))?;
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

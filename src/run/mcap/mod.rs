//! `--mcap OUT.mcap`: the run for Foxglove. JSON messages with Foxglove's well-known
//! schemas (copied from `@foxglove/schemas` 2.1.0 into `schemas/`) where one fits:
//!
//! | topic | schema | what |
//! | --- | --- | --- |
//! | `/world` | `foxglove.SceneUpdate` | walls, obstacles and boxes as cubes and cylinders, once at t = 0 |
//! | `/pose` | `foxglove.PoseInFrame` | the true pose, at the trace's pose samples |
//! | `/motion` | `ilmr.Motion` | speed and curvature at the same samples, for Foxglove's plot panel |
//! | `/scan` | `foxglove.LaserScan` | every scan, placed at the scanner's true pose |
//! | `/commands` | `foxglove.Log` | issue, start, end, overrun and error events with their source line |
//! | `/paths` | `foxglove.SceneUpdate` | each reference path a movement planned (the VM's `path` events) as a line strip, one entity per path, kept |
//!
//! Everything is in frame `world`; log time is the run's logical time, so the file is
//! the same for the same task, robot, world and seed.
//!
//! The file stops growing at [`MAX_MCAP_BYTES`]: its last message is then a log line
//! on `/commands` that says so, stderr says so once, and the run goes on.
//!
//! A run on a ROS 2 robot also records the robot's topics as they went over the link
//! (`odom`, `scan`, `battery_state` taken, `cmd_vel` sent), with ROS 2's schemas
//! (`ros2msg`) and samples (`cdr`), as rosbag2 does; its `scan` stands for `/scan`.

use std::collections::BTreeMap;
use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};

use ilmr_files::MAX_MCAP_BYTES;
use ilmr_sim::World;
use ilmr_sim::geometry::Shape;
use ilmr_vm::runtime::safety::{Code, Reaction};
use ilmr_vm::{Event, EventKind, How, Module};
use mcap::records::MessageHeader;
use serde_json::{Value, json};

use super::backend::WorldScan;
use super::setup::LoadedWorld;

const FRAME: &str = "world";

const MOTION_SCHEMA: &str = r#"{"title":"ilmr.Motion","description":"The robot's speed and curvature","type":"object","properties":{"timestamp":{"type":"object","title":"time","properties":{"sec":{"type":"integer","minimum":0},"nsec":{"type":"integer","minimum":0,"maximum":999999999}}},"speed":{"type":"number","description":"m/s"},"curvature":{"type":"number","description":"1/m"}}}"#;

/// Topic, schema name and schema text of each channel, in channel order.
const CHANNELS: [(&str, &str, &str); 6] = [
    (
        "/world",
        "foxglove.SceneUpdate",
        include_str!("schemas/foxglove.SceneUpdate.json"),
    ),
    (
        "/pose",
        "foxglove.PoseInFrame",
        include_str!("schemas/foxglove.PoseInFrame.json"),
    ),
    ("/motion", "ilmr.Motion", MOTION_SCHEMA),
    (
        "/scan",
        "foxglove.LaserScan",
        include_str!("schemas/foxglove.LaserScan.json"),
    ),
    (
        "/commands",
        "foxglove.Log",
        include_str!("schemas/foxglove.Log.json"),
    ),
    (
        "/paths",
        "foxglove.SceneUpdate",
        include_str!("schemas/foxglove.SceneUpdate.json"),
    ),
];

#[derive(Clone, Copy)]
enum Topic {
    World = 0,
    Pose,
    Motion,
    Scan,
    Commands,
    Paths,
}

pub struct McapOut {
    path: PathBuf,
    writer: mcap::Writer<BufWriter<File>>,
    /// By [`Topic`]; `None` for the scan of a ROS 2 robot, which its own `scan` topic
    /// records.
    channels: Vec<Option<u16>>,
    /// The channels of a ROS 2 robot's topics, by topic, made as their first message
    /// comes; and their schemas, by type.
    ros2_channels: BTreeMap<String, u16>,
    ros2_schemas: BTreeMap<&'static str, u16>,
    sequence: u32,
    task: String,
    /// Reference paths written so far: the next one's entity id.
    paths: u32,
    /// Bytes the messages take so far (records, message indexes); the schemas and the
    /// summary fit in [`CLOSING_ROOM`].
    written: u64,
    cap: u64,
    /// The cap was reached: no more messages are written.
    full: bool,
}

/// What one message costs beyond its data: the record's opcode, length and header,
/// and its entry in the chunk's message index.
const MESSAGE_OVERHEAD: u64 = 1 + 8 + 22 + 16;
/// Room kept under the cap for the schemas, the last message and the summary.
const CLOSING_ROOM: u64 = 256 * 1024;

fn stamp(t: f64) -> Value {
    let ns = nanos(t);
    json!({"sec": ns / 1_000_000_000, "nsec": ns % 1_000_000_000})
}

fn nanos(t: f64) -> u64 {
    (t.max(0.0) * 1e9).round() as u64
}

fn pose(x: f64, y: f64, h: f64) -> Value {
    json!({
        "position": {"x": x, "y": y, "z": 0.0},
        "orientation": {"x": 0.0, "y": 0.0, "z": (h / 2.0).sin(), "w": (h / 2.0).cos()}
    })
}

impl McapOut {
    /// `ros2`: the robot is a ROS 2 one, whose topics [`McapOut::ros2`] records.
    pub fn create(
        path: &Path,
        world: Option<&LoadedWorld>,
        task: &Path,
        ros2: bool,
    ) -> Result<McapOut, String> {
        McapOut::capped(path, world, task, ros2, MAX_MCAP_BYTES)
    }

    fn capped(
        path: &Path,
        world: Option<&LoadedWorld>,
        task: &Path,
        ros2: bool,
        cap: u64,
    ) -> Result<McapOut, String> {
        let file = File::create(path)
            .map_err(|e| format!("cannot write MCAP `{}`: {e}", path.display()))?;
        let options = mcap::WriteOptions::new().compression(None).profile("");
        let mut writer = mcap::Writer::with_options(BufWriter::new(file), options)
            .map_err(|e| format!("cannot write MCAP `{}`: {e}", path.display()))?;
        let mut channels = Vec::new();
        for (topic, name, schema) in CHANNELS {
            if ros2 && topic == CHANNELS[Topic::Scan as usize].0 {
                channels.push(None);
                continue;
            }
            let schema_id = writer
                .add_schema(name, "jsonschema", schema.trim_end().as_bytes())
                .map_err(|e| e.to_string())?;
            let channel = writer
                .add_channel(schema_id, topic, "json", &BTreeMap::new())
                .map_err(|e| e.to_string())?;
            channels.push(Some(channel));
        }
        let mut out = McapOut {
            path: path.to_path_buf(),
            writer,
            channels,
            ros2_channels: BTreeMap::new(),
            ros2_schemas: BTreeMap::new(),
            sequence: 0,
            task: task.display().to_string(),
            paths: 0,
            written: 0,
            cap,
            full: false,
        };
        if let Some(w) = world {
            out.write(Topic::World, 0.0, &scene(&w.world))?;
        }
        Ok(out)
    }

    /// Whether a message of `data` bytes still fits; at the first that does not, the
    /// closing log message is written instead and nothing fits after it.
    fn fits(&mut self, t: f64, data: usize) -> Result<bool, String> {
        if self.full {
            return Ok(false);
        }
        let cost = data as u64 + MESSAGE_OVERHEAD;
        if self.written + cost + CLOSING_ROOM <= self.cap {
            self.written += cost;
            return Ok(true);
        }
        self.full = true;
        let message = format!(
            "the MCAP file reached {} MiB, its limit (MAX_MCAP_BYTES); the rest of the run is not in it",
            self.cap >> 20
        );
        eprintln!("warning: `{}`: {message}", self.path.display());
        let log = json!({
            "timestamp": stamp(t),
            "level": 3,
            "message": message,
            "name": "ilmr",
            "file": self.task,
            "line": 0,
        });
        if let Some(channel_id) = self.channels[Topic::Commands as usize] {
            self.put(channel_id, t, &log)?;
        }
        Ok(false)
    }

    fn write(&mut self, topic: Topic, t: f64, message: &Value) -> Result<(), String> {
        let Some(channel_id) = self.channels[topic as usize] else {
            return Ok(());
        };
        let data = serde_json::to_vec(message).map_err(|e| e.to_string())?;
        if !self.fits(t, data.len())? {
            return Ok(());
        }
        self.put_bytes(channel_id, t, &data)
    }

    fn put(&mut self, channel_id: u16, t: f64, message: &Value) -> Result<(), String> {
        let data = serde_json::to_vec(message).map_err(|e| e.to_string())?;
        self.put_bytes(channel_id, t, &data)
    }

    fn put_bytes(&mut self, channel_id: u16, t: f64, data: &[u8]) -> Result<(), String> {
        self.sequence += 1;
        let header = MessageHeader {
            channel_id,
            sequence: self.sequence,
            log_time: nanos(t),
            publish_time: nanos(t),
        };
        self.writer
            .write_to_known_channel(&header, data)
            .map_err(|e| format!("cannot write MCAP `{}`: {e}", self.path.display()))
    }

    /// The tick's events and scan.
    pub fn tick(
        &mut self,
        module: &Module,
        events: &[Event],
        scan: Option<&WorldScan>,
    ) -> Result<(), String> {
        for e in events {
            match &e.kind {
                EventKind::Pose {
                    x,
                    y,
                    h,
                    speed,
                    curvature,
                    ..
                } => {
                    let p = json!({"timestamp": stamp(e.t), "frame_id": FRAME, "pose": pose(*x, *y, *h)});
                    self.write(Topic::Pose, e.t, &p)?;
                    let m =
                        json!({"timestamp": stamp(e.t), "speed": speed, "curvature": curvature});
                    self.write(Topic::Motion, e.t, &m)?;
                }
                EventKind::Var { .. } => {}
                EventKind::Path { points } => {
                    self.paths += 1;
                    let label = e
                        .stmt
                        .and_then(|s| module.stmt(s))
                        .map(|s| format!("line {}: {}", s.line, s.text));
                    let m = path_scene(e.t, self.paths, label.as_deref(), points);
                    self.write(Topic::Paths, e.t, &m)?;
                }
                _ => {
                    let log = self.log(module, e);
                    self.write(Topic::Commands, e.t, &log)?;
                }
            }
        }
        if let Some(s) = scan {
            let end = s.angle_min + s.angle_step * (s.ranges.len().saturating_sub(1)) as f64;
            let m = json!({
                "timestamp": stamp(s.t),
                "frame_id": FRAME,
                "pose": pose(s.origin.x, s.origin.y, s.origin.h),
                "start_angle": s.angle_min,
                "end_angle": end,
                "ranges": s.ranges,
                "intensities": [],
            });
            self.write(Topic::Scan, s.t, &m)?;
        }
        Ok(())
    }

    fn log(&self, module: &Module, e: &Event) -> Value {
        let stmt = e.stmt.and_then(|s| module.stmt(s));
        let (level, what) = match &e.kind {
            EventKind::End {
                how: How::Refused,
                reason,
                code,
                ..
            } => (
                3,
                format!(
                    "refused{}{}{}",
                    code.map(|c| format!(" ({})", c.code())).unwrap_or_default(),
                    reason
                        .as_ref()
                        .map(|r| format!(": {r}"))
                        .unwrap_or_default(),
                    code.map(|c| format!("; way out: {}", c.help()))
                        .unwrap_or_default()
                ),
            ),
            EventKind::End { how, linked, .. } => (
                2,
                format!(
                    "end {}{}",
                    how.name(),
                    if *linked { " (linked)" } else { "" }
                ),
            ),
            EventKind::Error { message } => (4, format!("error: {message}")),
            EventKind::Overrun { pending } => (3, format!("overrun, {pending} pending")),
            EventKind::Fault { fault, message } => {
                let reaction = fault.reaction();
                let code = Code::Fault(*fault);
                let level = match reaction {
                    Reaction::Raise | Reaction::SlowDown => 3,
                    _ => 4,
                };
                (
                    level,
                    format!(
                        "{} ({} {}): {message}; way out: {}",
                        crate::notice::reaction_verb(reaction.name()),
                        code.code(),
                        fault.name(),
                        code.help()
                    ),
                )
            }
            EventKind::Recovered { fault } => (
                2,
                format!("cleared ({} {})", Code::Fault(*fault).code(), fault.name()),
            ),
            other => (2, other.name().to_string()),
        };
        let message = match stmt {
            Some(s) => format!("{what}: {}", s.text),
            None => what,
        };
        let file = stmt
            .and_then(|s| module.files.get(s.file.0 as usize))
            .cloned()
            .unwrap_or_else(|| self.task.clone());
        json!({
            "timestamp": stamp(e.t),
            "level": level,
            "message": message,
            "name": "ilmr",
            "file": file,
            "line": stmt.map_or(0, |s| s.line),
        })
    }

    /// A ROS 2 robot's messages as they went over the link, on channels named by their
    /// topics, with ROS 2's schemas (`ros2msg`) and samples (`cdr`): as rosbag2 records
    /// them, so Foxglove and rosbag2 readers decode them as a bag's.
    pub fn ros2(&mut self, records: Vec<ilmr_ros2::robot::Recorded>) -> Result<(), String> {
        for r in records {
            if !self.fits(r.t, r.sample.len())? {
                continue;
            }
            let channel = match self.ros2_channels.get(&r.topic) {
                Some(&c) => c,
                None => {
                    let schema = match self.ros2_schemas.get(r.ros_type) {
                        Some(&s) => s,
                        None => {
                            let s = self
                                .writer
                                .add_schema(r.ros_type, "ros2msg", r.definition.as_bytes())
                                .map_err(|e| e.to_string())?;
                            self.ros2_schemas.insert(r.ros_type, s);
                            s
                        }
                    };
                    let c = self
                        .writer
                        .add_channel(schema, &r.topic, "cdr", &BTreeMap::new())
                        .map_err(|e| e.to_string())?;
                    self.ros2_channels.insert(r.topic.clone(), c);
                    c
                }
            };
            self.sequence += 1;
            let header = MessageHeader {
                channel_id: channel,
                sequence: self.sequence,
                log_time: nanos(r.t),
                publish_time: nanos(r.t),
            };
            self.writer
                .write_to_known_channel(&header, &r.sample)
                .map_err(|e| format!("cannot write MCAP `{}`: {e}", self.path.display()))?;
        }
        Ok(())
    }

    pub fn finish(mut self) -> Result<(), String> {
        self.writer
            .finish()
            .map_err(|e| format!("cannot write MCAP `{}`: {e}", self.path.display()))?;
        Ok(())
    }
}

/// Foxglove's `Log` level for a failure.
const LOG_ERROR: u8 = 4;

/// The whole MCAP file of a run that did not start: the `/commands` channel alone, with
/// one error log message that says why, in place of whatever the path held.
pub fn write_failure(path: &Path, task: &Path, reason: &str, exit: u8) -> Result<(), String> {
    let fail = |e: &dyn std::fmt::Display| format!("cannot write MCAP `{}`: {e}", path.display());
    let file = File::create(path).map_err(|e| fail(&e))?;
    let options = mcap::WriteOptions::new().compression(None).profile("");
    let mut writer =
        mcap::Writer::with_options(BufWriter::new(file), options).map_err(|e| fail(&e))?;
    let (topic, name, schema) = CHANNELS[Topic::Commands as usize];
    let schema_id = writer
        .add_schema(name, "jsonschema", schema.trim_end().as_bytes())
        .map_err(|e| fail(&e))?;
    let channel_id = writer
        .add_channel(schema_id, topic, "json", &BTreeMap::new())
        .map_err(|e| fail(&e))?;
    let log = json!({
        "timestamp": stamp(0.0),
        "level": LOG_ERROR,
        "message": format!("the run did not start (exit {exit}): {reason}"),
        "name": "ilmr",
        "file": task.display().to_string(),
        "line": 0,
    });
    let data = serde_json::to_vec(&log).map_err(|e| fail(&e))?;
    let header = MessageHeader {
        channel_id,
        sequence: 1,
        log_time: 0,
        publish_time: 0,
    };
    writer
        .write_to_known_channel(&header, &data)
        .map_err(|e| fail(&e))?;
    writer.finish().map_err(|e| fail(&e))?;
    Ok(())
}

/// The world's solids as a scene: walls, obstacles and boxes as cubes, round things as
/// cylinders, 1 m high.
fn scene(w: &World) -> Value {
    let grey = json!({"r": 0.55, "g": 0.55, "b": 0.55, "a": 1.0});
    let cube = |center: ilmr_sim::Vec2, heading: f64, length: f64, width: f64| {
        json!({
            "pose": pose_z(center.x, center.y, 0.5, heading),
            "size": {"x": length, "y": width, "z": 1.0},
            "color": grey,
        })
    };
    let mut cubes = Vec::new();
    let mut cylinders = Vec::new();
    for wall in &w.walls {
        for &(a, b) in &wall.pieces {
            let mid = ilmr_sim::Vec2::new((a.x + b.x) / 2.0, (a.y + b.y) / 2.0);
            let h = (b.y - a.y).atan2(b.x - a.x);
            cubes.push(cube(mid, h, a.distance(b), wall.thickness));
        }
    }
    let mut obb = |o: &ilmr_sim::geometry::Obb| {
        let h = o.axis.y.atan2(o.axis.x);
        cubes.push(cube(o.center, h, 2.0 * o.half.x, 2.0 * o.half.y));
    };
    for o in &w.obstacles {
        match o {
            Shape::Box(b) => obb(b),
            Shape::Circle(c) => cylinders.push(json!({
                "pose": pose_z(c.center.x, c.center.y, 0.5, 0.0),
                "size": {"x": 2.0 * c.radius, "y": 2.0 * c.radius, "z": 1.0},
                "bottom_scale": 1.0, "top_scale": 1.0,
                "color": grey,
            })),
        }
    }
    for b in &w.pickup_boxes {
        obb(&b.shape);
    }
    json!({
        "deletions": [],
        "entities": [{
            "timestamp": stamp(0.0),
            "frame_id": FRAME,
            "id": w.name,
            "lifetime": {"sec": 0, "nsec": 0},
            "frame_locked": false,
            "metadata": [],
            "arrows": [], "cubes": cubes, "spheres": [], "cylinders": cylinders,
            "lines": [], "triangles": [], "texts": [], "models": [],
        }],
    })
}

/// A reference path as a scene entity of its own (`path-N`, never replaced, so the
/// scene keeps every path the run planned), a line strip on the floor.
fn path_scene(t: f64, n: u32, label: Option<&str>, points: &[(f64, f64)]) -> Value {
    let points: Vec<Value> = points
        .iter()
        .map(|(x, y)| json!({"x": x, "y": y, "z": 0.0}))
        .collect();
    let metadata: Vec<Value> = label
        .map(|l| json!({"key": "command", "value": l}))
        .into_iter()
        .collect();
    json!({
        "deletions": [],
        "entities": [{
            "timestamp": stamp(t),
            "frame_id": FRAME,
            "id": format!("path-{n}"),
            "lifetime": {"sec": 0, "nsec": 0},
            "frame_locked": false,
            "metadata": metadata,
            "arrows": [], "cubes": [], "spheres": [], "cylinders": [],
            "lines": [{
                "type": 0,
                "pose": pose_z(0.0, 0.0, 0.0, 0.0),
                "thickness": 0.03,
                "scale_invariant": false,
                "points": points,
                "color": {"r": 0.15, "g": 0.15, "b": 0.15, "a": 1.0},
                "colors": [],
                "indices": [],
            }],
            "triangles": [], "texts": [], "models": [],
        }],
    })
}

fn pose_z(x: f64, y: f64, z: f64, h: f64) -> Value {
    json!({
        "position": {"x": x, "y": y, "z": z},
        "orientation": {"x": 0.0, "y": 0.0, "z": (h / 2.0).sin(), "w": (h / 2.0).cos()}
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn empty_module() -> Module {
        let model = ilmr_model::RobotModel::builtin("moro").expect("shipped model");
        let sources = [ilmr_compiler::check::Source::new("t.ilmr", "")];
        let analysis = ilmr_compiler::check::analyze(&sources, &model);
        ilmr_compiler::lower::lower(&analysis, &model, ilmr_compiler::FileId(0))
            .expect("an empty task lowers")
    }

    #[test]
    fn a_reference_path_is_a_line_strip_on_its_own_topic() {
        let path =
            std::env::temp_dir().join(format!("ilmr-mcap-paths-{}.mcap", std::process::id()));
        let module = empty_module();
        let mut out = McapOut::create(&path, None, Path::new("t.ilmr"), false).expect("create");
        let event = |t: f64, points: Vec<(f64, f64)>| {
            Event::new((t * 100.0) as u64, t, None, EventKind::Path { points })
        };
        let events = [
            event(0.5, vec![(0.0, 0.0), (1.5, 0.0)]),
            event(2.0, vec![(1.5, 0.0), (2.0, 0.5), (2.5, 1.0)]),
        ];
        out.tick(&module, &events, None).expect("write");
        out.finish().expect("finish");
        let bytes = std::fs::read(&path).expect("read back");
        let _ = std::fs::remove_file(&path);

        let mut paths = Vec::new();
        for m in mcap::MessageStream::new(&bytes).expect("an MCAP file") {
            let m = m.expect("a message");
            assert_ne!(m.channel.topic, "/commands", "a path is not a log line");
            if m.channel.topic == "/paths" {
                let schema = m.channel.schema.as_ref().expect("a schema");
                assert_eq!(schema.name, "foxglove.SceneUpdate");
                let v: Value = serde_json::from_slice(&m.data).expect("JSON");
                paths.push((m.log_time, v));
            }
        }
        assert_eq!(paths.len(), 2);
        let (time, second) = &paths[1];
        assert_eq!(*time, 2_000_000_000);
        let entity = &second["entities"][0];
        assert_eq!(entity["id"], json!("path-2"));
        assert_eq!(entity["frame_id"], json!("world"));
        let line = &entity["lines"][0];
        assert_eq!(line["type"], json!(0));
        assert_eq!(
            line["points"],
            json!([
                {"x": 1.5, "y": 0.0, "z": 0.0},
                {"x": 2.0, "y": 0.5, "z": 0.0},
                {"x": 2.5, "y": 1.0, "z": 0.0}
            ])
        );
    }

    #[test]
    fn a_file_stops_at_its_cap_with_a_closing_log_message() {
        let path = std::env::temp_dir().join(format!("ilmr-mcap-cap-{}.mcap", std::process::id()));
        let module = empty_module();
        let cap = 1 << 20;
        let mut out =
            McapOut::capped(&path, None, Path::new("t.ilmr"), false, cap).expect("create");
        for i in 0..20_000u32 {
            let t = f64::from(i) * 0.01;
            let pose = Event::new(
                u64::from(i),
                t,
                None,
                EventKind::Pose {
                    x: t,
                    y: 0.5,
                    h: 0.1,
                    speed: 0.4,
                    curvature: 0.0,
                    truth: true,
                },
            );
            out.tick(&module, &[pose], None)
                .expect("a full file is no error");
        }
        out.finish().expect("finish");
        let bytes = std::fs::read(&path).expect("read back");
        let _ = std::fs::remove_file(&path);
        assert!(bytes.len() as u64 <= cap, "{} bytes", bytes.len());
        assert!(bytes.len() as u64 > cap / 2, "{} bytes", bytes.len());
        let messages: Vec<_> = mcap::MessageStream::new(&bytes)
            .expect("an MCAP file")
            .map(|m| m.expect("a message"))
            .collect();
        let last = messages.last().expect("messages");
        assert_eq!(last.channel.topic, "/commands");
        let v: Value = serde_json::from_slice(&last.data).expect("JSON");
        assert_eq!(
            v["message"],
            json!(
                "the MCAP file reached 1 MiB, its limit (MAX_MCAP_BYTES); the rest of the run is not in it"
            )
        );
        let poses = messages
            .iter()
            .filter(|m| m.channel.topic == "/pose")
            .count();
        assert!(poses > 1000 && poses < 20_000, "{poses} poses kept");
    }
}

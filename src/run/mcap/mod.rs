//! `--mcap OUT.mcap`: the run for Foxglove, with the topics and typed messages of
//! [`crate::view`] (Foxglove's protobuf schemas, each channel carrying its schema),
//! in zstd-compressed chunks. Log time is the run's logical time, so the file is the
//! same for the same task, robot, world and seed.
//!
//! The file stops growing at [`MAX_MCAP_BYTES`] of messages (counted before
//! compression, so the file on disk is smaller): its last message is then a log line
//! on `/commands` that says so, stderr says so once, and the run goes on.
//!
//! A run on a ROS 2 robot also records the robot's topics as they went over the link
//! (`odom`, `scan`, `battery_state` taken, `cmd_vel` sent), with ROS 2's schemas
//! (`ros2msg`) and samples (`cdr`), as rosbag2 does; its `scan` stands for `/scan`.

use std::collections::BTreeMap;
use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};

use foxglove::schemas::log::Level;
use ilmr_files::MAX_MCAP_BYTES;
use ilmr_vm::{Event, Module};
use mcap::records::MessageHeader;

use super::backend::WorldScan;
use super::setup::LoadedWorld;
use crate::view::{Messages, Outgoing, Topic, nanos};

/// The topic of the recorded inputs, and the name of its schema (a trace line's).
pub const INPUTS_TOPIC: &str = "/ilmr/inputs";
const INPUTS_SCHEMA: &str = "ilmr.trace.Line";

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
    /// The channel of the recorded inputs ([`INPUTS_TOPIC`]), made with its first line.
    inputs: Option<u16>,
    sequence: u32,
    messages: Messages,
    /// The tick's messages, and one message's bytes: kept to spare an allocation per
    /// message.
    outgoing: Vec<Outgoing>,
    bytes: Vec<u8>,
    /// Bytes the messages take so far (records, message indexes), before
    /// compression; the schemas and the summary fit in [`CLOSING_ROOM`].
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

/// A writer with the project's options: zstd chunks, no profile (the messages are
/// Foxglove's, not ROS's).
fn writer(path: &Path) -> Result<mcap::Writer<BufWriter<File>>, String> {
    let fail = |e: &dyn std::fmt::Display| format!("cannot write MCAP `{}`: {e}", path.display());
    let file = File::create(path).map_err(|e| fail(&e))?;
    let options = mcap::WriteOptions::new()
        .compression(Some(mcap::Compression::Zstd))
        .profile("")
        .library(concat!("ilmrc ", env!("CARGO_PKG_VERSION")));
    mcap::Writer::with_options(BufWriter::new(file), options).map_err(|e| fail(&e))
}

/// Adds the topic's schema and channel.
fn channel(writer: &mut mcap::Writer<BufWriter<File>>, topic: Topic) -> Result<u16, String> {
    let schema = topic.schema();
    let schema_id = writer
        .add_schema(&schema.name, &schema.encoding, &schema.data)
        .map_err(|e| e.to_string())?;
    writer
        .add_channel(schema_id, topic.name(), "protobuf", &BTreeMap::new())
        .map_err(|e| e.to_string())
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
        let mut writer = writer(path)?;
        let mut channels = Vec::new();
        for topic in Topic::ALL {
            if ros2 && topic == Topic::Scan {
                channels.push(None);
            } else {
                channels.push(Some(channel(&mut writer, topic)?));
            }
        }
        let mut out = McapOut {
            path: path.to_path_buf(),
            writer,
            channels,
            ros2_channels: BTreeMap::new(),
            ros2_schemas: BTreeMap::new(),
            inputs: None,
            sequence: 0,
            messages: Messages::new(&task.display().to_string()),
            outgoing: Vec::new(),
            bytes: Vec::new(),
            written: 0,
            cap,
            full: false,
        };
        if let Some(w) = world {
            let world = out.messages.world(&w.world);
            out.write(&world)?;
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
        let note = self.messages.note(t, Level::Warning, message);
        self.put(&note)?;
        Ok(false)
    }

    fn write(&mut self, o: &Outgoing) -> Result<(), String> {
        if self.channels[o.topic as usize].is_none() {
            return Ok(());
        }
        self.bytes.clear();
        o.message.encode(&mut self.bytes);
        if !self.fits(o.t, self.bytes.len())? {
            return Ok(());
        }
        let Some(channel_id) = self.channels[o.topic as usize] else {
            return Ok(());
        };
        let bytes = std::mem::take(&mut self.bytes);
        let done = self.put_bytes(channel_id, o.t, &bytes);
        self.bytes = bytes;
        done
    }

    fn put(&mut self, o: &Outgoing) -> Result<(), String> {
        let Some(channel_id) = self.channels[o.topic as usize] else {
            return Ok(());
        };
        let mut bytes = Vec::new();
        o.message.encode(&mut bytes);
        self.put_bytes(channel_id, o.t, &bytes)
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
        let mut outgoing = std::mem::take(&mut self.outgoing);
        outgoing.clear();
        self.messages.tick(module, events, scan, &mut outgoing);
        let mut done = Ok(());
        for o in &outgoing {
            done = self.write(o);
            if done.is_err() {
                break;
            }
        }
        self.outgoing = outgoing;
        done
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
            self.put_bytes(channel, r.t, &r.sample)?;
        }
        Ok(())
    }

    /// A line of the recorded inputs (`--record-inputs`): the `run` and `tape` lines,
    /// interactive `line`s and each tick's `input`, as the trace has them (JSON, every
    /// digit), on [`INPUTS_TOPIC`], so that `ilmrc replay --inputs RUN.mcap` reads them.
    pub fn input(&mut self, line: &ilmr_trace::Record<'_>) -> Result<(), String> {
        let data = ilmr_trace::to_line(line);
        if !self.fits(line.t.0, data.len())? {
            return Ok(());
        }
        let channel = match self.inputs {
            Some(c) => c,
            None => {
                let schema = self
                    .writer
                    .add_schema(
                        INPUTS_SCHEMA,
                        "jsonschema",
                        ilmr_trace::json_schema().as_bytes(),
                    )
                    .map_err(|e| e.to_string())?;
                let c = self
                    .writer
                    .add_channel(schema, INPUTS_TOPIC, "json", &BTreeMap::new())
                    .map_err(|e| e.to_string())?;
                self.inputs = Some(c);
                c
            }
        };
        self.put_bytes(channel, line.t.0, data.as_bytes())
    }

    pub fn finish(mut self) -> Result<(), String> {
        self.writer
            .finish()
            .map_err(|e| format!("cannot write MCAP `{}`: {e}", self.path.display()))?;
        Ok(())
    }
}

/// The whole MCAP file of a run that did not start: the `/commands` channel alone, with
/// one error log message that says why, in place of whatever the path held.
pub fn write_failure(path: &Path, task: &Path, reason: &str, exit: u8) -> Result<(), String> {
    let fail = |e: &dyn std::fmt::Display| format!("cannot write MCAP `{}`: {e}", path.display());
    let mut writer = writer(path)?;
    let channel_id = channel(&mut writer, Topic::Commands)?;
    let note = Messages::new(&task.display().to_string()).note(
        0.0,
        Level::Error,
        format!("the run did not start (exit {exit}): {reason}"),
    );
    let mut data = Vec::new();
    note.message.encode(&mut data);
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

#[cfg(test)]
mod tests {
    use super::*;
    use foxglove::Decode;
    use foxglove::schemas::{Log, SceneUpdate};
    use ilmr_vm::EventKind;

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
                assert_eq!(schema.encoding, "protobuf");
                assert_eq!(m.channel.message_encoding, "protobuf");
                let scene = SceneUpdate::decode(&m.data[..]).expect("a SceneUpdate");
                paths.push((m.log_time, scene));
            }
        }
        assert_eq!(paths.len(), 2);
        let (time, second) = &paths[1];
        assert_eq!(*time, 2_000_000_000);
        let entity = &second.entities[0];
        assert_eq!(entity.id, "path-2");
        assert_eq!(entity.frame_id, "world");
        let line = &entity.lines[0];
        assert_eq!(line.r#type, 0, "a line strip");
        let points: Vec<_> = line.points.iter().map(|p| (p.x, p.y, p.z)).collect();
        assert_eq!(points, [(1.5, 0.0, 0.0), (2.0, 0.5, 0.0), (2.5, 1.0, 0.0)]);
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
        let messages: Vec<_> = mcap::MessageStream::new(&bytes)
            .expect("an MCAP file")
            .map(|m| m.expect("a message"))
            .collect();
        // The cap counts messages before compression: the file is smaller still.
        let carried: u64 = messages
            .iter()
            .map(|m| m.data.len() as u64 + MESSAGE_OVERHEAD)
            .sum();
        assert!(
            carried <= cap && carried > cap / 2,
            "{carried} bytes carried"
        );
        let last = messages.last().expect("messages");
        assert_eq!(last.channel.topic, "/commands");
        let log = Log::decode(&last.data[..]).expect("a Log");
        assert_eq!(
            log.message,
            "the MCAP file reached 1 MiB, its limit (MAX_MCAP_BYTES); the rest of the run is not in it"
        );
        let poses = messages
            .iter()
            .filter(|m| m.channel.topic == "/pose")
            .count();
        assert!(poses > 1000 && poses < 20_000, "{poses} poses kept");
    }
}

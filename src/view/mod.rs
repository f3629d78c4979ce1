//! What a viewer is shown of a run: Foxglove's typed messages (protobuf, with the
//! schemas of Foxglove's SDK) built from the VM's events, the scan and the world. The
//! recording (`run::mcap`) and the live view ([`live`]) publish the same messages on
//! the same topics, so a panel laid out for one shows the other.
//!
//! | topic | schema | what |
//! | --- | --- | --- |
//! | `/world` | `foxglove.SceneUpdate` | walls, obstacles and boxes as cubes and cylinders |
//! | `/pose` | `foxglove.PoseInFrame` | the true pose, at the trace's pose samples |
//! | `/tf` | `foxglove.FrameTransforms` | `world` to `base_link` at the same samples |
//! | `/motion` | `motion.Motion` | speed and curvature at the same samples |
//! | `/scan` | `foxglove.LaserScan` | every scan, placed at the scanner's true pose |
//! | `/commands` | `foxglove.Log` | command events, refusals, faults, overruns and errors, with their source line |
//! | `/paths` | `foxglove.SceneUpdate` | each reference path a movement planned, one entity per path, kept |
//! | `/trajectory` | `foxglove.SceneUpdate` | where the robot drove, one line strip per second of driving, kept |
//! | `/variables` | `variable.Variable` | each variable's fields when a statement sets them |
//!
//! Everything is in frame `world`, stamped with the run's logical time. Scan ranges
//! are given to the millimetre ([`RANGES_PER_METRE`]).

pub mod live;
mod scene;

use foxglove::Encode;
use foxglove::schemas::{
    FrameTransforms, LaserScan, Log, Point3, PoseInFrame, SceneUpdate, Timestamp, log,
};
use ilmr_sim::World;
use ilmr_vm::runtime::safety::{Code, Reaction};
use ilmr_vm::{Event, EventKind, How, Module};

use crate::run::backend::WorldScan;
pub use scene::nanos;
use scene::{PATH_COLOR, TRAJECTORY_COLOR, point, pose, scene, stamp, strip, transform};

pub const FRAME: &str = "world";
pub const ROBOT_FRAME: &str = "base_link";

/// The robot's speed and curvature, for Foxglove's plot panel.
#[derive(Debug, Clone, PartialEq, foxglove::Encode)]
pub struct Motion {
    pub timestamp: Timestamp,
    /// m/s
    pub speed: f64,
    /// 1/m
    pub curvature: f64,
}

/// A variable's fields (Table 8) after a statement set them.
#[derive(Debug, Clone, PartialEq, foxglove::Encode)]
pub struct Variable {
    pub timestamp: Timestamp,
    pub name: String,
    pub status: f64,
    pub x: f64,
    pub y: f64,
    pub h: f64,
    pub value: f64,
    pub dist: f64,
    /// How its command ended (`completed`, `broken`, ...), empty while it runs.
    pub how: String,
    /// The line of the statement that set it.
    pub line: u32,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Topic {
    World,
    Pose,
    Tf,
    Motion,
    Scan,
    Commands,
    Paths,
    Trajectory,
    Variables,
}

impl Topic {
    pub const ALL: [Topic; 9] = [
        Topic::World,
        Topic::Pose,
        Topic::Tf,
        Topic::Motion,
        Topic::Scan,
        Topic::Commands,
        Topic::Paths,
        Topic::Trajectory,
        Topic::Variables,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Topic::World => "/world",
            Topic::Pose => "/pose",
            Topic::Tf => "/tf",
            Topic::Motion => "/motion",
            Topic::Scan => "/scan",
            Topic::Commands => "/commands",
            Topic::Paths => "/paths",
            Topic::Trajectory => "/trajectory",
            Topic::Variables => "/variables",
        }
    }

    /// The schema of the topic's messages, as Foxglove's SDK describes the type.
    pub fn schema(self) -> foxglove::Schema {
        let schema = match self {
            Topic::World | Topic::Paths | Topic::Trajectory => SceneUpdate::get_schema(),
            Topic::Pose => PoseInFrame::get_schema(),
            Topic::Tf => FrameTransforms::get_schema(),
            Topic::Motion => Motion::get_schema(),
            Topic::Scan => LaserScan::get_schema(),
            Topic::Commands => Log::get_schema(),
            Topic::Variables => Variable::get_schema(),
        };
        schema.expect("Foxglove's types and the derived ones carry their schema")
    }
}

/// One message of a topic.
#[derive(Debug, Clone, PartialEq)]
pub enum Message {
    Scene(SceneUpdate),
    Pose(PoseInFrame),
    Transforms(FrameTransforms),
    Motion(Motion),
    Scan(LaserScan),
    Log(Log),
    Variable(Variable),
}

impl Message {
    /// The message's protobuf bytes, appended to `buf`.
    pub fn encode(&self, buf: &mut Vec<u8>) {
        // Encoding into a growing Vec cannot run out of room, the one way it fails.
        let done = match self {
            Message::Scene(m) => m.encode(buf).map_err(|e| e.to_string()),
            Message::Pose(m) => m.encode(buf).map_err(|e| e.to_string()),
            Message::Transforms(m) => m.encode(buf).map_err(|e| e.to_string()),
            Message::Motion(m) => m.encode(buf).map_err(|e| e.to_string()),
            Message::Scan(m) => m.encode(buf).map_err(|e| e.to_string()),
            Message::Log(m) => m.encode(buf).map_err(|e| e.to_string()),
            Message::Variable(m) => m.encode(buf).map_err(|e| e.to_string()),
        };
        if let Err(e) = done {
            unreachable!("encoding into a Vec failed: {e}");
        }
    }
}

/// A message on its way out, stamped with the run's logical time (seconds).
#[derive(Debug, Clone, PartialEq)]
pub struct Outgoing {
    pub topic: Topic,
    pub t: f64,
    pub message: Message,
}

/// Scan ranges are shown to the millimetre: the finest resolution of the Sick LMS 291
/// both robots carry (dissertation section 5.1), well under the scanner's noise.
/// Noise in every bit of a double does not compress: way_out's 600 s of scans take
/// 6.6 MB under zstd at full precision, 1.8 MB to the millimetre.
pub const RANGES_PER_METRE: f64 = 1000.0;

/// `r` to the nearest [`RANGES_PER_METRE`] step (the double nearest that decimal).
fn to_resolution(r: f64) -> f64 {
    if r.is_finite() {
        (r * RANGES_PER_METRE).round() / RANGES_PER_METRE
    } else {
        r
    }
}

/// How far apart (seconds of driving) the trajectory is cut into entities: a viewer
/// gets the newest piece within that time, and no message grows with the run.
const TRAJECTORY_PIECE: f64 = 1.0;

/// Turns a run's events into messages. It remembers what a viewer that comes late
/// must be sent again (the world, the paths and the trajectory so far are scene
/// entities, shown once published).
pub struct Messages {
    /// The task's file, for log lines of no statement.
    task: String,
    /// Reference paths so far: the next one's entity id.
    paths: u32,
    /// The trajectory piece being drawn: its number, start time and points.
    piece: u32,
    piece_start: f64,
    piece_points: Vec<Point3>,
}

impl Messages {
    pub fn new(task: &str) -> Messages {
        Messages {
            task: task.to_string(),
            paths: 0,
            piece: 0,
            piece_start: 0.0,
            piece_points: Vec::new(),
        }
    }

    /// The world's solids, once at the start.
    pub fn world(&self, world: &World) -> Outgoing {
        Outgoing {
            topic: Topic::World,
            t: 0.0,
            message: Message::Scene(scene(world)),
        }
    }

    /// A log line of no statement (the run's own news).
    pub fn note(&self, t: f64, level: log::Level, message: String) -> Outgoing {
        Outgoing {
            topic: Topic::Commands,
            t,
            message: Message::Log(Log {
                timestamp: Some(stamp(t)),
                level: level as i32,
                message,
                name: "ilmr".into(),
                file: self.task.clone(),
                line: 0,
            }),
        }
    }

    /// The tick's events and scan, in that order, appended to `out`.
    pub fn tick(
        &mut self,
        module: &Module,
        events: &[Event],
        scan: Option<&WorldScan>,
        out: &mut Vec<Outgoing>,
    ) {
        for e in events {
            let t = e.t;
            let mut put = |topic, message| out.push(Outgoing { topic, t, message });
            match &e.kind {
                EventKind::Pose {
                    x,
                    y,
                    h,
                    speed,
                    curvature,
                    ..
                } => self.robot(t, (*x, *y, *h), (*speed, *curvature), out),
                EventKind::Var { var, record, .. } => {
                    let stmt = e.stmt.and_then(|s| module.stmt(s));
                    put(
                        Topic::Variables,
                        Message::Variable(Variable {
                            timestamp: stamp(t),
                            name: module
                                .global(*var)
                                .map_or_else(|| "?".into(), |g| g.name.clone()),
                            status: record.status,
                            x: record.x,
                            y: record.y,
                            h: record.h,
                            value: record.value,
                            dist: record.dist,
                            how: record.how.map_or("", How::name).into(),
                            line: stmt.map_or(0, |s| s.line),
                        }),
                    );
                }
                EventKind::Path { points } => {
                    self.paths += 1;
                    let label = e
                        .stmt
                        .and_then(|s| module.stmt(s))
                        .map(|s| format!("line {}: {}", s.line, s.text));
                    let points = points.iter().map(|&(x, y)| point(x, y)).collect();
                    let id = format!("path-{}", self.paths);
                    put(
                        Topic::Paths,
                        Message::Scene(strip(t, id, label, points, PATH_COLOR, 0.03)),
                    );
                }
                _ => put(Topic::Commands, Message::Log(self.log(module, e))),
            }
        }
        if let Some(s) = scan {
            out.push(Messages::scan(s));
        }
    }

    /// The robot at a pose sample: its pose, transform, motion and trajectory.
    pub fn robot(
        &mut self,
        t: f64,
        (x, y, h): (f64, f64, f64),
        (speed, curvature): (f64, f64),
        out: &mut Vec<Outgoing>,
    ) {
        let mut put = |topic, message| out.push(Outgoing { topic, t, message });
        put(
            Topic::Pose,
            Message::Pose(PoseInFrame {
                timestamp: Some(stamp(t)),
                frame_id: FRAME.into(),
                pose: Some(pose(x, y, 0.0, h)),
            }),
        );
        put(Topic::Tf, Message::Transforms(transform(t, x, y, h)));
        put(
            Topic::Motion,
            Message::Motion(Motion {
                timestamp: stamp(t),
                speed,
                curvature,
            }),
        );
        if let Some(piece) = self.trajectory(t, x, y) {
            put(Topic::Trajectory, Message::Scene(piece));
        }
    }

    /// A scan, placed at the scanner's pose.
    pub fn scan(s: &WorldScan) -> Outgoing {
        let end = s.angle_min + s.angle_step * (s.ranges.len().saturating_sub(1)) as f64;
        Outgoing {
            topic: Topic::Scan,
            t: s.t,
            message: Message::Scan(LaserScan {
                timestamp: Some(stamp(s.t)),
                frame_id: FRAME.into(),
                pose: Some(pose(s.origin.x, s.origin.y, 0.0, s.origin.h)),
                start_angle: s.angle_min,
                end_angle: end,
                ranges: s.ranges.iter().map(|&r| to_resolution(r)).collect(),
                intensities: Vec::new(),
            }),
        }
    }

    /// Adds a pose to the trajectory; the piece it ends, when it ends one. A piece
    /// starts at the last point of the one before, so the strips join. Standing
    /// still adds nothing.
    fn trajectory(&mut self, t: f64, x: f64, y: f64) -> Option<SceneUpdate> {
        let p = point(x, y);
        if let Some(last) = self.piece_points.last()
            && (last.x - p.x).hypot(last.y - p.y) < 1e-6
        {
            return None;
        }
        if self.piece_points.is_empty() {
            self.piece_start = t;
        }
        self.piece_points.push(p);
        if t - self.piece_start < TRAJECTORY_PIECE || self.piece_points.len() < 2 {
            return None;
        }
        self.piece += 1;
        let points = std::mem::replace(&mut self.piece_points, vec![p]);
        self.piece_start = t;
        let id = format!("trajectory-{}", self.piece);
        Some(strip(t, id, None, points, TRAJECTORY_COLOR, 0.02))
    }

    fn log(&self, module: &Module, e: &Event) -> Log {
        let stmt = e.stmt.and_then(|s| module.stmt(s));
        let (level, what) = match &e.kind {
            EventKind::End {
                how: How::Refused,
                reason,
                code,
                ..
            } => (
                log::Level::Warning,
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
                log::Level::Info,
                format!(
                    "end {}{}",
                    how.name(),
                    if *linked { " (linked)" } else { "" }
                ),
            ),
            EventKind::Error { message } => (log::Level::Error, format!("error: {message}")),
            EventKind::Overrun { pending } => {
                (log::Level::Warning, format!("overrun, {pending} pending"))
            }
            EventKind::Fault { fault, message } => {
                let reaction = fault.reaction();
                let code = Code::Fault(*fault);
                let level = match reaction {
                    Reaction::Raise | Reaction::SlowDown => log::Level::Warning,
                    _ => log::Level::Error,
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
                log::Level::Info,
                format!("cleared ({} {})", Code::Fault(*fault).code(), fault.name()),
            ),
            other => (log::Level::Info, other.name().to_string()),
        };
        let message = match stmt {
            Some(s) => format!("{what}: {}", s.text),
            None => what,
        };
        let file = stmt
            .and_then(|s| module.files.get(s.file.0 as usize))
            .cloned()
            .unwrap_or_else(|| self.task.clone());
        Log {
            timestamp: Some(stamp(e.t)),
            level: level as i32,
            message,
            name: "ilmr".into(),
            file,
            line: stmt.map_or(0, |s| s.line),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn root() -> std::path::PathBuf {
        std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
    }

    /// Every `"/topic"` a JSON text names, with what follows a `.` (a message path) cut.
    fn topics_named(text: &str) -> Vec<String> {
        text.split('"')
            .skip(1)
            .step_by(2)
            .filter(|s| s.starts_with('/') && s.len() > 1)
            .map(|s| s.split('.').next().unwrap_or(s).to_string())
            .collect()
    }

    #[test]
    fn the_layout_names_only_topics_the_view_publishes() {
        let layout = std::fs::read_to_string(root().join("tools/foxglove/ilmr-layout.json"))
            .expect("the shipped layout");
        let named = topics_named(&layout);
        assert!(named.len() >= 7, "{named:?}");
        let known: Vec<&str> = Topic::ALL.iter().map(|t| t.name()).collect();
        for topic in &named {
            assert!(known.contains(&topic.as_str()), "{topic} is not published");
        }
    }

    #[test]
    fn the_docs_list_every_topic_with_its_schema() {
        let docs = std::fs::read_to_string(root().join("docs/foxglove.md")).expect("docs");
        for topic in Topic::ALL {
            let row = format!("| `{}` | `{}` |", topic.name(), topic.schema().name);
            assert!(docs.contains(&row), "docs/foxglove.md lacks `{row}`");
        }
    }

    #[test]
    fn ranges_are_given_to_the_millimetre_and_infinity_stays() {
        assert_eq!(to_resolution(2.600414456482875), 2.6);
        assert_eq!(to_resolution(1.23456), 1.235);
        assert_eq!(to_resolution(f64::INFINITY), f64::INFINITY);
    }

    #[test]
    fn the_trajectory_is_cut_into_joined_pieces_and_standing_adds_nothing() {
        let mut m = Messages::new("t.ilmr");
        let mut pieces = Vec::new();
        for i in 0..=250 {
            let t = f64::from(i) * 0.01;
            // Drives along x, stands still from 1.5 s to 2 s.
            let x = if (150..200).contains(&i) {
                1.5
            } else {
                t.min(1.5) + (t - 2.0).max(0.0)
            };
            if let Some(p) = m.trajectory(t, x, 0.0) {
                pieces.push(p);
            }
        }
        assert_eq!(pieces.len(), 2, "a piece a second of driving");
        let points = |p: &SceneUpdate| p.entities[0].lines[0].points.clone();
        let (a, b) = (points(&pieces[0]), points(&pieces[1]));
        assert_eq!(pieces[1].entities[0].id, "trajectory-2");
        assert_eq!(
            a.last(),
            b.first(),
            "the second starts where the first ended"
        );
        let xs: Vec<f64> = b.iter().map(|p| p.x).collect();
        assert!(
            xs.windows(2).all(|w| w[1] > w[0]),
            "no point while standing: {xs:?}"
        );
    }
}

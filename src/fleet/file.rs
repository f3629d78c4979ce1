//! The fleet file (docs/fleet.md): one `[[robot]]` table per robot, each the options
//! `serve` takes for one robot, with a name a planner addresses it by. Relative paths
//! are relative to the fleet file.
//!
//! This reader depends on nothing of the binary (std, serde, toml, `ilmr_files` and
//! `ilmr_testfile`'s name of a ROS 2 robot): the fuzz target (`tests/fuzz/targets/fleets.rs`, and the AFL++ binary
//! through it) compiles it in by path, as it does `serve`'s protocol, since the root
//! package has no library. `super` turns a [`Member`] into `serve`'s options.

use std::fmt;
use std::ops::Range;
use std::path::{Path, PathBuf};

use ilmr_files::line_of;
use ilmr_testfile::place::ROS2_ROBOT;
use serde::Deserialize;
use toml::Spanned;

/// Robots in one fleet: each has a VM thread, and a ROS 2 one a DDS participant.
pub const MAX_FLEET_ROBOTS: usize = 64;

/// The longest robot name, characters.
pub const MAX_NAME: usize = 64;

/// The longest value of any other key, bytes: a path's longest (Linux's `PATH_MAX`).
/// Messages about a value quote it, and a file of a megabyte's value printed it whole.
pub const MAX_VALUE: usize = 4096;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct FileText {
    robot: Vec<Spanned<RobotEntry>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RobotEntry {
    name: Spanned<String>,
    robot: String,
    model: Option<String>,
    world: Option<String>,
    start: Option<String>,
    #[serde(default)]
    seed: u64,
    task: Option<PathBuf>,
    skills: Option<PathBuf>,
    namespace: Option<String>,
    domain: Option<u16>,
    #[serde(default)]
    loopback: bool,
    #[serde(default)]
    launch: bool,
}

/// One robot of a fleet, as the file gives it.
#[derive(Debug, Clone, PartialEq)]
pub struct Member {
    /// Letters, digits and `_`, starting with a letter, at most [`MAX_NAME`]; unique
    /// in the fleet.
    pub name: String,
    /// `moro`, `workpartner`, a ROBO.INI path, or [`ROS2_ROBOT`].
    pub robot: String,
    pub model: Option<String>,
    /// Where a simulated robot of this process is; `None` for a ROS 2 robot (a
    /// launched one's are in [`Launch`]).
    pub world: Option<String>,
    pub start: Option<String>,
    pub seed: u64,
    /// From the fleet file's folder when relative.
    pub task: Option<PathBuf>,
    pub skills: Option<PathBuf>,
    /// `Some` exactly for `robot = "ros2"`.
    pub ros2: Option<Ros2>,
    /// `launch = true`: `ilmrc fleet` starts `ilmrc sim --ros2` for this ROS 2 robot.
    pub launch: Option<Launch>,
}

/// A ROS 2 robot's DDS settings.
#[derive(Debug, Clone, PartialEq)]
pub struct Ros2 {
    /// `/` and the name unless the file gives one.
    pub namespace: String,
    pub domain: Option<u16>,
    pub loopback: bool,
}

/// The simulator `ilmrc fleet` starts for a ROS 2 robot: the body of its model, in its
/// world, at its start, with its seed.
#[derive(Debug, Clone, PartialEq)]
pub struct Launch {
    pub world: Option<String>,
    pub start: Option<String>,
}

/// Why a fleet file was refused, and the line it is about.
#[derive(Debug, Clone, PartialEq)]
pub struct Error {
    /// 1-based.
    pub line: usize,
    pub message: String,
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "line {}: {}", self.line, self.message)
    }
}

pub fn load(path: &Path) -> Result<Vec<Member>, String> {
    let text = ilmr_files::read_text(path, ilmr_files::Kind::Fleet)
        .map_err(|e| format!("cannot read fleet `{}`: {e}", path.display()))?;
    let base = path.parent().unwrap_or(Path::new("."));
    parse(&text, base).map_err(|e| format!("fleet `{}`: {e}", path.display()))
}

pub fn parse(text: &str, base: &Path) -> Result<Vec<Member>, Error> {
    let at = |span: Range<usize>, message: String| Error {
        line: line_of(text, span.start),
        message,
    };
    // The message alone: toml's Display quotes the whole line at fault, which may be
    // a megabyte long.
    let file: FileText = toml::from_str(text)
        .map_err(|e| at(e.span().unwrap_or(0..0), e.message().trim().to_string()))?;
    if file.robot.is_empty() {
        return Err(at(0..0, "no [[robot]]".into()));
    }
    if let Some(extra) = file.robot.get(MAX_FLEET_ROBOTS) {
        return Err(at(
            extra.span(),
            format!(
                "{} robots; a fleet has at most {MAX_FLEET_ROBOTS} (MAX_FLEET_ROBOTS)",
                file.robot.len()
            ),
        ));
    }
    let mut members: Vec<Member> = Vec::with_capacity(file.robot.len());
    for entry in file.robot {
        let table = entry.span();
        let e = entry.into_inner();
        let name_at = e.name.span();
        let name = e.name.into_inner();
        check_name(&name).map_err(|m| at(name_at.clone(), m))?;
        if members.iter().any(|m| m.name == name) {
            return Err(at(name_at, format!("two robots are named `{name}`")));
        }
        let paths = [("task", &e.task), ("skills", &e.skills)];
        let path_lengths = paths.map(|(k, p)| (k, p.as_ref().map_or(0, |p| p.as_os_str().len())));
        let texts = [
            ("robot", Some(&e.robot)),
            ("model", e.model.as_ref()),
            ("world", e.world.as_ref()),
            ("start", e.start.as_ref()),
            ("namespace", e.namespace.as_ref()),
        ];
        let lengths = texts.map(|(k, v)| (k, v.map_or(0, String::len)));
        if let Some((key, len)) = lengths
            .into_iter()
            .chain(path_lengths)
            .find(|(_, len)| *len > MAX_VALUE)
        {
            return Err(at(
                table,
                format!(
                    "robot `{name}`: `{key}` is {len} bytes; a value has at most {MAX_VALUE} (MAX_VALUE)"
                ),
            ));
        }
        let ros2 = e.robot.eq_ignore_ascii_case(ROS2_ROBOT);
        if !ros2 {
            for (key, given) in [
                ("namespace", e.namespace.is_some()),
                ("domain", e.domain.is_some()),
                ("loopback", e.loopback),
                ("launch", e.launch),
            ] {
                if given {
                    return Err(at(
                        table,
                        format!("robot `{name}`: `{key}` is for robot = \"ros2\""),
                    ));
                }
            }
        } else if (e.world.is_some() || e.start.is_some()) && !e.launch {
            return Err(at(
                table,
                format!(
                    "robot `{name}`: `world` and `start` place a simulated robot; a ROS 2 \
                     robot has them only with launch = true"
                ),
            ));
        }
        let from_base = |p: PathBuf| if p.is_absolute() { p } else { base.join(p) };
        let launch = (ros2 && e.launch).then(|| Launch {
            world: e.world.clone(),
            start: e.start.clone(),
        });
        let placed = |v: Option<String>| v.filter(|_| !ros2);
        members.push(Member {
            robot: e.robot,
            model: e.model,
            world: placed(e.world),
            start: placed(e.start),
            seed: e.seed,
            task: e.task.map(from_base),
            skills: e.skills.map(from_base),
            ros2: ros2.then(|| Ros2 {
                namespace: e.namespace.unwrap_or_else(|| format!("/{name}")),
                domain: e.domain,
                loopback: e.loopback,
            }),
            launch,
            name,
        });
    }
    Ok(members)
}

/// A name a planner types: letters, digits and `_`, starting with a letter, so that it
/// is also the default ROS 2 namespace (`/NAME`).
fn check_name(name: &str) -> Result<(), String> {
    let ok = name.chars().count() <= MAX_NAME
        && name.starts_with(|c: char| c.is_ascii_alphabetic())
        && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    if ok {
        Ok(())
    } else {
        Err(format!(
            "robot name `{}`: use up to {MAX_NAME} letters, digits and `_`, starting with a letter",
            name.chars().take(MAX_NAME).collect::<String>()
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const TWO: &str = r#"
[[robot]]
name = "r1"
robot = "ros2"
model = "moro"
loopback = true
launch = true
world = "empty"
start = "0,0,0"
task = "tasks/r1.ilmr"

[[robot]]
name = "lab"
robot = "workpartner"
world = "yard"
seed = 3
"#;

    #[test]
    fn a_fleet_file_gives_each_robot_serves_options() {
        let m = parse(TWO, Path::new("/fleets")).unwrap();
        assert_eq!(m.len(), 2);
        assert_eq!(m[0].name, "r1");
        let ros2 = m[0].ros2.as_ref().unwrap();
        assert_eq!(ros2.namespace, "/r1", "the name is the namespace");
        assert!(ros2.loopback);
        assert_eq!(
            m[0].task.as_deref(),
            Some(Path::new("/fleets/tasks/r1.ilmr"))
        );
        assert_eq!(
            m[0].launch,
            Some(Launch {
                world: Some("empty".into()),
                start: Some("0,0,0".into())
            })
        );
        assert_eq!(m[0].world, None, "the launched simulator has the world");
        assert_eq!(m[1].world.as_deref(), Some("yard"));
        assert_eq!(m[1].ros2, None);
        assert_eq!(m[1].seed, 3);
        assert!(m[1].launch.is_none());
    }

    #[test]
    fn mistakes_in_a_fleet_file_are_named_with_their_line() {
        for (text, line, says) in [
            ("", 1, "robot"),
            ("[[robot]]\nname = \"a\"\n", 1, "robot"),
            (
                "[[robot]]\nname = \"a\"\nrobot = \"moro\"\ncolour = 1\n",
                4,
                "colour",
            ),
            (
                "[[robot]]\nname = \"9a\"\nrobot = \"moro\"\n",
                2,
                "starting with a letter",
            ),
            (
                "[[robot]]\nrobot = \"moro\"\nname = \"a b\"\n",
                3,
                "letters, digits",
            ),
            (
                "[[robot]]\nname = \"a\"\nrobot = \"moro\"\n[[robot]]\nname = \"a\"\nrobot = \"moro\"\n",
                5,
                "two robots are named `a`",
            ),
            (
                "[[robot]]\nname = \"a\"\nrobot = \"moro\"\n\n[[robot]]\nname = \"b\"\nrobot = \"moro\"\nnamespace = \"/a\"\n",
                5,
                "for robot = \"ros2\"",
            ),
            (
                "[[robot]]\nname = \"a\"\nrobot = \"ros2\"\nworld = \"office\"\n",
                1,
                "launch = true",
            ),
        ] {
            let e = parse(text, Path::new(".")).unwrap_err();
            assert!(e.message.contains(says), "{text:?}: {e}");
            assert_eq!(e.line, line, "{text:?}: {e}");
        }
        let many = "[[robot]]\nname = \"a\"\nrobot = \"moro\"\n".repeat(MAX_FLEET_ROBOTS + 1);
        let e = parse(&many, Path::new(".")).unwrap_err();
        assert!(e.message.contains("MAX_FLEET_ROBOTS"), "{e}");
        assert_eq!(e.line, 3 * MAX_FLEET_ROBOTS + 1, "the first robot too many");
    }

    /// toml's own Display quotes the line at fault whole: a file of one long line
    /// would put a megabyte in the message.
    #[test]
    fn a_long_line_is_not_quoted_in_the_message() {
        let text = format!(
            "[[robot]]\nname = \"a\"\nrobot = \"moro\"\nx = {}\n",
            "1".repeat(1 << 20)
        );
        let e = parse(&text, Path::new(".")).unwrap_err();
        assert_eq!(e.line, 4);
        assert!(e.to_string().len() < 200, "{} bytes", e.to_string().len());
    }

    /// A robot, world or start of a megabyte was accepted, and `ilmrc fleet` quoted it
    /// whole when it named no robot, world or pose.
    #[test]
    fn a_value_longer_than_a_path_is_refused_with_its_line() {
        for key in ["robot", "model", "world", "start", "task", "skills"] {
            let long = "x".repeat(MAX_VALUE + 1);
            let mut text = "[[robot]]\nname = \"a\"\nrobot = \"moro\"\n\n[[robot]]\nname = \"b\"\n"
                .to_string();
            if key != "robot" {
                text.push_str("robot = \"moro\"\n");
            }
            text.push_str(&format!("{key} = \"{long}\"\n"));
            let e = parse(&text, Path::new(".")).unwrap_err();
            assert!(
                e.message.contains(&format!("`{key}` is 4097 bytes")),
                "{key}: {e}"
            );
            assert!(e.message.len() < 200, "{key}: {e}");
            assert_eq!(e.line, 5, "{key}: the robot's table");
        }
        let fine = format!(
            "[[robot]]\nname = \"a\"\nrobot = \"{}\"\n",
            "x".repeat(MAX_VALUE)
        );
        assert!(parse(&fine, Path::new(".")).is_ok());
    }

    #[test]
    fn the_limits_table_quotes_the_fleet_limit() {
        let docs = include_str!("../../docs/reliability.md");
        let row = docs
            .lines()
            .find(|l| l.starts_with('|') && l.contains("MAX_FLEET_ROBOTS"))
            .expect("a row names MAX_FLEET_ROBOTS");
        assert!(row.contains(&format!("{MAX_FLEET_ROBOTS} robots")), "{row}");
    }
}

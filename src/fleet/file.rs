//! The fleet file (docs/fleet.md): one `[[robot]]` table per robot, each the options
//! `serve` takes for one robot, with a name a planner addresses it by. Relative paths
//! are relative to the fleet file.

use std::path::{Path, PathBuf};

use serde::Deserialize;

use crate::live::RobotArgs;
use crate::ros2::Ros2Args;

/// Robots in one fleet: each has a VM thread, and a ROS 2 one a DDS participant.
pub const MAX_FLEET_ROBOTS: usize = 64;

/// The longest robot name, characters.
const MAX_NAME: usize = 64;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct FileText {
    robot: Vec<RobotEntry>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RobotEntry {
    name: String,
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

/// One robot of a fleet.
#[derive(Debug)]
pub struct Member {
    pub name: String,
    pub args: RobotArgs,
    /// `launch = true`: `ilmrc fleet` starts `ilmrc sim --ros2` for this ROS 2 robot.
    pub launch: Option<Launch>,
}

/// The simulator `ilmrc fleet` starts for a ROS 2 robot: the body of its model, in its
/// world, at its start, with its seed.
#[derive(Debug, Clone, PartialEq)]
pub struct Launch {
    pub world: Option<String>,
    pub start: Option<String>,
}

pub fn load(path: &Path) -> Result<Vec<Member>, String> {
    let text = ilmr_files::read_text(path, ilmr_files::Kind::Fleet)
        .map_err(|e| format!("cannot read fleet `{}`: {e}", path.display()))?;
    let base = path.parent().unwrap_or(Path::new("."));
    parse(&text, base).map_err(|e| format!("fleet `{}`: {e}", path.display()))
}

fn parse(text: &str, base: &Path) -> Result<Vec<Member>, String> {
    let file: FileText = toml::from_str(text).map_err(|e| e.to_string().trim().to_string())?;
    if file.robot.is_empty() {
        return Err("no [[robot]]".into());
    }
    if file.robot.len() > MAX_FLEET_ROBOTS {
        return Err(format!(
            "{} robots; a fleet has at most {MAX_FLEET_ROBOTS} (MAX_FLEET_ROBOTS)",
            file.robot.len()
        ));
    }
    let mut members: Vec<Member> = Vec::with_capacity(file.robot.len());
    for e in file.robot {
        check_name(&e.name)?;
        if members.iter().any(|m| m.name == e.name) {
            return Err(format!("two robots are named `{}`", e.name));
        }
        let ros2 = e.robot.eq_ignore_ascii_case(crate::ros2::ROBOT_NAME);
        if !ros2 {
            for (key, given) in [
                ("namespace", e.namespace.is_some()),
                ("domain", e.domain.is_some()),
                ("loopback", e.loopback),
                ("launch", e.launch),
            ] {
                if given {
                    return Err(format!(
                        "robot `{}`: `{key}` is for robot = \"ros2\"",
                        e.name
                    ));
                }
            }
        } else if (e.world.is_some() || e.start.is_some()) && !e.launch {
            return Err(format!(
                "robot `{}`: `world` and `start` place a simulated robot; a ROS 2 robot has \
                 them only with launch = true",
                e.name
            ));
        }
        let at = |p: PathBuf| if p.is_absolute() { p } else { base.join(p) };
        let launch = (ros2 && e.launch).then(|| Launch {
            world: e.world.clone(),
            start: e.start.clone(),
        });
        let placed = |v: Option<String>| v.filter(|_| launch.is_none());
        let namespace = match ros2 {
            true => Some(e.namespace.unwrap_or_else(|| format!("/{}", e.name))),
            false => None,
        };
        members.push(Member {
            args: RobotArgs {
                robot: e.robot,
                model: e.model,
                world: placed(e.world),
                start: placed(e.start),
                seed: e.seed,
                skills: e.skills.map(at),
                task: e.task.map(at),
                ros2: Ros2Args {
                    ros_namespace: namespace,
                    ros_domain: e.domain,
                    ros_wait: None,
                    ros_loopback: e.loopback,
                },
                view: Default::default(),
            },
            name: e.name,
            launch,
        });
    }
    Ok(members)
}

/// A name a planner types: letters, digits, `_` and `-`, starting with a letter, so
/// that it is also the default ROS 2 namespace (`/NAME`).
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
        assert_eq!(
            m[0].args.ros2.ros_namespace.as_deref(),
            Some("/r1"),
            "the name is the namespace"
        );
        assert!(m[0].args.ros2.ros_loopback);
        assert_eq!(
            m[0].args.task.as_deref(),
            Some(Path::new("/fleets/tasks/r1.ilmr"))
        );
        assert_eq!(
            m[0].launch,
            Some(Launch {
                world: Some("empty".into()),
                start: Some("0,0,0".into())
            })
        );
        assert_eq!(
            m[0].args.world, None,
            "the launched simulator has the world"
        );
        assert_eq!(m[1].args.world.as_deref(), Some("yard"));
        assert_eq!(m[1].args.ros2.ros_namespace, None);
        assert_eq!(m[1].args.seed, 3);
        assert!(m[1].launch.is_none());
    }

    #[test]
    fn mistakes_in_a_fleet_file_are_named() {
        for (text, says) in [
            ("", "robot"),
            ("[[robot]]\nname = \"a\"\n", "robot"),
            (
                "[[robot]]\nname = \"a\"\nrobot = \"moro\"\ncolour = 1\n",
                "colour",
            ),
            (
                "[[robot]]\nname = \"9a\"\nrobot = \"moro\"\n",
                "starting with a letter",
            ),
            (
                "[[robot]]\nname = \"a b\"\nrobot = \"moro\"\n",
                "letters, digits",
            ),
            (
                "[[robot]]\nname = \"a\"\nrobot = \"moro\"\n[[robot]]\nname = \"a\"\nrobot = \"moro\"\n",
                "two robots are named `a`",
            ),
            (
                "[[robot]]\nname = \"a\"\nrobot = \"moro\"\nnamespace = \"/a\"\n",
                "for robot = \"ros2\"",
            ),
            (
                "[[robot]]\nname = \"a\"\nrobot = \"ros2\"\nworld = \"office\"\n",
                "launch = true",
            ),
        ] {
            let e = parse(text, Path::new(".")).unwrap_err();
            assert!(e.contains(says), "{text:?}: {e}");
        }
        let many = "[[robot]]\nname = \"a\"\nrobot = \"moro\"\n".repeat(MAX_FLEET_ROBOTS + 1);
        assert!(
            parse(&many, Path::new("."))
                .unwrap_err()
                .contains("MAX_FLEET_ROBOTS")
        );
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

//! Fleet files, as `ilmrc fleet` and `serve --fleet` read them: the reader
//! (src/fleet/file.rs, compiled in here since the root package has no library). A
//! file it accepts holds one to `MAX_FLEET_ROBOTS` robots, each with a valid name of
//! its own and the settings of its kind of robot only; one it refuses gets a line of
//! the file and a short message.

use std::path::Path;

use crate::engine::{self, Budget, Stats};
use crate::mutate;

#[allow(dead_code)]
#[path = "../../../src/fleet/file.rs"]
mod file;

use file::{MAX_FLEET_ROBOTS, MAX_NAME, MAX_VALUE};

/// Where the fuzzed file is: relative paths in it are joined to this.
const BASE: &str = "/fleets";

/// The longest message a refusal may carry, bytes: a few sentences, whatever the file.
pub const MAX_MESSAGE: usize = 400;

/// The fleet files of the docs and of the tests that start fleets.
pub fn seeds() -> Vec<Vec<u8>> {
    let docs = std::fs::read_to_string(engine::root().join("docs/fleet.md"))
        .expect("docs/fleet.md is read");
    let mut out: Vec<Vec<u8>> = toml_blocks(&docs)
        .into_iter()
        .map(String::into_bytes)
        .collect();
    assert!(!out.is_empty(), "docs/fleet.md shows a fleet file");
    for seed in [
        // tests/serve.rs's two robots in one process.
        "[[robot]]\nname = \"a\"\nrobot = \"moro\"\nworld = \"empty\"\nstart = \"0,0,0\"\n\n\
         [[robot]]\nname = \"b\"\nrobot = \"moro\"\nworld = \"empty\"\nstart = \"0,5,0\"\n",
        // tests/ros2.rs's launched ROS 2 robot.
        "[[robot]]\nname = \"a\"\nrobot = \"ros2\"\nnamespace = \"/ns\"\n\
         loopback = true\nlaunch = true\nworld = \"empty\"\n",
        "[[robot]]\nname = \"w\"\nrobot = \"workpartner\"\nworld = \"yard\"\nseed = 3\n\
         skills = \"../examples/skills\"\ntask = \"/abs/go.ilmr\"\n",
        "[[robot]]\nname = \"r\"\nrobot = \"ROS2\"\nmodel = \"moro\"\ndomain = 65535\n",
    ] {
        out.push(seed.as_bytes().to_vec());
    }
    out
}

/// The fenced ```toml blocks of a markdown text.
fn toml_blocks(markdown: &str) -> Vec<String> {
    let mut blocks = Vec::new();
    let mut open: Option<String> = None;
    for line in markdown.lines() {
        match (&mut open, line.trim_start()) {
            (None, "```toml") => open = Some(String::new()),
            (Some(block), "```") => {
                blocks.push(std::mem::take(block));
                open = None;
            }
            (Some(block), _) => {
                block.push_str(line);
                block.push('\n');
            }
            (None, _) => {}
        }
    }
    blocks
}

/// The format's keys and values.
pub fn dictionary() -> Vec<String> {
    let words: Vec<String> = [
        "[[robot]]",
        "[robot]",
        "name = ",
        "robot = ",
        "model = ",
        "world = ",
        "start = ",
        "seed = ",
        "task = ",
        "skills = ",
        "namespace = ",
        "domain = ",
        "loopback = ",
        "launch = ",
        "\"ros2\"",
        "\"moro\"",
        "\"workpartner\"",
        "\"empty\"",
        "\"0,0,0\"",
        "true",
        "false",
        "65536",
        "18446744073709551616",
        "[",
        "]",
        "{",
        "}",
        "=",
        ",",
        "\"",
        "'''",
        "\"\"\"",
    ]
    .iter()
    .map(|w| w.to_string())
    .collect();
    mutate::with_numbers_and_spacing(words)
}

/// The target, shared by this loop and the AFL++ binary (`fuzz/src/bin/fleet.rs`).
pub fn feed(input: &[u8]) {
    // `ilmr_files::read_text` refuses other bytes before the reader sees them.
    let Ok(text) = std::str::from_utf8(input) else {
        return;
    };
    match file::parse(text, Path::new(BASE)) {
        Ok(members) => accepted(&members),
        Err(e) => {
            let lines = text.matches('\n').count() + 1;
            assert!(
                (1..=lines).contains(&e.line),
                "line {} of a file of {lines} lines: {e:?}",
                e.line
            );
            assert!(!e.message.is_empty(), "an error says why: {e:?}");
            assert!(
                e.message.len() <= MAX_MESSAGE,
                "a message of {} bytes: {:?}",
                e.message.len(),
                e.message.chars().take(MAX_MESSAGE).collect::<String>()
            );
        }
    }
}

/// What the file's documentation promises of an accepted fleet.
fn accepted(members: &[file::Member]) {
    assert!(
        (1..=MAX_FLEET_ROBOTS).contains(&members.len()),
        "{} robots accepted",
        members.len()
    );
    for (i, m) in members.iter().enumerate() {
        assert!(
            m.name.len() <= MAX_NAME
                && m.name.starts_with(|c: char| c.is_ascii_alphabetic())
                && m.name
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || c == '_'),
            "name {:?} accepted",
            m.name
        );
        assert!(
            members[..i].iter().all(|o| o.name != m.name),
            "two robots named {:?} accepted",
            m.name
        );
        let texts = [
            Some(&m.robot),
            m.model.as_ref(),
            m.world.as_ref(),
            m.start.as_ref(),
        ];
        for v in texts.into_iter().flatten() {
            assert!(
                v.len() <= MAX_VALUE,
                "a value of {} bytes accepted",
                v.len()
            );
        }
        for p in [&m.task, &m.skills].into_iter().flatten() {
            // The base is absolute, so every path joined to it is too.
            assert!(p.is_absolute(), "{p:?} is not from the file's folder");
        }
        match &m.ros2 {
            Some(_) => {
                assert!(m.robot.eq_ignore_ascii_case("ros2"), "{m:?}");
                assert!(
                    m.world.is_none() && m.start.is_none(),
                    "a ROS 2 robot placed: {m:?}"
                );
            }
            None => {
                assert!(!m.robot.eq_ignore_ascii_case("ros2"), "{m:?}");
                assert!(
                    m.launch.is_none(),
                    "a simulator launched for a simulated robot: {m:?}"
                );
            }
        }
    }
}

pub fn fuzz(budget: Budget) -> Stats {
    let corpus = seeds();
    let words = dictionary();
    engine::run(
        "fleet",
        &corpus,
        budget,
        |base, rng| mutate::text(base, rng, &corpus, &words),
        feed,
    )
}

//! Shared by the test drivers: load fixtures, check them, render what a person sees.

#![allow(dead_code)]

pub mod taskgen;

use std::path::{Path, PathBuf};

use ilmr_compiler::check::{Analysis, Source, analyze};
use ilmr_compiler::render::{self, RenderFile, Style};
use ilmr_model::RobotModel;

pub const ROBOTS: [&str; 2] = ["moro", "workpartner"];

/// The exit code a run's summary says (`  exit            3`).
pub fn summary_exit(summary: &str) -> Option<i32> {
    summary
        .lines()
        .find_map(|l| l.trim().strip_prefix("exit"))
        .and_then(|c| c.trim().parse().ok())
}

/// Runs the built `ilmrc` from the repository root: exit code, stdout, stderr.
pub fn ilmrc(args: &[&str]) -> (i32, String, String) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_ilmrc"))
        .args(args)
        .current_dir(root())
        .env("NO_COLOR", "1")
        .output()
        .expect("ilmrc runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// As [`ilmrc`], but killed (and the test failed) when it has not ended within
/// `limit`: a guard against a hang or an input that grows without bound, not a timing.
pub fn ilmrc_within(args: &[&str], limit: std::time::Duration) -> (i32, String, String) {
    use std::io::Read;
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_ilmrc"))
        .args(args)
        .current_dir(root())
        .env("NO_COLOR", "1")
        .stdin(std::process::Stdio::null())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("ilmrc runs");
    let drain = |pipe: Option<Box<dyn Read + Send>>| {
        std::thread::spawn(move || {
            let mut text = Vec::new();
            if let Some(mut p) = pipe {
                let _ = p.read_to_end(&mut text);
            }
            String::from_utf8_lossy(&text).into_owned()
        })
    };
    let out = drain(
        child
            .stdout
            .take()
            .map(|p| Box::new(p) as Box<dyn Read + Send>),
    );
    let err = drain(
        child
            .stderr
            .take()
            .map(|p| Box::new(p) as Box<dyn Read + Send>),
    );
    let deadline = std::time::Instant::now() + limit;
    let code = loop {
        if let Some(status) = child.try_wait().expect("wait for ilmrc") {
            break status.code().unwrap_or(-1);
        }
        if std::time::Instant::now() > deadline {
            let _ = child.kill();
            let _ = child.wait();
            panic!("`ilmrc {}` did not end within {limit:?}", args.join(" "));
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    };
    (
        code,
        out.join().unwrap_or_default(),
        err.join().unwrap_or_default(),
    )
}

pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The robot a fixture was written for, from its `// robot: NAME` line.
pub fn intended_robot(text: &str) -> &str {
    text.lines()
        .find_map(|l| l.trim().strip_prefix("// robot:"))
        .map(str::trim)
        .expect("fixtures name their robot with `// robot: NAME`")
}

pub fn model(name: &str) -> RobotModel {
    RobotModel::builtin(name).expect("shipped model")
}

/// The file itself, plus the example skill library.
pub fn program(path: &Path) -> Vec<Source> {
    let text = std::fs::read_to_string(path).unwrap();
    let display = path.strip_prefix(root()).unwrap().display().to_string();
    let mut sources = vec![Source::new(display, text)];
    let mut skills: Vec<PathBuf> = std::fs::read_dir(root().join("examples/skills"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    skills.sort();
    for p in skills {
        let display = p.strip_prefix(root()).unwrap().display().to_string();
        sources.push(Source::library(
            display,
            std::fs::read_to_string(&p).unwrap(),
        ));
    }
    sources
}

pub fn render_files<'a>(analysis: &'a Analysis<'_>) -> Vec<RenderFile<'a>> {
    analysis
        .files
        .iter()
        .map(|f| RenderFile {
            path: f.path,
            text: f.text,
        })
        .collect()
}

pub fn human(analysis: &Analysis<'_>) -> String {
    let out = render::human(&analysis.diagnostics, &render_files(analysis), Style::PLAIN);
    if out.is_empty() {
        "(no diagnostics)\n".into()
    } else {
        out
    }
}

pub fn check<'s>(sources: &'s [Source], robot: &str) -> (Analysis<'s>, RobotModel) {
    let m = model(robot);
    let analysis = analyze(sources, &m);
    (analysis, m)
}

/// An MCAP file as Foxglove's own Python libraries read it (`tools/read_mcap.py`,
/// with `mcap`, `mcap-protobuf-support` and `mcap-ros2-support`, which CI installs):
/// per topic its schema, encodings, counts and the essentials of its messages. Fails
/// unless every message decodes with its channel's schema.
pub fn foxglove_reads(mcap: &Path) -> serde_json::Value {
    let out = std::process::Command::new("python3")
        .arg(root().join("tools/read_mcap.py"))
        .arg(mcap)
        .output()
        .expect("python3 runs");
    let topics: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap_or_else(|e| {
        panic!(
            "tools/read_mcap.py read nothing ({e}); CI installs `mcap`, \
             `mcap-protobuf-support` and `mcap-ros2-support`:\n{}",
            String::from_utf8_lossy(&out.stderr)
        )
    });
    assert!(
        out.status.success(),
        "a message of {} did not decode: {topics}",
        mcap.display()
    );
    topics
}

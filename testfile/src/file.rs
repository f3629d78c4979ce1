//! A test file: TOML, one `[[test]]` table per test, keys at the top as every test's
//! defaults. Read with every value's span, so that each problem is said where it is;
//! all of a file's problems are found, not just the first.

use std::collections::HashMap;
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use toml::Spanned;
use toml::de::{DeTable, DeValue};

use ilmr_model::ModelWarning;

use crate::assertion::{self, Assertion, Context, Place, is_name};
use crate::codes::Code;
use crate::place::{self, Backend};
use crate::problem::Problem;
use crate::scenario::{Line, Scenario};
use crate::snapshot::{self, Snapshot};

/// Every key of a test and what it takes (docs/testing.md lists them from here).
pub const KEYS: [(&str, &str); 15] = [
    ("name", "the test's name (required in each `[[test]]`)"),
    (
        "task",
        "the task file, from the test file's folder (required)",
    ),
    ("skills", "a skill file or folder of skill files"),
    (
        "robot",
        "`moro`, `workpartner`, a ROBO.INI path, `scripted` or `none` (default `moro`)",
    ),
    (
        "model",
        "with `robot = \"scripted\"` or `\"none\"`: the model checked against",
    ),
    (
        "world",
        "`office`, `yard`, `empty` or a world file (default: the robot's)",
    ),
    (
        "start",
        "where the robot starts: `\"X,Y,HEADING\"` or `[X, Y, HEADING]`, metres and degrees",
    ),
    (
        "profile",
        "a simulated robot's errors: `ideal`, `basic` or `calibrated` (default) (`--sim-profile`)",
    ),
    (
        "seeds",
        "a seed, a list of seeds or a range `\"1-20\"`: every seed must pass (default 0)",
    ),
    (
        "faults",
        "faults to inject, as `--fault` takes them: `[\"scanner_dropout@5+3\"]`",
    ),
    (
        "lines",
        "interactive lines: `[{ t = 5, text = \"speed(0.2)\" }]`",
    ),
    (
        "scenario",
        "a scenario file (`--scenario`): taught paths; for `robot = \"scripted\"` its world",
    ),
    (
        "max_time",
        "seconds of logical time the run may take (default 600, as `ilmrc run`)",
    ),
    (
        "assert",
        "the assertions, one a string (required; grammar in docs/testing.md)",
    ),
    (
        "snapshot",
        "`true`, or `{ precision = 0.01, scans = true }`: compare the trace with a stored snapshot",
    ),
];

/// Seeds one test may run: a range beyond this is a typo more likely than a plan.
pub const MAX_SEEDS: u64 = 10_000;
/// Tests of one file: each holds its seeds, arguments and assertions, and the file's
/// defaults reach every one (a hundred thousand `[[test]]` of 10,000 seeds each took
/// gigabytes).
pub const MAX_TESTS: usize = 1_000;
/// Problems reported of one file, the first in the file's order: a file of a million
/// broken lines has millions, each shown with its line.
pub const MAX_PROBLEMS: usize = 100;
/// The longest `max_time`, seconds: a day of logical time (some minutes of a debug
/// build); a task that never ends is then cut off rather than run for weeks.
pub const MAX_TIME: f64 = 86_400.0;

/// A test file read and checked.
pub struct TestFile {
    pub path: PathBuf,
    pub text: String,
    pub tests: Vec<Test>,
}

/// One `[[test]]`: how to run it, and what must hold.
pub struct Test {
    pub name: String,
    /// The name's place in the file (the table's header when it has none).
    pub span: Range<usize>,
    /// `ilmrc run`'s arguments (after `run`), less the seed and the trace.
    pub argv: Vec<String>,
    pub lines: Vec<Line>,
    pub seeds: Vec<u64>,
    pub assertions: Vec<Assertion>,
    pub snapshot: Option<Snapshot>,
}

/// What reading a test file says besides its problems, which `ilmrc test` prints on
/// stderr as `ilmrc run` does.
#[derive(Debug, Clone, PartialEq)]
pub enum Note {
    /// A robot model file's warnings (a value out of range: the default stands in).
    Model {
        spec: String,
        warnings: Vec<ModelWarning>,
    },
    /// Files of a skill directory that hold no skills by their extension.
    SkillsIgnored { dir: PathBuf, files: Vec<PathBuf> },
}

/// A test file read: the tests when it has no problem, else every problem; what the
/// reader noted; and what each `[[test]]` table's assertions can name, for an editor.
pub struct Read {
    pub file: Result<TestFile, Vec<Problem>>,
    pub notes: Vec<Note>,
    pub outlines: Vec<Outline>,
}

/// One `[[test]]` table as an editor sees it: where it is, where its assertions are,
/// and what they can name (as far as its task and robot could be read).
#[derive(Debug, Clone, Default)]
pub struct Outline {
    /// The table, from its header.
    pub span: Range<usize>,
    /// Each string of its `assert`: the string's span, and where its content starts
    /// when the bytes there are the content as read (no escapes).
    pub asserts: Vec<(Range<usize>, Option<usize>)>,
    /// The task's statements, line and text; empty when it could not be read. Shared
    /// by the tests of one task.
    pub statements: Arc<Vec<(u32, String)>>,
    pub variables: Vec<String>,
    /// The world's named places, for a simulated robot.
    pub objects: Option<Vec<Place>>,
    /// The robot's model's name or file, when the robot could be placed.
    pub model: Option<String>,
    pub poses: bool,
    pub scans: bool,
}

impl Outline {
    /// The names an assertion of this test can use.
    pub fn context(&self) -> Context<'_> {
        Context {
            statements: &self.statements,
            variables: &self.variables,
            objects: self.objects.as_deref(),
            poses: self.poses,
            scans: self.scans,
        }
    }
}

/// Reads a test file; `Err` holds every problem found.
pub fn read(path: &Path, text: String) -> Result<TestFile, Vec<Problem>> {
    check(path, text).file
}

/// Reads a test file, with what an editor needs besides its problems.
pub fn check(path: &Path, text: String) -> Read {
    let mut notes = Vec::new();
    let mut outlines = Vec::new();
    let mut file = read_into(path, text, &mut notes, &mut outlines);
    // In the file's order, whichever way the reading ended.
    if let Err(problems) = &mut file {
        problems.sort_by_key(|p| (p.span.start, p.span.end));
        if problems.len() > MAX_PROBLEMS {
            let more = problems.len() - MAX_PROBLEMS;
            problems.truncate(MAX_PROBLEMS);
            let last = problems.pop().expect("MAX_PROBLEMS is above 0");
            problems.push(last.help(format!(
                "{more} more problem(s) after this one are not shown (MAX_PROBLEMS)"
            )));
        }
    }
    Read {
        file,
        notes,
        outlines,
    }
}

fn read_into(
    path: &Path,
    text: String,
    notes: &mut Vec<Note>,
    outlines: &mut Vec<Outline>,
) -> Result<TestFile, Vec<Problem>> {
    let mut problems = Vec::new();
    let (root, errors) = DeTable::parse_recoverable(&text);
    for e in errors {
        let span = e.span().unwrap_or(0..0);
        problems.push(Problem::new(
            Code::NotToml,
            span,
            e.message().trim().to_string(),
        ));
    }
    if !problems.is_empty() {
        return Err(problems);
    }
    let dir = path.parent().unwrap_or(Path::new(".")).to_path_buf();
    let root = root.into_inner();
    let mut tests = Vec::new();
    let mut defaults: Vec<(&Spanned<std::borrow::Cow<str>>, &Spanned<DeValue>)> = Vec::new();
    let mut tables = None;
    for (key, value) in root.iter() {
        match key.get_ref().as_ref() {
            "test" => tables = Some(value),
            "name" => problems.push(Problem::new(
                Code::UnknownKey,
                key.span(),
                "`name` belongs in a `[[test]]` table; the keys at the top are every test's defaults",
            )),
            k if KEYS.iter().any(|(n, _)| *n == k) => defaults.push((key, value)),
            k => problems.push(unknown_key(k, key.span(), true)),
        }
    }
    let Some(tables) = tables else {
        problems.push(
            Problem::new(Code::MissingKey, 0..0, "the file has no `[[test]]` table")
                .help("add `[[test]]` with a `name`, a `task` and `assert`"),
        );
        return Err(problems);
    };
    let Some(array) = tables.get_ref().as_array() else {
        problems.push(Problem::new(
            Code::WrongType,
            tables.span(),
            "`test` is an array of tables: write each test as `[[test]]`",
        ));
        return Err(problems);
    };
    if let Some(extra) = array.get(MAX_TESTS) {
        problems.push(Problem::new(
            Code::BadValue,
            extra.span(),
            format!(
                "{} tests; a file holds at most {MAX_TESTS} (MAX_TESTS)",
                array.len()
            ),
        ));
        return Err(problems);
    }
    let mut names: Vec<(String, Range<usize>)> = Vec::new();
    let mut tasks = Tasks::new();
    for item in array.iter() {
        let Some(table) = item.get_ref().as_table() else {
            problems.push(Problem::new(
                Code::WrongType,
                item.span(),
                "a test is a table",
            ));
            continue;
        };
        let mut keys: Vec<(&Spanned<std::borrow::Cow<str>>, &Spanned<DeValue>)> = defaults.clone();
        for (key, value) in table.iter() {
            let k = key.get_ref().as_ref();
            if k != "name" && !KEYS.iter().any(|(n, _)| *n == k) {
                problems.push(unknown_key(k, key.span(), false));
                continue;
            }
            keys.retain(|(d, _)| d.get_ref() != key.get_ref());
            keys.push((key, value));
        }
        let header = item.span();
        let named = table
            .get("name")
            .and_then(|v| v.get_ref().as_str().map(|n| (n, v.span())));
        if let Some((name, span)) = named {
            if names.iter().any(|(n, _)| n == name) {
                problems.push(
                    Problem::new(
                        Code::DuplicateName,
                        span.clone(),
                        format!("a second test named `{name}`"),
                    )
                    .help("each test of a file needs its own name"),
                );
            }
            names.push((name.to_string(), span));
        }
        let mut reader = Reader {
            path,
            text: &text,
            dir: &dir,
            keys,
            header: header.clone(),
            problems: &mut problems,
            notes,
            tasks: &mut tasks,
            outline: Outline {
                span: header.clone(),
                ..Outline::default()
            },
        };
        let test = reader.test();
        outlines.push(reader.outline);
        if let Some(test) = test {
            tests.push(test);
        }
    }
    if problems.is_empty() {
        Ok(TestFile {
            path: path.to_path_buf(),
            text,
            tests,
        })
    } else {
        Err(problems)
    }
}

fn unknown_key(key: &str, span: Range<usize>, top: bool) -> Problem {
    let mut names: Vec<&str> = KEYS.iter().map(|(n, _)| *n).collect();
    if !top {
        names.push("name");
    }
    Problem::new(Code::UnknownKey, span, format!("unknown key `{key}`")).suggest(key, names)
}

type Key<'a> = (
    &'a Spanned<std::borrow::Cow<'a, str>>,
    &'a Spanned<DeValue<'a>>,
);

struct Reader<'a, 'p> {
    path: &'a Path,
    text: &'a str,
    dir: &'a Path,
    keys: Vec<Key<'a>>,
    header: Range<usize>,
    problems: &'p mut Vec<Problem>,
    notes: &'p mut Vec<Note>,
    /// Each task's statements, read once for all the tests of the file.
    tasks: &'p mut Tasks,
    outline: Outline,
}

type Tasks = HashMap<PathBuf, Result<Arc<Vec<(u32, String)>>, String>>;

impl<'a> Reader<'a, '_> {
    fn get(&self, key: &str) -> Option<&'a Spanned<DeValue<'a>>> {
        self.keys
            .iter()
            .find(|(k, _)| k.get_ref().as_ref() == key)
            .map(|(_, v)| *v)
    }

    fn wrong(&mut self, key: &str, value: &Spanned<DeValue>, wanted: &str) {
        self.problems.push(Problem::new(
            Code::WrongType,
            value.span(),
            format!(
                "`{key}` takes {wanted}, not a {}",
                value.get_ref().type_str()
            ),
        ));
    }

    fn string(&mut self, key: &str) -> Option<(String, Range<usize>)> {
        let value = self.get(key)?;
        match value.get_ref().as_str() {
            Some(s) => Some((s.to_string(), value.span())),
            None => {
                self.wrong(key, value, "a string");
                None
            }
        }
    }

    /// `profile`: one of the simulator's error profiles, by name.
    fn profile(&mut self) -> Option<(ilmr_sim::SimProfile, Range<usize>)> {
        let (name, span) = self.string("profile")?;
        match ilmr_sim::SimProfile::parse(&name) {
            Some(p) => Some((p, span)),
            None => {
                let names: Vec<&str> = ilmr_sim::SimProfile::ALL.iter().map(|p| p.name()).collect();
                self.problems.push(Problem::new(
                    Code::BadValue,
                    span,
                    format!("no profile `{name}`: use {}", names.join(", ")),
                ));
                None
            }
        }
    }

    fn number(&mut self, key: &str) -> Option<(f64, Range<usize>)> {
        let value = self.get(key)?;
        match number(value.get_ref()) {
            Some(n) => Some((n, value.span())),
            None => {
                self.wrong(key, value, "a number");
                None
            }
        }
    }

    /// A path from the test file's folder, which must exist.
    fn file(&mut self, key: &str) -> Option<(PathBuf, Range<usize>)> {
        let (name, span) = self.string(key)?;
        let path = self.existing(&name, &span)?;
        Some((path, span))
    }

    /// `name` from the test file's folder, when it exists; else a problem at `span`.
    fn existing(&mut self, name: &str, span: &Range<usize>) -> Option<PathBuf> {
        let path = self.dir.join(name);
        if !path.exists() {
            self.problems.push(Problem::new(
                Code::MissingFile,
                span.clone(),
                format!("no file `{}`", path.display()),
            ));
            return None;
        }
        Some(path)
    }

    /// A name, or a path when it looks like one (taken from the test file's folder).
    fn name_or_path(&mut self, key: &str) -> Option<(String, Range<usize>)> {
        let (name, span) = self.string(key)?;
        if name.contains(['/', '\\', '.']) {
            let path = self.existing(&name, &span)?;
            return Some((path.display().to_string(), span));
        }
        Some((name, span))
    }

    fn test(&mut self) -> Option<Test> {
        let before = self.problems.len();
        let name = self.string("name");
        if name.is_none() && self.get("name").is_none() {
            self.problems.push(Problem::new(
                Code::MissingKey,
                self.header.clone(),
                "this test has no `name`",
            ));
        }
        let task = self.file("task");
        if task.is_none() && self.get("task").is_none() {
            self.problems.push(Problem::new(
                Code::MissingKey,
                self.header.clone(),
                "this test has no `task`",
            ));
        }
        let mut argv: Vec<String> = Vec::new();
        let unplaced = self.problems.len();
        let robot = self.name_or_path("robot");
        if let Some((r, span)) = &robot
            && r.eq_ignore_ascii_case(place::ROS2_ROBOT)
        {
            self.problems.push(Problem::new(
                Code::BadValue,
                span.clone(),
                "a test runs a simulated or scripted robot; `ros2` drives a real one",
            ));
        }
        let model = self.name_or_path("model");
        let world = self.name_or_path("world");
        let start = self.start();
        let profile = self.profile();
        let placed = self.problems.len() == unplaced;
        for (flag, v) in [
            ("--robot", &robot),
            ("--model", &model),
            ("--world", &world),
        ] {
            if let Some((v, _)) = v {
                argv.extend([flag.to_string(), v.clone()]);
            }
        }
        if let Some((s, _)) = &start {
            argv.extend(["--start".to_string(), s.clone()]);
        }
        if let Some((p, _)) = &profile {
            argv.extend(["--sim-profile".to_string(), p.name().to_string()]);
        }
        let mut skills = None;
        for key in ["skills", "scenario"] {
            if let Some((p, span)) = self.file(key) {
                if key == "skills" {
                    skills = Some(p.clone());
                }
                if key == "scenario"
                    && let Err(e) = Scenario::load(&p)
                {
                    self.problems.push(Problem::new(Code::BadValue, span, e));
                    continue;
                }
                argv.extend([format!("--{key}"), p.display().to_string()]);
            }
        }
        for fault in self.faults() {
            argv.extend(["--fault".to_string(), fault]);
        }
        let max_time = self.number("max_time");
        if let Some((t, span)) = &max_time {
            if t.is_finite() && *t > 0.0 && *t <= MAX_TIME {
                argv.extend(["--max-time".to_string(), t.to_string()]);
            } else {
                self.problems.push(Problem::new(
                    Code::BadValue,
                    span.clone(),
                    format!(
                        "`max_time` is a number of seconds above 0, at most {MAX_TIME} (MAX_TIME)"
                    ),
                ));
            }
        }
        let seeds = self.seeds();
        let lines = self.lines();
        let snap = self.snapshot();
        // The robot, world and start together, as `ilmrc run` takes them: the message
        // names the flag, so the problem goes to the key it is about.
        let choice = place::Choice {
            robot: robot.as_ref().map_or("moro", |r| r.0.as_str()),
            profile: profile.as_ref().map(|p| p.0),
            model: model.as_ref().map(|m| m.0.as_str()),
            world: world.as_ref().map(|w| w.0.as_str()),
            start: start.as_ref().map(|s| s.0.as_str()),
        };
        let notes = &mut *self.notes;
        let mut warn = |spec: &str, warnings: &[ModelWarning]| {
            if !warnings.is_empty() {
                notes.push(Note::Model {
                    spec: spec.to_string(),
                    warnings: warnings.to_vec(),
                });
            }
        };
        let setup = if placed {
            match place::place(&choice, &mut warn) {
                Ok(setup) => Some(setup),
                Err(e) => {
                    let profile = profile
                        .as_ref()
                        .map(|(p, span)| (p.name().to_string(), span.clone()));
                    let span = [
                        ("start", &start),
                        ("world", &world),
                        ("model", &model),
                        ("profile", &profile),
                    ]
                    .into_iter()
                    .find(|(k, v)| e.contains(k) && v.is_some())
                    .and_then(|(_, v)| v.as_ref().map(|v| v.1.clone()))
                    .or_else(|| robot.as_ref().map(|r| r.1.clone()))
                    .unwrap_or(self.header.clone());
                    self.problems.push(Problem::new(Code::BadValue, span, e));
                    None
                }
            }
        } else {
            None
        };
        if let Some(setup) = &setup {
            self.outline.model = Some(setup.model_spec.clone());
            self.outline.poses = setup.backend != Backend::None;
            self.outline.scans = setup.world.is_some();
            self.outline.objects = setup.world.as_ref().map(|w| places(&w.world));
        }
        let assertions = match (&task, &setup) {
            (Some((task, _)), Some(_)) => self.assertions(task, skills.as_deref(), &lines),
            _ => Vec::new(),
        };
        if let Some((task, _)) = task {
            argv.push(task.display().to_string());
        }
        if self.problems.len() > before {
            return None;
        }
        let (name, span) = name?;
        let snapshot = snap.map(|(precision, scans, at)| Snapshot {
            precision,
            scans,
            span: at,
            stem: snapshot::stem(self.path, &name),
        });
        Some(Test {
            name,
            span,
            argv,
            lines,
            seeds,
            assertions,
            snapshot,
        })
    }

    /// `true`, or a table of `precision` and `scans`; `None` when the test keeps none.
    fn snapshot(&mut self) -> Option<(f64, bool, Range<usize>)> {
        let value = self.get("snapshot")?;
        let span = value.span();
        if let Some(on) = value.get_ref().as_bool() {
            return on.then_some((snapshot::PRECISION, false, span));
        }
        let Some(table) = value.get_ref().as_table() else {
            self.wrong(
                "snapshot",
                value,
                "`true` or `{ precision = 0.01, scans = true }`",
            );
            return None;
        };
        let mut precision = snapshot::PRECISION;
        let mut scans = false;
        for (key, v) in table.iter() {
            match key.get_ref().as_ref() {
                "precision" => match number(v.get_ref()) {
                    Some(p) if p.is_finite() && p > 0.0 => precision = p,
                    _ => self.problems.push(Problem::new(
                        Code::BadValue,
                        v.span(),
                        "`precision` is a number above 0 (metres, radians, m/s)",
                    )),
                },
                "scans" => match v.get_ref().as_bool() {
                    Some(b) => scans = b,
                    None => self.wrong("scans", v, "`true` or `false`"),
                },
                k => self.problems.push(
                    Problem::new(
                        Code::UnknownKey,
                        key.span(),
                        format!("unknown key `{k}` of `snapshot`"),
                    )
                    .suggest(k, ["precision", "scans"]),
                ),
            }
        }
        Some((precision, scans, span))
    }

    fn start(&mut self) -> Option<(String, Range<usize>)> {
        let value = self.get("start")?;
        if let Some(s) = value.get_ref().as_str() {
            return Some((s.to_string(), value.span()));
        }
        let parts: Option<Vec<f64>> = value
            .get_ref()
            .as_array()
            .map(|a| a.iter().map(|v| number(v.get_ref())).collect::<Option<_>>())
            .unwrap_or(None);
        match parts {
            Some(p) if p.len() == 3 => Some((format!("{},{},{}", p[0], p[1], p[2]), value.span())),
            _ => {
                self.wrong("start", value, "`\"X,Y,HEADING\"` or `[X, Y, HEADING]`");
                None
            }
        }
    }

    fn faults(&mut self) -> Vec<String> {
        let Some(value) = self.get("faults") else {
            return Vec::new();
        };
        let Some(items) = value.get_ref().as_array() else {
            self.wrong("faults", value, "an array of strings");
            return Vec::new();
        };
        let mut out = Vec::new();
        for item in items.iter() {
            match item.get_ref().as_str() {
                Some(f) => match ilmr_sim::faults::flag::parse(f) {
                    Ok(_) => out.push(f.to_string()),
                    Err(e) => self
                        .problems
                        .push(Problem::new(Code::BadValue, item.span(), e)),
                },
                None => self.wrong("faults", item, "strings"),
            }
        }
        out
    }

    fn seeds(&mut self) -> Vec<u64> {
        let Some(value) = self.get("seeds") else {
            return vec![0];
        };
        let span = value.span();
        let bad = |m: String| Problem::new(Code::BadValue, span.clone(), m);
        let seed = |v: &DeValue| -> Option<u64> {
            v.as_integer().and_then(|i| {
                u64::from_str_radix(i.as_str().replace('_', "").as_str(), i.radix()).ok()
            })
        };
        if let Some(s) = seed(value.get_ref()) {
            return vec![s];
        }
        if let Some(items) = value.get_ref().as_array() {
            let seeds: Option<Vec<u64>> = items.iter().map(|v| seed(v.get_ref())).collect();
            return match seeds {
                Some(s) if s.len() as u64 > MAX_SEEDS => {
                    self.problems.push(bad(format!(
                        "{} seeds; a test runs at most {MAX_SEEDS} (MAX_SEEDS)",
                        s.len()
                    )));
                    Vec::new()
                }
                Some(s) if !s.is_empty() => s,
                _ => {
                    self.problems.push(bad(
                        "a list of seeds holds whole numbers from 0 up, at least one".into(),
                    ));
                    Vec::new()
                }
            };
        }
        if let Some(text) = value.get_ref().as_str() {
            let range = text.split_once('-').and_then(|(a, b)| {
                Some((a.trim().parse::<u64>().ok()?, b.trim().parse::<u64>().ok()?))
            });
            return match range {
                Some((a, b)) if a <= b && b - a < MAX_SEEDS => (a..=b).collect(),
                Some((a, b)) if a <= b => {
                    self.problems.push(bad(format!(
                        "{} seeds; a test runs at most {MAX_SEEDS} (MAX_SEEDS)",
                        b - a + 1
                    )));
                    Vec::new()
                }
                _ => {
                    self.problems.push(bad(format!(
                        "`{text}` is not a range of seeds such as \"1-20\" (first, then last)"
                    )));
                    Vec::new()
                }
            };
        }
        self.wrong(
            "seeds",
            value,
            "a seed, a list of seeds or a range \"1-20\"",
        );
        Vec::new()
    }

    fn lines(&mut self) -> Vec<Line> {
        let Some(value) = self.get("lines") else {
            return Vec::new();
        };
        let Some(items) = value.get_ref().as_array() else {
            self.wrong(
                "lines",
                value,
                "an array of `{ t = SECONDS, text = \"LINE\" }`",
            );
            return Vec::new();
        };
        let mut out = Vec::new();
        for item in items.iter() {
            let table = item.get_ref().as_table();
            let t = table
                .and_then(|t| t.get("t"))
                .and_then(|v| number(v.get_ref()));
            let text = table
                .and_then(|t| t.get("text"))
                .and_then(|v| v.get_ref().as_str());
            let extra = table.and_then(|t| {
                t.iter()
                    .find(|(k, _)| !matches!(k.get_ref().as_ref(), "t" | "text"))
            });
            match (t, text, extra) {
                (Some(t), Some(text), None) if t.is_finite() && t >= 0.0 => out.push(Line {
                    t,
                    text: text.to_string(),
                }),
                _ => self.problems.push(Problem::new(
                    Code::BadValue,
                    item.span(),
                    "an interactive line is `{ t = SECONDS, text = \"LINE\" }`, t from 0",
                )),
            }
        }
        out
    }

    fn assertions(&mut self, task: &Path, skills: Option<&Path>, lines: &[Line]) -> Vec<Assertion> {
        let Some(value) = self.get("assert") else {
            self.problems.push(
                Problem::new(
                    Code::MissingKey,
                    self.header.clone(),
                    "this test asserts nothing",
                )
                .help("add `assert = [\"...\"]`: a test that cannot fail proves nothing"),
            );
            return Vec::new();
        };
        let items: Vec<&Spanned<DeValue>> = match value.get_ref().as_array() {
            Some(a) if !a.is_empty() => a.iter().collect(),
            _ => {
                self.wrong("assert", value, "a non-empty array of strings");
                return Vec::new();
            }
        };
        self.outline.asserts = items
            .iter()
            .map(|item| {
                let span = item.span();
                let base = item
                    .get_ref()
                    .as_str()
                    .and_then(|t| content_offset(self.text, span.clone(), t));
                (span, base)
            })
            .collect();
        let read = self
            .tasks
            .entry(task.to_path_buf())
            .or_insert_with(|| {
                crate::sources::read_source(task).map(|s| Arc::new(statements(&s.text)))
            })
            .clone();
        let statements = match read {
            Ok(s) => s,
            Err(e) => {
                self.problems
                    .push(Problem::new(Code::MissingFile, self.header.clone(), e));
                return Vec::new();
            }
        };
        // A skill's variables are the task's too: its statements run in the task.
        let skills: Vec<String> = skills
            .and_then(|dir| {
                let read = crate::sources::read_skill_dir(dir).ok()?;
                if !read.ignored.is_empty() {
                    self.notes.push(Note::SkillsIgnored {
                        dir: dir.to_path_buf(),
                        files: read.ignored,
                    });
                }
                read.sources.ok()
            })
            .into_iter()
            .flatten()
            .flat_map(|s| self::statements(&s.text))
            .map(|(_, t)| t)
            .collect();
        let mut variables: Vec<String> = statements
            .iter()
            .map(|(_, t)| t)
            .chain(&skills)
            .chain(lines.iter().map(|l| &l.text))
            .filter_map(|t| assigns(t))
            .collect();
        variables.sort_by_key(|v| v.to_ascii_lowercase());
        variables.dedup_by(|a, b| a.eq_ignore_ascii_case(b));
        self.outline.statements = statements;
        self.outline.variables = variables;
        let outline = std::mem::take(&mut self.outline);
        let ctx = outline.context();
        let mut out = Vec::new();
        for item in items {
            let Some(text) = item.get_ref().as_str() else {
                self.wrong("assert", item, "strings");
                continue;
            };
            let span = item.span();
            let base = content_offset(self.text, span.clone(), text);
            match assertion::parse(text, base, span, &ctx) {
                Ok(a) => out.push(a),
                Err(p) => self.problems.push(p),
            }
        }
        self.outline = outline;
        out
    }
}

fn number(v: &DeValue) -> Option<f64> {
    if let Some(i) = v.as_integer() {
        return i64::from_str_radix(&i.as_str().replace('_', ""), i.radix())
            .ok()
            .map(|i| i as f64);
    }
    v.as_float()
        .and_then(|f| f.as_str().replace('_', "").parse::<f64>().ok())
}

/// Where the string's content starts in the file, when its bytes there are the string
/// as read (a literal string, or a basic one without escapes).
fn content_offset(file: &str, span: Range<usize>, value: &str) -> Option<usize> {
    let raw = file.get(span.clone())?;
    for quote in ["'''", "\"\"\"", "'", "\""] {
        if raw.len() >= 2 * quote.len() && raw.starts_with(quote) && raw.ends_with(quote) {
            let mut start = quote.len();
            let inner = &raw[start..raw.len() - quote.len()];
            // A newline right after a multi-line string's opening quotes is not part of it.
            let inner = if quote.len() == 3 && inner.starts_with('\n') {
                start += 1;
                &inner[1..]
            } else {
                inner
            };
            return (inner == value).then_some(span.start + start);
        }
    }
    None
}

/// The task's statements as the trace names them: line and text, comments left out.
pub fn statements(source: &str) -> Vec<(u32, String)> {
    source
        .lines()
        .enumerate()
        .filter_map(|(i, line)| {
            let code = line.split("//").next().unwrap_or("").trim();
            (!code.is_empty()).then(|| (i as u32 + 1, code.to_string()))
        })
        .collect()
}

/// The variable a statement assigns (`m=goahead(0.7)`, `cnt = cnt + 1`).
pub fn assigns(statement: &str) -> Option<String> {
    let (name, rest) = statement.split_once('=')?;
    let name = name.trim();
    (is_name(name) && !rest.starts_with('=')).then(|| name.to_string())
}

/// The world's named things: doors, boxes, targets (where they start) and the charger
/// as points, walls as their segments.
fn places(world: &ilmr_sim::World) -> Vec<Place> {
    let point = |name: &str, p: ilmr_sim::Point2<f64>| Place::Object {
        name: name.to_string(),
        from: (p.x, p.y),
        to: (p.x, p.y),
    };
    let mut out: Vec<Place> = Vec::new();
    out.extend(world.doors.iter().map(|d| point(&d.id, d.center)));
    out.extend(
        world
            .pickup_boxes
            .iter()
            .map(|b| point(&b.id, b.shape.center)),
    );
    out.extend(world.targets.iter().map(|t| point(&t.name, t.start)));
    out.extend(world.charger.iter().map(|c| point("charger", c.position)));
    out.extend(world.walls.iter().map(|w| Place::Object {
        name: w.id.clone(),
        from: (w.from.x, w.from.y),
        to: (w.to.x, w.to.y),
    }));
    out.retain(|p| matches!(p, Place::Object { name, .. } if !name.is_empty()));
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::codes::Code;

    /// A file without `[[test]]` returned its problems as found: a key's problem on
    /// line 2 came before the missing table's, at the file's start.
    #[test]
    fn problems_are_in_the_files_order_however_reading_ends() {
        let text = "max_time = 3\nname = \"x\"\n".to_string();
        let problems = read(Path::new("t.test.toml"), text).err().unwrap();
        let codes: Vec<Code> = problems.iter().map(|p| p.code).collect();
        assert_eq!(codes, [Code::MissingKey, Code::UnknownKey]);
    }

    /// Each `[[test]]` of 10,000 seeds held 80 KB: a hundred thousand of them
    /// exhausted memory before any was run.
    #[test]
    fn a_file_of_too_many_tests_is_refused_at_the_first_past_the_limit() {
        let tests: String = (0..=MAX_TESTS)
            .map(|i| format!("[[test]]\nname = \"t{i}\"\n"))
            .collect();
        let text = format!("seeds = \"0-9999\"\n{tests}");
        let problems = read(Path::new("t.test.toml"), text.clone()).err().unwrap();
        assert_eq!(problems.len(), 1, "{problems:?}");
        assert!(problems[0].message.contains("MAX_TESTS"), "{problems:?}");
        let last = text.rfind("[[test]]").unwrap();
        assert_eq!(
            problems[0].span.start, last,
            "the first test past the limit"
        );
    }

    /// A range of seeds was bounded, a list not: a list of a million seeds was taken.
    #[test]
    fn a_list_of_seeds_is_bounded_as_a_range_is() {
        let list = |n: u64| {
            let seeds: Vec<String> = (0..n).map(|s| s.to_string()).collect();
            format!("[[test]]\nname = \"t\"\nseeds = [{}]\n", seeds.join(", "))
        };
        let problems = read(Path::new("t.test.toml"), list(MAX_SEEDS + 1))
            .err()
            .unwrap();
        let said: Vec<&str> = problems.iter().map(|p| p.message.as_str()).collect();
        assert!(said.iter().any(|m| m.contains("MAX_SEEDS")), "{said:?}");
        let problems = read(Path::new("t.test.toml"), list(MAX_SEEDS))
            .err()
            .unwrap();
        assert!(problems.iter().all(|p| !p.message.contains("MAX_SEEDS")));
    }

    /// A million broken lines were three million problems, each shown with its line.
    #[test]
    fn the_first_problems_are_reported_and_the_rest_counted() {
        let problems = read(Path::new("t.test.toml"), "=\n".repeat(1_000))
            .err()
            .unwrap();
        assert_eq!(problems.len(), MAX_PROBLEMS);
        let help = problems[MAX_PROBLEMS - 1].help.as_deref().unwrap_or("");
        assert!(
            help.contains("more problem(s)") && help.contains("MAX_PROBLEMS"),
            "{help}"
        );
        assert!(problems.is_sorted_by_key(|p| p.span.start));
    }
}

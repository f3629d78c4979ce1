//! Trace snapshots: a test's run kept as a file beside the test file and compared with
//! every later run, as `cargo insta` keeps and compares values. Poses are rounded to
//! the test's precision and thinned to ten a second, scans are left out unless asked
//! for, and paths are named by their file name: the same task, robot, world and seed
//! give the same bytes wherever the test is run from.

use std::path::{Path, PathBuf};

use ilmr_trace::{Event, Num, Record};

pub use ilmr_testfile::snapshot::{Snapshot, file_stem};

/// The file a run that differs from its snapshot is written to, beside it.
pub const PENDING: &str = ".new";
/// Lines of a difference `--review` shows on each side.
const SHOWN: usize = 20;

fn round(x: f64, p: f64) -> f64 {
    if !x.is_finite() {
        return x;
    }
    let r = (x / p).round() * p;
    // No `-0`: a value rounded to nothing reads the same from either side.
    if r == 0.0 { 0.0 } else { r }
}

fn file_name(path: &str) -> String {
    Path::new(path)
        .file_name()
        .map_or(path.to_string(), |n| n.to_string_lossy().into_owned())
}

/// The snapshot text of a run's records.
pub fn text(records: &[Record<'_>], s: &Snapshot) -> String {
    let p = s.precision;
    let r = |n: &mut Num| n.0 = round(n.0, p);
    let last_pose = records
        .iter()
        .rposition(|r| matches!(r.event, Event::Pose(_)));
    let mut out = String::new();
    for (i, record) in records.iter().enumerate() {
        let mut record = record.clone();
        match &mut record.event {
            Event::Scan(_) if !s.scans => continue,
            Event::Scan(scan) => {
                r(&mut scan.x);
                r(&mut scan.y);
                r(&mut scan.h);
            }
            Event::Pose(pose) => {
                let tenths = record.t.0 * 10.0;
                if (tenths - tenths.round()).abs() > 1e-6 && Some(i) != last_pose {
                    continue;
                }
                for n in [
                    &mut pose.x,
                    &mut pose.y,
                    &mut pose.h,
                    &mut pose.v,
                    &mut pose.c,
                ] {
                    r(n);
                }
            }
            Event::Run(run) => {
                run.task = file_name(&run.task).into();
                run.world = file_name(&run.world).into();
                for n in [&mut run.start.x, &mut run.start.y, &mut run.start.h] {
                    r(n);
                }
            }
            Event::Mark(m) => {
                for n in [&mut m.x, &mut m.y, &mut m.h] {
                    r(n);
                }
            }
            Event::Var(v) => {
                for n in [&mut v.x, &mut v.y, &mut v.h, &mut v.dist]
                    .into_iter()
                    .flatten()
                {
                    r(n);
                }
            }
            Event::Path(path) => {
                let points: Vec<(f64, f64)> = path
                    .points
                    .0
                    .iter()
                    .map(|&(x, y)| (round(x, p), round(y, p)))
                    .collect();
                path.points = points.into();
            }
            _ => {}
        }
        out.push_str(&ilmr_trace::to_line(&record));
        out.push('\n');
    }
    out
}

/// Compares a run's snapshot text with the stored one. When they differ (or none is
/// stored) the run's is written beside it as pending, and the error says how.
pub fn compare(stored: &Path, text: &str) -> Result<(), String> {
    let pending = pending_of(stored);
    let old = std::fs::read_to_string(stored).ok();
    if old.as_deref() == Some(text) {
        let _ = std::fs::remove_file(&pending);
        return Ok(());
    }
    if let Some(dir) = pending.parent() {
        std::fs::create_dir_all(dir)
            .map_err(|e| format!("cannot make `{}`: {e}", dir.display()))?;
    }
    std::fs::write(&pending, text)
        .map_err(|e| format!("cannot write `{}`: {e}", pending.display()))?;
    let what = match &old {
        None => format!("no snapshot `{}` yet", stored.display()),
        Some(old) => {
            let (line, _, _) = difference(old, text);
            format!(
                "the trace differs from `{}` from line {} on",
                stored.display(),
                line + 1
            )
        }
    };
    Err(format!(
        "{what}; the run's is pending in `{}`",
        pending.display()
    ))
}

fn pending_of(stored: &Path) -> PathBuf {
    let mut name = stored.as_os_str().to_os_string();
    name.push(PENDING);
    PathBuf::from(name)
}

/// The first line that differs, and the differing lines of each side between the
/// common start and the common end.
fn difference<'a>(old: &'a str, new: &'a str) -> (usize, Vec<&'a str>, Vec<&'a str>) {
    let a: Vec<&str> = old.lines().collect();
    let b: Vec<&str> = new.lines().collect();
    let head = a.iter().zip(&b).take_while(|(x, y)| x == y).count();
    let tail = a[head..]
        .iter()
        .rev()
        .zip(b[head..].iter().rev())
        .take_while(|(x, y)| x == y)
        .count();
    (
        head,
        a[head..a.len() - tail].to_vec(),
        b[head..b.len() - tail].to_vec(),
    )
}

/// The pending snapshots of a test file.
pub fn pending(test_file: &Path) -> Result<Vec<PathBuf>, String> {
    let dir = test_file
        .parent()
        .unwrap_or(Path::new("."))
        .join("snapshots");
    let prefix = format!("{}__", file_stem(test_file));
    let Ok(entries) = std::fs::read_dir(&dir) else {
        return Ok(Vec::new());
    };
    let mut out: Vec<PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            p.file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .is_some_and(|n| n.starts_with(&prefix) && n.ends_with(PENDING))
        })
        .collect();
    out.sort();
    Ok(out)
}

fn stored_of(pending: &Path) -> PathBuf {
    let s = pending.to_string_lossy();
    PathBuf::from(s.strip_suffix(PENDING).unwrap_or(&s))
}

/// What `--review` shows of a pending snapshot: where it differs from the stored one.
pub fn review(pending: &Path) -> String {
    let stored = stored_of(pending);
    let new = std::fs::read_to_string(pending).unwrap_or_default();
    let Ok(old) = std::fs::read_to_string(&stored) else {
        return format!(
            "new snapshot {} ({} lines)\n",
            stored.display(),
            new.lines().count()
        );
    };
    let (line, gone, came) = difference(&old, &new);
    let mut out = format!(
        "snapshot {}: from line {} on, {} line(s) stored, {} line(s) now\n",
        stored.display(),
        line + 1,
        gone.len(),
        came.len()
    );
    for l in gone.iter().take(SHOWN) {
        out.push_str(&format!("- {}\n", cut(l)));
    }
    for l in came.iter().take(SHOWN) {
        out.push_str(&format!("+ {}\n", cut(l)));
    }
    if gone.len().max(came.len()) > SHOWN {
        out.push_str(&format!("  ... ({SHOWN} lines of each side shown)\n"));
    }
    out
}

/// A trace line cut to what a terminal shows.
fn cut(line: &str) -> String {
    const WIDTH: usize = 160;
    if line.chars().count() <= WIDTH {
        return line.to_string();
    }
    let mut s: String = line.chars().take(WIDTH).collect();
    s.push_str(" ...");
    s
}

/// Stores a pending snapshot in place of the stored one.
pub fn accept(pending: &Path) -> Result<PathBuf, String> {
    let stored = stored_of(pending);
    std::fs::rename(pending, &stored)
        .map_err(|e| format!("cannot store `{}`: {e}", stored.display()))?;
    Ok(stored)
}

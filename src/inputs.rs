//! Reading what the command line names: source files, skill directories, robot models.

use std::path::Path;

use ilmr_compiler::check::Source;
use ilmr_model::{ModelWarning, RobotModel};

pub use ilmr_testfile::place::{Robot, load_robot};
pub use ilmr_testfile::sources::read_source;

/// The skill files of a directory (`*.ilms`, and `*.ilmr` files that hold skills), in
/// name order so that every run sees them the same way; or the one skill file given.
/// Files of other extensions in the directory are named in a note on stderr, so that a
/// `turns.ilm` is not silently left out.
pub fn read_skill_dir(dir: &Path) -> Result<Vec<Source>, String> {
    let read = ilmr_testfile::sources::read_skill_dir(dir)?;
    note_ignored(dir, &read.ignored);
    read.sources
}

pub fn note_ignored(dir: &Path, ignored: &[std::path::PathBuf]) {
    if ignored.is_empty() {
        return;
    }
    let names: Vec<String> = ignored
        .iter()
        .filter_map(|p| p.file_name().map(|n| format!("`{}`", n.to_string_lossy())))
        .collect();
    eprintln!(
        "note: --skills `{}`: {} not read (only `.ilms` and `.ilmr` files hold skills)",
        dir.display(),
        names.join(", ")
    );
}

/// The model a command drives or builds for, with its warnings (a value out of range, a
/// line that could not be read: the default stands in) said on stderr, so that a run on
/// a model `check` warns about is not silently a run on other values.
pub fn load_robot_model(spec: &str) -> Result<RobotModel, String> {
    let robot = load_robot(spec)?;
    warn_about(spec, &robot.warnings);
    Ok(robot.model)
}

pub fn warn_about(spec: &str, warnings: &[ModelWarning]) {
    for w in warnings {
        match w.line {
            Some(line) => eprintln!("warning: {spec}:{line}: {}", w.message),
            None => eprintln!("warning: {spec}: {}", w.message),
        }
    }
}

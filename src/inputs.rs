//! Reading what the command line names: source files, skill directories, robot models.

use std::path::{Path, PathBuf};

use ilmr_compiler::check::Source;
use ilmr_model::{ModelWarning, RobotModel};

pub fn read_source(path: &Path) -> Result<Source, String> {
    ilmr_files::read_text(path, ilmr_files::Kind::Source)
        .map(|text| Source::new(path.display().to_string(), text))
        .map_err(|e| format!("cannot read `{}`: {e}", path.display()))
}

/// The skill files of a directory (`*.ilms`, and `*.ilmr` files that hold skills), in
/// name order so that every run sees them the same way; or the one skill file given.
/// Files of other extensions in the directory are named in a note on stderr, so that a
/// `turns.ilm` is not silently left out.
pub fn read_skill_dir(dir: &Path) -> Result<Vec<Source>, String> {
    if std::fs::metadata(dir).is_ok_and(|m| m.is_file()) {
        return read_source(dir).map(|s| vec![Source::library(s.path, s.text)]);
    }
    let entries = std::fs::read_dir(dir)
        .map_err(|e| format!("cannot read skill directory `{}`: {e}", dir.display()))?;
    let (mut paths, mut ignored): (Vec<PathBuf>, Vec<PathBuf>) = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        // Sub-directories are not read; anything else named as a skill file is, so
        // that a FIFO or a device is refused rather than passed over.
        .filter(|p| !p.is_dir())
        .partition(|p| {
            p.extension()
                .is_some_and(|x| x.eq_ignore_ascii_case("ilms") || x.eq_ignore_ascii_case("ilmr"))
        });
    paths.sort();
    ignored.retain(|p| {
        !p.file_name()
            .is_some_and(|n| n.to_string_lossy().starts_with('.'))
    });
    if !ignored.is_empty() {
        ignored.sort();
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
    paths
        .iter()
        .map(|p| read_source(p).map(|s| Source::library(s.path, s.text)))
        .collect()
}

/// A loaded robot model, with where it came from so that its warnings can point there.
pub struct Robot {
    pub model: RobotModel,
    pub warnings: Vec<ModelWarning>,
    /// The model file's path and text, when it came from a file.
    pub file: Option<Source>,
}

/// `moro`, `workpartner`, or a path to a ROBO.INI file.
pub fn load_robot(spec: &str) -> Result<Robot, String> {
    if let Some(model) = RobotModel::builtin(spec) {
        return Ok(Robot {
            model,
            warnings: Vec::new(),
            file: None,
        });
    }
    let path = Path::new(spec);
    let looks_like_path = spec.contains(['/', '\\', '.']);
    if !looks_like_path {
        return Err(format!(
            "unknown robot `{spec}`: use {} or a path to a ROBO.INI file",
            RobotModel::builtin_names().join(", ")
        ));
    }
    let (model, warnings) =
        RobotModel::load(path).map_err(|e| format!("cannot read robot model `{spec}`: {e}"))?;
    // The model was read a moment ago; its text only places its warnings.
    let text = ilmr_files::read(path, ilmr_files::Kind::RobotModel)
        .map(|bytes| String::from_utf8_lossy(&bytes).into_owned())
        .unwrap_or_default();
    Ok(Robot {
        model,
        warnings,
        file: Some(Source::new(spec, text)),
    })
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

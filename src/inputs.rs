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
/// name order so that every run sees them the same way.
pub fn read_skill_dir(dir: &Path) -> Result<Vec<Source>, String> {
    let entries = std::fs::read_dir(dir)
        .map_err(|e| format!("cannot read skill directory `{}`: {e}", dir.display()))?;
    let mut paths: Vec<PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            p.extension()
                .is_some_and(|x| x.eq_ignore_ascii_case("ilms") || x.eq_ignore_ascii_case("ilmr"))
        })
        .collect();
    paths.sort();
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

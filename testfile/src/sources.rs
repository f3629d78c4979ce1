//! Reading the task and skill files a test (or a command line) names.

use std::path::{Path, PathBuf};

use ilmr_compiler::check::Source;

pub fn read_source(path: &Path) -> Result<Source, String> {
    ilmr_files::read_text(path, ilmr_files::Kind::Source)
        .map(|text| Source::new(path.display().to_string(), text))
        .map_err(|e| format!("cannot read `{}`: {e}", path.display()))
}

/// The skill files of a directory (`*.ilms`, and `*.ilmr` files that hold skills), in
/// name order so that every run sees them the same way; or the one skill file given.
pub struct SkillDir {
    /// The skill files, or the first that could not be read.
    pub sources: Result<Vec<Source>, String>,
    /// Files of other extensions in the directory, to be named in a note so that a
    /// `turns.ilm` is not silently left out.
    pub ignored: Vec<PathBuf>,
}

pub fn read_skill_dir(dir: &Path) -> Result<SkillDir, String> {
    if std::fs::metadata(dir).is_ok_and(|m| m.is_file()) {
        return read_source(dir).map(|s| SkillDir {
            sources: Ok(vec![Source::library(s.path, s.text)]),
            ignored: Vec::new(),
        });
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
    ignored.sort();
    let sources = paths
        .iter()
        .map(|p| read_source(p).map(|s| Source::library(s.path, s.text)))
        .collect();
    Ok(SkillDir { sources, ignored })
}

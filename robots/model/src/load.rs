//! Where models come from: text, files, the shipped robots, the defaults.

use std::io;
use std::path::Path;

use crate::model::{ModelWarning, RobotModel};
use crate::names::same_name;
use crate::parse::{Fallback, parse_text};

/// The defaults: Figure 39 (Workpartner's ROBO.INI, the only one the
/// dissertation prints) plus the devices, objects, identifier and
/// parameters every robot needs, with Workpartner's values.
pub(crate) const DEFAULT_INI: &str = include_str!("../models/default.ini");
const WORKPARTNER_INI: &str = include_str!("../models/workpartner.ini");
const MORO_INI: &str = include_str!("../models/moro.ini");

const BUILTINS: &[(&str, &str)] = &[("moro", MORO_INI), ("workpartner", WORKPARTNER_INI)];
const BUILTIN_NAMES: &[&str] = &["moro", "workpartner"];

/// Parsed without a fallback, because the fallback is this model; a test
/// checks it parses without warnings.
pub(crate) fn defaults_model() -> RobotModel {
    parse_text(DEFAULT_INI, "default", Fallback::Nothing).0
}

impl RobotModel {
    /// Reads ROBO.INI text. Never fails: problems come back as warnings,
    /// sorted by line, and the model holds everything readable plus the
    /// defaults that stood in for corrupt lines. Text without any section
    /// tag counts as corrupt as a whole and gives the defaults.
    pub fn parse(text: &str, name: &str) -> (RobotModel, Vec<ModelWarning>) {
        parse_text(text, name, Fallback::Defaults)
    }

    /// Reads a ROBO.INI file; the model is named after the file stem.
    ///
    /// A missing file is not an error: the result is the defaults model
    /// with one warning naming the path. Text that is not UTF-8 is read with
    /// the bad bytes replaced, and warned about. Only other I/O failures
    /// (permissions, a directory, a device or FIFO, a file over
    /// `ilmr_files::MAX_ROBOT_MODEL_BYTES`) are `Err`, since no
    /// default can stand in for a file that exists but cannot be read
    /// without hiding a real fault from the operator.
    pub fn load(path: &Path) -> io::Result<(RobotModel, Vec<ModelWarning>)> {
        let bytes = match ilmr_files::read(path, ilmr_files::Kind::RobotModel) {
            Ok(bytes) => bytes,
            Err(e) if e.is_not_found() => {
                let warning = ModelWarning::file(format!(
                    "robot model file `{}` not found; the built-in defaults are used",
                    path.display()
                ));
                return Ok((RobotModel::defaults(), vec![warning]));
            }
            Err(e) => return Err(e.into()),
        };
        let name = path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        let (text, utf8_warning) = decode(&bytes);
        let (mut model, mut warnings) = RobotModel::parse(&text, &name);
        model.source = Some(path.to_path_buf());
        if let Some(w) = utf8_warning {
            warnings.insert(0, w);
            warnings.sort_by_key(|w| w.line);
        }
        Ok((model, warnings))
    }

    /// A shipped model by name, ignoring case: `"moro"` or `"workpartner"`.
    pub fn builtin(name: &str) -> Option<RobotModel> {
        let (canonical, text) = BUILTINS.iter().find(|(n, _)| same_name(n, name))?;
        Some(parse_text(text, canonical, Fallback::Defaults).0)
    }

    /// The names `builtin` accepts.
    pub fn builtin_names() -> &'static [&'static str] {
        BUILTIN_NAMES
    }

    /// The model used when ROBO.INI is missing, named `"default"`: Figure 39
    /// plus battery, odometry, door, charger, `navi` and the parameters every
    /// robot needs, valued as on Workpartner.
    pub fn defaults() -> RobotModel {
        defaults_model()
    }
}

/// Old ROBO.INI files may be Latin-1; read what is readable and say where
/// the first bad byte was.
fn decode(bytes: &[u8]) -> (String, Option<ModelWarning>) {
    match std::str::from_utf8(bytes) {
        Ok(text) => (text.to_string(), None),
        Err(e) => {
            let valid = &bytes[..e.valid_up_to()];
            let line = valid.iter().filter(|&&b| b == b'\n').count() + 1;
            let line = u32::try_from(line).unwrap_or(u32::MAX);
            let warning = ModelWarning::at(
                line,
                "the file is not valid UTF-8; invalid bytes were replaced by U+FFFD",
            );
            (String::from_utf8_lossy(bytes).into_owned(), Some(warning))
        }
    }
}

//! Which robot the program is checked against: the workspace's ROBO.INI when there is
//! one, else the `ilmr.robot` setting (`moro`, `workpartner` or a path), else MoRo, the
//! default of `ilmrc check`.

use std::path::Path;

use ilmr_model::{ModelWarning, RobotModel};
use tower_lsp_server::ls_types::Uri;

use crate::workspace::Workspace;

pub const DEFAULT_ROBOT: &str = "moro";

#[derive(Debug, Clone)]
pub struct Robot {
    pub model: RobotModel,
    /// The model file when the model came from the workspace, for its warnings.
    pub file: Option<Uri>,
    pub warnings: Vec<ModelWarning>,
    /// Why this model: shown to the user when the setting could not be followed.
    pub note: Option<String>,
}

pub fn choose(workspace: &Workspace, setting: Option<&str>) -> Robot {
    if let Some(doc) = workspace.robot_model() {
        // Named by the file stem, as `ilmrc check --robot path/ROBO.INI` names it, so that
        // messages naming the robot read the same in the editor and on the command line.
        let name = doc
            .uri
            .to_file_path()
            .and_then(|p| p.file_stem().map(|n| n.to_string_lossy().into_owned()))
            .unwrap_or_else(|| "ROBO".to_string());
        let (mut model, warnings) = RobotModel::parse(&doc.text, &name);
        model.source = doc.uri.to_file_path().map(|p| p.into_owned());
        return Robot {
            model,
            file: Some(doc.uri.clone()),
            warnings,
            note: None,
        };
    }
    let setting = setting.map(str::trim).filter(|s| !s.is_empty());
    let Some(setting) = setting else {
        return builtin(DEFAULT_ROBOT, None);
    };
    if let Some(model) = RobotModel::builtin(setting) {
        return Robot {
            model,
            file: None,
            warnings: Vec::new(),
            note: None,
        };
    }
    let looks_like_path = setting.contains(['/', '\\', '.']);
    let path = Path::new(setting);
    let path = match workspace.roots().first() {
        Some(root) if path.is_relative() => root.join(path),
        _ => path.to_path_buf(),
    };
    if !looks_like_path || !path.is_file() {
        return builtin(
            DEFAULT_ROBOT,
            Some(format!(
                "robot `{setting}` is neither {} nor a ROBO.INI file; checking against `{DEFAULT_ROBOT}`",
                RobotModel::builtin_names().join(" nor ")
            )),
        );
    }
    match RobotModel::load(&path) {
        Ok((model, warnings)) => Robot {
            model,
            file: Uri::from_file_path(&path),
            warnings,
            note: None,
        },
        Err(e) => builtin(
            DEFAULT_ROBOT,
            Some(format!(
                "cannot read robot model `{}`: {e}; checking against `{DEFAULT_ROBOT}`",
                path.display()
            )),
        ),
    }
}

fn builtin(name: &str, note: Option<String>) -> Robot {
    Robot {
        model: RobotModel::builtin(name).unwrap_or_else(RobotModel::defaults),
        file: None,
        warnings: Vec::new(),
        note,
    }
}

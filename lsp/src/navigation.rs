//! Go to definition, find references and rename, for variables, skills and paths,
//! across every task and skill file of the workspace. Names ignore case, so every
//! spelling of a name is one symbol.

use ilmr_compiler::Span;
use ilmr_compiler::diagnostic::FileId;
use ilmr_model::RobotModel;
use ilmr_stdlib::{Command, RESERVED};

use crate::analysis::{Program, Symbol};

pub fn definition(program: &Program, file: FileId, offset: usize) -> Vec<(FileId, Span)> {
    let Some((_, symbol)) = program.symbol_at(file, offset) else {
        return Vec::new();
    };
    let mut defs = match &symbol {
        Symbol::Variable(name) => program.variable_defs(name),
        Symbol::Skill(id) => {
            let info = program.analysis().skills.get(*id);
            vec![(
                info.file,
                program.tree(info.file).skills[info.index].name.span,
            )]
        }
        // A path is made where it is first named (`record(p)`, `createpath(p,..)`).
        Symbol::Path(_) => program.occurrences(&symbol).into_iter().take(1).collect(),
    };
    defs.retain(|(f, _)| program.uri(*f).is_some());
    defs
}

pub fn references(
    program: &Program,
    file: FileId,
    offset: usize,
    include_declaration: bool,
) -> Vec<(FileId, Span)> {
    let Some((_, symbol)) = program.symbol_at(file, offset) else {
        return Vec::new();
    };
    let mut all = program.occurrences(&symbol);
    if !include_declaration {
        let defs = definition(program, file, offset);
        all.retain(|d| !defs.contains(d));
    }
    all
}

/// The name under the cursor if it can be renamed: a variable, a path or a skill of
/// the workspace (built-in skills live in no file the editor can change).
pub fn prepare_rename(program: &Program, file: FileId, offset: usize) -> Option<(Span, String)> {
    let (span, symbol) = program.symbol_at(file, offset)?;
    if let Symbol::Skill(id) = symbol {
        program.uri(program.analysis().skills.get(id).file)?;
    }
    Some((span, span.slice(program.text(file)).to_string()))
}

#[derive(Debug, Clone, PartialEq, Eq)]
pub enum RenameError {
    NothingToRename,
    InvalidName(String),
}

impl std::fmt::Display for RenameError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            RenameError::NothingToRename => {
                f.write_str("only variables, skills and paths of the workspace can be renamed")
            }
            RenameError::InvalidName(why) => f.write_str(why),
        }
    }
}

pub fn rename(
    program: &Program,
    model: &RobotModel,
    file: FileId,
    offset: usize,
    new_name: &str,
) -> Result<Vec<(FileId, Span)>, RenameError> {
    prepare_rename(program, file, offset).ok_or(RenameError::NothingToRename)?;
    check_name(program, model, new_name)?;
    let (_, symbol) = program
        .symbol_at(file, offset)
        .ok_or(RenameError::NothingToRename)?;
    Ok(program.occurrences(&symbol))
}

/// A new name must lex as one name and must not mean something else already.
fn check_name(program: &Program, model: &RobotModel, name: &str) -> Result<(), RenameError> {
    let mut chars = name.chars();
    let valid = chars.next().is_some_and(|c| c.is_alphabetic() || c == '_')
        && chars.all(|c| c.is_alphanumeric() || c == '_');
    let taken = if !valid {
        Some("not a name: a letter or `_`, then letters, digits or `_`".to_string())
    } else if Command::from_name(name).is_some() {
        Some(format!("`{name}` is a command"))
    } else if RESERVED.iter().any(|r| r.eq_ignore_ascii_case(name)) {
        Some(format!("`{name}` is a reserved word"))
    } else if program.analysis().skills.find(name).is_some() {
        Some(format!("`{name}` is a skill"))
    } else if model.parameter(name).is_some()
        || model.identifier(name).is_some()
        || model.color(name).is_some()
    {
        Some(format!("`{name}` is a constant of robot `{}`", model.name))
    } else {
        None
    };
    match taken {
        Some(why) => Err(RenameError::InvalidName(why)),
        None => Ok(()),
    }
}

//! The ILMR standard library: the catalogue of the 33 elementary commands (Table 7 of
//! the dissertation) and the built-in skills.
//!
//! Invariant: this crate is the only source of a command's name, grammar, units, ranges,
//! produced variable fields and documentation. The parser stays generic (`name(args)`);
//! the checker, the lowering, the VM, the language server and the generated reference
//! docs all read [`CATALOGUE`].

mod catalogue;
mod command;
pub mod pattern;
pub mod reference;
pub mod skills;
pub mod spec;
pub mod units;

pub use catalogue::CATALOGUE;
pub use command::Command;
pub use spec::{
    Category, CommandSpec, Ends, Field, Form, Limit, ModelNames, NameSpace, Occurs, Param,
    ParamKind, Range, Sets, Syntax, Unit, VarKind,
};

/// Words that are statements of their own and can name neither a variable nor a skill.
pub const RESERVED: &[&str] = &[
    "if", "endif", "while", "endwhile", "break", "check", "checkend", "priority", "highest",
];

/// Every keyword any command's grammar accepts, sorted and without repeats.
pub fn all_keywords() -> Vec<&'static str> {
    let mut words: Vec<&'static str> = CATALOGUE.iter().flat_map(|s| s.keywords()).collect();
    words.sort_unstable();
    words.dedup();
    words
}

//! Skills every program may call without a `--skills` directory. They are ILMR source,
//! parsed and checked by the compiler like any skill file.

/// A skill file shipped inside the toolchain.
#[derive(Debug, Clone, Copy)]
pub struct BuiltinSkillFile {
    /// A path-like name for diagnostics (`<stdlib>/charging.ilms`).
    pub path: &'static str,
    pub source: &'static str,
}

pub static BUILTIN_SKILL_FILES: &[BuiltinSkillFile] = &[BuiltinSkillFile {
    path: "<stdlib>/charging.ilms",
    source: include_str!("../skills/charging.ilms"),
}];

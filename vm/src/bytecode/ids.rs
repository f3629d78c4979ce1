//! Typed indices into a [`super::Module`]'s tables.

use serde::{Deserialize, Serialize};

macro_rules! id {
    ($($(#[$doc:meta])* $name:ident),* $(,)?) => {$(
        $(#[$doc])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
        #[serde(transparent)]
        pub struct $name(pub u32);

        impl $name {
            pub fn index(self) -> usize {
                self.0 as usize
            }
        }
    )*};
}

id! {
    /// A global variable slot.
    VarId,
    /// A number in the constant table.
    ConstId,
    /// A string in the name table (keywords, model names, paths, break patterns).
    NameId,
    /// An expression (a range of expression code).
    ExprId,
    /// A command block (a range of statement code).
    BlockId,
    /// The task or a skill.
    UnitId,
    /// A statement record of the source map.
    StmtId,
    /// A source file.
    FileId,
}

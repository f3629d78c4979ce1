//! The ILMR bytecode: a [`Module`] of tables that the compiler's lowering fills through
//! [`ModuleBuilder`] and the VM runs. See `docs/bytecode.md`.

mod builder;
mod disasm;
pub mod file;
mod ids;
mod index;
pub mod limits;
mod op;
mod serde_kinds;
mod validate;
mod wire;

pub use builder::{BuildError, ModuleBuilder};
pub use disasm::{disassemble, render_expr};
pub use ids::{BlockId, ConstId, ExprId, FileId, NameId, StmtId, UnitId, VarId};
pub use op::{Arg, ArgRange, ExprOp, Instr, Op, Opcode};
pub use validate::ModuleError;

pub(crate) use serde_kinds::{serde_field, serde_var_kind};

use ilmr_stdlib::VarKind;
use serde::{Deserialize, Serialize};

/// The format's name, which a module's header carries (the file starts with
/// [`file::MAGIC`]).
pub const MAGIC_NAME: &str = "ILMB";
/// The version of the `.ilmb` format: bumped on every change to the file's layout, the
/// tables or the instructions (docs/bytecode.md says what a version promises). 1 was
/// the JSON file of sessions 1 to 4; 2 is the binary file.
pub const VERSION: u32 = 2;

#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Header {
    pub magic: String,
    pub version: u32,
    /// The toolchain that built the module (`ilmrc 0.1.0`), recorded in the file.
    pub compiler: String,
}

impl Default for Header {
    fn default() -> Header {
        Header {
            magic: MAGIC_NAME.to_string(),
            version: VERSION,
            // The VM and the compiler are built together, under one version.
            compiler: format!("ilmrc {}", env!("CARGO_PKG_VERSION")),
        }
    }
}

/// One statement of the source: what traces print and `break(pattern)` matches.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Stmt {
    /// The statement's source text, trimmed, without its comment.
    pub text: String,
    pub file: FileId,
    /// 1-based.
    pub line: u32,
    /// Byte offsets into the file, end exclusive.
    pub span: (u32, u32),
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Global {
    /// As first written; variables are matched case-insensitively.
    pub name: String,
    #[serde(with = "serde_var_kind")]
    pub kind: VarKind,
}

/// The task or a skill: a list of top-level blocks that start together.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Unit {
    pub name: String,
    pub skill: bool,
    pub blocks: Vec<BlockId>,
}

/// A command block: `len` instructions from `start` in `Module::code`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Block {
    pub start: u32,
    pub len: u32,
}

/// An expression: `len` ops from `start` in `Module::expr_code`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Expr {
    pub start: u32,
    pub len: u32,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Module {
    pub header: Header,
    pub files: Vec<String>,
    pub stmts: Vec<Stmt>,
    pub consts: Vec<f64>,
    pub names: Vec<String>,
    pub globals: Vec<Global>,
    pub units: Vec<Unit>,
    /// The task's unit.
    pub main: UnitId,
    pub blocks: Vec<Block>,
    pub code: Vec<Instr>,
    pub args: Vec<Arg>,
    pub exprs: Vec<Expr>,
    pub expr_code: Vec<ExprOp>,
}

/// How many entries each table of a module holds; a [`Fragment`] records the counts of
/// the module it was compiled against.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct Counts {
    pub files: u32,
    pub stmts: u32,
    pub consts: u32,
    pub names: u32,
    pub globals: u32,
    pub units: u32,
    pub blocks: u32,
    pub code: u32,
    pub args: u32,
    pub exprs: u32,
    pub expr_code: u32,
}

/// New code compiled against a live module (an interactive line): the entries it adds
/// to each table, and the blocks to start as new top-level blocks.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Fragment {
    pub base: Counts,
    /// Holds only the added entries; its `main` and header are unused.
    pub added: Module,
    pub start: Vec<BlockId>,
}

impl Module {
    pub fn counts(&self) -> Counts {
        fn n<T>(v: &[T]) -> u32 {
            u32::try_from(v.len()).unwrap_or(u32::MAX)
        }
        Counts {
            files: n(&self.files),
            stmts: n(&self.stmts),
            consts: n(&self.consts),
            names: n(&self.names),
            globals: n(&self.globals),
            units: n(&self.units),
            blocks: n(&self.blocks),
            code: n(&self.code),
            args: n(&self.args),
            exprs: n(&self.exprs),
            expr_code: n(&self.expr_code),
        }
    }

    pub fn stmt(&self, id: StmtId) -> Option<&Stmt> {
        self.stmts.get(id.index())
    }

    /// Per statement: whether it issues a movement command (the catalogue says which
    /// commands are). Traces and pictures mark where these start and end.
    pub fn movement_statements(&self) -> Vec<bool> {
        let mut movement = vec![false; self.stmts.len()];
        for instr in &self.code {
            if let Op::Issue { command, .. } = instr.op
                && command.spec().movement
                && let Some(m) = movement.get_mut(instr.stmt.index())
            {
                *m = true;
            }
        }
        movement
    }

    pub fn name(&self, id: NameId) -> &str {
        self.names.get(id.index()).map_or("?", String::as_str)
    }

    pub fn global(&self, id: VarId) -> Option<&Global> {
        self.globals.get(id.index())
    }

    /// Looks a variable up by name in any letter case.
    pub fn find_global(&self, name: &str) -> Option<VarId> {
        self.globals
            .iter()
            .position(|g| g.name.eq_ignore_ascii_case(name))
            .and_then(|i| u32::try_from(i).ok())
            .map(VarId)
    }

    /// Looks a unit up by name in any letter case.
    pub fn find_unit(&self, name: &str) -> Option<UnitId> {
        self.units
            .iter()
            .position(|u| u.name.eq_ignore_ascii_case(name))
            .and_then(|i| u32::try_from(i).ok())
            .map(UnitId)
    }

    pub fn block_code(&self, id: BlockId) -> &[Instr] {
        self.blocks
            .get(id.index())
            .and_then(|b| {
                self.code
                    .get(b.start as usize..(b.start as usize + b.len as usize))
            })
            .unwrap_or(&[])
    }

    /// Instruction `pc` of a block, without slicing the block: the VM's fetch.
    #[inline]
    pub fn instr_at(&self, id: BlockId, pc: u32) -> Option<&Instr> {
        let b = self.blocks.get(id.index())?;
        if pc < b.len {
            self.code.get(b.start as usize + pc as usize)
        } else {
            None
        }
    }

    pub fn expr_ops(&self, id: ExprId) -> &[ExprOp] {
        self.exprs
            .get(id.index())
            .and_then(|e| {
                self.expr_code
                    .get(e.start as usize..(e.start as usize + e.len as usize))
            })
            .unwrap_or(&[])
    }

    pub fn arg_list(&self, range: ArgRange) -> &[Arg] {
        self.args
            .get(range.start as usize..(range.start as usize + range.len as usize))
            .unwrap_or(&[])
    }

    /// The `.ilmb` file of this module ([`file`]).
    pub fn to_bytes(&self) -> Vec<u8> {
        file::encode(self)
    }

    /// Reads an `.ilmb` file: its header, length and checksum, the tables, then every
    /// index ([`Module::validate`]).
    pub fn from_bytes(bytes: &[u8]) -> Result<Module, ModuleError> {
        file::decode(bytes)
    }

    /// Appends a fragment compiled against exactly this module, after validating what
    /// it adds. In place: the cost is the fragment's, not the module's. On an error the
    /// module is as it was.
    pub fn append(&mut self, fragment: &Fragment) -> Result<(), ModuleError> {
        let base = self.counts();
        if fragment.base != base {
            return Err(ModuleError::StaleFragment);
        }
        let a = &fragment.added;
        self.files.extend(a.files.iter().cloned());
        self.stmts.extend(a.stmts.iter().cloned());
        self.consts.extend(a.consts.iter().copied());
        self.names.extend(a.names.iter().cloned());
        self.globals.extend(a.globals.iter().cloned());
        self.units.extend(a.units.iter().cloned());
        self.blocks.extend(a.blocks.iter().copied());
        self.code.extend(a.code.iter().copied());
        self.args.extend(a.args.iter().copied());
        self.exprs.extend(a.exprs.iter().copied());
        self.expr_code.extend(a.expr_code.iter().copied());
        let checked = self.validate_from(&base).and_then(|()| {
            match fragment
                .start
                .iter()
                .find(|b| b.index() >= self.blocks.len())
            {
                Some(b) => Err(ModuleError::Index {
                    what: "fragment start block",
                    index: b.0,
                    len: self.blocks.len(),
                }),
                None => Ok(()),
            }
        });
        if checked.is_err() {
            self.truncate(&base);
        }
        checked
    }

    /// Drops every entry past `base` (undoes an append).
    pub fn truncate(&mut self, base: &Counts) {
        self.files.truncate(base.files as usize);
        self.stmts.truncate(base.stmts as usize);
        self.consts.truncate(base.consts as usize);
        self.names.truncate(base.names as usize);
        self.globals.truncate(base.globals as usize);
        self.units.truncate(base.units as usize);
        self.blocks.truncate(base.blocks as usize);
        self.code.truncate(base.code as usize);
        self.args.truncate(base.args as usize);
        self.exprs.truncate(base.exprs as usize);
        self.expr_code.truncate(base.expr_code as usize);
    }
}

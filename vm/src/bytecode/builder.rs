//! [`ModuleBuilder`]: the API the compiler's lowering calls. Inner blocks are built
//! before the instructions that refer to them, so each block's code is contiguous.

use ilmr_stdlib::VarKind;

use super::ids::{BlockId, ConstId, ExprId, FileId, NameId, StmtId, UnitId, VarId};
use super::index::Index;
use super::op::{Arg, ArgRange, ExprOp, Instr};
use super::{Block, Counts, Expr, Fragment, Global, Header, Module, ModuleError, Stmt, Unit};

#[derive(Debug, Clone, PartialEq)]
pub enum BuildError {
    /// A variable declared twice with different kinds.
    KindConflict {
        name: String,
        was: VarKind,
        now: VarKind,
    },
    /// A unit name used twice.
    DuplicateUnit(String),
    /// The finished module failed validation (an id from another builder, a bad
    /// expression, `priority` not first ...).
    Invalid(ModuleError),
    /// A table outgrew u32 indices.
    TooLarge(&'static str),
}

impl std::fmt::Display for BuildError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            BuildError::KindConflict { name, was, now } => write!(
                f,
                "variable {name} is {} and cannot also be {}",
                was.describe(),
                now.describe()
            ),
            BuildError::DuplicateUnit(n) => write!(f, "unit {n} defined twice"),
            BuildError::Invalid(e) => write!(f, "invalid module: {e}"),
            BuildError::TooLarge(what) => write!(f, "too many {what}"),
        }
    }
}

impl std::error::Error for BuildError {}

fn index<T>(v: &[T], what: &'static str) -> Result<u32, BuildError> {
    u32::try_from(v.len()).map_err(|_| BuildError::TooLarge(what))
}

#[derive(Debug, Clone)]
pub struct ModuleBuilder {
    m: Module,
    /// Set when building a fragment against a live module.
    base: Option<Counts>,
    index: Index,
}

impl Default for ModuleBuilder {
    fn default() -> Self {
        Self::new()
    }
}

impl ModuleBuilder {
    /// A builder for a whole task. Unit 0 is the task (`main`) until [`Self::set_main`].
    pub fn new() -> ModuleBuilder {
        ModuleBuilder {
            m: Module {
                header: Header::default(),
                files: Vec::new(),
                stmts: Vec::new(),
                consts: Vec::new(),
                names: Vec::new(),
                globals: Vec::new(),
                units: Vec::new(),
                main: UnitId(0),
                blocks: Vec::new(),
                code: Vec::new(),
                args: Vec::new(),
                exprs: Vec::new(),
                expr_code: Vec::new(),
            },
            base: None,
            index: Index::default(),
        }
    }

    /// A builder for an interactive line: it sees the live module's variables, skills,
    /// names and constants, and [`Self::finish_fragment`] returns only what it added.
    pub fn extending(live: &Module) -> ModuleBuilder {
        ModuleBuilder {
            m: live.clone(),
            base: Some(live.counts()),
            index: Index::after(live.counts()),
        }
    }

    /// A builder that owns the live module while a line is lowered into it (see
    /// `Vm::add_line`): nothing is copied, and [`Self::into_extended`] gives the module
    /// back with the line appended.
    pub fn lent(live: Module) -> ModuleBuilder {
        let base = live.counts();
        ModuleBuilder {
            m: live,
            base: Some(base),
            index: Index::after(base),
        }
    }

    /// The module and the counts it had when it was lent (`None` for a builder not
    /// made by [`Self::lent`] or [`Self::extending`]).
    pub fn into_extended(self) -> (Module, Option<Counts>) {
        (self.m, self.base)
    }

    pub fn file(&mut self, path: &str) -> Result<FileId, BuildError> {
        if let Some(i) = self.index.file(&self.m, path) {
            return Ok(FileId(i));
        }
        self.new_file(path)
    }

    /// A file the module cannot have yet (an interactive line's own text): no search of
    /// the files before it, which grow by one with every line joined.
    pub fn new_file(&mut self, path: &str) -> Result<FileId, BuildError> {
        let id = index(&self.m.files, "files")?;
        self.m.files.push(path.to_string());
        self.index.added_file(&self.m, id);
        Ok(FileId(id))
    }

    /// Room for `statements` more statements with an instruction and an expression
    /// each, and for `variables` more variables, so that a large task's tables grow
    /// once instead of being copied as they double.
    pub fn reserve(&mut self, statements: usize, variables: usize) {
        self.m.stmts.reserve(statements);
        self.m.code.reserve(statements);
        self.m.exprs.reserve(statements);
        self.m.expr_code.reserve(statements.saturating_mul(2));
        self.m.globals.reserve(variables);
        self.index.reserve_globals(&self.m, variables);
    }

    /// Records a statement; `text` is trimmed here.
    pub fn stmt(
        &mut self,
        file: FileId,
        line: u32,
        span: (u32, u32),
        text: &str,
    ) -> Result<StmtId, BuildError> {
        let id = index(&self.m.stmts, "statements")?;
        self.m.stmts.push(Stmt {
            text: text.trim().to_string(),
            file,
            line,
            span,
        });
        Ok(StmtId(id))
    }

    /// Interns a number (by bit pattern, so -0.0 and 0.0 stay apart).
    pub fn constant(&mut self, value: f64) -> Result<ConstId, BuildError> {
        if let Some(i) = self.index.constant(&self.m, value) {
            return Ok(ConstId(i));
        }
        let id = index(&self.m.consts, "constants")?;
        self.m.consts.push(value);
        self.index.added_constant(&self.m, id);
        Ok(ConstId(id))
    }

    /// Interns a name exactly as written (keywords and model names keep their case for
    /// messages; the VM compares them case-insensitively).
    pub fn name(&mut self, text: &str) -> Result<NameId, BuildError> {
        if let Some(i) = self.index.name(&self.m, text) {
            return Ok(NameId(i));
        }
        let id = index(&self.m.names, "names")?;
        self.m.names.push(text.to_string());
        self.index.added_name(&self.m, id);
        Ok(NameId(id))
    }

    /// Declares a global variable, or returns the existing slot of that name (any case).
    pub fn global(&mut self, name: &str, kind: VarKind) -> Result<VarId, BuildError> {
        if let Some(id) = self.find_global(name) {
            let was = self.m.globals[id.index()].kind;
            if was != kind {
                return Err(BuildError::KindConflict {
                    name: name.to_string(),
                    was,
                    now: kind,
                });
            }
            return Ok(id);
        }
        let id = index(&self.m.globals, "variables")?;
        self.m.globals.push(Global {
            name: name.to_string(),
            kind,
        });
        self.index.added_global(&self.m, id);
        Ok(VarId(id))
    }

    /// The variable of this name (any case); declared with `kind` if there is none. An
    /// existing variable keeps the kind it has: the lowering names the field of every
    /// read, so a slot's kind only labels it in listings and traces.
    pub fn global_keeping_kind(&mut self, name: &str, kind: VarKind) -> Result<VarId, BuildError> {
        index(&self.m.globals, "variables")?;
        let (id, _) = self.index.global_or_push(&mut self.m, name, || Global {
            name: name.to_string(),
            kind,
        });
        Ok(VarId(id))
    }

    /// A variable by name in any letter case.
    pub fn find_global(&self, name: &str) -> Option<VarId> {
        self.index.global(&self.m, name).map(VarId)
    }

    /// A unit by name in any letter case.
    pub fn find_unit(&self, name: &str) -> Option<UnitId> {
        self.index.unit(&self.m, name).map(UnitId)
    }

    /// Declares a unit so that calls can refer to it before its blocks exist.
    pub fn declare_unit(&mut self, name: &str, skill: bool) -> Result<UnitId, BuildError> {
        if self.find_unit(name).is_some() {
            return Err(BuildError::DuplicateUnit(name.to_string()));
        }
        let id = index(&self.m.units, "units")?;
        self.m.units.push(Unit {
            name: name.to_string(),
            skill,
            blocks: Vec::new(),
        });
        self.index.added_unit(&self.m, id);
        Ok(UnitId(id))
    }

    /// Sets a unit's top-level blocks (they start together when the unit runs).
    pub fn define_unit(&mut self, unit: UnitId, blocks: &[BlockId]) {
        if let Some(u) = self.m.units.get_mut(unit.index()) {
            u.blocks = blocks.to_vec();
        }
    }

    pub fn set_main(&mut self, unit: UnitId) {
        self.m.main = unit;
    }

    /// Appends an expression given in postfix.
    pub fn expr(&mut self, ops: &[ExprOp]) -> Result<ExprId, BuildError> {
        let start = index(&self.m.expr_code, "expression ops")?;
        let id = index(&self.m.exprs, "expressions")?;
        self.m.expr_code.extend_from_slice(ops);
        self.m.exprs.push(Expr {
            start,
            len: ops.len() as u32,
        });
        Ok(ExprId(id))
    }

    /// A constant expression.
    pub fn num(&mut self, value: f64) -> Result<ExprId, BuildError> {
        let c = self.constant(value)?;
        self.expr(&[ExprOp::Const(c)])
    }

    pub fn args(&mut self, args: &[Arg]) -> Result<ArgRange, BuildError> {
        let start = index(&self.m.args, "arguments")?;
        self.m.args.extend_from_slice(args);
        Ok(ArgRange {
            start,
            len: args.len() as u32,
        })
    }

    /// Appends a block of instructions, contiguous in the code table.
    pub fn block(&mut self, code: &[Instr]) -> Result<BlockId, BuildError> {
        let start = index(&self.m.code, "instructions")?;
        let id = index(&self.m.blocks, "blocks")?;
        self.m.code.extend_from_slice(code);
        self.m.blocks.push(Block {
            start,
            len: code.len() as u32,
        });
        Ok(BlockId(id))
    }

    /// The module so far, for lookups while lowering.
    pub fn module(&self) -> &Module {
        &self.m
    }

    /// Validates and returns the module.
    pub fn finish(self) -> Result<Module, BuildError> {
        self.m.validate().map_err(BuildError::Invalid)?;
        Ok(self.m)
    }

    /// Validates and returns what was added to the live module, with the blocks to
    /// start. Also usable on a builder made with [`Self::new`] (the base is empty).
    pub fn finish_fragment(self, start: &[BlockId]) -> Result<Fragment, BuildError> {
        let base = self.base.unwrap_or_default();
        self.m.validate_from(&base).map_err(BuildError::Invalid)?;
        let mut m = self.m;
        fn tail<T>(v: &mut Vec<T>, from: u32) -> Vec<T> {
            v.split_off((from as usize).min(v.len()))
        }
        let added = Module {
            header: Header::default(),
            files: tail(&mut m.files, base.files),
            stmts: tail(&mut m.stmts, base.stmts),
            consts: tail(&mut m.consts, base.consts),
            names: tail(&mut m.names, base.names),
            globals: tail(&mut m.globals, base.globals),
            units: tail(&mut m.units, base.units),
            main: m.main,
            blocks: tail(&mut m.blocks, base.blocks),
            code: tail(&mut m.code, base.code),
            args: tail(&mut m.args, base.args),
            exprs: tail(&mut m.exprs, base.exprs),
            expr_code: tail(&mut m.expr_code, base.expr_code),
        };
        Ok(Fragment {
            base,
            added,
            start: start.to_vec(),
        })
    }
}

//! Variables: global records (section 4.5.6) whose names ignore case. The table knows
//! which command bound each variable and whether a binding precedes the current
//! statement in the text.

use std::rc::Rc;

use smallvec::{SmallVec, smallvec};

use crate::check::fold::{self, FoldMap};

use ilmr_stdlib::VarKind;

use crate::diagnostic::FileId;
use crate::span::Span;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct VarId(pub u32);

/// Where a variable is bound or read. Most variables are bound once and many are read
/// once, so one place is kept without an allocation.
pub type Places = SmallVec<[(FileId, Span); 1]>;

#[derive(Debug, Clone)]
pub struct Var {
    /// The first spelling, which the formatter writes everywhere.
    pub spelling: String,
    pub kind: VarKind,
    pub defs: Places,
    pub uses: Places,
}

#[derive(Debug, Default, Clone)]
pub struct Vars {
    vars: Vec<Var>,
    index: FoldMap<VarId>,
    /// Whether a binding of each variable precedes the statement being checked.
    bound: Vec<bool>,
    /// Variables bound anywhere in the program, which a skill may use: consulted on a
    /// miss rather than copied into every skill's table.
    globals: Option<Rc<FoldMap<VarKind>>>,
    /// The globals are a running program's: compiled code reads them by kind, so a new
    /// binding cannot change one's kind.
    fixed: bool,
    /// Keep only a variable's first definition and first use (`Detail::Diagnostics`).
    first_only: bool,
    key: String,
}

impl Vars {
    pub fn find(&mut self, name: &str) -> Option<VarId> {
        self.index.get(fold::lookup(name, &mut self.key)).copied()
    }

    /// Every variable under its lower-cased key, in no particular order.
    pub(crate) fn keys(&self) -> impl Iterator<Item = (&str, VarId)> {
        self.index.iter().map(|(key, id)| (key, *id))
    }

    /// An empty table with room for `n` variables in its lists, whose room is written
    /// only as variables come. The index grows as names come instead: its slots are
    /// written where names hash, all over the table, and a program that binds its
    /// names again and again (counters, the corpus ten times) would write a table many
    /// times its variables, and look names up across it.
    pub(crate) fn with_capacity(n: usize) -> Vars {
        Vars {
            vars: Vec::with_capacity(n),
            bound: Vec::with_capacity(n),
            ..Vars::default()
        }
    }

    /// A table for a skill body, which sees the program's variables as bound.
    pub(crate) fn with_globals(globals: Rc<FoldMap<VarKind>>) -> Vars {
        Vars {
            globals: Some(globals),
            ..Vars::default()
        }
    }

    /// The table keeping what `detail` asks for.
    pub fn with_detail(self, detail: super::Detail) -> Vars {
        Vars {
            first_only: detail == super::Detail::Diagnostics,
            ..self
        }
    }

    /// A table for a line joining a running program, whose variables keep their kinds.
    pub(crate) fn with_fixed_globals(globals: Rc<FoldMap<VarKind>>) -> Vars {
        Vars {
            fixed: true,
            ..Vars::with_globals(globals)
        }
    }

    /// The kind a running program's variable must keep, if `name` is one.
    pub fn fixed_kind(&mut self, name: &str) -> Option<VarKind> {
        if !self.fixed {
            return None;
        }
        let globals = self.globals.as_ref()?;
        globals.get(fold::lookup(name, &mut self.key)).copied()
    }

    /// A variable bound before this point of the text (or, in a skill, anywhere).
    pub fn bound(&mut self, name: &str) -> Option<VarId> {
        if let Some(id) = self.find(name).filter(|id| self.bound[id.0 as usize]) {
            return Some(id);
        }
        let globals = self.globals.as_ref()?;
        let kind = *globals.get(fold::lookup(name, &mut self.key))?;
        let id = VarId(self.vars.len() as u32);
        self.index
            .insert(super::constants::key(name, &mut self.key), id);
        self.vars.push(Var {
            spelling: name.to_string(),
            kind,
            defs: Places::new(),
            uses: Places::new(),
        });
        self.bound.push(true);
        Some(id)
    }

    pub fn bind(&mut self, name: &str, kind: VarKind, file: FileId, span: Span) -> VarId {
        // One probe of the index finds the variable or makes room for it: a lookup and
        // then an insertion hashed and probed a new name twice (25,000 of them in the
        // 1x corpus).
        let next = VarId(self.vars.len() as u32);
        let id = *self.index.get_or_insert_named(name, &mut self.key, || next);
        if id == next {
            self.vars.push(Var {
                spelling: name.to_string(),
                kind,
                defs: smallvec![(file, span)],
                uses: Places::new(),
            });
            self.bound.push(true);
            return id;
        }
        let var = &mut self.vars[id.0 as usize];
        var.kind = kind;
        if !self.first_only || var.defs.is_empty() {
            var.defs.push((file, span));
        }
        self.bound[id.0 as usize] = true;
        id
    }

    pub fn use_at(&mut self, id: VarId, file: FileId, span: Span) {
        let uses = &mut self.vars[id.0 as usize].uses;
        if !self.first_only || uses.is_empty() {
            uses.push((file, span));
        }
    }

    pub fn len(&self) -> usize {
        self.vars.len()
    }

    pub fn is_empty(&self) -> bool {
        self.vars.is_empty()
    }

    pub fn get(&self, id: VarId) -> &Var {
        &self.vars[id.0 as usize]
    }

    pub fn iter(&self) -> impl Iterator<Item = (VarId, &Var)> {
        self.vars
            .iter()
            .enumerate()
            .map(|(i, v)| (VarId(i as u32), v))
    }

    /// Names bound so far, for suggestions.
    pub fn bound_names(&self) -> impl Iterator<Item = &str> {
        self.vars
            .iter()
            .zip(&self.bound)
            .filter(|(_, b)| **b)
            .map(|(v, _)| v.spelling.as_str())
    }

    /// Which variables are bound, to restore after a `check` block (whose statements are
    /// only validated and bind nothing).
    pub fn snapshot(&self) -> Vec<bool> {
        self.bound.clone()
    }

    pub fn restore(&mut self, snapshot: Vec<bool>) {
        let len = self.bound.len();
        self.bound = snapshot;
        self.bound.resize(len, false);
    }
}

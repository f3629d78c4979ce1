//! Variables: global records (section 4.5.6) whose names ignore case. The table knows
//! which command bound each variable and whether a binding precedes the current
//! statement in the text.

use std::collections::HashMap;

use ilmr_stdlib::VarKind;

use crate::diagnostic::FileId;
use crate::span::Span;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct VarId(pub u32);

#[derive(Debug, Clone)]
pub struct Var {
    /// The first spelling, which the formatter writes everywhere.
    pub spelling: String,
    pub kind: VarKind,
    pub defs: Vec<(FileId, Span)>,
    pub uses: Vec<(FileId, Span)>,
}

#[derive(Debug, Default, Clone)]
pub struct Vars {
    vars: Vec<Var>,
    index: HashMap<String, VarId>,
    /// Whether a binding of each variable precedes the statement being checked.
    bound: Vec<bool>,
    key: String,
}

impl Vars {
    pub fn find(&mut self, name: &str) -> Option<VarId> {
        self.key.clear();
        self.key.extend(name.chars().flat_map(char::to_lowercase));
        self.index.get(self.key.as_str()).copied()
    }

    /// A variable bound before this point of the text.
    pub fn bound(&mut self, name: &str) -> Option<VarId> {
        self.find(name).filter(|id| self.bound[id.0 as usize])
    }

    pub fn bind(&mut self, name: &str, kind: VarKind, file: FileId, span: Span) -> VarId {
        let id = match self.find(name) {
            Some(id) => id,
            None => {
                let id = VarId(self.vars.len() as u32);
                let key = self.key.clone();
                self.index.insert(key, id);
                self.vars.push(Var {
                    spelling: name.to_string(),
                    kind,
                    defs: Vec::new(),
                    uses: Vec::new(),
                });
                self.bound.push(false);
                id
            }
        };
        let var = &mut self.vars[id.0 as usize];
        var.kind = kind;
        var.defs.push((file, span));
        self.bound[id.0 as usize] = true;
        id
    }

    pub fn use_at(&mut self, id: VarId, file: FileId, span: Span) {
        self.vars[id.0 as usize].uses.push((file, span));
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

    /// Marks every variable as bound: the program-wide view a skill body starts from.
    pub fn bind_all(&mut self) {
        self.bound.iter_mut().for_each(|b| *b = true);
    }
}

//! The builder's index of what it interned: files, names and constants by value,
//! variables and units by name in any letter case. A task declares one variable per
//! name it binds, so a search of the table per lookup made lowering quadratic in the
//! number of variables (51 s for 100,000 blocks, issue 14).
//!
//! The tables hold ids into the module's own vectors, so nothing is stored twice. A
//! builder lent a live module (an interactive line) indexes only what the line adds and
//! searches the live part on a miss, as it did before: indexing the whole program per
//! line would cost more than the few lookups a line makes.

use std::hash::{BuildHasher, Hasher};

use hashbrown::HashTable;
use hashbrown::hash_table::Entry;
use rustc_hash::{FxBuildHasher, FxHasher};

use super::{Counts, Global, Module};

#[derive(Debug, Clone, Default)]
pub(super) struct Index {
    /// Entries before these counts are not in the tables.
    from: Counts,
    files: HashTable<u32>,
    names: HashTable<u32>,
    consts: HashTable<u32>,
    globals: HashTable<u32>,
    units: HashTable<u32>,
}

fn exact(s: &str) -> u64 {
    FxBuildHasher.hash_one(s)
}

/// A hash under which names equal in any ASCII letter case collide, as
/// `eq_ignore_ascii_case` needs; no folded copy of the name is made.
fn folded(s: &str) -> u64 {
    let mut h = FxHasher::default();
    for chunk in s.as_bytes().chunks(8) {
        let mut word = [0u8; 8];
        for (w, b) in word.iter_mut().zip(chunk) {
            *w = b.to_ascii_lowercase();
        }
        h.write_u64(u64::from_le_bytes(word));
    }
    h.write_usize(s.len());
    h.finish()
}

fn bits(value: f64) -> u64 {
    FxBuildHasher.hash_one(value.to_bits())
}

/// Looks `key` up in `table`, then in the entries before `from` that the table does
/// not hold.
fn find<T>(
    table: &HashTable<u32>,
    from: u32,
    entries: &[T],
    hash: u64,
    eq: impl Fn(&T) -> bool,
) -> Option<u32> {
    if let Some(&i) = table.find(hash, |&i| entries.get(i as usize).is_some_and(&eq)) {
        return Some(i);
    }
    let older = (from as usize).min(entries.len());
    entries[..older]
        .iter()
        .position(eq)
        .and_then(|i| u32::try_from(i).ok())
}

impl Index {
    /// An index of nothing, for a builder whose module already holds `from`.
    pub(super) fn after(from: Counts) -> Index {
        Index {
            from,
            ..Index::default()
        }
    }

    pub(super) fn file(&self, m: &Module, path: &str) -> Option<u32> {
        find(&self.files, self.from.files, &m.files, exact(path), |f| {
            f == path
        })
    }

    pub(super) fn name(&self, m: &Module, text: &str) -> Option<u32> {
        find(&self.names, self.from.names, &m.names, exact(text), |n| {
            n == text
        })
    }

    pub(super) fn constant(&self, m: &Module, value: f64) -> Option<u32> {
        find(
            &self.consts,
            self.from.consts,
            &m.consts,
            bits(value),
            |c| c.to_bits() == value.to_bits(),
        )
    }

    pub(super) fn global(&self, m: &Module, name: &str) -> Option<u32> {
        find(
            &self.globals,
            self.from.globals,
            &m.globals,
            folded(name),
            |g| g.name.eq_ignore_ascii_case(name),
        )
    }

    pub(super) fn unit(&self, m: &Module, name: &str) -> Option<u32> {
        find(&self.units, self.from.units, &m.units, folded(name), |u| {
            u.name.eq_ignore_ascii_case(name)
        })
    }

    /// The variable named `name` in any case, or `make()` pushed as a new one: one
    /// probe of the table either way. Whether it is new comes back with the id.
    pub(super) fn global_or_push(
        &mut self,
        m: &mut Module,
        name: &str,
        make: impl FnOnce() -> Global,
    ) -> (u32, bool) {
        let globals = &m.globals;
        let entry = self.globals.entry(
            folded(name),
            |&i| {
                globals
                    .get(i as usize)
                    .is_some_and(|g| g.name.eq_ignore_ascii_case(name))
            },
            |&i| globals.get(i as usize).map_or(0, |g| folded(&g.name)),
        );
        match entry {
            Entry::Occupied(e) => (*e.get(), false),
            Entry::Vacant(v) => {
                let older = (self.from.globals as usize).min(m.globals.len());
                if let Some(i) = m.globals[..older]
                    .iter()
                    .position(|g| g.name.eq_ignore_ascii_case(name))
                {
                    return (i as u32, false);
                }
                let id = m.globals.len() as u32;
                m.globals.push(make());
                v.insert(id);
                (id, true)
            }
        }
    }

    pub(super) fn reserve_globals(&mut self, m: &Module, more: usize) {
        self.globals.reserve(more, |&i| {
            m.globals.get(i as usize).map_or(0, |g| folded(&g.name))
        });
    }

    // Each `added_*` records entry `id`, just pushed and not found before.

    pub(super) fn added_file(&mut self, m: &Module, id: u32) {
        let hash = |&i: &u32| m.files.get(i as usize).map_or(0, |f| exact(f));
        self.files.insert_unique(hash(&id), id, hash);
    }

    pub(super) fn added_name(&mut self, m: &Module, id: u32) {
        let hash = |&i: &u32| m.names.get(i as usize).map_or(0, |n| exact(n));
        self.names.insert_unique(hash(&id), id, hash);
    }

    pub(super) fn added_constant(&mut self, m: &Module, id: u32) {
        let hash = |&i: &u32| m.consts.get(i as usize).map_or(0, |&c| bits(c));
        self.consts.insert_unique(hash(&id), id, hash);
    }

    pub(super) fn added_global(&mut self, m: &Module, id: u32) {
        let hash = |&i: &u32| m.globals.get(i as usize).map_or(0, |g| folded(&g.name));
        self.globals.insert_unique(hash(&id), id, hash);
    }

    pub(super) fn added_unit(&mut self, m: &Module, id: u32) {
        let hash = |&i: &u32| m.units.get(i as usize).map_or(0, |u| folded(&u.name));
        self.units.insert_unique(hash(&id), id, hash);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_equal_in_any_case_hash_alike_and_others_apart() {
        for (a, b) in [
            ("Counter", "cOUNTER"),
            ("x", "X"),
            ("a_long_name_of_17", "A_LONG_NAME_OF_17"),
        ] {
            assert_eq!(folded(a), folded(b), "{a} {b}");
        }
        // Same folded bytes in the first word but another length.
        assert_ne!(folded("ab"), folded("ab\0"));
        assert_ne!(folded("c1"), folded("c2"));
    }
}

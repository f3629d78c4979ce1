//! Compiled guards: an `if` whose condition is `var.field <op> const` (or
//! `const <op> var.field`, or a bare `var`, true when its field is not 0) waits in a
//! list per (variable, field, operator), grouped by
//! its constant in ascending order. For one value of the field the constants that make
//! such a condition true are a run of groups at one end of the list (`<`, `<=`, `>`,
//! `>=`), in the middle (`==`) or at both ends (`!=`); binary searches with the VM's own
//! comparison find them, so a change of the variable touches only the guards that are
//! now true and the rest cost nothing.
//!
//! Entries are dropped lazily: a guard that fires or ends only counts as dead in its
//! list (the node knows its list, not its place in it); the dead are swept from the
//! groups a wake takes, and the whole list is compacted once they are the majority.

use ilmr_stdlib::Field;

use super::vars::NONE;
use crate::bytecode::ExprOp;

/// A comparison of two numbers, as every ILMR expression compares: equal within 1e-9.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Cmp {
    Lt,
    Le,
    Eq,
    Ne,
    Gt,
    Ge,
    /// A bare value as a condition: true when not exactly 0 (the constant is unused).
    Truthy,
}

/// Equality tolerance of `==`, `!=`, `<=`, `>=` (and the strictness of `<`, `>`).
const EQ_TOLERANCE: f64 = 1e-9;

impl Cmp {
    pub fn of(op: ExprOp) -> Option<Cmp> {
        Some(match op {
            ExprOp::Lt => Cmp::Lt,
            ExprOp::Le => Cmp::Le,
            ExprOp::Eq => Cmp::Eq,
            ExprOp::Ne => Cmp::Ne,
            ExprOp::Gt => Cmp::Gt,
            ExprOp::Ge => Cmp::Ge,
            _ => return None,
        })
    }

    /// `a op b`. The expression evaluator and the guard lists share this, so a
    /// compiled guard fires exactly when its expression would be true.
    #[inline]
    pub fn holds(self, a: f64, b: f64) -> bool {
        let eq = (a - b).abs() <= EQ_TOLERANCE;
        match self {
            Cmp::Lt => a < b && !eq,
            Cmp::Le => a < b || eq,
            Cmp::Eq => eq,
            Cmp::Ne => !eq,
            Cmp::Gt => a > b && !eq,
            Cmp::Ge => a > b || eq,
            Cmp::Truthy => a != 0.0,
        }
    }

    /// The operator that reads the same with its operands swapped (`c < x` is
    /// `x > c`). Exact: `c - x` is `-(x - c)` in IEEE arithmetic, so the tolerance
    /// test gives the same answer either way round.
    fn swapped(self) -> Cmp {
        match self {
            Cmp::Lt => Cmp::Gt,
            Cmp::Le => Cmp::Ge,
            Cmp::Gt => Cmp::Lt,
            Cmp::Ge => Cmp::Le,
            other => other,
        }
    }
}

/// A guard condition of the compiled shape, normalised to `var.field <op> c`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Shape {
    pub var: u32,
    pub field: Field,
    pub op: Cmp,
    pub c: f64,
}

impl Shape {
    /// Recognises `field const cmp`, `const field cmp` or a bare `field`. A constant
    /// that is not finite keeps the general path: the runs of true constants rely on
    /// ordering them.
    pub fn compile(ops: &[ExprOp], consts: &[f64]) -> Option<Shape> {
        if let &[ExprOp::Field(var, field)] = ops {
            return Some(Shape {
                var: var.0,
                field,
                op: Cmp::Truthy,
                c: 0.0,
            });
        }
        let &[a, b, op] = ops else {
            return None;
        };
        let op = Cmp::of(op)?;
        let (var, field, c, op) = match (a, b) {
            (ExprOp::Field(v, f), ExprOp::Const(c)) => (v, f, c, op),
            (ExprOp::Const(c), ExprOp::Field(v, f)) => (v, f, c, op.swapped()),
            _ => return None,
        };
        let c = consts.get(c.index()).copied().filter(|c| c.is_finite())?;
        Some(Shape {
            var: var.0,
            field,
            op,
            c,
        })
    }
}

/// A waiting compiled guard: its node and its place in subscription order.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Entry {
    pub seq: u64,
    pub node: u32,
    pub epoch: u32,
}

/// The guards of one constant, in subscription order.
#[derive(Debug)]
struct Group {
    c: f64,
    entries: Vec<Entry>,
}

#[derive(Debug)]
struct List {
    var: u32,
    field: Field,
    op: Cmp,
    /// Ascending by `c`, no two equal, none empty.
    groups: Vec<Group>,
    /// Entries in `groups`, live or dead.
    entries: u32,
    /// Entries whose guard has fired or ended.
    dead: u32,
    /// The variable's next list.
    next: u32,
}

/// Groups `lo..hi` of list `list` were taken by a wake.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Taken {
    list: u32,
    lo: u32,
    hi: u32,
}

/// List ids stay below this, so that a node's subscription head can tell a list id
/// from a subscription pool index by the top bit.
pub(crate) const MAX_LISTS: u32 = 1 << 31;

/// Compaction waits for this many dead entries, so small lists are left alone.
const COMPACT_AT: u32 = 64;

#[derive(Debug, Default)]
pub(crate) struct Watches {
    lists: Vec<List>,
    /// Per variable: its first list, and how many live guards its lists hold; only
    /// up to the last variable watched (a variable past them has no list).
    first: Vec<u32>,
    live: Vec<u32>,
    /// The variables there are.
    vars: usize,
}

impl Watches {
    pub fn grow(&mut self, n: usize) {
        self.vars = self.vars.max(n);
    }

    pub fn footprint(&self) -> usize {
        use std::mem::size_of;
        let groups: usize = self
            .lists
            .iter()
            .map(|l| {
                l.groups.capacity() * size_of::<Group>()
                    + l.groups
                        .iter()
                        .map(|g| g.entries.capacity() * size_of::<Entry>())
                        .sum::<usize>()
            })
            .sum();
        self.lists.capacity() * size_of::<List>()
            + (self.first.capacity() + self.live.capacity()) * size_of::<u32>()
            + groups
    }

    /// Live compiled guards on `var`.
    pub fn live(&self, var: u32) -> u32 {
        self.live.get(var as usize).copied().unwrap_or(0)
    }

    /// Adds a guard; returns its list, or `None` for a variable out of range.
    /// `is_live` tells whether an entry's guard still waits (for compaction).
    pub fn add(
        &mut self,
        shape: Shape,
        entry: Entry,
        is_live: impl Fn(&Entry) -> bool,
    ) -> Option<u32> {
        let id = self.list_for(shape)?;
        let list = &mut self.lists[id as usize];
        let at = list.groups.partition_point(|g| g.c < shape.c);
        match list.groups.get_mut(at) {
            Some(g) if g.c == shape.c => g.entries.push(entry),
            _ => list.groups.insert(
                at,
                Group {
                    c: shape.c,
                    entries: vec![entry],
                },
            ),
        }
        list.entries += 1;
        self.live[shape.var as usize] += 1;
        self.compact(id, is_live);
        Some(id)
    }

    fn list_for(&mut self, shape: Shape) -> Option<u32> {
        let v = shape.var as usize;
        if v >= self.vars {
            return None;
        }
        if v >= self.first.len() {
            self.first.resize(v + 1, NONE);
            self.live.resize(v + 1, 0);
        }
        let mut id = self.first[v];
        while id != NONE {
            let l = &self.lists[id as usize];
            if l.field == shape.field && l.op == shape.op {
                return Some(id);
            }
            id = l.next;
        }
        let id = u32::try_from(self.lists.len())
            .ok()
            .filter(|&i| i < MAX_LISTS)?;
        self.lists.push(List {
            var: shape.var,
            field: shape.field,
            op: shape.op,
            groups: Vec::new(),
            entries: 0,
            dead: 0,
            next: self.first[shape.var as usize],
        });
        self.first[shape.var as usize] = id;
        Some(id)
    }

    /// A guard of `list` fired or ended: its entry is dead from now on.
    pub fn drop_one(&mut self, list: u32) {
        if let Some(l) = self.lists.get_mut(list as usize) {
            l.dead += 1;
            if let Some(n) = self.live.get_mut(l.var as usize) {
                *n = n.saturating_sub(1);
            }
        }
    }

    /// The guards of `var` whose condition holds for the variable's present fields
    /// (`field_of`), appended to `out` as `(list, entry)` group by group; the groups
    /// are recorded in `taken` for [`Self::settle`]. Dead entries are included: the
    /// caller checks each node anyway.
    pub fn take_true(
        &self,
        var: u32,
        field_of: impl Fn(Field) -> f64,
        out: &mut impl FnMut(u32, Entry),
        taken: &mut Vec<Taken>,
    ) {
        let mut id = self.first.get(var as usize).copied().unwrap_or(NONE);
        while id != NONE {
            let l = &self.lists[id as usize];
            let a = field_of(l.field);
            let (first, second) = true_runs(&l.groups, l.op, a);
            for (lo, hi) in [first, second] {
                if lo < hi {
                    taken.push(Taken {
                        list: id,
                        lo: lo as u32,
                        hi: hi as u32,
                    });
                    for g in &l.groups[lo..hi] {
                        for &e in &g.entries {
                            out(id, e);
                        }
                    }
                }
            }
            id = l.next;
        }
    }

    /// After a wake: sweeps the dead from the groups it took (a guard that was true
    /// but did not fire, after a budget overrun, stays) and drops emptied groups.
    pub fn settle(&mut self, taken: &[Taken], is_live: impl Fn(&Entry) -> bool) {
        for t in taken {
            let Some(l) = self.lists.get_mut(t.list as usize) else {
                continue;
            };
            let hi = (t.hi as usize).min(l.groups.len());
            let lo = (t.lo as usize).min(hi);
            let mut removed = 0u32;
            for g in &mut l.groups[lo..hi] {
                let before = g.entries.len();
                g.entries.retain(&is_live);
                removed += (before - g.entries.len()) as u32;
            }
            l.entries -= removed;
            l.dead = l.dead.saturating_sub(removed);
            l.groups.retain(|g| !g.entries.is_empty());
        }
        for t in taken {
            self.compact(t.list, &is_live);
        }
    }

    /// Drops every dead entry of a list once the dead are the majority, so that the
    /// sweep costs at most one pass per dead entry.
    fn compact(&mut self, list: u32, is_live: impl Fn(&Entry) -> bool) {
        let Some(l) = self.lists.get_mut(list as usize) else {
            return;
        };
        if l.dead < COMPACT_AT || l.dead * 2 < l.entries {
            return;
        }
        for g in &mut l.groups {
            g.entries.retain(&is_live);
        }
        l.groups.retain(|g| !g.entries.is_empty());
        l.entries = l.groups.iter().map(|g| g.entries.len() as u32).sum();
        l.dead = 0;
    }
}

/// The groups (ascending constants) for which `a op c` holds: at most two runs.
/// Each comparison is monotone in `c` for a fixed `a` (the rounded difference
/// `a - c` is), so each run edge is a partition point.
fn true_runs(groups: &[Group], op: Cmp, a: f64) -> ((usize, usize), (usize, usize)) {
    let n = groups.len();
    let first_true = |op: Cmp| groups.partition_point(|g| !op.holds(a, g.c));
    let none = (n, n);
    match op {
        Cmp::Lt | Cmp::Le => ((first_true(op), n), none),
        Cmp::Gt | Cmp::Ge => ((0, groups.partition_point(|g| op.holds(a, g.c))), none),
        // `a == c` is `a <= c` but not `a < c`; `!=` is the rest.
        Cmp::Eq => ((first_true(Cmp::Le), first_true(Cmp::Lt)), none),
        Cmp::Ne => ((0, first_true(Cmp::Le)), (first_true(Cmp::Lt), n)),
        Cmp::Truthy if Cmp::Truthy.holds(a, 0.0) => ((0, n), none),
        Cmp::Truthy => (none, none),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bytecode::{ConstId, VarId};

    const OPS: [Cmp; 7] = [
        Cmp::Lt,
        Cmp::Le,
        Cmp::Eq,
        Cmp::Ne,
        Cmp::Gt,
        Cmp::Ge,
        Cmp::Truthy,
    ];

    fn groups(cs: &[f64]) -> Vec<Group> {
        let mut cs = cs.to_vec();
        cs.sort_by(f64::total_cmp);
        cs.dedup();
        cs.into_iter()
            .map(|c| Group {
                c,
                entries: Vec::new(),
            })
            .collect()
    }

    #[test]
    fn the_true_runs_are_exactly_the_constants_the_comparison_holds_for() {
        let cs = [
            -3.0,
            -1.0,
            -1e-10,
            0.0,
            5e-10,
            1e-9,
            1.5e-9,
            0.5,
            1.0,
            1.0 + 1e-9,
            2.0,
            1e6,
        ];
        let gs = groups(&cs);
        let mut rng = ilmr_geometry::SplitMix64::new(7);
        let mut values = vec![
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            -0.0,
            0.0,
            1.0,
            1.0 - 1e-9,
            1.0 + 2e-9,
        ];
        values.extend(gs.iter().flat_map(|g| {
            [
                g.c,
                g.c + 1e-9,
                g.c - 1e-9,
                f64::from_bits(g.c.to_bits() + 1),
            ]
        }));
        for _ in 0..2_000 {
            let r = rng.next_u64();
            let base = gs[(r % gs.len() as u64) as usize].c;
            let jitter = ((r >> 8) % 4001) as f64 - 2000.0;
            values.push(base + jitter * 1e-12);
        }
        for a in values {
            for op in OPS {
                let (r1, r2) = true_runs(&gs, op, a);
                for (i, g) in gs.iter().enumerate() {
                    let inside = (r1.0..r1.1).contains(&i) || (r2.0..r2.1).contains(&i);
                    assert_eq!(inside, op.holds(a, g.c), "{a} {op:?} {}", g.c);
                }
            }
        }
    }

    #[test]
    fn a_constant_on_the_left_reads_as_the_swapped_operator() {
        let consts = [2.0, f64::NAN];
        let t = VarId(3);
        let shape = Shape::compile(
            &[
                ExprOp::Const(ConstId(0)),
                ExprOp::Field(t, Field::X),
                ExprOp::Lt,
            ],
            &consts,
        );
        assert_eq!(
            shape,
            Some(Shape {
                var: 3,
                field: Field::X,
                op: Cmp::Gt,
                c: 2.0
            })
        );
        for op in &OPS[..6] {
            let op = *op;
            for x in [1.0, 2.0 - 1e-9, 2.0, 2.0 + 5e-10, 3.0, f64::NAN] {
                assert_eq!(op.holds(2.0, x), op.swapped().holds(x, 2.0), "{op:?} {x}");
            }
        }
        let nan = [
            ExprOp::Field(t, Field::X),
            ExprOp::Const(ConstId(1)),
            ExprOp::Lt,
        ];
        assert_eq!(Shape::compile(&nan, &consts), None);
        let sum = [
            ExprOp::Field(t, Field::X),
            ExprOp::Const(ConstId(0)),
            ExprOp::Add,
        ];
        assert_eq!(Shape::compile(&sum, &consts), None);
        let bare = Shape::compile(&[ExprOp::Field(t, Field::Status)], &consts);
        assert_eq!(
            bare.map(|s| (s.op, s.field)),
            Some((Cmp::Truthy, Field::Status))
        );
    }

    #[test]
    fn a_wake_takes_only_the_true_groups_and_settling_drops_the_fired() {
        let mut w = Watches::default();
        w.grow(1);
        let shape = |c| Shape {
            var: 0,
            field: Field::Value,
            op: Cmp::Lt,
            c,
        };
        let live = |_: &Entry| true;
        for (seq, c) in [(0, 5.0), (1, 1.0), (2, 5.0), (3, 3.0)] {
            let e = Entry {
                seq,
                node: seq as u32,
                epoch: 0,
            };
            assert_eq!(w.add(shape(c), e, live), Some(0));
        }
        assert_eq!(w.live(0), 4);
        let mut seen = Vec::new();
        let mut taken = Vec::new();
        w.take_true(0, |_| 2.0, &mut |_, e| seen.push(e.seq), &mut taken);
        assert_eq!(seen, vec![3, 0, 2], "2 < 3 and 2 < 5, group by group");
        for _ in 0..3 {
            w.drop_one(0);
        }
        w.settle(&taken, |e| e.seq == 1);
        assert_eq!(w.live(0), 1);
        seen.clear();
        taken.clear();
        w.take_true(0, |_| -1.0, &mut |_, e| seen.push(e.seq), &mut taken);
        assert_eq!(seen, vec![1]);
        assert_eq!(w.lists[0].entries, 1);
        assert_eq!(w.lists[0].dead, 0);
    }

    #[test]
    fn dead_entries_are_compacted_once_they_are_the_majority() {
        let mut w = Watches::default();
        w.grow(1);
        let shape = Shape {
            var: 0,
            field: Field::Value,
            op: Cmp::Gt,
            c: 0.0,
        };
        let n = 4 * COMPACT_AT as u64;
        for seq in 0..n {
            let e = Entry {
                seq,
                node: seq as u32,
                epoch: 0,
            };
            w.add(shape, e, |_| true);
        }
        // Three guards in four end without firing.
        for _ in 0..3 * n / 4 {
            w.drop_one(0);
        }
        assert_eq!(w.lists[0].dead as u64, 3 * n / 4, "not compacted yet");
        let e = Entry {
            seq: n,
            node: n as u32,
            epoch: 0,
        };
        w.add(shape, e, |e| e.seq % 4 == 3 || e.seq == n);
        assert_eq!(w.lists[0].dead, 0);
        assert_eq!(w.lists[0].entries as u64, n / 4 + 1);
        assert_eq!(w.live(0) as u64, n / 4 + 1);
    }
}

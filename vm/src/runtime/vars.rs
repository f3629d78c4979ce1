//! Variable records (Table 8 plus how the command ended) and the subscriptions that wake
//! guards and waits when a variable changes. Subscriptions are intrusive lists in one
//! pool: a doubly linked list per variable and a singly linked list per node (so a node
//! drops all of its subscriptions at once). Guards of the shape `var.field <op> const`
//! wait in [`Watches`] instead. Every subscription takes a sequence number, so a wake
//! puts both kinds back into subscription order.

use ilmr_stdlib::Field;
use serde::Serialize;

use super::watch::{Entry, MAX_LISTS, Shape, Taken, Watches};

pub(crate) const NONE: u32 = u32::MAX;

/// A node's subscription head with this bit set names the [`Watches`] list of its
/// compiled guard (the rest of the bits) rather than a pool chain; the pool stays
/// below 2^31 entries.
const WATCH: u32 = MAX_LISTS;

/// How a command ended: the trace's own type, so the VM and the trace's readers
/// share one vocabulary.
pub use ilmr_trace::How;

/// A variable: the fields of Table 8 and how its command ended (`None` while it runs
/// or for plain arithmetic).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct VarRecord {
    pub status: f64,
    pub x: f64,
    pub y: f64,
    pub h: f64,
    pub value: f64,
    pub dist: f64,
    pub how: Option<How>,
}

/// Fields changed by one write, as a bit set over [`FIELDS`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct FieldMask(pub u8);

/// Trace order of the fields.
pub const FIELDS: [Field; 6] = [
    Field::Status,
    Field::X,
    Field::Y,
    Field::H,
    Field::Value,
    Field::Dist,
];

impl FieldMask {
    pub fn bit(f: Field) -> u8 {
        match f {
            Field::Status => 1,
            Field::X => 2,
            Field::Y => 4,
            Field::H => 8,
            Field::Value => 16,
            Field::Dist => 32,
        }
    }
    pub fn has(self, f: Field) -> bool {
        self.0 & FieldMask::bit(f) != 0
    }
    pub fn is_empty(self) -> bool {
        self.0 == 0
    }
}

/// What every variable holds, kept dense: the two fields an assignment writes (a
/// counter's whole state), 16 bytes a variable.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct Core {
    pub status: f64,
    pub value: f64,
}

/// The fields of a pose or a distance (`x`, `y`, `h`, `dist`), in [`Vars::places`]:
/// only a variable that a command ever set one of them in has one, so a variable of
/// arithmetic costs its [`Core`] alone, not six fields.
type Place = [f64; 4];

/// Where `f` lies in a [`Place`]; None for the fields of [`Core`].
#[inline]
fn place_of(f: Field) -> Option<usize> {
    match f {
        Field::Status | Field::Value => None,
        Field::X => Some(0),
        Field::Y => Some(1),
        Field::H => Some(2),
        Field::Dist => Some(3),
    }
}

impl VarRecord {
    pub fn get(&self, f: Field) -> f64 {
        match f {
            Field::Status => self.status,
            Field::X => self.x,
            Field::Y => self.y,
            Field::H => self.h,
            Field::Value => self.value,
            Field::Dist => self.dist,
        }
    }
}

#[derive(Debug, Clone, Copy)]
struct Sub {
    seq: u64,
    node: u32,
    /// The guard's condition, so that waking evaluates it without touching the
    /// node; NONE for a `wait(v)`.
    cond: u32,
    var: u32,
    prev: u32,
    next: u32,
    next_of_node: u32,
}

/// A variable's subscription list, and whether a wake of it is queued.
#[derive(Debug, Clone, Copy)]
struct Head {
    first: u32,
    last: u32,
    queued: bool,
}

const EMPTY: Head = Head {
    first: NONE,
    last: NONE,
    queued: false,
};

/// What a woken subscriber is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Waiter {
    /// A `wait(v)`.
    Wait,
    /// A guard on the general path, with its condition.
    Guard { cond: u32 },
    /// A compiled guard whose condition held when the wake began; `epoch` tells a
    /// dead entry (the node ended or was reused) from a live one.
    Watch { epoch: u32 },
}

/// A subscriber of a woken variable.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Woken {
    pub seq: u64,
    pub node: u32,
    pub waiter: Waiter,
}

#[derive(Debug, Default)]
pub(crate) struct Vars {
    cores: Vec<Core>,
    /// Each variable's index in `places` (NONE: its pose and distance are all zero),
    /// up to the last variable that has one: a program of counters keeps none.
    place: Vec<u32>,
    places: Vec<Place>,
    /// How each variable's command ended, up to the last variable a command has
    /// ended into: assignments, which clear it, leave the rest without one.
    hows: Vec<Option<How>>,
    /// The subscription lists of the variables up to the last one anything has
    /// subscribed to or watched ([`Vars::head`]): a variable past them has none, and
    /// a program of many variables that nothing waits on keeps none.
    heads: Vec<Head>,
    subs: Vec<Sub>,
    free_subs: u32,
    watches: Watches,
    /// The next subscription's sequence number.
    seq: u64,
    /// Reused: the watch groups the wake being evaluated took.
    taken: Vec<Taken>,
}

impl Vars {
    pub fn new(n: usize) -> Vars {
        let mut watches = Watches::default();
        watches.grow(n);
        Vars {
            cores: vec![Core::default(); n],
            place: Vec::new(),
            places: Vec::new(),
            hows: Vec::new(),
            heads: Vec::new(),
            subs: Vec::new(),
            free_subs: NONE,
            watches,
            seq: 0,
            taken: Vec::new(),
        }
    }

    pub fn footprint(&self) -> usize {
        use std::mem::size_of;
        self.cores.capacity() * size_of::<Core>()
            + self.place.capacity() * size_of::<u32>()
            + self.places.capacity() * size_of::<Place>()
            + self.hows.capacity() * size_of::<Option<How>>()
            + self.heads.capacity() * size_of::<Head>()
            + self.subs.capacity() * size_of::<Sub>()
            + self.watches.footprint()
            + self.taken.capacity() * size_of::<Taken>()
    }

    pub fn grow(&mut self, n: usize) {
        if n > self.cores.len() {
            self.cores.resize(n, Core::default());
            self.watches.grow(n);
        }
    }

    /// The subscription list of `var`, made (with those before it) on first use;
    /// None for a variable out of range.
    fn head(&mut self, var: u32) -> Option<&mut Head> {
        let v = var as usize;
        if v >= self.cores.len() {
            return None;
        }
        if v >= self.heads.len() {
            self.heads.resize(v + 1, EMPTY);
        }
        self.heads.get_mut(v)
    }

    pub fn get(&self, v: u32) -> VarRecord {
        let Some(c) = self.cores.get(v as usize) else {
            return VarRecord::default();
        };
        let [x, y, h, dist] = self.place(v).copied().unwrap_or_default();
        VarRecord {
            status: c.status,
            x,
            y,
            h,
            value: c.value,
            dist,
            how: self.how(v),
        }
    }

    /// `v`'s pose and distance, if it has any.
    #[inline]
    fn place(&self, v: u32) -> Option<&Place> {
        let i = *self.place.get(v as usize)?;
        self.places.get(i as usize)
    }

    /// `v`'s pose and distance, made (all zero) if it has none; None for a variable
    /// out of range.
    fn place_mut(&mut self, v: u32) -> Option<&mut Place> {
        let i = v as usize;
        if i >= self.cores.len() {
            return None;
        }
        if i >= self.place.len() {
            self.place.resize(i + 1, NONE);
        }
        if self.place[i] == NONE {
            self.place[i] = self.places.len() as u32;
            self.places.push(Place::default());
        }
        self.places.get_mut(self.place[i] as usize)
    }

    fn how(&self, v: u32) -> Option<How> {
        self.hows.get(v as usize).copied().flatten()
    }

    /// Writes a whole record.
    #[cfg(test)]
    fn put(&mut self, v: u32, r: &VarRecord) {
        if (v as usize) < self.cores.len() {
            for f in FIELDS {
                self.set(v, f, r.get(f));
            }
            self.set_how(v, r.how);
        }
    }

    /// One field, without copying the record (expressions).
    #[inline]
    pub fn field(&self, v: u32, f: Field) -> f64 {
        match f {
            Field::Status => self.cores.get(v as usize).map_or(0.0, |c| c.status),
            Field::Value => self.cores.get(v as usize).map_or(0.0, |c| c.value),
            _ => place_of(f)
                .and_then(|i| self.place(v).map(|p| p[i]))
                .unwrap_or(0.0),
        }
    }

    /// Nothing would hear a write of `v`: no wait or guard subscribes to it or
    /// watches it, and no wake of it is queued ([`Vars::queue_wake`] would queue
    /// nothing).
    #[inline]
    pub fn quiet(&self, v: u32) -> bool {
        self.heads
            .get(v as usize)
            .is_none_or(|h| !h.queued && h.first == NONE && self.watches.live(v) == 0)
    }

    /// Marks a wake of `v` as queued; returns false if one already was or nothing
    /// subscribes to `v`.
    pub fn queue_wake(&mut self, v: u32) -> bool {
        let watched = self.watches.live(v) > 0;
        match self.heads.get_mut(v as usize) {
            Some(h) if !h.queued && (h.first != NONE || watched) => {
                h.queued = true;
                true
            }
            _ => false,
        }
    }

    /// Takes the queued wake of `v`: appends to `out`, in subscription order, every
    /// wait and general guard subscribed to `v` and the compiled guards whose
    /// condition now holds (some of them may have ended: see [`Waiter::Watch`]).
    /// Compiled guards that stay false are not looked at.
    pub fn take_wake(&mut self, v: u32, out: &mut Vec<Woken>) {
        let Some(h) = self.heads.get_mut(v as usize) else {
            return;
        };
        h.queued = false;
        let mut id = h.first;
        while id != NONE {
            let s = &self.subs[id as usize];
            let waiter = if s.cond == NONE {
                Waiter::Wait
            } else {
                Waiter::Guard { cond: s.cond }
            };
            out.push(Woken {
                seq: s.seq,
                node: s.node,
                waiter,
            });
            id = s.next;
        }
        let general = out.len();
        let record = self.get(v);
        self.taken.clear();
        self.watches.take_true(
            v,
            |f| record.get(f),
            &mut |_, e: Entry| {
                out.push(Woken {
                    seq: e.seq,
                    node: e.node,
                    waiter: Waiter::Watch { epoch: e.epoch },
                })
            },
            &mut self.taken,
        );
        // Each source is in subscription order already; the stable sort merges runs.
        if out.len() > general && !out.is_sorted_by_key(|w| w.seq) {
            out.sort_by_key(|w| w.seq);
        }
    }

    /// After the wake taken last: forgets the compiled guards that fired or ended.
    pub fn settle_wake(&mut self, is_live: impl Fn(&Entry) -> bool) {
        let taken = std::mem::take(&mut self.taken);
        self.watches.settle(&taken, is_live);
        self.taken = taken;
    }

    /// Subscribes compiled guard `node` (of generation `epoch`); returns the node's
    /// subscription head, or None (nothing subscribed) for a variable out of range.
    pub fn watch(
        &mut self,
        shape: Shape,
        node: u32,
        epoch: u32,
        is_live: impl Fn(&Entry) -> bool,
    ) -> Option<u32> {
        let entry = Entry {
            seq: self.seq,
            node,
            epoch,
        };
        // A watched variable's wake is queued through its head.
        self.head(shape.var)?;
        let list = self.watches.add(shape, entry, is_live)?;
        self.seq += 1;
        Some(WATCH | list)
    }

    /// Writes one field; returns whether it changed.
    pub fn set(&mut self, v: u32, f: Field, value: f64) -> bool {
        if self.field(v, f).to_bits() == value.to_bits() {
            return false;
        }
        let slot = match place_of(f) {
            None => self.cores.get_mut(v as usize).map(|c| match f {
                Field::Status => &mut c.status,
                _ => &mut c.value,
            }),
            Some(i) => self.place_mut(v).map(|p| &mut p[i]),
        };
        match slot {
            Some(slot) => {
                *slot = value;
                true
            }
            None => false,
        }
    }

    /// `v = value` of an assignment: value and status 1, no `how`; returns the
    /// fields to trace (the value always, the status if it changed).
    #[inline]
    pub fn assign(&mut self, v: u32, value: f64) -> FieldMask {
        let Some(r) = self.cores.get_mut(v as usize) else {
            return FieldMask(FieldMask::bit(Field::Value));
        };
        let mut mask = FieldMask::bit(Field::Value);
        if r.status.to_bits() != 1.0f64.to_bits() {
            r.status = 1.0;
            mask |= FieldMask::bit(Field::Status);
        }
        r.value = value;
        if let Some(h) = self.hows.get_mut(v as usize) {
            *h = None;
        }
        FieldMask(mask)
    }

    /// Every variable's status and value, for a loop over many frames that reads
    /// and writes them in place, and the first variable from which on nothing is
    /// heard and no command's end is kept (past the subscription lists and the
    /// ends): at or above it [`Vars::quiet`] holds, and an assignment of a status
    /// already 1 writes the value alone ([`Vars::plain`]).
    #[inline]
    pub fn dense(&mut self) -> (&mut [Core], u32) {
        let floor = self.heads.len().max(self.hows.len());
        (&mut self.cores, u32::try_from(floor).unwrap_or(u32::MAX))
    }

    /// An assignment of `v` would write its value and nothing else: `v` exists, its
    /// status is already 1 and no command's end is kept for it. A round that may
    /// have to take its writes back ([`Vars::swap_value`]) writes only such.
    #[inline]
    pub fn plain(&self, v: u32) -> bool {
        self.cores
            .get(v as usize)
            .is_some_and(|c| c.status.to_bits() == 1.0f64.to_bits())
            && self.hows.get(v as usize).is_none_or(|h| h.is_none())
    }

    /// Writes `value` into `v`'s value and returns the old one: for a
    /// [`Vars::plain`] variable what [`Vars::assign`] does, and, with the old value
    /// written back, also what undoes it.
    #[inline]
    pub fn swap_value(&mut self, v: u32, value: f64) -> f64 {
        debug_assert!(
            self.cores
                .get(v as usize)
                .is_some_and(|c| c.status.to_bits() == 1.0f64.to_bits())
        );
        match self.cores.get_mut(v as usize) {
            Some(c) => std::mem::replace(&mut c.value, value),
            None => 0.0,
        }
    }

    pub fn set_how(&mut self, v: u32, how: Option<How>) {
        let i = v as usize;
        if i >= self.cores.len() {
            return;
        }
        if i >= self.hows.len() {
            if how.is_none() {
                return;
            }
            self.hows.resize(i + 1, None);
        }
        self.hows[i] = how;
    }

    pub fn clear(&mut self, v: u32) -> FieldMask {
        let mut mask = FieldMask::default();
        if (v as usize) < self.cores.len() {
            for f in FIELDS {
                if self.field(v, f) != 0.0 {
                    mask.0 |= FieldMask::bit(f);
                }
            }
            self.cores[v as usize] = Core::default();
            // The place stays the variable's: a variable that held a pose once is
            // likely to again.
            if let Some(i) = self.place.get(v as usize).copied()
                && let Some(p) = self.places.get_mut(i as usize)
            {
                *p = Place::default();
            }
            self.set_how(v, None);
        }
        mask
    }

    /// Subscribes `node` to changes of `var`; `node_head` is the node's list head,
    /// `cond` the guard's condition (NONE for a wait).
    pub fn subscribe(&mut self, node: u32, cond: u32, var: u32, node_head: &mut u32) {
        let Some(tail) = self.head(var).map(|h| h.last) else {
            return;
        };
        if self.free_subs == NONE && self.subs.len() >= WATCH as usize {
            return;
        }
        let sub = Sub {
            seq: self.seq,
            node,
            cond,
            var,
            prev: tail,
            next: NONE,
            next_of_node: *node_head,
        };
        let id = if self.free_subs != NONE {
            let id = self.free_subs;
            self.free_subs = self.subs[id as usize].next;
            self.subs[id as usize] = sub;
            id
        } else {
            self.subs.push(sub);
            (self.subs.len() - 1) as u32
        };
        if tail != NONE {
            self.subs[tail as usize].next = id;
        } else {
            self.heads[var as usize].first = id;
        }
        self.heads[var as usize].last = id;
        *node_head = id;
        self.seq += 1;
    }

    /// Drops every subscription of a node.
    pub fn unsubscribe_all(&mut self, node_head: &mut u32) {
        if *node_head != NONE && *node_head & WATCH != 0 {
            self.watches.drop_one(*node_head & !WATCH);
            *node_head = NONE;
            return;
        }
        let mut id = *node_head;
        while id != NONE {
            let s = self.subs[id as usize];
            if s.prev != NONE {
                self.subs[s.prev as usize].next = s.next;
            } else {
                self.heads[s.var as usize].first = s.next;
            }
            if s.next != NONE {
                self.subs[s.next as usize].prev = s.prev;
            } else {
                self.heads[s.var as usize].last = s.prev;
            }
            self.subs[id as usize].next = self.free_subs;
            self.free_subs = id;
            id = s.next_of_node;
        }
        *node_head = NONE;
    }

    /// Calls `f` for every node subscribed to `var`, in subscription order.
    pub fn for_each_subscriber(&self, var: u32, mut f: impl FnMut(u32)) {
        let mut id = self.heads.get(var as usize).map_or(NONE, |h| h.first);
        while id != NONE {
            let s = &self.subs[id as usize];
            f(s.node);
            id = s.next;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_assignment_writes_and_reports_as_a_write_of_value_and_status() {
        let values = [0.0, 1.0, -0.0, f64::NAN, 1e300, 1.0];
        let starts = [
            VarRecord::default(),
            VarRecord {
                status: 1.0,
                value: 1.0,
                how: Some(How::Broken),
                ..VarRecord::default()
            },
        ];
        for start in starts {
            for v in values {
                let (mut a, mut b) = (Vars::new(1), Vars::new(1));
                a.put(0, &start);
                b.put(0, &start);
                let mut mask = FieldMask::bit(Field::Value);
                for (f, x) in [(Field::Value, v), (Field::Status, 1.0)] {
                    if b.set(0, f, x) {
                        mask |= FieldMask::bit(f);
                    }
                }
                b.set_how(0, None);
                assert_eq!(a.assign(0, v), FieldMask(mask));
                assert_eq!(format!("{:?}", a.get(0)), format!("{:?}", b.get(0)));
            }
        }
    }

    #[test]
    fn how_is_kept_only_up_to_the_last_variable_a_command_ended_into() {
        let mut vars = Vars::new(1000);
        let bare = vars.footprint();
        vars.assign(999, 3.0);
        vars.set_how(999, None);
        assert_eq!(vars.footprint(), bare, "assignments keep no how");
        vars.set_how(2, Some(How::Completed));
        assert_eq!(vars.get(2).how, Some(How::Completed));
        assert!(vars.footprint() < bare + 16);
        vars.assign(2, 1.0);
        assert_eq!(vars.get(2).how, None);
        vars.set_how(2, Some(How::Broken));
        vars.clear(2);
        assert_eq!(vars.get(2), VarRecord::default());
    }

    /// The dense cores and the places on demand read and write as six fields a
    /// variable did: random writes, assignments and clears against whole records.
    #[test]
    fn fields_kept_apart_read_as_whole_records() {
        let n = 12;
        let mut vars = Vars::new(n);
        let mut model = vec![VarRecord::default(); n];
        let values = [0.0, -0.0, 1.0, 2.5, f64::NAN, -7.0];
        let mut rng = ilmr_geometry::SplitMix64::new(0x2545_f491_4f6c_dd1d);
        let mut next = move || rng.next_u64();
        for _ in 0..5_000 {
            let v = (next() % (n as u64 + 2)) as u32;
            let f = FIELDS[(next() % 6) as usize];
            let x = values[(next() % values.len() as u64) as usize];
            let m = model.get_mut(v as usize);
            match next() % 8 {
                0 => {
                    let want = m.map_or(FieldMask::default(), |r| {
                        let mut mask = FieldMask::default();
                        for f in FIELDS {
                            if r.get(f) != 0.0 {
                                mask.0 |= FieldMask::bit(f);
                            }
                        }
                        *r = VarRecord::default();
                        mask
                    });
                    assert_eq!(vars.clear(v), want);
                }
                1 => {
                    if let Some(r) = m {
                        r.status = 1.0;
                        r.value = x;
                        r.how = None;
                    }
                    vars.assign(v, x);
                }
                2 => {
                    if let Some(r) = m {
                        r.how = Some(How::Completed);
                    }
                    vars.set_how(v, Some(How::Completed));
                }
                _ => {
                    let changed = m.is_some_and(|r| {
                        let slot = match f {
                            Field::Status => &mut r.status,
                            Field::X => &mut r.x,
                            Field::Y => &mut r.y,
                            Field::H => &mut r.h,
                            Field::Value => &mut r.value,
                            Field::Dist => &mut r.dist,
                        };
                        let changed = slot.to_bits() != x.to_bits();
                        *slot = x;
                        changed
                    });
                    assert_eq!(vars.set(v, f, x), changed, "{v} {f:?} {x}");
                }
            }
            for (i, r) in model.iter().enumerate() {
                assert_eq!(format!("{r:?}"), format!("{:?}", vars.get(i as u32)));
                for f in FIELDS {
                    assert_eq!(vars.field(i as u32, f).to_bits(), r.get(f).to_bits());
                }
            }
        }
    }

    #[test]
    fn a_variable_of_arithmetic_costs_its_value_and_status_alone() {
        let mut vars = Vars::new(1000);
        let bare = vars.footprint();
        assert!(bare <= 1000 * 16 + 256, "{bare}");
        for v in 0..1000 {
            vars.assign(v, f64::from(v));
        }
        assert_eq!(vars.footprint(), bare);
        vars.set(7, Field::X, 0.0);
        assert_eq!(
            vars.footprint(),
            bare,
            "a write that changes nothing keeps no place"
        );
        vars.set(7, Field::X, 1.5);
        assert!(vars.footprint() > bare);
        assert_eq!(vars.get(7).x, 1.5);
        assert_eq!(vars.get(8).x, 0.0);
    }

    #[test]
    fn subscriptions_wake_in_order_and_drop_per_node() {
        let mut vars = Vars::new(2);
        let (mut a, mut b) = (NONE, NONE);
        vars.subscribe(10, NONE, 0, &mut a);
        vars.subscribe(11, NONE, 0, &mut b);
        vars.subscribe(10, NONE, 1, &mut a);
        let mut seen = Vec::new();
        vars.for_each_subscriber(0, |n| seen.push(n));
        assert_eq!(seen, vec![10, 11]);
        vars.unsubscribe_all(&mut a);
        seen.clear();
        vars.for_each_subscriber(0, |n| seen.push(n));
        vars.for_each_subscriber(1, |n| seen.push(n));
        assert_eq!(seen, vec![11]);
        // Freed records are reused.
        vars.subscribe(12, NONE, 1, &mut a);
        assert!(vars.subs.len() <= 3);
    }
}

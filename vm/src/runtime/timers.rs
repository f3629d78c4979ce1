//! The `wait(seconds)` wake-ups: a timing wheel of one slot per tick for the next
//! [`SLOTS`] ticks, and a heap for the rare wait beyond them. Adding and firing a timer
//! cost the same whatever the number of sleepers (a binary heap took `log n` and was
//! the tick loop's largest cost with 100,000 blocks each waiting a tick).
//!
//! Timers fire in the order of their due tick, then in the order they were set: a
//! slot holds one due tick and is appended to in order; a timer that went to the heap
//! was set before any timer for its tick went straight to the slot, and it is moved to
//! the slot before any could (the heap is drained up to the wheel's horizon at each
//! tick, and a timer goes straight to a slot only below the horizon).

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use super::nodes::NodeRef;

/// A `wait(seconds)` wake-up: the block that sleeps and which of its sleeps this is.
/// A sleep ended early (`break`) leaves its entry behind; the count tells it from a
/// later sleep of the same block.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) struct Alarm {
    pub node: NodeRef,
    pub nap: u32,
}

/// Ticks the wheel holds: ten seconds at 100 Hz.
pub const SLOTS: u64 = 1024;

#[derive(Debug)]
pub(crate) struct Timers {
    /// Slot `due % SLOTS` holds the timers due at `due`, for `due` below `horizon`.
    wheel: Vec<Vec<Alarm>>,
    /// Timers due at or past `horizon`, by (due, sequence).
    far: BinaryHeap<Reverse<(u64, u64, Alarm)>>,
    /// Emptied slot buffers, for the next slot that fills: the room of a tick's timers
    /// moves on with them rather than staying behind in a slot a thousand ticks away.
    spare: Vec<Vec<Alarm>>,
    seq: u64,
    horizon: u64,
}

impl Default for Timers {
    fn default() -> Timers {
        Timers {
            wheel: (0..SLOTS).map(|_| Vec::new()).collect(),
            far: BinaryHeap::new(),
            spare: Vec::new(),
            seq: 0,
            horizon: SLOTS,
        }
    }
}

impl Timers {
    /// Sets a timer for tick `due`, which must be later than the current tick.
    #[inline]
    pub(crate) fn set(&mut self, due: u64, node: Alarm) {
        if due < self.horizon {
            self.slot(due).push(node);
        } else {
            self.seq += 1;
            self.far.push(Reverse((due, self.seq, node)));
        }
    }

    /// The timers due at `tick`, in the order they were set, for `fire` to walk and
    /// hand back with [`Timers::done`]. Called once a tick, for every tick in turn.
    pub(crate) fn due(&mut self, tick: u64) -> Vec<Alarm> {
        let horizon = tick.saturating_add(SLOTS);
        while let Some(&Reverse((due, _, node))) = self.far.peek() {
            if due >= horizon {
                break;
            }
            self.far.pop();
            self.slot(due).push(node);
        }
        self.horizon = self.horizon.max(horizon);
        std::mem::take(&mut self.wheel[(tick % SLOTS) as usize])
    }

    /// Gives back the buffer [`Timers::due`] lent, emptied, so that its room is reused.
    pub(crate) fn done(&mut self, mut fired: Vec<Alarm>) {
        if fired.capacity() > 0 {
            fired.clear();
            self.spare.push(fired);
        }
    }

    /// Whether a timer for `due` would go to an empty slot: a round that sets its
    /// alarms for `due` in order may then write them into a buffer of its own and
    /// hand it over with [`Timers::adopt`], which is what setting them one by one
    /// leaves.
    #[inline]
    pub(crate) fn empty_slot(&self, due: u64) -> bool {
        due < self.horizon && self.wheel[(due % SLOTS) as usize].is_empty()
    }

    /// Makes `alarms` the timers due at `due`, whose slot [`Timers::empty_slot`]
    /// found empty and which nothing has set since; the slot's own buffer, empty,
    /// goes to the spares.
    pub(crate) fn adopt(&mut self, due: u64, alarms: Vec<Alarm>) {
        debug_assert!(self.empty_slot(due));
        let old = std::mem::replace(&mut self.wheel[(due % SLOTS) as usize], alarms);
        self.done(old);
    }

    fn slot(&mut self, due: u64) -> &mut Vec<Alarm> {
        let slot = &mut self.wheel[(due % SLOTS) as usize];
        if slot.capacity() == 0
            && let Some(spare) = self.spare.pop()
        {
            *slot = spare;
        }
        slot
    }

    /// Bytes held.
    pub(crate) fn footprint(&self) -> usize {
        use std::mem::size_of;
        self.wheel.capacity() * size_of::<Vec<Alarm>>()
            + self
                .wheel
                .iter()
                .map(|s| s.capacity() * size_of::<Alarm>())
                .sum::<usize>()
            + self
                .spare
                .iter()
                .map(|s| s.capacity() * size_of::<Alarm>())
                .sum::<usize>()
            + self.far.capacity() * size_of::<Reverse<(u64, u64, Alarm)>>()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn node(idx: u32) -> Alarm {
        Alarm {
            node: NodeRef { idx, epoch: 0 },
            nap: 0,
        }
    }

    /// Fires every tick up to `last`, as the VM calls it.
    fn run(t: &mut Timers, from: u64, last: u64) -> Vec<(u64, u32)> {
        let mut out = Vec::new();
        for tick in from..=last {
            let fired = t.due(tick);
            out.extend(fired.iter().map(|n| (tick, n.node.idx)));
            t.done(fired);
        }
        out
    }

    #[test]
    fn timers_fire_by_due_tick_then_in_the_order_they_were_set() {
        let mut t = Timers::default();
        // Set at tick 0: near ones to the wheel, far ones to the heap.
        t.set(5, node(1));
        t.set(SLOTS + 10, node(2));
        t.set(3, node(3));
        t.set(SLOTS + 10, node(4));
        t.set(5, node(5));
        assert_eq!(run(&mut t, 0, 20), [(3, 3), (5, 1), (5, 5)]);
        // At tick 20 the horizon passed SLOTS + 10: the heap's two are in their slot,
        // before one set now for the same tick.
        t.set(SLOTS + 10, node(6));
        assert_eq!(
            run(&mut t, 21, SLOTS + 10),
            [(SLOTS + 10, 2), (SLOTS + 10, 4), (SLOTS + 10, 6)]
        );
    }

    #[test]
    fn a_wait_for_ever_stays_in_the_heap() {
        let mut t = Timers::default();
        t.set(u64::MAX, node(1));
        assert!(run(&mut t, 0, 3 * SLOTS).is_empty());
        assert_eq!(t.far.len(), 1);
    }

    #[test]
    fn the_order_matches_a_heap_of_due_and_sequence() {
        // Pseudo-random waits set over 3,000 ticks, against the heap the VM used.
        let mut t = Timers::default();
        let mut reference = BinaryHeap::new();
        let (mut seq, mut x) = (0u64, 12345u64);
        let mut got = Vec::new();
        let mut want = Vec::new();
        for tick in 0..3000u64 {
            let fired = t.due(tick);
            got.extend(fired.iter().map(|n| n.node.idx));
            t.done(fired);
            while let Some(&Reverse((due, _, idx))) = reference.peek() {
                if due > tick {
                    break;
                }
                reference.pop();
                want.push(idx);
            }
            let mut next = || {
                x = x
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                x >> 33
            };
            for _ in 0..next() % 4 {
                let x = next();
                let wait = 1 + x % (if x % 7 == 0 { 3 * SLOTS } else { 40 });
                seq += 1;
                t.set(tick + wait, node(seq as u32));
                reference.push(Reverse((tick + wait, seq, seq as u32)));
            }
        }
        assert!(got.len() > 1000, "{} fired", got.len());
        assert_eq!(got, want);
    }
}

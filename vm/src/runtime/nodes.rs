//! The live-command tree in one arena. Every live thing (a block issuing statements,
//! an `if`, a `while`, a skill call, a wait, a command) is a [`Node`] of at most 128
//! bytes; children hang off their parent in an intrusive list so that ending a node
//! can end its whole subtree without allocating.

use ilmr_hal::Side;
use ilmr_stdlib::{Command, Field};

use super::frame::FrameState;
use super::vars::NONE;

/// A block's `holder` while its own `wait(seconds)` holds it. A wait of time is not a
/// node of its own: it has nothing to step and no children, so the block sleeps in
/// place and the timer names the block (a node per wait was an allocation, a link and
/// an unlink per step of every sleeping loop).
pub(crate) const SLEEPING: u32 = NONE - 1;

/// A block's `holder` when it is a loop's body that has ended, kept in place under
/// its `while` for the next iteration ([`Nodes::park`]): not live.
pub(crate) const PARKED: u32 = NONE - 2;

#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct BlockState {
    pub block: u32,
    pub pc: u32,
    /// The child that holds this block (`wait(v)`, init, a skill call), [`SLEEPING`]
    /// for its own `wait(seconds)` (the instruction before `pc`), [`PARKED`], or NONE.
    pub holder: u32,
    /// How many times the block has slept: names the current sleep to its timer.
    pub nap: u32,
    /// Every instruction has been issued; the block ends when its children have.
    pub issued: bool,
    /// Skill call depth.
    pub depth: u16,
    /// The first block of a skill call: it continues its caller's strand, so when it
    /// has issued its last statement the calling block goes on at once, in line.
    pub inline: bool,
}

/// A movement's evaluated arguments. Stored as f32 (sub-millimetre over kilometres)
/// so that a node stays within 64 bytes; planning works in f64.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum MoveSpec {
    /// NaN: no distance, go on until broken.
    Goahead {
        d: f32,
    },
    TurnExact {
        deg: f32,
        c: f32,
    },
    TurnSide {
        left: bool,
    },
    /// `h` NaN: no heading given. `r`: may reverse and turn first.
    To {
        x: f32,
        y: f32,
        h: f32,
        rel: bool,
        r: bool,
    },
    ToVar {
        var: u32,
        rel: bool,
        r: bool,
    },
    FollowPath {
        name: u32,
        reverse: bool,
        backwards: bool,
    },
    /// `d` NaN: the robot model's `followwall_d`.
    FollowWall {
        mode: WallMode,
        d: f32,
    },
    FollowTarget {
        object: u32,
        d: f32,
    },
    ApproachVar {
        var: u32,
        d: f32,
    },
    ApproachObject {
        object: u32,
        d: f32,
    },
}

/// Which wall `followwall` follows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum WallMode {
    Side(Side),
    Middle,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Which {
    /// The whole device: a plain value, or the nearest scanner range.
    All,
    Side(Side),
    Index(u32),
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum SensorSpec {
    Reading {
        device: u32,
        which: Which,
    },
    Search {
        sensor: u32,
        object: u32,
        side: Option<Side>,
    },
    Locate {
        field: Field,
    },
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Kind {
    Free,
    Root,
    Block(BlockState),
    /// A block that only computes and sleeps, run as a compact frame
    /// (`super::frame`): it stands for the block, its loops and their bodies.
    Frame(FrameState),
    If {
        cond: u32,
        body: u32,
        fired: bool,
    },
    While {
        cond: u32,
        body: u32,
        iteration: u32,
    },
    Call {
        unit: u32,
        depth: u16,
    },
    WaitVar {
        var: u32,
    },
    Movement {
        command: Command,
        spec: MoveSpec,
    },
    Sensor {
        spec: SensorSpec,
        forever: bool,
        since: u32,
    },
    Async {
        op: u32,
        /// The tick it started, for `operation_timeout`.
        since: u32,
    },
    SpeedAfter {
        value: f32,
        node: u32,
        epoch: u32,
    },
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Node {
    pub epoch: u32,
    pub parent: u32,
    pub first_child: u32,
    pub next: u32,
    pub prev: u32,
    pub children: u32,
    pub stmt: u32,
    pub bind: u32,
    pub subs: u32,
    pub queued: bool,
    /// Part of a subtree being ended: must not start.
    pub dying: bool,
    pub kind: Kind,
}

impl Node {
    fn fresh(epoch: u32) -> Node {
        Node {
            epoch,
            parent: NONE,
            first_child: NONE,
            next: NONE,
            prev: NONE,
            children: 0,
            stmt: NONE,
            bind: NONE,
            subs: NONE,
            queued: false,
            dying: false,
            kind: Kind::Free,
        }
    }
}

/// A node index with the generation it had, so stale references are detected.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) struct NodeRef {
    pub idx: u32,
    pub epoch: u32,
}

/// What a live node is doing, for [`crate::runtime::Activity`]: a pure function of
/// its kind, counted as nodes are allocated, change state and are freed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Class {
    /// The root, a fired `if`, a `while`, a skill call, a block that has issued
    /// everything: alive only through what they contain.
    Container,
    /// A block with statements left to issue (running, queued or held).
    Issuing,
    /// An `if` that has not fired.
    Guard,
    /// `wait(v)`, and blocks asleep in `wait(seconds)`.
    Sleep,
    Movement,
    /// Readings, searches, asynchronous operations, `speed(v,w)`.
    Active,
    /// Readings and searches with `forever`: they never end by themselves, so a task
    /// left with only these (and guards) can only wait.
    Endless,
}

impl Class {
    pub const COUNT: usize = 7;

    pub fn of(kind: &Kind) -> Option<Class> {
        Some(match kind {
            Kind::Free => return None,
            Kind::Block(b) if !b.issued => Class::Issuing,
            Kind::If { fired: false, .. } => Class::Guard,
            Kind::Root
            | Kind::Block(_)
            | Kind::Frame(_)
            | Kind::If { .. }
            | Kind::While { .. }
            | Kind::Call { .. } => Class::Container,
            Kind::WaitVar { .. } => Class::Sleep,
            Kind::Movement { .. } => Class::Movement,
            Kind::Sensor { forever: true, .. } => Class::Endless,
            Kind::Sensor { .. } | Kind::Async { .. } | Kind::SpeedAfter { .. } => Class::Active,
        })
    }
}

/// A loop body kept for the next iteration: not live.
fn is_parked(kind: &Kind) -> bool {
    match kind {
        Kind::Block(b) => b.holder == PARKED,
        Kind::Frame(f) => f.parked,
        _ => false,
    }
}

#[derive(Debug, Default)]
pub(crate) struct Nodes {
    pub all: Vec<Node>,
    free: Vec<u32>,
    pub live: usize,
    /// Live nodes per [`Class`], and sleeping blocks under [`Class::Sleep`].
    pub classes: [usize; Class::COUNT],
    /// Blocks asleep in a `wait(seconds)`: each stands for the wait node it replaces
    /// in [`Nodes::live`]'s count of commands.
    pub sleepers: usize,
}

impl Nodes {
    pub fn alloc(&mut self, parent: u32, stmt: u32, bind: u32, kind: Kind) -> NodeRef {
        let idx = match self.free.pop() {
            Some(i) => i,
            None => {
                self.all.push(Node::fresh(0));
                (self.all.len() - 1) as u32
            }
        };
        let epoch = self.all[idx as usize].epoch;
        let mut n = Node::fresh(epoch);
        n.parent = parent;
        n.stmt = stmt;
        n.bind = bind;
        n.kind = kind;
        self.all[idx as usize] = n;
        self.count(&kind, 1);
        if parent != NONE {
            self.link(parent, idx);
        }
        self.live += 1;
        NodeRef { idx, epoch }
    }

    /// Appends `child` to the end of `parent`'s children so that ending order follows
    /// issue order.
    fn link(&mut self, parent: u32, child: u32) {
        // Children are kept as a ring-free list with the newest first; `prev` of the
        // first child points at the last so that appending stays O(1).
        let first = self.all[parent as usize].first_child;
        if first == NONE {
            self.all[parent as usize].first_child = child;
            self.all[child as usize].prev = child;
        } else {
            let last = self.all[first as usize].prev;
            self.all[last as usize].next = child;
            self.all[child as usize].prev = last;
            self.all[first as usize].prev = child;
        }
        self.all[child as usize].next = NONE;
        self.all[parent as usize].children += 1;
    }

    pub fn unlink(&mut self, child: u32) {
        let parent = self.all[child as usize].parent;
        if parent == NONE {
            return;
        }
        let first = self.all[parent as usize].first_child;
        let (prev, next) = (self.all[child as usize].prev, self.all[child as usize].next);
        if first == child {
            self.all[parent as usize].first_child = next;
            if next != NONE {
                self.all[next as usize].prev = prev;
            }
        } else {
            self.all[prev as usize].next = next;
            if next != NONE {
                self.all[next as usize].prev = prev;
            } else {
                self.all[first as usize].prev = prev;
            }
        }
        self.all[child as usize].parent = NONE;
        self.all[parent as usize].children = self.all[parent as usize].children.saturating_sub(1);
    }

    fn count(&mut self, kind: &Kind, up: isize) {
        if let Some(c) = Class::of(kind) {
            let n = &mut self.classes[c as usize];
            *n = n.saturating_add_signed(up);
        }
    }

    /// Changes a node's kind in place (a guard fires, a block has issued everything),
    /// keeping the class counts.
    pub fn update_kind(&mut self, idx: u32, f: impl FnOnce(&mut Kind)) {
        let before = self.all[idx as usize].kind;
        f(&mut self.all[idx as usize].kind);
        let after = self.all[idx as usize].kind;
        if Class::of(&before) != Class::of(&after) {
            self.count(&before, -1);
            self.count(&after, 1);
        }
    }

    pub fn free(&mut self, idx: u32) {
        let kind = self.all[idx as usize].kind;
        self.count(&kind, -1);
        let n = &mut self.all[idx as usize];
        n.epoch = n.epoch.wrapping_add(1);
        n.kind = Kind::Free;
        self.free.push(idx);
        if !is_parked(&kind) {
            self.live = self.live.saturating_sub(1);
        }
    }

    /// A loop's body block has ended: rather than being freed and a new one allocated
    /// and linked for the next iteration, it stays linked under its `while`, no longer
    /// live, under a new generation (so that no old reference to it, a queue entry, a
    /// timer or the priority block, takes it for alive), until [`Nodes::unpark`].
    pub fn park(&mut self, idx: u32) {
        let n = &mut self.all[idx as usize];
        // A block ends only when it has issued everything: it is a container already.
        match &mut n.kind {
            Kind::Block(b) => {
                debug_assert!(b.issued);
                b.holder = PARKED;
            }
            Kind::Frame(f) => f.parked = true,
            _ => return,
        }
        n.epoch = n.epoch.wrapping_add(1);
        n.queued = false;
        self.live = self.live.saturating_sub(1);
    }

    /// Block `idx` has issued everything (or, `false`, starts issuing again): moves
    /// it between [`Class::Issuing`] and [`Class::Container`].
    pub fn set_issued(&mut self, idx: u32, issued: bool) {
        if let Kind::Block(b) = &mut self.all[idx as usize].kind
            && b.issued != issued
        {
            b.issued = issued;
            let (from, to) = if issued {
                (Class::Issuing, Class::Container)
            } else {
                (Class::Container, Class::Issuing)
            };
            self.classes[from as usize] = self.classes[from as usize].saturating_sub(1);
            self.classes[to as usize] += 1;
        }
    }

    /// Block `idx` is a parked loop body.
    pub fn parked(&self, idx: u32) -> bool {
        idx != NONE && is_parked(&self.all[idx as usize].kind)
    }

    /// Starts a parked loop body again from its first statement (a frame's caller
    /// sets its pc).
    pub fn unpark(&mut self, idx: u32) -> NodeRef {
        match &mut self.all[idx as usize].kind {
            Kind::Block(b) => {
                b.holder = NONE;
                b.pc = 0;
            }
            Kind::Frame(f) => f.parked = false,
            _ => {}
        }
        self.set_issued(idx, false);
        self.live += 1;
        self.at(idx)
    }

    /// Block `idx` sleeps in its own `wait(seconds)`; returns the sleep's number.
    pub fn sleep(&mut self, idx: u32) -> u32 {
        let mut nap = 0;
        if let Kind::Block(b) = &mut self.all[idx as usize].kind {
            b.holder = SLEEPING;
            b.nap = b.nap.wrapping_add(1);
            nap = b.nap;
        }
        self.classes[Class::Sleep as usize] += 1;
        self.sleepers += 1;
        nap
    }

    /// Block `idx` wakes from its `wait(seconds)` (the wait ended); it is held no
    /// longer.
    pub fn wake(&mut self, idx: u32) {
        let was = match &mut self.all[idx as usize].kind {
            Kind::Block(b) if b.holder == SLEEPING => {
                b.holder = NONE;
                true
            }
            Kind::Frame(f) if f.asleep => {
                f.asleep = false;
                true
            }
            _ => false,
        };
        if was {
            let n = &mut self.classes[Class::Sleep as usize];
            *n = n.saturating_sub(1);
            self.sleepers = self.sleepers.saturating_sub(1);
        }
    }

    /// The block is asleep in the sleep numbered `nap`.
    pub fn asleep(&self, r: NodeRef, nap: u32) -> bool {
        self.alive(r)
            && match self.all[r.idx as usize].kind {
                Kind::Block(b) => b.holder == SLEEPING && b.nap == nap,
                Kind::Frame(f) => f.asleep && f.nap == nap,
                _ => false,
            }
    }

    pub fn footprint(&self) -> usize {
        self.all.capacity() * std::mem::size_of::<Node>()
            + self.free.capacity() * std::mem::size_of::<u32>()
    }

    pub fn alive(&self, r: NodeRef) -> bool {
        self.all
            .get(r.idx as usize)
            .is_some_and(|n| n.epoch == r.epoch && !matches!(n.kind, Kind::Free))
    }

    pub fn get(&self, idx: u32) -> &Node {
        &self.all[idx as usize]
    }

    pub fn get_mut(&mut self, idx: u32) -> &mut Node {
        &mut self.all[idx as usize]
    }

    pub fn at(&self, idx: u32) -> NodeRef {
        NodeRef {
            idx,
            epoch: self.all[idx as usize].epoch,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_node_fits_in_64_bytes() {
        assert!(
            std::mem::size_of::<Node>() <= 64,
            "{}",
            std::mem::size_of::<Node>()
        );
    }

    #[test]
    fn children_keep_issue_order_through_unlinks() {
        let mut n = Nodes::default();
        let root = n.alloc(NONE, NONE, NONE, Kind::Root).idx;
        let kids: Vec<u32> = (0..4)
            .map(|_| n.alloc(root, NONE, NONE, Kind::WaitVar { var: 0 }).idx)
            .collect();
        n.unlink(kids[1]);
        n.unlink(kids[3]);
        let mut order = Vec::new();
        let mut c = n.get(root).first_child;
        while c != NONE {
            order.push(c);
            c = n.get(c).next;
        }
        assert_eq!(order, vec![kids[0], kids[2]]);
        assert_eq!(n.get(root).children, 2);
        let k = n.alloc(root, NONE, NONE, Kind::WaitVar { var: 0 }).idx;
        n.unlink(kids[0]);
        let first = n.get(root).first_child;
        assert_eq!(first, kids[2]);
        assert_eq!(n.get(first).next, k);
    }
}

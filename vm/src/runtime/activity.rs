//! What is still live, for a runner deciding whether a run has ended (the guide: "a
//! run ends when nothing is left but `if` guards that are waiting and the robot is at
//! rest"). Counted as nodes live, so a query costs nothing per live command.

/// Below this measured and commanded speed the robot is at rest, m/s.
pub const REST_SPEED: f64 = 1e-3;

/// A census of the live commands after a tick. Every live node is in exactly one of
/// the first five counts or is a container (a fired `if`, a `while`, a skill call, a
/// block that has issued everything), which lives only through what it holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Activity {
    /// Commands acting every tick: the movement holding the reservation, readings,
    /// searches, asynchronous operations (`init`, `manipulate`, `movemode`) and
    /// `speed(v,w)` waiting for its movement.
    pub running_commands: usize,
    /// Of `running_commands`, the readings and searches with `forever`.
    pub endless_readings: usize,
    /// Movement commands waiting for the reservation.
    pub queued_movements: usize,
    /// `if` guards that have not fired: they cost nothing until a variable they read
    /// changes.
    pub waiting_guards: usize,
    /// `wait(seconds)` and `wait(v)`.
    pub sleeping: usize,
    /// Blocks with statements left to issue: queued, suspended by the budget, or held
    /// by a wait, `init` or a skill call.
    pub issuing_blocks: usize,
    /// Entries of the ready queue (non-zero only after a budget overrun) and
    /// interactive blocks not yet started (they wait for a priority block to end).
    pub ready: usize,
    /// The robot reports no speed and the VM commands none (below [`REST_SPEED`]).
    pub robot_at_rest: bool,
}

impl Activity {
    /// Nothing is left but waiting `if` guards (possibly none) and the robot is at
    /// rest: nothing the task does can change any more except through a variable a
    /// guard reads, which only an interactive line could write.
    pub fn only_guards_waiting(&self) -> bool {
        self.running_commands == 0
            && self.queued_movements == 0
            && self.sleeping == 0
            && self.issuing_blocks == 0
            && self.ready == 0
            && self.robot_at_rest
    }

    /// As [`Activity::only_guards_waiting`], but endless readings (`forever`) may
    /// still run: they change variables only as the world changes, and nothing in
    /// the task moves the robot any more.
    pub fn only_waiting(&self) -> bool {
        Activity {
            running_commands: self.running_commands - self.endless_readings,
            ..*self
        }
        .only_guards_waiting()
    }
}

//! When each statement of a file is issued, relative to the others: the model of the
//! schedule that the actuator ownership check (W0905, `owners.rs`) reasons with, read
//! out statement by statement for the language server's concurrency lens. The walk is
//! `owners.rs`'s own, so the lens and the warning cannot disagree about what runs
//! together.

use ilmr_model::RobotModel;

use crate::check::Analysis;
use crate::diagnostic::FileId;
use crate::span::Span;

/// What lets a statement be issued.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Start {
    /// Issued when its unit starts (a task at t=0, a skill when called), in block
    /// `block` (from 1) of the unit's `blocks` top-level blocks, which all start then.
    Unit {
        skill: bool,
        block: u32,
        blocks: u32,
    },
    /// Held back until the statement `by` of its block let it go: a `wait`, an `init`
    /// or a call of a skill whose first block holds.
    HeldBy { by: Span },
    /// In block `block` of `blocks` of a guard's body: runs once, when the condition of
    /// the `if` at `guard` first holds.
    Guard {
        guard: Span,
        block: u32,
        blocks: u32,
    },
    /// In block `block` of `blocks` of a loop's body: runs every iteration the
    /// condition of the `while` at `guard` holds.
    Loop {
        guard: Span,
        block: u32,
        blocks: u32,
    },
}

/// One statement's place in the schedule.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Moment {
    /// The statement's own line (`Stmt::span`).
    pub span: Span,
    pub start: Start,
    /// The first statement of its block issued at this moment (the others of the
    /// moment follow it in the same tick).
    pub first: bool,
    /// A movement command that waits for the movement reservation behind this
    /// earlier movement of its block, which no `wait` on it separates from it.
    pub queued_after: Option<Span>,
}

/// The moments of every statement of `file` that runs (not those inside
/// `check`...`checkend`), sorted by position. Linear in the file's statements.
pub fn schedule(analysis: &Analysis<'_>, model: &RobotModel, file: FileId) -> Vec<Moment> {
    let mut moments = super::owners::moments(
        &analysis.files,
        &analysis.skills,
        &analysis.units,
        model,
        file,
    );
    moments.sort_by_key(|m| m.span.start);
    moments
}

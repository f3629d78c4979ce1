//! The ILMR bytecode and virtual machine.
//!
//! [`bytecode`] holds the instruction set, the module tables, the builder the
//! compiler's lowering calls and the disassembler. [`Vm`] runs a module against a
//! [`ilmr_hal::Hal`] at 100 Hz: top-level blocks start together, issued commands run
//! concurrently, movement commands share one reservation, and every tick has a budget.
//! [`runtime::safety`] holds issue 7's guarantees: computed commands that could harm
//! the robot are refused with stable codes, a supervisor checks the robot every tick,
//! and every halt brakes within the model's deceleration (`docs/reliability.md`).
//!
//! Invariants: the VM never panics on a validated module or on anything the robot
//! reports; runtime failures become trace events and variable states. Time is logical,
//! so the same module, robot and inputs give a byte-identical trace.

pub mod bytecode;
pub mod runtime;

pub use bytecode::{Module, ModuleBuilder};
pub use runtime::activity::Activity;
pub use runtime::clock::{Clock, Jitter, RealClock, SimClock};
pub use runtime::config::{Config, Controller, TURN_SHARE, TraceLevel};
pub use runtime::trace::{Event, EventKind, render_event, to_jsonl, write_jsonl};
pub use runtime::vars::{How, VarRecord};
pub use runtime::{LineError, Vm, VmError};

//! The ILMR front end: lexer, error-recovering parser, checker against the robot model,
//! and the lowering to bytecode.
//!
//! Invariants: parsing never fails (it returns a tree and diagnostics); every node and
//! diagnostic has a byte span; the checker reads command facts only from `ilmr-stdlib`
//! and robot facts only from `ilmr-model`.

pub mod ast;
pub mod check;
pub mod diagnostic;
pub mod format;
pub mod kept;
pub mod lexer;
pub mod limits;
pub mod lower;
pub mod parser;
pub mod render;
pub mod span;
pub mod tree;

pub use diagnostic::{Code, Diagnostic, FileId, Severity};
pub use span::{LineIndex, Span};

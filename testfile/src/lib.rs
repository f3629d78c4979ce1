//! Test files of ILMR tasks (`*.test.toml`, docs/testing.md), read and checked: the
//! TOML with every value's span, the assertion language's parser with did-you-mean,
//! and the stable codes `A01xx`-`A03xx`. `ilmrc test` runs what this reads, and the
//! language server shows the same problems and completes assertions from it, so the
//! editor and `ilmrc test` never disagree.
//!
//! A test file names the robot, world and scenario of `ilmrc run`; what those names
//! mean, short of a ROS 2 robot's settings, is here too (`place`, `scenario`), so that
//! both check them alike. Nothing here runs a task.
//!
//! Layers: below the CLI (`ilmrc`) and the language server (`ilmr-lsp`); it imports
//! the compiler (for did-you-mean), the simulator's worlds, the robot models and the
//! trace's types, never the VM's runtime or either tool.

pub mod assertion;
pub mod codes;
pub mod complete;
pub mod file;
pub mod place;
pub mod problem;
pub mod scenario;
pub mod snapshot;
pub mod sources;

/// The suffix that makes a file a test file.
pub const SUFFIX: &str = ".test.toml";

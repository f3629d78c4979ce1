//! `--scenario FILE.json`: what the scripted robot's world does during a run. The format
//! and its reader are in `ilmr_testfile::scenario`, where a test file's `scenario` is
//! checked too.

pub use ilmr_testfile::scenario::*;

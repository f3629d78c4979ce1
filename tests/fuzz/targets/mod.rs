//! One module per kind of input `ilmrc` reads, each with its seed corpus, its
//! mutator and the target that must not panic.

pub mod corpus;
pub mod fleets;
pub mod models;
pub mod modules;
pub mod requests;
pub mod scenarios;
pub mod skills;
pub mod tasks;
pub mod testfiles;
pub mod traces;
pub mod worlds;

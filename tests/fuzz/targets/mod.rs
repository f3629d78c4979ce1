//! One module per kind of input `ilmrc` reads, each with its seed corpus, its
//! mutator and the target that must not panic.

pub mod corpus;
pub mod models;
pub mod modules;
pub mod requests;
pub mod skills;
pub mod tasks;
pub mod traces;
pub mod worlds;

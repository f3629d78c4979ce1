//! The ILMR language server. An engine that works on the checked program and answers
//! each LSP feature (`engine.rs` and the feature modules), and a thin protocol layer
//! over stdio (`server.rs`, with `transport.rs`, `framing.rs` and `message.rs` in front
//! of tower-lsp-server to answer malformed messages).
//!
//! Invariants: the server checks with the compiler's own `check::analyze` and formats
//! with its `format::format`, so the editor and `ilmrc` never disagree; byte offsets
//! become LSP positions (UTF-16) only through `line_index`.

pub mod analysis;
pub mod completion;
pub mod context;
pub mod diagnostics;
pub mod docs;
pub mod engine;
pub mod framing;
pub mod hover;
pub mod in_view;
pub mod lens;
pub mod line_index;
pub mod message;
pub mod navigation;
pub mod outline;
pub mod robot;
pub mod run;
pub mod semantic;
pub mod server;
pub mod signature;
pub mod symbols;
pub mod testfiles;
pub mod transport;
pub mod units;
pub mod workspace;

pub use engine::{Engine, Publish, Settings};

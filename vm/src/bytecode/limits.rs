//! Facts of the bytecode format that every reader of a module shares: the VM sizes its
//! evaluation stack from them, the validator refuses a module past them, and a loader
//! or disassembler needs nothing else to check a module.

/// The most values an expression may hold on the evaluation stack at once;
/// `Module::validate` refuses a deeper one, so the VM's stack of this size never
/// overflows. An expression of n operators needs at most n + 1 values, and the
/// compiler accepts at most 256 operators on a line, so every expression it lowers
/// fits.
pub const EXPR_STACK: usize = 257;

/// The longest name of the toolchain an `.ilmb` file records (`ilmrc 0.1.0`), in bytes.
pub const MAX_COMPILER_NAME: usize = 64;

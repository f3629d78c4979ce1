//! How large a program may be where size becomes depth: every pass over the tree (the
//! parser, the checker, the lowering, the formatter, the language server) recurses once
//! per level, so the levels are bounded before any tree is built. A program past a limit
//! gets a diagnostic at the first place it is passed; the tree never holds more.
//!
//! The limits are far above what tasks use (the dissertation's tasks in `examples/` nest
//! at most 4 blocks deep and hold at most 2 operators and parentheses on a line). At the
//! limits, an unoptimised build needs up to 4 MB of native stack (chumsky's combinators
//! are deep there), an optimised one a fraction of that: threads that compile get
//! [`COMPILER_STACK`].

use crate::lexer::Token;
use crate::span::Span;

/// Blocks (`if`, `while`, `check`) open at once, inside one another.
pub const MAX_BLOCK_DEPTH: usize = 256;

/// Operators (`+ - * /`, unary minus, comparisons) and opening parentheses on one line.
/// An expression tree is no deeper than the operators it holds, so this also bounds
/// every expression's depth and the VM's evaluation stack
/// ([`ilmr_vm::bytecode::limits::EXPR_STACK`]).
pub const MAX_LINE_OPERATORS: usize = 256;

const _: () = assert!(MAX_LINE_OPERATORS < ilmr_vm::bytecode::limits::EXPR_STACK);

/// Diagnostics kept for one program (one analysis, one parsed file): the first ones in
/// source order. Past it they are counted, not kept (`crate::kept`), so a file of
/// millions of broken lines costs bounded memory and output.
pub const MAX_DIAGNOSTICS: usize = 1000;

/// Steps "did you mean" may take in one program (one analysis). A search over the
/// program's own names (variables, skills) takes a step per name skipped on its length
/// and [`SUGGESTION_COMPARISON`] steps per edit distance computed; once they are spent,
/// misspelt names get no suggestion. That is a million edit distances, under a second
/// of searching, where a file binding 200,000 names and misusing 3,000 others took five
/// minutes.
pub const SUGGESTION_STEPS: u64 = 100_000_000;

/// What one edit distance costs in [`SUGGESTION_STEPS`]: about what a hundred names
/// skipped on their length cost.
pub const SUGGESTION_COMPARISON: u64 = 100;

/// Matches of `break(pattern)` needles in statements the checker enumerates for one
/// program (W0701, W0702, W0904): each distinct needle is counted once per place it ends
/// in a statement. Past it the checker says nothing about patterns, rather than
/// something wrong. Only texts built for it come near: needles of a thousand lengths,
/// each found at every place of megabytes of statements.
pub const PATTERN_MATCHES: u64 = 50_000_000;

/// The native stack a thread that checks, lowers or formats a program is given: twice
/// what an unoptimised build needs at the limits (`compiler/tests/limits.rs` runs there
/// on half of it). Only touched pages cost memory.
pub const COMPILER_STACK: usize = 16 << 20;

/// The operator or parenthesis at which a line's tokens pass [`MAX_LINE_OPERATORS`].
pub fn operators_past_limit(line: &[(Token, Span)]) -> Option<Span> {
    line.iter()
        .filter(|(t, _)| counts_as_operator(*t))
        .nth(MAX_LINE_OPERATORS)
        .map(|&(_, span)| span)
}

/// Whether a token counts towards [`MAX_LINE_OPERATORS`].
fn counts_as_operator(token: Token) -> bool {
    matches!(
        token,
        Token::LParen
            | Token::Plus
            | Token::Minus
            | Token::Star
            | Token::Slash
            | Token::EqEq
            | Token::NotEq
            | Token::Lt
            | Token::Le
            | Token::Gt
            | Token::Ge
            | Token::GeAlt
    )
}

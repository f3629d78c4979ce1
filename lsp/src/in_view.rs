//! The statements a request's range reaches, for the hints that are computed for the
//! visible part of a document only.

use ilmr_compiler::Span;
use ilmr_compiler::ast::{Block, Stmt};

/// The statements of `blocks` (not of their bodies) from the first block that reaches
/// `range` up to the first statement that starts after it. Blocks and statements are
/// in text order, so the blocks before the range are skipped by a binary search and
/// nothing after it is looked at.
pub fn statements_reaching<'b, 't>(
    blocks: &'b [Block<'t>],
    range: Span,
) -> impl Iterator<Item = &'b Stmt<'t>> {
    let from = blocks.partition_point(|b| b.span.end < range.start);
    blocks[from..]
        .iter()
        .take_while(move |b| b.span.start <= range.end)
        .flat_map(move |b| {
            b.stmts
                .iter()
                .take_while(move |s| s.span.start <= range.end)
        })
}

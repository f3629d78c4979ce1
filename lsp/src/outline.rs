//! The shape of one file: document symbols (skills, `while`, `if` and `check` blocks,
//! nested as written, to `MAX_OUTLINE_DEPTH`) and folding ranges (the same blocks and
//! runs of comment lines).

use ilmr_compiler::Span;
use ilmr_compiler::ast::{Block, SourceFile, StmtKind};
use tower_lsp_server::ls_types::{DocumentSymbol, FoldingRange, FoldingRangeKind, SymbolKind};

use crate::line_index::LineIndex;

/// How deep document symbols nest; deeper blocks are listed at this depth, after the
/// block holding them. Each level is two levels of JSON, and clients built on serde
/// refuse JSON nested deeper than 128 (the whole answer, not just the outline).
pub const MAX_OUTLINE_DEPTH: usize = 32;

pub fn symbols(tree: &SourceFile<'_>, text: &str, index: &LineIndex) -> Vec<DocumentSymbol> {
    let mut out = Vec::new();
    blocks(&tree.blocks, 1, &mut out, text, index);
    for skill in &tree.skills {
        let span = skill.header.to(skill.span);
        out.push(symbol(
            skill.name.text.to_string(),
            Some("skill".to_string()),
            SymbolKind::FUNCTION,
            span,
            skill.name.span,
            {
                let mut children = Vec::new();
                blocks(&skill.blocks, 2, &mut children, text, index);
                children
            },
            text,
            index,
        ));
    }
    out
}

/// The symbols of `blocks`, at nesting `depth` (1 for the file's own), onto `out`.
/// The recursion is bounded by the compiler's block depth limit.
fn blocks(
    blocks: &[Block<'_>],
    depth: usize,
    out: &mut Vec<DocumentSymbol>,
    text: &str,
    index: &LineIndex,
) {
    for stmt in blocks.iter().flat_map(|b| &b.stmts) {
        let (kind, detail, body, end) = match &stmt.kind {
            StmtKind::If(c) => (SymbolKind::EVENT, "guard", &c.body, c.end),
            StmtKind::While { body, .. } => (SymbolKind::NAMESPACE, "loop", &body.body, body.end),
            StmtKind::Check { body, end } => (SymbolKind::NAMESPACE, "validated only", body, *end),
            _ => continue,
        };
        let last = end
            .or_else(|| body.last().map(|b| b.span))
            .unwrap_or(stmt.span);
        let mut children = Vec::new();
        let nested = depth < MAX_OUTLINE_DEPTH;
        if nested {
            self::blocks(body, depth + 1, &mut children, text, index);
        }
        out.push(symbol(
            stmt.span.slice(text).trim().to_string(),
            Some(detail.to_string()),
            kind,
            stmt.span.to(last),
            stmt.span,
            children,
            text,
            index,
        ));
        if !nested {
            self::blocks(body, depth, out, text, index);
        }
    }
}

#[allow(clippy::too_many_arguments, deprecated)]
fn symbol(
    name: String,
    detail: Option<String>,
    kind: SymbolKind,
    span: Span,
    selection: Span,
    children: Vec<DocumentSymbol>,
    text: &str,
    index: &LineIndex,
) -> DocumentSymbol {
    DocumentSymbol {
        name,
        detail,
        kind,
        tags: None,
        deprecated: None,
        range: index.range(text, span),
        selection_range: index.range(text, selection),
        children: (!children.is_empty()).then_some(children),
    }
}

pub fn folding_ranges(tree: &SourceFile<'_>, text: &str, index: &LineIndex) -> Vec<FoldingRange> {
    let mut out = Vec::new();
    let line = |offset: u32| index.line_of(offset as usize) as u32;
    let mut push = |start: u32, end: u32, kind: Option<FoldingRangeKind>| {
        if end > start {
            out.push(FoldingRange {
                start_line: start,
                start_character: None,
                end_line: end,
                end_character: None,
                kind,
                collapsed_text: None,
            });
        }
    };
    let mut stmts = Vec::new();
    tree.for_each_stmt(&mut |s| stmts.push((s.span, closing(&s.kind))));
    for (span, end) in stmts {
        // The closing line stays visible, as editors show `}`.
        if let Some(end) = end {
            push(line(span.start), line(end.start).saturating_sub(1), None);
        }
    }
    for skill in &tree.skills {
        let last = trimmed_end(text, skill.span);
        push(line(skill.header.start), line(last), None);
    }
    let mut run: Option<(u32, u32)> = None;
    for c in &tree.comments {
        let l = line(c.start);
        let own_line = text[..c.start as usize]
            .rsplit('\n')
            .next()
            .is_some_and(|before| before.trim().is_empty());
        run = match run {
            Some((start, end)) if own_line && l == end + 1 => Some((start, l)),
            Some((start, end)) => {
                push(start, end, Some(FoldingRangeKind::Comment));
                own_line.then_some((l, l))
            }
            None => own_line.then_some((l, l)),
        };
    }
    if let Some((start, end)) = run {
        push(start, end, Some(FoldingRangeKind::Comment));
    }
    out.sort_by_key(|r| (r.start_line, r.end_line));
    out
}

fn closing(kind: &StmtKind<'_>) -> Option<Span> {
    match kind {
        StmtKind::If(c) | StmtKind::While { body: c, .. } => c.end,
        StmtKind::Check { end, .. } => *end,
        _ => None,
    }
}

/// Where a span's text ends once trailing blank lines are dropped.
fn trimmed_end(text: &str, span: Span) -> u32 {
    let s = span.slice(text);
    span.start + s.trim_end().len() as u32
}

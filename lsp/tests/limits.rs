//! Hostile sizes through the engine: files at and past the compiler's depth limits fit
//! the engine's stack with a margin; a 100,000-line file and a megabyte-long line get
//! every feature's answer in linear time. The time bounds are guards against a
//! quadratic walk (which takes hours at these sizes), not benchmarks.

use std::time::{Duration, Instant};

use ilmr_compiler::diagnostic::Code;
use ilmr_compiler::limits::{MAX_BLOCK_DEPTH, MAX_LINE_OPERATORS};
use ilmr_lsp::outline::MAX_OUTLINE_DEPTH;
use ilmr_lsp::{Engine, Settings};
use tower_lsp_server::ls_types::{
    DocumentSymbol, InlayHint, InlayHintLabel, InlayHintTooltip, NumberOrString, Position, Range,
    Uri,
};

const TASK: &str = "file:///ws/task.ilmr";

/// Far above what these take in an unoptimised build, far below a quadratic walk.
const GUARD: Duration = Duration::from_secs(60);

fn engine_with(text: String) -> (Engine, Uri) {
    let mut engine = Engine::new(
        Vec::new(),
        Settings {
            robot: Some("moro".into()),
            snippets: true,
            ilmrc: None,
        },
    );
    let uri: Uri = TASK.parse().expect("a URI");
    engine.open(uri.clone(), 1, text);
    (engine, uri)
}

/// Asks every feature at `at` and names those whose answer was not empty.
fn every_feature(engine: &Engine, uri: &Uri, at: Position) -> Vec<&'static str> {
    let whole = Range::new(Position::new(0, 0), Position::new(u32::MAX, 0));
    [
        ("diagnostics", !engine.diagnostics(uri).is_empty()),
        ("completion", !engine.completion(uri, at).is_empty()),
        ("hover", engine.hover(uri, at).is_some()),
        ("signature", engine.signature_help(uri, at).is_some()),
        ("definition", !engine.definition(uri, at).is_empty()),
        ("references", !engine.references(uri, at, true).is_empty()),
        ("prepare_rename", engine.prepare_rename(uri, at).is_some()),
        ("rename", engine.rename(uri, at, "uusi").is_ok()),
        ("symbols", !engine.document_symbols(uri).is_empty()),
        ("folding", !engine.folding_ranges(uri).is_empty()),
        ("tokens", !engine.semantic_tokens(uri).is_empty()),
        ("formatting", engine.formatting(uri).is_some()),
        ("code_actions", !engine.code_actions(uri, whole).is_empty()),
        ("inlay_hints", !engine.inlay_hints(uri, whole).is_empty()),
        ("code_lenses", !engine.code_lenses(uri).is_empty()),
        (
            "highlights",
            !engine.document_highlights(uri, at).is_empty(),
        ),
        (
            "workspace_symbols",
            !engine.workspace_symbols("").is_empty(),
        ),
    ]
    .into_iter()
    .filter_map(|(name, answered)| answered.then_some(name))
    .collect()
}

#[test]
fn a_100000_line_file_gets_every_answer_in_linear_time() {
    // One variable bound on every line: its 100,000 bindings and 200,000 references,
    // which a search per reference turns into 10^10 steps.
    let mut text = String::from("// kierros\nkäännös = 0\n");
    for i in 0..100_000 {
        text.push_str("käännös = käännös + 1\n");
        if i % 100 == 0 {
            text.push_str("if(käännös > 2)\n    wait(1)\nendif\n");
        }
    }
    text.push_str("wait(käännös)\n");
    let lines = text.lines().count() as u32;
    assert!(lines > 100_000);
    let started = Instant::now();
    let (engine, uri) = engine_with(text);
    let answered = every_feature(&engine, &uri, Position::new(lines - 1, 7));
    // A clean file: no diagnostics, so no quick fixes.
    let all_but = [
        "completion",
        "hover",
        "signature",
        "definition",
        "references",
    ];
    let rest = [
        "prepare_rename",
        "rename",
        "symbols",
        "folding",
        "tokens",
        "formatting",
        "inlay_hints",
        "code_lenses",
        "highlights",
        "workspace_symbols",
    ];
    assert_eq!(answered, [&all_but[..], &rest[..]].concat());
    let references = engine.references(&uri, Position::new(2, 2), true);
    assert_eq!(references.len(), 1 + 200_000 + 1_000 + 1);
    assert!(started.elapsed() < GUARD, "{:?}", started.elapsed());
}

#[test]
fn a_megabyte_line_gets_every_answer_in_linear_time() {
    // Half a million numbers on one line that is not ASCII: every semantic token's
    // column is counted in UTF-16 units, and walking the line for each is 10^11 steps.
    let mut line = String::from("käännös = sensor(scanner,door,");
    for _ in 0..500_000 {
        line.push_str("1,");
    }
    line.push_str("1) // ä\n");
    assert!(line.len() > 1_000_000);
    let text = format!("ö = 1\n{line}wait(ö)\n");
    let started = Instant::now();
    let (engine, uri) = engine_with(text);
    let answered = every_feature(&engine, &uri, Position::new(1, 3));
    // `sensor` with half a million arguments is an error; the line holds no block.
    let names = [
        "diagnostics",
        "completion",
        "hover",
        "definition",
        "references",
    ];
    let rest = [
        "prepare_rename",
        "rename",
        "tokens",
        "formatting",
        "inlay_hints",
        "code_lenses",
        "highlights",
        "workspace_symbols",
    ];
    assert_eq!(answered, [&names[..], &rest[..]].concat());
    // In the middle of the arguments: the line before the cursor is read whole.
    let inside = Position::new(1, 500_000);
    assert!(engine.signature_help(&uri, inside).is_some());
    assert!(
        engine.completion(&uri, inside).is_empty(),
        "no form takes so many"
    );
    assert!(engine.semantic_tokens(&uri).len() > 500_000);
    assert!(started.elapsed() < GUARD, "{:?}", started.elapsed());
}

#[test]
fn twenty_thousand_breaks_of_one_pattern_label_each_statement_in_a_few_lines() {
    // Every statement is ended by every `break(w)` and every priority block: a label
    // naming each made 120 MB of hints at 2,000 of them and grew as their square.
    const N: usize = 20_000;
    let mut text = String::new();
    for i in 0..N {
        text.push_str(&format!("w{i} = goahead(1)\n\nbreak(w)\n\n"));
    }
    for _ in 0..N / 10 {
        text.push_str("priority = highest\nspeed(0)\n\n");
    }
    let started = Instant::now();
    let (engine, uri) = engine_with(text);
    let whole = Range::new(Position::new(0, 0), Position::new(u32::MAX, 0));
    let hints = engine.inlay_hints(&uri, whole);
    let label = |h: &InlayHint| match &h.label {
        InlayHintLabel::String(s) => s.clone(),
        InlayHintLabel::LabelParts(_) => panic!("hints are plain strings"),
    };
    let first = hints
        .iter()
        .map(label)
        .find(|l| l.contains("ended by break"))
        .expect("the first goahead is labelled");
    assert!(
        first.ends_with(&format!(
            "and by {} more breaks · and by {} more priority blocks",
            N - 3,
            N / 10 - 3
        )),
        "{first}"
    );
    let longest = hints.iter().map(|h| label(h).len()).max().unwrap_or(0);
    assert!(longest < 400, "a label of {longest} bytes");
    let tooltips: usize = hints
        .iter()
        .map(|h| match &h.tooltip {
            Some(InlayHintTooltip::String(s)) => s.len(),
            _ => 0,
        })
        .max()
        .unwrap_or(0);
    assert!(tooltips < 2_000, "a tooltip of {tooltips} bytes");
    assert!(started.elapsed() < GUARD, "{:?}", started.elapsed());
}

/// `64 MiB`, `8 KiB`, `2,000`: as the README's table writes them.
fn shown(value: usize, bytes: bool) -> String {
    const MIB: usize = 1024 * 1024;
    if bytes && value.is_multiple_of(MIB) {
        return format!("{} MiB", value / MIB);
    }
    if bytes && value.is_multiple_of(1024) {
        return format!("{} KiB", value / 1024);
    }
    let digits = value.to_string();
    let mut out = String::new();
    for (i, d) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(d);
    }
    out
}

#[test]
fn the_readme_quotes_every_limit() {
    use ilmr_lsp::{framing, server, workspace};
    let limits = [
        (
            "framing::MAX_MESSAGE_BYTES",
            framing::MAX_MESSAGE_BYTES,
            true,
        ),
        ("framing::MAX_HEADER_BYTES", framing::MAX_HEADER_BYTES, true),
        (
            "server::ENGINE_STACK_BYTES",
            server::ENGINE_STACK_BYTES,
            true,
        ),
        ("server::STACK_MARGIN", server::STACK_MARGIN, false),
        ("outline::MAX_OUTLINE_DEPTH", MAX_OUTLINE_DEPTH, false),
        ("workspace::MAX_FILES", workspace::MAX_FILES, false),
        ("workspace::MAX_SCAN_BYTES", workspace::MAX_SCAN_BYTES, true),
        ("workspace::MAX_DEPTH", workspace::MAX_DEPTH, false),
        (
            "workspace::MAX_SCANNED_ENTRIES",
            workspace::MAX_SCANNED_ENTRIES,
            false,
        ),
        (
            "completion::MAX_VARIABLE_ITEMS",
            ilmr_lsp::completion::MAX_VARIABLE_ITEMS,
            false,
        ),
        (
            "symbols::MAX_WORKSPACE_SYMBOLS",
            ilmr_lsp::symbols::MAX_WORKSPACE_SYMBOLS,
            false,
        ),
        ("lens::ENDED_LISTED", ilmr_lsp::lens::ENDED_LISTED, false),
        (
            "run::RUN_TIMEOUT (seconds)",
            ilmr_lsp::run::RUN_TIMEOUT.as_secs() as usize,
            false,
        ),
    ];
    let readme = include_str!("../README.md");
    let table = readme.split("### Limits").nth(1).expect("a Limits section");
    let rows: Vec<&str> = table
        .lines()
        .skip_while(|l| !l.starts_with('|'))
        .take_while(|l| l.starts_with('|'))
        .skip(2)
        .collect();
    assert_eq!(
        rows.len(),
        limits.len(),
        "one row per limit:\n{}",
        rows.join("\n")
    );
    for (name, value, bytes) in limits {
        let row = rows
            .iter()
            .find(|r| r.contains(&format!("`{name}`")))
            .unwrap_or_else(|| panic!("no row for {name}"));
        let cells: Vec<&str> = row.split('|').map(str::trim).collect();
        assert_eq!(cells[2], shown(value, bytes), "{name}");
    }
}

/// Files at the compiler's limits, with where their deepest point is, and the same
/// `depth_past` levels past them. Files 1,000,000 levels past stay within the size
/// `ilmrc` reads (8 MiB): `if`s are left unclosed, and `while`s, whose lines are
/// longer, go one level past at most.
fn deep_files(depth_past: usize) -> Vec<(&'static str, String, Position)> {
    let ops = MAX_LINE_OPERATORS + depth_past;
    let blocks = MAX_BLOCK_DEPTH + depth_past;
    let parens = |ops: usize| format!("x = {}1{}", "(".repeat(ops), ")".repeat(ops));
    let sum = |ops: usize| format!("x = 1{}", "+1".repeat(ops));
    let ifs = format!(
        "x = 1\n{}{}\n",
        "if(x)\n".repeat(blocks),
        parens(MAX_LINE_OPERATORS)
    );
    let whiles = MAX_BLOCK_DEPTH + depth_past.min(1);
    let whiles = format!(
        "x = 1\n{}{}\n{}",
        "while(x < 2)\n".repeat(whiles),
        sum(MAX_LINE_OPERATORS),
        "endwhile\n".repeat(whiles)
    );
    let middle = |ops: usize| Position::new(0, (4 + ops) as u32);
    let inner = Position::new(blocks as u32 + 1, (4 + MAX_LINE_OPERATORS) as u32);
    vec![
        ("parens", format!("{}\nwait(x)\n", parens(ops)), middle(ops)),
        ("sum", format!("{}\nwait(x)\n", sum(ops)), middle(ops)),
        ("ifs", ifs, inner),
        ("whiles", whiles, inner),
    ]
}

fn too_deep(engine: &Engine, uri: &Uri) -> bool {
    let limit_codes = [Code::TooComplex.as_str(), Code::TooDeep.as_str()];
    engine.diagnostics(uri).iter().any(
        |d| matches!(&d.code, Some(NumberOrString::String(c)) if limit_codes.contains(&c.as_str())),
    )
}

#[test]
fn the_engine_stack_holds_the_deepest_files_with_a_margin() {
    // On a stack STACK_MARGIN times smaller than the engine's: a file at the limits
    // with every feature asked at its deepest point, and files past them.
    let stack = ilmr_lsp::server::ENGINE_STACK_BYTES / ilmr_lsp::server::STACK_MARGIN;
    let run = std::thread::Builder::new()
        .stack_size(stack)
        .spawn(|| {
            for (past, accepted) in [(0, true), (1, false), (1_000_000, false)] {
                for (name, text, deepest) in deep_files(past) {
                    assert!(text.len() as u64 <= ilmr_files::MAX_SOURCE_BYTES, "{name}");
                    let (engine, uri) = engine_with(text);
                    assert_eq!(!too_deep(&engine, &uri), accepted, "{name} {past} past");
                    every_feature(&engine, &uri, deepest);
                }
            }
        })
        .expect("a thread");
    run.join().expect("no overflow, no panic");
}

fn outline_depth(symbols: &[DocumentSymbol]) -> usize {
    symbols
        .iter()
        .map(|s| 1 + outline_depth(s.children.as_deref().unwrap_or_default()))
        .max()
        .unwrap_or(0)
}

fn outline_count(symbols: &[DocumentSymbol]) -> usize {
    symbols
        .iter()
        .map(|s| 1 + outline_count(s.children.as_deref().unwrap_or_default()))
        .sum()
}

#[test]
fn the_outline_nests_no_deeper_than_its_limit_and_keeps_every_block() {
    let ifs = format!(
        "x = 1\n{}wait(1)\n{}",
        "if(x)\n".repeat(MAX_BLOCK_DEPTH),
        "endif\n".repeat(MAX_BLOCK_DEPTH)
    );
    let (engine, uri) = engine_with(ifs);
    let symbols = engine.document_symbols(&uri);
    assert_eq!(outline_depth(&symbols), MAX_OUTLINE_DEPTH);
    assert_eq!(outline_count(&symbols), MAX_BLOCK_DEPTH);
    // As JSON, well within the depth serde-based clients read (128).
    let json = serde_json::to_string(&symbols).unwrap();
    assert!(serde_json::from_str::<serde_json::Value>(&json).is_ok());
}

//! The hand-written reader and the chumsky grammar agree: `parse` (reader first, grammar
//! for the lines it declines) gives the same tree and the same diagnostics as the
//! grammar run over the whole file, on every program in the repository, on the benchmark
//! corpus, and on generated and mutated lines. And the reader does take the lines it was
//! written for, so the speed is not lost silently.

use proptest::prelude::*;

use super::*;

#[path = "../../benches/corpus.rs"]
mod corpus;
#[path = "../../tests/support/programs.rs"]
mod programs;

/// The grammar alone over the whole file: how `parse` worked before the reader.
fn reference(source: &str, file: FileId) -> Parsed<'_> {
    let lexed = lexer::lex(source);
    let tokens = with_final_newline(lexed.tokens, source);
    let patterns = tokens
        .iter()
        .filter(|(t, _)| *t == Token::Break)
        .filter_map(|&(_, span)| unclosed_pattern(source, span, file))
        .collect();
    let (tokens, mut syntax, ends) = prepared(tokens, source, file);
    let (lines, errors) = lines::parse_lines(&tokens, source);
    // Each line's errors, explained as `parse` explains them; a block end of no block
    // was already reported and read as a broken line.
    let mut errors = errors.into_iter().peekable();
    let mut from = 0;
    for to in tokens
        .iter()
        .enumerate()
        .filter(|(_, (t, _))| *t == Token::Newline)
    {
        let line = &tokens[from..=to.0];
        from = to.0 + 1;
        let mut mine = Vec::new();
        while let Some(e) = errors.next_if(|e| e.span().start <= to.1.1.start) {
            mine.push(e);
        }
        let whole = line[0].1.to(line[line.len() - 1].1);
        if !ends
            .iter()
            .any(|end| whole.start <= end.start && end.end <= whole.end)
        {
            syntax.extend(explained_errors(line, mine, file, source).0);
        }
    }
    let mut builder = blocks::Builder::new(source, file);
    let mut unclosed = Vec::new();
    for parsed in lines {
        unclosed.extend(unclosed_args(&parsed.line, file));
        builder.line(parsed);
    }
    let (tree, structure) = builder.finish(lexed.comments);
    let break_patterns = tokens
        .iter()
        .any(|&(t, span)| t == Token::Break && lexer::break_pattern(source, span).inner.is_some());
    finish(
        tree,
        [
            patterns,
            syntax.into_iter().collect(),
            structure,
            unclosed.into_iter().collect(),
        ],
        break_patterns,
    )
}

/// What `parse` does to each line before a parser sees it, done to the whole file's
/// tokens: characters that stand for others are read as those, and a block end written
/// as in another language becomes the token it means (a skill's end line, one error
/// token, whose span it returns). The diagnostics are the ones `parse` gives for them.
fn prepared(
    tokens: Vec<(Token, Span)>,
    source: &str,
    file: FileId,
) -> (Vec<(Token, Span)>, Vec<Diagnostic>, Vec<Span>) {
    let mut out = Vec::with_capacity(tokens.len());
    let mut diagnostics = Vec::new();
    let mut ends = Vec::new();
    for line in tokens.split_inclusive(|(t, _)| *t == Token::Newline) {
        let (newline, content) = line.split_last().unwrap();
        let mut content = content.to_vec();
        if content.iter().any(|(t, _)| *t == Token::Error) {
            diagnostics.extend(characters::read_through(&mut content, source, file));
        }
        if let Some((meant, d)) = hints::block_end(&content, source, file) {
            diagnostics.push(d);
            let whole = content[0].1.to(content[content.len() - 1].1);
            let token = match meant {
                Line::EndIf => Token::EndIf,
                Line::EndWhile => Token::EndWhile,
                Line::Checkend => Token::Checkend,
                _ => {
                    ends.push(whole);
                    Token::Error
                }
            };
            content = vec![(token, whole)];
        }
        // A line explained and read as something else is read so here too.
        let mut whole_line = content.clone();
        whole_line.push(*newline);
        let (_, errors) = lines::parse_lines(&whole_line, source);
        if let Some(explained) = errors
            .first()
            .and_then(|e| hints::explain(&content, source, file, *e.span()))
            && let Some(read_as) = explained.read_as
        {
            let mut again = read_as.clone();
            again.push(*newline);
            if lines::parse_lines(&again, source).1.is_empty() {
                diagnostics.push(explained.diagnostic);
                content = read_as;
            }
        }
        out.extend(content);
        out.push(*newline);
    }
    (out, diagnostics, ends)
}

/// The line grammar ends every line with a line break; the last line gets one.
fn with_final_newline(mut tokens: Vec<(Token, Span)>, source: &str) -> Vec<(Token, Span)> {
    if tokens.last().is_none_or(|(t, _)| *t != Token::Newline) {
        tokens.push((Token::Newline, Span::empty(source.len())));
    }
    tokens
}

fn assert_agree(source: &str) {
    // The trees' Debug output recurses once per level, and the fixtures nest up to the
    // block limit.
    let source = source.to_string();
    std::thread::Builder::new()
        .stack_size(crate::limits::COMPILER_STACK)
        .spawn(move || agree(&source))
        .unwrap()
        .join()
        .unwrap_or_else(|e| std::panic::resume_unwind(e));
}

fn agree(source: &str) {
    let fast = parse(source, FileId(0));
    let slow = reference(source, FileId(0));
    assert_eq!(
        format!("{:?}", fast.file),
        format!("{:?}", slow.file),
        "trees differ for {source:?}"
    );
    assert_eq!(
        fast.diagnostics, slow.diagnostics,
        "diagnostics differ for {source:?}"
    );
    assert_eq!(fast.break_patterns, slow.break_patterns);
    let mut any = false;
    fast.file.for_each_stmt(&mut |stmt| {
        any |= matches!(stmt.kind, StmtKind::Break { pattern: Some(_) });
    });
    assert!(
        fast.break_patterns || !any,
        "a pattern the flag missed in {source:?}"
    );
}

/// The line the reader makes of `text`, next to the grammar's.
fn both(text: &str) -> (Option<String>, String) {
    let mut tokens = lexer::lex(text).tokens;
    let n = tokens.len();
    tokens.push((Token::Newline, Span::empty(text.len())));
    let fast = fast::line(&tokens[..n], text).map(|l| format!("{l:?}"));
    let (lines, _) = lines::parse_lines(&tokens, text);
    (fast, format!("{:?}", lines[0].line))
}

fn repository_programs() -> &'static [(String, String)] {
    static PROGRAMS: std::sync::OnceLock<Vec<(String, String)>> = std::sync::OnceLock::new();
    // A line past the operator limit reaches neither the reader nor the grammar (it is
    // cut short before both, and `compiler/tests/limits.rs` tests that), so the programs
    // that hold one prove nothing here.
    PROGRAMS.get_or_init(|| {
        programs::repository_programs()
            .into_iter()
            .filter(|(_, text)| {
                text.lines().all(|line| {
                    crate::limits::operators_past_limit(&lexer::lex(line).tokens).is_none()
                })
            })
            .collect()
    })
}

#[test]
fn every_program_in_the_repository() {
    let programs = repository_programs();
    assert!(programs.len() > 20, "found only {}", programs.len());
    for (_, text) in programs {
        assert_agree(text);
    }
}

#[test]
fn the_benchmark_corpus() {
    let c = corpus::generate(3_000);
    assert_agree(&c.task);
    assert_agree(&c.skills);
}

#[test]
fn the_reader_takes_every_line_of_the_corpus() {
    let c = corpus::generate(1_200);
    for line in c.task.lines().chain(c.skills.lines()) {
        if line.trim().is_empty() {
            continue;
        }
        let (fast, slow) = both(line);
        assert_eq!(fast.as_deref(), Some(slow.as_str()), "{line:?}");
    }
}

#[test]
fn edge_shapes() {
    for text in [
        "\n\n  \nspeed(1)\n\n",
        "  \n",
        "turn(d=90,c=0.5) // comment\n",
        "x = -(-(a)) * --3 / (b - -c)",
        "if((a) => 3)\nendif",
        "v = while(c = 2)\nendwhile",
        "break(turn(d=)) // x\nbreak\nbreak(while(c",
        "priority = highest\npriority = lowest",
        "f(1,)\nf(,)\nf(1 2)\nf(a==1)\nv = a(1) + 2\nf(1",
        "a b\nv = \nv = while\nif(a\nif a\nwhile(a) b\ncheck(1)\nendif x",
        "TURN1:\nSkill two:\n x :\n",
        "v=1\r\nw = v\r\n",
        "käännös = 1\nÄ(käännös)",
        "g = gotoxy(1,2,3,4)\ns = sensor(scanner, door, left)\nsavepos(home)",
        "$\nf($)\nv = 1 $",
    ] {
        assert_agree(text);
    }
}

const NAMES: &[&str] = &[
    "a",
    "cnt",
    "V1",
    "turn",
    "speed",
    "sensor",
    "door",
    "left",
    "d",
    "c",
    "käännös",
    "Takebox",
];

fn expr() -> impl Strategy<Value = String> {
    let leaf = prop_oneof![
        (0u32..1000).prop_map(|n| n.to_string()),
        (0u32..100, 0u32..100).prop_map(|(a, b)| format!("{a}.{b}")),
        Just(".5".to_string()),
        proptest::sample::select(NAMES).prop_map(str::to_string),
    ];
    leaf.prop_recursive(4, 24, 2, |inner| {
        prop_oneof![
            inner.clone().prop_map(|e| format!("-{e}")),
            inner.clone().prop_map(|e| format!("({e})")),
            (
                inner.clone(),
                proptest::sample::select(&["+", "-", "*", "/", " + ", " - "][..]),
                inner
            )
                .prop_map(|(a, op, b)| format!("{a}{op}{b}")),
        ]
    })
}

fn condition() -> impl Strategy<Value = String> {
    prop_oneof![
        expr(),
        (
            expr(),
            proptest::sample::select(&["<", "<=", "==", "=", "!=", ">", ">=", "=>"][..]),
            expr()
        )
            .prop_map(|(a, op, b)| format!("{a} {op} {b}")),
    ]
}

fn args() -> impl Strategy<Value = String> {
    let arg = prop_oneof![
        expr(),
        (proptest::sample::select(NAMES), expr()).prop_map(|(k, v)| format!("{k}={v}")),
    ];
    proptest::collection::vec(arg, 0..4).prop_map(|a| format!("({})", a.join(",")))
}

/// A line the grammar accepts.
fn clean_line() -> impl Strategy<Value = String> {
    let name = || proptest::sample::select(NAMES);
    prop_oneof![
        (name(), args()).prop_map(|(n, a)| format!("{n}{a}")),
        name().prop_map(str::to_string),
        (name(), name(), args()).prop_map(|(v, n, a)| format!("{v} = {n}{a}")),
        (name(), expr()).prop_map(|(v, e)| format!("{v}={e}")),
        condition().prop_map(|c| format!("if({c})")),
        condition().prop_map(|c| format!("While ({c})")),
        (name(), condition()).prop_map(|(v, c)| format!("{v} = while({c})")),
        proptest::sample::select(
            &[
                "endif",
                "ENDWHILE",
                "check",
                "checkend",
                "break",
                "break(turn(d=))",
                "priority = highest",
                "Skill1:",
            ][..]
        )
        .prop_map(str::to_string),
    ]
}

/// Pieces that break lines in the ways people do.
const DAMAGE: &[&str] = &[
    "(", ")", ",", "=", "==", "-", "*", ":", "if", "while", "endif", "break(", "$", " ", "1", "x",
    "\n",
];

fn damaged_line() -> impl Strategy<Value = String> {
    (
        clean_line(),
        proptest::collection::vec((0usize..64, 0usize..3, 0..DAMAGE.len()), 0..3),
    )
        .prop_map(|(line, cuts)| {
            let mut chars: Vec<char> = line.chars().collect();
            for (at, len, piece) in cuts {
                let at = at % (chars.len() + 1);
                let end = (at + len).min(chars.len());
                chars.splice(at..end, DAMAGE[piece].chars());
            }
            chars.into_iter().collect()
        })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 600, ..ProptestConfig::default() })]

    #[test]
    fn the_reader_takes_clean_lines_as_the_grammar_does(line in clean_line()) {
        let (fast, slow) = both(&line);
        prop_assert_eq!(fast.as_deref(), Some(slow.as_str()), "{:?}", line);
    }

    #[test]
    fn files_of_damaged_lines_parse_alike(
        lines in proptest::collection::vec(
            prop_oneof![3 => damaged_line(), 1 => Just(String::new())],
            0..16,
        ),
    ) {
        assert_agree(&lines.join("\n"));
    }

    #[test]
    fn damaged_repository_programs_parse_alike(
        which in 0usize..1000,
        cuts in proptest::collection::vec((0usize..100_000, 0usize..6, 0..DAMAGE.len()), 1..10),
    ) {
        let programs = repository_programs();
        let mut chars: Vec<char> = programs[which % programs.len()].1.chars().collect();
        for (at, len, piece) in cuts {
            let at = at % (chars.len() + 1);
            let end = (at + len).min(chars.len());
            chars.splice(at..end, DAMAGE[piece].chars());
        }
        assert_agree(&chars.into_iter().collect::<String>());
    }
}

//! Nesting and size past the limits of `ilmr_compiler::limits`, at depths from a handful
//! to a million: checking, formatting and lowering end with the limit's diagnostic at the
//! first place it is passed, or, at the limit, with a program; never with an overflowing
//! stack. Each case runs on a thread with a small stack, so that a pass that recurses
//! more than the limits allow fails here in an unoptimised build, not on a robot.

use ilmr_compiler::Code;
use ilmr_compiler::check::{Source, analyze};
use ilmr_compiler::diagnostic::MAX_PLACES_SHOWN;
use ilmr_compiler::limits::{
    MAX_BLOCK_DEPTH, MAX_LINE_OPERATORS, PATTERN_MATCHES, SUGGESTION_COMPARISON, SUGGESTION_STEPS,
};
use ilmr_model::RobotModel;

/// Half the stack the tools give a thread that compiles, and the main thread's on Linux.
const STACK: usize = ilmr_compiler::limits::COMPILER_STACK / 2;

const DEPTHS: &[usize] = &[1, 10, 100, 255, 256, 257, 1_000, 100_000, 1_000_000];

struct Outcome {
    codes: Vec<Code>,
    /// Byte offset of the first diagnostic.
    first_at: Option<usize>,
    lowered: bool,
    formatted: bool,
}

fn run(task: String, skills: Option<String>) -> Outcome {
    std::thread::Builder::new()
        .stack_size(STACK)
        .spawn(move || {
            let model = RobotModel::builtin("moro").unwrap();
            let mut sources = vec![Source::new("task.ilmr", task.clone())];
            if let Some(skills) = skills {
                sources.push(Source::library("skills.ilms", skills));
            }
            let analysis = analyze(&sources, &model);
            // Warnings (a variable bound and never used) are beside the point here.
            let errors = || analysis.diagnostics.iter().filter(|d| d.is_error());
            let codes = errors().map(|d| d.code).collect();
            let first_at = errors().next().map(|d| d.span.start as usize);
            let lowered =
                ilmr_compiler::lower::lower(&analysis, &model, ilmr_compiler::FileId(0)).is_ok();
            let formatted = ilmr_compiler::format::format(&task, &model).is_ok();
            Outcome {
                codes,
                first_at,
                lowered,
                formatted,
            }
        })
        .unwrap()
        .join()
        .expect("the compiler overflowed or panicked")
}

/// `x = ` and an expression of `n` levels built by `shape`, then a line that uses `x`.
fn expression_task(n: usize, shape: fn(usize) -> String) -> String {
    format!("x = {}\ny = x\nspeed(y)\n", shape(n))
}

fn parens(n: usize) -> String {
    format!("{}1{}", "(".repeat(n), ")".repeat(n))
}

fn sum(n: usize) -> String {
    std::iter::repeat_n("1", n + 1)
        .collect::<Vec<_>>()
        .join("+")
}

fn minus(n: usize) -> String {
    format!("{}1", "-".repeat(n))
}

/// `1*(1*(1*(...)))`: an operator and a parenthesis a level.
fn right_nested(n: usize) -> String {
    format!("{}1{}", "1*(".repeat(n / 2), ")".repeat(n / 2))
}

/// Where the expression's (limit + 1)th operator or parenthesis stands.
fn past_limit(task: &str) -> usize {
    task.char_indices()
        .filter(|(_, c)| "(+-*/".contains(*c))
        .nth(MAX_LINE_OPERATORS)
        .map(|(i, _)| i)
        .unwrap()
}

#[test]
fn expressions_at_every_depth() {
    for shape in [parens, sum, minus, right_nested] {
        for &n in DEPTHS {
            let task = expression_task(n, shape);
            let out = run(task.clone(), None);
            let first_line = task.lines().next().unwrap();
            let operators = first_line.chars().filter(|c| "(+-*/".contains(*c)).count();
            if operators <= MAX_LINE_OPERATORS {
                assert!(
                    out.codes.is_empty(),
                    "{n} levels: {:?} in {}",
                    out.codes,
                    &task[..task.len().min(80)]
                );
                assert!(out.lowered && out.formatted, "{n} levels");
            } else {
                assert_eq!(out.codes, [Code::TooComplex], "{n} levels");
                assert_eq!(out.first_at, Some(past_limit(&task)), "{n} levels");
                assert!(!out.lowered && !out.formatted, "{n} levels");
            }
        }
    }
}

/// A condition past the limit keeps its `if` and `while` paired with their closers.
#[test]
fn a_condition_past_the_limit_keeps_its_block() {
    for head in ["if", "while", "w = while"] {
        let close = if head == "if" { "endif" } else { "endwhile" };
        let task = format!(
            "{head}({} > 0)\nspeed(0.1)\n{close}\nspeed(0.2)\n",
            sum(300)
        );
        let out = run(task, None);
        assert_eq!(out.codes, [Code::TooComplex], "{head}");
    }
}

fn nested_blocks(n: usize, open: &str, close: &str) -> String {
    format!(
        "x = 1\n{}speed(0.1)\n{}speed(0.2)\n",
        format!("{open}\n").repeat(n),
        format!("{close}\n").repeat(n)
    )
}

#[test]
fn blocks_at_every_depth() {
    for (open, close) in [
        ("if(x > 0)", "endif"),
        ("while(x < 1)", "endwhile"),
        ("check", "checkend"),
    ] {
        for &n in DEPTHS {
            let task = nested_blocks(n, open, close);
            let out = run(task.clone(), None);
            if n <= MAX_BLOCK_DEPTH {
                assert!(out.codes.is_empty(), "{open} x{n}: {:?}", out.codes);
                assert!(out.lowered && out.formatted, "{open} x{n}");
            } else {
                assert_eq!(out.codes, [Code::TooDeep], "{open} x{n}");
                let line = task[..out.first_at.unwrap()].lines().count();
                assert_eq!(line, MAX_BLOCK_DEPTH + 1, "the first block past the limit");
                assert!(!out.lowered && !out.formatted, "{open} x{n}");
            }
        }
    }
}

/// Unclosed blocks past the limit: one error for the limit, and one for each block that
/// was built and never closed, as for any unclosed block.
#[test]
fn unclosed_blocks_past_the_limit() {
    let task = format!("x = 1\n{}", "if(x > 0)\n".repeat(100_000));
    let out = run(task, None);
    let deep = out.codes.iter().filter(|c| **c == Code::TooDeep).count();
    let unclosed = out.codes.iter().filter(|c| **c == Code::UnclosedIf).count();
    assert_eq!((deep, unclosed), (1, MAX_BLOCK_DEPTH));
}

/// A skill header ends the blocks skipped past the limit, as it ends any open block.
#[test]
fn a_skill_header_ends_a_skipped_block() {
    let skills = format!(
        "Deep:\nx = 1\n{}speed(0.1)\nNext:\nspeed(sideways)\n",
        "if(x > 0)\n".repeat(MAX_BLOCK_DEPTH + 5)
    );
    let out = run("Deep\nNext\n".into(), Some(skills));
    assert!(out.codes.contains(&Code::TooDeep), "{:?}", out.codes);
    assert!(
        out.codes.contains(&Code::NestedSkillHeader),
        "{:?}",
        out.codes
    );
    assert!(
        out.codes.contains(&Code::UnboundVariable),
        "the skill after it is checked: {:?}",
        out.codes
    );
}

fn skill_chain(n: usize) -> String {
    (0..n)
        .map(|i| {
            let body = if i + 1 < n {
                format!("S{}", i + 1)
            } else {
                "speed(0.1)".into()
            };
            format!("S{i}:\n{body}\n\n")
        })
        .collect()
}

#[test]
fn skill_chains_at_every_depth() {
    let max = usize::from(ilmr_vm::Config::default().max_call_depth);
    for n in [1, 10, max, max + 1, 1_000, 100_000] {
        let out = run("S0\n".into(), Some(skill_chain(n)));
        if n <= max {
            assert!(out.codes.is_empty(), "{n} skills: {:?}", out.codes);
            assert!(out.lowered, "{n} skills");
        } else {
            assert_eq!(out.codes, [Code::SkillsTooDeep], "{n} skills");
            assert!(!out.lowered, "{n} skills");
        }
    }
}

/// The deepest the limits allow, all at once: blocks at the limit inside each of a
/// chain of skills at the limit, the innermost with an expression at the limit.
#[test]
fn every_limit_at_once() {
    let max = usize::from(ilmr_vm::Config::default().max_call_depth);
    let skills: String = (0..max)
        .map(|i| {
            let inner = if i + 1 < max {
                format!("S{}", i + 1)
            } else {
                format!("y = {}", parens(MAX_LINE_OPERATORS))
            };
            format!(
                "S{i}:\nx = 1\n{}{inner}\n{}\n",
                "if(x > 0)\n".repeat(MAX_BLOCK_DEPTH),
                "endif\n".repeat(MAX_BLOCK_DEPTH)
            )
        })
        .collect();
    let out = run("S0\n".into(), Some(skills));
    assert!(out.codes.is_empty(), "{:?}", out.codes);
    assert!(out.lowered);
}

/// The docs quote the limits: keep them in step.
/// A program that binds many names of one length and then misuses others of that length
/// makes every "did you mean" compare against every name: they stop once the program's
/// budget is spent, and the errors are still reported, with the advice to bind them.
#[test]
fn suggestions_stop_when_the_budget_is_spent() {
    let names = 20_000;
    let misuses = 100;
    let mut task: String = (0..names)
        .map(|i| format!("v{}=1\nspeed(v{})\n", 10_000 + i, 10_000 + i))
        .collect();
    task.extend((0..misuses).map(|i| format!("speed(q{})\n", 10_000 + i)));
    let model = RobotModel::builtin("moro").unwrap();
    let sources = [Source::new("task.ilmr", task)];
    let analysis = analyze(&sources, &model);
    let unbound: Vec<_> = (analysis.diagnostics.iter())
        .filter(|d| d.code == Code::UnboundVariable)
        .collect();
    assert_eq!(unbound.len(), misuses);
    // Each search compares against every name: `q10000` is one edit from `v10000`.
    let per_search = names as u64 * SUGGESTION_COMPARISON;
    let affordable = (SUGGESTION_STEPS / per_search) as usize;
    assert!(affordable < misuses, "the case no longer spends the budget");
    let suggested = |d: &&ilmr_compiler::Diagnostic| d.fix.is_some();
    // The model's own constants are candidates too, so the last affordable search may
    // fall short.
    assert!(unbound[..affordable - 1].iter().all(suggested));
    assert_eq!(unbound[0].fix.as_ref().unwrap().replacement, "v10000");
    assert!(!unbound[affordable..].iter().any(suggested));
    assert!(unbound[affordable..].iter().all(|d| {
        d.help
            .as_deref()
            .is_some_and(|h| h.starts_with("bind it first"))
    }));
}

/// Fifty waits on one variable that fifty `followwall`s set: each W0904 shows five of
/// them and counts the rest, where it listed all fifty (output that grew as the square
/// of the file: 12 MB for 300 such pairs).
#[test]
fn a_warning_shows_a_few_of_its_places() {
    let task = "t=followwall(left)\nwait(t)\n".repeat(50);
    let model = RobotModel::builtin("moro").unwrap();
    let sources = [Source::new("task.ilmr", task)];
    let analysis = analyze(&sources, &model);
    let waits: Vec<_> = (analysis.diagnostics.iter())
        .filter(|d| d.code == Code::WaitNeverWakes)
        .collect();
    assert_eq!(waits.len(), 50);
    for d in waits {
        assert_eq!(d.secondary.len(), MAX_PLACES_SHOWN);
        assert!(
            d.secondary[MAX_PLACES_SHOWN - 1]
                .message
                .ends_with("(and 45 more like it)")
        );
    }
}

/// Patterns `a`, `aa`, ... up to 300 letters and statements of 300 `a`s: every pattern
/// ends at nearly every place of every statement. A few statements are judged (each
/// pattern is found in all of them, W0702); past [`PATTERN_MATCHES`] nothing is said.
#[test]
fn patterns_past_the_match_limit_are_not_judged() {
    let judged = |statements: usize| {
        let patterns: String = (1..=300)
            .map(|k| format!("break({})\n", "a".repeat(k)))
            .collect();
        let task = patterns + &format!("x{}=1\n", "a".repeat(300)).repeat(statements);
        let model = RobotModel::builtin("moro").unwrap();
        let sources = [Source::new("task.ilmr", task)];
        let analysis = analyze(&sources, &model);
        (analysis.diagnostics.iter())
            .filter(|d| {
                matches!(
                    d.code,
                    Code::PatternMatchesSeveral | Code::PatternMatchesNothing
                )
            })
            .count()
    };
    assert_eq!(judged(3), 300);
    // Each statement ends about 300 * 300 / 2 matches.
    let past = (PATTERN_MATCHES / (300 * 300 / 2)) as usize + 10;
    assert_eq!(judged(past), 0);
}

#[test]
fn the_diagnostics_reference_quotes_the_limits() {
    let max = ilmr_vm::Config::default().max_call_depth;
    assert!(
        Code::TooComplex
            .doc()
            .contains(&format!("({MAX_LINE_OPERATORS})"))
    );
    assert!(
        Code::TooDeep
            .doc()
            .contains(&format!("({MAX_BLOCK_DEPTH})"))
    );
    assert!(Code::SkillsTooDeep.doc().contains(&format!("({max} calls")));
}

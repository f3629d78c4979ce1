//! Loops that never give the tick back (W0902). The VM evaluates a `while`'s condition
//! again as soon as every command its last pass started has ended; when each of them
//! ended the instant it was issued (arithmetic, settings, `actuator`: the catalogue's
//! `Ends::AtIssue`), the next pass follows at once, in the same tick. If the body also
//! changes nothing its condition reads, the condition cannot turn false before the
//! tick ends, and the loop runs pass after pass until the tick's budget is spent; the
//! VM suspends it and resumes it next tick, where the same happens again.
//!
//! Only a body whose statements all end at issue can do this: an `if` is a guard that
//! may wait, a nested `while` may last, a skill may wait or move. So a body is read
//! down to its first statement that can last and no further, which keeps the check
//! linear however deeply loops nest.

use ilmr_stdlib::Command;
use ilmr_vm::Config;
use smallvec::SmallVec;

use crate::ast::{Arg, Args, Block, Expr, ExprKind, Stmt, StmtKind};
use crate::check::loops::names_in;
use crate::check::skills::Skills;
use crate::diagnostic::{Code, Diagnostic, FileId};
use crate::kept::Kept;
use crate::render::thousands;

/// What the W0902 check needs to know of the whole program.
pub struct Program<'a> {
    pub skills: &'a Skills,
    /// Whether a name is a variable anywhere in the program.
    pub is_variable: &'a dyn Fn(&str) -> bool,
}

/// W0902 when `stmt`, a `while`, never gives the tick back while its condition holds.
pub fn check(
    program: &Program<'_>,
    file: FileId,
    text: &str,
    stmt: &Stmt<'_>,
    cond: &Expr<'_>,
    body: &[Block<'_>],
    diags: &mut Kept,
) {
    if !may_starve(program.skills, cond, body) {
        return;
    }
    let mut read: SmallVec<[&str; 4]> = SmallVec::new();
    names_in(cond, &mut read);
    read.retain(|n| (program.is_variable)(n));
    let mut ops = 1 + expr_ops(program, cond);
    if body.len() > 1 {
        // Several blocks are started by one call.
        ops += 1;
    }
    let mut statements = 0usize;
    for s in body.iter().flat_map(|b| b.stmts.iter()) {
        ops += cost(program, s);
        statements += 1;
    }
    let config = Config::default();
    let budget = config.budget_ops;
    let passes = thousands(budget / ops);
    let budget = thousands(budget);
    let tick_ms = config.period * 1000.0;
    let head = stmt.span.slice(text).lines().next().unwrap_or("").trim();
    let condition = cond.span.slice(text).trim();
    let body_says = if statements == 0 {
        "its body is empty"
    } else {
        "nothing in its body lasts past the instant it is issued"
    };
    let (when, until) = if read.is_empty() {
        ("it never ends".to_string(), "for ever")
    } else {
        (
            format!("while `{condition}` holds"),
            "until something else changes its condition",
        )
    };
    diags.push(
        Diagnostic::new(
            Code::StarvingLoop,
            file,
            stmt.span,
            format!(
                "`{head}` never gives the tick back: {body_says}, and it changes nothing its condition reads"
            ),
        )
        .with_label(format!(
            "{when}: up to {passes} passes a tick, at least {ops} operations each"
        ))
        .with_help(format!(
            "it spends the VM's whole budget ({budget} operations every {tick_ms} ms tick) {until}; blocks queued behind it wait a tick, and the trace shows an `overrun` each tick. Put `wait(0.1)` in its body, or wait with a guard `if(...)` or `wait(v)`"
        )),
    );
}

/// Whether the loop may starve at all, without a cost: most loops wait, move or count
/// in their body, and are left at their first such statement. Needs only the skills,
/// not the program's variables.
pub fn may_starve(skills: &Skills, cond: &Expr<'_>, body: &[Block<'_>]) -> bool {
    let mut read: SmallVec<[&str; 4]> = SmallVec::new();
    names_in(cond, &mut read);
    for s in body.iter().flat_map(|b| b.stmts.iter()) {
        if !ends_at_issue(skills, s) {
            return false;
        }
        if written(s).any(|w| read.iter().any(|r| r.eq_ignore_ascii_case(w))) {
            // The body may turn the condition false within the tick: a counting loop.
            return false;
        }
    }
    true
}

/// Whether a statement of the body surely ends the instant it is issued.
fn ends_at_issue(skills: &Skills, stmt: &Stmt<'_>) -> bool {
    match &stmt.kind {
        StmtKind::Assign { value, .. } => match &value.kind {
            // `v = name`: a copy, a constant, a bare command or a skill call.
            ExprKind::Name(n) => match Command::from_name(n.text) {
                Some(command) => command.spec().ends.at_issue(std::iter::empty()),
                None => skills.find(n.text).is_none(),
            },
            _ => true,
        },
        StmtKind::Call { call, .. } => Command::from_name(call.name.text).is_some_and(|command| {
            command
                .spec()
                .ends
                .at_issue(positional_names(call.args.as_ref()))
        }),
        // Only checked, never run.
        StmtKind::Check { .. } => true,
        StmtKind::If(_)
        | StmtKind::While { .. }
        | StmtKind::Break { .. }
        | StmtKind::Priority
        | StmtKind::Error => false,
    }
}

/// The VM operations a statement that ends at issue costs at least: its instruction
/// and the expression it evaluates.
fn cost(program: &Program<'_>, stmt: &Stmt<'_>) -> u32 {
    match &stmt.kind {
        StmtKind::Assign { value, .. } if !matches!(value.kind, ExprKind::Name(_)) => {
            1 + expr_ops(program, value)
        }
        StmtKind::Check { .. } => 0,
        _ => 1,
    }
}

/// The names a statement of an at-issue body writes: what it assigns or binds, and the
/// variables its command names (`savepos(p)`, `clear(v)`).
fn written<'s>(stmt: &'s Stmt<'s>) -> impl Iterator<Item = &'s str> {
    let (first, args) = match &stmt.kind {
        StmtKind::Assign { target, .. } => (Some(target.text), None),
        StmtKind::Call { bind, call } => (bind.map(|b| b.text), call.args.as_ref()),
        _ => (None, None),
    };
    first.into_iter().chain(positional_names(args))
}

/// The postfix operations the lowering makes of an expression, as it folds constant
/// parts (`compiler/src/lower/expr.rs`): a lower bound of what evaluating it costs.
fn expr_ops(program: &Program<'_>, e: &Expr<'_>) -> u32 {
    fn ops(program: &Program<'_>, e: &Expr<'_>) -> Option<u32> {
        match &e.kind {
            ExprKind::Number(_) | ExprKind::Error => None,
            ExprKind::Name(n) => (program.is_variable)(n.text).then_some(1),
            ExprKind::Neg(inner) => ops(program, inner).map(|n| n + 1),
            ExprKind::Binary { lhs, rhs, .. } => match (ops(program, lhs), ops(program, rhs)) {
                (None, None) => None,
                (a, b) => Some(a.unwrap_or(1) + b.unwrap_or(1) + 1),
            },
            ExprKind::Compare { lhs, rhs, .. } => {
                Some(ops(program, lhs).unwrap_or(1) + ops(program, rhs).unwrap_or(1) + 1)
            }
        }
    }
    ops(program, e).unwrap_or(1)
}

/// The bare names among a call's positional arguments (keywords, or variables).
fn positional_names<'a>(args: Option<&'a Args<'a>>) -> impl Iterator<Item = &'a str> {
    args.into_iter()
        .flat_map(|a| a.items.iter())
        .filter_map(|a| match a {
            Arg::Positional(Expr {
                kind: ExprKind::Name(n),
                ..
            }) => Some(n.text),
            _ => None,
        })
}

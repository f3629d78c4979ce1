//! A readable listing of a module, after clox's `debug.c`: one instruction per line
//! with its index, source line (`|` when it repeats) and statement text. Used by tests
//! as snapshots and by `ilmrc` for `--disassemble`.

use std::fmt::Write;

use ilmr_stdlib::Field;

use super::Module;
use super::ids::{BlockId, ExprId, VarId};
use super::op::{Arg, ArgRange, ExprOp, Op};

fn var(m: &Module, v: VarId) -> &str {
    m.global(v).map_or("?", |g| g.name.as_str())
}

fn num(x: f64) -> String {
    format!("{x}")
}

/// An expression in infix with full parentheses for nested operators.
pub fn render_expr(m: &Module, id: ExprId) -> String {
    let mut stack: Vec<(String, bool)> = Vec::new();
    for op in m.expr_ops(id) {
        let atom = match *op {
            ExprOp::Const(c) => Some(m.consts.get(c.index()).map_or("?".into(), |x| num(*x))),
            ExprOp::Field(v, f) => Some(match f {
                Field::Status => var(m, v).to_string(),
                other => format!("{}.{}", var(m, v), other.name()),
            }),
            ExprOp::PosEq(a, b) => Some(format!("{} at {}", var(m, a), var(m, b))),
            _ => None,
        };
        if let Some(a) = atom {
            stack.push((a, false));
            continue;
        }
        if *op == ExprOp::Neg {
            let (a, compound) = stack.pop().unwrap_or_else(|| ("?".into(), false));
            stack.push((
                if compound {
                    format!("-({a})")
                } else {
                    format!("-{a}")
                },
                false,
            ));
            continue;
        }
        let sym = match op {
            ExprOp::Add => "+",
            ExprOp::Sub => "-",
            ExprOp::Mul => "*",
            ExprOp::Div => "/",
            ExprOp::Lt => "<",
            ExprOp::Le => "<=",
            ExprOp::Eq => "==",
            ExprOp::Ne => "!=",
            ExprOp::Gt => ">",
            _ => ">=",
        };
        let (b, bc) = stack.pop().unwrap_or_else(|| ("?".into(), false));
        let (a, ac) = stack.pop().unwrap_or_else(|| ("?".into(), false));
        let wrap = |s: String, c: bool| if c { format!("({s})") } else { s };
        stack.push((format!("{} {sym} {}", wrap(a, ac), wrap(b, bc)), true));
    }
    stack.pop().map_or_else(|| "?".into(), |(s, _)| s)
}

fn render_args(m: &Module, args: ArgRange) -> String {
    let parts: Vec<String> = m
        .arg_list(args)
        .iter()
        .map(|a| match *a {
            Arg::Num(e) => render_expr(m, e),
            Arg::Word(n) => m.name(n).to_string(),
            Arg::Setting { key, value } => format!("{}={}", m.name(key), render_expr(m, value)),
            Arg::Var(v) => format!("@{}", var(m, v)),
        })
        .collect();
    parts.join(", ")
}

fn operands(m: &Module, op: &Op) -> String {
    let mut s = match *op {
        Op::Issue { command, args, .. } => format!("{command} {}", render_args(m, args)),
        Op::Assign { var: v, expr } => format!("{} = {}", var(m, v), render_expr(m, expr)),
        Op::Copy { to, from } => format!("{} = {}", var(m, to), var(m, from)),
        Op::WaitTime { seconds, .. } => format!("{} s", render_expr(m, seconds)),
        Op::WaitVar { var: v, .. } | Op::Clear { var: v } => var(m, v).to_string(),
        Op::If { cond, body, .. } | Op::While { cond, body, .. } => {
            format!("{} -> block {}", render_expr(m, cond), body.0)
        }
        Op::Call { unit, .. } => m
            .units
            .get(unit.index())
            .map_or("?".into(), |u| u.name.clone()),
        Op::Break { pattern } => format!("{:?}", m.name(pattern)),
        Op::BreakAll | Op::Stop | Op::Cont | Op::Priority => String::new(),
    };
    if let Some(b) = op.bind() {
        let _ = write!(s, " => {}", var(m, b));
    }
    s.trim().to_string()
}

/// The whole module: globals, then every unit's blocks in the order they nest.
pub fn disassemble(m: &Module) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "module v{} ({} statements)",
        m.header.version,
        m.stmts.len()
    );
    for (i, g) in m.globals.iter().enumerate() {
        let _ = writeln!(
            out,
            "var {i:>3} {} : {}",
            g.name,
            super::serde_kinds::var_kind_name(g.kind)
        );
    }
    let mut listed = vec![false; m.blocks.len()];
    for (i, u) in m.units.iter().enumerate() {
        let role = if i == m.main.index() {
            "task"
        } else if u.skill {
            "skill"
        } else {
            "unit"
        };
        let _ = writeln!(out, "== {role} {} ==", u.name);
        for b in &u.blocks {
            block(m, *b, &mut listed, &mut out);
        }
    }
    for i in 0..m.blocks.len() {
        if !listed[i] {
            let _ = writeln!(out, "== unreachable ==");
            block(m, BlockId(i as u32), &mut listed, &mut out);
        }
    }
    out
}

fn block(m: &Module, id: BlockId, listed: &mut [bool], out: &mut String) {
    match listed.get_mut(id.index()) {
        Some(seen) if !*seen => *seen = true,
        _ => return,
    }
    let start = m.blocks.get(id.index()).map_or(0, |b| b.start);
    let _ = writeln!(out, "-- block {}", id.0);
    let mut last_line = None;
    let mut nested = Vec::new();
    for (k, instr) in m.block_code(id).iter().enumerate() {
        let stmt = m.stmt(instr.stmt);
        let line = stmt.map_or(0, |s| s.line);
        let line_col = if last_line == Some(line) {
            "   |".to_string()
        } else {
            format!("{line:>4}")
        };
        last_line = Some(line);
        let text = stmt.map_or("", |s| s.text.as_str());
        let _ = writeln!(
            out,
            "{:04} {line_col}  {:<9} {:<32} ; {text}",
            start as usize + k,
            instr.op.opcode().mnemonic(),
            operands(m, &instr.op),
        );
        if let Op::If { body, .. } | Op::While { body, .. } = instr.op {
            nested.push(body);
        }
    }
    for b in nested {
        block(m, b, listed, out);
    }
}

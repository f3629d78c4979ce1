//! Arithmetic and conditions: names resolve to variables (bound before in the text) or
//! to constants of the robot model; constant parts are folded so ranges can be checked.

use ilmr_stdlib::VarKind;

use crate::ast::{BinOp, CmpOp, Expr, ExprKind, Name};
use crate::check::{Cx, Findings, Resolved};
use crate::diagnostic::{Code, Diagnostic};

/// What checking an expression learnt about its value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Value {
    /// Known at check time (literals, model constants and arithmetic of them).
    Const(f64),
    /// Known only when the task runs.
    Runtime,
    /// A position variable (only meaningful in `==`/`!=` comparisons).
    Position,
    /// Already reported.
    Invalid,
}

impl Cx<'_, '_> {
    /// A number-valued expression.
    pub fn value(&mut self, f: &mut Findings, e: &Expr<'_>) -> Value {
        match &e.kind {
            ExprKind::Number(n) => Value::Const(*n),
            ExprKind::Name(name) => match self.name_value(f, name) {
                Value::Position => {
                    f.diags.push(self.position_as_number(name));
                    Value::Invalid
                }
                v => v,
            },
            ExprKind::Neg(inner) => match self.value(f, inner) {
                Value::Const(v) => Value::Const(-v),
                v => v,
            },
            ExprKind::Binary { op, lhs, rhs } => {
                let (a, b) = (self.value(f, lhs), self.value(f, rhs));
                match (a, b) {
                    (Value::Const(a), Value::Const(b)) => Value::Const(match op {
                        BinOp::Add => a + b,
                        BinOp::Sub => a - b,
                        BinOp::Mul => a * b,
                        BinOp::Div => a / b,
                    }),
                    (Value::Invalid, _) | (_, Value::Invalid) => Value::Invalid,
                    _ => Value::Runtime,
                }
            }
            ExprKind::Compare { op_span, .. } => {
                f.diags.push(
                    Diagnostic::new(
                        Code::Syntax,
                        self.file,
                        *op_span,
                        "a comparison can stand only in the condition of `if` or `while`",
                    )
                    .with_label("comparison here"),
                );
                Value::Invalid
            }
            ExprKind::Error => Value::Invalid,
        }
    }

    /// A name in an expression: a variable bound before, else a model constant.
    fn name_value(&mut self, f: &mut Findings, name: &Name<'_>) -> Value {
        if let Some(id) = self.vars.bound(name.text) {
            f.uses.push((id, name.span));
            f.refs.push((name.span, Resolved::Variable(id)));
            let kind = self.vars.get(id).kind;
            return if kind == VarKind::Position {
                Value::Position
            } else {
                Value::Runtime
            };
        }
        if let Some(v) = self.model_constant(name.text) {
            f.refs.push((name.span, Resolved::Model));
            return Value::Const(v);
        }
        f.diags.push(self.unbound(name));
        Value::Invalid
    }

    /// `[PARAMETERS]` (with their defaults), `[IDENTIFIERS]` and `[COLORS]` are constants.
    pub fn model_constant(&mut self, name: &str) -> Option<f64> {
        self.constants.get(name, self.buf)
    }

    pub fn unbound(&mut self, name: &Name<'_>) -> Diagnostic {
        if self.quiet {
            return Diagnostic::new(Code::UnboundVariable, self.file, name.span, "");
        }
        let d = Diagnostic::new(
            Code::UnboundVariable,
            self.file,
            name.span,
            format!("`{}` is used before anything binds it", name.text),
        )
        .with_label("no variable or model constant of this name yet");
        let candidates = self
            .vars
            .bound_names()
            .chain(self.model.parameters.iter().map(|p| p.name.as_str()));
        match self.suggestions.closest(name.text, candidates) {
            Some(s) => d.with_help(format!("did you mean `{s}`?")).with_fix(
                format!("replace with `{s}`"),
                name.span,
                s,
            ),
            None => d.with_help(
                "bind it first, e.g. `v = sensor(...)` or `v = 0`, in a statement above this one",
            ),
        }
    }

    fn position_as_number(&self, name: &Name<'_>) -> Diagnostic {
        Diagnostic::new(
            Code::WrongVariableKind,
            self.file,
            name.span,
            format!("`{}` holds a position, not a number", name.text),
        )
        .with_label("a position has x, y and h but no value")
        .with_help("compare positions only with each other (`a == b`), or use the variable where a position is expected (`gotoxy(v)`)")
    }

    /// The condition of `if` or `while`.
    pub fn condition(&mut self, f: &mut Findings, e: &Expr<'_>) {
        match &e.kind {
            // A bare variable means its status; any kind of variable has one.
            ExprKind::Name(name) => {
                if let Some(id) = self.vars.bound(name.text) {
                    f.uses.push((id, name.span));
                    f.refs.push((name.span, Resolved::Variable(id)));
                } else if self.model_constant(name.text).is_some() {
                    f.refs.push((name.span, Resolved::Model));
                } else {
                    f.diags.push(self.unbound(name));
                }
            }
            ExprKind::Compare {
                op,
                op_span,
                lhs,
                rhs,
            } => {
                let a = self.operand(f, lhs);
                let b = self.operand(f, rhs);
                let positions = (a == Value::Position, b == Value::Position);
                match positions {
                    (true, true) if !matches!(op, CmpOp::Eq | CmpOp::Ne) => {
                        f.diags.push(
                            Diagnostic::new(
                                Code::WrongVariableKind,
                                self.file,
                                *op_span,
                                format!("positions cannot be ordered with `{}`", op.symbol()),
                            )
                            .with_label("only `==` and `!=` compare positions"),
                        );
                    }
                    (true, false) | (false, true) if a != Value::Invalid && b != Value::Invalid => {
                        let (side, other) = if positions.0 { (lhs, rhs) } else { (rhs, lhs) };
                        let mut d = Diagnostic::new(
                            Code::WrongVariableKind,
                            self.file,
                            side.span,
                            "a position is compared with a number",
                        )
                        .with_label("this holds a position");
                        d = d.with_secondary(self.file, other.span, "this is a number");
                        f.diags.push(d);
                    }
                    _ => {}
                }
            }
            _ => {
                self.value(f, e);
            }
        }
    }

    /// One side of a comparison: a position variable is allowed here.
    fn operand(&mut self, f: &mut Findings, e: &Expr<'_>) -> Value {
        match &e.kind {
            ExprKind::Name(name) => self.name_value(f, name),
            _ => self.value(f, e),
        }
    }
}

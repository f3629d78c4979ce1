//! The shapes most expressions have (`c<100`, `c+1`, `0.01`: one operand, or two and
//! an operator), decoded once per expression when the module is loaded or grows, so
//! that evaluating one is a load and a `match` (as Lua's `OP_ADDK`/`OP_LTI` take their
//! operands from the instruction) rather than a walk of its postfix ops. Other
//! expressions keep the stack evaluator. Both give the same values: the arithmetic and
//! [`Cmp::holds`] are shared.

use ilmr_stdlib::Field;

use super::vars::Vars;
use super::watch::Cmp;
use crate::bytecode::{ExprOp, Module};

/// A value an expression reads without the stack.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Operand {
    Const(f64),
    Field(u32, Field),
}

impl Operand {
    fn of(op: &ExprOp, consts: &[f64]) -> Option<Operand> {
        match *op {
            ExprOp::Const(c) => Some(Operand::Const(
                consts.get(c.index()).copied().unwrap_or(0.0),
            )),
            ExprOp::Field(v, f) => Some(Operand::Field(v.0, f)),
            _ => None,
        }
    }

    #[inline]
    fn value(self, vars: &Vars) -> f64 {
        match self {
            Operand::Const(c) => c,
            Operand::Field(v, f) => vars.field(v, f),
        }
    }
}

/// An operator of a two-operand shape. Division is left to the stack evaluator,
/// which reports division by zero.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Bin {
    Add,
    Sub,
    Mul,
    Cmp(Cmp),
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Shape {
    One(Operand),
    Two(Operand, Operand, Bin),
    /// Any other expression: the stack evaluator.
    General,
}

/// One decoded expression: its shape and its length in ops, which the tick's budget
/// is charged.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Decoded {
    pub shape: Shape,
    pub len: u32,
}

impl Decoded {
    /// The value of a shape that needs no stack; `None` for [`Shape::General`].
    #[inline]
    pub fn value(&self, vars: &Vars) -> Option<f64> {
        match self.shape {
            Shape::One(x) => Some(x.value(vars)),
            Shape::Two(x, y, op) => {
                let (a, b) = (x.value(vars), y.value(vars));
                Some(match op {
                    Bin::Add => a + b,
                    Bin::Sub => a - b,
                    Bin::Mul => a * b,
                    Bin::Cmp(c) => f64::from(u8::from(c.holds(a, b))),
                })
            }
            Shape::General => None,
        }
    }
}

fn decode(ops: &[ExprOp], consts: &[f64]) -> Shape {
    match ops {
        [x] => Operand::of(x, consts).map_or(Shape::General, Shape::One),
        [x, y, op] => {
            let (Some(a), Some(b)) = (Operand::of(x, consts), Operand::of(y, consts)) else {
                return Shape::General;
            };
            let bin = match *op {
                ExprOp::Add => Bin::Add,
                ExprOp::Sub => Bin::Sub,
                ExprOp::Mul => Bin::Mul,
                other => match Cmp::of(other) {
                    Some(c) => Bin::Cmp(c),
                    None => return Shape::General,
                },
            };
            Shape::Two(a, b, bin)
        }
        _ => Shape::General,
    }
}

/// The decoded expressions of a module, by `ExprId`.
#[derive(Debug, Default)]
pub(crate) struct Decoder {
    pub all: Vec<Decoded>,
}

impl Decoder {
    /// Decodes the expressions the module gained since the last call.
    pub fn grow(&mut self, m: &Module) {
        let from = self.all.len();
        self.all.extend(m.exprs.iter().skip(from).map(|e| {
            let ops = m
                .expr_code
                .get(e.start as usize..(e.start as usize + e.len as usize))
                .unwrap_or(&[]);
            Decoded {
                shape: decode(ops, &m.consts),
                len: ops.len() as u32,
            }
        }));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bytecode::{ConstId, VarId};

    #[test]
    fn common_shapes_decode_and_others_stay_general() {
        let consts = [100.0, 1.0];
        let c = |i| ExprOp::Const(ConstId(i));
        let v = ExprOp::Field(VarId(3), Field::Value);
        assert_eq!(
            decode(&[v, c(0), ExprOp::Lt], &consts),
            Shape::Two(
                Operand::Field(3, Field::Value),
                Operand::Const(100.0),
                Bin::Cmp(Cmp::Lt)
            )
        );
        assert_eq!(decode(&[c(1)], &consts), Shape::One(Operand::Const(1.0)));
        assert_eq!(decode(&[v, c(1), ExprOp::Div], &consts), Shape::General);
        assert_eq!(decode(&[v, ExprOp::Neg], &consts), Shape::General);
        assert_eq!(
            decode(&[v, c(1), ExprOp::Add, c(0), ExprOp::Lt], &consts),
            Shape::General
        );
    }
}

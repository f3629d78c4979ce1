//! Expressions to postfix. Constant parts (literals and robot-model constants) are
//! folded, as the checker folds them to check ranges; a variable reads the field its
//! kind means in a number (`dist`, `value`, `status`), or its status in a bare
//! condition; two positions compared with `==`/`!=` become `POSEQ`.

use ilmr_stdlib::{Field, VarKind};
use ilmr_vm::bytecode::{ExprId, ExprOp, VarId};
use smallvec::{SmallVec, smallvec};

use super::scope::Scope;
use super::stmt::{Lowered, Lowerer};
use super::{build_error, internal};
use crate::ast::{BinOp, CmpOp, Expr, ExprKind, Name};
use crate::check::Resolved;

/// Postfix ops; most expressions of a task fit inline.
type Ops = SmallVec<[ExprOp; 4]>;

/// An expression on its way to postfix.
enum Val {
    Const(f64),
    Ops(Ops),
}

/// A variable read as a number: the field its kind means in one (a position, which
/// has none, reads its status).
fn read((v, kind): (VarId, VarKind)) -> Val {
    Val::Ops(smallvec![ExprOp::Field(
        v,
        kind.numeric_field().unwrap_or(Field::Status),
    )])
}

impl Lowerer<'_> {
    /// A number-valued expression.
    pub fn value(&mut self, sc: &Scope<'_>, e: &Expr<'_>) -> Lowered<ExprId> {
        let v = self.val(sc, e)?;
        self.emit(sc, e, v)
    }

    /// The condition of `if` or `while`.
    pub fn condition(&mut self, sc: &Scope<'_>, e: &Expr<'_>) -> Lowered<ExprId> {
        let v = match &e.kind {
            ExprKind::Name(n) => match self.var(sc, n)? {
                Some((v, _)) => Val::Ops(smallvec![ExprOp::Field(v, Field::Status)]),
                None => Val::Const(self.constant(sc, n)?),
            },
            ExprKind::Compare { op, lhs, rhs, .. } => {
                // Both sides' variables first, then their values: the order in which
                // the module's variables and constants are made.
                let sides = (self.side(sc, lhs)?, self.side(sc, rhs)?);
                if let (Some((a, VarKind::Position)), Some((b, VarKind::Position))) = sides {
                    let mut ops = smallvec![ExprOp::PosEq(a, b)];
                    match op {
                        CmpOp::Eq => {}
                        CmpOp::Ne => {
                            let zero = self
                                .b
                                .constant(0.0)
                                .map_err(|err| build_error(sc.file, e.span, err))?;
                            ops.extend([ExprOp::Const(zero), ExprOp::Eq]);
                        }
                        _ => return Err(internal(sc.file, e.span, "positions cannot be ordered")),
                    }
                    Val::Ops(ops)
                } else {
                    let (a, b) = (
                        self.side_val(sc, lhs, sides.0)?,
                        self.side_val(sc, rhs, sides.1)?,
                    );
                    let cmp = match op {
                        CmpOp::Lt => ExprOp::Lt,
                        CmpOp::Le => ExprOp::Le,
                        CmpOp::Eq => ExprOp::Eq,
                        CmpOp::Ne => ExprOp::Ne,
                        CmpOp::Gt => ExprOp::Gt,
                        CmpOp::Ge => ExprOp::Ge,
                    };
                    self.combine(sc, e, a, b, cmp)?
                }
            }
            _ => self.val(sc, e)?,
        };
        self.emit(sc, e, v)
    }

    fn emit(&mut self, sc: &Scope<'_>, e: &Expr<'_>, v: Val) -> Lowered<ExprId> {
        let r = match v {
            Val::Const(c) => self.b.num(c),
            Val::Ops(ops) => self.b.expr(&ops),
        };
        r.map_err(|err| build_error(sc.file, e.span, err))
    }

    fn val(&mut self, sc: &Scope<'_>, e: &Expr<'_>) -> Lowered<Val> {
        Ok(match &e.kind {
            ExprKind::Number(n) => Val::Const(*n),
            ExprKind::Name(n) => match self.var(sc, n)? {
                Some(var) => read(var),
                None => Val::Const(self.constant(sc, n)?),
            },
            ExprKind::Neg(inner) => match self.val(sc, inner)? {
                Val::Const(c) => Val::Const(-c),
                Val::Ops(mut ops) => {
                    ops.push(ExprOp::Neg);
                    Val::Ops(ops)
                }
            },
            ExprKind::Binary { op, lhs, rhs } => {
                let (a, b) = (self.val(sc, lhs)?, self.val(sc, rhs)?);
                let (fold, code): (fn(f64, f64) -> f64, ExprOp) = match op {
                    BinOp::Add => (|a, b| a + b, ExprOp::Add),
                    BinOp::Sub => (|a, b| a - b, ExprOp::Sub),
                    BinOp::Mul => (|a, b| a * b, ExprOp::Mul),
                    BinOp::Div => (|a, b| a / b, ExprOp::Div),
                };
                match (a, b) {
                    // A constant division by zero is left for the VM to report when
                    // the statement runs, like any other.
                    (Val::Const(x), Val::Const(y)) if !(code == ExprOp::Div && y == 0.0) => {
                        Val::Const(fold(x, y))
                    }
                    (a, b) => self.combine(sc, e, a, b, code)?,
                }
            }
            ExprKind::Compare { .. } | ExprKind::Error => {
                return Err(internal(sc.file, e.span, "not a number"));
            }
        })
    }

    fn combine(
        &mut self,
        sc: &Scope<'_>,
        e: &Expr<'_>,
        a: Val,
        b: Val,
        op: ExprOp,
    ) -> Lowered<Val> {
        let mut ops = self.ops(sc, e, a)?;
        ops.extend(self.ops(sc, e, b)?);
        ops.push(op);
        Ok(Val::Ops(ops))
    }

    fn ops(&mut self, sc: &Scope<'_>, e: &Expr<'_>, v: Val) -> Lowered<Ops> {
        Ok(match v {
            Val::Ops(ops) => ops,
            Val::Const(c) => smallvec![ExprOp::Const(
                self.b
                    .constant(c)
                    .map_err(|err| build_error(sc.file, e.span, err))?,
            )],
        })
    }

    /// A name the checker resolved to a variable, with the kind it has in this unit.
    fn var(&mut self, sc: &Scope<'_>, n: &Name<'_>) -> Lowered<Option<(VarId, VarKind)>> {
        match sc.resolved(n.span) {
            Some(Resolved::Variable(id)) => {
                let kind = sc.vars.get(id).kind;
                Ok(Some((self.slot(sc, id, n.span)?, kind)))
            }
            _ => Ok(None),
        }
    }

    /// A variable standing alone as one side of a comparison (two positions compare
    /// with `POSEQ`).
    fn side(&mut self, sc: &Scope<'_>, e: &Expr<'_>) -> Lowered<Option<(VarId, VarKind)>> {
        match &e.kind {
            ExprKind::Name(n) => self.var(sc, n),
            _ => Ok(None),
        }
    }

    /// The value of a side [`Self::side`] looked at.
    fn side_val(
        &mut self,
        sc: &Scope<'_>,
        e: &Expr<'_>,
        side: Option<(VarId, VarKind)>,
    ) -> Lowered<Val> {
        match side {
            Some(var) => Ok(read(var)),
            None => self.val(sc, e),
        }
    }

    /// `[PARAMETERS]` (with their defaults), `[IDENTIFIERS]` and `[COLORS]`, as the
    /// checker reads them.
    fn constant(&self, sc: &Scope<'_>, n: &Name<'_>) -> Lowered<f64> {
        let m = self.model;
        m.parameter_or_default(n.text)
            .or_else(|| m.identifier(n.text))
            .or_else(|| m.color(n.text))
            .ok_or_else(|| {
                internal(
                    sc.file,
                    n.span,
                    format!("`{}` is neither a variable nor a constant", n.text),
                )
            })
    }
}

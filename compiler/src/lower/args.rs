//! Arguments of an `ISSUE`, resolved against the catalogue form the checker matched:
//! each positional argument is given the parameter it filled (by the checker's own
//! rule for optional parameters), then lowered by that parameter's kind.

use ilmr_stdlib::{Command, Form, ModelNames, Occurs, ParamKind};
use ilmr_vm::bytecode::{Arg, ArgRange};

use super::build_error;
use super::internal;
use super::scope::Scope;
use super::stmt::{Lowered, Lowerer};
use crate::ast::{self, Call, ExprKind};
use crate::check::Resolved;
use crate::span::Span;

fn fits(command: Command, kind: &ParamKind, e: &ast::Expr<'_>) -> bool {
    crate::check::fits(command.spec(), kind, e)
}

/// Pairs each positional argument with the kind of the parameter it fills.
fn assign<'a, 's>(
    command: Command,
    form: &'static Form,
    positional: &[&'a ast::Expr<'s>],
) -> Vec<(&'static ParamKind, &'a ast::Expr<'s>)> {
    let mut out = Vec::with_capacity(positional.len());
    let mut next = 0;
    for param in form
        .params
        .iter()
        .filter(|p| !matches!(p.kind, ParamKind::Setting { .. }))
    {
        match param.occurs {
            Occurs::One => {
                if let Some(e) = positional.get(next) {
                    out.push((&param.kind, *e));
                    next += 1;
                }
            }
            Occurs::Optional => {
                if let Some(e) = positional
                    .get(next)
                    .filter(|e| fits(command, &param.kind, e))
                {
                    out.push((&param.kind, *e));
                    next += 1;
                }
            }
            Occurs::Many | Occurs::Pairs => {
                while let Some(e) = positional.get(next) {
                    out.push((&param.kind, *e));
                    next += 1;
                }
            }
        }
    }
    out
}

impl Lowerer<'_> {
    pub fn args(
        &mut self,
        sc: &Scope<'_>,
        command: Command,
        form: usize,
        call: &Call<'_>,
        span: Span,
    ) -> Lowered<ArgRange> {
        let spec = command.spec();
        let Some(form) = spec.forms.get(form) else {
            return Err(internal(sc.file, span, "the matched form does not exist"));
        };
        let items: &[ast::Arg<'_>] = call.args.as_ref().map_or(&[], |a| &a.items);
        let positional: Vec<&ast::Expr<'_>> = items
            .iter()
            .filter_map(|a| match a {
                ast::Arg::Positional(e) => Some(e),
                ast::Arg::Setting { .. } => None,
            })
            .collect();
        let mut out = Vec::with_capacity(items.len() + 1);
        for (kind, e) in assign(command, form, &positional) {
            out.push(self.arg(sc, command, kind, e)?);
        }
        for item in items {
            if let ast::Arg::Setting { key, value } = item {
                let key = self
                    .b
                    .name(&key.text.to_ascii_lowercase())
                    .map_err(|e| build_error(sc.file, span, e))?;
                out.push(Arg::Setting {
                    key,
                    value: self.value(sc, value)?,
                });
            }
        }
        // Distances the grammar leaves out come from the robot model, so that the VM
        // needs no model of its own.
        let default = match command {
            Command::Approach if positional.len() < 2 => Some(self.model.bs_security()),
            Command::FollowWall if positional.len() < 2 => Some(self.model.followwall_d()),
            _ => None,
        };
        if let Some(d) = default {
            out.push(Arg::Num(
                self.b.num(d).map_err(|e| build_error(sc.file, span, e))?,
            ));
        }
        self.b.args(&out).map_err(|e| build_error(sc.file, span, e))
    }

    fn arg(
        &mut self,
        sc: &Scope<'_>,
        command: Command,
        kind: &ParamKind,
        e: &ast::Expr<'_>,
    ) -> Lowered<Arg> {
        let fail = |what: &str| internal(sc.file, e.span, format!("expected {what} here"));
        let name = match &e.kind {
            ExprKind::Name(n) => Some(*n),
            _ => None,
        };
        let word = |low: &mut Self, text: &str| {
            low.b
                .name(text)
                .map(Arg::Word)
                .map_err(|err| build_error(sc.file, e.span, err))
        };
        match *kind {
            ParamKind::Keyword { words } | ParamKind::Mode { words, .. } => {
                let n = name.ok_or_else(|| fail("a keyword"))?;
                let w = words
                    .iter()
                    .find(|w| n.is(w))
                    .ok_or_else(|| fail("a keyword"))?;
                word(self, w)
            }
            ParamKind::Value { .. } | ParamKind::Setting { .. } => Ok(Arg::Num(self.value(sc, e)?)),
            ParamKind::Model { names } => {
                let model = self.model;
                let canonical: Option<String> = match (&e.kind, names) {
                    (ExprKind::Number(n), ModelNames::Device) if n.fract() == 0.0 => {
                        model.device_by_id(*n as i64).map(|d| d.name.clone())
                    }
                    (ExprKind::Name(n), ModelNames::Device) => {
                        model.device(n.text).map(|d| d.name.clone())
                    }
                    (ExprKind::Name(n), ModelNames::Object) => {
                        model.object(n.text).map(|o| o.name.clone())
                    }
                    (ExprKind::Name(n), ModelNames::Service) => {
                        model.device(n.text).map(|d| d.name.clone()).or_else(|| {
                            model
                                .identifiers
                                .iter()
                                .find(|i| i.name.eq_ignore_ascii_case(n.text))
                                .map(|i| i.name.clone())
                        })
                    }
                    _ => None,
                };
                let c = canonical.ok_or_else(|| fail("a name of the robot model"))?;
                word(self, &c)
            }
            ParamKind::Position | ParamKind::Variable => self
                .variable_of(sc, e)
                .map(Arg::Var)
                .ok_or_else(|| fail("a variable")),
            ParamKind::Name { .. } => {
                let n = name.ok_or_else(|| fail("a name"))?;
                word(self, n.text)
            }
            ParamKind::OneOf { kinds } => {
                // The shape picks the first kind that fits, as in the checker; where a
                // name could be a variable or a model name, its resolution decides.
                let resolved = name.and_then(|n| sc.resolved(n.span));
                let by_resolution = kinds.iter().find(|k| {
                    matches!(
                        (resolved, k),
                        (
                            Some(Resolved::Variable(_)),
                            ParamKind::Position | ParamKind::Variable
                        ) | (Some(Resolved::Model), ParamKind::Model { .. })
                            | (Some(Resolved::Keyword), ParamKind::Keyword { .. })
                    )
                });
                let chosen = by_resolution
                    .or_else(|| kinds.iter().find(|k| fits(command, k, e)))
                    .ok_or_else(|| fail("an argument of this command"))?;
                self.arg(sc, command, chosen, e)
            }
        }
    }
}

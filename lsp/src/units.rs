//! Which parameter each argument of a command fills, in the form the checker matched,
//! and the unit the catalogue (`ilmr_stdlib`) gives it: the inlay hints of units
//! (`speed(0.4 m/s)`) and a number's hover both read it here, so the editor never
//! states a unit the catalogue does not.

use ilmr_compiler::Span;
use ilmr_compiler::ast::{Arg, Args, Block, ExprKind, StmtKind};
use ilmr_compiler::check::{Target, Unit as CheckedUnit, fits};
use ilmr_compiler::diagnostic::FileId;
use ilmr_stdlib::{Command, Form, Param, ParamKind, Unit};

use crate::analysis::Program;
use crate::in_view::statements_reaching;

/// Each argument with the parameter it fills (`None`: more arguments than the form
/// has parameters, or a setting the form does not know).
pub fn params<'a, 's>(
    form: &'static Form,
    args: &'a Args<'s>,
) -> impl Iterator<Item = (&'a Arg<'s>, Option<&'static Param>)> + 'a {
    let mut positional = form
        .params
        .iter()
        .filter(|p| !matches!(p.kind, ParamKind::Setting { .. }));
    let mut repeated: Option<&'static Param> = None;
    args.items.iter().map(move |arg| {
        let param = match arg {
            Arg::Setting { key, .. } => form
                .params
                .iter()
                .find(|p| matches!(p.kind, ParamKind::Setting { key: k, .. } if key.is(k))),
            Arg::Positional(_) => match repeated {
                Some(p) => Some(p),
                None => {
                    let p = positional.next();
                    // `Many` and `Pairs` take every positional argument after them.
                    if let Some(p) = p
                        && matches!(
                            p.occurs,
                            ilmr_stdlib::Occurs::Many | ilmr_stdlib::Occurs::Pairs
                        )
                    {
                        repeated = Some(p);
                    }
                    p
                }
            },
        };
        (arg, param)
    })
}

/// The unit of a value given for `param` of `command`, if it has one.
pub fn unit_of(command: Command, param: &Param, arg: &Arg<'_>) -> Option<Unit> {
    let value = match arg {
        Arg::Positional(e) => e,
        Arg::Setting { value, .. } => &**value,
    };
    // A keyword (`turn(left)`) has no unit, though a number could stand in its place.
    if let ExprKind::Name(n) = &value.kind
        && command.spec().has_keyword(n.text)
    {
        return None;
    }
    let unit = match &param.kind {
        ParamKind::Value { unit, .. } | ParamKind::Setting { unit, .. } => *unit,
        ParamKind::OneOf { kinds } => kinds.iter().find_map(|k| match k {
            ParamKind::Value { unit, .. } if fits(command.spec(), k, value) => Some(*unit),
            _ => None,
        })?,
        _ => return None,
    };
    (unit != Unit::None).then_some(unit)
}

/// A unit's hint: where it goes (after the value) and its symbol.
#[derive(Debug, Clone, PartialEq)]
pub struct UnitHint {
    pub at: usize,
    pub symbol: &'static str,
    /// The parameter's name and documentation, for the tooltip.
    pub param: &'static str,
    pub doc: &'static str,
}

/// The units of the arguments of the command calls that start inside `range`.
pub fn hints(program: &Program, file: FileId, range: Span) -> Vec<UnitHint> {
    let units: Vec<&CheckedUnit> = program.units_of(file).collect();
    let tree = program.tree(file);
    let mut out = Vec::new();
    walk(&tree.blocks, range, &units, &mut out);
    for skill in &tree.skills {
        if skill.span.start <= range.end && range.start <= skill.span.end {
            walk(&skill.blocks, range, &units, &mut out);
        }
    }
    out
}

fn walk(blocks: &[Block<'_>], range: Span, units: &[&CheckedUnit], out: &mut Vec<UnitHint>) {
    for stmt in statements_reaching(blocks, range) {
        match &stmt.kind {
            StmtKind::Call {
                call:
                    ilmr_compiler::ast::Call {
                        args: Some(args), ..
                    },
                ..
            } if stmt.span.start >= range.start => {
                let target = units.iter().find_map(|u| u.targets.get(&stmt.span));
                let Some(&Target::Command { command, form }) = target else {
                    continue;
                };
                let form = &command.spec().forms[form];
                for (arg, param) in params(form, args) {
                    let Some(param) = param else { continue };
                    if let Some(unit) = unit_of(command, param, arg) {
                        out.push(UnitHint {
                            at: arg.span().end as usize,
                            symbol: unit.symbol(),
                            param: param.name,
                            doc: param.doc,
                        });
                    }
                }
            }
            StmtKind::If(c) | StmtKind::While { body: c, .. } => {
                walk(&c.body, range, units, out);
            }
            _ => {}
        }
    }
}

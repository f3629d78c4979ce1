//! A command's arguments against the forms of its catalogue entry. Every form is tried;
//! the one that fits with the fewest problems is taken, and only its problems are
//! reported, so `turn(lft)` says "did you mean `left`?" rather than listing every form.

use ilmr_model::Device;
use smallvec::SmallVec;

use ilmr_stdlib::units;
use ilmr_stdlib::{
    CommandSpec, Form, Limit, ModelNames, NameSpace, Occurs, ParamKind, Range, Unit, VarKind,
};

use crate::ast::{Arg, Args, Expr, ExprKind, Name};
use crate::check::expr::Value;
use crate::check::keywords::is_keyword;
use crate::check::suggest;
use crate::check::{Cx, Findings, Resolved};
use crate::diagnostic::{Code, Diagnostic};
use crate::span::Span;

/// The outcome of matching one form.
pub struct FormMatch<'s> {
    pub form: usize,
    pub findings: Findings,
    /// Names a `savepos` binds as position variables.
    pub binds_position: Option<Name<'s>>,
    cost: u32,
}

/// Costs rank the forms: a wrong count outweighs a wrong kind, and a word that is no
/// keyword and close to none is more likely a variable than a typo.
const COST_COUNT: u32 = 10;
const COST_KIND: u32 = 2;
const COST_STRANGER: u32 = 3;

impl<'m, 'v> Cx<'m, 'v> {
    pub fn match_forms<'s>(
        &mut self,
        spec: &'static CommandSpec,
        args: Option<&Args<'s>>,
        at: Span,
    ) -> FormMatch<'s> {
        let items: &[Arg<'s>] = args.map_or(&[], |a| &a.items);
        let mut best: Option<FormMatch<'s>> = None;
        // Forms whose shape fits the arguments first: a correct call then matches its
        // form at the first try, and no messages are built for forms it never meant.
        if let [form] = spec.forms {
            return self.match_form(spec, 0, form, items, at);
        }
        // Plausibility is asked lazily: a correct call usually fits a form before the
        // last, and the forms after it are never looked at.
        let mut plausible: SmallVec<[Option<bool>; 8]> =
            smallvec::smallvec![None; spec.forms.len()];
        let order = [true, false]
            .into_iter()
            .flat_map(|wanted| (0..spec.forms.len()).map(move |i| (wanted, i)));
        for (wanted, i) in order {
            let form = &spec.forms[i];
            let fits = match plausible[i] {
                Some(known) => known,
                None => *plausible[i].insert(self.plausible(spec, form, items)),
            };
            if fits != wanted {
                continue;
            }
            let m = self.match_form(spec, i, form, items, at);
            if m.cost == 0 {
                if let Some(b) = best {
                    self.discard(b.findings);
                }
                return m;
            }
            // Ties go to the catalogue's order, not to the order of trying.
            let better = best
                .as_ref()
                .is_none_or(|b| (m.cost, m.form) < (b.cost, b.form));
            let loser = if better { best.replace(m) } else { Some(m) };
            if let Some(loser) = loser {
                self.discard(loser.findings);
            }
        }
        best.expect("call commands have at least one form")
    }

    fn match_form<'s>(
        &mut self,
        spec: &'static CommandSpec,
        index: usize,
        form: &'static Form,
        items: &[Arg<'s>],
        at: Span,
    ) -> FormMatch<'s> {
        let mut m = FormMatch {
            form: index,
            findings: self.findings(),
            binds_position: None,
            cost: 0,
        };
        let positional: SmallVec<[&Expr<'s>; 8]> = items
            .iter()
            .filter_map(|a| match a {
                Arg::Positional(e) => Some(e),
                Arg::Setting { .. } => None,
            })
            .collect();
        let mut device: Option<&'m Device> = None;
        let mut next = 0;
        for param in form
            .params
            .iter()
            .filter(|p| !matches!(p.kind, ParamKind::Setting { .. }))
        {
            match param.occurs {
                Occurs::One => match positional.get(next) {
                    Some(e) => {
                        self.accept(&mut m, spec, param.name, &param.kind, e, &mut device);
                        next += 1;
                    }
                    None => {
                        m.cost += COST_COUNT;
                        let span = positional
                            .last()
                            .map_or(at, |e| Span::empty(e.span.end as usize));
                        m.findings.diags.push(self.count_error(
                            spec,
                            span,
                            format!("`{}` is missing its {} argument", spec.name, param.name),
                        ));
                    }
                },
                Occurs::Optional => {
                    if let Some(e) = positional.get(next)
                        && self.fits(spec, &param.kind, e)
                    {
                        self.accept(&mut m, spec, param.name, &param.kind, e, &mut device);
                        next += 1;
                    }
                }
                Occurs::Many => {
                    while let Some(e) = positional.get(next) {
                        self.accept(&mut m, spec, param.name, &param.kind, e, &mut device);
                        next += 1;
                    }
                }
                Occurs::Pairs => {
                    let rest = &positional[next.min(positional.len())..];
                    for e in rest {
                        self.accept(&mut m, spec, param.name, &param.kind, e, &mut device);
                    }
                    if rest.len() % 2 == 1 {
                        m.cost += COST_COUNT;
                        let last = rest[rest.len() - 1];
                        m.findings.diags.push(self.count_error(
                            spec,
                            last.span,
                            "coordinates come in x, y pairs; this x has no y".to_string(),
                        ));
                    }
                    next = positional.len();
                }
            }
        }
        if let Some(extra) = positional.get(next) {
            m.cost += COST_COUNT * (positional.len() - next) as u32;
            let d = self.extra_argument(spec, form, extra);
            m.findings.diags.push(d);
        }
        self.settings(&mut m, spec, form, items, at);
        if items.len() < form.min_args as usize && m.cost == 0 {
            m.cost += COST_COUNT;
            m.findings.diags.push(self.count_error(
                spec,
                at,
                format!(
                    "`{}` needs at least {} argument(s)",
                    spec.name, form.min_args
                ),
            ));
        }
        m
    }

    /// Whether the arguments have the shape of this form: their count, their setting
    /// keys and, for the required parameters, names where names belong.
    fn plausible(&mut self, spec: &CommandSpec, form: &Form, items: &[Arg<'_>]) -> bool {
        let mut positional = items.iter().filter_map(|a| match a {
            Arg::Positional(e) => Some(e),
            Arg::Setting { .. } => None,
        });
        let settings_fit = items.iter().all(|a| match a {
            Arg::Setting { key, .. } => form
                .params
                .iter()
                .any(|p| matches!(p.kind, ParamKind::Setting { key: k, .. } if key.is(k))),
            Arg::Positional(_) => true,
        });
        let required_settings = form.params.iter().all(|p| match p.kind {
            ParamKind::Setting { key, .. } if p.occurs == Occurs::One => items
                .iter()
                .any(|a| matches!(a, Arg::Setting { key: k, .. } if k.is(key))),
            _ => true,
        });
        if !settings_fit || !required_settings {
            return false;
        }
        let mut max = 0usize;
        let mut unbounded = false;
        for p in form
            .params
            .iter()
            .filter(|p| !matches!(p.kind, ParamKind::Setting { .. }))
        {
            match p.occurs {
                Occurs::One => match positional.next() {
                    Some(e) if self.fits(spec, &p.kind, e) => max += 1,
                    _ => return false,
                },
                Occurs::Optional => max += 1,
                Occurs::Many | Occurs::Pairs => unbounded = true,
            }
        }
        let given = items
            .iter()
            .filter(|a| matches!(a, Arg::Positional(_)))
            .count();
        unbounded || given <= max
    }

    fn count_error(&self, spec: &CommandSpec, span: Span, message: String) -> Diagnostic {
        Diagnostic::new(Code::ArgumentCount, self.file, span, message)
            .with_label("wrong number of arguments")
            .with_help(format!("the grammar is:\n{}", spec.grammar))
    }

    fn extra_argument(&self, spec: &CommandSpec, form: &Form, extra: &Expr<'_>) -> Diagnostic {
        // A typo of an optional keyword reads better as "did you mean" than as "too many".
        if let ExprKind::Name(name) = &extra.kind {
            let words: Vec<&str> = form
                .params
                .iter()
                .flat_map(|p| keyword_words(&p.kind))
                .collect();
            let misplaced = words.iter().any(|w| name.is(w));
            if let Some(s) =
                suggest::closest(name.text, words.iter().copied()).filter(|_| !misplaced)
            {
                return Diagnostic::new(
                    Code::UnknownKeyword,
                    self.file,
                    name.span,
                    format!("`{}` is not a keyword of `{}`", name.text, spec.name),
                )
                .with_label(format!("did you mean `{s}`?"))
                .with_fix(format!("replace with `{s}`"), name.span, s);
            }
        }
        self.count_error(
            spec,
            extra.span,
            format!("`{}` does not take this many arguments", spec.name),
        )
        .with_label("one argument too many")
    }

    fn fits(&self, spec: &CommandSpec, kind: &ParamKind, e: &Expr<'_>) -> bool {
        fits(spec, kind, e)
    }

    fn accept<'s>(
        &mut self,
        m: &mut FormMatch<'s>,
        spec: &CommandSpec,
        param: &str,
        kind: &ParamKind,
        e: &Expr<'s>,
        device: &mut Option<&'m Device>,
    ) {
        let name = match &e.kind {
            ExprKind::Name(n) => Some(*n),
            _ => None,
        };
        match *kind {
            ParamKind::Keyword { words } => match name {
                Some(n) if words.iter().any(|w| n.is(w)) => {
                    m.findings.refs.push((n.span, Resolved::Keyword));
                }
                _ => self.not_a_keyword(m, spec, words, e),
            },
            ParamKind::Mode { words, what } => match name {
                Some(n) if words.iter().any(|w| n.is(w)) => {
                    m.findings.refs.push((n.span, Resolved::Keyword));
                    if self.model.identifier(n.text).is_none() {
                        m.cost += COST_KIND;
                        m.findings.diags.push(
                            Diagnostic::new(
                                Code::UnsupportedMode,
                                self.file,
                                n.span,
                                format!("robot `{}` has no {what} `{}`", self.model.name, n.text),
                            )
                            .with_label(format!(
                                "not among the [IDENTIFIERS] of {}",
                                self.model.name
                            )),
                        );
                    }
                }
                _ => self.not_a_keyword(m, spec, words, e),
            },
            ParamKind::Value { range, unit } => {
                let v = self.value(&mut m.findings, e);
                if let Value::Const(v) = v {
                    self.check_range(m, spec, param, range, v, e.span, *device);
                    self.suspect_unit(m, spec, param, unit, range, e);
                } else if v == Value::Invalid {
                    m.cost += COST_KIND;
                }
            }
            ParamKind::Setting { .. } => unreachable!("settings are matched by key"),
            ParamKind::Model { names } => self.model_name(m, names, e, device),
            ParamKind::Position => self.variable(m, e, true),
            ParamKind::Variable => self.variable(m, e, false),
            ParamKind::Name { space } => match name {
                Some(n) => {
                    m.findings.refs.push((n.span, Resolved::Path));
                    if space == NameSpace::SavedPosition {
                        m.binds_position = Some(n);
                    }
                }
                None => self.wrong_kind(m, e, "a name"),
            },
            ParamKind::OneOf { kinds } => match self
                .object_for_unbound(kinds, name)
                .or_else(|| kinds.iter().find(|k| self.fits(spec, k, e)))
            {
                Some(chosen) => self.accept(m, spec, param, chosen, e, device),
                None => {
                    let expected: Vec<String> = kinds.iter().map(describe).collect();
                    self.wrong_kind(m, e, &expected.join(" or "));
                }
            },
        }
    }

    /// `approach(door)`: a name that no variable has but an object of the model has is
    /// that object where the argument may be one (otherwise the first kind that fits, a
    /// position variable, would call it unbound).
    fn object_for_unbound<'k>(
        &mut self,
        kinds: &'k [ParamKind],
        name: Option<Name<'_>>,
    ) -> Option<&'k ParamKind> {
        let n = name?;
        if self.vars.bound(n.text).is_some() || self.model.object(n.text).is_none() {
            return None;
        }
        kinds.iter().find(|k| {
            matches!(
                k,
                ParamKind::Model {
                    names: ModelNames::Object
                }
            )
        })
    }

    fn not_a_keyword(
        &mut self,
        m: &mut FormMatch<'_>,
        spec: &CommandSpec,
        words: &[&str],
        e: &Expr<'_>,
    ) {
        let ExprKind::Name(n) = &e.kind else {
            m.cost += COST_KIND;
            m.findings.diags.push(
                Diagnostic::new(
                    Code::ArgumentKind,
                    self.file,
                    e.span,
                    format!("`{}` expects {} here", spec.name, suggest::one_of(words)),
                )
                .with_label("not a keyword"),
            );
            return;
        };
        let d = Diagnostic::new(
            Code::UnknownKeyword,
            self.file,
            n.span,
            format!("`{}` is not a keyword `{}` accepts here", n.text, spec.name),
        );
        match suggest::closest(n.text, words.iter().copied()) {
            Some(s) => {
                m.cost += COST_KIND;
                m.findings
                    .diags
                    .push(d.with_label(format!("did you mean `{s}`?")).with_fix(
                        format!("replace with `{s}`"),
                        n.span,
                        s,
                    ));
            }
            None => {
                m.cost += COST_STRANGER;
                m.findings
                    .diags
                    .push(d.with_label(format!("expected {}", suggest::one_of(words))));
            }
        }
    }

    fn wrong_kind(&mut self, m: &mut FormMatch<'_>, e: &Expr<'_>, expected: &str) {
        // A number where a name belongs (or the reverse) says this form was not meant.
        m.cost += COST_STRANGER;
        m.findings.diags.push(
            Diagnostic::new(
                Code::ArgumentKind,
                self.file,
                e.span,
                format!("expected {expected} here"),
            )
            .with_label(format!("this is not {expected}")),
        );
    }

    fn variable(&mut self, m: &mut FormMatch<'_>, e: &Expr<'_>, position: bool) {
        let ExprKind::Name(n) = &e.kind else {
            return self.wrong_kind(
                m,
                e,
                if position {
                    "a position variable"
                } else {
                    "a variable"
                },
            );
        };
        let Some(id) = self.vars.bound(n.text) else {
            m.cost += COST_KIND;
            let d = self.unbound(n);
            m.findings.diags.push(d);
            return;
        };
        m.findings.uses.push((id, n.span));
        m.findings.refs.push((n.span, Resolved::Variable(id)));
        let kind = self.vars.get(id).kind;
        if position && !kind.is_position() {
            m.cost += COST_KIND;
            m.findings.diags.push(
                Diagnostic::new(
                    Code::WrongVariableKind,
                    self.file,
                    n.span,
                    format!("`{}` is {}, not a position", n.text, kind.describe()),
                )
                .with_label("a position is needed here")
                .with_help(
                    "positions come from `sensor(scanner,object)`, `findtarget`, `savepos` and movement commands",
                ),
            );
        }
    }

    fn model_name(
        &mut self,
        m: &mut FormMatch<'_>,
        names: ModelNames,
        e: &Expr<'_>,
        device: &mut Option<&'m Device>,
    ) {
        let model = self.model;
        match (&e.kind, names) {
            (ExprKind::Number(n), ModelNames::Device) => {
                match model.device_by_id(*n as i64).filter(|_| n.fract() == 0.0) {
                    Some(d) => *device = Some(d),
                    None => {
                        m.cost += COST_KIND;
                        m.findings.diags.push(
                            Diagnostic::new(
                                Code::UnknownDevice,
                                self.file,
                                e.span,
                                format!(
                                    "robot `{}` has no sensor or actuator number {n}",
                                    model.name
                                ),
                            )
                            .with_label("not in [SENSORSANDACTUATORS]"),
                        );
                    }
                }
            }
            (ExprKind::Name(n), _) => {
                let found = match names {
                    ModelNames::Device => model
                        .device(n.text)
                        .inspect(|d| *device = Some(d))
                        .is_some(),
                    ModelNames::Object => model.object(n.text).is_some(),
                    ModelNames::Service => {
                        model.device(n.text).is_some() || model.identifier(n.text).is_some()
                    }
                };
                if found {
                    m.findings.refs.push((n.span, Resolved::Model));
                    return;
                }
                m.cost += COST_KIND;
                let (code, what, section, candidates): (Code, &str, &str, Vec<&str>) = match names {
                    ModelNames::Device => (
                        Code::UnknownDevice,
                        "sensor or actuator",
                        "[SENSORSANDACTUATORS]",
                        model.devices.iter().map(|d| d.name.as_str()).collect(),
                    ),
                    ModelNames::Object => (
                        Code::UnknownObject,
                        "object",
                        "[OBJECTS]",
                        model.objects.iter().map(|o| o.name.as_str()).collect(),
                    ),
                    ModelNames::Service => (
                        Code::UnknownService,
                        "sensor or service",
                        "[SENSORSANDACTUATORS] or [IDENTIFIERS]",
                        model
                            .devices
                            .iter()
                            .map(|d| d.name.as_str())
                            .chain(model.identifiers.iter().map(|i| i.name.as_str()))
                            .collect(),
                    ),
                };
                let d = Diagnostic::new(
                    code,
                    self.file,
                    n.span,
                    format!("robot `{}` has no {what} `{}`", model.name, n.text),
                );
                m.findings
                    .diags
                    .push(match suggest::closest(n.text, candidates) {
                        Some(s) => d.with_label(format!("did you mean `{s}`?")).with_fix(
                            format!("replace with `{s}`"),
                            n.span,
                            s,
                        ),
                        None => d.with_label(format!("not in {section} of the robot model")),
                    });
            }
            _ => self.wrong_kind(m, e, &describe(&ParamKind::Model { names })),
        }
    }

    fn settings<'s>(
        &mut self,
        m: &mut FormMatch<'s>,
        spec: &CommandSpec,
        form: &Form,
        items: &[Arg<'s>],
        at: Span,
    ) {
        let keys: Vec<&str> = form
            .params
            .iter()
            .filter_map(|p| match p.kind {
                ParamKind::Setting { key, .. } => Some(key),
                _ => None,
            })
            .collect();
        let mut seen: Vec<(&str, Span)> = Vec::new();
        for item in items {
            let Arg::Setting { key, value } = item else {
                continue;
            };
            let param = form.params.iter().find(|p| match p.kind {
                ParamKind::Setting { key: k, .. } => key.is(k),
                _ => false,
            });
            let Some(param) = param else {
                m.cost += COST_COUNT;
                let d = Diagnostic::new(
                    Code::BadSetting,
                    self.file,
                    key.span,
                    if keys.is_empty() {
                        format!("`{}` takes no named settings here", spec.name)
                    } else {
                        format!("`{}` has no setting `{}`", spec.name, key.text)
                    },
                );
                m.findings
                    .diags
                    .push(match suggest::closest(key.text, keys.iter().copied()) {
                        Some(s) => d.with_label(format!("did you mean `{s}=`?")).with_fix(
                            format!("replace with `{s}`"),
                            key.span,
                            s,
                        ),
                        None if keys.is_empty() => d.with_label("not a setting of this form"),
                        None => {
                            d.with_label(format!("its settings are {}", suggest::one_of(&keys)))
                        }
                    });
                self.value(&mut m.findings, value);
                continue;
            };
            let ParamKind::Setting {
                key: k,
                range,
                unit,
            } = param.kind
            else {
                unreachable!()
            };
            if let Some((_, first)) = seen.iter().find(|(s, _)| *s == k) {
                m.cost += COST_KIND;
                m.findings.diags.push(
                    Diagnostic::new(
                        Code::BadSetting,
                        self.file,
                        key.span,
                        format!("setting `{k}` is given twice"),
                    )
                    .with_label("given again here")
                    .with_secondary(self.file, *first, "first given here"),
                );
            }
            seen.push((k, key.span));
            m.findings.refs.push((key.span, Resolved::Keyword));
            if let Value::Const(v) = self.value(&mut m.findings, value) {
                self.check_range(m, spec, k, range, v, value.span, None);
                self.suspect_unit(m, spec, k, unit, range, value);
            }
        }
        for param in form.params {
            if let ParamKind::Setting { key, .. } = param.kind
                && param.occurs == Occurs::One
                && !seen.iter().any(|(s, _)| *s == key)
            {
                m.cost += COST_COUNT;
                m.findings.diags.push(
                    Diagnostic::new(
                        Code::BadSetting,
                        self.file,
                        at,
                        format!("`{}` needs the setting `{key}=` ({})", spec.name, param.doc),
                    )
                    .with_label(format!("`{key}=` is missing"))
                    .with_help(format!("the grammar is:\n{}", spec.grammar)),
                );
            }
        }
    }

    #[allow(clippy::too_many_arguments)]
    fn check_range(
        &mut self,
        m: &mut FormMatch<'_>,
        spec: &CommandSpec,
        param: &str,
        range: Range,
        v: f64,
        span: Span,
        device: Option<&Device>,
    ) {
        let model = self.model;
        let constants = self.constants;
        let param_bound = |param: &str| constants.parameter_or_default(param, model);
        // The message text is built only for a value out of range: this runs for every
        // constant argument of a program.
        let (ok, limit, bound): (bool, Limit, Box<dyn Fn() -> String + '_>) = match range {
            Range::Any => return,
            Range::Between { min, max, limit } => (
                (min..=max).contains(&v),
                limit,
                Box::new(move || format!("between {min} and {max}")),
            ),
            Range::Positive => (v > 0.0, Limit::Refuse, Box::new(|| "greater than 0".into())),
            Range::NonNegative => (v >= 0.0, Limit::Refuse, Box::new(|| "0 or more".into())),
            Range::Symmetric {
                param: bound,
                limit,
            }
            | Range::Magnitude {
                param: bound,
                limit,
            } => {
                let Some(p) = param_bound(bound) else {
                    return self.unsupported(m, bound, span);
                };
                (
                    v.abs() <= p,
                    limit,
                    Box::new(move || format!("within ±{p} (`{bound}` of {})", model.name)),
                )
            }
            Range::UpTo {
                param: bound,
                limit,
            } => {
                let Some(p) = param_bound(bound) else {
                    return self.unsupported(m, bound, span);
                };
                (
                    (0.0..=p).contains(&v),
                    limit,
                    Box::new(move || format!("between 0 and {p} (`{bound}` of {})", model.name)),
                )
            }
            Range::DeviceRange => {
                let Some(d) = device else { return };
                (
                    (d.min..=d.max).contains(&v),
                    Limit::Refuse,
                    Box::new(move || {
                        format!(
                            "between {} and {} (the range of `{}`)",
                            d.min, d.max, d.name
                        )
                    }),
                )
            }
            Range::ReadingIndex => {
                let Some(d) = device else { return };
                if v.fract() == 0.0 && v >= 0.0 && v < f64::from(d.readings) {
                    return;
                }
                m.cost += COST_KIND;
                m.findings.diags.push(
                    Diagnostic::new(
                        Code::ReadingIndex,
                        self.file,
                        span,
                        format!("`{}` has no reading number {v}", d.name),
                    )
                    .with_label(format!(
                        "readings are numbered 0 to {}",
                        d.readings.saturating_sub(1)
                    )),
                );
                return;
            }
        };
        if ok {
            return;
        }
        let (code, message) = match limit {
            Limit::Refuse => (
                Code::OutOfRange,
                format!("{v} is out of range for the {param} of `{}`", spec.name),
            ),
            Limit::Warn => (
                Code::BeyondCapability,
                format!(
                    "{v} is beyond what {} can do as the {param} of `{}`",
                    model.name, spec.name
                ),
            ),
        };
        if code == Code::OutOfRange {
            m.cost += COST_KIND;
        }
        m.findings.diags.push(
            Diagnostic::new(code, self.file, span, message)
                .with_label(format!("must be {}", bound())),
        );
    }

    /// W0409: a number written out that looks like another unit, where its value in
    /// that unit is one the argument admits.
    fn suspect_unit(
        &mut self,
        m: &mut FormMatch<'_>,
        spec: &CommandSpec,
        param: &str,
        unit: Unit,
        range: Range,
        e: &Expr<'_>,
    ) {
        let written = match &e.kind {
            ExprKind::Number(v) => *v,
            ExprKind::Neg(inner) => match inner.kind {
                ExprKind::Number(v) => -v,
                _ => return,
            },
            _ => return,
        };
        // A position is not a distance: outdoors (Workpartner's yard) a coordinate of
        // hundreds of metres is ordinary, and would read as centimetres.
        if matches!(param, "x" | "y") {
            return;
        }
        let Some(suspect) = units::suspect(unit, written) else {
            return;
        };
        if !self.admits(range, suspect.meant) {
            return;
        }
        let exact = units::round_for_people(suspect.meant);
        let meant = units::round_for_people(suspect.likely);
        let about = if meant == exact {
            String::new()
        } else {
            format!(", about {meant}")
        };
        let number = units::round_for_people(written);
        m.findings.diags.push(
            Diagnostic::new(
                Code::SuspectUnit,
                self.file,
                e.span,
                format!(
                    "{number} {} as the `{param}` of `{}` looks like {}",
                    unit.words(),
                    spec.name,
                    suspect.looks_like
                ),
            )
            .with_label(format!(
                "the {param} is in {} ({})",
                unit.words(),
                unit.symbol()
            ))
            .with_help(format!(
                "{number} {} is {exact} {}{about}: write `{meant}` if that was meant",
                suspect.looks_like,
                unit.symbol()
            ))
            .with_fix(format!("replace with `{meant}`"), e.span, meant),
        );
    }

    /// Whether a number range admits `v`; ranges that depend on a device admit nothing.
    fn admits(&self, range: Range, v: f64) -> bool {
        let bound = |param: &str| self.constants.parameter_or_default(param, self.model);
        match range {
            Range::Any => true,
            Range::Between { min, max, .. } => (min..=max).contains(&v),
            Range::Positive => v > 0.0,
            Range::NonNegative => v >= 0.0,
            Range::Symmetric { param, .. } | Range::Magnitude { param, .. } => {
                bound(param).is_some_and(|p| v.abs() <= p)
            }
            Range::UpTo { param, .. } => bound(param).is_some_and(|p| (0.0..=p).contains(&v)),
            Range::DeviceRange | Range::ReadingIndex => false,
        }
    }

    fn unsupported(&mut self, m: &mut FormMatch<'_>, param: &str, span: Span) {
        m.cost += COST_KIND;
        m.findings.diags.push(
            Diagnostic::new(
                Code::Unsupported,
                self.file,
                span,
                format!(
                    "robot `{}` cannot do this: its model has no `{param}`",
                    self.model.name
                ),
            )
            .with_label(format!("needs `{param}` in [PARAMETERS]")),
        );
    }
}

/// Whether an optional parameter takes this argument, by its shape only. The lowering
/// uses the same rule to pair arguments with the parameters they filled.
pub fn fits(spec: &CommandSpec, kind: &ParamKind, e: &Expr<'_>) -> bool {
    let name = match &e.kind {
        ExprKind::Name(n) => Some(n.text),
        _ => None,
    };
    match kind {
        ParamKind::Keyword { words } | ParamKind::Mode { words, .. } => {
            name.is_some_and(|n| words.iter().any(|w| w.eq_ignore_ascii_case(n)))
        }
        ParamKind::OneOf { kinds } => kinds.iter().any(|k| fits(spec, k, e)),
        ParamKind::Model {
            names: ModelNames::Device,
        } => matches!(e.kind, ExprKind::Number(_)) || name.is_some_and(|n| !is_keyword(spec, n)),
        ParamKind::Value { .. } => name.is_none_or(|n| !is_keyword(spec, n)),
        _ => name.is_some_and(|n| !is_keyword(spec, n)),
    }
}

/// What a parameter accepts, in words, for messages.
fn describe(kind: &ParamKind) -> String {
    match *kind {
        ParamKind::Keyword { words } | ParamKind::Mode { words, .. } => suggest::one_of(words),
        ParamKind::Value { .. } | ParamKind::Setting { .. } => "a number".into(),
        ParamKind::Model {
            names: ModelNames::Device,
        } => "a sensor or actuator of the robot model".into(),
        ParamKind::Model {
            names: ModelNames::Object,
        } => "an object of the robot model".into(),
        ParamKind::Model {
            names: ModelNames::Service,
        } => "a sensor or service of the robot model".into(),
        ParamKind::Position => "a position variable".into(),
        ParamKind::Variable => "a variable".into(),
        ParamKind::Name { .. } => "a name".into(),
        ParamKind::OneOf { kinds } => kinds.iter().map(describe).collect::<Vec<_>>().join(" or "),
    }
}

fn keyword_words(kind: &ParamKind) -> Vec<&'static str> {
    match *kind {
        ParamKind::Keyword { words } | ParamKind::Mode { words, .. } => words.to_vec(),
        ParamKind::OneOf { kinds } => kinds.iter().flat_map(keyword_words).collect(),
        _ => Vec::new(),
    }
}

/// What a variable bound to this command holds.
pub fn produced(spec: &CommandSpec, form: usize) -> VarKind {
    spec.forms.get(form).map_or(VarKind::Status, |f| f.produces)
}

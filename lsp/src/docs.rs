//! Markdown for hovers, completion items and signatures, read from the catalogue and
//! the robot model. Ranges that name a model parameter (`max_speed`) are shown with the
//! robot's value, since that is the bound the checker applies.

use std::fmt::Write;

use ilmr_model::{ModelName, RobotModel, parameter_spec};
use ilmr_stdlib::{CommandSpec, Form, Limit, ModelNames, Occurs, Param, ParamKind, Range, Unit};

pub fn command(spec: &CommandSpec, model: &RobotModel) -> String {
    let mut out = format!(
        "**{}** — {}\n\n{}\n",
        spec.title,
        spec.category.title(),
        spec.summary
    );
    if !spec.doc.is_empty() {
        let _ = write!(out, "\n{}\n", spec.doc);
    }
    let _ = write!(out, "\n```bnf\n{}\n```\n", spec.grammar);
    for form in spec.forms {
        out.push('\n');
        out.push_str(&form_text(form, model));
    }
    if !spec.examples.is_empty() {
        let examples: Vec<String> = spec
            .examples
            .iter()
            .map(|e| format!("`{}`", e.replace('\n', "` / `")))
            .collect();
        let _ = write!(out, "\nExamples: {}\n", examples.join(", "));
    }
    let _ = write!(out, "\n*Section {} of the dissertation.*", spec.section);
    out
}

fn form_text(form: &Form, model: &RobotModel) -> String {
    let mut out = format!(
        "- **{}**: a bound variable holds {}\n",
        form.label,
        form.produces.describe()
    );
    for p in form.params {
        let _ = writeln!(out, "  - {}", param(p, model));
    }
    out
}

/// One parameter: name, what it accepts (units and the robot's range) and its doc.
pub fn param(p: &Param, model: &RobotModel) -> String {
    let occurs = match p.occurs {
        Occurs::One => "",
        Occurs::Optional => " (optional)",
        Occurs::Many => " (any number)",
        Occurs::Pairs => " (x, y pairs)",
    };
    format!("`{}`{occurs}: {} — {}", p.name, kind(&p.kind, model), p.doc)
}

pub fn kind(kind: &ParamKind, model: &RobotModel) -> String {
    match *kind {
        ParamKind::Keyword { words } => words.join(" \\| "),
        ParamKind::Mode { words, what } => {
            let defined: Vec<&str> = words
                .iter()
                .copied()
                .filter(|w| model.identifier(w).is_some())
                .collect();
            if defined.is_empty() {
                format!("{what}: none on robot `{}`", model.name)
            } else {
                format!("{what}: {}", defined.join(" \\| "))
            }
        }
        ParamKind::Value { unit, range } => format!("number{}", bounds(unit, range, model)),
        ParamKind::Setting { key, unit, range } => {
            format!("`{key}=` number{}", bounds(unit, range, model))
        }
        ParamKind::Model { names } => match names {
            ModelNames::Device => "a sensor or actuator of the model, by name or number".into(),
            ModelNames::Object => "an object of the model".into(),
            ModelNames::Service => "a sensor or service of the model".into(),
        },
        ParamKind::Position => "a variable holding a position".into(),
        ParamKind::Variable => "a variable".into(),
        ParamKind::Name { .. } => "a name".into(),
        ParamKind::OneOf { kinds } => kinds
            .iter()
            .map(|k| self::kind(k, model))
            .collect::<Vec<_>>()
            .join(" or "),
    }
}

fn bounds(unit: Unit, range: Range, model: &RobotModel) -> String {
    let limit = |l: Limit| match l {
        Limit::Refuse => "refused outside",
        Limit::Warn => "warned outside",
    };
    let value = |param: &str| {
        model
            .parameter_or_default(param)
            .map_or(format!("`{param}`"), |v| format!("{v} (`{param}`)"))
    };
    let range = match range {
        Range::Any => String::new(),
        Range::Between { min, max, limit: l } => format!("{} {min} … {max}", limit(l)),
        Range::Positive => "greater than 0".into(),
        Range::NonNegative => "0 or more".into(),
        Range::Symmetric { param, limit: l } | Range::Magnitude { param, limit: l } => {
            format!("{} ±{}", limit(l), value(param))
        }
        Range::UpTo { param, limit: l } => format!("{} 0 … {}", limit(l), value(param)),
        Range::DeviceRange => "within the actuator's range in the model".into(),
        Range::ReadingIndex => "0 … readings − 1 of the sensor".into(),
    };
    let parts: Vec<&str> = [unit.symbol(), range.as_str()]
        .into_iter()
        .filter(|s| !s.is_empty())
        .collect();
    if parts.is_empty() {
        String::new()
    } else {
        format!(" [{}]", parts.join(", "))
    }
}

/// What a name of the robot model stands for, as ROBO.INI defines it.
pub fn model_name(name: ModelName<'_>, model: &RobotModel) -> String {
    let source = model
        .source
        .as_ref()
        .map_or(format!("robot `{}`", model.name), |p| {
            format!("`{}`", p.display())
        });
    let line = match name.line() {
        0 => "a default of the toolchain".to_string(),
        n => format!("line {n} of {source}"),
    };
    match name {
        ModelName::Device(d) => format!(
            "**{}** — sensor or actuator {} of robot `{}`\n\nrange {} … {}, {} reading(s) per sample\n\n*{line}*",
            d.name, d.id, model.name, d.min, d.max, d.readings
        ),
        ModelName::Object(o) => format!(
            "**{}** — object of robot `{}`\n\nparameters: {}\n\n*{line}*",
            o.name,
            model.name,
            o.params.join(" ")
        ),
        ModelName::Color(v) | ModelName::Identifier(v) => format!(
            "**{}** — {} of robot `{}` = {}\n\n*{line}*",
            v.name,
            name.kind(),
            model.name,
            v.value
        ),
        ModelName::Parameter(v) => {
            let mut out = format!(
                "**{}** — parameter of robot `{}` = {}",
                v.name, model.name, v.value
            );
            if let Some(spec) = parameter_spec(&v.name) {
                let _ = write!(out, " {}\n\n{}", spec.unit, spec.meaning);
            }
            let _ = write!(out, "\n\n*{line}*");
            out
        }
    }
}

/// A parameter of the toolchain the model leaves out, valued by its default.
pub fn default_parameter(name: &str, model: &RobotModel) -> Option<String> {
    let spec = parameter_spec(name)?;
    let value = model.parameter_or_default(name)?;
    Some(format!(
        "**{}** — parameter = {value} {} (the toolchain's default; robot `{}` does not set it)\n\n{}",
        spec.name, spec.unit, model.name, spec.meaning
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_show_the_robots_values() {
        let model = RobotModel::builtin("moro").unwrap();
        let speed = ilmr_stdlib::Command::Speed.spec();
        let text = param(&speed.forms[0].params[0], &model);
        assert!(
            text.contains("[m/s, refused outside ±0.8 (`max_speed`)]"),
            "{text}"
        );
        let wait = ilmr_stdlib::Command::FollowWall.spec();
        let text = param(&wait.forms[0].params[0], &model);
        assert!(
            text.starts_with("`side`: left \\| right \\| middle"),
            "{text}"
        );
    }
}

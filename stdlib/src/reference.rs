//! The command reference (`docs/commands.md`), generated from the catalogue so that the
//! docs cannot drift from what the checker accepts.

use std::fmt::Write;

use crate::spec::{Limit, ModelNames, Occurs, ParamKind, Range};
use crate::{CATALOGUE, Category};

pub fn reference_markdown() -> String {
    let mut out = String::from(
        "# Command reference\n\n\
         Generated from the catalogue in `stdlib/src/catalogue.rs` \
         (`UPDATE_DOCS=1 cargo test -p ilmr-stdlib` rewrites it). Commands and keywords \
         may be written in any letter case.\n",
    );
    for category in Category::ALL {
        let _ = write!(out, "\n## {}\n", category.title());
        for spec in CATALOGUE.iter().filter(|s| s.category == category) {
            let _ = write!(out, "\n### {}\n\n{}\n\n", spec.title, spec.summary);
            if !spec.doc.is_empty() {
                let _ = write!(out, "{}\n\n", spec.doc);
            }
            let _ = write!(out, "```bnf\n{}\n```\n\n", spec.grammar);
            let mut facts = vec![format!("section {}", spec.section)];
            if spec.movement {
                facts.push("movement command: takes the movement reservation".into());
            }
            if spec.holds_block {
                facts.push("holds the rest of its block until it ends".into());
            }
            match spec.ends {
                crate::spec::Ends::AtIssue => facts.push("ends when issued".into()),
                crate::spec::Ends::AtIssueWithout { keyword } => {
                    facts.push(format!("ends when issued, unless written with `{keyword}`"))
                }
                crate::spec::Ends::Never => facts.push(
                    "never ends by itself: only a `break`, a `priority` block or a refusal ends it"
                        .into(),
                ),
                crate::spec::Ends::NeverBare => facts.push(
                    "without an argument never ends by itself: only a `break`, a `priority` block or a refusal ends it"
                        .into(),
                ),
                crate::spec::Ends::Later => {}
            }
            match spec.sets {
                crate::spec::Sets::Nothing => {}
                crate::spec::Sets::Setting { what, unless } => facts.push(format!(
                    "sets the robot's {what}{}: of two blocks that set it in the same tick, the one issued last wins (W0905)",
                    unless.map_or(String::new(), |k| format!(" (unless written with `{k}`)"))
                )),
                crate::spec::Sets::Device => facts.push(
                    "sets the device it names: of two blocks that set one device in the same tick, the one issued last wins (W0905)"
                        .into(),
                ),
            }
            if let Some(device) = spec.needs_device {
                facts.push(format!(
                    "needs a `{device}` in the robot model's [SENSORSANDACTUATORS] (E0407 otherwise)"
                ));
            }
            let _ = writeln!(out, "*{}*\n", facts.join("; "));
            for form in spec.forms {
                let _ = writeln!(
                    out,
                    "- **{}** — a bound variable holds {}",
                    form.label,
                    form.produces.describe()
                );
                for p in form.params {
                    let occurs = match p.occurs {
                        Occurs::One => "",
                        Occurs::Optional => " (optional)",
                        Occurs::Many => " (any number)",
                        Occurs::Pairs => " (pairs)",
                    };
                    let _ = writeln!(
                        out,
                        "  - `{}`{occurs}: {} — {}",
                        p.name,
                        kind_text(&p.kind),
                        p.doc
                    );
                }
            }
            let examples: Vec<String> = spec
                .examples
                .iter()
                .map(|e| format!("`{}`", e.replace('\n', "` / `")))
                .collect();
            let _ = writeln!(out, "\nExamples: {}", examples.join(", "));
        }
    }
    units_section(&mut out);
    out
}

/// What the checker says of units, from the tables of `units.rs`.
fn units_section(out: &mut String) {
    out.push_str(
        "\n## Units\n\n\
         Values are plain numbers in the unit the reference gives for each argument: metres, \
         metres per second, degrees, seconds, 1/m. A unit written after a number is an error \
         (E0106) whose fix writes the number converted into the argument's unit. The units \
         it recognises:\n\n| written | one of it is |\n| --- | --- |\n",
    );
    for u in crate::units::WRITTEN_UNITS {
        let unit = crate::CATALOGUE
            .iter()
            .flat_map(|s| s.forms)
            .flat_map(|f| f.params)
            .find_map(|p| match p.kind {
                ParamKind::Value { unit, .. } | ParamKind::Setting { unit, .. }
                    if unit.dimension() == Some(u.dimension) =>
                {
                    Some(unit)
                }
                _ => None,
            });
        let spellings: Vec<String> = u.spellings.iter().map(|s| format!("`{s}`")).collect();
        let _ = writeln!(
            out,
            "| {} | {} {} |",
            spellings.join(", "),
            crate::units::round_for_people(u.factor),
            unit.map_or("", |u| u.symbol())
        );
    }
    let _ = write!(
        out,
        "\nA literal number that looks written in another unit gets a warning (W0409) when its \
         value in that unit is within the argument's range: a degree value with a fraction no \
         larger than {} (a full turn in radians) that is in radians within {} degrees of a \
         multiple of {} degrees, such as `turn(d=1.57,c=1)` (90 degrees), looks like \
         radians; a length of {} m or more in one command looks like centimetres, but for \
         a position (`x`, `y`: a coordinate outdoors is often hundreds of metres).\n",
        crate::units::round_for_people(crate::units::RADIANS_UP_TO),
        crate::units::ROUND_ANGLE_SLACK,
        crate::units::ROUND_ANGLE_DEGREES,
        crate::units::CENTIMETRES_FROM
    );
}

fn kind_text(kind: &ParamKind) -> String {
    match *kind {
        ParamKind::Keyword { words } => words.join(" \\| "),
        ParamKind::Mode { words, what } => {
            format!("{what}: {} (as the model defines)", words.join(" \\| "))
        }
        ParamKind::Value { unit, range } => {
            format!("number{}{}", unit_text(unit.symbol()), range_text(range))
        }
        ParamKind::Setting { key, unit, range } => format!(
            "`{key}=` number{}{}",
            unit_text(unit.symbol()),
            range_text(range)
        ),
        ParamKind::Model { names } => match names {
            ModelNames::Device => "sensor or actuator of the model (name or number)".into(),
            ModelNames::Object => "object of the model".into(),
            ModelNames::Service => "sensor or service of the model".into(),
        },
        ParamKind::Position => "position variable".into(),
        ParamKind::Variable => "variable".into(),
        ParamKind::Name { .. } => "name".into(),
        ParamKind::OneOf { kinds } => kinds.iter().map(kind_text).collect::<Vec<_>>().join(" or "),
    }
}

fn unit_text(symbol: &str) -> String {
    if symbol.is_empty() {
        String::new()
    } else {
        format!(" [{symbol}]")
    }
}

fn range_text(range: Range) -> String {
    let limit = |l: Limit| match l {
        Limit::Refuse => "refused outside",
        Limit::Warn => "warned outside",
    };
    match range {
        Range::Any => String::new(),
        Range::Between { min, max, limit: l } => format!(", {} {min} ... {max}", limit(l)),
        Range::Positive => ", greater than 0".into(),
        Range::NonNegative => ", 0 or more".into(),
        Range::Symmetric { param, limit: l } | Range::Magnitude { param, limit: l } => {
            format!(", {} -{param} ... {param}", limit(l))
        }
        Range::UpTo { param, limit: l } => format!(", {} 0 ... {param}", limit(l)),
        Range::DeviceRange => ", within the actuator's range in the model".into(),
        Range::ReadingIndex => ", 0 ... readings - 1 of the sensor".into(),
    }
}

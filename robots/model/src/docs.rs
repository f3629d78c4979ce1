//! The parameter table of `docs/robot-model.md`, generated from the specs so
//! that the documentation cannot drift from the code (a test compares them).

use crate::limits::{MAX_DEVICE_ID, MAX_MAGNITUDE, MAX_READINGS, MAX_SECTION_ENTRIES, shown};
use crate::params::{PARAMETER_SPECS, ParamDefault};

/// A Markdown table with one row per known parameter: name, unit, default,
/// admissible range, meaning and readers.
pub fn parameter_table_markdown() -> String {
    let mut out = String::from(
        "| parameter | unit | default | admits | meaning | read by |\n\
         | --- | --- | --- | --- | --- | --- |\n",
    );
    for spec in PARAMETER_SPECS {
        let default = match spec.default {
            ParamDefault::Value(v) => v.to_string(),
            ParamDefault::SameAs(other) => format!("= `{}`", other.name),
            ParamDefault::Absent => "none (feature absent)".to_string(),
        };
        out.push_str(&format!(
            "| `{}` | {} | {} | {} | {} | {} |\n",
            spec.name,
            spec.unit,
            default,
            spec.valid.describe(),
            spec.meaning,
            spec.readers
        ));
    }
    out
}

/// A Markdown table of the ranges of every number of a ROBO.INI that is not
/// a known parameter, from the same constants the reader checks against.
pub fn field_table_markdown() -> String {
    let m = shown(MAX_MAGNITUDE);
    let rows = [
        (
            "[SENSORSANDACTUATORS] id",
            format!("an integer, 0 to {MAX_DEVICE_ID}"),
        ),
        (
            "[SENSORSANDACTUATORS] min, max",
            format!("-{m} to {m}, min <= max"),
        ),
        (
            "[SENSORSANDACTUATORS] readings",
            format!("an integer, 1 to {MAX_READINGS}"),
        ),
        ("[OBJECTS] numeric parameter", format!("-{m} to {m}")),
        ("[COLORS] value", format!("-{m} to {m}")),
        ("[IDENTIFIERS] value", format!("-{m} to {m}")),
        (
            "[PARAMETERS] value of an unknown name",
            format!("-{m} to {m}"),
        ),
        (
            "entries of one section",
            format!("at most {MAX_SECTION_ENTRIES}"),
        ),
    ];
    let mut out = String::from("| field | admits |\n| --- | --- |\n");
    for (field, admits) in rows {
        out.push_str(&format!("| {field} | {admits} |\n"));
    }
    out
}

//! The parameter table of `docs/robot-model.md`, generated from the specs so
//! that the documentation cannot drift from the code (a test compares them).

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

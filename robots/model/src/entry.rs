//! Reading one entry line of a section into a device, object or named value.
//! The line is already split into fields; what it means in context
//! (duplicates, ranges of known parameters, defaults) is `parse`'s job.

use crate::limits::{MAX_DEVICE_ID, MAX_MAGNITUDE, MAX_READINGS, out_of_range, shown};
use crate::model::{Device, NamedValue, Object};
use crate::names::is_valid_name;

/// The sections that hold entries. `[END]` holds none.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) enum Section {
    Devices,
    Objects,
    Colors,
    Identifiers,
    Parameters,
}

impl Section {
    pub(crate) const ALL: [Section; 5] = [
        Section::Devices,
        Section::Objects,
        Section::Colors,
        Section::Identifiers,
        Section::Parameters,
    ];

    pub(crate) fn tag(self) -> &'static str {
        match self {
            Section::Devices => "SENSORSANDACTUATORS",
            Section::Objects => "OBJECTS",
            Section::Colors => "COLORS",
            Section::Identifiers => "IDENTIFIERS",
            Section::Parameters => "PARAMETERS",
        }
    }

    /// What one entry is called in messages.
    pub(crate) fn noun(self) -> &'static str {
        match self {
            Section::Devices => "device",
            Section::Objects => "object",
            Section::Colors => "color",
            Section::Identifiers => "identifier",
            Section::Parameters => "parameter",
        }
    }

    fn layout(self) -> &'static str {
        match self {
            Section::Devices => "5 fields (name id min max readings)",
            Section::Objects => "a name and at least one parameter",
            Section::Colors | Section::Identifiers | Section::Parameters => "2 fields (name value)",
        }
    }
}

/// A successfully read entry line.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Entry {
    Device(Device),
    Object(Object),
    Value(NamedValue),
}

impl Entry {
    pub(crate) fn name(&self) -> &str {
        match self {
            Entry::Device(d) => &d.name,
            Entry::Object(o) => &o.name,
            Entry::Value(v) => &v.name,
        }
    }
}

/// Why an entry line could not be read. `name` is set when the line starts
/// with a usable name, so that a default of that name can stand in.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Problem {
    pub(crate) name: Option<String>,
    pub(crate) message: String,
}

/// Reads the fields of one entry line of `section`. `fields` is never empty.
pub(crate) fn read_entry(section: Section, fields: &[&str], line: u32) -> Result<Entry, Problem> {
    let Some(&first) = fields.first() else {
        return Err(Problem {
            name: None,
            message: format!("empty {} entry", section.noun()),
        });
    };
    if !is_valid_name(first) {
        let hint = if first.starts_with("//") {
            " (comment lines start with `;` or `#`)"
        } else {
            ""
        };
        return Err(Problem {
            name: None,
            message: format!(
                "`{first}` is not a valid {} name (a letter, then letters, digits or `_`){hint}",
                section.noun()
            ),
        });
    }
    let fail = |message: String| Problem {
        name: Some(first.to_string()),
        message,
    };
    let count_ok = match section {
        Section::Devices => fields.len() == 5,
        Section::Objects => fields.len() >= 2,
        _ => fields.len() == 2,
    };
    if !count_ok {
        return Err(fail(count_message(section, fields)));
    }
    let name = first.to_string();
    match section {
        Section::Devices => read_device(name, &fields[1..], line).map_err(fail),
        Section::Objects => Ok(Entry::Object(Object {
            name,
            params: fields[1..].iter().map(|f| f.to_string()).collect(),
            line,
        })),
        _ => {
            let value = number(fields[1], "value").map_err(fail)?;
            Ok(Entry::Value(NamedValue { name, value, line }))
        }
    }
}

/// A number a device, colour, identifier or unknown parameter may hold:
/// within `MAX_MAGNITUDE` either way. Known parameters have their own ranges.
pub(crate) fn bounded(value: f64, what: &str) -> Result<f64, String> {
    if value.abs() <= MAX_MAGNITUDE {
        Ok(value)
    } else {
        Err(out_of_range(
            what,
            &shown(value),
            &format!("-{} to {}", shown(MAX_MAGNITUDE), shown(MAX_MAGNITUDE)),
        ))
    }
}

fn count_message(section: Section, fields: &[&str]) -> String {
    let mut message = format!(
        "[{}] expects {}, found {} field{}",
        section.tag(),
        section.layout(),
        fields.len(),
        if fields.len() == 1 { "" } else { "s" }
    );
    if fields
        .iter()
        .skip(1)
        .any(|f| f.starts_with(';') || f.starts_with('#') || f.starts_with("//"))
    {
        message.push_str(" (comments must be on a line of their own)");
    }
    message
}

fn read_device(name: String, fields: &[&str], line: u32) -> Result<Entry, String> {
    let [id, min, max, readings] = fields else {
        return Err(format!(
            "expected 4 fields after the name, found {}",
            fields.len()
        ));
    };
    let id = match id.parse::<i64>() {
        Ok(id) if (0..=MAX_DEVICE_ID).contains(&id) => id,
        _ => {
            return Err(format!(
                "device id `{id}` is not an integer from 0 to {MAX_DEVICE_ID}"
            ));
        }
    };
    let min = bounded(number(min, "minimum")?, &format!("{name} minimum"))?;
    let max = bounded(number(max, "maximum")?, &format!("{name} maximum"))?;
    if min > max {
        return Err(format!("minimum {min} is greater than maximum {max}"));
    }
    let readings = match readings.parse::<u64>() {
        Ok(n) if (1..=u64::from(MAX_READINGS)).contains(&n) => n as u32,
        Ok(n) if n > 0 => {
            return Err(out_of_range(
                &format!("{name} readings"),
                &n.to_string(),
                &format!("1 to {MAX_READINGS}"),
            ));
        }
        _ => {
            return Err(format!(
                "number of readings `{readings}` is not a positive integer"
            ));
        }
    };
    Ok(Entry::Device(Device {
        name,
        id,
        min,
        max,
        readings,
        line,
    }))
}

/// A finite real number. `what` names the field in the message.
pub(crate) fn number(text: &str, what: &str) -> Result<f64, String> {
    match parse_number(text) {
        Some(v) => Ok(v),
        None if text.contains(',') && parse_number(&text.replace(',', ".")).is_some() => Err(
            format!("{what} `{text}` is not a number (write `.` as the decimal point)"),
        ),
        None => Err(format!("{what} `{text}` is not a number")),
    }
}

/// Rust's float syntax minus `inf` and `NaN`, which no robot quantity is.
pub(crate) fn parse_number(text: &str) -> Option<f64> {
    text.parse::<f64>().ok().filter(|v| v.is_finite())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(section: Section, line: &str) -> Result<Entry, Problem> {
        let fields: Vec<&str> = line.split_whitespace().collect();
        read_entry(section, &fields, 3)
    }

    fn message(section: Section, line: &str) -> String {
        match read(section, line) {
            Ok(e) => panic!("expected a problem, read {e:?}"),
            Err(p) => p.message,
        }
    }

    #[test]
    fn reads_figure_39_lines() {
        assert_eq!(
            read(Section::Devices, "scanner 1 0 30000 361"),
            Ok(Entry::Device(Device {
                name: "scanner".into(),
                id: 1,
                min: 0.0,
                max: 30000.0,
                readings: 361,
                line: 3
            }))
        );
        assert_eq!(
            read(Section::Objects, "user yellow 30"),
            Ok(Entry::Object(Object {
                name: "user".into(),
                params: vec!["yellow".into(), "30".into()],
                line: 3
            }))
        );
        assert_eq!(
            read(Section::Parameters, "max_speed 0.6"),
            Ok(Entry::Value(NamedValue {
                name: "max_speed".into(),
                value: 0.6,
                line: 3
            }))
        );
    }

    #[test]
    fn explains_bad_fields() {
        let cases = [
            (
                Section::Devices,
                "scanner 1 0 30000",
                "[SENSORSANDACTUATORS] expects 5 fields (name id min max readings), found 4 fields",
            ),
            (
                Section::Devices,
                "scanner x 0 1 1",
                "device id `x` is not an integer from 0 to 2147483647",
            ),
            (
                Section::Devices,
                "scanner 1.5 0 1 1",
                "device id `1.5` is not an integer from 0 to 2147483647",
            ),
            (
                Section::Devices,
                "scanner -1 0 1 1",
                "device id `-1` is not an integer from 0 to 2147483647",
            ),
            (
                Section::Devices,
                "scanner 1 a 1 1",
                "minimum `a` is not a number",
            ),
            (
                Section::Devices,
                "scanner 1 0 inf 1",
                "maximum `inf` is not a number",
            ),
            (
                Section::Devices,
                "scanner 1 5 1 1",
                "minimum 5 is greater than maximum 1",
            ),
            (
                Section::Devices,
                "scanner 1 0 1 0",
                "number of readings `0` is not a positive integer",
            ),
            (
                Section::Objects,
                "door",
                "[OBJECTS] expects a name and at least one parameter, found 1 field",
            ),
            (
                Section::Parameters,
                "max_speed",
                "[PARAMETERS] expects 2 fields (name value), found 1 field",
            ),
            (
                Section::Parameters,
                "max_speed 0,6",
                "value `0,6` is not a number (write `.` as the decimal point)",
            ),
            (
                Section::Parameters,
                "max_speed NaN",
                "value `NaN` is not a number",
            ),
            (
                Section::Parameters,
                "max_speed 0.6 ; m/s",
                "[PARAMETERS] expects 2 fields (name value), found 4 fields (comments must be on a line of their own)",
            ),
            (
                Section::Colors,
                "1yellow 18",
                "`1yellow` is not a valid color name (a letter, then letters, digits or `_`)",
            ),
            (
                Section::Identifiers,
                "// off 0",
                "`//` is not a valid identifier name (a letter, then letters, digits or `_`) (comment lines start with `;` or `#`)",
            ),
        ];
        for (section, line, expected) in cases {
            assert_eq!(message(section, line), expected, "{line}");
        }
    }

    #[test]
    fn a_problem_keeps_a_usable_name_for_defaults() {
        let p = read(Section::Devices, "scanner 1 0").unwrap_err();
        assert_eq!(p.name.as_deref(), Some("scanner"));
        let p = read(Section::Devices, "9scanner 1 0 1 1").unwrap_err();
        assert_eq!(p.name, None);
    }
}

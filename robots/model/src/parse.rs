//! ROBO.INI text to a model. Parsing never fails: every problem becomes a
//! warning with its line, the line is skipped or a default stands in, and
//! the rest of the file is still read.
//!
//! ```text
//! file    ::= { blank | comment | tag | entry }
//! comment ::= ("; " | "#") text             (own line only)
//! tag     ::= "[" section "]"               (case-insensitive)
//! section ::= SENSORSANDACTUATORS | OBJECTS | COLORS | IDENTIFIERS | PARAMETERS | END
//! entry   ::= name field { field }          (fields split on whitespace)
//! ```

use std::collections::BTreeMap;

use crate::entry::{Entry, Problem, Section, bounded, parse_number, read_entry};
use crate::limits::{MAX_SECTION_ENTRIES, out_of_range, shown};
use crate::model::{ModelWarning, NamedValue, RobotModel};
use crate::names::{fold, is_valid_name, same_name};
use crate::params::{
    BATTERY_FULL, DEFAULT_SPEED, LOW_BATTERY, MAX_SPEED, NAV_RATE, NAV_TIMEOUT, ODOMETRY_RATE,
    ODOMETRY_TIMEOUT, ParamDefault, ParamSpec, SCANNER_RATE, SCANNER_TIMEOUT, parameter_spec,
};
use crate::ros2::{ROS2_SETTINGS, Ros2Setting, ros2_setting};
use crate::write::{device_line, object_line, value_line};

/// The tag of the `[ROS2]` section.
const ROS2_TAG: &str = "ROS2";

/// Whether entries of the defaults model may stand in for corrupt lines.
/// Only the defaults model itself is parsed without.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Fallback {
    Defaults,
    Nothing,
}

pub(crate) fn parse_text(
    text: &str,
    name: &str,
    fallback: Fallback,
) -> (RobotModel, Vec<ModelWarning>) {
    let mut parser = Parser::new(name, fallback);
    let mut last_line = 0;
    for (index, raw) in text.lines().enumerate() {
        let line = u32::try_from(index + 1).unwrap_or(u32::MAX);
        last_line = line;
        let raw = if index == 0 {
            raw.strip_prefix('\u{feff}').unwrap_or(raw)
        } else {
            raw
        };
        parser.line(line, raw.trim());
    }
    parser.finish(last_line)
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum State {
    BeforeFirstTag,
    In(Section),
    /// `[ROS2]`: words, not numbers, so not one of the numeric [`Section`]s.
    Ros2,
    Unknown,
    Ended,
}

/// Lines skipped for one reason, reported once.
#[derive(Debug, Clone, Copy)]
struct Skipped {
    first: u32,
    count: u32,
}

impl Skipped {
    fn add(slot: &mut Option<Skipped>, line: u32) {
        match slot {
            Some(s) => s.count += 1,
            None => {
                *slot = Some(Skipped {
                    first: line,
                    count: 1,
                })
            }
        }
    }
}

struct UnknownSection {
    line: u32,
    message: String,
    lines: u32,
}

struct Parser {
    model: RobotModel,
    warnings: Vec<ModelWarning>,
    fallback: Fallback,
    defaults: Option<RobotModel>,
    state: State,
    found_tag: bool,
    content_lines: u32,
    /// Folded name to defining line, per section.
    seen: BTreeMap<(Section, String), u32>,
    /// Device id to the name and line that took it.
    ids: BTreeMap<i64, (String, u32)>,
    before_first_tag: Option<Skipped>,
    after_end: Option<Skipped>,
    unknown: Option<UnknownSection>,
    /// Entry lines of a section past `MAX_SECTION_ENTRIES`.
    too_many: BTreeMap<Section, Skipped>,
}

impl Parser {
    fn new(name: &str, fallback: Fallback) -> Parser {
        Parser {
            model: RobotModel {
                name: name.to_string(),
                devices: Vec::new(),
                objects: Vec::new(),
                colors: Vec::new(),
                identifiers: Vec::new(),
                parameters: Vec::new(),
                ros2: Vec::new(),
                source: None,
            },
            warnings: Vec::new(),
            fallback,
            defaults: None,
            state: State::BeforeFirstTag,
            found_tag: false,
            content_lines: 0,
            seen: BTreeMap::new(),
            ids: BTreeMap::new(),
            before_first_tag: None,
            after_end: None,
            unknown: None,
            too_many: BTreeMap::new(),
        }
    }

    fn warn(&mut self, line: u32, message: impl Into<String>) {
        self.warnings.push(ModelWarning::at(line, message));
    }

    fn line(&mut self, line: u32, text: &str) {
        if text.is_empty() || text.starts_with(';') || text.starts_with('#') {
            return;
        }
        self.content_lines += 1;
        if self.state == State::Ended {
            Skipped::add(&mut self.after_end, line);
            return;
        }
        if text.starts_with('[') {
            self.tag(line, text);
            return;
        }
        match self.state {
            State::BeforeFirstTag => Skipped::add(&mut self.before_first_tag, line),
            State::Unknown => {
                if let Some(u) = &mut self.unknown {
                    u.lines += 1;
                }
            }
            State::In(section) => {
                let fields: Vec<&str> = text.split_whitespace().collect();
                self.entry(section, &fields, line);
            }
            State::Ros2 => {
                let fields: Vec<&str> = text.split_whitespace().collect();
                self.ros2_entry(&fields, line);
            }
            State::Ended => {}
        }
    }

    // ---- section tags -------------------------------------------------

    /// tag ::= "[" section "]"
    fn tag(&mut self, line: u32, text: &str) {
        self.flush_unknown();
        let body = &text[1..];
        let (inner, rest) = match body.find(']') {
            Some(close) => (body[..close].trim(), body[close + 1..].trim()),
            None => {
                self.warn(line, format!("section tag `{text}` lacks its closing `]`"));
                (body.trim(), "")
            }
        };
        if !rest.is_empty() {
            self.warn(
                line,
                format!("text `{rest}` after the section tag [{inner}] is ignored"),
            );
        }
        if inner.eq_ignore_ascii_case("END") {
            self.found_tag = true;
            self.state = State::Ended;
            return;
        }
        if inner.eq_ignore_ascii_case(ROS2_TAG) {
            self.found_tag = true;
            self.state = State::Ros2;
            return;
        }
        if let Some(section) = Section::ALL
            .into_iter()
            .find(|s| inner.eq_ignore_ascii_case(s.tag()))
        {
            self.found_tag = true;
            self.state = State::In(section);
            return;
        }
        self.state = State::Unknown;
        let hint = closest_tag(inner)
            .map(|t| format!(" (did you mean [{t}]?)"))
            .unwrap_or_default();
        self.unknown = Some(UnknownSection {
            line,
            message: format!(
                "unknown section [{inner}]{hint}; the sections are [SENSORSANDACTUATORS], \
                 [OBJECTS], [COLORS], [IDENTIFIERS], [PARAMETERS], [ROS2] and [END]"
            ),
            lines: 0,
        });
    }

    fn flush_unknown(&mut self) {
        if let Some(u) = self.unknown.take() {
            let ignored = match u.lines {
                0 => "it holds no entries".to_string(),
                1 => "its 1 line is ignored".to_string(),
                n => format!("its {n} lines are ignored"),
            };
            self.warn(u.line, format!("{}; {ignored}", u.message));
        }
    }

    // ---- entries ------------------------------------------------------

    /// `name value` in `[ROS2]`: a known setting, once; anything else is a warning
    /// and the line is skipped (there is no default to stand in: the backend has its
    /// own).
    fn ros2_entry(&mut self, fields: &[&str], line: u32) {
        let [name, value] = fields[..] else {
            let shown_line = cut(&fields.join(" "));
            self.warn(
                line,
                format!(
                    "[{ROS2_TAG}] entry `{shown_line}` should have 2 fields (name value); the line is ignored"
                ),
            );
            return;
        };
        let Some(known) = ros2_setting(name) else {
            let hint = closest(name, ROS2_SETTINGS.iter().map(|(n, _)| *n))
                .map(|n| format!(" (did you mean `{n}`?)"))
                .unwrap_or_default();
            self.warn(
                line,
                format!(
                    "unknown [{ROS2_TAG}] setting `{}`{hint}; the line is ignored",
                    cut(name)
                ),
            );
            return;
        };
        if self.model.ros2.iter().any(|s| s.name == known) {
            self.warn(
                line,
                format!("duplicate [{ROS2_TAG}] setting `{known}`; the line is ignored"),
            );
            return;
        }
        if self.model.ros2.len() >= MAX_SECTION_ENTRIES {
            return;
        }
        self.model.ros2.push(Ros2Setting {
            name: known.to_string(),
            value: value.to_string(),
        });
    }

    fn entry(&mut self, section: Section, fields: &[&str], line: u32) {
        if self.entries(section) >= MAX_SECTION_ENTRIES {
            match self.too_many.get_mut(&section) {
                Some(s) => s.count += 1,
                None => {
                    self.too_many.insert(
                        section,
                        Skipped {
                            first: line,
                            count: 1,
                        },
                    );
                }
            }
            return;
        }
        if let Some(&first) = fields.first()
            && is_valid_name(first)
            && let Some(&first_line) = self.seen.get(&(section, fold(first)))
        {
            self.warn(
                line,
                format!(
                    "duplicate {} `{first}` (first defined on line {first_line}); the line is ignored",
                    section.noun()
                ),
            );
            return;
        }
        match read_entry(section, fields, line) {
            Ok(Entry::Value(value)) if section == Section::Parameters => {
                self.parameter(value);
            }
            Ok(Entry::Object(object))
                if let Some(Err(message)) = object
                    .params
                    .iter()
                    .filter_map(|p| parse_number(p))
                    .map(|v| bounded(v, &format!("{} parameter", object.name)))
                    .find(Result::is_err) =>
            {
                self.substitute(
                    section,
                    Problem {
                        name: Some(object.name),
                        message,
                    },
                    line,
                );
            }
            Ok(Entry::Value(value)) if bounded(value.value, &value.name).is_err() => {
                let message = bounded(value.value, &value.name).err().unwrap_or_default();
                self.substitute(
                    section,
                    Problem {
                        name: Some(value.name),
                        message,
                    },
                    line,
                );
            }
            Ok(entry) => {
                if let Err(message) = self.add(section, entry) {
                    self.warn(line, format!("{message}; the line is ignored"));
                }
            }
            Err(problem) => self.substitute(section, problem, line),
        }
    }

    fn entries(&self, section: Section) -> usize {
        match section {
            Section::Devices => self.model.devices.len(),
            Section::Objects => self.model.objects.len(),
            Section::Colors => self.model.colors.len(),
            Section::Identifiers => self.model.identifiers.len(),
            Section::Parameters => self.model.parameters.len(),
        }
    }

    /// Adds an entry that passed its own checks, unless its device id is taken.
    fn add(&mut self, section: Section, entry: Entry) -> Result<(), String> {
        let line = match &entry {
            Entry::Device(d) => d.line,
            Entry::Object(o) => o.line,
            Entry::Value(v) => v.line,
        };
        if let Entry::Device(d) = &entry {
            if let Some((owner, owner_line)) = self.ids.get(&d.id) {
                return Err(format!(
                    "device `{}` has id {}, already used by `{owner}` on line {owner_line}",
                    d.name, d.id
                ));
            }
            self.ids.insert(d.id, (d.name.clone(), line));
        }
        self.seen.insert((section, fold(entry.name())), line);
        match (section, entry) {
            (_, Entry::Device(d)) => self.model.devices.push(d),
            (_, Entry::Object(o)) => self.model.objects.push(o),
            (Section::Colors, Entry::Value(v)) => self.model.colors.push(v),
            (Section::Identifiers, Entry::Value(v)) => self.model.identifiers.push(v),
            (_, Entry::Value(v)) => self.model.parameters.push(v),
        }
        Ok(())
    }

    /// A parameter line that read as `name value`: known parameters must be
    /// in range, or their default stands in.
    fn parameter(&mut self, value: NamedValue) {
        let line = value.line;
        let Some(spec) = parameter_spec(&value.name) else {
            match bounded(value.value, &value.name) {
                Ok(_) => {
                    let _ = self.add(Section::Parameters, Entry::Value(value));
                }
                Err(message) => self.warn(line, format!("{message}; the line is ignored")),
            }
            return;
        };
        if spec.valid.admits(value.value) {
            let _ = self.add(Section::Parameters, Entry::Value(value));
            return;
        }
        let problem = out_of_range(
            &value.name,
            &shown(value.value),
            &format!("{} {}", spec.valid.describe(), spec.unit),
        );
        self.substitute(
            Section::Parameters,
            Problem {
                name: Some(value.name),
                message: problem,
            },
            line,
        );
    }

    /// A corrupt line: the default of the same name stands in where there is
    /// one; otherwise the line is dropped. Either way the warning says which.
    fn substitute(&mut self, section: Section, problem: Problem, line: u32) {
        let stand_in = problem
            .name
            .as_deref()
            .and_then(|name| self.default_entry(section, name, line));
        let Some((entry, shown)) = stand_in else {
            let consequence = match problem.name.as_deref().and_then(parameter_spec) {
                Some(ParamSpec {
                    default: ParamDefault::SameAs(other),
                    ..
                }) if section == Section::Parameters => format!(
                    "the line is ignored, so the value of `{}` is used",
                    other.name
                ),
                _ => "the line is ignored".to_string(),
            };
            self.warn(line, format!("{}; {consequence}", problem.message));
            return;
        };
        match self.add(section, entry) {
            Ok(()) => self.warn(
                line,
                format!("{}; the default {shown} is used", problem.message),
            ),
            Err(clash) => self.warn(
                line,
                format!(
                    "{}; its default would clash ({clash}), so the line is ignored",
                    problem.message
                ),
            ),
        }
    }

    /// The default entry named `name` in `section`, renamed to the file's
    /// spelling and placed on `line`, with how to show it in a warning.
    fn default_entry(
        &mut self,
        section: Section,
        name: &str,
        line: u32,
    ) -> Option<(Entry, String)> {
        if section == Section::Parameters {
            let spec = parameter_spec(name)?;
            let ParamDefault::Value(value) = spec.default else {
                return None;
            };
            let v = NamedValue {
                name: name.to_string(),
                value,
                line,
            };
            return Some((Entry::Value(v), value.to_string()));
        }
        if self.fallback == Fallback::Nothing {
            return None;
        }
        let defaults = self
            .defaults
            .get_or_insert_with(crate::load::defaults_model);
        match section {
            Section::Devices => defaults.device(name).map(|d| {
                let mut d = d.clone();
                d.name = name.to_string();
                d.line = line;
                let shown = format!("`{}`", device_line(&d));
                (Entry::Device(d), shown)
            }),
            Section::Objects => defaults.object(name).map(|o| {
                let mut o = o.clone();
                o.name = name.to_string();
                o.line = line;
                let shown = format!("`{}`", object_line(&o));
                (Entry::Object(o), shown)
            }),
            Section::Colors | Section::Identifiers => {
                let list = if section == Section::Colors {
                    &defaults.colors
                } else {
                    &defaults.identifiers
                };
                list.iter().find(|v| same_name(&v.name, name)).map(|v| {
                    let v = NamedValue {
                        name: name.to_string(),
                        value: v.value,
                        line,
                    };
                    let shown = format!("`{}`", value_line(&v));
                    (Entry::Value(v), shown)
                })
            }
            Section::Parameters => None,
        }
    }

    // ---- end of file --------------------------------------------------

    fn finish(mut self, last_line: u32) -> (RobotModel, Vec<ModelWarning>) {
        self.flush_unknown();
        if !self.found_tag && self.fallback == Fallback::Defaults {
            return self.no_sections();
        }
        if let Some(s) = self.before_first_tag {
            self.warn(
                s.first,
                format!(
                    "{} before the first section tag {} ignored",
                    lines(s.count),
                    if s.count == 1 { "is" } else { "are" }
                ),
            );
        }
        for (section, s) in std::mem::take(&mut self.too_many) {
            self.warn(
                s.first,
                format!(
                    "[{}]: more than {MAX_SECTION_ENTRIES} entries, out of range (expected at most \
                     {MAX_SECTION_ENTRIES}); {} from here on {} ignored",
                    section.tag(),
                    lines(s.count),
                    if s.count == 1 { "is" } else { "are" }
                ),
            );
        }
        if let Some(s) = self.after_end {
            self.warn(
                s.first,
                format!(
                    "{} after [END] {} ignored",
                    lines(s.count),
                    if s.count == 1 { "is" } else { "are" }
                ),
            );
        }
        if self.state != State::Ended && self.found_tag {
            self.warn(
                last_line,
                format!("the file ends without [END]; everything up to line {last_line} was read"),
            );
        }
        self.check_object_params();
        self.check_speeds();
        self.check_battery();
        self.check_timeout(&SCANNER_TIMEOUT, &SCANNER_RATE);
        self.check_timeout(&ODOMETRY_TIMEOUT, &ODOMETRY_RATE);
        self.check_timeout(&NAV_TIMEOUT, &NAV_RATE);
        self.warnings.sort_by_key(|w| w.line);
        (self.model, self.warnings)
    }

    /// Nothing that looks like ROBO.INI: the whole file counts as corrupt.
    /// Unknown-section warnings are kept: their did-you-mean is the fix.
    fn no_sections(self) -> (RobotModel, Vec<ModelWarning>) {
        let mut model = crate::load::defaults_model();
        model.name = self.model.name;
        let message = if self.content_lines == 0 {
            "the robot model has no content; the built-in defaults are used".to_string()
        } else {
            format!(
                "no known section tag such as [PARAMETERS] in {}; the built-in defaults are used",
                lines(self.content_lines)
            )
        };
        let mut warnings = vec![ModelWarning::file(message)];
        warnings.extend(self.warnings);
        (model, warnings)
    }

    fn file_line(&self, spec: &ParamSpec) -> Option<u32> {
        self.model
            .parameters
            .iter()
            .find(|p| same_name(&p.name, spec.name))
            .map(|p| p.line)
    }

    /// Object parameters that are not numbers refer to colours or
    /// identifiers (`user yellow 30`).
    fn check_object_params(&mut self) {
        let mut found = Vec::new();
        for object in &self.model.objects {
            for param in &object.params {
                if parse_number(param).is_some()
                    || self.model.color(param).is_some()
                    || self.model.identifier(param).is_some()
                {
                    continue;
                }
                let hint = closest(
                    param,
                    self.model
                        .colors
                        .iter()
                        .chain(&self.model.identifiers)
                        .map(|v| v.name.as_str()),
                )
                .map(|n| format!(" (did you mean `{n}`?)"))
                .unwrap_or_default();
                found.push((
                    object.line,
                    format!(
                        "object `{}` has parameter `{param}`, which is neither a number nor a name \
                         from [COLORS] or [IDENTIFIERS]{hint}; it is kept as written",
                        object.name
                    ),
                ));
            }
        }
        for (line, message) in found {
            self.warn(line, message);
        }
    }

    /// Movement starts at default_speed, which `speed()` could never exceed
    /// max_speed with; clamp it.
    fn check_speeds(&mut self) {
        let (default_speed, max_speed) = (self.model.default_speed(), self.model.max_speed());
        if default_speed <= max_speed {
            return;
        }
        let in_file = self.file_line(&DEFAULT_SPEED);
        let Some(line) = in_file.or_else(|| self.file_line(&MAX_SPEED)) else {
            return;
        };
        let what = if in_file.is_some() {
            ""
        } else {
            "the default "
        };
        self.warn(
            line,
            format!(
                "{what}default_speed {default_speed} exceeds max_speed {max_speed}; \
                 default_speed {max_speed} is used"
            ),
        );
        match self
            .model
            .parameters
            .iter_mut()
            .find(|p| same_name(&p.name, DEFAULT_SPEED.name))
        {
            Some(p) => p.value = max_speed,
            None => self.model.parameters.push(NamedValue {
                name: DEFAULT_SPEED.name.to_string(),
                value: max_speed,
                line,
            }),
        }
    }

    fn check_battery(&mut self) {
        let (low, full) = (self.model.low_battery(), self.model.battery_full());
        if low < full {
            return;
        }
        if let Some(line) = self
            .file_line(&LOW_BATTERY)
            .or_else(|| self.file_line(&BATTERY_FULL))
        {
            self.warn(
                line,
                format!(
                    "LowBattery {low} V is not below battery_full {full} V, so a full battery \
                     already reads as low; kept as written"
                ),
            );
        }
    }

    /// Supervision with a timeout shorter than the sample period would
    /// report faults between healthy samples.
    fn check_timeout(&mut self, timeout: &ParamSpec, rate: &ParamSpec) {
        let (Some(t), Some(r)) = (
            self.model.parameter_or_default(timeout.name),
            self.model.parameter_or_default(rate.name),
        ) else {
            return;
        };
        let period = 1.0 / r;
        if t >= period {
            return;
        }
        if let Some(line) = self.file_line(timeout).or_else(|| self.file_line(rate)) {
            self.warn(
                line,
                format!(
                    "{} {t} s is shorter than one sample period ({period} s at {} {r} Hz), so \
                     supervision would report faults between healthy samples; kept as written",
                    timeout.name, rate.name
                ),
            );
        }
    }
}

/// Text as a warning quotes it: at most 60 characters, so a hostile line does not
/// fill the message.
fn cut(text: &str) -> String {
    const SHOWN: usize = 60;
    if text.chars().count() > SHOWN {
        format!("{}...", text.chars().take(SHOWN).collect::<String>())
    } else {
        text.to_string()
    }
}

fn lines(n: u32) -> String {
    if n == 1 {
        "1 line".to_string()
    } else {
        format!("{n} lines")
    }
}

fn closest_tag(inner: &str) -> Option<&'static str> {
    let known = Section::ALL
        .iter()
        .map(|s| s.tag())
        .chain([ROS2_TAG, "END"]);
    closest(inner, known)
}

/// The candidate nearest to `wanted` ignoring case, if near enough to be a
/// plausible typo (a third of its length in edits, at least one).
fn closest<'a>(wanted: &str, candidates: impl Iterator<Item = &'a str>) -> Option<&'a str> {
    let wanted = fold(wanted);
    candidates
        .map(|c| (strsim::osa_distance(&wanted, &fold(c)), c))
        .filter(|(d, c)| *d <= (c.chars().count().max(wanted.chars().count()) / 3).max(1))
        .min_by_key(|(d, _)| *d)
        .map(|(_, c)| c)
}

//! Writing a model back as ROBO.INI text, and single entries as the line
//! that would define them (used in warnings that say which default stood in).

use std::fmt::Write as _;

use crate::model::{Device, NamedValue, Object, RobotModel};

pub(crate) fn device_line(d: &Device) -> String {
    format!("{} {} {} {} {}", d.name, d.id, d.min, d.max, d.readings)
}

pub(crate) fn object_line(o: &Object) -> String {
    let mut line = o.name.clone();
    for p in &o.params {
        line.push(' ');
        line.push_str(p);
    }
    line
}

pub(crate) fn value_line(v: &NamedValue) -> String {
    // `{}` on f64 prints the shortest text that parses back to the same
    // value, so writing and reading again is lossless.
    format!("{} {}", v.name, v.value)
}

impl RobotModel {
    /// The model as ROBO.INI text in Figure 39's layout: every section tag,
    /// one entry per line in model order, then `[END]`. Parsing the result
    /// gives the same entries back (line numbers aside).
    pub fn to_ini(&self) -> String {
        let mut out = String::new();
        let mut section = |tag: &str, lines: Vec<String>| {
            let _ = writeln!(out, "[{tag}]");
            for line in lines {
                let _ = writeln!(out, "{line}");
            }
        };
        section(
            "SENSORSANDACTUATORS",
            self.devices.iter().map(device_line).collect(),
        );
        section("OBJECTS", self.objects.iter().map(object_line).collect());
        section("COLORS", self.colors.iter().map(value_line).collect());
        section(
            "IDENTIFIERS",
            self.identifiers.iter().map(value_line).collect(),
        );
        section(
            "PARAMETERS",
            self.parameters.iter().map(value_line).collect(),
        );
        // Only a model that has one: the section is not the dissertation's.
        if !self.ros2.is_empty() {
            section(
                "ROS2",
                self.ros2
                    .iter()
                    .map(|s| format!("{} {}", s.name, s.value))
                    .collect(),
            );
        }
        out.push_str("[END]\n");
        out
    }
}

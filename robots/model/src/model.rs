//! The robot model as data: what a ROBO.INI file holds once it is read.

use std::fmt;
use std::path::PathBuf;

use serde::{Deserialize, Serialize};

/// One robot: its sensors and actuators, recognisable objects, colours,
/// identifiers and parameters, in file order.
///
/// Names keep the spelling of the file; lookups ignore case. Within one
/// section names are unique (the parser keeps the first and warns about the
/// rest), but the same name may appear in two sections: Figure 39 has
/// `scanner` both as a device and as an identifier.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RobotModel {
    /// The robot's name: the name given to `parse`, the file stem for
    /// `load`, `"default"` for the defaults model.
    pub name: String,
    /// `[SENSORSANDACTUATORS]`.
    pub devices: Vec<Device>,
    /// `[OBJECTS]`.
    pub objects: Vec<Object>,
    /// `[COLORS]`.
    pub colors: Vec<NamedValue>,
    /// `[IDENTIFIERS]`.
    pub identifiers: Vec<NamedValue>,
    /// `[PARAMETERS]`.
    pub parameters: Vec<NamedValue>,
    /// `[ROS2]`: how the robot is reached over ROS 2, where it speaks it.
    #[serde(default)]
    pub ros2: Vec<crate::Ros2Setting>,
    /// The file the model was read from; `None` for parsed text, the
    /// built-in models and the defaults.
    pub source: Option<PathBuf>,
}

/// A sensor or an actuator. ILMR commands accept the `id` wherever they
/// accept the name (`sensor(1,0)` is `sensor(scanner,0)` on Workpartner).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Device {
    pub name: String,
    pub id: i64,
    /// Smallest admissible reading (sensor) or reference value (actuator).
    pub min: f64,
    /// Largest admissible reading or reference value.
    pub max: f64,
    /// How many values one reading holds (361 for a SICK LMS 291 scan).
    pub readings: u32,
    /// 1-based line in the file; 0 for an entry of the defaults.
    pub line: u32,
}

/// A recognisable object. Its parameters are kept as written because their
/// meaning belongs to the recogniser: `user yellow 30` is a colour name and a
/// size, `door 0.8 1.2` a range of opening widths.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Object {
    pub name: String,
    pub params: Vec<String>,
    pub line: u32,
}

/// A `name value` entry of `[COLORS]`, `[IDENTIFIERS]` or `[PARAMETERS]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NamedValue {
    pub name: String,
    pub value: f64,
    pub line: u32,
}

/// Something the loader had to work around. The model it comes with is still
/// usable; the message says what was wrong and what was used instead.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct ModelWarning {
    /// 1-based line the warning is about; `None` when it concerns the whole
    /// file (for example a missing file).
    pub line: Option<u32>,
    pub message: String,
}

impl ModelWarning {
    pub(crate) fn at(line: u32, message: impl Into<String>) -> ModelWarning {
        ModelWarning {
            line: Some(line),
            message: message.into(),
        }
    }

    pub(crate) fn file(message: impl Into<String>) -> ModelWarning {
        ModelWarning {
            line: None,
            message: message.into(),
        }
    }
}

impl fmt::Display for ModelWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line {
            Some(line) => write!(f, "line {line}: {}", self.message),
            None => f.write_str(&self.message),
        }
    }
}

/// What a name of the model stands for. Serialize only: it borrows from the
/// model, so it cannot be deserialized on its own.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub enum ModelName<'a> {
    Device(&'a Device),
    Object(&'a Object),
    Color(&'a NamedValue),
    Identifier(&'a NamedValue),
    Parameter(&'a NamedValue),
}

impl<'a> ModelName<'a> {
    /// The name as spelled in the file.
    pub fn name(&self) -> &'a str {
        match self {
            ModelName::Device(d) => &d.name,
            ModelName::Object(o) => &o.name,
            ModelName::Color(v) | ModelName::Identifier(v) | ModelName::Parameter(v) => &v.name,
        }
    }

    /// The defining line (0 for defaults).
    pub fn line(&self) -> u32 {
        match self {
            ModelName::Device(d) => d.line,
            ModelName::Object(o) => o.line,
            ModelName::Color(v) | ModelName::Identifier(v) | ModelName::Parameter(v) => v.line,
        }
    }

    /// A one-word kind for hovers and messages: "device", "object",
    /// "color", "identifier" or "parameter".
    pub fn kind(&self) -> &'static str {
        match self {
            ModelName::Device(_) => "device",
            ModelName::Object(_) => "object",
            ModelName::Color(_) => "color",
            ModelName::Identifier(_) => "identifier",
            ModelName::Parameter(_) => "parameter",
        }
    }

    /// The number the name stands for where it has one: a device's id, a
    /// colour, identifier or parameter value. Objects have none.
    pub fn value(&self) -> Option<f64> {
        match self {
            // Device ids are small integers, exactly representable.
            ModelName::Device(d) => Some(d.id as f64),
            ModelName::Object(_) => None,
            ModelName::Color(v) | ModelName::Identifier(v) | ModelName::Parameter(v) => {
                Some(v.value)
            }
        }
    }
}

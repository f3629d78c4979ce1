//! The types in which the catalogue describes a command. They are plain data so that
//! the catalogue can be one `static` table and every consumer (checker, lowering, VM,
//! language server, docs generator) reads the same facts.

use serde::Serialize;

use crate::Command;

/// Table 7's four categories.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Category {
    Define,
    Movement,
    Action,
    ControlFlow,
}

impl Category {
    pub const ALL: [Category; 4] = [
        Category::Define,
        Category::Movement,
        Category::Action,
        Category::ControlFlow,
    ];

    pub fn title(self) -> &'static str {
        match self {
            Category::Define => "Define",
            Category::Movement => "Movement",
            Category::Action => "Action",
            Category::ControlFlow => "Control flow",
        }
    }
}

/// What a variable bound to a command holds (Table 8 fields it fills in).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum VarKind {
    /// Only `status`: the command has ended (skill calls, `while`, `wait`, define commands).
    Status,
    /// `value` from arithmetic or a constant.
    Number,
    /// `value` from a reading that keeps following its sensor (`sensor(battery)`, `locate(x)`).
    Reading,
    /// `x`, `y`, `h` of something found or saved (`sensor(scanner,door)`, `findtarget`, `savepos`).
    Position,
    /// `dist` travelled and the end pose `x`, `y`, `h` of a movement command.
    Movement,
}

impl VarKind {
    pub fn fields(self) -> &'static [Field] {
        match self {
            VarKind::Status => &[Field::Status],
            VarKind::Number | VarKind::Reading => &[Field::Status, Field::Value],
            VarKind::Position => &[Field::Status, Field::X, Field::Y, Field::H],
            VarKind::Movement => &[Field::Status, Field::Dist, Field::X, Field::Y, Field::H],
        }
    }

    /// The field a variable of this kind means when compared with a number, if any
    /// (guide: dist for movement commands, value for readings and arithmetic).
    pub fn numeric_field(self) -> Option<Field> {
        match self {
            VarKind::Status => Some(Field::Status),
            VarKind::Number | VarKind::Reading => Some(Field::Value),
            VarKind::Movement => Some(Field::Dist),
            VarKind::Position => None,
        }
    }

    /// Whether a variable of this kind can stand where a position is expected
    /// (`gotoxy(door)`, `turn(door)`): found objects, saved positions and the end
    /// pose of a movement command.
    pub fn is_position(self) -> bool {
        matches!(self, VarKind::Position | VarKind::Movement)
    }

    pub fn describe(self) -> &'static str {
        match self {
            VarKind::Status => "a status (1 when its command has ended)",
            VarKind::Number => "a number",
            VarKind::Reading => "a sensor reading",
            VarKind::Position => "a position",
            VarKind::Movement => "a movement (distance travelled and end pose)",
        }
    }
}

/// The fields of a variable record, Table 8, plus how its command ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Field {
    Status,
    X,
    Y,
    H,
    Value,
    Dist,
}

impl Field {
    pub fn name(self) -> &'static str {
        match self {
            Field::Status => "status",
            Field::X => "x",
            Field::Y => "y",
            Field::H => "h",
            Field::Value => "value",
            Field::Dist => "dist",
        }
    }

    pub fn doc(self) -> &'static str {
        match self {
            Field::Status => "1 when the associated command has ended, otherwise 0",
            Field::X => "x in metres",
            Field::Y => "y in metres",
            Field::H => "heading in radians",
            Field::Value => "the result of an arithmetic operation or a reading",
            Field::Dist => "the distance travelled by the associated command, in metres",
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Unit {
    None,
    Metres,
    MetresPerSecond,
    Degrees,
    PerMetre,
    Seconds,
}

impl Unit {
    pub fn symbol(self) -> &'static str {
        match self {
            Unit::None => "",
            Unit::Metres => "m",
            Unit::MetresPerSecond => "m/s",
            Unit::Degrees => "deg",
            Unit::PerMetre => "1/m",
            Unit::Seconds => "s",
        }
    }
}

/// What happens when a value known at check time falls outside its range.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Limit {
    /// Requirement 9: a harmful command is rejected before it runs.
    Refuse,
    /// The robot can run it but not as written (a curvature it will clip).
    Warn,
}

/// The admissible values of a number. Model-relative bounds name a `[PARAMETERS]` entry.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case", tag = "type")]
pub enum Range {
    Any,
    /// Inclusive bounds.
    Between {
        min: f64,
        max: f64,
        limit: Limit,
    },
    /// Greater than zero.
    Positive,
    /// Zero or more.
    NonNegative,
    /// `-param ..= param` of the robot model.
    Symmetric {
        param: &'static str,
        limit: Limit,
    },
    /// `|v| <= param`: the sign is free (a turn's curvature), the magnitude bounded.
    Magnitude {
        param: &'static str,
        limit: Limit,
    },
    /// `0 ..= param` of the robot model (road clearance).
    UpTo {
        param: &'static str,
        limit: Limit,
    },
    /// The `min ..= max` of the device named by the command's device argument.
    DeviceRange,
    /// `0 .. readings` of the device named by the command's device argument.
    ReadingIndex,
}

/// Which names of the robot model an argument accepts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ModelNames {
    /// `[SENSORSANDACTUATORS]`, by name or by number.
    Device,
    /// `[OBJECTS]`.
    Object,
    /// Devices or `[IDENTIFIERS]` (services such as `navi`).
    Service,
}

/// One kind of argument a parameter slot accepts.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case", tag = "type")]
pub enum ParamKind {
    /// Exactly one of these words.
    Keyword { words: &'static [&'static str] },
    /// One of these words, each of which the robot model must define in `[IDENTIFIERS]`.
    Mode {
        words: &'static [&'static str],
        what: &'static str,
    },
    /// A number: a literal, a model constant, a variable's value or arithmetic of these.
    Value { unit: Unit, range: Range },
    /// `key = value`, in any order among the other settings.
    Setting {
        key: &'static str,
        unit: Unit,
        range: Range,
    },
    /// A name from the robot model.
    Model { names: ModelNames },
    /// A variable that holds a position (found object, saved position, movement end pose).
    Position,
    /// A variable of any kind, by name.
    Variable,
    /// A free name: a path, a record file or a saved position.
    Name { space: NameSpace },
    /// Any one of these (tried in order).
    OneOf { kinds: &'static [ParamKind] },
}

/// What a free name names, so that the checker can tie a `followpath(p)` to its
/// `record(p)` and the language server can find references.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum NameSpace {
    /// A path recorded with `record` or made with `createpath`, followed with `followpath`.
    Path,
    /// `savepos(name)` binds `name` as a position variable.
    SavedPosition,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Occurs {
    One,
    Optional,
    /// Zero or more.
    Many,
    /// Zero or more pairs of this parameter (createpath's x,y coordinates).
    Pairs,
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Param {
    pub name: &'static str,
    pub kind: ParamKind,
    pub occurs: Occurs,
    pub doc: &'static str,
}

/// One alternative argument list of a command, with what a variable bound to it holds.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Form {
    pub params: &'static [Param],
    /// At least this many arguments (bodypose needs one setting of three optional ones).
    pub min_args: u8,
    pub produces: VarKind,
    /// Short label for messages: "exact turn", "position variable".
    pub label: &'static str,
}

/// How the statement is written: generic `name(args)` or special syntax the parser knows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Syntax {
    /// `name(args)`, or bare `name` when a form takes no arguments.
    Call,
    /// Block openers and closers and `break`, parsed by the grammar itself.
    Structural,
}

/// When a command ends, measured from the instant the VM issues it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case", tag = "type")]
pub enum Ends {
    /// Does its work when issued and has ended before the next statement is issued
    /// (settings, `record`, `actuator`, `stop`): it never waits for a later tick.
    AtIssue,
    /// As `AtIssue`, unless written with this keyword (`speed(v,w)` waits for the
    /// running movement).
    AtIssueWithout { keyword: &'static str },
    /// Can last into later ticks: movements, `wait`, operations of the robot
    /// (`init`, `manipulate`, `movemode`), searches and readings that wait for data.
    Later,
    /// Never ends by itself: only a `break`, a `priority` block or a refusal ends it
    /// (`followwall`), and its variable's status stays 0 until then.
    Never,
    /// As `Later`, but `Never` when written without an argument (`goahead()`).
    NeverBare,
}

impl Ends {
    /// Whether a statement of this command, with these keyword arguments, surely ends
    /// at issue.
    pub fn at_issue<'a>(self, mut keywords: impl Iterator<Item = &'a str>) -> bool {
        match self {
            Ends::AtIssue => true,
            Ends::AtIssueWithout { keyword } => !keywords.any(|k| k.eq_ignore_ascii_case(keyword)),
            Ends::Later | Ends::Never | Ends::NeverBare => false,
        }
    }

    /// Whether a statement of this command, with this many arguments, never ends by
    /// itself.
    pub fn never(self, args: usize) -> bool {
        match self {
            Ends::Never => true,
            Ends::NeverBare => args == 0,
            _ => false,
        }
    }
}

/// What a command sets on the robot outside the movement queue. The robot keeps the
/// last value set, so when two blocks that run at the same time set the same thing in
/// one tick, the one the VM issues last wins (docs/language.md, "Actuators outside the
/// movement queue"; the checker's W0905).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case", tag = "type")]
pub enum Sets {
    Nothing,
    /// One setting of the robot, named for messages (`speed`, `body pose`), unless the
    /// statement is written with `unless` (`speed(v,w)` acts through the movement
    /// queue).
    Setting {
        what: &'static str,
        unless: Option<&'static str>,
    },
    /// The device its first argument names (`actuator(brake,on)` sets the brake).
    Device,
}

impl Sets {
    /// What a statement of this command with these keyword arguments sets: the name
    /// of a setting, or `Device` for the device of its first argument.
    pub fn applies<'a>(self, mut keywords: impl Iterator<Item = &'a str>) -> Sets {
        match self {
            Sets::Setting {
                unless: Some(k), ..
            } if keywords.any(|w| w.eq_ignore_ascii_case(k)) => Sets::Nothing,
            other => other,
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CommandSpec {
    pub command: Command,
    /// Lower-case canonical name.
    pub name: &'static str,
    /// The spelling of Table 7 (`GotoXY`), for docs.
    pub title: &'static str,
    pub category: Category,
    pub syntax: Syntax,
    /// Shares the one movement reservation (section 4.3).
    pub movement: bool,
    /// Holds the rest of its own block back until it ends (guide: wait and init).
    pub holds_block: bool,
    /// A device the robot model must list in `[SENSORSANDACTUATORS]` for the command
    /// to be possible on that robot (`manipulate` needs a `manipulator`).
    pub needs_device: Option<&'static str>,
    /// Whether the command can last past the instant it is issued: a `while` whose
    /// body holds only commands that cannot never gives the tick back (W0902).
    pub ends: Ends,
    /// What it sets outside the movement queue, which the robot keeps until set again.
    pub sets: Sets,
    /// The BNF as the dissertation gives it (with this project's decisions applied).
    pub grammar: &'static str,
    pub forms: &'static [Form],
    pub summary: &'static str,
    pub doc: &'static str,
    pub examples: &'static [&'static str],
    /// Where the dissertation specifies it.
    pub section: &'static str,
}

impl CommandSpec {
    /// Every keyword any form of this command accepts, for completion and for telling a
    /// keyword argument from a variable of the same spelling.
    pub fn keywords(&self) -> impl Iterator<Item = &'static str> + '_ {
        self.forms
            .iter()
            .flat_map(|f| f.params.iter())
            .flat_map(|p| kind_keywords(&p.kind))
    }

    /// Whether `word` (any case) is a keyword somewhere in this command's grammar. The
    /// checker asks this for every name argument, so it walks the table without
    /// allocating.
    pub fn has_keyword(&self, word: &str) -> bool {
        fn in_kind(kind: &ParamKind, word: &str) -> bool {
            match *kind {
                ParamKind::Keyword { words } | ParamKind::Mode { words, .. } => {
                    words.iter().any(|k| k.eq_ignore_ascii_case(word))
                }
                ParamKind::OneOf { kinds } => kinds.iter().any(|k| in_kind(k, word)),
                _ => false,
            }
        }
        self.forms
            .iter()
            .flat_map(|f| f.params)
            .any(|p| in_kind(&p.kind, word))
    }

    /// The unit of a number argument: the setting `key`, or else the positional argument
    /// at `index` (settings not counted), in the first form that takes a number there.
    pub fn unit_of(&self, key: Option<&str>, index: usize) -> Option<Unit> {
        fn unit(kind: &ParamKind) -> Option<Unit> {
            match *kind {
                ParamKind::Value { unit, .. } | ParamKind::Setting { unit, .. } => Some(unit),
                ParamKind::OneOf { kinds } => kinds.iter().find_map(unit),
                _ => None,
            }
        }
        self.forms.iter().find_map(|form| match key {
            Some(key) => form.params.iter().find_map(|p| match p.kind {
                ParamKind::Setting { key: k, unit, .. } if k.eq_ignore_ascii_case(key) => {
                    Some(unit)
                }
                _ => None,
            }),
            None => {
                let positional: Vec<&Param> = form
                    .params
                    .iter()
                    .filter(|p| !matches!(p.kind, ParamKind::Setting { .. }))
                    .collect();
                let repeats = positional
                    .last()
                    .filter(|p| matches!(p.occurs, Occurs::Many | Occurs::Pairs));
                positional
                    .get(index)
                    .or(repeats.filter(|_| index >= positional.len()))
                    .and_then(|p| unit(&p.kind))
            }
        })
    }

    /// Whether some form takes no arguments, so the command may be written bare.
    pub fn allows_bare(&self) -> bool {
        self.forms.iter().any(|f| f.min_args == 0)
    }
}

fn kind_keywords(kind: &ParamKind) -> Box<dyn Iterator<Item = &'static str>> {
    match *kind {
        ParamKind::Keyword { words } | ParamKind::Mode { words, .. } => {
            Box::new(words.iter().copied())
        }
        ParamKind::OneOf { kinds } => Box::new(kinds.iter().flat_map(kind_keywords)),
        _ => Box::new(std::iter::empty()),
    }
}

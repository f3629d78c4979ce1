//! The assertions of a test: what the run must do, evaluated on its trace. The grammar
//! is in docs/testing.md; [`parse`] reads one assertion into an [`Assertion`].

mod lex;
mod parse;

use std::ops::Range;

pub use lex::Tok as Token;
pub use parse::{Context, HAPPENINGS, STARTS, STATES, Want, parse, wants};

#[derive(Debug, Clone, PartialEq)]
pub struct Assertion {
    /// The assertion's text in the test file.
    pub span: Range<usize>,
    pub text: String,
    pub kind: Kind,
}

impl Assertion {
    /// Whether it is read from the trace's scans (which a test's trace leaves out
    /// otherwise).
    pub fn reads_scans(&self) -> bool {
        matches!(
            &self.kind,
            Kind::Always(_, State::Clearance(..))
                | Kind::Never(_, Never::State(State::Clearance(..)))
        )
    }
}

#[derive(Debug, Clone, PartialEq)]
pub enum Kind {
    /// The goal holds at some time, by `within` seconds when given.
    Eventually { within: Option<f64>, goal: Goal },
    /// The state holds at every sample within the scope.
    Always(Scope, State),
    /// Within the scope the happening never happens, or the state never holds.
    Never(Scope, Never),
    /// A's first end is no later than B's first start.
    Before(Command, Command),
    /// A starts no earlier than B and ends no later than B (or the run's end, while B
    /// is still live).
    During(Command, Command),
    /// The check holds when the run has ended.
    AtEnd(Final),
}

/// The part of the run `always` and `never` speak of: from and until given times, and
/// while a command is live (from its start to its first end, or the run's end).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Scope {
    pub from: Option<f64>,
    pub until: Option<f64>,
    pub during: Option<Command>,
}

#[derive(Debug, Clone, PartialEq)]
pub enum Goal {
    /// The command ends, as `how` when given.
    Ends {
        command: Command,
        how: Option<ilmr_trace::How>,
    },
    Var(VarCheck),
    Near(Near),
    Happens(Happening),
}

#[derive(Debug, Clone, PartialEq)]
pub enum State {
    /// The robot's speed (its absolute value) of each pose sample.
    Speed(Cmp, f64),
    /// The distance from the scanner to its nearest hit, each scan.
    Clearance(Cmp, f64),
    /// The robot's position of each pose sample is in the box.
    Inside {
        min: (f64, f64),
        max: (f64, f64),
    },
    Near(Near),
}

#[derive(Debug, Clone, PartialEq)]
pub enum Never {
    Happening(Happening),
    State(State),
}

#[derive(Debug, Clone, PartialEq)]
pub enum Happening {
    /// A command was refused (an `end` event, `refused`).
    Refused,
    /// A command ended broken.
    Broken,
    /// A block overran the tick's budget.
    Overrun,
    /// A runtime error.
    Error,
    /// The supervisor raised a fault: any, or the one named.
    Fault(Option<String>),
}

#[derive(Debug, Clone, PartialEq)]
pub enum Final {
    Near(Near),
    /// The last heading within `within` degrees of `of` degrees.
    Heading {
        within: f64,
        of: f64,
    },
    /// How many commands ended so.
    Count(ilmr_trace::How, Cmp, f64),
    Var(VarCheck),
}

/// A statement of the task: by its line, or by its text.
#[derive(Debug, Clone, PartialEq)]
pub struct Command {
    pub span: Range<usize>,
    /// The line the statement is on in the task file.
    pub line: Option<u32>,
    /// The statement's text (a line's text, when the reference is a line) in the
    /// canonical form of [`canonical`].
    pub text: String,
    /// As written in the assertion, for messages.
    pub shown: String,
}

impl Command {
    /// Whether a trace event's statement is this one. A line is the task file's: a
    /// skill's statement on the same line is another.
    pub fn is(&self, s: &ilmr_trace::Stmt<'_>) -> bool {
        self.line.is_none_or(|l| l == s.line && s.file.is_none())
            && same_statement(&self.text, &s.text)
    }
}

/// A statement's text without spaces or case: `M = GoAhead( 0.7 )` is `m=goahead(0.7)`.
pub fn canonical(text: &str) -> String {
    text.chars()
        .filter(|c| !c.is_whitespace())
        .flat_map(char::to_lowercase)
        .collect()
}

/// The words of an assertion with their bytes, or `None` where it does not lex.
pub fn tokens(text: &str) -> Option<Vec<(Token, Range<usize>)>> {
    lex::lex(text).ok()
}

/// `wanted` (canonical) names the statement `text` (as a statement by text does).
pub fn names_statement(wanted: &str, text: &str) -> bool {
    same_statement(wanted, text)
}

/// `wanted` (canonical) names the traced statement `text`, with or without the
/// variable it assigns: `goahead(0.7)` names `m=goahead(0.7)`.
fn same_statement(wanted: &str, text: &str) -> bool {
    let text = canonical(text);
    if text == wanted {
        return true;
    }
    match text.split_once('=') {
        Some((name, rest)) if is_name(name) && !rest.starts_with('=') => rest == wanted,
        _ => false,
    }
}

pub fn is_name(s: &str) -> bool {
    let mut chars = s.chars();
    chars
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// A variable's field compared with a number.
#[derive(Debug, Clone, PartialEq)]
pub struct VarCheck {
    pub name: String,
    pub field: Field,
    pub cmp: Cmp,
    pub value: f64,
}

/// The fields of a variable a `var` event carries (Table 8).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Field {
    Value,
    Status,
    X,
    Y,
    H,
    Dist,
}

impl Field {
    pub const ALL: [(&'static str, Field); 6] = [
        ("value", Field::Value),
        ("status", Field::Status),
        ("x", Field::X),
        ("y", Field::Y),
        ("h", Field::H),
        ("dist", Field::Dist),
    ];

    pub fn name(self) -> &'static str {
        Field::ALL
            .iter()
            .find(|(_, f)| *f == self)
            .map_or("value", |(n, _)| n)
    }
}

/// The robot within `distance` metres of a place.
#[derive(Debug, Clone, PartialEq)]
pub struct Near {
    pub distance: f64,
    pub place: Place,
}

#[derive(Debug, Clone, PartialEq)]
pub enum Place {
    Point(f64, f64),
    /// A named object of the world, and where it is: a point, or a wall's segment.
    Object {
        name: String,
        from: (f64, f64),
        to: (f64, f64),
    },
}

impl Place {
    /// Metres from `(x, y)` to the place.
    pub fn distance(&self, x: f64, y: f64) -> f64 {
        match self {
            Place::Point(px, py) => (x - px).hypot(y - py),
            Place::Object { from, to, .. } => ilmr_hal::segment_distance((x, y), *from, *to),
        }
    }

    pub fn describe(&self) -> String {
        match self {
            Place::Point(x, y) => format!("({}, {})", num(*x), num(*y)),
            Place::Object { name, .. } => format!("`{name}`"),
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Cmp {
    Eq,
    Ne,
    Lt,
    Le,
    Gt,
    Ge,
}

impl Cmp {
    pub const ALL: [(&'static str, Cmp); 6] = [
        ("==", Cmp::Eq),
        ("!=", Cmp::Ne),
        ("<=", Cmp::Le),
        (">=", Cmp::Ge),
        ("<", Cmp::Lt),
        (">", Cmp::Gt),
    ];

    /// Values within a ten-thousandth are equal: the trace keeps four decimals.
    pub fn holds(self, a: f64, b: f64) -> bool {
        let eq = (a - b).abs() <= 0.5e-4 || a == b;
        match self {
            Cmp::Eq => eq,
            Cmp::Ne => !eq,
            Cmp::Lt => a < b && !eq,
            Cmp::Le => a <= b || eq,
            Cmp::Gt => a > b && !eq,
            Cmp::Ge => a >= b || eq,
        }
    }

    pub fn symbol(self) -> &'static str {
        Cmp::ALL
            .iter()
            .find(|(_, c)| *c == self)
            .map_or("==", |(s, _)| s)
    }
}

/// A number as the trace writes it (at most four decimals).
pub fn num(x: f64) -> String {
    ilmr_trace::fmt_num(x)
}

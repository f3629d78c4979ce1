use serde::{Deserialize, Serialize};

use crate::{CATALOGUE, CommandSpec};

/// The elementary commands, in the order of Table 7 (column by column).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
#[repr(u8)]
pub enum Command {
    MoveMode,
    LocMode,
    Speed,
    BodyPose,
    Locate,
    AdvanceStop,
    ObsAvoid,
    Record,
    Use,
    SavePos,
    CreatePath,
    Goahead,
    Turn,
    FollowPath,
    FollowWall,
    FollowTarget,
    GotoXY,
    GotoRelXY,
    Approach,
    Sensor,
    FindTarget,
    Actuator,
    Manipulate,
    Init,
    If,
    While,
    Break,
    Stop,
    Cont,
    Wait,
    Check,
    Checkend,
    Clear,
}

impl Command {
    pub const COUNT: usize = 33;

    pub fn all() -> impl Iterator<Item = Command> {
        CATALOGUE.iter().map(|s| s.command)
    }

    pub fn spec(self) -> &'static CommandSpec {
        &CATALOGUE[self as usize]
    }

    pub fn name(self) -> &'static str {
        self.spec().name
    }

    /// Commands of which some statement never ends by itself (`Ends::Never`, and
    /// `Ends::NeverBare` written without arguments): what a `wait` may wait on forever.
    pub fn never_ending() -> impl Iterator<Item = Command> {
        Command::all().filter(|c| c.spec().ends.never(0))
    }

    /// Looks a command up by name in any letter case (section 4.5: commands can be given
    /// in upper-case, lower-case or any mixture).
    pub fn from_name(name: &str) -> Option<Command> {
        // Names are 3 to 12 ASCII letters; comparing lengths first keeps this a handful of
        // byte compares per statement on the checker's hot path.
        CATALOGUE
            .iter()
            .find(|s| s.name.len() == name.len() && s.name.eq_ignore_ascii_case(name))
            .map(|s| s.command)
    }
}

impl std::fmt::Display for Command {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

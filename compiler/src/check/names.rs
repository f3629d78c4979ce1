//! What a name means before variables are consulted: a command, a skill, a constant of
//! the robot model. Every binding asks all three (a variable may be none of them) and
//! every call asks two, so one table answers them in one lookup.
//!
//! The table holds exactly the keys of the tables it merges, and is consulted only for
//! ASCII names, whose lower-casing every table agrees on; other names are asked of each
//! table (`Command::from_name`, `Skills::find`, `Constants::get`), so a lookup here
//! always answers what the separate lookups answer.

use ilmr_stdlib::Command;

use crate::check::constants::Constants;
use crate::check::fold::FoldMap;
use crate::check::skills::{SkillId, Skills};

#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Meaning {
    pub command: Option<Command>,
    pub skill: Option<SkillId>,
    pub constant: Option<f64>,
}

/// Built from a `Constants` and a `Skills`, and asked with the same two.
#[derive(Debug, Default)]
pub struct Names {
    /// `None` where building the table would cost more than the lookups it saves (an
    /// interactive line): every name is then asked of each table.
    table: Option<FoldMap<Meaning>>,
}

impl Names {
    pub fn new(constants: &Constants, skills: &Skills) -> Names {
        let mut table: FoldMap<Meaning> =
            FoldMap::with_capacity(Command::COUNT + skills.len() + constants.len());
        for command in Command::all() {
            table
                .get_or_insert_with(&command.name().to_ascii_lowercase(), Meaning::default)
                .command
                .get_or_insert(command);
        }
        for (key, id) in skills.keys() {
            table.get_or_insert_with(key, Meaning::default).skill = Some(id);
        }
        for (key, value) in constants.iter() {
            table.get_or_insert_with(key, Meaning::default).constant = Some(value);
        }
        Names { table: Some(table) }
    }

    /// Names answered by the separate tables.
    pub fn unindexed() -> Names {
        Names { table: None }
    }

    pub fn meaning(
        &self,
        name: &str,
        constants: &Constants,
        skills: &Skills,
        buf: &mut String,
    ) -> Meaning {
        let Some(table) = self.table.as_ref().filter(|_| name.is_ascii()) else {
            return Meaning {
                command: Command::from_name(name),
                skill: skills.find(name),
                constant: constants.get(name, buf),
            };
        };
        table.get(name).copied().unwrap_or_default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_lookup_answers_what_the_separate_tables_answer() {
        let model = ilmr_model::RobotModel::builtin("moro").unwrap();
        let constants = Constants::new(&model);
        let skills = Skills::from_names(["Takebox", "TURN1", "käännös", "ΟΔΟΣ"]);
        let names = Names::new(&constants, &skills);
        let mut buf = String::new();
        let meaning = |name: &str| names.meaning(name, &constants, &skills, &mut String::new());
        let unindexed = Names::unindexed();
        let long = "x".repeat(100);
        for name in [
            "turn",
            "TURN",
            "Turn1",
            "takebox",
            "Käännös",
            "ΟΔΟΣ",
            "οδοσ",
            "max_speed",
            "MAX_SPEED",
            "left",
            "cnt",
            "",
            &long,
            "sensor",
            "k\u{212A}",
        ] {
            let separate = Meaning {
                command: Command::from_name(name),
                skill: skills.find(name),
                constant: constants.get(name, &mut buf),
            };
            assert_eq!(meaning(name), separate, "{name:?}");
            let plain = unindexed.meaning(name, &constants, &skills, &mut String::new());
            assert_eq!(plain, separate, "{name:?}");
        }
        assert_eq!(meaning("cnt"), Meaning::default());
        assert_eq!(meaning("GoToXY").command, Some(Command::GotoXY));
    }
}

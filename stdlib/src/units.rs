//! Units as people write them, and numbers that look written in another unit than the
//! command's. ILMR values are plain numbers in the unit of the catalogue ([`Unit`]); the
//! checker reads this table to say what `speed(30 km/h)` should have been, and to warn
//! where `turn(d=1.57,c=1)` looks like radians. `docs/commands.md` quotes both tables.

use crate::spec::Unit;

/// What a unit measures: a number may be converted only within one dimension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dimension {
    Length,
    Speed,
    Angle,
    Time,
    Curvature,
}

impl Unit {
    pub fn dimension(self) -> Option<Dimension> {
        match self {
            Unit::None => None,
            Unit::Metres => Some(Dimension::Length),
            Unit::MetresPerSecond => Some(Dimension::Speed),
            Unit::Degrees => Some(Dimension::Angle),
            Unit::PerMetre => Some(Dimension::Curvature),
            Unit::Seconds => Some(Dimension::Time),
        }
    }

    /// The unit's name in a sentence ("metres").
    pub fn words(self) -> &'static str {
        match self {
            Unit::None => "plain numbers",
            Unit::Metres => "metres",
            Unit::MetresPerSecond => "metres per second",
            Unit::Degrees => "degrees",
            Unit::PerMetre => "1/m",
            Unit::Seconds => "seconds",
        }
    }
}

/// A unit written after a number: its spellings (compared without case, after the
/// number with spaces removed) and how many of the catalogue's unit one of it is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WrittenUnit {
    pub spellings: &'static [&'static str],
    pub dimension: Dimension,
    /// Value in the catalogue's unit of this dimension (m, m/s, degrees, s) of one of it.
    pub factor: f64,
}

const DEGREES_PER_RADIAN: f64 = 180.0 / std::f64::consts::PI;

pub const WRITTEN_UNITS: &[WrittenUnit] = &[
    WrittenUnit {
        spellings: &["m", "metre", "metres", "meter", "meters"],
        dimension: Dimension::Length,
        factor: 1.0,
    },
    WrittenUnit {
        spellings: &["cm"],
        dimension: Dimension::Length,
        factor: 0.01,
    },
    WrittenUnit {
        spellings: &["mm"],
        dimension: Dimension::Length,
        factor: 0.001,
    },
    WrittenUnit {
        spellings: &["km"],
        dimension: Dimension::Length,
        factor: 1000.0,
    },
    WrittenUnit {
        spellings: &["m/s", "mps"],
        dimension: Dimension::Speed,
        factor: 1.0,
    },
    WrittenUnit {
        spellings: &["km/h", "kmh", "kph", "km/t"],
        dimension: Dimension::Speed,
        factor: 1.0 / 3.6,
    },
    WrittenUnit {
        spellings: &["cm/s"],
        dimension: Dimension::Speed,
        factor: 0.01,
    },
    WrittenUnit {
        spellings: &["mph"],
        dimension: Dimension::Speed,
        factor: 0.44704,
    },
    WrittenUnit {
        spellings: &["deg", "degree", "degrees", "°"],
        dimension: Dimension::Angle,
        factor: 1.0,
    },
    WrittenUnit {
        spellings: &["rad", "radian", "radians"],
        dimension: Dimension::Angle,
        factor: DEGREES_PER_RADIAN,
    },
    WrittenUnit {
        spellings: &["s", "sec", "second", "seconds"],
        dimension: Dimension::Time,
        factor: 1.0,
    },
    WrittenUnit {
        spellings: &["ms"],
        dimension: Dimension::Time,
        factor: 0.001,
    },
    WrittenUnit {
        spellings: &["min"],
        dimension: Dimension::Time,
        factor: 60.0,
    },
];

/// The written unit spelt `text` (any case), if it is one.
pub fn written_unit(text: &str) -> Option<&'static WrittenUnit> {
    WRITTEN_UNITS
        .iter()
        .find(|u| u.spellings.iter().any(|s| s.eq_ignore_ascii_case(text)))
}

/// A degree value no larger than a full turn in radians, with a fraction, whose value
/// in radians is a round angle (see [`round_angle`]), is read as radians: no robot here
/// turns or heads by 1.57 degrees on purpose, and 1.57 rad is 90 degrees.
pub const RADIANS_UP_TO: f64 = std::f64::consts::TAU;

/// A length of this many metres or more in one command is read as centimetres: no robot
/// here drives 100 m in one command or works on a map that large.
pub const CENTIMETRES_FROM: f64 = 100.0;

/// A number that looks written in another unit than its parameter's.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Suspect {
    /// The unit it looks written in ("radians").
    pub looks_like: &'static str,
    /// The value in the parameter's unit if it was written in that one.
    pub meant: f64,
    /// The round value it most likely stood for (`meant` when none is near).
    pub likely: f64,
}

/// Whether `value`, a literal given where `unit` is expected, looks like another unit.
pub fn suspect(unit: Unit, value: f64) -> Option<Suspect> {
    let magnitude = value.abs();
    match unit {
        Unit::Degrees if magnitude > 0.0 && magnitude <= RADIANS_UP_TO && value.fract() != 0.0 => {
            let meant = value * DEGREES_PER_RADIAN;
            round_angle(meant).map(|likely| Suspect {
                looks_like: "radians",
                meant,
                likely,
            })
        }
        Unit::Metres if magnitude >= CENTIMETRES_FROM => Some(Suspect {
            looks_like: "centimetres",
            meant: value / 100.0,
            likely: value / 100.0,
        }),
        _ => None,
    }
}

/// Angles people turn or head by in radians are fractions of pi: multiples of this
/// many degrees (pi/12).
pub const ROUND_ANGLE_DEGREES: f64 = 15.0;
/// How near (degrees) a converted value must come to such a multiple to be taken for
/// it: 1.57 rad is 89.954 degrees, and the one who wrote it meant 90.
pub const ROUND_ANGLE_SLACK: f64 = 0.5;

/// The multiple of [`ROUND_ANGLE_DEGREES`] that `degrees` stands for, if it is that near.
pub fn round_angle(degrees: f64) -> Option<f64> {
    let nearest = (degrees / ROUND_ANGLE_DEGREES).round() * ROUND_ANGLE_DEGREES;
    ((degrees - nearest).abs() <= ROUND_ANGLE_SLACK && nearest != 0.0).then_some(nearest)
}

/// A number as a person would write it: at most three decimals, no trailing zeros.
pub fn round_for_people(value: f64) -> String {
    let text = format!("{value:.3}");
    let text = text.trim_end_matches('0').trim_end_matches('.');
    if text == "-0" {
        "0".to_string()
    } else {
        text.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn written_units_convert_into_the_catalogues_unit() {
        let kmh = written_unit("KM/H").unwrap();
        assert_eq!(kmh.dimension, Dimension::Speed);
        assert_eq!(round_for_people(30.0 * kmh.factor), "8.333");
        assert_eq!(
            round_for_people(0.5 * written_unit("rad").unwrap().factor),
            "28.648"
        );
        assert_eq!(written_unit("furlong"), None);
    }

    #[test]
    fn every_spelling_names_one_unit() {
        let mut all: Vec<&str> = WRITTEN_UNITS
            .iter()
            .flat_map(|u| u.spellings)
            .copied()
            .collect();
        let n = all.len();
        all.sort_unstable();
        all.dedup();
        assert_eq!(all.len(), n);
    }

    #[test]
    fn radians_and_centimetres_are_suspected_where_implausible() {
        let r = suspect(Unit::Degrees, 1.57).unwrap();
        assert_eq!(r.looks_like, "radians");
        assert_eq!(round_for_people(r.meant), "89.954");
        assert_eq!(suspect(Unit::Degrees, 90.0), None);
        assert_eq!(suspect(Unit::Degrees, 3.0), None);
        assert_eq!(suspect(Unit::Degrees, 0.0), None);
        assert_eq!(suspect(Unit::Degrees, 7.5), None);
        assert_eq!(suspect(Unit::Metres, 120.0).unwrap().meant, 1.2);
        assert_eq!(suspect(Unit::Metres, 99.0), None);
        assert_eq!(suspect(Unit::MetresPerSecond, 300.0), None);
        assert_eq!(round_for_people(-0.0001), "0");
        assert_eq!(round_for_people(2.0), "2");
        assert_eq!(round_angle(89.954), Some(90.0));
        assert_eq!(round_angle(28.648), None);
        assert_eq!(suspect(Unit::Degrees, -1.57).unwrap().likely, -90.0);
        assert_eq!(suspect(Unit::Degrees, 0.785).unwrap().likely, 45.0);
        // 0.3 rad is 17.2 degrees, no angle anyone means: a small heading, not radians.
        assert_eq!(suspect(Unit::Degrees, 0.3), None);
        assert_eq!(suspect(Unit::Degrees, 0.5), None);
    }
}

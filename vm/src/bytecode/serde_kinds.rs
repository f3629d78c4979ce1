//! Serde for the catalogue's `Field` and `VarKind`, which the stdlib only serialises.
//! In JSON they travel by their lower-case names; in the `.ilmb` file by their place
//! in the tables below, which are the format's own numbering (reordering the stdlib's
//! enums does not change a file).

use ilmr_stdlib::{Field, VarKind};

const FIELDS: [Field; 6] = [
    Field::Status,
    Field::X,
    Field::Y,
    Field::H,
    Field::Value,
    Field::Dist,
];

const VAR_KINDS: [VarKind; 5] = [
    VarKind::Status,
    VarKind::Number,
    VarKind::Reading,
    VarKind::Position,
    VarKind::Movement,
];

fn field_from_name(name: &str) -> Option<Field> {
    FIELDS.into_iter().find(|f| f.name() == name)
}

pub(crate) fn var_kind_from_name(name: &str) -> Option<VarKind> {
    VAR_KINDS.into_iter().find(|k| var_kind_name(*k) == name)
}

pub(crate) fn var_kind_name(kind: VarKind) -> &'static str {
    match kind {
        VarKind::Status => "status",
        VarKind::Number => "number",
        VarKind::Reading => "reading",
        VarKind::Position => "position",
        VarKind::Movement => "movement",
    }
}

fn number<T: PartialEq + Copy>(table: &[T], value: T) -> u8 {
    // Every value has its place: the tables list each variant once.
    table.iter().position(|&t| t == value).unwrap_or(0) as u8
}

pub(crate) mod serde_field {
    use ilmr_stdlib::Field;
    use serde::{Deserialize, Deserializer, Serializer, de::Error};

    use super::{FIELDS, number};

    pub fn serialize<S: Serializer>(f: &Field, s: S) -> Result<S::Ok, S::Error> {
        if s.is_human_readable() {
            s.serialize_str(f.name())
        } else {
            s.serialize_u8(number(&FIELDS, *f))
        }
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Field, D::Error> {
        if d.is_human_readable() {
            let name = String::deserialize(d)?;
            super::field_from_name(&name)
                .ok_or_else(|| D::Error::custom(format!("no field {name}")))
        } else {
            let n = u8::deserialize(d)?;
            FIELDS
                .get(n as usize)
                .copied()
                .ok_or_else(|| D::Error::custom(format!("no field number {n}")))
        }
    }
}

pub(crate) mod serde_var_kind {
    use ilmr_stdlib::VarKind;
    use serde::{Deserialize, Deserializer, Serializer, de::Error};

    use super::{VAR_KINDS, number};

    pub fn serialize<S: Serializer>(k: &VarKind, s: S) -> Result<S::Ok, S::Error> {
        if s.is_human_readable() {
            s.serialize_str(super::var_kind_name(*k))
        } else {
            s.serialize_u8(number(&VAR_KINDS, *k))
        }
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<VarKind, D::Error> {
        if d.is_human_readable() {
            let name = String::deserialize(d)?;
            super::var_kind_from_name(&name)
                .ok_or_else(|| D::Error::custom(format!("no variable kind {name}")))
        } else {
            let n = u8::deserialize(d)?;
            VAR_KINDS
                .get(n as usize)
                .copied()
                .ok_or_else(|| D::Error::custom(format!("no variable kind number {n}")))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_field_and_kind_has_one_number_and_one_name() {
        for (i, f) in FIELDS.iter().enumerate() {
            assert_eq!(number(&FIELDS, *f) as usize, i);
            assert_eq!(field_from_name(f.name()), Some(*f));
        }
        for (i, k) in VAR_KINDS.iter().enumerate() {
            assert_eq!(number(&VAR_KINDS, *k) as usize, i);
            assert_eq!(var_kind_from_name(var_kind_name(*k)), Some(*k));
        }
        // Movement and Number together hold every field.
        let mut all: Vec<Field> = VarKind::Movement.fields().to_vec();
        all.extend(VarKind::Number.fields());
        assert!(all.iter().all(|f| FIELDS.contains(f)));
        assert!(FIELDS.iter().all(|f| all.contains(f)));
    }
}

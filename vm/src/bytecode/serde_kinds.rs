//! Serde for the catalogue's `Field` and `VarKind`, which the stdlib only serialises.
//! They travel by their lower-case names.

fn field_from_name(name: &str) -> Option<ilmr_stdlib::Field> {
    use ilmr_stdlib::VarKind;
    // Movement holds status, dist, x, y, h; Number adds value: together every field.
    VarKind::Movement
        .fields()
        .iter()
        .chain(VarKind::Number.fields())
        .copied()
        .find(|f| f.name() == name)
}

pub(crate) fn var_kind_from_name(name: &str) -> Option<ilmr_stdlib::VarKind> {
    use ilmr_stdlib::VarKind::*;
    [Status, Number, Reading, Position, Movement]
        .into_iter()
        .find(|k| var_kind_name(*k) == name)
}

pub(crate) fn var_kind_name(kind: ilmr_stdlib::VarKind) -> &'static str {
    use ilmr_stdlib::VarKind::*;
    match kind {
        Status => "status",
        Number => "number",
        Reading => "reading",
        Position => "position",
        Movement => "movement",
    }
}

pub(crate) mod serde_field {
    use ilmr_stdlib::Field;
    use serde::{Deserialize, Deserializer, Serializer, de::Error};

    pub fn serialize<S: Serializer>(f: &Field, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(f.name())
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Field, D::Error> {
        let name = String::deserialize(d)?;
        super::field_from_name(&name).ok_or_else(|| D::Error::custom(format!("no field {name}")))
    }
}

pub(crate) mod serde_var_kind {
    use ilmr_stdlib::VarKind;
    use serde::{Deserialize, Deserializer, Serializer, de::Error};

    pub fn serialize<S: Serializer>(k: &VarKind, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(super::var_kind_name(*k))
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<VarKind, D::Error> {
        let name = String::deserialize(d)?;
        super::var_kind_from_name(&name)
            .ok_or_else(|| D::Error::custom(format!("no variable kind {name}")))
    }
}

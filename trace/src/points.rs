//! Lists of points, `[[x, y], ...]`: reference paths and scanner hits.

use std::borrow::Cow;

use schemars::{JsonSchema, Schema, SchemaGenerator};
use serde::ser::SerializeSeq;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use crate::Num;

/// Points as `[x, y]` pairs of [`Num`]s. The writer lends its own list (`Cow`), so a
/// reference path is written without copying it.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Points<'a>(pub Cow<'a, [(f64, f64)]>);

impl<'a> From<&'a [(f64, f64)]> for Points<'a> {
    fn from(points: &'a [(f64, f64)]) -> Points<'a> {
        Points(Cow::Borrowed(points))
    }
}

impl From<Vec<(f64, f64)>> for Points<'static> {
    fn from(points: Vec<(f64, f64)>) -> Points<'static> {
        Points(Cow::Owned(points))
    }
}

impl Serialize for Points<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut seq = s.serialize_seq(Some(self.0.len()))?;
        for &(x, y) in self.0.iter() {
            seq.serialize_element(&[Num(x), Num(y)])?;
        }
        seq.end()
    }
}

impl<'de> Deserialize<'de> for Points<'_> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let pairs = Vec::<[Num; 2]>::deserialize(d)?;
        Ok(Points(Cow::Owned(
            pairs.into_iter().map(|[x, y]| (x.0, y.0)).collect(),
        )))
    }
}

impl JsonSchema for Points<'_> {
    fn schema_name() -> Cow<'static, str> {
        "Points".into()
    }

    fn json_schema(generator: &mut SchemaGenerator) -> Schema {
        <Vec<[Num; 2]>>::json_schema(generator)
    }
}

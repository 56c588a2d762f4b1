//! Serde for the names an error carries (of coordinates, constraints,
//! inputs, methods): `&'static str` in the error, because they come from
//! the model's and the method's constants. Serialized as strings;
//! deserialized into strings that live for the rest of the program (each
//! deserialized name is allocated once and never freed: a few bytes per
//! error read back, which is what a `&'static str` field costs to fill
//! from data).

use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// One name.
pub(crate) mod one {
    use super::*;

    pub(crate) fn serialize<S: Serializer>(name: &&'static str, s: S) -> Result<S::Ok, S::Error> {
        name.serialize(s)
    }

    pub(crate) fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<&'static str, D::Error> {
        Ok(String::deserialize(d)?.leak())
    }
}

/// A list of names.
pub(crate) mod list {
    use super::*;

    pub(crate) fn serialize<S: Serializer>(
        names: &&'static [&'static str],
        s: S,
    ) -> Result<S::Ok, S::Error> {
        names.serialize(s)
    }

    pub(crate) fn deserialize<'de, D: Deserializer<'de>>(
        d: D,
    ) -> Result<&'static [&'static str], D::Error> {
        let names: Vec<&'static str> = Vec::<String>::deserialize(d)?
            .into_iter()
            .map(|n| &*n.leak())
            .collect();
        Ok(names.leak())
    }
}

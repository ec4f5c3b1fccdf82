//! Serde form of a `Vec<bool>` as a string of `0` and `1` (one byte per element instead of
//! a JSON array of `true`/`false`): the contact sets of a checkpoint, in the library's
//! and in the output layer's (`#[serde(with = "adhesim::bit_string")]`).

use serde::{Deserialize, Deserializer, Serializer};

/// Writes `bits` as one string of `0` and `1`.
pub fn serialize<S: Serializer>(bits: &[bool], serializer: S) -> Result<S::Ok, S::Error> {
    let text: String = bits.iter().map(|&b| if b { '1' } else { '0' }).collect();
    serializer.serialize_str(&text)
}

/// Reads a string of `0` and `1`; any other character is an error naming it.
pub fn deserialize<'de, D: Deserializer<'de>>(deserializer: D) -> Result<Vec<bool>, D::Error> {
    let text = String::deserialize(deserializer)?;
    text.bytes()
        .map(|b| match b {
            b'0' => Ok(false),
            b'1' => Ok(true),
            other => Err(serde::de::Error::custom(format!(
                "a bit string holds `{}`",
                char::from(other).escape_default()
            ))),
        })
        .collect()
}

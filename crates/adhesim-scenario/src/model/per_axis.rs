//! `[grid]` values given once for both axes (a square) or per axis as `[x, y]`.

use serde::de::{DeserializeOwned, Error as _};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// One value for both axes, or one per axis `[x, y]` (rectangular grids, docs/validation.md §12: `n = [nx, ny]`,
/// `size = [sx, sy]`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PerAxis<T> {
    /// `key = value`: the same along x and y.
    Both(T),
    /// `key = [x, y]`.
    Axes(T, T),
}

impl<T: Copy> PerAxis<T> {
    /// (x, y).
    pub fn pair(&self) -> (T, T) {
        match *self {
            Self::Both(value) => (value, value),
            Self::Axes(x, y) => (x, y),
        }
    }
}

impl<T: Copy> PerAxis<T> {
    /// The value as the scenario file gives it, each number written by `show`.
    pub fn show(&self, show: impl Fn(T) -> String) -> String {
        match *self {
            Self::Both(value) => show(value),
            Self::Axes(x, y) => format!("[{}, {}]", show(x), show(y)),
        }
    }
}

impl<T: Copy + std::fmt::Display> std::fmt::Display for PerAxis<T> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.show(|value| value.to_string()))
    }
}

impl<T: Serialize> Serialize for PerAxis<T> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self {
            Self::Both(value) => value.serialize(serializer),
            Self::Axes(x, y) => [x, y].serialize(serializer),
        }
    }
}

impl<'de, T: DeserializeOwned> Deserialize<'de> for PerAxis<T> {
    /// A value of T, or an array of exactly two; an element's error is T's own message
    /// (so that the key at fault is found as for any other value).
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let value = toml::Value::deserialize(deserializer)?;
        let one = |value: toml::Value| T::deserialize(value).map_err(|e| D::Error::custom(e.message().trim()));
        match value {
            toml::Value::Array(items) if items.len() == 2 => {
                let mut items = items.into_iter();
                let x = one(items.next().expect("two items"))?;
                let y = one(items.next().expect("two items"))?;
                Ok(Self::Axes(x, y))
            }
            toml::Value::Array(items) => Err(D::Error::custom(format!(
                "expected one value for both axes or two as [x, y], got an array of {}",
                items.len()
            ))),
            other => Ok(Self::Both(one(other)?)),
        }
    }
}

//! JSON parsed with every object's keys unique. `serde_json` keeps the last of repeated
//! keys silently (RFC 8259 §4 leaves the behaviour to the parser), so a hand-edited sidecar
//! holding `"rpm": 1800 … "rpm": 900` ran at 900 rpm without a word (outside probe, stop 69).
//! A repeated key is refused instead, naming the key, its line and its column.

use serde::de::{Deserialize, Deserializer, Error, MapAccess, SeqAccess, Visitor};
use serde_json::{Map, Value};

/// A [`Value`] whose objects were read with unique keys.
struct Unique(Value);

impl<'de> Deserialize<'de> for Unique {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(UniqueVisitor).map(Unique)
    }
}

struct UniqueVisitor;

impl<'de> Visitor<'de> for UniqueVisitor {
    type Value = Value;

    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("a JSON value")
    }
    fn visit_bool<E: Error>(self, v: bool) -> Result<Value, E> {
        Ok(Value::Bool(v))
    }
    fn visit_i64<E: Error>(self, v: i64) -> Result<Value, E> {
        Ok(Value::from(v))
    }
    fn visit_u64<E: Error>(self, v: u64) -> Result<Value, E> {
        Ok(Value::from(v))
    }
    fn visit_f64<E: Error>(self, v: f64) -> Result<Value, E> {
        Ok(Value::from(v))
    }
    fn visit_str<E: Error>(self, v: &str) -> Result<Value, E> {
        Ok(Value::String(v.to_string()))
    }
    fn visit_string<E: Error>(self, v: String) -> Result<Value, E> {
        Ok(Value::String(v))
    }
    fn visit_unit<E: Error>(self) -> Result<Value, E> {
        Ok(Value::Null)
    }
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Value, A::Error> {
        let mut v = Vec::new();
        while let Some(Unique(x)) = seq.next_element()? {
            v.push(x);
        }
        Ok(Value::Array(v))
    }
    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Value, A::Error> {
        let mut m = Map::new();
        while let Some(k) = map.next_key::<String>()? {
            if m.contains_key(&k) {
                return Err(A::Error::custom(format!(
                    "key {k:?} appears twice in one object (which one is meant?)"
                )));
            }
            let Unique(v) = map.next_value()?;
            m.insert(k, v);
        }
        Ok(Value::Object(m))
    }
}

/// Parses `bytes` as one JSON value, refusing an object that repeats a key (the message
/// names the key, line and column, as `serde_json`'s own errors do).
pub fn from_slice(bytes: &[u8]) -> Result<Value, serde_json::Error> {
    serde_json::from_slice::<Unique>(bytes).map(|u| u.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn repeated_keys_are_refused_at_any_depth_and_the_rest_reads_as_serde_json() {
        let ok = br#"{"a": [1, -2, 2.5, "x", null, true, {"b": {}}], "c": {"d": 1e300}}"#;
        assert_eq!(
            from_slice(ok).unwrap(),
            serde_json::from_slice::<Value>(ok).unwrap()
        );
        for bad in [
            &br#"{"rpm": 1800.0, "fs": 1, "rpm": 900.0}"#[..],
            br#"{"bearing": {"geometry": {"elements": 9,
                 "elements": 12}}}"#,
            br#"[{"x": 1}, {"rpm": 1, "rpm": 1}]"#,
        ] {
            let e = from_slice(bad).unwrap_err().to_string();
            assert!(e.contains("appears twice") && e.contains("line"), "{e}");
        }
        // The same key in different objects is no repeat.
        assert!(from_slice(br#"{"a": {"k": 1}, "b": {"k": 2}, "k": 3}"#).is_ok());
    }
}

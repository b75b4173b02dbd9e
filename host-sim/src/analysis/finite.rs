//! The last guard before a result is printed: finds a non-finite number anywhere in a
//! serialisable value (JSON would print it as `null`, text as `NaN`/`inf`), so that a
//! command can fail with a message instead of presenting it (docs/reliability.md).

use serde::ser::{self, Serialize};
use std::fmt;

/// Path (`a.b[3].c`) and value of the first non-finite number in `v`, if any.
pub fn first_non_finite<T: Serialize + ?Sized>(v: &T) -> Option<(String, f64)> {
    let mut s = Scan {
        path: vec![],
        found: None,
    };
    let _ = v.serialize(&mut s);
    s.found
}

struct Scan {
    path: Vec<String>,
    found: Option<(String, f64)>,
}

#[derive(Debug)]
struct Stop;
impl fmt::Display for Stop {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("non-finite number")
    }
}
impl std::error::Error for Stop {}
impl ser::Error for Stop {
    fn custom<T: fmt::Display>(_: T) -> Self {
        Stop
    }
}

impl Scan {
    fn float(&mut self, v: f64) -> Result<(), Stop> {
        if v.is_finite() {
            Ok(())
        } else {
            self.found = Some((self.path.join("."), v));
            Err(Stop)
        }
    }
    fn nested<T: Serialize + ?Sized>(&mut self, key: String, v: &T) -> Result<(), Stop> {
        self.path.push(key);
        let r = v.serialize(&mut *self);
        self.path.pop();
        r
    }
}

macro_rules! ok_scalars {
    ($($f:ident: $t:ty),*) => { $(fn $f(self, _: $t) -> Result<(), Stop> { Ok(()) })* };
}

/// The `serialize_*` methods that begin a compound value: every one scans its contents with a
/// fresh [`Seq`] (the arguments, a name, a variant or a length, are not needed).
macro_rules! begin_compound {
    ($($f:ident($($t:ty),*)),*) => {$(
        fn $f(self, $(_: $t),*) -> Result<Self::SerializeSeq, Stop> {
            Ok(Seq { s: self, i: 0 })
        }
    )*};
}

impl<'a> ser::Serializer for &'a mut Scan {
    type Ok = ();
    type Error = Stop;
    type SerializeSeq = Seq<'a>;
    type SerializeTuple = Seq<'a>;
    type SerializeTupleStruct = Seq<'a>;
    type SerializeTupleVariant = Seq<'a>;
    type SerializeMap = Seq<'a>;
    type SerializeStruct = Seq<'a>;
    type SerializeStructVariant = Seq<'a>;
    ok_scalars!(serialize_bool: bool, serialize_i8: i8, serialize_i16: i16, serialize_i32: i32,
        serialize_i64: i64, serialize_u8: u8, serialize_u16: u16, serialize_u32: u32,
        serialize_u64: u64, serialize_char: char, serialize_str: &str, serialize_bytes: &[u8],
        serialize_unit_struct: &'static str);
    fn serialize_f32(self, v: f32) -> Result<(), Stop> {
        self.float(v as f64)
    }
    fn serialize_f64(self, v: f64) -> Result<(), Stop> {
        self.float(v)
    }
    fn serialize_none(self) -> Result<(), Stop> {
        Ok(())
    }
    fn serialize_some<T: Serialize + ?Sized>(self, v: &T) -> Result<(), Stop> {
        v.serialize(self)
    }
    fn serialize_unit(self) -> Result<(), Stop> {
        Ok(())
    }
    fn serialize_unit_variant(self, _: &'static str, _: u32, _: &'static str) -> Result<(), Stop> {
        Ok(())
    }
    fn serialize_newtype_struct<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        v: &T,
    ) -> Result<(), Stop> {
        v.serialize(self)
    }
    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
        v: &T,
    ) -> Result<(), Stop> {
        self.nested(variant.into(), v)
    }
    begin_compound!(
        serialize_seq(Option<usize>),
        serialize_tuple(usize),
        serialize_tuple_struct(&'static str, usize),
        serialize_tuple_variant(&'static str, u32, &'static str, usize),
        serialize_map(Option<usize>),
        serialize_struct(&'static str, usize),
        serialize_struct_variant(&'static str, u32, &'static str, usize)
    );
}

/// Any compound value: elements are named by their index, fields by their name.
struct Seq<'a> {
    s: &'a mut Scan,
    i: usize,
}

impl Seq<'_> {
    fn element<T: Serialize + ?Sized>(&mut self, v: &T) -> Result<(), Stop> {
        let k = format!("[{}]", self.i);
        self.i += 1;
        self.s.nested(k, v)
    }
}

macro_rules! compound {
    ($($tr:ident :: $m:ident),*) => {$(
        impl ser::$tr for Seq<'_> {
            type Ok = ();
            type Error = Stop;
            fn $m<T: Serialize + ?Sized>(&mut self, v: &T) -> Result<(), Stop> {
                self.element(v)
            }
            fn end(self) -> Result<(), Stop> {
                Ok(())
            }
        }
    )*};
}
compound!(
    SerializeSeq::serialize_element,
    SerializeTuple::serialize_element,
    SerializeTupleStruct::serialize_field,
    SerializeTupleVariant::serialize_field
);

impl ser::SerializeMap for Seq<'_> {
    type Ok = ();
    type Error = Stop;
    fn serialize_key<T: Serialize + ?Sized>(&mut self, _: &T) -> Result<(), Stop> {
        Ok(())
    }
    fn serialize_value<T: Serialize + ?Sized>(&mut self, v: &T) -> Result<(), Stop> {
        self.element(v)
    }
    fn end(self) -> Result<(), Stop> {
        Ok(())
    }
}

macro_rules! fields {
    ($($tr:ident),*) => {$(
        impl ser::$tr for Seq<'_> {
            type Ok = ();
            type Error = Stop;
            fn serialize_field<T: Serialize + ?Sized>(
                &mut self,
                key: &'static str,
                v: &T,
            ) -> Result<(), Stop> {
                self.s.nested(key.into(), v)
            }
            fn end(self) -> Result<(), Stop> {
                Ok(())
            }
        }
    )*};
}
fields!(SerializeStruct, SerializeStructVariant);

#[cfg(test)]
mod tests {
    use super::*;
    use serde::Serialize;

    #[derive(Serialize)]
    struct Inner {
        k: f64,
    }
    #[derive(Serialize)]
    struct Outer {
        a: f64,
        b: Vec<Inner>,
        c: Option<f64>,
    }

    #[test]
    fn finds_the_first_non_finite_number_and_its_path() {
        let ok = Outer {
            a: 1.0,
            b: vec![Inner { k: 2.0 }],
            c: None,
        };
        assert_eq!(first_non_finite(&ok), None);
        let bad = Outer {
            a: 1.0,
            b: vec![Inner { k: 2.0 }, Inner { k: f64::NAN }],
            c: Some(f64::INFINITY),
        };
        let (path, v) = first_non_finite(&bad).unwrap();
        assert_eq!(path, "b.[1].k");
        assert!(v.is_nan());
        let v = serde_json::json!({"x": [1.0, 2.0]});
        assert_eq!(first_non_finite(&v), None);
    }
}

//! The deserializer the schema is read through: a TOML value, read as toml's own deserializer
//! reads it, except that
//!
//! * a struct (every table of the schema, wherever it sits: a field, an `Option`, an element of
//!   an array of tables) is read only from a TOML table. serde's derived structs also accept a
//!   sequence, field by field in declaration order, so that without this check
//!   `stability = [1.0]` would silently read as `kinetic_energy_fraction = 1`;
//! * a float given where the schema wants an integer, a string or a boolean, and an integer out
//!   of its type's range, are reported in short notation ([`crate::units::short`]), never as a
//!   300-digit expansion;
//! * a number, boolean or list where the schema wants one of a set of names is reported as what
//!   it is, with the names.

use crate::units::short;
use serde::de::{self, DeserializeSeed, Deserializer, Expected, MapAccess, SeqAccess, Visitor};
use toml::Value;

type Error = toml::de::Error;

/// A TOML value to deserialize the schema from.
pub(crate) struct Strict(pub(crate) Value);

/// What a TOML value is, for "expected a table, found ...".
fn kind(v: &Value) -> String {
    match v {
        Value::String(_) => "a string".into(),
        Value::Integer(i) => format!("a number ({})", short(*i as f64)),
        Value::Float(x) => format!("a number ({})", short(*x)),
        Value::Boolean(_) => "a boolean".into(),
        Value::Datetime(_) => "a date-time".into(),
        Value::Array(_) => "an array".into(),
        Value::Table(_) => "a table".into(),
    }
}

/// The error for a float where `visitor` wants something else.
fn float_where_not_wanted(x: f64, visitor: &dyn Expected) -> Error {
    de::Error::invalid_type(
        de::Unexpected::Other(&format!("floating point `{}`", short(x))),
        visitor,
    )
}

impl Strict {
    fn seq<'de, V: Visitor<'de>>(items: Vec<Value>, visitor: V) -> Result<V::Value, Error> {
        let len = items.len();
        let expected = (&visitor as &dyn Expected).to_string();
        let mut seq = Seq(items.into_iter());
        let out = visitor.visit_seq(&mut seq)?;
        if seq.0.len() == 0 {
            Ok(out)
        } else {
            Err(de::Error::invalid_length(len, &expected.as_str()))
        }
    }

    fn map<'de, V: Visitor<'de>>(table: toml::Table, visitor: V) -> Result<V::Value, Error> {
        let len = table.len();
        let mut map = Map {
            iter: table.into_iter(),
            value: None,
        };
        let out = visitor.visit_map(&mut map)?;
        if map.iter.len() == 0 {
            Ok(out)
        } else {
            Err(de::Error::invalid_length(
                len,
                &"fewer entries in the table",
            ))
        }
    }

    /// Anything but a number: a float is refused in short notation, the rest read as usual.
    fn not_a_number<'de, V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        match self.0 {
            Value::Float(x) => Err(float_where_not_wanted(x, &visitor)),
            _ => self.deserialize_any(visitor),
        }
    }
}

/// An integer type: a float or an integer out of the type's range is refused in short notation.
macro_rules! integer {
    ($($method:ident: $t:ty),* $(,)?) => {$(
        fn $method<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
            match self.0 {
                Value::Float(x) => Err(float_where_not_wanted(x, &visitor)),
                Value::Integer(i) if <$t>::try_from(i).is_err() => Err(de::Error::invalid_value(
                    de::Unexpected::Other(&format!("integer `{}`", short(i as f64))),
                    &visitor,
                )),
                other => other.deserialize_any(visitor),
            }
        }
    )*};
}

/// Everything else that is not a number.
macro_rules! not_a_number {
    ($($method:ident),* $(,)?) => {$(
        fn $method<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
            self.not_a_number(visitor)
        }
    )*};
}

impl<'de> Deserializer<'de> for Strict {
    type Error = Error;

    fn deserialize_any<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        match self.0 {
            Value::Array(items) => Strict::seq(items, visitor),
            Value::Table(table) => Strict::map(table, visitor),
            other => other.deserialize_any(visitor),
        }
    }

    fn deserialize_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        _fields: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, Error> {
        match self.0 {
            Value::Table(table) => Strict::map(table, visitor),
            other => Err(de::Error::custom(format!(
                "expected a table, found {}",
                kind(&other)
            ))),
        }
    }

    // `None` is a missing field, so a present value is always `Some`.
    fn deserialize_option<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        visitor.visit_some(self)
    }

    fn deserialize_newtype_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        visitor: V,
    ) -> Result<V::Value, Error> {
        visitor.visit_newtype_struct(self)
    }

    fn deserialize_enum<V: Visitor<'de>>(
        self,
        name: &'static str,
        variants: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, Error> {
        match self.0 {
            // A name (or, for a variant with data, a table): anything else is said as what it
            // is, with the names expected, not as serde's "unit variant".
            other @ (Value::String(_) | Value::Table(_)) => {
                other.deserialize_enum(name, variants, visitor)
            }
            other => {
                let names: Vec<String> = variants.iter().map(|v| format!("\"{v}\"")).collect();
                Err(de::Error::custom(format!(
                    "expected one of {}, found {}",
                    names.join(", "),
                    kind(&other)
                )))
            }
        }
    }

    fn deserialize_f64<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        self.deserialize_any(visitor)
    }

    fn deserialize_f32<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        self.deserialize_any(visitor)
    }

    fn deserialize_ignored_any<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        self.0.deserialize_ignored_any(visitor)
    }

    integer! {
        deserialize_u8: u8, deserialize_u16: u16, deserialize_u32: u32, deserialize_u64: u64,
        deserialize_u128: u128, deserialize_i8: i8, deserialize_i16: i16, deserialize_i32: i32,
        deserialize_i64: i64, deserialize_i128: i128,
    }

    not_a_number! {
        deserialize_bool, deserialize_char, deserialize_str, deserialize_string,
        deserialize_bytes, deserialize_byte_buf, deserialize_unit, deserialize_seq,
        deserialize_map, deserialize_identifier,
    }

    fn deserialize_unit_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        visitor: V,
    ) -> Result<V::Value, Error> {
        self.not_a_number(visitor)
    }

    fn deserialize_tuple<V: Visitor<'de>>(
        self,
        _len: usize,
        visitor: V,
    ) -> Result<V::Value, Error> {
        self.not_a_number(visitor)
    }

    fn deserialize_tuple_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        _len: usize,
        visitor: V,
    ) -> Result<V::Value, Error> {
        self.not_a_number(visitor)
    }
}

/// The elements of an array, each read strictly.
struct Seq(std::vec::IntoIter<Value>);

impl<'de> SeqAccess<'de> for Seq {
    type Error = Error;

    fn next_element_seed<T: DeserializeSeed<'de>>(
        &mut self,
        seed: T,
    ) -> Result<Option<T::Value>, Error> {
        self.0
            .next()
            .map(|v| seed.deserialize(Strict(v)))
            .transpose()
    }

    fn size_hint(&self) -> Option<usize> {
        Some(self.0.len())
    }
}

/// The entries of a table, each value read strictly.
struct Map {
    iter: <toml::Table as IntoIterator>::IntoIter,
    value: Option<Value>,
}

impl<'de> MapAccess<'de> for Map {
    type Error = Error;

    fn next_key_seed<K: DeserializeSeed<'de>>(
        &mut self,
        seed: K,
    ) -> Result<Option<K::Value>, Error> {
        match self.iter.next() {
            Some((key, value)) => {
                self.value = Some(value);
                seed.deserialize(de::value::StringDeserializer::<Error>::new(key))
                    .map(Some)
            }
            None => Ok(None),
        }
    }

    fn next_value_seed<T: DeserializeSeed<'de>>(&mut self, seed: T) -> Result<T::Value, Error> {
        match self.value.take() {
            Some(value) => seed.deserialize(Strict(value)),
            None => Err(de::Error::custom("a table value was read twice")),
        }
    }

    fn size_hint(&self) -> Option<usize> {
        Some(self.iter.len())
    }
}

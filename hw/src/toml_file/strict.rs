//! A deserializer adapter that holds fixed-length arrays to their length: toml lets `[f64; 2]` take the
//! first two of three numbers and drop the rest; read through [`Strict`], the array is refused instead,
//! saying how many values were found and how many are allowed.

use std::fmt;

use serde::de::{
    DeserializeSeed, Deserializer, EnumAccess, Error, IgnoredAny, MapAccess, SeqAccess, VariantAccess,
    Visitor,
};

/// Wraps a deserializer, or what it hands on (a seed, a sequence, a map, an enum, a variant), so that
/// every tuple read through it (`[T; N]`, `(A, B)`, a tuple struct or tuple variant) must hold exactly
/// its length, at any depth: inside structs, maps, options, sequences, enums, newtypes and `Spanned`.
pub(crate) struct Strict<T>(pub(crate) T);

/// The visitor of a value read through [`Strict`]; `len` is the exact length when it reads a tuple.
struct Visit<V> {
    visitor: V,
    len: Option<usize>,
}

impl<V> Visit<V> {
    fn any(visitor: V) -> Self {
        Self { visitor, len: None }
    }
}

/// "3 values where exactly 2 are allowed".
fn wrong_length<E: Error>(found: usize, allowed: usize) -> E {
    let plural = if found == 1 { "" } else { "s" };
    let verb = if allowed == 1 { "is" } else { "are" };
    E::custom(format_args!("{found} value{plural} where exactly {allowed} {verb} allowed"))
}

macro_rules! forward_deserialize {
    ($($method:ident($($arg:ident: $ty:ty),*);)*) => {$(
        fn $method<V: Visitor<'de>>(self, $($arg: $ty,)* visitor: V) -> Result<V::Value, D::Error> {
            self.0.$method($($arg,)* Visit::any(visitor))
        }
    )*};
}

impl<'de, D: Deserializer<'de>> Deserializer<'de> for Strict<D> {
    type Error = D::Error;

    forward_deserialize! {
        deserialize_any(); deserialize_bool(); deserialize_char(); deserialize_unit(); deserialize_option();
        deserialize_i8(); deserialize_i16(); deserialize_i32(); deserialize_i64(); deserialize_i128();
        deserialize_u8(); deserialize_u16(); deserialize_u32(); deserialize_u64(); deserialize_u128();
        deserialize_f32(); deserialize_f64(); deserialize_str(); deserialize_string();
        deserialize_bytes(); deserialize_byte_buf(); deserialize_identifier(); deserialize_ignored_any();
        deserialize_seq(); deserialize_map();
        deserialize_unit_struct(name: &'static str);
        deserialize_newtype_struct(name: &'static str);
        deserialize_struct(name: &'static str, fields: &'static [&'static str]);
        deserialize_enum(name: &'static str, variants: &'static [&'static str]);
    }

    fn deserialize_tuple<V: Visitor<'de>>(self, len: usize, visitor: V) -> Result<V::Value, D::Error> {
        self.0.deserialize_tuple(len, Visit { visitor, len: Some(len) })
    }

    fn deserialize_tuple_struct<V: Visitor<'de>>(
        self,
        name: &'static str,
        len: usize,
        visitor: V,
    ) -> Result<V::Value, D::Error> {
        self.0.deserialize_tuple_struct(name, len, Visit { visitor, len: Some(len) })
    }

    fn is_human_readable(&self) -> bool {
        self.0.is_human_readable()
    }
}

macro_rules! forward_visit {
    ($($method:ident($($v:ident: $ty:ty)?);)*) => {$(
        fn $method<E: Error>(self $(, $v: $ty)?) -> Result<V::Value, E> {
            self.visitor.$method($($v)?)
        }
    )*};
}

impl<'de, V: Visitor<'de>> Visitor<'de> for Visit<V> {
    type Value = V::Value;

    fn expecting(&self, formatter: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.visitor.expecting(formatter)
    }

    forward_visit! {
        visit_bool(v: bool); visit_char(v: char); visit_none(); visit_unit();
        visit_i8(v: i8); visit_i16(v: i16); visit_i32(v: i32); visit_i64(v: i64); visit_i128(v: i128);
        visit_u8(v: u8); visit_u16(v: u16); visit_u32(v: u32); visit_u64(v: u64); visit_u128(v: u128);
        visit_f32(v: f32); visit_f64(v: f64);
        visit_str(v: &str); visit_borrowed_str(v: &'de str); visit_string(v: String);
        visit_bytes(v: &[u8]); visit_borrowed_bytes(v: &'de [u8]); visit_byte_buf(v: Vec<u8>);
    }

    fn visit_some<D: Deserializer<'de>>(self, deserializer: D) -> Result<V::Value, D::Error> {
        self.visitor.visit_some(Strict(deserializer))
    }

    fn visit_newtype_struct<D: Deserializer<'de>>(self, deserializer: D) -> Result<V::Value, D::Error> {
        self.visitor.visit_newtype_struct(Strict(deserializer))
    }

    fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<V::Value, A::Error> {
        self.visitor.visit_map(Strict(map))
    }

    fn visit_enum<A: EnumAccess<'de>>(self, data: A) -> Result<V::Value, A::Error> {
        self.visitor.visit_enum(Strict(data))
    }

    /// For a tuple: refuses a sequence whose length (toml's exact size hint) is not the tuple's before
    /// reading it, and one with values left over after the inner visitor is done. The error comes from
    /// inside the array's own `deserialize_*` call, so toml gives it the array's span.
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<V::Value, A::Error> {
        let Some(len) = self.len else { return self.visitor.visit_seq(Strict(seq)) };
        if let Some(found) = seq.size_hint().filter(|&found| found != len) {
            return Err(wrong_length(found, len));
        }
        let value = self.visitor.visit_seq(Strict(&mut seq))?;
        let mut left = 0;
        while seq.next_element::<IgnoredAny>()?.is_some() {
            left += 1;
        }
        if left == 0 { Ok(value) } else { Err(wrong_length(len + left, len)) }
    }
}

impl<'de, S: DeserializeSeed<'de>> DeserializeSeed<'de> for Strict<S> {
    type Value = S::Value;

    fn deserialize<D: Deserializer<'de>>(self, deserializer: D) -> Result<S::Value, D::Error> {
        self.0.deserialize(Strict(deserializer))
    }
}

impl<'de, A: SeqAccess<'de>> SeqAccess<'de> for Strict<A> {
    type Error = A::Error;

    fn next_element_seed<T: DeserializeSeed<'de>>(&mut self, seed: T) -> Result<Option<T::Value>, A::Error> {
        self.0.next_element_seed(Strict(seed))
    }

    fn size_hint(&self) -> Option<usize> {
        self.0.size_hint()
    }
}

impl<'de, A: MapAccess<'de>> MapAccess<'de> for Strict<A> {
    type Error = A::Error;

    fn next_key_seed<K: DeserializeSeed<'de>>(&mut self, seed: K) -> Result<Option<K::Value>, A::Error> {
        self.0.next_key_seed(Strict(seed))
    }

    fn next_value_seed<T: DeserializeSeed<'de>>(&mut self, seed: T) -> Result<T::Value, A::Error> {
        self.0.next_value_seed(Strict(seed))
    }

    fn size_hint(&self) -> Option<usize> {
        self.0.size_hint()
    }
}

impl<'de, A: EnumAccess<'de>> EnumAccess<'de> for Strict<A> {
    type Error = A::Error;
    type Variant = Strict<A::Variant>;

    fn variant_seed<S: DeserializeSeed<'de>>(self, seed: S) -> Result<(S::Value, Self::Variant), A::Error> {
        self.0.variant_seed(Strict(seed)).map(|(value, variant)| (value, Strict(variant)))
    }
}

impl<'de, A: VariantAccess<'de>> VariantAccess<'de> for Strict<A> {
    type Error = A::Error;

    fn unit_variant(self) -> Result<(), A::Error> {
        self.0.unit_variant()
    }

    fn newtype_variant_seed<T: DeserializeSeed<'de>>(self, seed: T) -> Result<T::Value, A::Error> {
        self.0.newtype_variant_seed(Strict(seed))
    }

    fn tuple_variant<V: Visitor<'de>>(self, len: usize, visitor: V) -> Result<V::Value, A::Error> {
        self.0.tuple_variant(len, Visit { visitor, len: Some(len) })
    }

    fn struct_variant<V: Visitor<'de>>(
        self,
        fields: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, A::Error> {
        self.0.struct_variant(fields, Visit::any(visitor))
    }
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeMap;

    use serde::Deserialize;
    use toml::Spanned;

    use crate::toml_file::{TomlProblem, deserialize};

    #[derive(Debug, Deserialize)]
    #[serde(deny_unknown_fields)]
    struct Doc {
        list: Vec<[f64; 3]>,
        rows: [[f64; 2]; 3],
        position_m: Spanned<[f64; 3]>,
        pair: (f64, f64),
        gap: Gap,
        tool: Tool,
        outer: Outer,
        trocars: BTreeMap<String, [f64; 3]>,
    }

    #[derive(Debug, Deserialize)]
    #[serde(deny_unknown_fields)]
    struct Outer {
        stitch_x_m: [f64; 2],
        trocar_m: Option<[f64; 3]>,
    }

    #[derive(Debug, Deserialize, PartialEq)]
    struct Gap(f64, f64);

    #[derive(Debug, Deserialize, PartialEq)]
    #[serde(rename_all = "snake_case", deny_unknown_fields)]
    enum Tool {
        Needle { tip_m: [f64; 3] },
        Point([f64; 2]),
    }

    /// Every array and tuple at its exact length; line numbers below count from here.
    const VALID: &str = "\
list = [
    [0.0, 0.0, 1.0],
    [0.0, 0.1, 1.0],
]
rows = [[1.0, 2.0], [3.0, 4.0], [5.0, 6.0]]
position_m = [0.0, 0.0, 0.95]
pair = [1.0, 2.0]
gap = [0.5, 0.6]
tool = { needle = { tip_m = [0.0, 0.0, 1.0] } }

[outer]
stitch_x_m = [-0.01, 0.01]
trocar_m = [0.0, 0.1, 1.0]

[trocars]
left = [-0.08, 0.12, 1.02]
";

    fn refused(text: &str) -> TomlProblem {
        match deserialize::<Doc>(text) {
            Ok(doc) => panic!("read {doc:?} from\n{text}"),
            Err(p) => p,
        }
    }

    /// Arrays of exactly their length still read at every depth (nested, in a `Vec`, an `Option`, a map,
    /// a newtype, an enum), and `Spanned` still gets its array's span through the adapter.
    #[test]
    fn arrays_of_their_length_are_read() {
        let doc = deserialize::<Doc>(VALID).unwrap();
        assert_eq!(doc.list, [[0.0, 0.0, 1.0], [0.0, 0.1, 1.0]]);
        assert_eq!(doc.rows, [[1.0, 2.0], [3.0, 4.0], [5.0, 6.0]]);
        assert_eq!(*doc.position_m.get_ref(), [0.0, 0.0, 0.95]);
        assert_eq!(&VALID[doc.position_m.span()], "[0.0, 0.0, 0.95]");
        assert_eq!((doc.pair, doc.gap), ((1.0, 2.0), Gap(0.5, 0.6)));
        assert_eq!(doc.tool, Tool::Needle { tip_m: [0.0, 0.0, 1.0] });
        assert_eq!((doc.outer.stitch_x_m, doc.outer.trocar_m), ([-0.01, 0.01], Some([0.0, 0.1, 1.0])));
        assert_eq!(doc.trocars["left"], [-0.08, 0.12, 1.02]);
        let text =
            VALID.replace("tool = { needle = { tip_m = [0.0, 0.0, 1.0] } }", "tool = { point = [1.0, 2.0] }");
        assert_eq!(deserialize::<Doc>(&text).unwrap().tool, Tool::Point([1.0, 2.0]));
    }

    /// An array with one value too many or too few is refused, not cut short or padded: the error names
    /// the array's 1-based line, the key's path and how many values were found and are allowed.
    #[test]
    fn an_array_too_long_or_too_short_is_refused_with_line_key_and_counts() {
        let cases = [
            ("stitch_x_m = [-0.01, 0.01]", "stitch_x_m = [-0.01, 0.0, 0.01]", 12, "outer.stitch_x_m", 3, 2),
            ("stitch_x_m = [-0.01, 0.01]", "stitch_x_m = [-0.01]", 12, "outer.stitch_x_m", 1, 2),
            ("trocar_m = [0.0, 0.1, 1.0]", "trocar_m = [0.0, 0.1, 1.0, 2.0]", 13, "outer.trocar_m", 4, 3),
            ("trocar_m = [0.0, 0.1, 1.0]", "trocar_m = [0.0, 0.1]", 13, "outer.trocar_m", 2, 3),
            ("    [0.0, 0.1, 1.0],", "    [0.0, 0.1, 1.0, 0.0],", 3, "list[1]", 4, 3),
            ("    [0.0, 0.1, 1.0],", "    [0.0, 0.1],", 3, "list[1]", 2, 3),
            ("[5.0, 6.0]]", "[5.0, 6.0, 7.0]]", 5, "rows[2]", 3, 2),
            ("[5.0, 6.0]]", "[5.0, 6.0], [7.0, 8.0]]", 5, "rows", 4, 3),
            ("[3.0, 4.0], [5.0, 6.0]]", "[3.0, 4.0]]", 5, "rows", 2, 3),
            ("[0.0, 0.0, 0.95]", "[0.0, 0.0, 0.95, 1.0]", 6, "position_m", 4, 3),
            ("[0.0, 0.0, 0.95]", "[0.0, 0.0]", 6, "position_m", 2, 3),
            ("pair = [1.0, 2.0]", "pair = [1.0, 2.0, 3.0]", 7, "pair", 3, 2),
            ("gap = [0.5, 0.6]", "gap = [0.5]", 8, "gap", 1, 2),
            ("tip_m = [0.0, 0.0, 1.0]", "tip_m = [0.0, 0.0, 1.0, 2.0]", 9, "tool.needle.tip_m", 4, 3),
            ("left = [-0.08, 0.12, 1.02]", "left = [-0.08, 0.12, 1.02, 0.0]", 16, "trocars.left", 4, 3),
        ];
        for (old, new, line, key, found, allowed) in cases {
            assert!(VALID.contains(old), "{old}");
            let p = refused(&VALID.replacen(old, new, 1));
            let are = if allowed == 1 { "is" } else { "are" };
            let s = if found == 1 { "" } else { "s" };
            let reason = format!("{found} value{s} where exactly {allowed} {are} allowed");
            assert_eq!((p.line, p.key.as_str(), p.reason.as_str()), (line, key, reason.as_str()), "{new}");
        }
        let text =
            VALID.replace("tool = { needle = { tip_m = [0.0, 0.0, 1.0] } }", "tool = { point = [1.0] }");
        let p = refused(&text);
        assert_eq!((p.line, p.reason.as_str()), (9, "1 value where exactly 2 are allowed"), "{p}");
    }

    /// A sequence that does not tell its length up front still may not hold more than its tuple: the
    /// values left after the array is read are counted and refused.
    #[test]
    fn values_left_over_in_a_sequence_of_unknown_length_are_refused() {
        use serde::de::value::{Error, SeqDeserializer};
        let seq = |n: usize| SeqDeserializer::<_, Error>::new((1..=n).map(|i| i as f64).filter(|_| true));
        assert_eq!(<[f64; 2]>::deserialize(super::Strict(seq(2))).unwrap(), [1.0, 2.0]);
        let e = <[f64; 2]>::deserialize(super::Strict(seq(4))).unwrap_err();
        assert_eq!(e.to_string(), "4 values where exactly 2 are allowed");
    }
}

//! The scene file's reference page (`docs/reference/scene.md`) against the loader
//! (`knotlab_sim::scene`): guards against the reference drifting from what the loader accepts. Every
//! key the loader accepts has a row on the page, and every row names a key the loader accepts.
//!
//! Keys are compared as dotted paths: `solver.dt_s`, `servo.calibration_offset_rad.left`; a key of an
//! array of tables as `obstacles[].centre_m`; a key of a named table as `presets.NAME.play_rad`; a
//! top-level key alone (`description`).
//!
//! The page: a `## [table]` or `## [[table]]` heading (or `## Top level`) starts the rows of that
//! table; any other `##` heading ends them. Under a table heading every table row but the header and
//! its separator is one key: `` | `key` | meaning | unit | allowed | default | ``, the key as written
//! under that heading.
//!
//! The loader's keys: the shipped scenes (`scenarios/default.toml`, the rope, and `scenarios/chain.toml`,
//! the chain) and a fixture that also sets every key they leave out are parsed with
//! [`parse_scene`]; the keys of their texts and of their parsed `SceneConfig`s serialized back to TOML
//! are collected. The fixture is itself checked against the schema: a walk through `SceneConfig`'s
//! `Deserialize` impl lists every key its structs declare, and each must be among those collected,
//! so a key added to the schema but left out of the fixture fails here rather than going unseen. The
//! same walk gives the names an enum key takes (`thread.model`, `evaluation.accepted`); its row must
//! list each, quoted as in the file.

use std::cell::RefCell;
use std::collections::{BTreeMap, BTreeSet};

use knotlab_sim::scene::{SceneConfig, parse_scene};
use serde::Deserialize as _;
use serde::de::value::{Error as WalkError, StrDeserializer};
use serde::de::{self, DeserializeSeed, Deserializer, IntoDeserializer, MapAccess, SeqAccess, Visitor};

const PAGE: &str = include_str!("../../../docs/reference/scene.md");
const DEFAULT: &str = include_str!("../../../scenarios/default.toml");
const CHAIN: &str = include_str!("../../../scenarios/chain.toml");

/// Tables whose keys are names the file chooses (`[presets.endopar]`): each reads as `NAME`.
const NAMED_TABLES: [&str; 1] = ["presets"];

/// The shipped rope scene with every key it leaves out set: the rope's optional key, a random obstacle,
/// a preset setting every bound, a fixed obstacle. (The chain's keys come from `scenarios/chain.toml`.)
fn every_key_scene() -> String {
    let text = with_lines_after(DEFAULT, "rope_spacing_radii = ", "rope_direct_bending = true");
    format!(
        "{text}
[[randomization.obstacle]]
probability = 0.5
offset_m = [[0.03, 0.05], [-0.02, 0.02], [0.0, 0.01]]
half_extents_m = [[0.005, 0.01], [0.005, 0.01], [0.01, 0.02]]

[presets.every_key]
description = \"sets every bound\"
stitch_x_m = [-0.01, 0.01]
stitch_y_m = [-0.01, 0.01]
stitch_z_m = [0.0, 0.0]
stitch_rotate_rad = [-0.1, 0.1]
play_rad = [0.0, 0.001]
calibration_rad = [-0.001, 0.001]
thread_friction = [0.1, 0.2]
thread_bend_stiffness = [1e-5, 3e-5]
force_noise_n = [0.0, 0.01]

[[obstacles]]
centre_m = [0.2, 0.2, 1.1]
half_extents_m = [0.01, 0.02, 0.03]
"
    )
}

/// `text` with `extra` inserted after its one line starting with `line_start`.
fn with_lines_after(text: &str, line_start: &str, extra: &str) -> String {
    let hits = text.lines().filter(|l| l.starts_with(line_start)).count();
    assert_eq!(hits, 1, "the fixture's anchor `{line_start}` must start exactly one line of the scene");
    let mut out = String::new();
    for line in text.lines() {
        out.push_str(line);
        out.push('\n');
        if line.starts_with(line_start) {
            out.push_str(extra);
            out.push('\n');
        }
    }
    out
}

/// The path of key `key` in a table at `prefix` (`""` at the top level).
fn join(prefix: &str, key: &str) -> String {
    let key = if NAMED_TABLES.contains(&prefix) { "NAME" } else { key };
    if prefix.is_empty() { key.to_owned() } else { format!("{prefix}.{key}") }
}

/// Adds the path of every key in `table` (at `prefix`) to `keys`: a table's keys by their own paths, an
/// array of tables' keys as `prefix.key[].inner`, any other value (numbers, strings, arrays of them) as a
/// key of its own. An empty array says nothing of what it would hold and adds nothing.
fn toml_keys(prefix: &str, table: &toml::Table, keys: &mut BTreeSet<String>) {
    for (key, value) in table {
        let path = join(prefix, key);
        match value {
            toml::Value::Table(inner) => toml_keys(&path, inner, keys),
            toml::Value::Array(items) if items.is_empty() => {}
            toml::Value::Array(items) if items.iter().all(toml::Value::is_table) => {
                for item in items {
                    toml_keys(&format!("{path}[]"), item.as_table().expect("a table"), keys);
                }
            }
            _ => {
                keys.insert(path);
            }
        }
    }
}

/// Every key of scene `text`, which must load: those written in it and those of the scene it loads
/// to, serialized back (every field but an `Option` left out and empty lists and tables).
fn scene_keys(text: &str, name: &str, keys: &mut BTreeSet<String>) {
    let scene = parse_scene(text, name).unwrap_or_else(|e| panic!("{name} must load: {e}"));
    toml_keys("", &text.parse::<toml::Table>().expect("a scene that loads is TOML"), keys);
    let serialized = toml::Value::try_from(&scene).expect("a loaded scene serializes to TOML");
    toml_keys("", serialized.as_table().expect("a scene serializes to a table"), keys);
}

/// Every key the loader accepted in the shipped scenes and the fixture.
fn loaded_keys() -> BTreeSet<String> {
    let mut keys = BTreeSet::new();
    scene_keys(DEFAULT, "scenarios/default.toml", &mut keys);
    scene_keys(CHAIN, "scenarios/chain.toml", &mut keys);
    scene_keys(&every_key_scene(), "every_key_scene", &mut keys);
    keys
}

/// Every key the page documents, with its row; a key documented twice, or a row under a table heading
/// that does not name one key, fails, naming the page's line.
fn documented_rows() -> BTreeMap<String, &'static str> {
    let mut keys = BTreeMap::new();
    let mut prefix: Option<String> = None;
    for (i, line) in PAGE.lines().enumerate() {
        let line_no = i + 1;
        if let Some(heading) = line.strip_prefix("## ") {
            let heading = heading.trim();
            prefix = if heading == "Top level" {
                Some(String::new())
            } else if let Some(name) = heading.strip_prefix("[[").and_then(|h| h.strip_suffix("]]")) {
                Some(format!("{name}[]"))
            } else {
                heading.strip_prefix('[').and_then(|h| h.strip_suffix(']')).map(str::to_owned)
            };
            continue;
        }
        let (Some(prefix), Some(row)) = (&prefix, line.trim().strip_prefix('|')) else { continue };
        let first = row.split('|').next().unwrap_or("").trim();
        if first == "key" || first.starts_with("---") {
            continue;
        }
        let key = first
            .strip_prefix('`')
            .and_then(|k| k.strip_suffix('`'))
            .filter(|k| !k.is_empty() && !k.contains(['`', ' ']))
            .unwrap_or_else(|| {
                panic!("docs/reference/scene.md:{line_no}: a row under a table heading must name one key in backticks, got `{first}`")
            });
        let path = if prefix.is_empty() { key.to_owned() } else { format!("{prefix}.{key}") };
        let earlier = keys.insert(path.clone(), line);
        assert!(earlier.is_none(), "docs/reference/scene.md:{line_no}: `{path}` has a row already");
    }
    keys
}

/// Every key the page documents.
fn documented_keys() -> BTreeSet<String> {
    documented_rows().into_keys().collect()
}

/// Every key the loader accepts has a row on the page.
#[test]
fn every_key_the_loader_accepts_has_a_row_in_the_reference() {
    let documented = documented_keys();
    let missing: Vec<String> = loaded_keys().into_iter().filter(|k| !documented.contains(k)).collect();
    assert!(
        missing.is_empty(),
        "the loader accepts these keys, which docs/reference/scene.md does not document: {missing:?}"
    );
}

/// Every row of the page names a key the loader accepts.
#[test]
fn every_key_in_the_reference_is_one_the_loader_accepts() {
    let loaded = loaded_keys();
    let unknown: Vec<String> = documented_keys().into_iter().filter(|k| !loaded.contains(k)).collect();
    assert!(
        unknown.is_empty(),
        "docs/reference/scene.md documents these keys, which no scene here loads with (the loader refuses them, or every_key_scene does not set them): {unknown:?}"
    );
}

/// The scenes the keys are collected from set every key the schema declares: a key added to a struct
/// of the scene must be set in `every_key_scene` (or a shipped scene), so that the two tests above
/// see it.
#[test]
fn the_collected_keys_are_every_key_the_schema_declares() {
    let declared: BTreeSet<String> = schema_keys().into_keys().collect();
    let loaded = loaded_keys();
    let unset: Vec<&String> = declared.difference(&loaded).collect();
    assert!(
        unset.is_empty(),
        "no scene here sets these keys of the schema; set them in every_key_scene: {unset:?}"
    );
    let undeclared: Vec<&String> = loaded.difference(&declared).collect();
    assert!(
        undeclared.is_empty(),
        "these keys loaded, but the schema walk did not find them: {undeclared:?}"
    );
}

/// The row of a key that takes one of a few names (`thread.model`, `evaluation.accepted`) lists every
/// name the loader takes, quoted as in the file (`` `"rope"` ``).
#[test]
fn the_reference_lists_every_name_an_enum_key_takes() {
    let rows = documented_rows();
    for (key, names) in schema_keys() {
        let Some(row) = rows.get(&key) else { continue };
        let unlisted: Vec<&str> =
            names.iter().copied().filter(|n| !row.contains(&format!("`\"{n}\"`"))).collect();
        assert!(
            unlisted.is_empty(),
            "docs/reference/scene.md: the row of `{key}` does not list {unlisted:?}"
        );
    }
}

/// Every key `SceneConfig`'s `Deserialize` impl declares, with the names it takes if it is an enum (none
/// otherwise), found by deserializing it from [`SchemaWalk`].
fn schema_keys() -> BTreeMap<String, &'static [&'static str]> {
    let keys = RefCell::new(BTreeMap::new());
    SceneConfig::deserialize(SchemaWalk { path: String::new(), keys: &keys })
        .unwrap_or_else(|e| panic!("the schema walk: {e}"));
    keys.into_inner()
}

/// A deserializer that hands a `Deserialize` impl every field it asks for (a struct's declared
/// fields, one element of a list, one entry named `NAME` of a map, an enum's first variant, zero or
/// false or an empty string for a scalar) and records the path of each value that is not a table, with
/// an enum's variants.
/// Paths follow [`toml_keys`]: a list's element adds `[]`, dropped again at a value that is not a table
/// (`[f64; 3]` is its key alone). Types that only `deserialize_any` could read (untagged enums,
/// `flatten`) fail the walk, naming the path.
struct SchemaWalk<'a> {
    path: String,
    keys: &'a RefCell<BTreeMap<String, &'static [&'static str]>>,
}

impl SchemaWalk<'_> {
    fn record(&self) {
        self.record_names(&[]);
    }

    fn record_names(&self, names: &'static [&'static str]) {
        self.keys.borrow_mut().insert(self.path.trim_end_matches("[]").to_owned(), names);
    }

    fn at(&self, path: String) -> Self {
        SchemaWalk { path, keys: self.keys }
    }
}

macro_rules! walk_scalars {
    ($($method:ident => $visit:ident($value:expr);)*) => {$(
        fn $method<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, WalkError> {
            self.record();
            visitor.$visit($value)
        }
    )*};
}

impl<'de> Deserializer<'de> for SchemaWalk<'_> {
    type Error = WalkError;

    fn deserialize_any<V: Visitor<'de>>(self, _visitor: V) -> Result<V::Value, WalkError> {
        Err(de::Error::custom(format!(
            "`{}`: a value only `deserialize_any` reads; walk it another way",
            self.path
        )))
    }

    walk_scalars! {
        deserialize_bool => visit_bool(false);
        deserialize_i8 => visit_i64(0);
        deserialize_i16 => visit_i64(0);
        deserialize_i32 => visit_i64(0);
        deserialize_i64 => visit_i64(0);
        deserialize_u8 => visit_u64(0);
        deserialize_u16 => visit_u64(0);
        deserialize_u32 => visit_u64(0);
        deserialize_u64 => visit_u64(0);
        deserialize_f32 => visit_f64(0.0);
        deserialize_f64 => visit_f64(0.0);
        deserialize_str => visit_str("");
        deserialize_string => visit_str("");
    }

    fn deserialize_option<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, WalkError> {
        visitor.visit_some(self)
    }

    fn deserialize_newtype_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        visitor: V,
    ) -> Result<V::Value, WalkError> {
        visitor.visit_newtype_struct(self)
    }

    fn deserialize_seq<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, WalkError> {
        visitor.visit_seq(Elements { walk: self.at(format!("{}[]", self.path)), left: 1 })
    }

    fn deserialize_tuple<V: Visitor<'de>>(self, len: usize, visitor: V) -> Result<V::Value, WalkError> {
        visitor.visit_seq(Elements { walk: self.at(format!("{}[]", self.path)), left: len })
    }

    fn deserialize_map<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, WalkError> {
        visitor.visit_map(Fields { walk: self, names: &["NAME"], next: 0 })
    }

    fn deserialize_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        fields: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, WalkError> {
        visitor.visit_map(Fields { walk: self, names: fields, next: 0 })
    }

    fn deserialize_enum<V: Visitor<'de>>(
        self,
        name: &'static str,
        variants: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, WalkError> {
        self.record_names(variants);
        let first = variants.first().ok_or_else(|| de::Error::custom(format!("{name} has no variants")))?;
        let variant: StrDeserializer<'_, WalkError> = (*first).into_deserializer();
        visitor.visit_enum(variant)
    }

    serde::forward_to_deserialize_any! {
        i128 u128 char bytes byte_buf unit unit_struct tuple_struct identifier ignored_any
    }
}

/// A struct's fields (or a map's one entry), each value walked at its own path.
struct Fields<'a> {
    walk: SchemaWalk<'a>,
    names: &'static [&'static str],
    next: usize,
}

impl<'de> MapAccess<'de> for Fields<'_> {
    type Error = WalkError;

    fn next_key_seed<K: DeserializeSeed<'de>>(&mut self, seed: K) -> Result<Option<K::Value>, WalkError> {
        let Some(name) = self.names.get(self.next) else { return Ok(None) };
        let name: StrDeserializer<'_, WalkError> = (*name).into_deserializer();
        seed.deserialize(name).map(Some)
    }

    fn next_value_seed<S: DeserializeSeed<'de>>(&mut self, seed: S) -> Result<S::Value, WalkError> {
        let name = self.names[self.next];
        self.next += 1;
        let path =
            if self.walk.path.is_empty() { name.to_owned() } else { format!("{}.{name}", self.walk.path) };
        seed.deserialize(self.walk.at(path))
    }
}

/// A list's or a tuple's elements, all walked at the same path.
struct Elements<'a> {
    walk: SchemaWalk<'a>,
    left: usize,
}

impl<'de> SeqAccess<'de> for Elements<'_> {
    type Error = WalkError;

    fn next_element_seed<S: DeserializeSeed<'de>>(&mut self, seed: S) -> Result<Option<S::Value>, WalkError> {
        if self.left == 0 {
            return Ok(None);
        }
        self.left -= 1;
        seed.deserialize(self.walk.at(self.walk.path.clone())).map(Some)
    }
}

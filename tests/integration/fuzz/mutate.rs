//! The fuzzers' inputs: mutations of a valid text (on its characters: numbers, lists, lines, bytes;
//! and on its TOML or JSON tree: numbers, arrays, types, keys) and raw random text.

use std::sync::Arc;

use proptest::collection::vec;
use proptest::prelude::*;
use proptest::sample::{Index, select};

/// Numbers a parser must refuse or bound, as TOML, JSON, CSV and XML spell them (or fail to).
pub const NUMBERS: &[&str] = &[
    "nan",
    "NaN",
    "-nan",
    "inf",
    "-inf",
    "+inf",
    "infinity",
    "1e308",
    "-1e308",
    "1e999",
    "-0.0",
    "-0",
    "0",
    "0.0",
    "1000000000000000000",
    "-1000000000000000000",
    "1e18",
    "99999999999999999999999",
    "-1",
    "-2.5",
    "5e-324",
    "1e-300",
    "4294967296",
    "18446744073709551615",
    "9223372036854775807",
    "-9223372036854775808",
    "0x10",
    "1_000",
    "1.",
    ".5",
    "1e",
];

/// Values of another type than the one they replace, in TOML's, JSON's and plain text's spelling.
pub const OTHER_VALUES: &[&str] = &[
    "\"text\"",
    "\"\"",
    "\"1.0\"",
    "true",
    "false",
    "[]",
    "[1.0, 2.0]",
    "[[]]",
    "{}",
    "{ x = 1 }",
    "{\"x\": 1}",
    "null",
    "word",
    "",
    "1979-05-27T07:32:00Z",
    "'single'",
    "\"\\u0000\"",
];

/// Text spliced into an input.
pub fn noise() -> impl Strategy<Value = String> {
    prop_oneof![
        4 => "[\\[\\]{}<>=,.:;\"'#\n\r\t a-z0-9_+-]{0,40}",
        1 => any::<String>().prop_map(|s| s.chars().take(40).collect()),
        1 => select(NUMBERS).prop_map(str::to_owned),
        1 => select(OTHER_VALUES).prop_map(str::to_owned),
    ]
}

/// What changes in a list (a `[...]` array, a line's comma-separated fields, or an XML attribute's
/// space-separated numbers).
#[derive(Debug, Clone)]
pub enum ListOp {
    /// Drop one element.
    Drop(Index),
    /// Write one element twice.
    Duplicate(Index),
    /// Append a copy of one element.
    Append(Index),
    /// Append a number.
    AppendNumber(&'static str),
    /// Keep only the first elements.
    KeepFirst(Index),
    /// Remove every element.
    Clear,
    /// One element, many times (up to 200).
    Grow(Index, usize),
}

fn list_op() -> impl Strategy<Value = ListOp> {
    prop_oneof![
        3 => any::<Index>().prop_map(ListOp::Drop),
        3 => any::<Index>().prop_map(ListOp::Duplicate),
        2 => any::<Index>().prop_map(ListOp::Append),
        1 => select(NUMBERS).prop_map(ListOp::AppendNumber),
        1 => any::<Index>().prop_map(ListOp::KeepFirst),
        1 => Just(ListOp::Clear),
        1 => (any::<Index>(), 2..200usize).prop_map(|(i, n)| ListOp::Grow(i, n)),
    ]
}

impl ListOp {
    /// Applies the op to a list's elements; `number` makes the element an appended number is.
    fn apply<T: Clone>(&self, items: &mut Vec<T>, number: impl Fn(&'static str) -> T) {
        let at = |i: &Index, items: &Vec<T>| (!items.is_empty()).then(|| i.index(items.len()));
        match self {
            ListOp::Drop(i) => {
                if let Some(k) = at(i, items) {
                    items.remove(k);
                }
            }
            ListOp::Duplicate(i) => {
                if let Some(k) = at(i, items) {
                    items.insert(k, items[k].clone());
                }
            }
            ListOp::Append(i) => {
                if let Some(k) = at(i, items) {
                    items.push(items[k].clone());
                }
            }
            ListOp::AppendNumber(n) => items.push(number(n)),
            ListOp::KeepFirst(i) => {
                if let Some(k) = at(i, items) {
                    items.truncate(k);
                }
            }
            ListOp::Clear => items.clear(),
            ListOp::Grow(i, n) => {
                if let Some(k) = at(i, items) {
                    let item = items[k].clone();
                    items.splice(k..k, std::iter::repeat_n(item, *n));
                }
            }
        }
    }
}

/// A change to a text, on its characters.
#[derive(Debug, Clone)]
pub enum TextMutation {
    /// A number replaced by another (NaN, infinities, huge, negative, zero, malformed).
    Number(Index, &'static str),
    /// A value (number, string, boolean) replaced by one of another type.
    Retype(Index, &'static str),
    /// A list made longer or shorter.
    List(Index, ListOp),
    /// The text cut at a byte (the char boundary at or before it).
    Truncate(Index),
    /// A line written twice (a TOML key or table given twice, a CSV row repeated).
    DuplicateLine(Index),
    /// A line removed.
    DeleteLine(Index),
    /// A line written many times (up to 2,000).
    RepeatLine(Index, usize),
    /// Two lines swapped.
    SwapLines(Index, Index),
    /// Text spliced in at a byte.
    Insert(Index, String),
    /// Up to 64 bytes removed at a byte.
    DeleteBytes(Index, usize),
    /// A byte overwritten (an invalid UTF-8 result read lossily).
    SetByte(Index, u8),
    /// An opening bracket, brace, quote or tag many times (up to 20,000), closed as many times or
    /// not at all, spliced in at a byte: deep nesting.
    Nest(Index, (&'static str, &'static str), usize, bool),
    /// A value wrapped in as many arrays, tables or elements (up to 20,000): deep nesting a parser
    /// reads.
    NestValue(Index, (&'static str, &'static str), usize),
}

/// Openings and their closings: TOML's, JSON's and XML's nesting.
const NESTINGS: &[(&str, &str)] = &[
    ("[", "]"),
    ("{", "}"),
    ("[[", "]]"),
    ("{ a = ", " }"),
    ("{\"a\":", "}"),
    ("<a>", "</a>"),
    ("<link>", "</link>"),
    ("\"", "\""),
    ("(", ")"),
];

/// One text mutation.
pub fn text_mutation() -> impl Strategy<Value = TextMutation> {
    let depth = || prop_oneof![2..100usize, 100..20_000usize];
    prop_oneof![
        6 => (any::<Index>(), select(NUMBERS)).prop_map(|(i, n)| TextMutation::Number(i, n)),
        3 => (any::<Index>(), select(OTHER_VALUES)).prop_map(|(i, v)| TextMutation::Retype(i, v)),
        4 => (any::<Index>(), list_op()).prop_map(|(i, op)| TextMutation::List(i, op)),
        2 => any::<Index>().prop_map(TextMutation::Truncate),
        2 => any::<Index>().prop_map(TextMutation::DuplicateLine),
        2 => any::<Index>().prop_map(TextMutation::DeleteLine),
        1 => (any::<Index>(), 2..2000usize).prop_map(|(i, n)| TextMutation::RepeatLine(i, n)),
        1 => (any::<Index>(), any::<Index>()).prop_map(|(a, b)| TextMutation::SwapLines(a, b)),
        2 => (any::<Index>(), noise()).prop_map(|(i, s)| TextMutation::Insert(i, s)),
        1 => (any::<Index>(), 1..64usize).prop_map(|(i, n)| TextMutation::DeleteBytes(i, n)),
        1 => (any::<Index>(), any::<u8>()).prop_map(|(i, b)| TextMutation::SetByte(i, b)),
        1 => (any::<Index>(), select(NESTINGS), depth(), any::<bool>())
            .prop_map(|(i, pair, n, closed)| TextMutation::Nest(i, pair, n, closed)),
        1 => (any::<Index>(), select(NESTINGS), depth()).prop_map(|(i, pair, n)| TextMutation::NestValue(i, pair, n)),
    ]
}

/// Where the tokens of a text lie: numbers, and every value (number, quoted string, boolean, nan, inf).
struct Tokens {
    numbers: Vec<(usize, usize)>,
    values: Vec<(usize, usize)>,
}

fn tokens(text: &str) -> Tokens {
    let b = text.as_bytes();
    let mut numbers = Vec::new();
    let mut values = Vec::new();
    let word = |c: u8| c.is_ascii_alphanumeric() || c == b'_' || c == b'.';
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        if c == b'"' {
            let start = i;
            i += 1;
            while i < b.len() && b[i] != b'"' && b[i] != b'\n' {
                i += if b[i] == b'\\' { 2 } else { 1 };
            }
            let end = if i < b.len() && b[i] == b'"' { i + 1 } else { i.min(b.len()) };
            values.push((start, end));
            i = end;
            continue;
        }
        let after_word = i > 0 && word(b[i - 1]);
        let digit_at = |k: usize| k < b.len() && b[k].is_ascii_digit();
        let starts_number = c.is_ascii_digit() || ((c == b'-' || c == b'+' || c == b'.') && digit_at(i + 1));
        if starts_number && !after_word {
            let start = i;
            i += 1;
            while i < b.len() && (b[i].is_ascii_digit() || b"._eE".contains(&b[i])) {
                if (b[i] == b'e' || b[i] == b'E') && i + 1 < b.len() && (b[i + 1] == b'-' || b[i + 1] == b'+')
                {
                    i += 1;
                }
                i += 1;
            }
            numbers.push((start, i));
            values.push((start, i));
            continue;
        }
        if c.is_ascii_alphabetic() && !after_word {
            let start = i;
            while i < b.len() && word(b[i]) {
                i += 1;
            }
            if matches!(&text[start..i], "true" | "false" | "nan" | "inf" | "NaN" | "null") {
                values.push((start, i));
            }
            continue;
        }
        i += 1;
    }
    Tokens { numbers, values }
}

/// The lists of a text: innermost `[...]` arrays (split on commas outside braces and quotes), the
/// comma-separated fields of lines without brackets, and quoted strings of space-separated words (XML
/// attributes such as `xyz="0 0 0.1"`). Each: where its contents lie and the separator.
fn lists(text: &str) -> Vec<(usize, usize, char)> {
    let b = text.as_bytes();
    let mut out = Vec::new();
    let mut open = None;
    let mut in_string = false;
    let mut string_start = 0;
    for (i, &c) in b.iter().enumerate() {
        match c {
            b'"' => {
                if in_string && text[string_start + 1..i].trim().contains(' ') {
                    out.push((string_start + 1, i, ' '));
                }
                in_string = !in_string;
                string_start = i;
            }
            b'\n' => in_string = false,
            b'[' if !in_string => open = Some(i),
            b']' if !in_string => {
                if let Some(o) = open.take() {
                    out.push((o + 1, i, ','));
                }
            }
            _ => {}
        }
    }
    let mut start = 0;
    for line in text.split_inclusive('\n') {
        let body = line.trim_end_matches(['\n', '\r']);
        if body.contains(',') && !body.contains('[') && !body.contains(']') {
            out.push((start, start + body.len(), ','));
        }
        start += line.len();
    }
    out
}

/// Splits a list's contents on `sep` outside braces and quotes.
fn split_list(contents: &str, sep: char) -> Vec<String> {
    if sep == ' ' {
        return contents.split_whitespace().map(str::to_owned).collect();
    }
    let mut items = Vec::new();
    let (mut depth, mut quoted, mut current) = (0i32, false, String::new());
    for c in contents.chars() {
        match c {
            '"' => quoted = !quoted,
            '{' if !quoted => depth += 1,
            '}' if !quoted => depth -= 1,
            _ => {}
        }
        if c == sep && depth == 0 && !quoted {
            items.push(std::mem::take(&mut current));
        } else {
            current.push(c);
        }
    }
    if !current.trim().is_empty() || !items.is_empty() {
        items.push(current);
    }
    items
}

/// The byte at or before `at` that starts a char.
fn floor_char(text: &str, mut at: usize) -> usize {
    at = at.min(text.len());
    while !text.is_char_boundary(at) {
        at -= 1;
    }
    at
}

/// The lines of a text with their endings.
fn lines(text: &str) -> Vec<String> {
    text.split_inclusive('\n').map(str::to_owned).collect()
}

/// A line ended by a newline (the last line of a text may lack it).
fn ended(line: &str) -> String {
    if line.ends_with('\n') { line.to_owned() } else { format!("{line}\n") }
}

impl TextMutation {
    /// Applies the mutation to `text`.
    pub fn apply(&self, text: &mut String) {
        let pick = |i: &Index, n: usize| (n > 0).then(|| i.index(n));
        match self {
            TextMutation::Number(i, with) => {
                let numbers = tokens(text).numbers;
                if let Some(k) = pick(i, numbers.len()) {
                    text.replace_range(numbers[k].0..numbers[k].1, with);
                }
            }
            TextMutation::Retype(i, with) => {
                let values = tokens(text).values;
                if let Some(k) = pick(i, values.len()) {
                    text.replace_range(values[k].0..values[k].1, with);
                }
            }
            TextMutation::List(i, op) => {
                let all = lists(text);
                if let Some(k) = pick(i, all.len()) {
                    let (start, end, sep) = all[k];
                    let mut items = split_list(&text[start..end], sep);
                    op.apply(&mut items, str::to_owned);
                    let joined = items.join(&sep.to_string());
                    text.replace_range(start..end, &joined);
                }
            }
            TextMutation::Truncate(i) => {
                let at = floor_char(text, i.index(text.len() + 1));
                text.truncate(at);
            }
            TextMutation::DuplicateLine(i) => {
                let mut ls = lines(text);
                if let Some(k) = pick(i, ls.len()) {
                    let line = ended(&ls[k]);
                    ls[k] = line.clone();
                    ls.insert(k, line);
                    *text = ls.concat();
                }
            }
            TextMutation::DeleteLine(i) => {
                let mut ls = lines(text);
                if let Some(k) = pick(i, ls.len()) {
                    ls.remove(k);
                    *text = ls.concat();
                }
            }
            TextMutation::RepeatLine(i, n) => {
                let mut ls = lines(text);
                if let Some(k) = pick(i, ls.len()) {
                    let line = ended(&ls[k]);
                    ls[k] = line.clone();
                    ls.splice(k..k, std::iter::repeat_n(line, *n));
                    *text = ls.concat();
                }
            }
            TextMutation::SwapLines(a, b) => {
                let mut ls = lines(text);
                if !ls.is_empty() {
                    let (a, b) = (a.index(ls.len()), b.index(ls.len()));
                    let last = ls.len() - 1;
                    ls[last] = ended(&ls[last]);
                    ls.swap(a, b);
                    *text = ls.concat();
                }
            }
            TextMutation::Insert(i, s) => {
                let at = floor_char(text, i.index(text.len() + 1));
                text.insert_str(at, s);
            }
            TextMutation::DeleteBytes(i, n) => {
                let start = floor_char(text, i.index(text.len() + 1));
                let end = floor_char(text, start + n);
                text.replace_range(start..end, "");
            }
            TextMutation::SetByte(i, byte) => {
                if !text.is_empty() {
                    let mut bytes = std::mem::take(text).into_bytes();
                    let at = i.index(bytes.len());
                    bytes[at] = *byte;
                    *text = String::from_utf8_lossy(&bytes).into_owned();
                }
            }
            TextMutation::Nest(i, (open, close), n, closed) => {
                let at = floor_char(text, i.index(text.len() + 1));
                let close = if *closed { close.repeat(*n) } else { String::new() };
                text.insert_str(at, &(open.repeat(*n) + &close));
            }
            TextMutation::NestValue(i, (open, close), n) => {
                let values = tokens(text).values;
                if let Some(k) = pick(i, values.len()) {
                    let (start, end) = values[k];
                    let wrapped = format!("{}{}{}", open.repeat(*n), &text[start..end], close.repeat(*n));
                    text.replace_range(start..end, &wrapped);
                }
            }
        }
    }
}

/// `seed` changed by one to four text mutations: the mutations and the text they make.
pub fn mutated_text(seeds: Vec<Arc<str>>) -> impl Strategy<Value = (Vec<TextMutation>, String)> {
    (select(seeds), vec(text_mutation(), 1..=4)).prop_map(|(seed, mutations)| {
        let mut text = seed.to_string();
        for m in &mutations {
            m.apply(&mut text);
        }
        (mutations, text)
    })
}

/// Raw text: random bytes read lossily, random chars, characters a TOML, JSON, CSV or XML parser
/// looks at, and a valid text's beginning followed by noise.
pub fn raw_text(seeds: Vec<Arc<str>>) -> impl Strategy<Value = String> {
    prop_oneof![
        2 => vec(any::<u8>(), 0..2048).prop_map(|b| String::from_utf8_lossy(&b).into_owned()),
        1 => any::<String>(),
        3 => "[\\[\\]{}<>/=,.:;\"'#\n\r\t a-z0-9_+-]{0,600}",
        2 => (select(seeds), any::<Index>(), noise()).prop_map(|(seed, i, tail)| {
            let at = floor_char(&seed, i.index(seed.len() + 1));
            format!("{}{tail}", &seed[..at])
        }),
    ]
}

/// A number a parser must refuse or bound, put in a TOML or JSON tree.
#[derive(Debug, Clone, Copy)]
pub enum Special {
    /// A float.
    Float(f64),
    /// An integer.
    Int(i64),
}

const SPECIALS: &[Special] = &[
    Special::Float(f64::NAN),
    Special::Float(f64::INFINITY),
    Special::Float(f64::NEG_INFINITY),
    Special::Float(1e308),
    Special::Float(-1e308),
    Special::Float(-0.0),
    Special::Float(0.0),
    Special::Float(5e-324),
    Special::Float(-1.0),
    Special::Float(1e18),
    Special::Int(0),
    Special::Int(-1),
    Special::Int(1_000_000_000_000_000_000),
    Special::Int(-1_000_000_000_000_000_000),
    Special::Int(i64::MAX),
    Special::Int(i64::MIN),
    Special::Int(u32::MAX as i64 + 1),
];

/// The special number `text` (one of [`NUMBERS`]) reads as, or 1e18 where it reads as none.
fn special_of(text: &str) -> Special {
    text.parse::<i64>()
        .map(Special::Int)
        .or_else(|_| text.parse::<f64>().map(Special::Float))
        .unwrap_or(Special::Float(1e18))
}

/// A value of another type put in place of a tree's node.
#[derive(Debug, Clone, Copy)]
pub enum Retype {
    /// A string.
    Str,
    /// A boolean.
    Bool,
    /// An integer.
    Int,
    /// A float.
    Float,
    /// `[]`.
    EmptyArray,
    /// `[1.0, 2.0]`.
    Array,
    /// `{}`.
    EmptyTable,
    /// `{ x = 1 }`.
    Table,
    /// JSON's `null` (TOML has none: a string there).
    Null,
}

/// A change to a TOML or JSON tree.
#[derive(Debug, Clone)]
pub enum TreeMutation {
    /// A number replaced by a special one.
    Number(Index, Special),
    /// Any node but the root replaced by a value of another type.
    Retype(Index, Retype),
    /// An array made longer or shorter.
    Array(Index, ListOp),
    /// A table's key removed.
    RemoveKey(Index, Index),
    /// A table given an unknown key.
    AddKey(Index),
}

/// One tree mutation.
pub fn tree_mutation() -> impl Strategy<Value = TreeMutation> {
    let retype = select(
        &[
            Retype::Str,
            Retype::Bool,
            Retype::Int,
            Retype::Float,
            Retype::EmptyArray,
            Retype::Array,
            Retype::EmptyTable,
            Retype::Table,
            Retype::Null,
        ][..],
    );
    prop_oneof![
        6 => (any::<Index>(), select(SPECIALS)).prop_map(|(i, s)| TreeMutation::Number(i, s)),
        3 => (any::<Index>(), retype).prop_map(|(i, r)| TreeMutation::Retype(i, r)),
        4 => (any::<Index>(), list_op()).prop_map(|(i, op)| TreeMutation::Array(i, op)),
        2 => (any::<Index>(), any::<Index>()).prop_map(|(i, k)| TreeMutation::RemoveKey(i, k)),
        1 => any::<Index>().prop_map(TreeMutation::AddKey),
    ]
}

/// What a tree's node is.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// A number.
    Number,
    /// An array.
    Array,
    /// A table (object).
    Table,
    /// Anything else.
    Other,
}

/// A TOML or JSON value as the tree mutations see it.
pub trait Tree: Clone + std::fmt::Debug {
    /// What the node is.
    fn kind(&self) -> Kind;
    /// Its children (array elements, table values).
    fn children(&mut self) -> Vec<&mut Self>;
    /// The elements, if an array.
    fn elements(&mut self) -> Option<&mut Vec<Self>>;
    /// Removes the key `at` picks, if a table with keys.
    fn remove_key(&mut self, at: &Index);
    /// Adds an unknown key, if a table.
    fn add_key(&mut self);
    /// A special number as a node.
    fn number(s: Special) -> Self;
    /// Replaces the node by a special number.
    fn set_special(&mut self, s: Special) {
        *self = Self::number(s);
    }
    /// Replaces the node by a value of another type.
    fn retype(&mut self, r: Retype);
    /// The tree as text.
    fn to_text(&self) -> Option<String>;
}

fn count<T: Tree>(node: &mut T, want: &impl Fn(Kind) -> bool) -> usize {
    let here = usize::from(want(node.kind()));
    here + node.children().into_iter().map(|c| count(c, want)).sum::<usize>()
}

fn visit<T: Tree>(
    node: &mut T,
    want: &impl Fn(Kind) -> bool,
    k: &mut usize,
    f: &mut impl FnMut(&mut T),
) -> bool {
    if want(node.kind()) {
        if *k == 0 {
            f(node);
            return true;
        }
        *k -= 1;
    }
    node.children().into_iter().any(|c| visit(c, want, k, f))
}

/// Applies `f` to the node of a kind `want` accepts that `at` picks (pre-order), if there is one.
fn at_node<T: Tree>(root: &mut T, at: &Index, want: impl Fn(Kind) -> bool, mut f: impl FnMut(&mut T)) {
    let n = count(root, &want);
    if n > 0 {
        let mut k = at.index(n);
        visit(root, &want, &mut k, &mut f);
    }
}

impl TreeMutation {
    /// Applies the mutation to `root`.
    pub fn apply<T: Tree>(&self, root: &mut T) {
        match self {
            TreeMutation::Number(at, s) => at_node(root, at, |k| k == Kind::Number, |n| n.set_special(*s)),
            TreeMutation::Retype(at, r) => {
                // Any node but the root (the first in pre-order).
                let n = count(root, &|_| true);
                if n > 1 {
                    let mut k = 1 + at.index(n - 1);
                    visit(root, &|_| true, &mut k, &mut |node: &mut T| node.retype(*r));
                }
            }
            TreeMutation::Array(at, op) => at_node(
                root,
                at,
                |k| k == Kind::Array,
                |n| {
                    if let Some(elements) = n.elements() {
                        op.apply(elements, |text| T::number(special_of(text)));
                    }
                },
            ),
            TreeMutation::RemoveKey(at, key) => {
                at_node(root, at, |k| k == Kind::Table, |n| n.remove_key(key))
            }
            TreeMutation::AddKey(at) => at_node(root, at, |k| k == Kind::Table, Tree::add_key),
        }
    }
}

/// `seed`'s tree changed by one to three tree mutations, then by up to two text mutations: the
/// mutations and the text they make.
pub fn mutated_tree<T: Tree + 'static>(
    seeds: Vec<(Arc<str>, T)>,
) -> impl Strategy<Value = (Vec<TreeMutation>, Vec<TextMutation>, String)> {
    (select(seeds), vec(tree_mutation(), 1..=3), vec(text_mutation(), 0..=2)).prop_map(
        |((text, tree), tree_mutations, text_mutations)| {
            let mut tree = tree;
            for m in &tree_mutations {
                m.apply(&mut tree);
            }
            let mut out = tree.to_text().unwrap_or_else(|| text.to_string());
            for m in &text_mutations {
                m.apply(&mut out);
            }
            (tree_mutations, text_mutations, out)
        },
    )
}

impl Tree for toml::Value {
    fn kind(&self) -> Kind {
        match self {
            toml::Value::Integer(_) | toml::Value::Float(_) => Kind::Number,
            toml::Value::Array(_) => Kind::Array,
            toml::Value::Table(_) => Kind::Table,
            _ => Kind::Other,
        }
    }

    fn children(&mut self) -> Vec<&mut Self> {
        match self {
            toml::Value::Array(a) => a.iter_mut().collect(),
            toml::Value::Table(t) => t.iter_mut().map(|(_, v)| v).collect(),
            _ => Vec::new(),
        }
    }

    fn elements(&mut self) -> Option<&mut Vec<Self>> {
        self.as_array_mut()
    }

    fn remove_key(&mut self, at: &Index) {
        if let toml::Value::Table(t) = self
            && !t.is_empty()
        {
            let key = t.keys().nth(at.index(t.len())).cloned();
            if let Some(key) = key {
                t.remove(&key);
            }
        }
    }

    fn add_key(&mut self) {
        if let toml::Value::Table(t) = self {
            t.insert("not_a_key".to_owned(), toml::Value::Integer(1));
        }
    }

    fn number(s: Special) -> Self {
        match s {
            Special::Float(x) => toml::Value::Float(x),
            Special::Int(i) => toml::Value::Integer(i),
        }
    }

    fn retype(&mut self, r: Retype) {
        *self = match r {
            Retype::Str | Retype::Null => toml::Value::String("text".to_owned()),
            Retype::Bool => toml::Value::Boolean(true),
            Retype::Int => toml::Value::Integer(1),
            Retype::Float => toml::Value::Float(1.5),
            Retype::EmptyArray => toml::Value::Array(Vec::new()),
            Retype::Array => toml::Value::Array(vec![toml::Value::Float(1.0), toml::Value::Float(2.0)]),
            Retype::EmptyTable => toml::Value::Table(toml::Table::new()),
            Retype::Table => {
                let mut t = toml::Table::new();
                t.insert("x".to_owned(), toml::Value::Integer(1));
                toml::Value::Table(t)
            }
        };
    }

    fn to_text(&self) -> Option<String> {
        toml::to_string(self).ok()
    }
}

impl Tree for serde_json::Value {
    fn kind(&self) -> Kind {
        match self {
            serde_json::Value::Number(_) => Kind::Number,
            serde_json::Value::Array(_) => Kind::Array,
            serde_json::Value::Object(_) => Kind::Table,
            _ => Kind::Other,
        }
    }

    fn children(&mut self) -> Vec<&mut Self> {
        match self {
            serde_json::Value::Array(a) => a.iter_mut().collect(),
            serde_json::Value::Object(o) => o.values_mut().collect(),
            _ => Vec::new(),
        }
    }

    fn elements(&mut self) -> Option<&mut Vec<Self>> {
        self.as_array_mut()
    }

    fn remove_key(&mut self, at: &Index) {
        if let serde_json::Value::Object(o) = self
            && !o.is_empty()
        {
            let key = o.keys().nth(at.index(o.len())).cloned();
            if let Some(key) = key {
                o.shift_remove(&key);
            }
        }
    }

    fn add_key(&mut self) {
        if let serde_json::Value::Object(o) = self {
            o.insert("not_a_key".to_owned(), serde_json::Value::from(1));
        }
    }

    fn number(s: Special) -> Self {
        // JSON has no NaN nor infinity: those become null here (the text mutations spell them).
        match s {
            Special::Float(x) => serde_json::Number::from_f64(x).map_or(serde_json::Value::Null, Into::into),
            Special::Int(i) => serde_json::Value::from(i),
        }
    }

    fn retype(&mut self, r: Retype) {
        *self = match r {
            Retype::Str => serde_json::Value::from("text"),
            Retype::Null => serde_json::Value::Null,
            Retype::Bool => serde_json::Value::from(true),
            Retype::Int => serde_json::Value::from(1),
            Retype::Float => serde_json::Value::from(1.5),
            Retype::EmptyArray => serde_json::json!([]),
            Retype::Array => serde_json::json!([1.0, 2.0]),
            Retype::EmptyTable => serde_json::json!({}),
            Retype::Table => serde_json::json!({ "x": 1 }),
        };
    }

    fn to_text(&self) -> Option<String> {
        serde_json::to_string_pretty(self).ok()
    }
}

//! The rig's URDF reader on the mutated shipped URDF (hw/urdf/knotlab_rig.urdf), on raw text, and on
//! hostile XML (entity expansion, deep nesting).

use std::sync::Arc;

use knotlab_hw::rig::Rig;

use super::mutate::{mutated_text, raw_text};
use super::{Outcome, cases, fuzz, isolated, outcome, shipped};

fn parse(text: &str) -> Outcome {
    outcome(Rig::from_urdf_str(text, "rig.urdf"))
}

/// Documents that expand entities, or are large: an XML reader must refuse them or read them in
/// bounded time and memory.
fn expanding_and_large() -> Vec<(&'static str, String)> {
    let mut laughs = String::from("<?xml version=\"1.0\"?>\n<!DOCTYPE robot [\n<!ENTITY l0 \"lol\">\n");
    for k in 1..=9 {
        let previous = format!("&l{};", k - 1);
        laughs += &format!("<!ENTITY l{k} \"{}\">\n", previous.repeat(10));
    }
    laughs += "]>\n<robot name=\"&l9;\"><link name=\"&l9;\"/></robot>\n";
    let recursive = "<?xml version=\"1.0\"?>\n<!DOCTYPE robot [<!ENTITY a \"&b;\"><!ENTITY b \"&a;\">]>\n<robot name=\"&a;\"/>\n";
    let external = "<?xml version=\"1.0\"?>\n<!DOCTYPE robot [<!ENTITY x SYSTEM \"file:///etc/passwd\">]>\n<robot name=\"&x;\"/>\n";
    vec![
        ("billion laughs", laughs),
        ("recursive entities", recursive.to_owned()),
        ("external entity", external.to_owned()),
        (
            "10,000 links of one name",
            format!("<robot name=\"r\">{}</robot>", "<link name=\"l\"/>".repeat(10_000)),
        ),
        ("a 4 MiB attribute", format!("<robot name=\"{}\"/>", "r".repeat(1 << 22))),
    ]
}

/// Documents nested 20,000 deep, closed and not: a reader that recurses per level overflows its stack.
fn deeply_nested() -> Vec<(&'static str, String)> {
    vec![
        ("20,000 unclosed elements", format!("<robot name=\"r\">{}", "<link name=\"l\">".repeat(20_000))),
        (
            "20,000 nested elements",
            format!("<robot name=\"r\">{}{}</robot>", "<link>".repeat(20_000), "</link>".repeat(20_000)),
        ),
    ]
}

/// Parses each document, printing what the reader said and how long it took; an empty error
/// message fails.
fn parse_each(documents: Vec<(&'static str, String)>) {
    for (what, text) in documents {
        eprintln!("fuzz urdf/hostile: {what} ...");
        let started = std::time::Instant::now();
        let said = parse(&text);
        let first_line = said.as_ref().map_or_else(|e| e.lines().next().unwrap_or(""), |()| "Ok");
        eprintln!("fuzz urdf/hostile: {what}: {first_line} ({:.1?})", started.elapsed());
        if let Err(e) = said {
            assert!(!e.trim().is_empty(), "{what}: the error's message is empty");
        }
    }
}

/// The URDF reader never panics on documents that expand entities (a billion laughs, recursive and
/// external entities) or are large (10,000 links of one name, a 4 MiB attribute), and names what it
/// refuses.
#[test]
fn urdf_reader_survives_entity_expansion_and_large_documents() {
    isolated(|| parse_each(expanding_and_large()));
}

/// The URDF reader does not overflow its stack on documents nested 20,000 deep, closed or not.
#[test]
fn urdf_reader_survives_deep_nesting() {
    isolated(|| parse_each(deeply_nested()));
}

/// The URDF reader never panics on the mutated shipped URDF (numbers, space-separated vectors,
/// values, lines, bytes, deep nesting) or on raw text, and names what it refuses.
#[test]
fn urdf_reader_survives_mutated_and_random_input() {
    isolated(|| {
        let seed: Arc<str> = Arc::from(shipped("hw/urdf/knotlab_rig.urdf"));
        assert_eq!(parse(&seed), Ok(()), "the shipped URDF reads");
        fuzz("urdf/text", cases(), mutated_text(vec![seed.clone()]), |(_, text)| parse(text));
        fuzz("urdf/raw", cases(), raw_text(vec![seed]), |text| parse(text));
    });
}

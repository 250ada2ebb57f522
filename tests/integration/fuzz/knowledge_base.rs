//! The knowledge base parser on a knowledge base learned here (what `knotlab learn` writes for the
//! shipped demonstration and pattern), mutated in its text and in its JSON tree, and on raw text.

use std::path::Path;
use std::sync::Arc;

use knotlab_learner::demonstration::load_demonstration;
use knotlab_learner::pattern::load_pattern;
use knotlab_learner::primitive::{learn, parse_knowledge_base};

use super::mutate::{mutated_text, mutated_tree, raw_text};
use super::{cases, fuzz, isolated, outcome};

/// Most path keys an instrument keeps in the fuzzed knowledge base: the learned one holds thousands
/// (700 kB of JSON); a mutation of one key among 40 finds what one among thousands would, 20 times
/// faster a case.
const PATH_KEYS: usize = 40;

/// `knotlab learn`'s knowledge base for the shipped demonstration and pattern, as it writes it.
fn learned_knowledge_base() -> serde_json::Value {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let demo =
        load_demonstration(&root.join("scenarios/demos/instrument-tie")).expect("the shipped demonstration");
    let pattern =
        load_pattern(&root.join("scenarios/patterns/knot_tying.toml")).expect("the shipped pattern");
    let kb = learn(&demo, &pattern).expect("learning the shipped demonstration");
    serde_json::to_value(&kb).expect("JSON")
}

/// The knowledge base with each instrument's path thinned to [`PATH_KEYS`] evenly spaced keys (the
/// first and the last kept), if it still reads; else as learned.
fn seed() -> String {
    let learned = learned_knowledge_base();
    let mut thinned = learned.clone();
    for instrument in thinned["instruments"].as_array_mut().into_iter().flatten() {
        if let Some(path) = instrument.get_mut("path").and_then(serde_json::Value::as_array_mut)
            && path.len() > PATH_KEYS
        {
            let n = path.len();
            let keep: Vec<usize> = (0..PATH_KEYS).map(|k| k * (n - 1) / (PATH_KEYS - 1)).collect();
            *path = keep.into_iter().map(|k| path[k].clone()).collect();
        }
    }
    let text = |v: &serde_json::Value| serde_json::to_string_pretty(v).expect("JSON") + "\n";
    let (thinned, learned) = (text(&thinned), text(&learned));
    match parse_knowledge_base(&thinned, "kb.json") {
        Ok(_) => thinned,
        Err(e) => {
            eprintln!(
                "fuzz knowledge-base: the thinned knowledge base does not read ({e}): fuzzing the learned one"
            );
            learned
        }
    }
}

/// The knowledge base parser never panics on a mutated learned knowledge base (numbers, arrays of
/// another length, values of another type, keys removed or added, truncated, NaN and infinities
/// spelled in the text) or on raw text, and names what it refuses.
#[test]
fn knowledge_base_parser_survives_mutated_and_random_input() {
    isolated(|| {
        let text = seed();
        assert_eq!(
            outcome(parse_knowledge_base(&text, "kb.json")),
            Ok(()),
            "the learned knowledge base reads back"
        );
        let seed: Arc<str> = Arc::from(text.as_str());
        let tree: serde_json::Value = serde_json::from_str(&text).expect("JSON");
        let parse = |text: &str| outcome(parse_knowledge_base(text, "kb.json"));
        fuzz("knowledge-base/text", cases(), mutated_text(vec![seed.clone()]), |(_, text)| parse(text));
        fuzz("knowledge-base/tree", cases(), mutated_tree(vec![(seed.clone(), tree)]), |(_, _, text)| {
            parse(text)
        });
        fuzz("knowledge-base/raw", cases(), raw_text(vec![seed]), |text| parse(text));
    });
}

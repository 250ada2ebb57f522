//! The demonstration's parsers on the shipped demonstration (scenarios/demos/instrument-tie), its
//! CSV files cut to their first rows so that a case stays short: the metadata (`demo.toml`), one
//! instrument's samples, and the folder loader on a temp dir of mutated files.

use std::sync::Arc;

use proptest::collection::vec;
use proptest::prelude::*;

use knotlab_learner::demonstration::csv::parse_samples;
use knotlab_learner::demonstration::load_demonstration;
use knotlab_learner::demonstration::metadata::parse_metadata;

use super::mutate::{TextMutation, TreeMutation, mutated_text, raw_text, text_mutation, tree_mutation};
use super::toml_files::fuzz_toml;
use super::{TempDir, cases, fuzz, isolated, outcome, shipped};

/// The shipped demonstration.
const DEMO: &str = "scenarios/demos/instrument-tie";

/// Its instruments' CSV files.
const CSV_FILES: [&str; 3] = ["left.csv", "right.csv", "assist.csv"];

/// The rows of each CSV file the fuzzers start from (1.2 s at the shipped 100 Hz).
const ROWS: usize = 120;

/// The shipped sample rate, Hz.
const RATE_HZ: f64 = 100.0;

/// A shipped CSV file's header and first [`ROWS`] rows.
fn csv_seed(file: &str) -> String {
    shipped(&format!("{DEMO}/{file}")).split_inclusive('\n').take(ROWS + 1).collect()
}

/// The shipped `demo.toml`, its sample counts cut to [`ROWS`].
fn metadata_seed() -> String {
    let text = shipped(&format!("{DEMO}/demo.toml"));
    let mut out = String::new();
    for line in text.split_inclusive('\n') {
        if line.trim_start().starts_with("samples =") {
            out.push_str(&format!("samples = {ROWS}\n"));
        } else {
            out.push_str(line);
        }
    }
    assert!(out.contains(&format!("samples = {ROWS}")), "demo.toml names its sample counts");
    out
}

/// The metadata parser never panics on a mutated shipped `demo.toml` or on raw text, and names what it
/// refuses.
#[test]
fn demonstration_metadata_parser_survives_mutated_and_random_input() {
    isolated(|| {
        fuzz_toml("demo-metadata", &[&format!("{DEMO}/demo.toml")], |text| {
            outcome(parse_metadata(text, "demo.toml"))
        });
    });
}

/// The samples parser never panics on a mutated shipped instrument file (numbers, fields, rows,
/// header) or on raw text, whatever sample count and rate the metadata gave it, and names what it
/// refuses.
#[test]
fn demonstration_samples_parser_survives_mutated_and_random_input() {
    isolated(|| {
        let seeds: Vec<Arc<str>> = CSV_FILES.iter().map(|f| Arc::from(csv_seed(f))).collect();
        for (file, text) in CSV_FILES.iter().zip(&seeds) {
            assert_eq!(
                outcome(parse_samples(text, file, ROWS, RATE_HZ)),
                Ok(()),
                "{file}'s first rows parse"
            );
        }
        // The count and the rate a (valid) demo.toml may give: the count any from 2 up, the rate any from
        // 100 Hz up.
        let expected = prop_oneof![
            8 => Just(ROWS),
            1 => Just(2usize),
            1 => Just(ROWS - 1),
            1 => Just(ROWS + 1),
            1 => Just(1_000_000_000_000_000_000usize),
            1 => Just(i64::MAX as usize),
        ];
        let rate = prop_oneof![8 => Just(RATE_HZ), 1 => Just(1000.0), 1 => Just(1e308)];
        fuzz(
            "demo-samples/text",
            cases(),
            (mutated_text(seeds.clone()), expected, rate),
            |((_, text), n, hz)| outcome(parse_samples(text, "left.csv", *n, *hz)),
        );
        fuzz("demo-samples/raw", cases(), raw_text(seeds), |text| {
            outcome(parse_samples(text, "left.csv", ROWS, RATE_HZ))
        });
    });
}

/// Which file of the demonstration a folder case mutates, and how.
#[derive(Debug, Clone)]
enum FolderCase {
    /// `demo.toml`'s text.
    MetadataText(Vec<TextMutation>),
    /// `demo.toml`'s tree (then its text).
    MetadataTree(Vec<TreeMutation>, Vec<TextMutation>),
    /// One instrument's CSV file.
    Samples(usize, Vec<TextMutation>),
    /// One file missing.
    Missing(usize),
}

/// The folder loader never panics on a demonstration directory with one mutated or missing file (it
/// reads what `demo.toml` names, whatever the name), and names what it refuses.
#[test]
fn demonstration_folder_loader_survives_mutated_files() {
    isolated(|| {
        let dir = TempDir::new("demonstration");
        let metadata = metadata_seed();
        let csvs: Vec<String> = CSV_FILES.iter().map(|f| csv_seed(f)).collect();
        let write_all = || {
            std::fs::write(dir.0.join("demo.toml"), &metadata).expect("write demo.toml");
            for (file, text) in CSV_FILES.iter().zip(&csvs) {
                std::fs::write(dir.0.join(file), text).expect("write csv");
            }
        };
        write_all();
        assert_eq!(outcome(load_demonstration(&dir.0)), Ok(()), "the cut demonstration loads");

        let tree = toml::Value::Table(metadata.parse::<toml::Table>().expect("TOML"));
        let case = prop_oneof![
            3 => vec(text_mutation(), 1..=3).prop_map(FolderCase::MetadataText),
            2 => (vec(tree_mutation(), 1..=2), vec(text_mutation(), 0..=1))
                .prop_map(|(t, x)| FolderCase::MetadataTree(t, x)),
            4 => (0..CSV_FILES.len(), vec(text_mutation(), 1..=3)).prop_map(|(k, m)| FolderCase::Samples(k, m)),
            1 => (0..=CSV_FILES.len()).prop_map(FolderCase::Missing),
        ];
        fuzz("demo-folder", cases() / 10, case, |case| {
            write_all();
            match case {
                FolderCase::MetadataText(mutations) => {
                    let mut text = metadata.clone();
                    mutations.iter().for_each(|m| m.apply(&mut text));
                    std::fs::write(dir.0.join("demo.toml"), text).expect("write demo.toml");
                }
                FolderCase::MetadataTree(tree_mutations, text_mutations) => {
                    let mut t = tree.clone();
                    tree_mutations.iter().for_each(|m| m.apply(&mut t));
                    let mut text = toml::to_string(&t).unwrap_or_else(|_| metadata.clone());
                    text_mutations.iter().for_each(|m| m.apply(&mut text));
                    std::fs::write(dir.0.join("demo.toml"), text).expect("write demo.toml");
                }
                FolderCase::Samples(k, mutations) => {
                    let mut text = csvs[*k].clone();
                    mutations.iter().for_each(|m| m.apply(&mut text));
                    std::fs::write(dir.0.join(CSV_FILES[*k]), text).expect("write csv");
                }
                FolderCase::Missing(k) => {
                    let file = if *k == CSV_FILES.len() { "demo.toml" } else { CSV_FILES[*k] };
                    std::fs::remove_file(dir.0.join(file)).expect("remove a file");
                }
            }
            outcome(load_demonstration(&dir.0))
        });
    });
}

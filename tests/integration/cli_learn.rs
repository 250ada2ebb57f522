//! `knotlab learn` end to end: a synthetic demonstration written to disk, decomposed by the shipped
//! pattern into the knowledge base; demonstrations that are not the task rejected with exit code 3 and
//! the reason; bad files named.

use super::common;

use std::path::PathBuf;

use serde_json::Value;

use common::{json, knotlab};
use knotlab_learner::demonstration::write_demonstration;
use knotlab_learner::primitive::load_knowledge_base;
use knotlab_learner::synthetic::{SyntheticSettings, canonical_demonstration};

struct TempDir(PathBuf);

impl TempDir {
    fn new(name: &str) -> Self {
        let dir = std::env::temp_dir().join(format!("knotlab-cli-learn-{name}-{}", std::process::id()));
        std::fs::remove_dir_all(&dir).ok();
        std::fs::create_dir_all(&dir).expect("temp dir");
        Self(dir)
    }

    fn path(&self, name: &str) -> String {
        self.0.join(name).to_str().expect("utf-8 path").to_owned()
    }

    /// Writes a synthetic demonstration into `name` and returns its path.
    fn demo(&self, name: &str, settings: &SyntheticSettings) -> String {
        let (demo, _) = canonical_demonstration(settings);
        let path = self.path(name);
        write_demonstration(std::path::Path::new(&path), &demo).expect("write the demonstration");
        path
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        std::fs::remove_dir_all(&self.0).ok();
    }
}

const PATTERN: &str = "scenarios/patterns/knot_tying.toml";

fn field<'a>(v: &'a Value, key: &str) -> &'a Value {
    v.get(key).unwrap_or_else(|| panic!("no '{key}' in {v}"))
}

/// `knotlab learn` accepts a synthetic demonstration, lists every detected feature in time order, decomposes
/// it into the pattern's 11 primitives per instrument, and writes the knowledge base it prints.
#[test]
fn learn_prints_the_decomposition_and_writes_the_knowledge_base() {
    let dir = TempDir::new("ok");
    let demo = dir.demo("demo", &SyntheticSettings::canonical(5, 100.0));
    let kb = dir.path("skill.json");
    let (code, report) = json(&["learn", "--demo", &demo, "--pattern", PATTERN, "--out", &kb, "--json"]);
    assert_eq!(code, 0, "{report}");
    assert_eq!(field(&report, "accepted"), true);
    // Every detected feature is listed, each instrument's in time order, as many as the counts say.
    let detected = field(&report, "detected").as_array().unwrap();
    let counted: u64 =
        field(&report, "features").as_array().unwrap().iter().map(|c| c[1].as_u64().unwrap()).sum();
    assert_eq!(detected.len() as u64, counted);
    for w in detected.windows(2) {
        if w[0]["instrument"] == w[1]["instrument"] {
            assert!(w[0]["time_s"].as_f64().unwrap() <= w[1]["time_s"].as_f64().unwrap(), "{w:?}");
        }
    }
    let loops = detected.iter().filter(|f| f["instrument"] == "right" && f["kind"] == "loop").count();
    assert_eq!(loops, 2, "the right's two wraps");
    let instruments = field(&report, "instruments").as_array().unwrap();
    let names: Vec<(String, Vec<(String, String)>)> = instruments
        .iter()
        .map(|i| {
            let prims = field(i, "primitives")
                .as_array()
                .unwrap()
                .iter()
                .map(|p| {
                    (
                        field(p, "name").as_str().unwrap().to_owned(),
                        field(p, "type").as_str().unwrap().to_owned(),
                    )
                })
                .collect();
            (field(i, "instrument").as_str().unwrap().to_owned(), prims)
        })
        .collect();
    let pair = |a: &str, b: &str| (a.to_owned(), b.to_owned());
    assert_eq!(
        names,
        vec![
            (
                "left".to_owned(),
                vec![
                    pair("L1", "linear"),
                    pair("L2", "synchronized"),
                    pair("L3", "linear"),
                    pair("L4", "linear"),
                    pair("L5", "linear"),
                    pair("L6", "linear")
                ]
            ),
            (
                "right".to_owned(),
                vec![pair("R2", "2d"), pair("R3", "linear"), pair("R4", "linear"), pair("R5", "force")]
            ),
            ("assist".to_owned(), vec![pair("A1", "linear")]),
        ]
    );
    for i in instruments {
        for p in field(i, "primitives").as_array().unwrap() {
            let (a, b) = (field(p, "start_s").as_f64().unwrap(), field(p, "end_s").as_f64().unwrap());
            assert!(b > a && a > 0.0, "span of {p}");
        }
    }
    // The knowledge base on disk holds the same primitives.
    let kb = load_knowledge_base(std::path::Path::new(&kb)).unwrap();
    assert_eq!(kb.instruments.iter().map(|i| i.primitives.len()).sum::<usize>(), 11);
    assert_eq!(kb.frame, "stitch");

    // The text form says the same.
    let (code, text, _) = knotlab(&["learn", "--demo", &demo, "--out", &dir.path("again.json")]);
    assert_eq!(code, 0, "{text}");
    for needle in ["left", "  L1   linear", "  R2   2d", "(with R2)", "knowledge base:"] {
        assert!(text.contains(needle), "'{needle}' missing from:\n{text}");
    }
}

/// A demonstration with one wrap, no tail grasp or cut short is rejected with exit code 3, the missing
/// element and the reason, and no knowledge base is written.
#[test]
fn demonstrations_that_are_not_the_task_are_rejected_with_the_reason() {
    let dir = TempDir::new("rejected");
    let cases = [
        ("single", SyntheticSettings { wraps: 1, ..SyntheticSettings::canonical(6, 100.0) }, "R2_loop2"),
        (
            "nograsp",
            SyntheticSettings { grasp_tail: false, ..SyntheticSettings::canonical(6, 100.0) },
            "grasp_tail",
        ),
        ("cut", SyntheticSettings { cut_at_s: Some(4.0), ..SyntheticSettings::canonical(6, 100.0) }, ""),
    ];
    for (name, settings, element) in cases {
        let demo = dir.demo(name, &settings);
        let kb = dir.path(&format!("{name}.json"));
        let (code, report) = json(&["learn", "--demo", &demo, "--pattern", PATTERN, "--out", &kb, "--json"]);
        assert_eq!(code, 3, "{name}: {report}");
        assert_eq!(field(&report, "accepted"), false);
        let failures = field(&report, "failures").as_array().unwrap();
        let first = &failures[0];
        if !element.is_empty() {
            assert_eq!(field(first, "element"), element, "{name}: {report}");
        }
        assert_eq!(field(first, "cause"), "not_found", "{name}: {report}");
        assert!(
            field(first, "stopped_at_s").as_f64().unwrap()
                <= field(first, "recording_end_s").as_f64().unwrap()
        );
        assert!(field(&report, "reason").as_str().unwrap().contains("not a demonstration of"), "{report}");
        assert!(!std::path::Path::new(&kb).exists(), "{name}: nothing written for a rejected demonstration");
        // Text: the reason goes to stdout and stderr, the exit code is 3.
        let (code, stdout, stderr) = knotlab(&["learn", "--demo", &demo, "--out", &kb]);
        assert_eq!(code, 3);
        assert!(stdout.contains("rejected:") && stderr.contains("rejected:"), "{stdout}\n{stderr}");
    }
}

/// A NaN in a demonstration, an unknown feature kind in a pattern, a missing demonstration and a missing
/// `--out` are refused, naming the file, line and field, or the flag.
#[test]
fn bad_files_and_flags_are_named() {
    let dir = TempDir::new("bad");
    let demo = dir.demo("demo", &SyntheticSettings::canonical(8, 100.0));
    let kb = dir.path("kb.json");

    // A demonstration with NaN: the file, the line and the column.
    let csv = dir.0.join("demo").join("right.csv");
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
    let mut fields: Vec<String> = lines[9].split(',').map(str::to_owned).collect();
    fields[2] = "nan".to_owned();
    lines[9] = fields.join(",");
    std::fs::write(&csv, lines.join("\n") + "\n").unwrap();
    let (code, _, stderr) = knotlab(&["learn", "--demo", &demo, "--out", &kb]);
    assert_eq!(code, 1);
    assert!(stderr.contains("right.csv:10: y_m: NaN"), "{stderr}");
    let (code, report) = json(&["learn", "--demo", &demo, "--out", &kb, "--json"]);
    assert_eq!(code, 1);
    assert!(field(&report, "error").as_str().unwrap().contains("right.csv:10: y_m"), "{report}");

    // A malformed pattern: the line and the field.
    let demo = dir.demo("demo2", &SyntheticSettings::canonical(8, 100.0));
    let pattern = dir.path("pattern.toml");
    let shipped = std::fs::read_to_string(PATTERN).unwrap();
    std::fs::write(&pattern, shipped.replacen("kind = \"loop\"", "kind = \"loops\"", 1)).unwrap();
    let line = shipped.lines().position(|l| l.contains("kind = \"loop\"")).unwrap() + 1;
    let (code, _, stderr) = knotlab(&["learn", "--demo", &demo, "--pattern", &pattern, "--out", &kb]);
    assert_eq!(code, 1);
    assert!(
        stderr.contains(&format!("pattern.toml:{line}: right.feature[1].kind: unknown feature kind 'loops'")),
        "{stderr}"
    );

    // A demonstration directory that does not exist.
    let (code, _, stderr) = knotlab(&["learn", "--demo", &dir.path("nowhere"), "--out", &kb]);
    assert_eq!(code, 1);
    assert!(stderr.contains("demo.toml: cannot read"), "{stderr}");

    // A missing flag.
    let (code, _, stderr) = knotlab(&["learn", "--demo", &demo]);
    assert_eq!(code, 2, "clap's usage error");
    assert!(stderr.contains("--out"), "{stderr}");
}

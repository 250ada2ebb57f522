//! `knotlab mc` end to end on short trials (`--until`): the same seed gives byte-identical summaries with
//! one and two jobs; a run killed mid-way (its last line cut short) and resumed has every trial once;
//! a damaged results file is named.

mod common;

use std::path::{Path, PathBuf};

use common::knotlab;

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("knotlab-cli-mc-{name}-{}", std::process::id()));
    std::fs::remove_dir_all(&d).ok();
    d
}

fn mc(out: &Path, trials: u64, jobs: u64) -> (i32, String) {
    let (code, stdout, stderr) = knotlab(&[
        "mc",
        "--trials",
        &trials.to_string(),
        "--seed",
        "7",
        "--jobs",
        &jobs.to_string(),
        "--until",
        "0.3",
        "--method",
        "dmp",
        "--method",
        "replay",
        "--out",
        out.to_str().expect("a UTF-8 path"),
    ]);
    (code, format!("{stdout}{stderr}"))
}

fn lines(out: &Path) -> Vec<serde_json::Value> {
    std::fs::read_to_string(out.join("results.jsonl"))
        .expect("results.jsonl")
        .lines()
        .map(|l| serde_json::from_str(l).expect("a JSON line"))
        .collect()
}

#[test]
fn the_same_seed_gives_the_same_summary_with_one_or_two_jobs() {
    let (a, b) = (dir("jobs1"), dir("jobs2"));
    assert_eq!(mc(&a, 3, 1).0, 0);
    assert_eq!(mc(&b, 3, 2).0, 0);
    let (sa, sb) =
        (std::fs::read(a.join("summary.json")).unwrap(), std::fs::read(b.join("summary.json")).unwrap());
    assert_eq!(sa, sb, "summary.json differs between --jobs 1 and --jobs 2");
    let summary: serde_json::Value = serde_json::from_slice(&sa).unwrap();
    assert_eq!(summary["methods"][0]["trials"], 3);
    // The draws vary from trial to trial (the scene's [randomization]).
    let draws: Vec<String> = lines(&a).iter().map(|l| l["draw"]["stitch_offset_m"].to_string()).collect();
    assert!(draws.iter().any(|d| d != &draws[0]), "{draws:?}");
    std::fs::remove_dir_all(&a).ok();
    std::fs::remove_dir_all(&b).ok();
}

#[test]
fn a_killed_run_resumes_with_every_trial_once() {
    let out = dir("resume");
    assert_eq!(mc(&out, 2, 2).0, 0);
    // As if killed while writing: the last line cut in the middle.
    let path = out.join("results.jsonl");
    let text = std::fs::read_to_string(&path).unwrap();
    std::fs::write(&path, &text[..text.len() - 40]).unwrap();
    let (code, log) = mc(&out, 4, 2);
    assert_eq!(code, 0, "{log}");
    let mut seen: Vec<(u64, String)> = lines(&out)
        .iter()
        .map(|l| (l["trial"].as_u64().unwrap(), l["method"].as_str().unwrap().to_owned()))
        .collect();
    seen.sort();
    let expected: Vec<(u64, String)> =
        (0..4).flat_map(|t| ["dmp", "replay"].map(|m| (t, m.to_owned()))).collect();
    assert_eq!(seen, expected, "every trial of every method exactly once");
    // A damaged line that is not the last is an error naming the file and the line.
    let text = std::fs::read_to_string(&path).unwrap();
    std::fs::write(&path, text.replacen("{\"trial\"", "{\"trial?\"", 1)).unwrap();
    let (code, log) = mc(&out, 4, 1);
    assert_eq!(code, 1);
    assert!(log.contains("results.jsonl: line 1"), "{log}");
    std::fs::remove_dir_all(&out).ok();
}

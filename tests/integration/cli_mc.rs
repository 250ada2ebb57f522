//! `knotlab mc` end to end on short trials (`--until`): the same seed gives byte-identical summaries with
//! one and two jobs and with two shards merged; a run killed mid-way (SIGKILL, or its last line cut
//! short) and resumed has every trial once; Ctrl-C (SIGINT) stops it cleanly and it resumes; a damaged
//! results file, another run's directory, an unknown preset and an incomplete merge are named.

use super::common;

use std::path::{Path, PathBuf};

use common::knotlab;

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("knotlab-cli-mc-{name}-{}", std::process::id()));
    std::fs::remove_dir_all(&d).ok();
    d
}

fn mc_args(out: &Path, trials: u64, jobs: u64) -> Vec<String> {
    let out = out.to_str().expect("a UTF-8 path");
    let trials = trials.to_string();
    let jobs = jobs.to_string();
    ["mc", "--trials", &trials, "--seed", "7", "--jobs", &jobs, "--until", "0.3", "--method", "dmp"]
        .iter()
        .chain(&["--method", "replay", "--out", out])
        .map(|s| s.to_string())
        .collect()
}

fn mc_with(out: &Path, trials: u64, jobs: u64, more: &[&str]) -> (i32, String) {
    let mut args = mc_args(out, trials, jobs);
    args.extend(more.iter().map(|s| s.to_string()));
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let (code, stdout, stderr) = knotlab(&args);
    (code, format!("{stdout}{stderr}"))
}

fn mc(out: &Path, trials: u64, jobs: u64) -> (i32, String) {
    mc_with(out, trials, jobs, &[])
}

/// The (trial, method) pairs in the results, sorted.
fn pairs(out: &Path) -> Vec<(u64, String)> {
    let mut seen: Vec<(u64, String)> = lines(out)
        .iter()
        .map(|l| {
            (l["trial"].as_u64().expect("a trial index"), l["method"].as_str().expect("a method").to_owned())
        })
        .collect();
    seen.sort();
    seen
}

fn expected_pairs(trials: u64) -> Vec<(u64, String)> {
    (0..trials).flat_map(|t| ["dmp", "replay"].map(|m| (t, m.to_owned()))).collect()
}

/// Starts `knotlab mc` in the background and waits until its results hold at least one line.
fn spawn_until_a_line(out: &Path, trials: u64) -> std::process::Child {
    let child = std::process::Command::new(env!("CARGO_BIN_EXE_knotlab"))
        .args(mc_args(out, trials, 1))
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .expect("start knotlab mc");
    let started = std::time::Instant::now();
    while std::fs::read_to_string(out.join("results.jsonl")).map_or(0, |t| t.lines().count()) == 0 {
        assert!(started.elapsed().as_secs() < 300, "no trial finished in 300 s");
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
    child
}

fn lines(out: &Path) -> Vec<serde_json::Value> {
    std::fs::read_to_string(out.join("results.jsonl"))
        .expect("results.jsonl")
        .lines()
        .map(|l| serde_json::from_str(l).expect("a JSON line"))
        .collect()
}

/// A Monte Carlo run of one seed writes a byte-identical summary.json with one job and with two, its draws
/// varying by trial, each line counting the thread's self-crossings and naming the first and saying how far
/// the thread stretched, the summary (and the console's) tallying the stretch.
#[test]
fn the_same_seed_gives_the_same_summary_with_one_or_two_jobs() {
    let (a, b) = (dir("jobs1"), dir("jobs2"));
    let (code, text) = mc(&a, 3, 1);
    assert_eq!(code, 0, "{text}");
    // The console's summary says how far the thread stretched, as summary.json does.
    assert!(text.contains("stretched beyond 5 % in") && text.contains("of 3 (for a median"), "{text}");
    assert_eq!(mc(&b, 3, 2).0, 0);
    let (sa, sb) =
        (std::fs::read(a.join("summary.json")).unwrap(), std::fs::read(b.join("summary.json")).unwrap());
    assert_eq!(sa, sb, "summary.json differs between --jobs 1 and --jobs 2");
    let summary: serde_json::Value = serde_json::from_slice(&sa).unwrap();
    assert_eq!(summary["methods"][0]["trials"], 3);
    // The draws vary from trial to trial (the scene's [randomization]).
    let draws: Vec<String> = lines(&a).iter().map(|l| l["draw"]["stitch_offset_m"].to_string()).collect();
    assert!(draws.iter().any(|d| d != &draws[0]), "{draws:?}");
    // Each line counts the thread's passes through itself.
    for l in lines(&a) {
        assert!(l["thread_self_crossings"].as_u64().is_some(), "{l}");
        // ... and names the first, when there is one.
        let first = &l["first_self_crossing"];
        assert_eq!(first.is_null(), l["thread_self_crossings"] == 0, "{l}");
        // ... and how far the thread stretched, and how long beyond 5 %.
        assert!(l["thread_max_stretch"].as_f64().is_some_and(|r| r >= 0.0), "{l}");
        assert!(l["thread_stretched_s"].as_f64().is_some_and(|s| s >= 0.0), "{l}");
    }
    let stretch = &summary["methods"][0]["thread_stretch"];
    assert_eq!(stretch["measured_trials"], 3, "{summary}");
    std::fs::remove_dir_all(&a).ok();
    std::fs::remove_dir_all(&b).ok();
}

/// A run whose last results line is cut short resumes with every trial counted exactly once; a damaged line
/// that is not the last is an error naming the file and the line.
#[test]
fn a_killed_run_resumes_with_every_trial_once() {
    let out = dir("resume");
    assert_eq!(mc(&out, 2, 2).0, 0);
    // As if killed while writing: the last line cut in the middle.
    let path = out.join("results.jsonl");
    let text = std::fs::read_to_string(&path).unwrap();
    std::fs::write(&path, &text[..text.len() - 40]).unwrap();
    // Resumed with more trials: a trial is the same whatever their number.
    let (code, log) = mc(&out, 4, 2);
    assert_eq!(code, 0, "{log}");
    assert_eq!(pairs(&out), expected_pairs(4), "every trial of every method exactly once");
    // A damaged line that is not the last is an error naming the file and the line.
    let text = std::fs::read_to_string(&path).unwrap();
    std::fs::write(&path, text.replacen("{\"trial\"", "{\"trial?\"", 1)).unwrap();
    let (code, log) = mc(&out, 4, 1);
    assert_eq!(code, 1);
    assert!(log.contains("results.jsonl: line 1"), "{log}");
    std::fs::remove_dir_all(&out).ok();
}

/// A Monte Carlo run killed with SIGKILL resumes with every trial of every method counted exactly once.
#[test]
fn a_run_killed_with_sigkill_resumes_with_every_trial_once() {
    let out = dir("sigkill");
    let mut child = spawn_until_a_line(&out, 6);
    child.kill().expect("SIGKILL");
    child.wait().expect("reaped");
    let before = pairs(&out).len();
    let (code, log) = mc(&out, 6, 2);
    assert_eq!(code, 0, "{log}");
    assert_eq!(pairs(&out), expected_pairs(6), "killed after {before} lines: every pair exactly once");
    std::fs::remove_dir_all(&out).ok();
}

/// Ctrl-C (SIGINT) stops a Monte Carlo run with exit code 130, whole lines only and a summary covering them,
/// and the run resumes with every trial counted once.
#[test]
fn ctrl_c_stops_cleanly_and_the_run_resumes() {
    let out = dir("sigint");
    let mut child = spawn_until_a_line(&out, 400);
    let pid = child.id().to_string();
    let sent = std::process::Command::new("kill").args(["-INT", &pid]).status().expect("run kill");
    assert!(sent.success());
    let status = child.wait().expect("reaped");
    assert_eq!(status.code(), Some(130), "a run stopped by Ctrl-C exits 130");
    // Every line written is whole, none twice, and the summary covers them.
    let done = pairs(&out);
    let mut unique = done.clone();
    unique.dedup();
    assert_eq!(done, unique);
    assert!(done.len() < 800, "stopped before the end");
    let summary: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("summary.json")).expect("summary.json")).unwrap();
    let counted: u64 =
        summary["methods"].as_array().unwrap().iter().map(|m| m["trials"].as_u64().unwrap()).sum();
    assert_eq!(counted as usize, done.len());
    // Resumed up to a few trials past where it stopped.
    let trials = done.iter().map(|(t, _)| t + 1).max().unwrap_or(0) + 1;
    let (code, log) = mc(&out, trials, 2);
    assert_eq!(code, 0, "{log}");
    assert_eq!(pairs(&out), expected_pairs(trials));
    std::fs::remove_dir_all(&out).ok();
}

/// Two shards merged give the single run's summary.json and lines; a merge with a shard missing, or with
/// another seed's shard, a shard given twice or an output that is a shard, is refused, naming what is
/// missing, differs or repeats.
#[test]
fn two_shards_merged_give_the_single_run() {
    let (whole, s0, s1, merged) = (dir("whole"), dir("shard0"), dir("shard1"), dir("merged"));
    assert_eq!(mc(&whole, 5, 2).0, 0);
    assert_eq!(mc_with(&s0, 5, 1, &["--shard", "0/2"]).0, 0);
    // Shard 0 of 2 holds trials 0, 2, 4 alone.
    assert_eq!(pairs(&s0).iter().map(|(t, _)| *t).collect::<Vec<_>>(), vec![0, 0, 2, 2, 4, 4]);
    let (s0s, s1s, ms) = (s0.display().to_string(), s1.display().to_string(), merged.display().to_string());
    // Merging before every shard is there names what is missing.
    let (code, stdout, stderr) = knotlab(&["mc", "merge", &s0s, "--out", &ms]);
    assert_eq!(code, 1, "{stdout}");
    assert!(stderr.contains("4 (trial, method) pairs") && stderr.contains("1 dmp"), "{stderr}");
    assert_eq!(mc_with(&s1, 5, 2, &["--shard", "1/2"]).0, 0);
    let (code, stdout, stderr) = knotlab(&["mc", "merge", &s0s, &s1s, "--out", &ms]);
    assert_eq!(code, 0, "{stdout}{stderr}");
    let read = |d: &Path| std::fs::read(d.join("summary.json")).expect("summary.json");
    assert_eq!(read(&whole), read(&merged), "summary.json of the merged shards differs from the single run");
    let without_wall = |d: &Path| -> Vec<serde_json::Value> {
        lines(d)
            .into_iter()
            .map(|mut l| {
                l["wall_seconds"] = 0.0.into();
                l
            })
            .collect()
    };
    let mut single = without_wall(&whole);
    single.sort_by_key(|l| (l["trial"].as_u64(), l["method"].as_str().map(str::to_owned)));
    assert_eq!(single, without_wall(&merged), "the merged lines are the single run's, sorted");
    // A shard of another run (another seed) is refused, naming the difference.
    let other = dir("other");
    let (code, _) = knotlab_mc_seed(&other, 5, "8", &["--shard", "1/2"]);
    assert_eq!(code, 0);
    let (code, _, stderr) = knotlab(&["mc", "merge", &s0s, &other.display().to_string(), "--out", &ms]);
    assert_eq!(code, 1);
    assert!(stderr.contains("seed: 7 here, 8 asked"), "{stderr}");
    // A shard given twice, or an output that is one of the shards, is refused and nothing is written.
    let before = std::fs::read(s0.join("results.jsonl")).expect("shard 0's results");
    let (code, _, stderr) = knotlab(&["mc", "merge", &s0s, &s1s, &s0s, "--out", &ms]);
    assert_eq!(code, 1);
    assert!(stderr.contains(&s0s) && stderr.contains("given twice"), "{stderr}");
    let (code, _, stderr) = knotlab(&["mc", "merge", &s0s, &s1s, "--out", &s0s]);
    assert_eq!(code, 1);
    assert!(stderr.contains("is one of the shards being merged"), "{stderr}");
    assert_eq!(std::fs::read(s0.join("results.jsonl")).expect("shard 0's results"), before);
    for d in [whole, s0, s1, merged, other] {
        std::fs::remove_dir_all(&d).ok();
    }
}

fn knotlab_mc_seed(out: &Path, trials: u64, seed: &str, more: &[&str]) -> (i32, String) {
    let mut args = mc_args(out, trials, 1);
    let at = args.iter().position(|a| a == "--seed").expect("--seed") + 1;
    args[at] = seed.to_owned();
    args.extend(more.iter().map(|s| s.to_string()));
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let (code, stdout, stderr) = knotlab(&args);
    (code, format!("{stdout}{stderr}"))
}

/// Another seed's output directory and an unknown preset are refused with the reason; the `ideal` preset
/// draws no play or calibration error, and `endopar` draws play.
#[test]
fn another_runs_directory_and_an_unknown_preset_are_named() {
    let out = dir("another");
    assert_eq!(mc(&out, 1, 1).0, 0);
    let (code, log) = knotlab_mc_seed(&out, 1, "8", &[]);
    assert_eq!(code, 1);
    assert!(log.contains("run.json") && log.contains("seed: 7 here, 8 asked"), "{log}");
    let (code, log) = mc_with(&dir("preset"), 1, 1, &["--preset", "nope"]);
    assert_eq!(code, 1);
    assert!(log.contains("presets.nope") && log.contains("endopar, ideal"), "{log}");
    // The presets change what is drawn: ideal draws no play and no calibration error.
    let ideal = dir("ideal");
    assert_eq!(mc_with(&ideal, 2, 1, &["--preset", "ideal"]).0, 0);
    for l in lines(&ideal) {
        assert_eq!(l["draw"]["play_rad"], 0.0);
        assert_eq!(l["draw"]["calibration_max_rad"], 0.0);
    }
    // Resumed without the preset: the refusal names both values as a person reads them.
    let (code, log) = mc_with(&ideal, 2, 1, &[]);
    assert_eq!(code, 1);
    assert!(log.contains("preset: ideal here, none asked"), "{log}");
    let endopar = dir("endopar");
    assert_eq!(mc_with(&endopar, 2, 1, &["--preset", "endopar"]).0, 0);
    for l in lines(&endopar) {
        assert!(l["draw"]["play_rad"].as_f64().unwrap() >= 0.0005, "{l}");
    }
    for d in [out, ideal, endopar] {
        std::fs::remove_dir_all(&d).ok();
    }
}

/// Guards against a run that measures nothing or silently does less than asked: `--trials 0` (it
/// reported 0.0 % and exited 0), `--jobs 0` (quietly one thread) and `--record-trials` past the last
/// trial (quietly none recorded) are refused, naming the flag and the value, before any trial runs;
/// so are more trials than a run may have (1e11 aborted asking for 4 GB) and more threads than 1024.
#[test]
fn zero_trials_zero_jobs_and_a_trial_to_record_beyond_the_run_are_refused() {
    let out = dir("refused-counts");
    for (trials, jobs, more, says) in [
        (0, 1, &[][..], "--trials 0"),
        (2, 0, &[][..], "--jobs 0"),
        (2, 1, &["--record-trials", "5"][..], "--record-trials 5"),
        (100_000_000_000, 1, &[][..], "--trials 100000000000: a run has at most 100000000"),
        (2, 5000, &[][..], "--jobs 5000: at most 1024 threads"),
    ] {
        let (code, text) = mc_with(&out, trials, jobs, more);
        assert_eq!(code, 1, "{text}");
        assert!(text.contains(says), "'{says}' missing from: {text}");
        assert!(!out.join("results.jsonl").exists(), "no trial may run: {text}");
    }
    std::fs::remove_dir_all(&out).ok();
}

/// Guards against counting trials that belong to another run: resuming into a folder whose
/// `results.jsonl` has no `run.json` (it reported the old lines as its own and ran nothing), or one
/// with a line of another seed, a method the run does not run, a trial beyond its count, or a trial
/// twice (the first won), is refused naming the file and line; `knotlab report` refuses the same
/// lines rather than count them.
#[test]
fn lines_that_do_not_belong_to_the_run_are_refused_by_mc_and_report() {
    let out = dir("foreign");
    assert_eq!(mc(&out, 2, 1).0, 0);
    let results = out.join("results.jsonl");
    let good = std::fs::read_to_string(&results).expect("the results");
    let first: serde_json::Value = serde_json::from_str(good.lines().next().expect("a line")).expect("JSON");
    let with = |field: &str, value: serde_json::Value| {
        let mut l = first.clone();
        l[field] = value;
        format!("{good}{l}\n")
    };
    let cases = [
        (with("seed", 8.into()), "seed 8 is not the run's (7)"),
        (with("method", "fluid".into()), "method fluid is not one of the run's"),
        (with("trial", 9.into()), "trial 9 is beyond the run's 2 trials"),
        (format!("{good}{first}\n"), "again (first on line 1)"),
    ];
    let line = good.lines().count() + 1;
    for (text, says) in &cases {
        std::fs::write(&results, text).expect("written");
        let (code, log) = mc(&out, 2, 1);
        assert_eq!(code, 1, "{log}");
        assert!(log.contains(&format!("results.jsonl:{line}")) && log.contains(says), "'{says}': {log}");
        let (code, stdout, stderr) = knotlab(&["report", out.to_str().expect("UTF-8")]);
        assert_eq!(code, 1, "{stdout}{stderr}");
        assert!(stderr.contains(says), "report, '{says}': {stderr}");
    }
    // Without run.json, the lines are traced to no run.
    std::fs::write(&results, &good).expect("written");
    std::fs::remove_file(out.join("run.json")).expect("run.json");
    let (code, log) = knotlab_mc_seed(&out, 2, "5", &[]);
    assert_eq!(code, 1, "{log}");
    assert!(log.contains("no run.json"), "{log}");
    // The report, with no run.json to check against, still refuses a trial given twice and a line of
    // another seed than the first line's.
    for (text, says) in &cases[3..] {
        std::fs::write(&results, text).expect("written");
        let (code, stdout, stderr) = knotlab(&["report", out.to_str().expect("UTF-8")]);
        assert_eq!(code, 1, "{stdout}{stderr}");
        assert!(stderr.contains(says), "report without run.json, '{says}': {stderr}");
    }
    std::fs::write(&results, with("seed", 8.into())).expect("written");
    let (code, _, stderr) = knotlab(&["report", out.to_str().expect("UTF-8")]);
    assert_eq!(code, 1, "{stderr}");
    assert!(stderr.contains("seed 8 is not the run's (7)"), "{stderr}");
    std::fs::remove_dir_all(&out).ok();
}

/// Guards against one folder mixing two skills: `run.json` records the fingerprint of the skill and
/// the demonstration it came from, and resuming with another demonstration (one sample moved by a
/// micrometre) is refused naming the field, where the same one resumes.
#[test]
fn resuming_with_another_skill_is_refused() {
    let out = dir("skill");
    assert_eq!(mc(&out, 1, 1).0, 0);
    let info: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("run.json")).expect("run.json"))
            .expect("JSON");
    assert_eq!(info["skill_fingerprint"].as_str().map(str::len), Some(16), "{info}");
    let demo = dir("skill-demo");
    std::fs::create_dir_all(&demo).expect("a folder");
    let shipped = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/demos/instrument-tie");
    for name in ["demo.toml", "left.csv", "right.csv", "assist.csv"] {
        std::fs::copy(shipped.join(name), demo.join(name)).expect("copied");
    }
    let left = std::fs::read_to_string(demo.join("left.csv")).expect("left.csv");
    let mut rows: Vec<String> = left.lines().map(str::to_owned).collect();
    let mut fields: Vec<String> = rows[100].split(',').map(str::to_owned).collect();
    fields[1] = (fields[1].parse::<f64>().expect("x_m") + 1e-6).to_string();
    rows[100] = fields.join(",");
    std::fs::write(demo.join("left.csv"), rows.join("\n") + "\n").expect("written");
    let (code, log) = mc_with(&out, 2, 1, &["--demo", demo.to_str().expect("UTF-8")]);
    assert_eq!(code, 1, "{log}");
    assert!(log.contains("skill_fingerprint"), "{log}");
    assert_eq!(mc(&out, 2, 1).0, 0, "the same skill resumes");
    for d in [out, demo] {
        std::fs::remove_dir_all(&d).ok();
    }
}

/// Guards against a resume asking for fewer trials breaking its folder: `run.json` was rewritten with
/// the smaller count while the lines beyond it stayed, and every later resume, report and merge
/// refused "trial 1 is beyond the run's 1 trials". The run keeps its count; the smaller resume
/// summarizes the trials asked for, and the folder still reports and resumes.
#[test]
fn a_resume_asking_for_fewer_trials_keeps_the_folder_whole() {
    let out = dir("fewer");
    assert_eq!(mc(&out, 2, 1).0, 0);
    let (code, log) = mc(&out, 1, 1);
    assert_eq!(code, 0, "{log}");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["trials"], 1, "{summary}");
    let run: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("run.json")).unwrap()).unwrap();
    assert_eq!(run["trials"], 2, "{run}");
    let (code, _, stderr) = knotlab(&["report", out.to_str().unwrap()]);
    assert_eq!(code, 0, "{stderr}");
    assert_eq!(mc(&out, 2, 1).0, 0);
    std::fs::remove_dir_all(&out).ok();
}

/// Guards against a method given twice with another between running twice per trial (only adjacent
/// repeats were dropped): the duplicate lines then made every resume, report and merge refuse the
/// folder. Each method runs once, in the order first given.
#[test]
fn a_method_given_twice_runs_once() {
    let out = dir("methods-twice");
    let (code, log) = mc_with(&out, 1, 1, &["--method", "dmp"]);
    assert_eq!(code, 0, "{log}");
    let run: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("run.json")).unwrap()).unwrap();
    assert_eq!(run["methods"], serde_json::json!(["dmp", "replay"]), "{run}");
    assert_eq!(lines(&out).len(), 2);
    std::fs::remove_dir_all(&out).ok();
}

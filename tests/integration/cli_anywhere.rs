//! `knotlab` run from a directory without the repository's scenario files: the commands' defaults (the
//! scene, the demonstration, the task pattern, the expert's plan, the rig) are the shipped files built
//! into the binary, giving what the repository's files give; `knotlab shipped dump` writes them out
//! byte for byte and does not overwrite.

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};

use serde_json::Value;

/// The repository root (where the shipped files are).
fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A fresh empty directory under the system's temporary directory.
fn empty_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("knotlab-cli-anywhere-{name}-{}", std::process::id()));
    std::fs::remove_dir_all(&d).ok();
    std::fs::create_dir_all(&d).expect("create the directory");
    d
}

/// `knotlab ARGS` started in directory `cwd`.
fn spawn_in(cwd: &Path, args: &[&str]) -> Child {
    Command::new(env!("CARGO_BIN_EXE_knotlab"))
        .current_dir(cwd)
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start knotlab")
}

/// Exit code, stdout and stderr of a finished `knotlab`.
fn finished(child: Child) -> (i32, String, String) {
    let Output { status, stdout, stderr } = child.wait_with_output().expect("wait for knotlab");
    (
        status.code().unwrap_or(-1),
        String::from_utf8_lossy(&stdout).into_owned(),
        String::from_utf8_lossy(&stderr).into_owned(),
    )
}

/// Runs `knotlab ARGS` in directory `cwd`: exit code, stdout, stderr.
fn knotlab_in(cwd: &Path, args: &[&str]) -> (i32, String, String) {
    finished(spawn_in(cwd, args))
}

/// Runs `knotlab ARGS` in `cwd`, expecting exit 0 and JSON on stdout.
fn json_in(cwd: &Path, args: &[&str]) -> Value {
    let (code, stdout, stderr) = knotlab_in(cwd, args);
    assert_eq!(code, 0, "knotlab {}: {stdout}{stderr}", args.join(" "));
    serde_json::from_str(&stdout).unwrap_or_else(|e| panic!("not JSON ({e}): {stdout}\n{stderr}"))
}

fn read(path: &Path) -> Vec<u8> {
    std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// Guards the Monte Carlo run's defaults: from an empty directory `knotlab mc` used to stop at
/// `scenarios/default.toml: cannot read`; it must run on the built-in scene, demonstration and pattern,
/// record the same scene name as before, and give the run (run.json, with its scene and skill
/// fingerprints) and the verdicts (summary.json) that the repository's files give, and `knotlab report`
/// must read the run there.
#[test]
fn mc_from_an_empty_directory_is_the_run_of_the_shipped_files() {
    let here = empty_dir("mc");
    let reference = empty_dir("mc-reference");
    // Seed 3's two trials, each cut at 4 s: what is compared is the run the files make (its inputs'
    // fingerprints, the draws, the figures measured), not whether the knot is tied.
    let common = ["mc", "--trials", "2", "--jobs", "1", "--seed", "3", "--until", "4", "--json"];
    let mut anywhere: Vec<&str> = common.to_vec();
    anywhere.extend(["--out", "runs/first"]);
    let reference_out = reference.join("run");
    let reference_out = reference_out.to_str().expect("a UTF-8 path");
    let mut from_files: Vec<&str> = common.to_vec();
    from_files.extend([
        "--scene",
        "scenarios/default.toml",
        "--demo",
        "scenarios/demos/instrument-tie",
        "--pattern",
        "scenarios/patterns/knot_tying.toml",
        "--out",
        reference_out,
    ]);
    // Both at once: each is one thread.
    let a = spawn_in(&here, &anywhere);
    let b = spawn_in(&root(), &from_files);
    let (code, stdout, stderr) = finished(a);
    assert_eq!(code, 0, "from an empty directory: {stdout}{stderr}");
    let (code, ref_stdout, ref_stderr) = finished(b);
    assert_eq!(code, 0, "from the repository's files: {ref_stdout}{ref_stderr}");

    let run = here.join("runs/first");
    for name in ["results.jsonl", "summary.json", "run.json"] {
        assert!(run.join(name).is_file(), "no {name} in {}", run.display());
    }
    let info: Value = serde_json::from_slice(&read(&run.join("run.json"))).expect("run.json");
    assert_eq!(info["scene"], "scenarios/default.toml", "{info}");
    let reference_dir = PathBuf::from(reference_out);
    assert_eq!(
        String::from_utf8_lossy(&read(&run.join("run.json"))),
        String::from_utf8_lossy(&read(&reference_dir.join("run.json"))),
        "run.json: the built-in files against the repository's"
    );
    let summary: Value = serde_json::from_slice(&read(&run.join("summary.json"))).expect("summary.json");
    let reference_summary: Value =
        serde_json::from_slice(&read(&reference_dir.join("summary.json"))).expect("summary.json");
    assert_eq!(summary["methods"][0]["trials"], 2, "{summary}");
    assert_eq!(summary, reference_summary, "summary.json: the built-in files against the repository's");

    let report = json_in(&here, &["report", "runs/first", "--json"]);
    assert!(here.join("runs/first/report.html").is_file(), "{report}");

    std::fs::remove_dir_all(&here).ok();
    std::fs::remove_dir_all(&reference).ok();
}

/// Guards `knotlab learn` and `knotlab run` without the repository: from an empty directory they must
/// learn the built-in demonstration with the built-in pattern into the knowledge base the repository's
/// files give (byte for byte), name them by their repository paths as before, and run a trial on the
/// built-in scene.
#[test]
fn learn_and_run_from_an_empty_directory_use_the_shipped_files() {
    let here = empty_dir("learn");
    let report = json_in(&here, &["learn", "--out", "kb.json", "--json"]);
    assert_eq!(report["accepted"], true, "{report}");
    assert_eq!(report["demo"], "scenarios/demos/instrument-tie", "{report}");
    assert_eq!(report["pattern"], "scenarios/patterns/knot_tying.toml", "{report}");
    let reference = here.join("reference.json");
    let reference_arg = reference.to_str().expect("a UTF-8 path");
    json_in(
        &root(),
        &[
            "learn",
            "--demo",
            "scenarios/demos/instrument-tie",
            "--pattern",
            "scenarios/patterns/knot_tying.toml",
            "--out",
            reference_arg,
            "--json",
        ],
    );
    assert!(
        read(&here.join("kb.json")) == read(&reference),
        "kb.json differs from the repository files' one"
    );

    let trial = json_in(&here, &["run", "--until", "0.3", "--json"]);
    assert_eq!(trial["scene"], "scenarios/default.toml", "{trial}");
    assert_eq!(trial["execution"]["status"], "simulated", "{trial}");
    let trial =
        json_in(&here, &["run", "--skill", "kb.json", "--until", "0.3", "--method", "replay", "--json"]);
    assert_eq!(trial["method"], "replay", "{trial}");
    std::fs::remove_dir_all(&here).ok();
}

/// Guards the other commands' defaults from an empty directory: `demo` (the built-in scene and expert's
/// plan; seed 0 without --seed or --seeds, as its help says), `validate`, `sim` (the built-in chain
/// scene) and `obstacles` must run, naming the files as before.
#[test]
fn demo_validate_sim_and_obstacles_run_from_an_empty_directory() {
    let here = empty_dir("others");
    // One experiment is enough to see which suture is checked (the whole suite: cli_sim's test).
    let validate = spawn_in(&here, &["validate", "--only", "material", "--json"]);
    let demo = json_in(&here, &["demo", "--until", "0.1", "--out", "demo", "--json"]);
    assert_eq!(demo["scene"], "scenarios/default.toml", "{demo}");
    assert_eq!(demo["expert"], "scenarios/experts/instrument-tie.toml", "{demo}");
    assert_eq!(demo["results"][0]["seed"], 0, "{demo}");
    assert!(here.join("demo/demo.toml").is_file(), "{demo}");

    let sim = json_in(&here, &["sim", "--seconds", "0.05", "--json"]);
    assert_eq!(sim["scene"], "scenarios/chain.toml", "{sim}");

    let obstacles = json_in(
        &here,
        &["obstacles", "--arm", "left", "--cells", "4", "--subcells", "1", "--out", "o", "--json"],
    );
    assert_eq!(obstacles["scene"], "scenarios/default.toml", "{obstacles}");
    assert!(here.join("o/obstacles.csv").is_file(), "{obstacles}");

    // Exit 1 says a judged check failed; the run itself must have been made.
    let (code, stdout, stderr) = finished(validate);
    assert!(code == 0 || code == 1, "{stdout}{stderr}");
    let validation: Value = serde_json::from_str(&stdout).expect("JSON");
    assert_eq!(validation["suture_from"], "scenarios/default.toml", "{validation}");
    assert_eq!(validation["experiments"], serde_json::json!(["material"]), "{validation}");
    let checks = validation["checks"].as_array().expect("checks");
    assert!(!checks.is_empty() && checks.iter().all(|c| c["experiment"] == "material"), "{validation}");
    std::fs::remove_dir_all(&here).ok();
}

/// Guards `knotlab shipped dump`: every built-in file (the list `knotlab shipped list` gives, which must
/// hold the commands' defaults) is written under its repository path, byte for byte the repository's;
/// a second dump refuses, writing nothing, until --force.
#[test]
fn shipped_dump_writes_the_repository_files_and_does_not_overwrite() {
    let here = empty_dir("dump");
    let list = json_in(&here, &["shipped", "list", "--json"]);
    let paths: Vec<String> = list
        .as_array()
        .expect("a list")
        .iter()
        .map(|f| f["path"].as_str().expect("a path").to_owned())
        .collect();
    for default in [
        "scenarios/default.toml",
        "scenarios/chain.toml",
        "scenarios/patterns/knot_tying.toml",
        "scenarios/experts/instrument-tie.toml",
        "scenarios/demos/instrument-tie/demo.toml",
        "scenarios/demos/instrument-tie/left.csv",
        "scenarios/demos/instrument-tie/right.csv",
        "scenarios/demos/instrument-tie/assist.csv",
        "scenarios/rigs/sim-gamepad.toml",
        "scenarios/rigs/sim.toml",
        "scenarios/rigs/melfa.toml",
        "scenarios/rigs/lab.toml",
    ] {
        assert!(paths.iter().any(|p| p == default), "{default} is not shipped: {paths:?}");
    }

    let dumped = json_in(&here, &["shipped", "dump", "--out", "D", "--json"]);
    assert_eq!(dumped["files"].as_array().map(Vec::len), Some(paths.len()), "{dumped}");
    for path in &paths {
        let written = read(&here.join("D").join(path));
        assert!(written == read(&root().join(path)), "D/{path} is not the repository's file");
    }

    let edited = here.join("D/scenarios/default.toml");
    std::fs::write(&edited, "# edited\n").expect("edit");
    std::fs::remove_file(here.join("D/scenarios/rigs/sim.toml")).expect("remove");
    let (code, stdout, stderr) = knotlab_in(&here, &["shipped", "dump", "--out", "D"]);
    assert_eq!(code, 1, "{stdout}{stderr}");
    assert!(stderr.contains("D/scenarios/default.toml") && stderr.contains("--force"), "{stderr}");
    assert_eq!(read(&edited), b"# edited\n", "an existing file was overwritten");
    assert!(!here.join("D/scenarios/rigs/sim.toml").exists(), "a refused dump wrote a file");

    let (code, stdout, stderr) = knotlab_in(&here, &["shipped", "dump", "--out", "D", "--force"]);
    assert_eq!(code, 0, "{stdout}{stderr}");
    assert!(read(&edited) == read(&root().join("scenarios/default.toml")), "--force did not overwrite");
    assert!(here.join("D/scenarios/rigs/sim.toml").is_file(), "--force did not write the missing file");
    std::fs::remove_dir_all(&here).ok();
}

/// Guards the help of the defaults that moved into the binary: each names the shipped file and says
/// it is built in; `demo --seed` shows its default and still cannot be given with --seeds.
#[test]
fn help_names_the_built_in_defaults() {
    let here = empty_dir("help");
    for (command, arg, file) in [
        ("mc", "--scene", "scenarios/default.toml"),
        ("mc", "--demo", "scenarios/demos/instrument-tie"),
        ("mc", "--pattern", "scenarios/patterns/knot_tying.toml"),
        ("run", "--scene", "scenarios/default.toml"),
        ("demo", "--expert", "scenarios/experts/instrument-tie.toml"),
        ("learn", "--demo", "scenarios/demos/instrument-tie"),
        ("validate", "--suture-from", "scenarios/default.toml"),
        ("sim", "--scene", "scenarios/chain.toml"),
        ("obstacles", "--scene", "scenarios/default.toml"),
        ("session", "--rig", "scenarios/rigs/sim-gamepad.toml"),
    ] {
        let (code, help, stderr) = knotlab_in(&here, &[command, "--help"]);
        assert_eq!(code, 0, "{stderr}");
        let line = help
            .lines()
            .skip_while(|l| !l.trim_start().starts_with(arg))
            .take_while(|l| l.trim_start().starts_with(arg) || !l.trim_start().starts_with('-'))
            .collect::<Vec<_>>()
            .join(" ");
        // The help is wrapped to the terminal's width: compare with the spaces collapsed.
        let line = line.split_whitespace().collect::<Vec<_>>().join(" ");
        let wanted = format!("[default: the shipped {file}, built in]");
        assert!(line.contains(&wanted), "{command} {arg}: no `{wanted}` in: {line}");
    }
    let (_, help, _) = knotlab_in(&here, &["demo", "--help"]);
    let seed = help
        .lines()
        .skip_while(|l| !l.trim_start().starts_with("--seed "))
        .take_while(|l| l.trim_start().starts_with("--seed ") || !l.trim_start().starts_with('-'))
        .collect::<Vec<_>>()
        .join(" ");
    assert!(seed.contains("[default: 0]"), "demo --seed: {seed}");
    let (code, _, stderr) = knotlab_in(&here, &["demo", "--seed", "1", "--seeds", "0..2", "--out", "never"]);
    assert_eq!(code, 2, "--seed with --seeds: {stderr}");
    assert!(!here.join("never").exists(), "--seed with --seeds ran");
    std::fs::remove_dir_all(&here).ok();
}

//! The README's commands run as written: every `knotlab` command in its code blocks and tables names a
//! command that exists with flags it takes, and the workflow's commands run, in an empty directory,
//! at tiny sizes.

use std::path::{Path, PathBuf};
use std::process::Command;

/// Every `knotlab ...` command of the README: the lines of its `sh` code blocks and its backticked
/// commands, a trailing `# comment` cut off; a placeholder for the command (`knotlab COMMAND
/// --help`) is left out.
fn readme_commands() -> Vec<String> {
    let text =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("README.md")).expect("README");
    let mut commands = Vec::new();
    let mut in_sh = false;
    for line in text.lines() {
        if line.starts_with("```") {
            in_sh = line == "```sh";
            continue;
        }
        if in_sh {
            let command = line.split(" #").next().unwrap_or("").trim();
            if command.starts_with("knotlab ") {
                commands.push(command.to_owned());
            }
        } else {
            for quoted in line.split('`').skip(1).step_by(2) {
                if quoted.starts_with("knotlab ") {
                    commands.push(quoted.to_owned());
                }
            }
        }
    }
    commands.retain(|c| c.split_whitespace().nth(1).is_some_and(|w| w != w.to_uppercase()));
    commands
}

/// Runs `knotlab ARGS` in `dir`: exit code, stdout and stderr together.
fn knotlab_in(dir: &Path, args: &[&str]) -> (i32, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_knotlab"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("run knotlab");
    let text = format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    (out.status.code().unwrap_or(-1), text)
}

fn empty_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("knotlab-readme-{name}-{}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).expect("a temporary directory");
    dir
}

/// Every README command names an existing subcommand, and every flag it gives is one that subcommand
/// takes (its `--help` lists it): a renamed flag or command in the code cannot leave the README
/// behind.
#[test]
fn every_readme_command_exists_with_its_flags() {
    let commands = readme_commands();
    assert!(commands.len() >= 8, "too few commands found: {commands:?}");
    let dir = empty_dir("flags");
    for command in &commands {
        let words: Vec<&str> = command.split_whitespace().skip(1).collect();
        let path: Vec<&str> = words.iter().take_while(|w| !w.starts_with('-')).copied().collect();
        // The subcommand path: each word the help of the path before it lists among its commands
        // (`knotlab report runs/x`: `runs/x` is the report's argument, not a command).
        let mut sub: Vec<&str> = Vec::new();
        for word in path {
            let mut probe = sub.clone();
            probe.push("--help");
            let (_, help) = knotlab_in(&dir, &probe);
            let listed = help
                .lines()
                .skip_while(|l| !l.starts_with("Commands:"))
                .any(|l| l.split_whitespace().next() == Some(word) && l.starts_with("  "));
            if !listed {
                break;
            }
            sub.push(word);
        }
        assert!(!sub.is_empty(), "no knotlab command in `{command}`");
        let mut help_args = sub.clone();
        help_args.push("--help");
        let (code, help) = knotlab_in(&dir, &help_args);
        assert_eq!(code, 0, "`knotlab {}` --help: {help}", sub.join(" "));
        for flag in words.iter().filter(|w| w.starts_with("--")) {
            let flag = flag.split('=').next().unwrap_or(flag);
            assert!(help.contains(flag), "`{command}`: `knotlab {}` takes no {flag}:\n{help}", sub.join(" "));
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// The workflow's commands run as the README gives them, in an empty directory with only the binary,
/// cut to a second of skill and one trial: learn, one trial at a moved stitch, a Monte Carlo run and
/// its report each exit 0 and write what the README says they write.
#[test]
fn the_workflow_runs_in_an_empty_directory() {
    let dir = empty_dir("workflow");
    let (code, text) = knotlab_in(&dir, &["learn", "--out", "kb.json"]);
    assert_eq!(code, 0, "{text}");
    assert!(dir.join("kb.json").exists());
    let (code, text) = knotlab_in(
        &dir,
        &[
            "run",
            "--skill",
            "kb.json",
            "--seed",
            "3",
            "--stitch-offset",
            "0.01,0,0",
            "--json",
            "--until",
            "1",
        ],
    );
    assert_eq!(code, 0, "{text}");
    let (code, text) = knotlab_in(
        &dir,
        &["mc", "--skill", "kb.json", "--trials", "1", "--jobs", "1", "--until", "1", "--out", "runs/first"],
    );
    assert_eq!(code, 0, "{text}");
    for file in ["results.jsonl", "summary.json", "run.json"] {
        assert!(dir.join("runs/first").join(file).exists(), "no {file}: {text}");
    }
    let (code, text) = knotlab_in(&dir, &["report", "runs/first"]);
    assert_eq!(code, 0, "{text}");
    assert!(dir.join("runs/first/report.html").exists(), "{text}");
    std::fs::remove_dir_all(&dir).ok();
}

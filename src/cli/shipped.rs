//! `knotlab shipped`: the scenario files built into knotlab, the defaults of its commands. `list` names
//! them; `dump --out DIR` writes them under DIR with their repository paths, to be edited and passed
//! back with --scene, --demo, --pattern, --expert or --rig.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::Context;
use clap::{Args, Subcommand};
use serde_json::json;

use super::output::{Output, outln};
use knotlab_scenarios::shipped::{self, ShippedFile};

#[derive(Debug, Subcommand)]
pub enum ShippedCommand {
    /// Name the built-in files: their repository paths, sizes and which commands default to them.
    List(ListArgs),
    /// Write the built-in files under DIR with their repository paths (DIR/scenarios/default.toml,
    /// ...); refuses, writing nothing, when one of them is already there (unless --force).
    Dump(DumpArgs),
}

#[derive(Debug, Args)]
pub struct ListArgs {
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
}

#[derive(Debug, Args)]
pub struct DumpArgs {
    /// The directory to write under (created if missing).
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
    /// Overwrite files that are already there.
    #[arg(long)]
    force: bool,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
}

pub fn run(command: ShippedCommand, out: &mut Output) -> anyhow::Result<ExitCode> {
    match command {
        ShippedCommand::List(args) => list(&args, out),
        ShippedCommand::Dump(args) => dump(&args, out),
    }
}

fn list(args: &ListArgs, out: &mut Output) -> anyhow::Result<ExitCode> {
    let files = shipped::all();
    if args.json {
        let value: Vec<_> = files
            .iter()
            .map(|f| json!({ "path": f.path, "bytes": f.text.len(), "about": f.about }))
            .collect();
        outln!(out, "{}", serde_json::to_string_pretty(&value)?);
    } else {
        let width = files.iter().map(|f| f.path.len()).max().unwrap_or(0);
        for f in &files {
            outln!(out, "{:<width$}  {:>7} bytes  {}", f.path, f.text.len(), f.about);
        }
    }
    Ok(ExitCode::SUCCESS)
}

/// Where `file` goes under `dir`.
fn target(dir: &Path, file: &ShippedFile) -> PathBuf {
    file.path.split('/').fold(dir.to_path_buf(), |path, part| path.join(part))
}

fn dump(args: &DumpArgs, out: &mut Output) -> anyhow::Result<ExitCode> {
    let files = shipped::all();
    let targets: Vec<PathBuf> = files.iter().map(|f| target(&args.out, f)).collect();
    if !args.force {
        let there: Vec<&PathBuf> = targets.iter().filter(|p| p.symlink_metadata().is_ok()).collect();
        if let Some(first) = there.first() {
            let more = match there.len() - 1 {
                0 => String::new(),
                n => format!(" (and {n} more of the shipped files)"),
            };
            anyhow::bail!("{}{more}: already there (--force overwrites); nothing written", first.display());
        }
    }
    for (file, path) in files.iter().zip(&targets) {
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent)
                .with_context(|| format!("{}: cannot create", parent.display()))?;
        }
        std::fs::write(path, file.text).with_context(|| format!("{}: cannot write", path.display()))?;
    }
    let written: Vec<String> = targets.iter().map(|p| p.display().to_string()).collect();
    if args.json {
        let value = json!({ "out": args.out.display().to_string(), "files": written });
        outln!(out, "{}", serde_json::to_string_pretty(&value)?);
    } else {
        for path in &written {
            outln!(out, "{path}");
        }
        outln!(out, "wrote {} shipped files under {}", written.len(), args.out.display());
    }
    Ok(ExitCode::SUCCESS)
}

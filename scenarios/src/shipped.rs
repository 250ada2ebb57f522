//! The shipped scenario files, built in: the scenes, the demonstration, the task pattern, the expert's
//! plan and the rig configs that the `knotlab` commands and the Python package default to, so that
//! they run from any directory. A file named on the command line replaces the built-in one; `knotlab
//! shipped dump` writes them out, under their repository paths, to be edited.

use std::path::Path;

use crate::expert::{GeometryFileError, TieGeometry, load_tie_geometry, parse_tie_geometry};
use knotlab_hw::rig_config::{RigConfig, RigConfigError, load_rig_config, parse_rig_config};
use knotlab_learner::demonstration::{DemoError, Demonstration, load_demonstration, read_demonstration_dir};
use knotlab_learner::pattern::{PatternError, TaskPattern, load_pattern, parse_pattern};
use knotlab_sim::scene::{SceneConfig, SceneError, load_scene, parse_scene};

/// One shipped file: its path in the repository (the name outputs and errors give it) and its text.
#[derive(Clone, Copy, Debug)]
pub struct ShippedFile {
    /// The path in the repository, `/`-separated.
    pub path: &'static str,
    /// The file's text, byte for byte.
    pub text: &'static str,
    /// What it is and which commands default to it.
    pub about: &'static str,
}

/// `shipped!("x.toml", "about")`: the file `scenarios/x.toml` of the repository (this crate's
/// directory), built in.
macro_rules! shipped {
    ($file:literal, $about:literal) => {
        ShippedFile {
            path: concat!("scenarios/", $file),
            text: include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/", $file)),
            about: $about,
        }
    };
}

/// The nominal scene: `mc`, `run`, `demo`, `obstacles`, `validate` and `session` default to it.
pub const SCENE: ShippedFile = shipped!(
    "default.toml",
    "the scene (with its randomization and presets) of mc, run, demo, obstacles, validate, session"
);
/// The capsule-chain scene `sim` defaults to.
pub const CHAIN_SCENE: ShippedFile = shipped!("chain.toml", "the capsule-chain scene of sim");
/// The knot-tying task pattern.
pub const PATTERN: ShippedFile =
    shipped!("patterns/knot_tying.toml", "the task pattern of learn, run, mc, session");
/// The scripted expert's plan `demo` runs.
pub const EXPERT: ShippedFile = shipped!("experts/instrument-tie.toml", "the expert's plan of demo");
/// Every key of an expert's plan with its base value (a reference to edit a plan by).
pub const EXPERT_BASE: ShippedFile =
    shipped!("experts/base.toml", "every key of an expert's plan, at its base value");
/// The rig `session` defaults to.
pub const GAMEPAD_RIG: ShippedFile =
    shipped!("rigs/sim-gamepad.toml", "the rig of session (a gamepad steers)");
/// The simulated rig with dummy masters and pedals.
pub const SIM_RIG: ShippedFile =
    shipped!("rigs/sim.toml", "a rig of dummy masters and pedals (session --rig)");
/// The rig of the MELFA arms.
pub const MELFA_RIG: ShippedFile =
    shipped!("rigs/melfa.toml", "the MELFA arms' rig (run --rig, session --rig)");
/// The lab's rig: every device real.
pub const LAB_RIG: ShippedFile = shipped!(
    "rigs/lab.toml",
    "the lab's rig, every device real: MELFA arms, CANopen instrument drives, Net F/T sensors (run --rig)"
);
/// Ghia, Ghia and Shin's lid-driven cavity table.
pub const GHIA: ShippedFile =
    shipped!("reference/ghia1982-cavity.csv", "the lid-driven cavity's reference (fluid cavity --reference)");

/// The canonical demonstration's directory.
pub const DEMO_DIR: &str = "scenarios/demos/instrument-tie";
/// The canonical demonstration's files (`DEMO_DIR/...`).
pub const DEMO: [ShippedFile; 4] = [
    shipped!("demos/instrument-tie/demo.toml", "the demonstration of learn, run, mc, session: its metadata"),
    shipped!("demos/instrument-tie/left.csv", "the demonstration: the left instrument"),
    shipped!("demos/instrument-tie/right.csv", "the demonstration: the right instrument"),
    shipped!("demos/instrument-tie/assist.csv", "the demonstration: the assisting instrument"),
];

/// Every shipped file, in the order `knotlab shipped list` gives them.
pub fn all() -> Vec<ShippedFile> {
    let mut files = vec![SCENE, CHAIN_SCENE, PATTERN, EXPERT, EXPERT_BASE];
    files.extend(DEMO);
    files.extend([GAMEPAD_RIG, SIM_RIG, MELFA_RIG, LAB_RIG, GHIA]);
    files
}

/// The name a file goes by in outputs and errors: its path as given, else the shipped file's path.
pub fn name(path: Option<&Path>, shipped: &ShippedFile) -> String {
    path.map_or_else(|| shipped.path.to_owned(), |p| p.display().to_string())
}

/// The demonstration's name: its directory as given, else the shipped one's.
pub fn demo_name(path: Option<&Path>) -> String {
    path.map_or_else(|| DEMO_DIR.to_owned(), |p| p.display().to_string())
}

/// The scene file at `path`, else the shipped `scene`.
pub fn scene(path: Option<&Path>, shipped: &ShippedFile) -> Result<SceneConfig, SceneError> {
    match path {
        Some(path) => load_scene(path),
        None => parse_scene(shipped.text, shipped.path),
    }
}

/// The task pattern at `path`, else the shipped one.
pub fn pattern(path: Option<&Path>) -> Result<TaskPattern, PatternError> {
    match path {
        Some(path) => load_pattern(path),
        None => parse_pattern(PATTERN.text, PATTERN.path),
    }
}

/// The expert's plan at `path`, else the shipped one.
pub fn tie_geometry(path: Option<&Path>) -> Result<TieGeometry, GeometryFileError> {
    match path {
        Some(path) => load_tie_geometry(path),
        None => parse_tie_geometry(EXPERT.text, EXPERT.path),
    }
}

/// The rig config at `path`, else the shipped `rig`.
pub fn rig_config(path: Option<&Path>, shipped: &ShippedFile) -> Result<RigConfig, RigConfigError> {
    match path {
        Some(path) => load_rig_config(path),
        None => parse_rig_config(shipped.text, shipped.path),
    }
}

/// The demonstration in directory `path`, else the shipped one.
pub fn demonstration(path: Option<&Path>) -> Result<Demonstration, DemoError> {
    if let Some(dir) = path {
        return load_demonstration(dir);
    }
    // The empty path: whatever the current directory holds, the files come from the binary.
    read_demonstration_dir(Path::new(""), |name| {
        let path = format!("{DEMO_DIR}/{name}");
        match DEMO.iter().find(|f| f.path == path) {
            Some(file) => Ok((path, file.text.to_owned())),
            None => Err(DemoError::Io {
                file: path,
                action: "cannot read",
                error: std::io::Error::new(std::io::ErrorKind::NotFound, "not a shipped file"),
            }),
        }
    })
}

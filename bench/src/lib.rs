//! knotlab's evaluation: Monte Carlo knot-tying runs ([`mc`]) and the performance benchmarks in
//! `benches/` (`cargo bench -p knotlab-bench`).

pub mod mc;
pub mod report;

/// The shipped nominal scene (`scenarios/default.toml`, compiled in) for a benchmark; exits with the
/// scene's error if it does not parse.
pub fn shipped_scene() -> knotlab_sim::scene::SceneConfig {
    scene_or_exit(include_str!("../../scenarios/default.toml"), "scenarios/default.toml")
}

/// The scene in `text` (read from `name`), or exit with its error (for benchmarks).
pub fn scene_or_exit(text: &str, name: &str) -> knotlab_sim::scene::SceneConfig {
    match knotlab_sim::scene::parse_scene(text, name) {
        Ok(scene) => scene,
        Err(e) => {
            eprintln!("{e}");
            std::process::exit(1);
        }
    }
}

/// Indices 1, 2, ..., `len - 1`, 0, 1, ... in turn: a benchmark's inputs taken one after another from a
/// set of `len` (at least one).
pub fn round_robin(len: usize) -> impl FnMut() -> usize {
    let mut next = 0;
    move || {
        next = (next + 1) % len.max(1);
        next
    }
}

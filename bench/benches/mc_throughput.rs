//! Benchmark: Monte Carlo throughput, full knot-tying trials per minute (issue 11's target: at least 30
//! on 2 cores). Learns once from the shipped demonstration, then runs `KNOTLAB_BENCH_TRIALS` trials
//! (default 4) of the default scene by the fluid method on `KNOTLAB_BENCH_JOBS` threads (default 2) into
//! a fresh directory, and prints trials per minute with the simulated seconds per wall second.
//!
//! `cargo bench -p knotlab-bench --bench mc_throughput`

use std::error::Error;
use std::path::Path;
use std::time::Instant;

use knotlab_bench::mc::{McOptions, run_mc};
use knotlab_learner::demonstration::load_demonstration;
use knotlab_learner::pattern::load_pattern;
use knotlab_learner::primitive::learn;
use knotlab_learner::synthesis::Method;
use knotlab_scenarios::trial::Learned;
use knotlab_sim::scene::load_scene;

fn env_number(name: &str, default: u64) -> u64 {
    std::env::var(name).ok().and_then(|v| v.parse().ok()).unwrap_or(default)
}

fn main() -> Result<(), Box<dyn Error>> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let trials = env_number("KNOTLAB_BENCH_TRIALS", 4);
    let jobs = env_number("KNOTLAB_BENCH_JOBS", 2) as usize;
    let demonstration = load_demonstration(&root.join("scenarios/demos/instrument-tie"))?;
    let pattern = load_pattern(&root.join("scenarios/patterns/knot_tying.toml"))?;
    let started = Instant::now();
    let learned = Learned { knowledge: learn(&demonstration, &pattern)?, demonstration };
    let learn_s = started.elapsed().as_secs_f64();
    let out = std::env::temp_dir().join(format!("knotlab-bench-mc-{}", std::process::id()));
    std::fs::remove_dir_all(&out).ok();
    let options = McOptions {
        scene: load_scene(&root.join("scenarios/default.toml"))?,
        scene_name: "scenarios/default.toml".to_owned(),
        preset: None,
        trials,
        seed: 0,
        jobs,
        methods: vec![Method::Fluid],
        out: out.clone(),
        until_s: None,
        shard: None,
    };
    let started = Instant::now();
    let mut simulated_s = 0.0;
    let mut trial_wall_s = 0.0;
    run_mc(&learned, &options, |line, _, _| {
        simulated_s += line.sim_seconds;
        trial_wall_s += line.wall_seconds;
    })?;
    let wall_s = started.elapsed().as_secs_f64();
    std::fs::remove_dir_all(&out).ok();
    println!(
        "mc throughput: {trials} trials on {jobs} threads in {wall_s:.1} s = {:.2} trials/min  [target: at least 30 on 2 cores]",
        trials as f64 / wall_s * 60.0
    );
    println!(
        "per trial: {:.1} s simulated, {:.1} s wall on one thread ({:.2} simulated s per wall s); learning once: {learn_s:.2} s",
        simulated_s / trials.max(1) as f64,
        trial_wall_s / trials.max(1) as f64,
        simulated_s / trial_wall_s.max(1e-9)
    );
    Ok(())
}

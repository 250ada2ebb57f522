//! Benchmark: Monte Carlo throughput, full knot-tying trials per minute (target: at least 30 on 2
//! cores). Learns once from the shipped demonstration, then times `KNOTLAB_BENCH_TRIALS` trials
//! (default 4) of the default scene by the fluid method on `KNOTLAB_BENCH_JOBS` threads (default 2)
//! with divan, counted per trial (trials per second: times 60 for the minute).
//!
//! `cargo bench -p knotlab-bench --bench mc_throughput`

use std::error::Error;
use std::path::Path;

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

fn main() {
    divan::main();
}

/// `KNOTLAB_BENCH_TRIALS` trials of the default scene by the fluid method on `KNOTLAB_BENCH_JOBS`
/// threads into a fresh directory, counted per trial (the skill learned once, before).
#[divan::bench(sample_count = 1, sample_size = 1)]
fn trials(bencher: divan::Bencher) {
    let setup = || -> Result<(Learned, McOptions), Box<dyn Error>> {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
        let demonstration = load_demonstration(&root.join("scenarios/demos/instrument-tie"))?;
        let pattern = load_pattern(&root.join("scenarios/patterns/knot_tying.toml"))?;
        let learned = Learned { knowledge: learn(&demonstration, &pattern)?, demonstration };
        let options = McOptions {
            scene: load_scene(&root.join("scenarios/default.toml"))?,
            scene_name: "scenarios/default.toml".to_owned(),
            preset: None,
            trials: env_number("KNOTLAB_BENCH_TRIALS", 4),
            seed: 0,
            jobs: env_number("KNOTLAB_BENCH_JOBS", 2) as usize,
            methods: vec![Method::Fluid],
            out: std::env::temp_dir().join(format!("knotlab-bench-mc-{}", std::process::id())),
            until_s: None,
            shard: None,
            skill_fingerprint: knotlab_bench::mc::run_info::skill_fingerprint(&learned),
        };
        Ok((learned, options))
    };
    let (learned, options) = setup().expect("the shipped demonstration, pattern and scene");
    let mut simulated_s = 0.0;
    bencher.counter(divan::counter::ItemsCount::new(options.trials as usize)).bench_local(|| {
        std::fs::remove_dir_all(&options.out).ok();
        run_mc(&learned, &options, |line, _, _| simulated_s += line.sim_seconds).expect("the trials run");
    });
    std::fs::remove_dir_all(&options.out).ok();
    println!("{:.1} s simulated a trial", simulated_s / options.trials.max(1) as f64);
}

//! Benchmark: learning from one demonstration of the knot (about 9 s, synthetic, at 100 Hz and at
//! 1 kHz): detecting its features, matching the shipped pattern, extracting the primitives.
//!
//! `cargo bench -p knotlab-bench --bench segment` times each stage with divan, on nine seeded
//! demonstrations in turn. (How well the pattern decomposes them: `cargo bench -p knotlab-lab
//! --bench segmentation`.)

use std::hint::black_box;
use std::path::Path;

use knotlab_learner::demonstration::Demonstration;
use knotlab_learner::features::{FeatureSet, detect};
use knotlab_learner::pattern::{TaskPattern, load_pattern};
use knotlab_learner::primitive::extract;
use knotlab_learner::segment::decompose;
use knotlab_learner::synthetic::{SyntheticSettings, canonical_demonstration};

fn main() {
    divan::main();
}

/// The demonstrations' sample rates, Hz.
const RATES: [f64; 2] = [100.0, 1000.0];

fn pattern() -> TaskPattern {
    load_pattern(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenarios/patterns/knot_tying.toml"))
        .expect("the shipped pattern")
}

/// Nine seeded demonstrations at `rate_hz` with their features.
fn demonstrations(pattern: &TaskPattern, rate_hz: f64) -> Vec<(Demonstration, FeatureSet)> {
    (0..9)
        .map(|seed| {
            let (demo, _) = canonical_demonstration(&SyntheticSettings::canonical(seed, rate_hz));
            let features = detect(&demo, &pattern.detector).expect("features");
            (demo, features)
        })
        .collect()
}

/// Detecting the features of one demonstration.
#[divan::bench(args = RATES)]
fn features(bencher: divan::Bencher, rate_hz: f64) {
    let pattern = pattern();
    let demos = demonstrations(&pattern, rate_hz);
    bencher
        .with_inputs(knotlab_bench::round_robin(demos.len()))
        .bench_local_values(|i| detect(black_box(&demos[i].0), &pattern.detector));
}

/// Matching the pattern against one demonstration's features.
#[divan::bench(args = RATES)]
fn matching(bencher: divan::Bencher, rate_hz: f64) {
    let pattern = pattern();
    let demos = demonstrations(&pattern, rate_hz);
    bencher
        .with_inputs(knotlab_bench::round_robin(demos.len()))
        .bench_local_values(|i| decompose(&pattern, black_box(&demos[i].1)));
}

/// Extracting the primitives of one decomposed demonstration.
#[divan::bench(args = RATES)]
fn extraction(bencher: divan::Bencher, rate_hz: f64) {
    let pattern = pattern();
    let demos: Vec<_> = demonstrations(&pattern, rate_hz)
        .into_iter()
        .map(|(demo, features)| {
            let d = decompose(&pattern, &features).expect("a decomposition");
            (demo, features, d)
        })
        .collect();
    bencher.with_inputs(knotlab_bench::round_robin(demos.len())).bench_local_values(|i| {
        let (demo, features, d) = &demos[i];
        extract(black_box(demo), &pattern, features, d)
    });
}

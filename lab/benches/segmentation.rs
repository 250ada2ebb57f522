//! Benchmark: how well the shipped knot-tying pattern decomposes synthetic demonstrations whose
//! primitive boundaries are known (learner::synthetic: minimum-jerk moves, speed +-20 % per run,
//! pauses 0.1-0.4 s, tremor 0.1-0.2 mm at 8-12 Hz, force noise 0.01-0.02 N per axis), in the
//! JIGSAWS-style measures: the median and 90th-percentile boundary error, boundary precision, recall
//! and F1 within +-50 ms, and the segmental edit score (Lea et al. 2016); also at 1 kHz, at a third of
//! the speed, at twice the noise, and the rejection rate of demonstrations that are not the task (a
//! single wrap, the tail never grasped, the recording cut before the pulls). (The time to learn
//! from one demonstration is `cargo bench -p knotlab-bench --bench segment`.)
//!
//! `cargo bench -p knotlab-lab --bench segmentation` prints the tables; `-- --seeds N` sets the
//! demonstrations per row (default 50).

use std::path::Path;

use knotlab_learner::features::detect;
use knotlab_learner::pattern::{TaskPattern, load_pattern};
use knotlab_learner::segment::decompose;
use knotlab_learner::segment::metrics::{
    BoundaryCounts, boundary_counts, boundary_errors, median, segmental_edit_score,
};
use knotlab_learner::synthetic::{SyntheticSettings, canonical_demonstration};

/// One row: how the demonstrations are made.
struct Row {
    name: &'static str,
    make: fn(u64) -> SyntheticSettings,
}

fn percentile(values: &[f64], p: f64) -> f64 {
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    v.get(((v.len() as f64 - 1.0) * p).round() as usize).copied().unwrap_or(f64::NAN)
}

fn accuracy(pattern: &TaskPattern, row: &Row, seeds: u64) -> Result<(), Box<dyn std::error::Error>> {
    let mut errors = Vec::new();
    let mut counts = BoundaryCounts::default();
    let mut edit = Vec::new();
    let mut rejected = 0;
    for seed in 0..seeds {
        let settings = (row.make)(seed);
        let (demo, truth) = canonical_demonstration(&settings);
        let features = detect(&demo, &pattern.detector)?;
        match decompose(pattern, &features) {
            Ok(d) => {
                errors.extend(boundary_errors(&truth.spans(), &d.spans()));
                counts.add(boundary_counts(&truth.spans(), &d.spans(), 0.05));
                edit.push(segmental_edit_score(&truth.spans(), &d.spans(), 0.01));
            }
            Err(_) => rejected += 1,
        }
    }
    let mean_edit = if edit.is_empty() { f64::NAN } else { edit.iter().sum::<f64>() / edit.len() as f64 };
    println!(
        "{:<28} {:>5} {:>8} {:>10.1} {:>10.1} {:>10.1} {:>9.3} {:>9.3} {:>9.3} {:>9.1}",
        row.name,
        seeds,
        rejected,
        1e3 * median(&errors),
        1e3 * percentile(&errors, 0.9),
        1e3 * percentile(&errors, 1.0),
        counts.precision(),
        counts.recall(),
        counts.f1(),
        mean_edit,
    );
    Ok(())
}

fn rejections(pattern: &TaskPattern, seeds: u64) -> Result<(), Box<dyn std::error::Error>> {
    println!();
    println!("{:<28} {:>5} {:>8}  first missing element (count)", "not the task", "demos", "rejected");
    let variants: [Row; 3] = [
        Row {
            name: "a single wrap",
            make: |seed| SyntheticSettings { wraps: 1, ..SyntheticSettings::canonical(seed, 100.0) },
        },
        Row {
            name: "the tail never grasped",
            make: |seed| SyntheticSettings { grasp_tail: false, ..SyntheticSettings::canonical(seed, 100.0) },
        },
        Row {
            name: "cut before the pull",
            make: |seed| {
                let full = SyntheticSettings::canonical(seed, 100.0);
                let (_, truth) = canonical_demonstration(&full);
                let pull = truth.primitives.iter().filter(|p| p.name == "R5");
                let cut = pull.map(|p| p.start_s).fold(f64::INFINITY, f64::min) - 0.05;
                SyntheticSettings { cut_at_s: Some(cut), ..full }
            },
        },
    ];
    for Row { name, make } in variants {
        let mut rejected = 0;
        let mut missing: Vec<(String, usize)> = Vec::new();
        for seed in 0..seeds {
            let (demo, _) = canonical_demonstration(&make(seed));
            let features = detect(&demo, &pattern.detector)?;
            if let Err(r) = decompose(pattern, &features) {
                rejected += 1;
                let element =
                    r.primary().map_or("?".to_owned(), |f| format!("{}.{}", f.instrument, f.element));
                match missing.iter_mut().find(|(e, _)| *e == element) {
                    Some((_, n)) => *n += 1,
                    None => missing.push((element, 1)),
                }
            }
        }
        let list: Vec<String> = missing.iter().map(|(e, n)| format!("{e} ({n})")).collect();
        println!("{name:<28} {seeds:>5} {rejected:>8}  {}", list.join(", "));
    }
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let seeds: u64 = args
        .iter()
        .position(|a| a == "--seeds")
        .and_then(|i| args.get(i + 1))
        .and_then(|s| s.parse().ok())
        .unwrap_or(50);
    let pattern =
        load_pattern(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenarios/patterns/knot_tying.toml"))?;
    println!("segmentation of synthetic knot-tying demonstrations by scenarios/patterns/knot_tying.toml");
    println!(
        "{:<28} {:>5} {:>8} {:>10} {:>10} {:>10} {:>9} {:>9} {:>9} {:>9}",
        "demonstrations",
        "demos",
        "rejected",
        "median ms",
        "p90 ms",
        "max ms",
        "prec@50",
        "rec@50",
        "F1@50",
        "edit"
    );
    let rows = [
        Row { name: "nominal, 100 Hz", make: |seed| SyntheticSettings::canonical(seed, 100.0) },
        Row { name: "nominal, 1 kHz", make: |seed| SyntheticSettings::canonical(seed + 1000, 1000.0) },
        Row {
            name: "a third of the speed, 100 Hz",
            make: |seed| SyntheticSettings {
                speed_scale: 0.3,
                ..SyntheticSettings::canonical(seed + 2000, 100.0)
            },
        },
        Row {
            name: "twice the noise, 100 Hz",
            make: |seed| SyntheticSettings {
                tremor_m: (2e-4, 3e-4),
                position_noise_m: 5e-5,
                force_noise_n: (0.03, 0.04),
                ..SyntheticSettings::canonical(seed + 3000, 100.0)
            },
        },
        Row {
            name: "short pauses, +-35 % speed",
            make: |seed| SyntheticSettings {
                speed_variation: 0.35,
                pause_s: (0.08, 0.15),
                ..SyntheticSettings::canonical(seed + 4000, 100.0)
            },
        },
    ];
    for row in &rows {
        accuracy(&pattern, row, seeds)?;
    }
    rejections(&pattern, seeds)?;
    Ok(())
}

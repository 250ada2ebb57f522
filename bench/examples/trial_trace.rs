//! One trial of a Monte Carlo run, traced: where the suture is stretched, whether it passed through
//! itself, what the instruments' gauges read and what holds it, between two times of the skill:
//!
//! ```text
//! cargo run --release -p knotlab-bench --example trial_trace -- TRIAL FROM_S TO_S [PRESET] [METHOD] [SEED] [EVERY]
//! ```
//!
//! The trial draws what trial TRIAL of `knotlab mc --seed SEED [--preset PRESET] --method METHOD`
//! draws on the shipped scene (PRESET `-` for none; defaults: `workspace`, `fluid`, seed 1), so its
//! verdict is that run's. Every EVERY control cycles (1 ms each; default 10) from FROM_S to TO_S
//! seconds of the skill it prints one line: the time, the most stretched segment and its stretch
//! (the fraction beyond its rest length), the stretch of the segments around it, the segment pairs
//! the thread passed through itself at in the last step, the gauges (N), the particles the bodies
//! hold and the grips. At the end, the verdict and the first pass through itself.
//!
//! A run of segments stretched alike is tension; every other segment stretched (a sawtooth) is
//! particles pushed one by one by contacts after the lengths were solved: solver error, not pull.

use knotlab_bench::mc::drawn_trial;
use knotlab_hw::rig::ArmName;
use knotlab_learner::synthesis::Method;
use knotlab_scenarios::expert::RecordOptions;
use knotlab_scenarios::trial::run_trial;

#[path = "common/shared.rs"]
mod shared;

const NAME: &str = "trial_trace";

fn fail(message: String) -> ! {
    shared::fail(NAME, message)
}

fn arg<T: std::str::FromStr>(args: &[String], k: usize, what: &str, default: Option<T>) -> T {
    shared::arg(NAME, args, k, what, default)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let trial: u64 = arg(&args, 1, "TRIAL", None);
    let from_s: f64 = arg(&args, 2, "FROM_S", None);
    let to_s: f64 = arg(&args, 3, "TO_S", None);
    let preset: String = arg(&args, 4, "PRESET", Some("workspace".to_owned()));
    let method = match arg(&args, 5, "METHOD", Some("fluid".to_owned())).as_str() {
        "fluid" => Method::Fluid,
        "dmp" => Method::Dmp,
        "replay" => Method::Replay,
        other => fail(format!("argument 5 (METHOD): {other:?}: use fluid, dmp or replay")),
    };
    let seed: u64 = arg(&args, 6, "SEED", Some(1));
    let every: u64 = arg(&args, 7, "EVERY", Some(10));
    if every == 0 {
        fail("argument 7 (EVERY): must be at least 1".to_owned());
    }
    let (learned, scene) = shared::shipped_trial_inputs(NAME, &preset);
    let (setup, _) = drawn_trial(&scene, "default", seed, trial, method);
    let mut observer = |record: &knotlab_hw::controller::CycleRecord,
                        world: &knotlab_sim::world::SimWorld| {
        let t = record.skill_time_s;
        if t < from_s || t > to_s || !record.cycle.is_multiple_of(every) {
            return;
        }
        let suture = world.suture();
        let Some(rope) = suture.as_rope() else { return };
        let (x, spacing_m) = (&rope.ropes.x, rope.spacing_m);
        let stretch = |i: usize| (x[i + 1] - x[i]).norm() / spacing_m - 1.0;
        let Some(worst) = (0..x.len().saturating_sub(1)).max_by(|a, b| stretch(*a).total_cmp(&stretch(*b)))
        else {
            return;
        };
        let around: Vec<String> = (worst.saturating_sub(3)..(worst + 4).min(x.len() - 1))
            .map(|i| format!("{:.2}", stretch(i)))
            .collect();
        let held: Vec<String> = rope
            .contacts
            .attachments
            .iter()
            .map(|a| format!("{}@{}", suture.body_name(a.body).unwrap_or_default(), a.particle))
            .collect();
        let grips: Vec<String> = rope
            .contacts
            .grips
            .iter()
            .map(|g| {
                let name = suture.body_name(g.body).unwrap_or_default();
                format!("{name}:{:.1}N{}", g.limit_n, if g.sliding { " sliding" } else { "" })
            })
            .collect();
        let gauge = |arm| record.arm(arm).map_or(0.0, |a| a.world_force_n.norm());
        println!(
            "t {t:7.3} s  segment {worst:3} stretched {:.3} [{}]  passed through {:?}  gauges left {:.2} right {:.2} assist {:.2} N  held {held:?}  grips {grips:?}  inside {:?}",
            stretch(worst),
            around.join(" "),
            rope.ropes.crossed_last_step(),
            gauge(ArmName::Left),
            gauge(ArmName::Right),
            gauge(ArmName::Assist),
            suture.inside(),
        );
    };
    let options = RecordOptions { cycles_per_sample: 10, ..RecordOptions::default() };
    let run =
        run_trial(&learned, &setup, &options, Some(&mut observer)).unwrap_or_else(|e| fail(e.to_string()));
    println!(
        "trial {trial}: {:?}; first pass through itself {:?}",
        run.run.evaluation.verdict,
        run.run.self_crossings.first()
    );
}

//! Benchmark: one trocar-constrained IK call on the shipped rig (target: at most 1 microsecond).
//!
//! `cargo bench -p knotlab-bench --bench ik` prints, per arm and target kind, the median time of one
//! call: batches of calls over 1,000 seeded reachable targets, each batch timed whole, the median taken
//! over batches (robust to the odd preempted batch on a shared 2-core machine).

use std::hint::black_box;
use std::time::Instant;

use knotlab_hw::kinematics::{ArmJoints, ArmModel, TipOrientation, TipTarget, Tool, ToolJoints};
use knotlab_hw::rig::{ArmName, Rig};
use nalgebra::Vector3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

const TARGETS: usize = 1_000;
const BATCHES: usize = 301;

struct Case {
    target: TipTarget,
    trocar: Vector3<f64>,
    seed: ArmJoints,
}

fn cases(model: &ArmModel, name: ArmName, jaw_only: bool, rng: &mut ChaCha8Rng) -> Vec<Case> {
    let draw = |rng: &mut ChaCha8Rng, lo: f64, hi: f64| rng.random_range(lo..=hi);
    (0..TARGETS)
        .map(|_| {
            let arm_rad =
                std::array::from_fn(|i| draw(rng, model.limits[i].lower_rad, model.limits[i].upper_rad));
            let tool = match &model.tool {
                Tool::Instrument { limits, .. } => ToolJoints {
                    roll_rad: draw(rng, limits.roll.lower_rad, limits.roll.upper_rad),
                    pitch_rad: if jaw_only {
                        0.0
                    } else {
                        draw(rng, limits.pitch.lower_rad, limits.pitch.upper_rad)
                    },
                    yaw_rad: draw(rng, limits.yaw.lower_rad, limits.yaw.upper_rad),
                    jaw_rad: 0.0,
                },
                Tool::Endoscope { .. } => ToolJoints::default(),
            };
            let truth = ArmJoints { arm_rad, tool };
            let axis = model.shaft_axis(&truth);
            let shaft_m = match &model.tool {
                Tool::Instrument { geometry, .. } => geometry.shaft_m,
                Tool::Endoscope { geometry } => geometry.shaft_m,
            };
            let trocar = axis.origin_m + axis.direction * (shaft_m - draw(rng, 0.01, 0.2));
            let tip = model.world_from_tip(&truth);
            let orientation = if jaw_only {
                TipOrientation::JawDirection(tip.rotation * Vector3::z())
            } else {
                TipOrientation::Frame(tip.rotation)
            };
            Case {
                target: TipTarget { world_position_m: tip.translation.vector, orientation },
                trocar,
                seed: name.ready_joints(),
            }
        })
        .collect()
}

/// Median nanoseconds per call, and the 10th and 90th percentiles, over batches of all cases.
fn time(model: &ArmModel, cases: &[Case]) -> (f64, f64, f64, usize) {
    let mut solved = 0;
    for c in cases {
        solved += usize::from(model.solve_tip(&c.target, &c.trocar, &c.seed).is_ok());
    }
    let mut per_call_ns: Vec<f64> = (0..BATCHES)
        .map(|_| {
            let start = Instant::now();
            for c in cases {
                let _ = black_box(model.solve_tip(
                    black_box(&c.target),
                    black_box(&c.trocar),
                    black_box(&c.seed),
                ));
            }
            start.elapsed().as_nanos() as f64 / cases.len() as f64
        })
        .collect();
    per_call_ns.sort_by(f64::total_cmp);
    let at = |q: f64| per_call_ns[((per_call_ns.len() - 1) as f64 * q).round() as usize];
    (at(0.5), at(0.1), at(0.9), solved)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let rig = Rig::shipped()?;
    let mut rng = ChaCha8Rng::seed_from_u64(20_261_122);
    println!("trocar-constrained IK, {TARGETS} reachable targets per row, median over {BATCHES} batches");
    for name in ArmName::ALL {
        let model = rig.arm(name).model;
        let kinds: &[(&str, bool)] = if name.carries_instrument() {
            &[("tip frame", false), ("jaw direction", true)]
        } else {
            &[("tip position", true)]
        };
        for (kind, jaw_only) in kinds {
            let mut cs = cases(&model, name, *jaw_only, &mut rng);
            if !name.carries_instrument() {
                for c in &mut cs {
                    c.target.orientation = TipOrientation::AlongShaft;
                }
            }
            let (median, p10, p90, solved) = time(&model, &cs);
            println!(
                "ik {name:<6} {kind:<13}: median {:.3} us/call (p10 {:.3}, p90 {:.3}); {solved}/{TARGETS} solved",
                median / 1e3,
                p10 / 1e3,
                p90 / 1e3
            );
        }
    }
    Ok(())
}

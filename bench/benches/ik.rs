//! Benchmark: one trocar-constrained IK call on the shipped rig (target: at most 1 microsecond).
//!
//! `cargo bench -p knotlab-bench --bench ik` times `ArmModel::solve_tip`, per arm and target kind,
//! with divan: each call on the next of 1,000 seeded reachable targets.

use std::hint::black_box;

use knotlab_hw::kinematics::{ArmJoints, ArmModel, TipOrientation, TipTarget, Tool, ToolJoints};
use knotlab_hw::rig::{ArmName, Rig};
use nalgebra::Vector3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

const TARGETS: usize = 1_000;

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

fn main() {
    divan::main();
}

/// The arms and target kinds timed: the instruments' tip frame and jaw direction, the endoscope's
/// tip position.
const KINDS: [&str; 7] = [
    "left tip frame",
    "left jaw direction",
    "right tip frame",
    "right jaw direction",
    "assist tip frame",
    "assist jaw direction",
    "camera tip position",
];

/// One IK call on the next of the arm's targets.
#[divan::bench(args = KINDS)]
fn solve_tip(bencher: divan::Bencher, kind: &str) {
    let rig = Rig::shipped().expect("the shipped rig");
    let Some(name) = ArmName::ALL.into_iter().find(|a| kind.starts_with(&a.to_string())) else { return };
    let model = rig.arm(name).model;
    let mut rng = ChaCha8Rng::seed_from_u64(20_261_122);
    let mut cs = cases(&model, name, !kind.ends_with("tip frame"), &mut rng);
    if !name.carries_instrument() {
        for c in &mut cs {
            c.target.orientation = TipOrientation::AlongShaft;
        }
    }
    bencher.with_inputs(knotlab_bench::round_robin(cs.len())).bench_local_values(|i| {
        let c = &cs[i];
        model.solve_tip(black_box(&c.target), black_box(&c.trocar), black_box(&c.seed))
    });
}

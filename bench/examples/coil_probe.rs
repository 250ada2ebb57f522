//! How the long end's turns round the instruments' jaws come and go during the winding, for one
//! trial of a Monte Carlo run on the shipped scene:
//!
//! ```text
//! cargo run --release -p knotlab-bench --example coil_probe -- TRIAL FROM_S TO_S [PRESET] [SEED] [EVERY_MS]
//! ```
//!
//! The trial draws what trial TRIAL of `knotlab mc --seed SEED --preset PRESET --method fluid` draws on
//! the shipped scene (PRESET `-` for none; defaults: from 3 s to 16.5 s, `workspace`, seed 1). Every
//! EVERY_MS (250) ms of the skill it prints the long end's turns round the left's and the right's jaws, the
//! left's jaws' direction and how far it stands from the skill's target for them (degrees), and the
//! right's tip relative to the left's, in the stitch's frame (x along the wound, y across it, z up),
//! and each arm's tracking lag (its tip against the skill's target for it, mm). With
//! `COIL_PROBE_JOINTS` set in the environment it also prints the left's measured and commanded joints
//! (degrees) and whether the controller held a joint to its speed.

use knotlab_bench::mc::drawn_trial;
use knotlab_hw::kinematics::TipOrientation;
use knotlab_hw::rig::ArmName;
use knotlab_learner::synthesis::Method;
use knotlab_scenarios::expert::RecordOptions;
use knotlab_scenarios::expert::diagnose::long_end_turns_around_jaws;
use knotlab_scenarios::trial::run_trial;
use nalgebra::Vector3;

#[path = "common/shared.rs"]
mod shared;

const NAME: &str = "coil_probe";

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let arg = |k, what, default| shared::arg(NAME, &args, k, what, default);
    let trial: u64 = shared::arg(NAME, &args, 1, "TRIAL", None);
    let from_s: f64 = arg(2, "FROM_S", Some(3.0));
    let to_s: f64 = arg(3, "TO_S", Some(16.5));
    let preset: String = shared::arg(NAME, &args, 4, "PRESET", Some("workspace".to_owned()));
    let seed: u64 = shared::arg(NAME, &args, 5, "SEED", Some(1));
    let every_ms: u64 = shared::arg(NAME, &args, 6, "EVERY_MS", Some(250));
    let (learned, scene) = shared::shipped_trial_inputs(NAME, &preset);
    let (setup, _) = drawn_trial(&scene, "default", seed, trial, Method::Fluid);
    let mut observer = |record: &knotlab_hw::controller::CycleRecord,
                        world: &knotlab_sim::world::SimWorld| {
        let t = record.skill_time_s;
        if t < from_s || t > to_s || !record.cycle.is_multiple_of(every_ms.max(1)) {
            return;
        }
        let frame = world.tissue().world_from_tissue;
        let in_stitch = |v: Vector3<f64>| frame.inverse_transform_vector(&v);
        let turns = |arm| long_end_turns_around_jaws(world, arm).unwrap_or(f64::NAN);
        let left = world.world_from_tip(ArmName::Left);
        let right = world.world_from_tip(ArmName::Right);
        let jaws = left.rotation * Vector3::z();
        let target = record.arm(ArmName::Left).and_then(|a| a.target).and_then(|t| match t.orientation {
            TipOrientation::JawDirection(d) => Some(d.normalize()),
            TipOrientation::Frame(r) => Some(r * Vector3::z()),
            TipOrientation::AlongShaft => None,
        });
        let off_deg = target.map_or(f64::NAN, |d| d.angle(&jaws).to_degrees());
        let j = in_stitch(jaws);
        let r = in_stitch(right.translation.vector - left.translation.vector) * 1e3;
        let lag_mm = |arm| {
            record.arm(arm).and_then(|a| a.target).map_or(f64::NAN, |t| {
                (t.world_position_m - world.world_from_tip(arm).translation.vector).norm() * 1e3
            })
        };
        if std::env::var_os("COIL_PROBE_JOINTS").is_some()
            && let Some(a) = record.arm(ArmName::Left)
        {
            let deg = |v: [f64; 10]| v.map(|x| format!("{:7.1}", x.to_degrees())).join("");
            println!("  left measured {} clamped {}", deg(a.measured.to_array()), a.clamped);
            println!("  left commanded{}", deg(a.commanded.to_array()));
        }
        println!(
            "t {t:6.2} turns left {:5.2} right {:5.2} left jaws [{:5.2} {:5.2} {:5.2}] off target {off_deg:5.1} deg right - left (mm) [{:6.1} {:6.1} {:6.1}] lag (mm) left {:4.1} right {:4.1}",
            turns(ArmName::Left),
            turns(ArmName::Right),
            j.x,
            j.y,
            j.z,
            r.x,
            r.y,
            r.z,
            lag_mm(ArmName::Left),
            lag_mm(ArmName::Right)
        );
    };
    let options =
        RecordOptions { cycles_per_sample: 10, stop_after_s: Some(to_s + 0.1), ..RecordOptions::default() };
    run_trial(&learned, &setup, &options, Some(&mut observer))
        .unwrap_or_else(|e| shared::fail(NAME, e.to_string()));
}

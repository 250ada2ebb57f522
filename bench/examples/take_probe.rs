//! Where the tail lies against the left's jaws as they close on it (the take), for one trial of a
//! Monte Carlo run on the shipped scene:
//!
//! ```text
//! cargo run --release -p knotlab-bench --example take_probe -- TRIAL FROM_S TO_S [PRESET] [SEED]
//! ```
//!
//! The trial draws what trial TRIAL of `knotlab mc --seed SEED --preset PRESET --method fluid` draws on
//! the shipped scene (PRESET `-` for none; defaults: from 15 s to 16.5 s, `workspace`, seed 1). Every
//! 50 ms of the skill from FROM_S to TO_S it prints the left's jaw opening, the centre of its jaws, the
//! tail's particle nearest the jaws' line and its distance from it, that particle's offset from the
//! jaws' centre, and the directions of the jaws, their hinge and the thread there, all in the stitch's
//! frame (x along the wound, y across it, z up), m; every second of the skill, the tail's last 30
//! particles (every 4th, mm) and the assist's tip.

use knotlab_bench::mc::drawn_trial;
use knotlab_hw::rig::ArmName;
use knotlab_learner::synthesis::Method;
use knotlab_scenarios::expert::RecordOptions;
use knotlab_scenarios::trial::run_trial;
use knotlab_sim::grasp::{JAW_CENTRE_OFFSET_M, jaw_line_m};
use nalgebra::{Point3, Vector3};

#[path = "common/shared.rs"]
mod shared;

const NAME: &str = "take_probe";

fn fail(message: String) -> ! {
    shared::fail(NAME, message)
}

fn arg<T: std::str::FromStr>(args: &[String], k: usize, what: &str, default: Option<T>) -> T {
    shared::arg(NAME, args, k, what, default)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let trial: u64 = arg(&args, 1, "TRIAL", None);
    let from_s: f64 = arg(&args, 2, "FROM_S", Some(15.0));
    let to_s: f64 = arg(&args, 3, "TO_S", Some(16.5));
    let preset: String = arg(&args, 4, "PRESET", Some("workspace".to_owned()));
    let seed: u64 = arg(&args, 5, "SEED", Some(1));
    let (learned, scene) = shared::shipped_trial_inputs(NAME, &preset);
    let (setup, _) = drawn_trial(&scene, "default", seed, trial, Method::Fluid);
    let mut observer = |record: &knotlab_hw::controller::CycleRecord,
                        world: &knotlab_sim::world::SimWorld| {
        let t = record.skill_time_s;
        if t < from_s || t > to_s || !record.cycle.is_multiple_of(50) {
            return;
        }
        let Some(rope) = world.suture().as_rope() else { return };
        let x = &rope.ropes.x;
        let tip = world.world_from_tip(ArmName::Left);
        let (hinge, end) = jaw_line_m(&tip, JAW_CENTRE_OFFSET_M);
        let centre = 0.5 * (hinge + end);
        let tail = x.len() * 2 / 3..x.len();
        let (i, d) = tail
            .map(|i| (i, knotlab_hw::geometry::segment_distance(&x[i], &x[i], &hinge, &end)))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .expect("a tail");
        let frame = world.tissue().world_from_tissue;
        let off = frame.inverse_transform_vector(&(x[i] - centre));
        let jaw_dir = frame.inverse_transform_vector(&(end - hinge).normalize());
        let hinge_dir = frame.inverse_transform_vector(&(tip.rotation * Vector3::y()));
        let along = if i + 1 < x.len() {
            frame.inverse_transform_vector(&(x[i + 1] - x[i]).normalize())
        } else {
            Vector3::zeros()
        };
        let c = frame.inverse_transform_point(&Point3::from(centre));
        if record.cycle.is_multiple_of(1000) {
            let pts: Vec<String> = (x.len() - 30..x.len())
                .step_by(4)
                .map(|k| {
                    let p = frame.inverse_transform_point(&Point3::from(x[k]));
                    format!("{k}:[{:.1} {:.1} {:.1}]", p.x * 1e3, p.y * 1e3, p.z * 1e3)
                })
                .collect();
            let a = frame.inverse_transform_point(&Point3::from(
                world.world_from_tip(ArmName::Assist).translation.vector,
            ));
            println!(
                "  t {t:.1} tail (mm) {} assist tip [{:.1} {:.1} {:.1}]",
                pts.join(" "),
                a.x * 1e3,
                a.y * 1e3,
                a.z * 1e3
            );
        }
        println!(
            "t {t:6.2} jaw {:.2} centre [{:.4} {:.4} {:.4}] nearest {i} at {:.4} m, offset [{:.4} {:.4} {:.4}] jaws [{:.2} {:.2} {:.2}] hinge [{:.2} {:.2} {:.2}] thread [{:.2} {:.2} {:.2}]",
            world.arm(ArmName::Left).command.tool.jaw_rad,
            c.x,
            c.y,
            c.z,
            d,
            off.x,
            off.y,
            off.z,
            jaw_dir.x,
            jaw_dir.y,
            jaw_dir.z,
            hinge_dir.x,
            hinge_dir.y,
            hinge_dir.z,
            along.x,
            along.y,
            along.z
        );
    };
    let options =
        RecordOptions { cycles_per_sample: 10, stop_after_s: Some(to_s + 0.1), ..RecordOptions::default() };
    run_trial(&learned, &setup, &options, Some(&mut observer)).unwrap_or_else(|e| fail(e.to_string()));
}

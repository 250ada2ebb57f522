//! Benchmark: the shipped scene (four arms through their servos, the rope through the stitch, the
//! flaps on their slides, the needle, the grasps) stepping through the `knotlab sim` stress sequence,
//! on one core. Target: faster than real time (a step of 1 ms in under 1 ms).
//!
//! `cargo bench -p knotlab-bench --bench scene_step` times the sequence played over one simulated
//! second (1,000 steps) with divan, counted per step; again in `scenarios/real-diameter.toml`, the
//! suture at its real diameter in its knots (0.225 mm, its particles 0.34 mm apart), its bending
//! solved a strand at once and its lengths, joints and contacts passed over four times a substep, the
//! rope `knotlab validate` passes 31 of 36 checks on. Found: 0.47 s for the shipped scene's second,
//! 4.9 s at the real diameter.
//! (How the chain's and the solver's discretisation trade speed for stretch and tunnelling:
//! `cargo bench -p knotlab-lab --bench scene`.)

use knotlab_hw::rig::Rig;
use knotlab_scenarios::stress::run_stress;
use knotlab_sim::world::SimWorld;

fn main() {
    divan::main();
}

/// The stress sequence over one second, from the task's start condition.
#[divan::bench(sample_count = 5, sample_size = 1)]
fn stress_sequence_in_one_second(bencher: divan::Bencher) {
    stress_second(bencher, knotlab_bench::shipped_scene());
}

/// The same in `scenarios/real-diameter.toml`: the suture at its real diameter in its knots, in four
/// passes.
#[divan::bench(sample_count = 5, sample_size = 1)]
fn stress_sequence_in_one_second_at_the_real_diameter(bencher: divan::Bencher) {
    let scene = knotlab_bench::scene_or_exit(
        include_str!("../../scenarios/real-diameter.toml"),
        "scenarios/real-diameter.toml",
    );
    stress_second(bencher, scene);
}

/// Times the stress sequence over one second in `scene`.
fn stress_second(bencher: divan::Bencher, scene: knotlab_sim::scene::SceneConfig) {
    let rig = Rig::shipped().expect("the shipped rig");
    let steps = (1.0 / scene.solver.dt_s).round() as usize;
    bencher
        .counter(divan::counter::ItemsCount::new(steps))
        .with_inputs(|| SimWorld::new(scene.clone(), rig.clone()).expect("the shipped scene builds"))
        .bench_local_values(|mut world| {
            let report = run_stress(&mut world, 1.0, &[], &mut |_, _| {});
            assert!(report.failure.is_none(), "a healthy second: {:?}", report.failure);
            world
        });
}

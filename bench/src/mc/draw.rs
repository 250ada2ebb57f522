//! One trial's draw: from the run's seed and the trial's index alone (a ChaCha stream per trial), so a
//! trial is the same whatever the number of jobs or shards. The scene's `[randomization]` says what is
//! drawn; every draw is uniform within its bounds.

use knotlab_scenarios::trial::StitchMove;
use knotlab_sim::scene::SceneConfig;
use nalgebra::Vector3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::Serialize;

/// What a trial drew.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Draw {
    /// The stitch's shift, m.
    pub stitch_offset_m: [f64; 3],
    /// The stitch's turn, rad.
    pub stitch_rotate_rad: f64,
    /// Backlash of every arm joint, rad.
    pub play_rad: f64,
    /// The largest calibration offset drawn over the arms' joints, rad.
    pub calibration_max_rad: f64,
    /// The thread's friction.
    pub thread_friction: f64,
    /// The thread's bending stiffness, N m/rad.
    pub thread_bend_stiffness: f64,
    /// The strain gauges' noise, N.
    pub force_noise_n: f64,
    /// The seed of the trial's own random draws in the simulation (sensor noise).
    pub sim_seed: u64,
}

fn uniform(rng: &mut ChaCha8Rng, [lo, hi]: [f64; 2]) -> f64 {
    if hi > lo { rng.random_range(lo..=hi) } else { lo }
}

/// The trial's own generator: the run's seed and the trial's index, nothing else.
pub fn trial_rng(seed: u64, trial: u64) -> ChaCha8Rng {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(trial);
    rng
}

/// Draws trial `trial` of the run `seed` on `scene`: the scene changed by the draw, the stitch move, and
/// what was drawn.
pub fn draw(scene: &SceneConfig, seed: u64, trial: u64) -> (SceneConfig, StitchMove, Draw) {
    let r = scene.randomization;
    let mut rng = trial_rng(seed, trial);
    let offset =
        [uniform(&mut rng, r.stitch_x_m), uniform(&mut rng, r.stitch_y_m), uniform(&mut rng, r.stitch_z_m)];
    let rotate = uniform(&mut rng, r.stitch_rotate_rad);
    let play = uniform(&mut rng, r.play_rad);
    let mut out = scene.clone();
    let mut calibration_max: f64 = 0.0;
    let o = &mut out.servo.calibration_offset_rad;
    for joints in [&mut o.left, &mut o.right, &mut o.assist] {
        for q in joints.iter_mut() {
            let c = uniform(&mut rng, r.calibration_rad);
            *q += c;
            calibration_max = calibration_max.max(c.abs());
        }
    }
    let friction = uniform(&mut rng, r.thread_friction);
    let stiffness = uniform(&mut rng, r.thread_bend_stiffness);
    let noise = uniform(&mut rng, r.force_noise_n);
    let sim_seed = rng.random();
    let drawn =
        |value: f64, [lo, hi]: [f64; 2], nominal: f64| if hi > lo || lo != 0.0 { value } else { nominal };
    out.servo.play_rad = drawn(play, r.play_rad, scene.servo.play_rad);
    out.thread.friction = drawn(friction, r.thread_friction, scene.thread.friction);
    out.thread.bend_stiffness_n_m_per_rad =
        drawn(stiffness, r.thread_bend_stiffness, scene.thread.bend_stiffness_n_m_per_rad);
    out.sensor.force_noise_n = drawn(noise, r.force_noise_n, scene.sensor.force_noise_n);
    let stitch = StitchMove { offset_m: Vector3::from(offset), rotate_rad: rotate };
    let d = Draw {
        stitch_offset_m: offset,
        stitch_rotate_rad: rotate,
        play_rad: out.servo.play_rad,
        calibration_max_rad: calibration_max,
        thread_friction: out.thread.friction,
        thread_bend_stiffness: out.thread.bend_stiffness_n_m_per_rad,
        force_noise_n: out.sensor.force_noise_n,
        sim_seed,
    };
    (out, stitch, d)
}

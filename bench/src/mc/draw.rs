//! One trial's draw: from the run's seed and the trial's index alone (a ChaCha stream per trial), so a
//! trial is the same whatever the number of jobs or shards. The scene's `[randomization]` says what is
//! drawn; every draw is uniform within its bounds (an obstacle's presence is a coin of its probability).

use knotlab_scenarios::trial::StitchMove;
use knotlab_sim::scene::{Obstacle, SceneConfig};
use knotlab_sim::tissue::Tissue;
use nalgebra::{Point3, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::Serialize;

/// What a trial drew.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Draw {
    /// The stitch's shift, m.
    pub stitch_offset_m: [f64; 3],
    /// The stitch's turn, rad.
    pub stitch_rotate_rad: f64,
    /// The tissue's tilt about the wound, rad (added to the scene's).
    pub stitch_tilt_rad: f64,
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
    /// The boxes of `[[randomization.obstacle]]` the trial placed (world frame), in the scene's
    /// `obstacles` after its own.
    pub obstacles: Vec<Obstacle>,
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
    let r = &scene.randomization;
    let mut rng = trial_rng(seed, trial);
    let offset =
        [uniform(&mut rng, r.stitch_x_m), uniform(&mut rng, r.stitch_y_m), uniform(&mut rng, r.stitch_z_m)];
    let rotate = uniform(&mut rng, r.stitch_rotate_rad);
    // Nothing drawn for a tilt of one value: a scene without tilt draws what it drew before.
    let tilt = uniform(&mut rng, r.stitch_tilt_rad);
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
    // Obstacles last, so that a scene without them draws what it drew before they existed.
    let stitch = StitchMove { offset_m: Vector3::from(offset), rotate_rad: rotate, tilt_rad: tilt };
    let mut moved = scene.clone();
    stitch.apply(&mut moved);
    let world_from_tissue = Tissue::frame(&moved.tissue);
    let mut obstacles = Vec::new();
    for o in &r.obstacles {
        let present = rng.random_bool(o.probability.clamp(0.0, 1.0));
        let at = o.offset_m.map(|b| uniform(&mut rng, b));
        let half = o.half_extents_m.map(|b| uniform(&mut rng, b));
        if present {
            let centre = world_from_tissue * Point3::from(Vector3::from(at));
            obstacles.push(Obstacle { centre_m: centre.coords.into(), half_extents_m: half });
        }
    }
    let drawn =
        |value: f64, [lo, hi]: [f64; 2], nominal: f64| if hi > lo || lo != 0.0 { value } else { nominal };
    out.servo.play_rad = drawn(play, r.play_rad, scene.servo.play_rad);
    out.thread.friction = drawn(friction, r.thread_friction, scene.thread.friction);
    out.thread.bend_stiffness_n_m_per_rad =
        drawn(stiffness, r.thread_bend_stiffness, scene.thread.bend_stiffness_n_m_per_rad);
    out.sensor.force_noise_n = drawn(noise, r.force_noise_n, scene.sensor.force_noise_n);
    out.obstacles.extend(obstacles.iter().copied());
    let d = Draw {
        stitch_offset_m: offset,
        stitch_rotate_rad: rotate,
        stitch_tilt_rad: tilt,
        play_rad: out.servo.play_rad,
        calibration_max_rad: calibration_max,
        thread_friction: out.thread.friction,
        thread_bend_stiffness: out.thread.bend_stiffness_n_m_per_rad,
        force_noise_n: out.sensor.force_noise_n,
        sim_seed,
        obstacles,
    };
    (out, stitch, d)
}

#[cfg(test)]
mod tests {
    use super::*;
    use knotlab_sim::scene::{RandomObstacle, parse_scene};

    fn scene() -> SceneConfig {
        parse_scene(include_str!("../../../scenarios/default.toml"), "default.toml")
            .expect("the default scene")
    }

    /// Adding random obstacles to a scene shifts none of a trial's other draws; a sure obstacle lands within
    /// its bounds in the moved tissue frame and an impossible one never appears.
    #[test]
    fn obstacles_are_placed_near_the_drawn_stitch_and_change_nothing_else() {
        let plain = scene();
        let mut with = plain.clone();
        let sure = RandomObstacle {
            probability: 1.0,
            offset_m: [[0.02, 0.03], [-0.01, 0.01], [0.0, 0.005]],
            half_extents_m: [[0.004, 0.006], [0.004, 0.006], [0.01, 0.01]],
        };
        with.randomization.obstacles = vec![sure, RandomObstacle { probability: 0.0, ..sure }];
        for trial in 0..20 {
            let (s0, m0, d0) = draw(&plain, 3, trial);
            let (s1, m1, d1) = draw(&with, 3, trial);
            // What was drawn before obstacles existed is drawn alike.
            assert_eq!((m0, d0.sim_seed, d0.play_rad), (m1, d1.sim_seed, d1.play_rad));
            assert!(d0.obstacles.is_empty() && s0.obstacles.len() == plain.obstacles.len());
            // The sure one is there, the impossible one is not.
            assert_eq!(d1.obstacles.len(), 1);
            assert_eq!(s1.obstacles.len(), plain.obstacles.len() + 1);
            let o = d1.obstacles[0];
            // In the moved tissue frame, its centre is within the bounds.
            let mut moved = plain.clone();
            m1.apply(&mut moved);
            let tissue = Tissue::frame(&moved.tissue);
            let local = tissue.inverse() * Point3::from(Vector3::from(o.centre_m));
            for (axis, [lo, hi]) in sure.offset_m.iter().enumerate() {
                assert!(local[axis] >= lo - 1e-12 && local[axis] <= hi + 1e-12, "{local:?}");
                let [lo, hi] = sure.half_extents_m[axis];
                assert!((lo..=hi).contains(&o.half_extents_m[axis]));
            }
        }
    }
}

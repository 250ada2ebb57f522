//! Benchmark: the suture's trade-off between stiffness and speed. For each discretisation (segments,
//! solver iterations, Gauss-Seidel sweeps) a 0.25 m thread is held at one end and pulled with 2 N at
//! the other for 1 s of simulated time (dt 1 ms); printed: the worst joint gap over the last half second
//! as a fraction of a segment, milliseconds per step and the real-time factor, on one core.
//!
//! `cargo bench -p knotlab-lab --bench thread`

use std::time::Instant;

use knotlab_sim::physics::{Physics, SolverParams};
use knotlab_sim::thread::{Thread, ThreadParams};
use nalgebra::Vector3;
use rapier3d::prelude::*;

fn measure(segments: usize, iterations: usize, sweeps: usize) -> Result<(f64, f64), String> {
    let solver = SolverParams {
        solver_iterations: iterations,
        pgs_iterations_per_substep: sweeps,
        ..Default::default()
    };
    let mut physics = Physics::new(&solver);
    let params = ThreadParams { segments, ..Default::default() };
    let thread = Thread::build(&mut physics, &params, &Vector3::new(0.0, 0.0, 1.0), &Vector3::x());
    let half = 0.5 * thread.segment_length_m;
    let anchor = physics.bodies.insert(RigidBodyBuilder::fixed().translation(Vector::new(0.0, 0.0, 1.0)));
    physics.impulse_joints.insert(
        anchor,
        thread.segments[0],
        SphericalJointBuilder::new().local_anchor2(Vector::new(-half, 0.0, 0.0)),
        true,
    );
    let tail = *thread.segments.last().ok_or("no segments")?;
    physics.bodies[tail].add_force(Vector::new(2.0, 0.0, 0.0), true);
    let steps = 1000;
    let mut worst: f64 = 0.0;
    let start = Instant::now();
    for step in 0..steps {
        physics.step(&|_| "segment".to_owned()).map_err(|e| e.to_string())?;
        if step >= steps / 2 {
            worst = worst.max(thread.max_stretch_ratio(&physics));
        }
    }
    Ok((worst, start.elapsed().as_secs_f64() * 1e3 / steps as f64))
}

fn main() {
    println!(
        "thread 0.25 m pulled with 2 N, dt 1 ms: segments, iterations x sweeps -> stretch, ms/step, real time"
    );
    for segments in [40, 60, 80, 100] {
        for (iterations, sweeps) in [(4, 4), (8, 1), (8, 4), (16, 1), (16, 4)] {
            match measure(segments, iterations, sweeps) {
                Ok((stretch, ms)) => println!(
                    "thread {segments:>3} segments, {iterations:>2} x {sweeps}: stretch {:>6.2} %, {ms:.3} ms/step, {:.2}x real time",
                    stretch * 100.0,
                    1.0 / ms
                ),
                Err(e) => {
                    println!("thread {segments:>3} segments, {iterations:>2} x {sweeps}: unstable ({e})")
                }
            }
        }
    }
}

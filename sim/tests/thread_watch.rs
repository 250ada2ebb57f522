//! The thread watch counts a strand passing through another strand of the same thread, and nothing
//! when the thread merely lies crossed over itself.

use knotlab_sim::physics::{Physics, SolverParams};
use knotlab_sim::thread::{Thread, ThreadParams};
use knotlab_sim::thread_watch::ThreadWatch;
use nalgebra::Vector3;
use rapier3d::prelude::Vector;

/// A weightless thread laid in a hook whose last leg crosses its first one `height_m` above it, in
/// the middle of a segment.
fn lay_crossed(physics: &mut Physics, thread: &Thread, height_m: f64) {
    let h = height_m;
    let polyline = [
        Vector3::new(0.0, 0.0, 0.0),
        Vector3::new(0.05, 0.0, 0.0),
        Vector3::new(0.05, 0.02, h),
        Vector3::new(0.028, 0.02, h),
        Vector3::new(0.028, -0.03, h),
    ];
    thread.lay_along(physics, &polyline);
}

fn setup() -> (Physics, Thread, ThreadWatch) {
    let solver = SolverParams::default();
    let mut physics = Physics::new(&solver);
    physics.gravity = Vector::ZERO;
    let params = ThreadParams::default();
    let thread = Thread::build(&mut physics, &params, &Vector3::zeros(), &Vector3::x());
    let watch = ThreadWatch::new(&physics, &thread, solver.prediction_distance_m);
    (physics, thread, watch)
}

fn step(physics: &mut Physics, thread: &Thread, watch: &mut ThreadWatch, steps: usize) {
    let radius_m = ThreadParams::default().radius_m;
    for _ in 0..steps {
        physics.step(&|_| String::new()).expect("a healthy step");
        let t = physics.step_count as f64 * physics.dt_s();
        watch.update(physics, thread, radius_m, t);
    }
}

#[test]
fn a_strand_lying_across_another_is_no_crossing() {
    let (mut physics, thread, mut watch) = setup();
    lay_crossed(&mut physics, &thread, 0.0012);
    step(&mut physics, &thread, &mut watch, 50);
    assert!(watch.crossings.is_empty(), "{:?}", watch.crossings);
}

#[test]
fn a_strand_moved_through_another_is_a_crossing() {
    let (mut physics, thread, mut watch) = setup();
    lay_crossed(&mut physics, &thread, 0.0012);
    step(&mut physics, &thread, &mut watch, 5);
    // The last leg jumps from above the first to below it, as a strand tunnelling in one step.
    lay_crossed(&mut physics, &thread, -0.0012);
    step(&mut physics, &thread, &mut watch, 5);
    assert!(!watch.crossings.is_empty(), "the pass went unseen");
    let (i, j) = watch.crossings[0].segments;
    let n = thread.segments.len();
    // The crossing is between the first leg and the last one.
    let first_leg = (0.05 / 0.25 * n as f64) as usize;
    assert!(i <= first_leg && j > first_leg + 2, "segments {i} and {j}");
    println!("{:?}", watch.crossings);
}

//! The thread watch counts a strand passing through another strand of the same thread, and nothing
//! when the thread merely lies crossed over itself: for the capsule chain and for the rope.

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
    let watch = ThreadWatch::new(&thread);
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

/// A strand lying crossed 1.2 mm above another for 50 steps counts no crossing.
#[test]
fn a_strand_lying_across_another_is_no_crossing() {
    let (mut physics, thread, mut watch) = setup();
    lay_crossed(&mut physics, &thread, 0.0012);
    step(&mut physics, &thread, &mut watch, 50);
    assert!(watch.crossings.is_empty(), "{:?}", watch.crossings);
}

/// A strand jumping from above another to below it in one step counts as a crossing between those two legs.
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

/// Guards the chain's watch against missing a strand driven through another by velocity (not laid
/// there): the first leg held where it lies, the last leg, 2.5 mm above it (beyond the solver's
/// prediction distance, so no contact is foreseen), is driven down at 10 m/s, 10 mm in a step.
/// (At 1-5 m/s the chain's contacts stop it, or it pushes the first leg along ahead of it.)
#[test]
fn a_chain_strand_driven_through_another_is_a_crossing() {
    let (mut physics, thread, mut watch) = setup();
    // As `lay_crossed`, the legs placed so that the last crosses the first in its fifth segment.
    let (h, x, y) = (0.0025, 0.028125, 0.01875);
    let polyline = [
        Vector3::new(0.0, 0.0, 0.0),
        Vector3::new(0.05, 0.0, 0.0),
        Vector3::new(0.05, y, h),
        Vector3::new(x, y, h),
        Vector3::new(x, -0.03, h),
    ];
    thread.lay_along(&mut physics, &polyline);
    step(&mut physics, &thread, &mut watch, 5);
    assert!(watch.crossings.is_empty(), "crossed before it was driven: {:?}", watch.crossings);
    for k in 0..8 {
        physics.bodies[thread.segments[k]].set_body_type(rapier3d::prelude::RigidBodyType::Fixed, true);
    }
    // The last leg, from where it turns down to 0.03 m beyond the crossing.
    let n = thread.segments.len() as f64;
    let turn_m = 0.05 + 2.0 * y + (0.05 - x) - y;
    let last_leg = (turn_m / 0.25 * n).ceil() as usize..((turn_m + y + 0.03) / 0.25 * n) as usize;
    for k in last_leg.clone() {
        physics.bodies[thread.segments[k]].set_linvel(Vector::new(0.0, 0.0, -10.0), true);
    }
    step(&mut physics, &thread, &mut watch, 2);
    assert_eq!(watch.crossings.len(), 1, "{:?}", watch.crossings);
    let (i, j) = watch.crossings[0].segments;
    assert!(i == 4 && last_leg.contains(&j), "segments {i} and {j}");
}

mod rope {
    //! The rope's own watch ([`knotlab_sim::rope::Ropes::crossed_last_step`]).

    use knotlab_sim::rope::{RopeParams, Ropes};
    use nalgebra::Vector3;

    /// A 20 mm strand along x at z = 0 (its ends pinned when `pinned`) and a 20 mm strand along y
    /// `height_m` above it, held (weightless, moved by hand) and carried down through the first at
    /// `speed_mps` for `steps` steps of 1 ms. Returns every pass counted, with its step.
    fn carried_through(
        pinned: bool,
        height_m: f64,
        speed_mps: f64,
        steps: usize,
    ) -> Vec<(usize, (usize, usize))> {
        let mut ropes = Ropes::new(RopeParams { substeps: 3, ..RopeParams::default() });
        let along_x =
            ropes.add_strand_along(&[Vector3::new(-0.01, 0.0, 0.0), Vector3::new(0.01, 0.0, 0.0)], 0.0006);
        if pinned {
            ropes.w[along_x.start] = 0.0;
            ropes.w[along_x.end - 1] = 0.0;
        }
        let carried = ropes.add_strand_along(
            &[Vector3::new(0.0, -0.01, height_m), Vector3::new(0.0, 0.01, height_m)],
            0.0006,
        );
        for p in carried.clone() {
            ropes.w[p] = 0.0;
        }
        let mut passes = Vec::new();
        // A step at rest first: the watch starts from where the rope lies after a step.
        ropes.step(0.001);
        for step in 0..steps {
            for p in carried.clone() {
                ropes.x[p].z -= speed_mps * 0.001;
            }
            ropes.step(0.001);
            passes.extend(ropes.crossed_last_step().iter().map(|&pair| (step, pair)));
        }
        passes
    }

    /// Guards the rope's watch against missing a pass: a held strand carried at 2 m/s (2 mm a step,
    /// five radii) through a taut one is one crossing, between the two strands' middle segments.
    #[test]
    fn a_rope_strand_driven_through_another_is_a_crossing() {
        let passes = carried_through(true, 0.0012, 2.0, 3);
        assert_eq!(passes.len(), 1, "{passes:?}");
        let (_, (i, j)) = passes[0];
        // 33 segments along x (0..33), then 33 along y (33..66): the middle of each.
        assert!((14..19).contains(&i) && (47..52).contains(&j), "segments {i} and {j}");
    }

    /// Guards the rope's watch against counting what is no pass: the same strand, free, pushed along
    /// ahead of the carried one at 5 cm/s, and a strand lying across another, count nothing.
    #[test]
    fn a_rope_strand_pushed_ahead_or_lying_across_is_no_crossing() {
        let pushed = carried_through(false, 0.0012, 0.05, 200);
        assert!(pushed.is_empty(), "pushed ahead: {pushed:?}");
        let lying = carried_through(true, 0.0004, 0.0, 100);
        assert!(lying.is_empty(), "lying across: {lying:?}");
    }
}

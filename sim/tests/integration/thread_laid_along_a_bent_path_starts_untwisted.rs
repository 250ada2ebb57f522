//! Regression: a thread laid along a path that bends out of one plane started twisted. Each segment
//! was turned from the x axis by its own smallest turn, so neighbours differed by a twist about the
//! thread's axis (up to 2.3 rad in the shipped scene's start layout) that the twist-locked joints
//! snapped straight in the first steps, throwing the thread about: a square knot laid loose passed
//! through itself before anything pulled on it. Segments are now laid by parallel transport.

use crate::common::chain;
use knotlab_hw::rig::Rig;
use knotlab_sim::physics::{Physics, SolverParams};
use knotlab_sim::scene::parse_scene;
use knotlab_sim::thread::{Thread, ThreadParams};
use knotlab_sim::world::SimWorld;
use nalgebra::Vector3;
use rapier3d::prelude::*;

/// The twist about the thread's axis between each pair of neighbours, rad.
fn twists(physics: &Physics, thread: &Thread) -> Vec<f64> {
    thread
        .segments
        .windows(2)
        .map(|pair| {
            let q = physics.bodies[pair[0]].rotation().inverse() * *physics.bodies[pair[1]].rotation();
            let twist = 2.0 * q.x.atan2(q.w);
            (twist + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU) - std::f64::consts::PI
        })
        .collect()
}

/// The shipped chain scene's start layout leaves no twist between neighbouring thread segments.
#[test]
fn the_shipped_start_layout_has_no_twist_between_neighbours() {
    let scene =
        parse_scene(include_str!("../../../scenarios/chain.toml"), "chain.toml").expect("the shipped scene");
    let world = SimWorld::new(scene, Rig::shipped().expect("the shipped rig")).expect("the scene builds");
    let worst = twists(world.physics(), chain(world.suture()).thread())
        .into_iter()
        .fold(0.0, |m: f64, t| m.max(t.abs()));
    assert!(worst < 1e-6, "neighbours twisted by up to {worst} rad");
}

/// A twist-locked strand laid round square corners in three planes moves under 0.1 mm in 20 ms instead of
/// being thrown about.
#[test]
fn a_strand_laid_round_corners_in_space_lies_still() {
    let params = ThreadParams { twist_free: false, ..ThreadParams::default() };
    let mut physics = Physics::new(&SolverParams::default());
    physics.gravity = Vector::ZERO;
    let thread = Thread::build(&mut physics, &params, &Vector3::zeros(), &Vector3::x());
    // Square corners turning in three planes in turn, as a loose knot's strands do.
    let u = 0.012;
    let path: Vec<Vector3<f64>> = [
        (0.0, 0.0, 0.0),
        (2.0, 0.0, 0.0),
        (2.0, 1.0, 0.0),
        (2.0, 1.0, 1.0),
        (1.0, 1.0, 1.0),
        (1.0, 2.0, 1.0),
        (1.0, 2.0, -1.0),
        (3.0, 2.0, -1.0),
        (3.0, 0.0, -1.0),
        (6.0, 0.0, -1.0),
    ]
    .iter()
    .map(|&(x, y, z)| Vector3::new(x, y, z) * u)
    .collect();
    thread.lay_along(&mut physics, &path);
    let laid = thread.centreline(&physics);
    for _ in 0..20 {
        physics.step(&|_| "thread segment".to_owned()).expect("a healthy step");
    }
    // Only the bending springs pull at the corners: in 20 ms they move it by a few micrometres. A
    // twisted layout snapping straight threw it about by millimetres.
    let moved = laid.iter().zip(thread.centreline(&physics)).map(|(a, b)| (a - b).norm()).fold(0.0, f64::max);
    assert!(moved < 1e-4, "the strand moved {moved} m in 20 ms");
}

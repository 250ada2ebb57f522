//! The tissue and the stitch: the elastic load holds the wound open and yields to a pull as its
//! stiffness says; (e) the thread slides through the stitch when pulled, and friction holds a pull
//! below it; the start condition holds the needle in the right jaws and the tail in the assist's.

use crate::common::chain;
use knotlab_hw::rig::{ArmName, Rig};
use knotlab_sim::scene::parse_scene;
use knotlab_sim::tissue::Flap;
use knotlab_sim::world::SimWorld;
use rapier3d::prelude::*;

fn world() -> SimWorld {
    let scene =
        parse_scene(include_str!("../../../scenarios/chain.toml"), "chain.toml").expect("shipped scene");
    SimWorld::new(scene, Rig::shipped().expect("shipped rig")).expect("the shipped scene builds")
}

fn run(w: &mut SimWorld, steps: usize) {
    for _ in 0..steps {
        w.step().expect("healthy step");
    }
}

/// The start condition holds the needle in the right's jaws and the tail in the assist's, the thread through
/// both flaps unstretched and the wound near its rest gap.
#[test]
fn the_start_condition_holds_needle_and_tail_through_the_stitch() {
    let mut w = world();
    run(&mut w, 300);
    assert_eq!(w.arm(ArmName::Right).held_at(), Some(0), "the right jaws hold the needle");
    // The assist's jaws hold the tail within its last centimetre (the segment between the jaws' middle).
    let last = chain(w.suture()).thread().segments.len() - 1;
    let last_cm = (0.01 / chain(w.suture()).thread().segment_length_m).ceil() as usize;
    let held = w.arm(ArmName::Assist).held_at().expect("the assist holds the thread");
    assert!(held + last_cm > last, "the assist holds segment {held} of {}, not the tail", last + 1);
    let [exit, entry] =
        chain(w.suture()).stitch().holes.map(|h| h.segment.expect("the thread is in both flaps"));
    assert!(exit < entry, "the needle end meets the exit first: {exit} {entry}");
    assert!(chain(w.suture()).thread().max_stretch_ratio(w.physics()) < 0.02);
    // The suture runs under the wound in a U: the thread's weight (0.01 kg, far heavier than a real
    // suture, for the solver) hanging from the jaws pulls the U, and with it the wound, a little
    // closed; never open.
    let closed_by = w.config().tissue.rest_gap_m - w.wound_gap_m();
    assert!((-5e-4..1.2e-3).contains(&closed_by), "closed by {closed_by} m");
}

/// A tissue tilted about the wound lies on its slope and stays where it lies: its normal is the upright
/// turned by the tilt about the wound, and its flaps keep their places (the body beneath carries
/// their weight along the slope; on the wound's load alone they would slide down it by m g sin(tilt)
/// / k, 2.4 mm at 0.25 rad, and the upper one would meet the wound's centre line), the gap at rest.
#[test]
fn a_tilted_tissue_lies_on_its_slope_its_flaps_where_they_were_laid() {
    let tilt_rad = 0.25;
    let mut scene =
        parse_scene(include_str!("../../../scenarios/chain.toml"), "chain.toml").expect("shipped scene");
    scene.tissue.tilt_rad = tilt_rad;
    let mut w = SimWorld::new(scene, Rig::shipped().expect("shipped rig")).expect("the tilted scene builds");
    let normal = w.tissue().normal();
    let expected_normal = nalgebra::Vector3::new(0.0, -tilt_rad.sin(), tilt_rad.cos());
    assert!((normal - expected_normal).norm() < 1e-12, "normal {normal:?}");
    w.free_thread();
    let far = w.tissue().world_from_tissue.translation.vector + nalgebra::Vector3::new(0.0, 0.0, 0.5);
    let (suture, physics) = w.suture_and_physics_mut();
    chain(suture).thread().lay_straight(physics, &far, &nalgebra::Vector3::x());
    // Where each flap sits along the slope (the tissue frame's y).
    let along_slope = |w: &SimWorld| {
        let tissue_from_world = w.tissue().world_from_tissue.inverse();
        [Flap::A, Flap::B].map(|flap| {
            let t = w.physics().bodies[w.tissue().flap(flap)].translation();
            (tissue_from_world * nalgebra::Point3::new(t.x, t.y, t.z)).y
        })
    };
    let start = along_slope(&w);
    run(&mut w, 3000);
    let end = along_slope(&w);
    for k in 0..2 {
        assert!((end[k] - start[k]).abs() < 1e-4, "flap {k} moved {} m along the slope", end[k] - start[k]);
    }
    let rest = w.config().tissue.rest_gap_m;
    assert!((w.wound_gap_m() - rest).abs() < 1e-4, "gap {}", w.wound_gap_m());
}

/// The wound's elastic load closes by the push over its stiffness within 15 % and reopens to its rest gap
/// once the push stops.
#[test]
fn the_elastic_load_yields_to_a_pull_by_its_stiffness_and_reopens() {
    let mut w = world();
    w.free_thread();
    // The thread out of the way, floating: only the load acts on the flaps.
    w.physics_mut().gravity = Vector::ZERO;
    let far = w.tissue().world_from_tissue.translation.vector + nalgebra::Vector3::new(0.0, 0.0, 0.5);
    let (suture, physics) = w.suture_and_physics_mut();
    chain(suture).thread().lay_straight(physics, &far, &nalgebra::Vector3::x());
    run(&mut w, 200);
    let rest = w.wound_gap_m();
    assert!((rest - w.config().tissue.rest_gap_m).abs() < 1e-4, "rest gap {rest}");
    // Push flap A towards B with 0.04 N: the gap closes by F / k (k = 20 N/m: 2 mm).
    let push_n = 0.04;
    let towards_b = w.tissue().world_from_tissue.rotation * nalgebra::Vector3::new(0.0, -push_n, 0.0);
    let flap = w.tissue().flap(Flap::A);
    w.physics_mut().bodies[flap].add_force(Vector::new(towards_b.x, towards_b.y, towards_b.z), true);
    run(&mut w, 1500);
    let pushed = w.wound_gap_m();
    let expected = push_n / w.config().tissue.opening_stiffness_n_per_m;
    println!(
        "rest gap {:.3} mm, pushed {:.3} mm, expected closing {:.3} mm",
        rest * 1e3,
        pushed * 1e3,
        expected * 1e3
    );
    assert!(((rest - pushed) - expected).abs() < 0.15 * expected, "closed by {} m", rest - pushed);
    w.physics_mut().bodies[flap].reset_forces(true);
    run(&mut w, 1500);
    assert!((w.wound_gap_m() - rest).abs() < 2e-4, "reopened to {}", w.wound_gap_m());
}

/// Lets go of both ends, then pulls the tail's end away from the wound with `force_n` for `steps`;
/// returns how far the thread slid through (needle side shortened), m, and the segments at the points.
fn pull_tail(force_n: f64, steps: usize) -> (f64, [Option<usize>; 2], [Option<usize>; 2]) {
    let mut w = world();
    for arm in [ArmName::Right, ArmName::Assist] {
        let mut open = w.arm(arm).command;
        open.tool.jaw_rad = SimWorld::JAW_OPEN_RAD;
        w.command(arm, open);
    }
    run(&mut w, 300);
    let before = chain(w.suture())
        .stitch()
        .needle_side_length_m(w.physics(), chain(w.suture()).thread(), w.tissue())
        .expect("stitched");
    let holes_before = chain(w.suture()).stitch().holes.map(|h| h.segment);
    let tail = *chain(w.suture()).thread().segments.last().expect("segments");
    let away = w.tissue().world_from_tissue.rotation * nalgebra::Vector3::new(0.0, force_n, 0.0);
    w.physics_mut().bodies[tail].add_force(Vector::new(away.x, away.y, away.z), true);
    run(&mut w, steps);
    let after = chain(w.suture())
        .stitch()
        .needle_side_length_m(w.physics(), chain(w.suture()).thread(), w.tissue())
        .expect("still stitched");
    (before - after, holes_before, chain(w.suture()).stitch().holes.map(|h| h.segment))
}

/// A 0.5 N pull on the tail slides the thread over 20 mm through the stitch, its points moving along the
/// thread towards the needle.
#[test]
fn the_thread_slides_through_the_stitch_when_pulled() {
    let (slid, before, after) = pull_tail(0.5, 120);
    println!(
        "pulled with 0.5 N for 0.12 s: slid {:.1} mm, points moved from segments {before:?} to {after:?}",
        slid * 1e3
    );
    assert!(slid > 0.02, "slid only {slid} m");
    // The stitch followed the thread along: both points now sit on segments nearer the needle.
    for (b, a) in before.iter().zip(after) {
        assert!(a.expect("in") < b.expect("in"), "{before:?} -> {after:?}");
    }
}

/// A 0.03 N pull, below the stitch's friction, draws the thread under 3 mm through it.
#[test]
fn stitch_friction_holds_a_pull_below_it() {
    // Two points at 0.05 N each: a 0.03 N pull does not drag the thread through.
    let (slid, _, _) = pull_tail(0.03, 300);
    println!("pulled with 0.03 N for 0.3 s: slid {:.2} mm", slid * 1e3);
    assert!(slid.abs() < 0.003, "slid {slid} m under a pull below the friction");
}

/// The start condition holds no knot: the evaluation says so without running the holding test, and
/// an untied thread, released, lets the load hold the wound open.
#[test]
fn an_untied_thread_is_no_knot_and_the_wound_stays_open() {
    use knotlab_sim::evaluate::evaluate_knot;
    use knotlab_sim::knot::{FailureMode, KnotType, Verdict};
    let mut w = world();
    run(&mut w, 200);
    let params = w.config().evaluation.clone();
    let result = evaluate_knot(&mut w, &params);
    assert_eq!(result.knot_before, Some(KnotType::Unknot));
    assert_eq!(result.verdict, Verdict::Failure(FailureMode::NoKnot));
    assert_eq!(result.gap_after_m, None, "no holding test without a knot");
    w.release_all();
    run(&mut w, 1000);
    assert!(w.arm(ArmName::Right).hold().is_none() && w.arm(ArmName::Assist).hold().is_none());
    assert!(w.wound_gap_m() > params.max_wound_gap_m, "gap {}", w.wound_gap_m());
}

/// Where each stitch point sits on the thread (`Stitch::arc_at_m`, from the segments) matches the
/// centreline the knot's span is measured on: the centreline's point at that arc length lies at the
/// hole, so the thread between the stitch and a knot is counted on one scale.
#[test]
fn the_stitch_points_arc_lengths_lie_at_the_holes_on_the_centreline() {
    let mut w = world();
    run(&mut w, 300);
    let line = chain(w.suture()).thread().centreline(w.physics());
    let mut arcs = vec![0.0];
    for pair in line.windows(2) {
        arcs.push(arcs.last().unwrap() + (pair[1] - pair[0]).norm());
    }
    let at = |arc_m: f64| {
        let k = arcs.iter().position(|&a| a >= arc_m).expect("on the thread").max(1);
        let t = (arc_m - arcs[k - 1]) / (arcs[k] - arcs[k - 1]);
        line[k - 1] + (line[k] - line[k - 1]) * t
    };
    let mut previous = f64::NEG_INFINITY;
    for flap in Flap::ALONG_THREAD {
        let arc_m = chain(w.suture())
            .stitch()
            .arc_at_m(w.physics(), chain(w.suture()).thread(), w.tissue(), flap)
            .expect("the thread is through");
        let hole = w.tissue().hole_m(w.physics(), flap);
        let off_m = (at(arc_m) - hole).norm();
        println!("{flap:?}: {:.1} mm along the thread, {:.3} mm from the hole", arc_m * 1e3, off_m * 1e3);
        assert!(off_m < 5e-4, "{flap:?}: the centreline at that arc length is {off_m} m from the hole");
        assert!(arc_m > previous, "the needle end meets the exit first");
        previous = arc_m;
    }
}

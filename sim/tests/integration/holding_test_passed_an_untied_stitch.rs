//! Regression: the holding test could not tell a knot from none. The wound's elastic load (20 N/m
//! over a 4 mm rest gap: at most 0.04 N a flap) is below the stitch's friction (0.05 N a point), so
//! once the thread's tension had closed the wound, nothing could draw the thread back through the
//! tissue: released, the wound opened only to 1.2-1.8 mm whether a knot held it or not (the scripted
//! expert with no turns at all, seeds 0-7, against 0.4-2.2 mm with its knot). The holding load
//! (`[evaluation] holding_load_n`) pulls each flap open during the settle with more than that
//! friction, so an untied stitch opens.

use crate::common::chain;
use knotlab_hw::rig::{ArmName, Rig};
use knotlab_sim::evaluate::hold;
use knotlab_sim::scene::parse_scene;
use knotlab_sim::world::SimWorld;
use nalgebra::Vector3;
use rapier3d::prelude::*;

fn run(w: &mut SimWorld, steps: usize) {
    for _ in 0..steps {
        w.step().expect("healthy step");
    }
}

/// The start condition with both ends let go and pulled up out of the tissue until the thread's
/// tension closes the wound, then let go: a stitch with no knot. Returns the world and the gap the
/// tension left.
fn closed_untied_stitch() -> (SimWorld, f64) {
    let scene =
        parse_scene(include_str!("../../../scenarios/chain.toml"), "chain.toml").expect("shipped scene");
    let mut w = SimWorld::new(scene, Rig::shipped().expect("shipped rig")).expect("the scene builds");
    for arm in [ArmName::Right, ArmName::Assist] {
        let mut open = w.arm(arm).command;
        open.tool.jaw_rad = SimWorld::JAW_OPEN_RAD;
        w.command(arm, open);
    }
    run(&mut w, 300);
    // Each end drawn up at 2 cm/s by a force of at most 0.4 N (as an instrument would pull it).
    let up = w.tissue().world_from_tissue.rotation * Vector3::new(0.0, 0.0, 1.0);
    let ends = [
        chain(w.suture()).thread().segments[0],
        *chain(w.suture()).thread().segments.last().expect("segments"),
    ];
    for _ in 0..1500 {
        for &end in &ends {
            let body = &mut w.physics_mut().bodies[end];
            let v = body.linvel();
            let rising_m_s = Vector3::new(v.x, v.y, v.z).dot(&up);
            let pull_n = (20.0 * (0.02 - rising_m_s)).clamp(0.0, 0.4);
            body.reset_forces(true);
            body.add_force(Vector::new(up.x * pull_n, up.y * pull_n, up.z * pull_n), true);
        }
        w.step().expect("healthy step");
    }
    let closed = w.wound_gap_m();
    for &end in &ends {
        w.physics_mut().bodies[end].reset_forces(true);
    }
    (w, closed)
}

/// The holding load opens a stitch closed with no knot to over twice the allowed wound gap, so the holding
/// test does not pass an untied stitch.
#[test]
fn the_holding_load_opens_a_stitch_with_no_knot() {
    let (mut unloaded, closed) = closed_untied_stitch();
    let mut params = unloaded.config().evaluation.clone();
    params.holding_load_n = 0.0;
    let without_load = hold(&mut unloaded, &params).expect("stable");
    let (mut loaded, _) = closed_untied_stitch();
    params.holding_load_n = 0.3;
    let with_load = hold(&mut loaded, &params).expect("stable");
    println!(
        "an untied stitch closed by the thread's tension to {:.2} mm, then let go for {} s: gap {:.2} mm \
         with the elastic load alone, {:.2} mm with {} N a flap more (a knot must hold it below {:.2} mm)",
        closed * 1e3,
        params.settle_s,
        without_load * 1e3,
        with_load * 1e3,
        params.holding_load_n,
        params.max_wound_gap_m * 1e3
    );
    assert!(closed < params.max_wound_gap_m, "the pull closed the wound to {closed} m");
    assert!(
        with_load > 2.0 * params.max_wound_gap_m,
        "loaded, the untied stitch opened to {with_load} m only"
    );
    assert!(with_load > without_load + 1e-3, "the load opened it: {without_load} -> {with_load} m");
}

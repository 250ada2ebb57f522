//! Regression (session 48): on the rope scene the right's gauge missed the thread's pull on the
//! needle it holds. The rope pulls the needle through its swage, an impulse applied to the needle's
//! body before Rapier's step; the jaws' joint takes it up in its first substeps, and the gauge read
//! only the joint's last substep. In the expert's first throw the right drew the long end through
//! the stitch against its friction and read 0.01-0.03 N all the while, so its pull never stopped at
//! its set force. Now the gauge of jaws holding the needle adds what the rope did to the needle.

use knotlab_hw::rig::{ArmName, Rig};
use knotlab_sim::scene::parse_scene;
use knotlab_sim::world::{JAW_CENTRE_OFFSET_M, SimWorld};
use nalgebra::{Point3, Vector3};

#[test]
fn the_right_reads_the_long_ends_pull_on_the_needle_it_holds() {
    let mut scene =
        parse_scene(include_str!("../../scenarios/default.toml"), "default.toml").expect("the shipped scene");
    // A short long end, so that a short draw makes it taut (the tail's 31 mm as in the scene).
    scene.thread.length_m = 0.1;
    let mut w = SimWorld::new(scene, Rig::shipped().expect("the rig")).expect("the rope scene builds");
    let across = w.tissue.world_from_tissue.rotation * Vector3::y();
    let tip = w.world_from_tip(ArmName::Right);
    let start = (tip * Point3::new(0.0, 0.0, -JAW_CENTRE_OFFSET_M)).coords;
    let dt_s = w.config.solver.dt_s;
    let (mut right_n, mut assist_n): (f64, f64) = (0.0, 0.0);
    let mut at_largest = (0.0, 0.0);
    // The right draws the long end away from the wound at 20 mm/s for 2 s; the assist holds the tail.
    for k in 1..=(2.0 / dt_s) as usize {
        let to = start - across * (0.02 * k as f64 * dt_s);
        let joints = w.joints_for_jaw_centre(ArmName::Right, &to).expect("within reach");
        w.command(ArmName::Right, joints);
        w.step().expect("healthy");
        let (r, a) =
            (w.arm(ArmName::Right).filtered_force_n.norm(), w.arm(ArmName::Assist).filtered_force_n.norm());
        if a > assist_n {
            at_largest = (r, a);
        }
        right_n = right_n.max(r);
        assist_n = assist_n.max(a);
    }
    println!(
        "largest gauges: right {right_n:.2} N, assist {assist_n:.2} N; at the assist's largest {:.2} N and {:.2} N; {:?}",
        at_largest.0, at_largest.1, w.events
    );
    // The thread drawn taut: the assist feels it through the stitch, the right at least as much (the
    // stitch's friction lies between them).
    assert!(assist_n > 0.5, "the long end never drew on the tail: {assist_n} N");
    let (right_then_n, assist_then_n) = at_largest;
    assert!(
        right_then_n > 0.8 * assist_then_n && right_then_n < assist_then_n + 1.5,
        "the right read {right_then_n:.2} N to the assist's {assist_then_n:.2} N"
    );
}

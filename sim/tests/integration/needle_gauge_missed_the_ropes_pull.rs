//! Guards the right's gauge on the rope scene: it must read the thread's pull on the needle it
//! holds. The rope pulls the needle through its swage, an impulse applied to the needle's body
//! before Rapier's step; the jaws' joint takes it up in its first substeps, so a gauge reading only
//! the joint's last substep misses it (in the expert's first throw the right, drawing the long end
//! through the stitch against its friction, then reads 0.01-0.03 N all the while, and its pull never
//! stops at its set force). The gauge of jaws holding the needle adds what the rope did to the
//! needle.

use knotlab_hw::rig::{ArmName, Rig};
use knotlab_sim::grasp::GraspEvent;
use knotlab_sim::scene::parse_scene;
use knotlab_sim::world::{JAW_CENTRE_OFFSET_M, SimWorld};
use nalgebra::{Point3, Vector3};

/// The right draws a 0.1 m thread's long end away from the wound at 20 mm/s for 2 s while the
/// assist holds the tail, the rope at its own resolution (`own_rope`: 20 substeps, particles 1.5
/// radii apart) or at the shipped scene's: every step's time and the right's and the assist's
/// filtered gauges, N, and the time the assist's grip first slipped, if it did.
fn drawn_taut(own_rope: bool) -> (Vec<(f64, f64, f64)>, Option<f64>) {
    let mut scene = parse_scene(include_str!("../../../scenarios/default.toml"), "default.toml")
        .expect("the shipped scene");
    // A short long end, so that a short draw makes it taut (the tail's 31 mm as in the scene).
    scene.thread.length_m = 0.1;
    if own_rope {
        scene.thread.rope_substeps = None;
        scene.thread.rope_spacing_radii = None;
    }
    let mut w = SimWorld::new(scene, Rig::shipped().expect("the rig")).expect("the rope scene builds");
    let across = w.tissue().world_from_tissue.rotation * Vector3::y();
    let tip = w.world_from_tip(ArmName::Right);
    let start = (tip * Point3::new(0.0, 0.0, -JAW_CENTRE_OFFSET_M)).coords;
    let dt_s = w.config().solver.dt_s;
    let mut gauges = Vec::new();
    for k in 1..=(2.0 / dt_s) as usize {
        let to = start - across * (0.02 * k as f64 * dt_s);
        let joints = w.joints_for_jaw_centre(ArmName::Right, &to).expect("within reach");
        w.command(ArmName::Right, joints);
        w.step().expect("healthy");
        gauges.push((
            w.time_s(),
            w.arm(ArmName::Right).filtered_force_n.norm(),
            w.arm(ArmName::Assist).filtered_force_n.norm(),
        ));
    }
    let slipped = w.events().iter().find_map(|e| match e {
        GraspEvent::Slipped { arm: ArmName::Assist, time_s, .. } => Some(*time_s),
        _ => None,
    });
    (gauges, slipped)
}

/// At the rope's own resolution the right's gauge reads the long end's pull on the needle it holds, about
/// what the assist reads on the tail, as the thread draws taut and until the assist's grip gives.
#[test]
fn the_right_reads_the_long_ends_pull_on_the_needle_it_holds() {
    // At the rope's own resolution the draw is smooth: as the assist's reading rises to its grip
    // (the first step it reads 95 % of the most it reads), the right reads about as much (the
    // stitch's friction lies between them). Once the grip gives, the thread drawn over the flaps'
    // edges reads more on the right than on the sliding grip. (At the shipped scene's 1.2 mm spacing
    // and 20 substeps the right read 7.2 N to the assist's 5.0 N there.)
    let (gauges, _) = drawn_taut(true);
    let most_n = gauges.iter().map(|g| g.2).fold(0.0, f64::max);
    let &(_, right_then_n, assist_n) =
        gauges.iter().find(|g| g.2 >= 0.95 * most_n).expect("the draw was stepped");
    assert!(assist_n > 0.5, "the long end never drew on the tail: {assist_n} N");
    assert!(
        right_then_n > 0.8 * assist_n && right_then_n < assist_n + 1.5,
        "the right read {right_then_n:.2} N to the assist's {assist_n:.2} N"
    );
}

/// At the shipped scene's rope resolution the right's gauge reads the long end's pull on its needle too, its
/// median while taut at least most of the assist's and at most what the stitch can add to it: the
/// flaps' friction and the capstan over their two edges (a quarter turn each at most), not twice it.
#[test]
fn at_the_shipped_scenes_resolution_the_right_reads_the_pull_too() {
    // At the shipped scene's coarser rope the assist's grip gives way in a jolt (2.7 N at one step,
    // the right reading 2.0 N then), so the two are compared through the taut draw
    // before it: the medians of both gauges while the assist reads over 0.5 N.
    let (gauges, slipped) = drawn_taut(false);
    let taut: Vec<&(f64, f64, f64)> =
        gauges.iter().filter(|(t, _, a)| *a > 0.5 && slipped.is_none_or(|s| *t < s)).collect();
    assert!(taut.len() > 100, "the thread was taut for {} steps only", taut.len());
    let median = |pick: fn(&(f64, f64, f64)) -> f64| {
        let mut values: Vec<f64> = taut.iter().map(|g| pick(g)).collect();
        values.sort_by(f64::total_cmp);
        values[values.len() / 2]
    };
    let (right_n, assist_n) = (median(|g| g.1), median(|g| g.2));
    println!(
        "taut for {} steps: the right's median {right_n:.2} N, the assist's {assist_n:.2} N",
        taut.len()
    );
    let scene =
        parse_scene(include_str!("../../../scenarios/default.toml"), "default.toml").expect("the scene");
    let capstan = (scene.thread.friction * std::f64::consts::PI).exp();
    let most_n = assist_n * capstan + 2.0 * scene.stitch.slide_friction_n + 0.5;
    assert!(
        right_n > 0.8 * assist_n && right_n < most_n,
        "the right read {right_n:.2} N to the assist's {assist_n:.2} N (at most {most_n:.2} N)"
    );
}

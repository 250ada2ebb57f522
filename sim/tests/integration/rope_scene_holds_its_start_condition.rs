//! The nominal scene, its suture the rope (`scenarios/default.toml`, `thread.model = "rope"`), builds in
//! the task's start condition and keeps it while the instruments stand still for a second: the right
//! jaws hold the needle (a body of its own, the rope swaged to it), the assist's hold the tail, the
//! thread stays through the stitch, the rope keeps its length, the gauges read no more than the
//! thread's pull, and the rope's contacts show it in the assist's jaws.

use super::common;

use knotlab_hw::rig::ArmName;
use knotlab_sim::tissue::Flap;
use knotlab_sim::world::SimWorld;

/// Standing still for a second, the rope scene keeps the needle and the tail held, the thread still in the
/// stitch and the rope at its length, gauges under 2 N and the tail lying in the assist's jaws.
#[test]
fn the_rope_scene_holds_the_needle_the_tail_and_the_stitch_standing_still() {
    let mut w = common::rope_world();
    let length_m = w.config().thread.length_m;
    assert!(w.suture().as_chain().is_none(), "no chain beside the rope");
    assert!(w.arm(ArmName::Right).holds_needle(), "the right holds the needle");
    assert!(
        w.arm(ArmName::Assist).hold().is_some_and(|h| h.joint_grasp().is_none()),
        "the assist grips the tail"
    );
    let arcs =
        |w: &SimWorld| [w.stitch_arc_at_m(Flap::B), w.stitch_arc_at_m(Flap::A)].map(|a| a.expect("through"));
    let before = arcs(&w);
    let mut settled = before;
    let mut largest_force_n: f64 = 0.0;
    for k in 1..=1000 {
        w.step().expect("the scene stays healthy");
        for arm in [ArmName::Left, ArmName::Right, ArmName::Assist] {
            largest_force_n = largest_force_n.max(w.arm(arm).filtered_force_n.norm());
        }
        if k == 100 {
            settled = arcs(&w);
        }
    }
    let after = arcs(&w);
    println!(
        "events {:?}; stitch at {before:?} -> {settled:?} (0.1 s) -> {after:?} m; gap {:.2} mm; largest gauge {largest_force_n:.2} N",
        w.events(),
        w.wound_gap_m() * 1e3
    );
    assert!(w.arm(ArmName::Right).holds() && w.arm(ArmName::Assist).holds(), "{:?}", w.events());
    // The thread settles by a few millimetres as the scene starts (the assist's grip slides at the
    // first step), and the stitch's friction then holds it where it is (without it, it swung on by
    // 1.8-2.6 mm).
    for ((b, s), a) in before.iter().zip(&settled).zip(&after) {
        assert!((b - a).abs() < 0.005, "the thread slid through the stitch: {before:?} -> {after:?} m");
        assert!((s - a).abs() < 0.001, "the thread slid once settled: {settled:?} -> {after:?} m");
    }
    let line = w.thread_centreline();
    let rope_m: f64 = line.windows(2).map(|p| (p[1] - p[0]).norm()).sum();
    assert!((rope_m - length_m).abs() < 0.002 * length_m, "the rope is {rope_m:.4} m long");
    // The thread weighs 0.1 N; the tissue's pull on it, standing, is less than a newton.
    assert!(largest_force_n < 2.0, "a gauge read {largest_force_n:.2} N");
    // Where the rope lies on the instruments: the tail in the assist's jaws, nothing on the free left.
    let contacts = w.thread_contacts();
    let held = w.arm(ArmName::Assist).held_at().expect("the assist holds the tail");
    let in_assist_jaws =
        contacts.iter().filter(|(p, link)| link.starts_with("assist_jaw") && p.abs_diff(held) < 12);
    assert!(in_assist_jaws.count() >= 2, "held at {held}: {contacts:?}");
    assert!(!contacts.iter().any(|(_, link)| link.starts_with("left_")), "{contacts:?}");
}

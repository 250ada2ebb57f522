//! The suture's stretch watch (reported in every trial as `thread_most_stretched`) reads what the
//! suture does: next to nothing at rest, and the stretch the stress sequence measures when the
//! instruments yank it.

use knotlab_hw::rig::Rig;
use knotlab_scenarios::stress::run_stress;
use knotlab_sim::scene::parse_scene;
use knotlab_sim::world::SimWorld;

fn nominal_world() -> SimWorld {
    let scene = parse_scene(include_str!("../../default.toml"), "default.toml").expect("the nominal scene");
    SimWorld::new(scene, Rig::shipped().expect("shipped rig")).expect("the nominal scene builds")
}

/// Guards the watch against reading nothing, or something else than the suture: it holds the
/// largest stretch the rope showed after any step, to the bit, and how long it was beyond 5 %, both for the nominal rope left lying
/// (which stays within the 5 % the summaries count apart: 2.4 % at most, in the start layout's
/// first steps; held exactly by the jaws, the rope no longer passes 5 % there) and played through
/// the stress sequence in 1 s (moves six times the nominal speed), where it passes 5 % and equals
/// the stress report's own largest figure.
#[test]
fn the_stretch_watch_reads_the_rope_at_rest_and_yanked() {
    let mut world = nominal_world();
    assert_eq!(world.suture().most_stretched(), None, "no step yet");
    let (mut largest, mut settled) = (0.0_f64, 0.0_f64);
    for k in 0..200 {
        world.step().expect("a healthy step");
        let now = world.suture().max_stretch_ratio(world.physics());
        largest = largest.max(now);
        if k >= 50 {
            settled = settled.max(now);
        }
    }
    let rest = world.suture().most_stretched().expect("noted after a step");
    assert_eq!(rest.ratio.to_bits(), largest.to_bits(), "{rest:?} against {largest}");
    assert!(settled < 0.05, "the rope lying still stretched {settled}");
    assert!(rest.ratio > 0.0 && rest.ratio < 0.05 && rest.over_5_percent_s == 0.0, "{rest:?}");

    let mut world = nominal_world();
    let report = run_stress(&mut world, 1.0, &[], &mut |_, _| {});
    let yanked = world.suture().most_stretched().expect("noted");
    assert!(yanked.ratio > 0.05, "yanked, the rope stretched only {yanked:?}");
    assert!(yanked.over_5_percent_s > 0.0015, "{yanked:?}");
    assert_eq!(yanked.ratio.to_bits(), report.max_stretch_ratio.to_bits(), "{yanked:?} against {report:?}");
    assert_eq!(yanked.time_s.to_bits(), report.max_stretch_at_s.to_bits());
}

//! The expert looks where the tail lies before the left closes on it (`[left_fetches] looks`,
//! `scenarios/tests/experts/looks-at-the-tail.toml`): the first throw's plan stops with
//! the left's jaws over the tail, and the descent is planned from the tail as it lies then. On the
//! rope scene a slack tail sags 4-8 mm off the straight line the base plan aims at, and on seed 1 a
//! left aiming there closes on its own coils instead. The jaws close on the tail where it is clear of
//! the tissue, and the right follows them down onto it.

use super::common;

use common::{event_segment, event_time_s, expert};
use knotlab_hw::rig::{ArmName, Rig};
use knotlab_scenarios::expert::LeftFetch;
use knotlab_scenarios::expert::tail::{TAKE_CLEARANCE_M, tail_ahead_of_jaws};
use knotlab_scenarios::expert::{
    RecordOptions, SecondThrow, TieGeometry, demonstrate_with, plan_instrument_tie, plan_second_tail_take,
    plan_second_throw, plan_tail_take,
};
use knotlab_sim::scene::parse_scene;
use knotlab_sim::world::SimWorld;

fn rope_scene() -> knotlab_sim::scene::SceneConfig {
    parse_scene(include_str!("../../default.toml"), "default.toml").expect("the shipped scene")
}

/// The nominal scene's world in its start condition, on the shipped rig.
fn rope_world() -> SimWorld {
    SimWorld::new(rope_scene(), Rig::shipped().expect("the rig")).expect("the rope scene builds")
}

/// The point ahead of the jaws lies on the tail nearest their line, with the tail's direction towards its
/// end and clear of the tissue, and no tail is found behind the jaws.
#[test]
fn the_point_ahead_of_the_jaws_is_on_the_tail_where_their_line_meets_it() {
    let world = rope_world();
    let line = world.thread_centreline();
    let inside = world.thread_inside().expect("through the stitch");
    let held = world.arm(ArmName::Assist).held_at().expect("the assist holds the tail");
    let tail_point = line[(*inside.end() + held) / 2];
    let up = world.tissue().world_from_tissue.rotation * nalgebra::Vector3::z();
    // Jaws 12 mm over the tail, pointing down at it, and a little to one side.
    let side = world.tissue().world_from_tissue.rotation * nalgebra::Vector3::x() * 0.0005;
    let jaw_centre = tail_point + up * 0.012 + side;
    let (found, along) = tail_ahead_of_jaws(&world, &jaw_centre, &-up).expect("a tail ahead");
    // ... with the way the tail runs there, towards its end.
    let towards_end = (line[held] - line[*inside.end() + 1]).normalize();
    assert!((along.norm() - 1.0).abs() < 1e-9 && along.dot(&towards_end) > 0.5, "{along:?}");
    let off_line = |p: &nalgebra::Vector3<f64>| {
        let d = p - jaw_centre;
        (d - up * d.dot(&up)).norm()
    };
    assert!(off_line(&found) <= off_line(&tail_point) + 1e-9, "{found:?} is further off than {tail_point:?}");
    assert!(off_line(&found) < 0.0006, "{:.2} mm off the jaws' line", off_line(&found) * 1e3);
    assert!((found - tail_point).norm() < 0.005, "{found:?} is not near {tail_point:?}");
    // Over the tail where it leaves the tissue (under 3 mm up), the jaws take it where it is clear
    // of the tissue: a jaw under it would press into the tissue.
    let surface = world.tissue().hole_m(world.physics(), knotlab_sim::tissue::Flap::A);
    let height = |p: &nalgebra::Vector3<f64>| (p - surface).dot(&up);
    let low = (*inside.end() + 1..held).map(|i| line[i]).find(|p| height(p) < 0.002).expect("a low point");
    let (over_low, _) = tail_ahead_of_jaws(&world, &(low + up * 0.012), &-up).expect("a tail ahead");
    assert!(height(&over_low) >= TAKE_CLEARANCE_M, "{:.2} mm up", height(&over_low) * 1e3);
    // Pointing away from it, the jaws see no tail ahead above the tissue there.
    let away = tail_ahead_of_jaws(&world, &jaw_centre, &up);
    assert!(away.is_none_or(|(p, _)| (p - jaw_centre).dot(&up) >= 0.0), "{away:?} is behind the jaws");
}

/// A looking plan ends the first throw with the jaws over the tail, well short of the whole tie, and only
/// a plan that looks has a tail take to plan after it.
#[test]
fn looking_splits_the_first_throw_at_the_tail() {
    let world = rope_world();
    let variation = knotlab_scenarios::expert::Variation::none();
    let looks = expert("looks-at-the-tail.toml");
    assert_eq!(
        TieGeometry { left_fetches: TieGeometry::default().left_fetches, ..looks.clone() },
        TieGeometry::default()
    );
    let whole = plan_instrument_tie(&world, &TieGeometry::default(), &variation);
    let to_the_tail = plan_instrument_tie(&world, &looks, &variation);
    let (part_s, whole_s) = (to_the_tail.duration_s(), whole.duration_s());
    assert!(part_s < whole_s - 5.0, "{part_s} s against {whole_s} s");
    assert!(plan_tail_take(&world, &looks, &variation).is_some());
    assert!(
        plan_tail_take(&world, &TieGeometry::default(), &variation).is_none(),
        "the shipped plan does not look"
    );
}

/// A second throw whose fetch looks stops at the tail and leaves a tail take to plan; one that does not
/// look, or fetches nothing, is planned whole.
#[test]
fn looking_splits_the_second_throw_at_the_tail_where_the_left_fetches_it() {
    let world = rope_world();
    let variation = knotlab_scenarios::expert::Variation::none();
    let looks = expert("looks-at-the-tail.toml");
    let fetch = looks.left_fetches.clone().expect("the first throw fetches");
    let blind = LeftFetch { looks: false, ..fetch.clone() };
    let with = |second: SecondThrow| TieGeometry { second_throw: Some(second), ..looks.clone() };
    // The assist takes the tail from the left, which fetches it after the turn as in the first throw.
    let fetching = SecondThrow { tail_hold_from_end_m: Some(0.005), ..SecondThrow::default() };
    let looking = with(SecondThrow { left_fetches: Some(fetch.clone()), ..fetching.clone() });
    let not_looking = with(SecondThrow { left_fetches: Some(blind), ..fetching.clone() });
    let part = plan_second_throw(&world, &looking, &variation).expect("a second throw");
    let whole = plan_second_throw(&world, &not_looking, &variation).expect("a second throw");
    assert!(
        part.duration_s() < whole.duration_s() - 5.0,
        "{} s against {} s",
        part.duration_s(),
        whole.duration_s()
    );
    let rest = plan_second_tail_take(&world, &looking, &variation).expect("the rest, from the tail");
    assert!(rest.name.contains("second throw"), "{}", rest.name);
    assert!(plan_second_tail_take(&world, &not_looking, &variation).is_none(), "it does not look");
    // Where the left keeps the tail, or the assist presents it, nothing is fetched: no split.
    for second in [
        SecondThrow { left_keeps_tail: true, left_fetches: Some(fetch.clone()), ..SecondThrow::default() },
        SecondThrow { assist_presents: true, left_fetches: Some(fetch.clone()), ..fetching },
    ] {
        let geometry = with(second);
        assert!(plan_second_tail_take(&world, &geometry, &variation).is_none());
        let skill = plan_second_throw(&world, &geometry, &variation).expect("a second throw");
        assert!(!skill.name.contains("to the tail"), "{}", skill.name);
    }
}

/// The take comes over the tail and then onto it along the jaws, which keep their direction, with the
/// hinge lying along the tail.
#[test]
fn the_take_comes_onto_the_tail_along_the_jaws_its_hinge_along_the_tail() {
    use knotlab_hw::skill::Orientation;
    use knotlab_sim::world::JAW_CENTRE_OFFSET_M;
    let world = rope_world();
    let variation = knotlab_scenarios::expert::Variation::none();
    let looks = expert("looks-at-the-tail.toml");
    let fetch = looks.left_fetches.clone().expect("a fetch");
    let framed =
        TieGeometry { left_fetches: Some(LeftFetch { hinge_along_tail: true, ..fetch.clone() }), ..looks };
    // The left's jaws as they stand, and the tail's point they look at.
    let tip = world.world_from_tip(ArmName::Left);
    let jaws = tip.rotation * nalgebra::Vector3::z();
    let centre = (tip * nalgebra::Point3::new(0.0, 0.0, -JAW_CENTRE_OFFSET_M)).coords;
    let (tail, along) = tail_ahead_of_jaws(&world, &centre, &jaws).expect("a tail ahead of the jaws");
    let off_line_m = (tail - centre - jaws * (tail - centre).dot(&jaws)).norm();
    assert!(off_line_m > 0.002, "the tail lies {:.1} mm off the jaws' line at the start", off_line_m * 1e3);
    let skill = plan_tail_take(&world, &framed, &variation).expect("the take");
    let left = skill.track(ArmName::Left).expect("the left");
    // Keys are the tip's: the jaw centre is the offset behind it along the jaws.
    let centre_of = |k: &knotlab_hw::skill::PoseKey| {
        nalgebra::Vector3::from(k.world_position_m) - jaws * JAW_CENTRE_OFFSET_M
    };
    let nearest_m = |p: nalgebra::Vector3<f64>| {
        left.poses.iter().map(|k| (centre_of(k) - p).norm()).fold(f64::INFINITY, f64::min)
    };
    // Over the tail first, then onto it along the jaws.
    let over = tail - jaws * fetch.approach_m;
    let (to_over, to_tail) = (nearest_m(over), nearest_m(tail));
    println!(
        "{:.1} mm off the line: over the tail within {:.2} mm, onto it within {:.2} mm",
        off_line_m * 1e3,
        to_over * 1e3,
        to_tail * 1e3
    );
    assert!(to_over < 0.0005 && to_tail < 0.0005, "{to_over} m, {to_tail} m");
    let when = |p: nalgebra::Vector3<f64>| {
        left.poses.iter().find(|k| (centre_of(k) - p).norm() < 0.0005).map(|k| k.time_s)
    };
    assert!(when(over) < when(tail), "over the tail before onto it");
    // The hinge (the frame's y) across the jaws along the tail where it lies.
    let across = (along - jaws * along.dot(&jaws)).normalize();
    let at_tail = left.poses.iter().find(|k| (centre_of(k) - tail).norm() < 0.0005).expect("at the tail");
    match at_tail.orientation {
        Orientation::Frame { quaternion_xyzw: [x, y, z, w] } => {
            let q = nalgebra::UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, y, z));
            assert!((q * nalgebra::Vector3::z()).dot(&jaws) > 0.9999, "the jaws keep their direction");
            let hinge = q * nalgebra::Vector3::y();
            assert!(hinge.dot(&across).abs() > 0.999, "the hinge {hinge:?} is not along the tail {across:?}");
        }
        other => panic!("the left holds {other:?}, not a frame"),
    }
}

/// On the rope scene (seed 1) the looking left grasps the tail near its end, not its own coils.
#[test]
fn on_the_rope_the_left_takes_the_tail_it_looked_at() {
    // Seed 1: a left that does not look closes on its own coils here (particle 91); looking,
    // it takes the tail near the assist's jaws, about 15 s in.
    let options =
        RecordOptions { cycles_per_sample: 10, stop_after_s: Some(15.5), ..RecordOptions::default() };
    let run = demonstrate_with(
        rope_scene(),
        "scenarios/default.toml",
        1,
        true,
        &expert("looks-at-the-tail.toml"),
        &options,
        None,
    )
    .expect("the run");
    assert!(run.fault.is_none(), "{:?}", run.fault);
    let take =
        run.events.iter().find(|e| e.starts_with("Grasped { arm: Left")).expect("the left takes something");
    let particle = event_segment(take).expect("a particle");
    let particles = run.final_scene.thread_m.len();
    assert!(
        particle > particles * 3 / 4,
        "the left took particle {particle} of {particles}: not the tail ({take})"
    );
    assert!(event_time_s(take).is_some_and(|t| t > 12.0), "{take}");
}

/// As the left goes down onto the tail the right follows it by the fetch's share, and stays put when told
/// not to follow.
#[test]
fn the_right_follows_the_left_down_onto_the_tail() {
    // The turns lie round both instruments' jaws: the right, left standing as the left goes down onto
    // the tail, draws them taut (seeds 0 and 19 of the shipped plan: 100-530 N on both gauges, equal
    // and opposite). It follows the descent by the fetch's share, as it followed the fetch.
    let world = rope_world();
    let variation = knotlab_scenarios::expert::Variation::none();
    let looks = expert("looks-at-the-tail.toml");
    let fetch = looks.left_fetches.clone().expect("a fetch");
    let shifts = |right_follows: f64| {
        let geometry =
            TieGeometry { left_fetches: Some(LeftFetch { right_follows, ..fetch.clone() }), ..looks.clone() };
        let skill = plan_tail_take(&world, &geometry, &variation).expect("the take");
        let (left, right) =
            (skill.track(ArmName::Left).expect("the left"), skill.track(ArmName::Right).expect("the right"));
        // Down on the tail once its jaws start to close; each where it first comes to rest from then
        // on (the right's move, slowed to its joints' speed, may end later).
        let open = left.jaw_at(0.0).expect("the left's jaws");
        let closes_s = left.jaw.iter().find(|k| k.jaw_rad < open - 1e-6).expect("the left closes").time_s;
        let rests = |track: &knotlab_hw::skill::Track| {
            let poses = &track.poses;
            let rest = (0..poses.len() - 1)
                .find(|&i| {
                    poses[i].time_s >= closes_s - 1e-9
                        && poses[i].world_position_m == poses[i + 1].world_position_m
                })
                .map_or(poses[poses.len() - 1].world_position_m, |i| poses[i].world_position_m);
            nalgebra::Vector3::from(rest) - track.target_at(0.0).expect("a target").world_position_m
        };
        (rests(left), rests(right))
    };
    let (left_down, right_down) = shifts(fetch.right_follows);
    println!("the left {:.1} mm, the right {:.1} mm", left_down.norm() * 1e3, right_down.norm() * 1e3);
    assert_eq!(fetch.right_follows, 1.0, "the recipe's right follows all the way");
    assert!(left_down.norm() > 0.003, "the left goes onto the tail: {left_down:?}");
    assert!((right_down - left_down).norm() < 5e-4, "the right {right_down:?}, the left {left_down:?}");
    let (_, right_still) = shifts(0.0);
    assert!(right_still.norm() < 1e-4, "told not to follow, the right stays: {right_still:?}");
}

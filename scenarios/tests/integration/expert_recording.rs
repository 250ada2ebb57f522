//! The scripted expert: its plan stays within the robots' reach at the nominal scene whatever the
//! human-like variation, and a recorded run is a valid demonstration (100 Hz, every instrument, the
//! grasps seen) that survives writing and loading unchanged.

use super::common;

use knotlab_hw::rig::{ArmName, Rig};
use knotlab_learner::demonstration::{GraspState, load_demonstration, write_demonstration};
use knotlab_scenarios::expert::{RecordOptions, TieGeometry, Variation, demonstrate, plan_instrument_tie};
use knotlab_sim::scene::parse_scene;
use knotlab_sim::world::{SimWorld, trocar_of};
use nalgebra::Vector3;

fn scene() -> knotlab_sim::scene::SceneConfig {
    parse_scene(include_str!("../../chain.toml"), "chain.toml").expect("the chain scene")
}

/// The experimental expert file `tests/experts/coils-on-the-left.toml`.
fn coils_on_the_left() -> TieGeometry {
    common::expert("coils-on-the-left.toml")
}

/// Whether the arm reaches every key of `track` in turn, each solved from the last; else which not.
fn reaches_every_key(world: &SimWorld, rig: &Rig, track: &knotlab_hw::skill::Track) -> Result<(), String> {
    let model = &rig.arm(track.arm).model;
    let trocar = trocar_of(world.config(), track.arm);
    let mut joints = world.arm(track.arm).command;
    for key in &track.poses {
        let target = track.target_at(key.time_s).expect("a target");
        joints = model
            .solve_tip(&target, &trocar, &joints)
            .map_err(|e| format!("the {} arm cannot reach its key at {:.2} s: {e}", track.arm, key.time_s))?;
    }
    Ok(())
}

/// The base plan is a well-formed three-arm skill each arm reaches key by key for every human variation,
/// with a long winding path for the right and a pace the variation changes.
#[test]
fn the_plan_is_reachable_for_every_variation() {
    let rig = Rig::shipped().expect("the shipped rig");
    let world = SimWorld::new(scene(), rig.clone()).expect("the scene builds");
    for seed in 0..4 {
        let skill = plan_instrument_tie(&world, &TieGeometry::default(), &Variation::human(seed));
        skill.check().expect("a well-formed skill");
        assert_eq!(skill.tracks.len(), 3, "left, right and assist");
        for track in &skill.tracks {
            if let Err(e) = reaches_every_key(&world, &rig, track) {
                panic!("seed {seed}: {e}");
            }
        }
        let right = skill.track(ArmName::Right).expect("the right winds");
        let path_m: f64 = right
            .poses
            .windows(2)
            .map(|w| (Vector3::from(w[1].world_position_m) - Vector3::from(w[0].world_position_m)).norm())
            .sum();
        assert!(
            path_m > 0.2,
            "seed {seed}: two turns of winding and the pulls make a long path, not {path_m} m"
        );
    }
    let slow = plan_instrument_tie(
        &world,
        &TieGeometry::default(),
        &Variation { slowness: 1.1, ..Variation::none() },
    );
    let fast = plan_instrument_tie(
        &world,
        &TieGeometry::default(),
        &Variation { slowness: 0.9, ..Variation::none() },
    );
    assert!(slow.duration_s() > fast.duration_s(), "the variation changes the pace");
}

/// A recorded run is a valid 100 Hz demonstration of every instrument, with the grasps seen, that writes
/// and loads back identical.
#[test]
fn a_recorded_run_is_a_valid_100_hz_demonstration_that_round_trips() {
    let options = RecordOptions { cycles_per_sample: 10, ..RecordOptions::default() };
    let run = demonstrate(scene(), "scenarios/chain.toml", 3, true, &options, None).expect("records");
    assert_eq!(run.fault, None, "the controller ran the skill to its end");
    let demo = &run.demonstration;
    demo.validate().expect("what the loader accepts");
    assert_eq!(demo.metadata.sample_rate_hz, 100.0);
    assert_eq!(demo.metadata.seed, Some(3));
    for record in &demo.instruments {
        let dt: Vec<f64> = record.samples.windows(2).map(|w| w[1].time_s - w[0].time_s).collect();
        assert!(dt.iter().all(|d| (d - 0.01).abs() < 1e-9), "{}: samples 10 ms apart", record.instrument);
        assert!(record.samples.len() as f64 >= 100.0 * run.simulated_s - 1.0);
    }
    let right = demo.instrument(ArmName::Right).expect("the right");
    assert_eq!(right.samples[0].grasp, GraspState::Holding, "the right starts holding the needle");
    let left = demo.instrument(ArmName::Left).expect("the left");
    assert!(
        left.samples.iter().any(|s| s.grasp == GraspState::ClosedEmpty),
        "the left closes its jaws to wind"
    );
    let moved = (left.samples.last().expect("samples").position_m - left.samples[0].position_m).norm();
    assert!(moved > 0.02, "the left moved {moved} m");

    let dir = std::env::temp_dir().join(format!("knotlab-expert-{}", std::process::id()));
    write_demonstration(&dir, demo).expect("writes");
    let loaded = load_demonstration(&dir).expect("loads");
    assert_eq!(&loaded, demo, "record, save, load gives identical data");
    let _ = std::fs::remove_dir_all(&dir);
}

/// The plan for `geometry` at the shipped scene, for each pulling arm (left, right): its track and
/// its one set-force event (the final pull's).
fn pulls(geometry: &TieGeometry) -> [(knotlab_hw::skill::Track, knotlab_hw::skill::ForceEvent); 2] {
    let world = SimWorld::new(scene(), Rig::shipped().expect("the shipped rig")).expect("the scene builds");
    let skill = plan_instrument_tie(&world, geometry, &Variation::none());
    [ArmName::Left, ArmName::Right].map(|arm| {
        let track = skill.track(arm).expect("the arm pulls").clone();
        let set: Vec<_> = track.events.iter().filter(|e| e.name == "set force").cloned().collect();
        assert_eq!(set.len(), 1, "{arm}: one set-force event");
        (track, set[0].clone())
    })
}

/// Each pull's set-force event fires at the pull force and opens the jaws, or holds instead when
/// `hold_at_force` says so.
#[test]
fn the_pulls_let_go_at_the_set_force_or_hold_it_as_the_geometry_says() {
    use knotlab_hw::skill::ForceAction;
    let actions = |hold_at_force: bool| {
        let geometry = TieGeometry { hold_at_force, ..TieGeometry::default() };
        pulls(&geometry).map(|(_, set)| {
            assert_eq!(set.threshold_n, geometry.pull_force_n);
            set.action
        })
    };
    for action in actions(false) {
        assert!(matches!(action, ForceAction::OpenJaw { .. }), "{action:?}");
    }
    for action in actions(true) {
        assert_eq!(action, ForceAction::Hold);
    }
}

/// A set-force hold ends as the jaws start to open, or lasts until they are open when told to hold
/// through the release.
#[test]
fn the_pulls_hold_through_the_release_when_told() {
    // For each pulling arm: when its set-force hold ends, when its jaws start to open at the end, and
    // when they are open.
    let windows = |hold_through_release: bool| {
        pulls(&TieGeometry { hold_through_release, ..TieGeometry::default() }).map(|(track, hold)| {
            let last = track.jaw.last().expect("jaw keys");
            assert!(last.jaw_rad >= SimWorld::JAW_OPEN_RAD - 1e-9, "{}: lets go at the end", track.arm);
            let opening = track.jaw.iter().rev().find(|k| k.jaw_rad < last.jaw_rad).expect("it was shut");
            (hold.until_s, opening.time_s, last.time_s)
        })
    };
    for (until_s, opening_s, _) in windows(false) {
        assert!((until_s - opening_s).abs() < 1e-9, "the hold ends as the jaws start to open");
    }
    for (until_s, _, opened_s) in windows(true) {
        assert!(until_s >= opened_s, "the hold lasts until the jaws have opened: {until_s} < {opened_s}");
    }
}

/// Given its own tail pull force, the left's set force uses it while the right keeps the pull force.
#[test]
fn the_left_pulls_the_tail_to_its_own_set_force_when_given_one() {
    let geometry = TieGeometry { tail_pull_force_n: Some(0.7), ..TieGeometry::default() };
    let [(_, left), (_, right)] = pulls(&geometry);
    assert_eq!(left.threshold_n, 0.7);
    assert_eq!(right.threshold_n, geometry.pull_force_n);
}

/// Pulls told to go on pass their shipped targets by the distance asked, level with the tissue, at the
/// shipped speed, and each fires with the other's set force.
#[test]
fn pulls_told_to_go_on_pass_their_targets_level_at_the_same_speed_and_stop_together() {
    let shipped = TieGeometry::default();
    let on = TieGeometry { pull_on_m: 0.03, pulls_stop_together: true, ..TieGeometry::default() };
    let world = SimWorld::new(scene(), Rig::shipped().expect("the shipped rig")).expect("the scene builds");
    let stitch = world.tissue().world_from_tissue;
    // Where each pull starts and ends, and its speed: it starts 0.5 s before its set force may fire
    // and ends where its target stops moving, at the latest 1 s before its hold runs out (these plans
    // have no variation; the pull that ends sooner holds still until both let go).
    let ends = |geometry: &TieGeometry| {
        pulls(geometry).map(|(track, set)| {
            let at = |t: f64| track.target_at(t).expect("a target").world_position_m;
            let start_s = set.from_s - 0.5;
            let last = at(set.until_s - 1.0);
            let end_s = (0..)
                .map(|k| start_s + k as f64 * 0.001)
                .take_while(|t| *t <= set.until_s - 1.0)
                .find(|t| (at(*t) - last).norm() < 1e-9)
                .expect("the pull ends before its hold runs out");
            let (from, to) = (at(start_s), last);
            (track.arm, from, to, (to - from).norm() / (end_s - start_s), set)
        })
    };
    for ((arm, from, to, speed, set), ((_, _, shipped_to, shipped_speed, shipped_set), target)) in ends(&on)
        .into_iter()
        .zip(ends(&shipped).into_iter().zip([shipped.left_pull_to_m, shipped.right_pull_to_m]))
    {
        // Shipped, each pull ends at its target (the tip a constant offset from the jaw centre).
        let shipped_target = stitch * nalgebra::Point3::from(Vector3::from(target));
        let offset = shipped_to - shipped_target.coords;
        assert!(offset.norm() < 0.01, "{arm}: the shipped pull ends at its target ({offset:?})");
        // Told to go on, 30 mm further the same way level with the tissue, as fast (the jaw centre
        // goes so; the tip, 5 mm ahead of it along jaws that keep pointing along the shaft, a little
        // differently).
        let normal = stitch.rotation * Vector3::z();
        let level = |v: Vector3<f64>| v - normal * normal.dot(&v);
        let beyond = to - shipped_to;
        assert!((beyond.norm() - 0.03).abs() < 0.002, "{arm}: {} m on", beyond.norm());
        assert!(beyond.normalize().dot(&level(shipped_to - from).normalize()) > 0.99, "{arm}: the same way");
        assert!((speed - shipped_speed).abs() < 0.05 * shipped_speed, "{speed} against {shipped_speed} m/s");
        assert_eq!(shipped_set.fires_with, None);
        assert_eq!(set.fires_with.as_deref(), Some("set force"), "each fires with the other's");
    }
}

/// Pulls that end at different times hold alike and open their jaws together, a second after the later
/// one ends.
#[test]
fn pulls_of_different_lengths_let_go_together() {
    // Sent 0.2 m on, the pulls stop where each arm's reach ends, one sooner than the other; both
    // hold until a second after the later one's end and open their jaws then, together (each letting
    // go at its own end, the left would let go of the tail while the right still drew).
    let far = TieGeometry { pull_on_m: 0.2, hold_through_release: true, ..TieGeometry::default() };
    let [(left, left_set), (right, right_set)] = pulls(&far);
    let opening_s = |track: &knotlab_hw::skill::Track| {
        let last = track.jaw.last().expect("jaw keys");
        track.jaw.iter().rev().find(|k| k.jaw_rad < last.jaw_rad).expect("it was shut").time_s
    };
    let pull_end_s = |track: &knotlab_hw::skill::Track, set: &knotlab_hw::skill::ForceEvent| {
        let at = |t: f64| track.target_at(t).expect("a target").world_position_m;
        let last = at(opening_s(track));
        (0..)
            .map(|k| set.from_s - 0.5 + k as f64 * 0.001)
            .find(|t| (at(*t) - last).norm() < 1e-9)
            .expect("the pull ends")
    };
    let (left_end_s, right_end_s) = (pull_end_s(&left, &left_set), pull_end_s(&right, &right_set));
    println!("the pulls end at {left_end_s:.3} s and {right_end_s:.3} s");
    assert!(
        (left_end_s - right_end_s).abs() > 0.1,
        "the pulls end together: {left_end_s} s, {right_end_s} s"
    );
    assert!((opening_s(&left) - opening_s(&right)).abs() < 1e-9, "the jaws open at different times");
    assert!(
        (opening_s(&left) - (left_end_s.max(right_end_s) + 1.0)).abs() < 0.01,
        "a second after the later"
    );
    assert_eq!(left_set.until_s, right_set.until_s, "the holds last alike");
}

/// Pulls sent on out of the arms' reach stop within it: every key stays reachable and some pull ends short.
#[test]
fn pulls_told_to_go_on_out_of_reach_stop_within_it() {
    let rig = Rig::shipped().expect("the shipped rig");
    let world = SimWorld::new(scene(), rig.clone()).expect("the scene builds");
    let far = TieGeometry { pull_on_m: 0.2, ..TieGeometry::default() };
    let skill = plan_instrument_tie(&world, &far, &Variation::human(3));
    let mut cut_short = 0;
    for (track, (_, set)) in
        [ArmName::Left, ArmName::Right].map(|arm| skill.track(arm).expect("it pulls")).iter().zip(pulls(&far))
    {
        reaches_every_key(&world, &rig, track).unwrap();
        // Where the pull ends against where it would have, the shipped target 0.2 m further on.
        let start = track.target_at(set.from_s - 0.5).expect("a target").world_position_m;
        let end = track
            .target_at(skill.tracks.iter().map(|t| t.poses.last().unwrap().time_s).fold(0.0, f64::max))
            .unwrap()
            .world_position_m;
        let shipped = if track.arm == ArmName::Left { far.left_pull_to_m } else { far.right_pull_to_m };
        let asked =
            (world.tissue().world_from_tissue * nalgebra::Point3::from(Vector3::from(shipped))).coords;
        if (end - start).norm() < (asked - start).norm() + 0.2 - 0.01 {
            cut_short += 1;
        }
    }
    assert!(cut_short > 0, "0.2 m on is out of the arms' reach at this scene: some pull must stop short");
}

/// A pull takes as long as `pull_s` says: a slower pull moves the set-force hold's end by the difference.
#[test]
fn each_pull_takes_as_long_as_told() {
    // The pull's last move, to its target, ends where the set-force hold would otherwise run out: it
    // starts with the pull and is `pull_s` long (the plan's pauses and the release come after).
    let hold_ends_s =
        |pull_s: f64| pulls(&TieGeometry { pull_s, ..TieGeometry::default() }).map(|(_, set)| set.until_s);
    let (shipped, slow) = (hold_ends_s(TieGeometry::default().pull_s), hold_ends_s(8.0));
    for (a, b) in shipped.iter().zip(&slow) {
        let longer_s = b - a;
        assert!((longer_s - (8.0 - 2.5)).abs() < 1e-6, "{longer_s} s longer for a pull 5.5 s slower");
    }
}

/// With `right_jaws_across_winding` the right's jaws stay across the left's all round the winding;
/// without it they reach back along the left's.
#[test]
fn while_winding_the_right_turns_its_jaws_across_the_left_as_the_geometry_says() {
    let world = SimWorld::new(scene(), Rig::shipped().expect("the shipped rig")).expect("the scene builds");
    let geometry = coils_on_the_left();
    // Cosines between the two instruments' jaws over the winding (it starts after the right reaches
    // the circle, 2 s in, and takes 8 s).
    let cosines = |right_jaws_across_winding: f64| {
        let geometry = TieGeometry { right_jaws_across_winding, ..geometry.clone() };
        let skill = plan_instrument_tie(&world, &geometry, &Variation::none());
        (30..100)
            .map(|k| {
                let t = k as f64 * 0.1;
                let (_, left) = jaws_at(&skill, &world, ArmName::Left, t);
                let (_, right) = jaws_at(&skill, &world, ArmName::Right, t);
                left.dot(&right).abs()
            })
            .collect::<Vec<f64>>()
    };
    let along_shaft = cosines(0.0);
    let least = along_shaft.iter().copied().fold(f64::INFINITY, f64::min);
    println!("along its shaft: cosine at least {least:.3}");
    assert!(least > 0.5, "along its shaft the right's jaws reach back along the left's: {least}");
    let across = cosines(1.0);
    let most = across.iter().copied().fold(0.0, f64::max);
    println!("across: cosine at most {most:.3}");
    assert!(most < 0.05, "across the left's jaws all the way round: {most}");
}

/// The left's jaws close to be wound round or stay open as `winding_jaw_rad` says, closing on the tail
/// either way.
#[test]
fn the_left_is_wound_round_with_its_jaws_as_open_as_the_geometry_says() {
    let world = SimWorld::new(scene(), Rig::shipped().expect("the shipped rig")).expect("the scene builds");
    let closings = |winding_jaw_rad: f64| {
        let geometry = TieGeometry { winding_jaw_rad, ..TieGeometry::default() };
        let skill = plan_instrument_tie(&world, &geometry, &Variation::none());
        let jaw = &skill.track(ArmName::Left).expect("the left").jaw;
        jaw.windows(2).filter(|w| w[0].jaw_rad > 0.3 && w[1].jaw_rad < 0.05).count()
    };
    assert_eq!(closings(0.0), 2, "closed to be wound round, then closed on the tail");
    assert_eq!(closings(0.6), 1, "wound round open, closed only on the tail");
}

/// `arm`'s jaw centre and jaw direction as its target stands at `time_s`.
fn jaws_at(
    skill: &knotlab_hw::skill::Skill,
    world: &SimWorld,
    arm: ArmName,
    time_s: f64,
) -> (Vector3<f64>, Vector3<f64>) {
    use knotlab_hw::kinematics::TipOrientation;
    use knotlab_sim::world::JAW_CENTRE_OFFSET_M;
    let target = skill.track(arm).and_then(|t| t.target_at(time_s)).expect("a target");
    let tip = target.world_position_m;
    let jaws = match target.orientation {
        TipOrientation::Frame(r) => r * Vector3::z(),
        TipOrientation::JawDirection(d) => d.normalize(),
        TipOrientation::AlongShaft => (tip - trocar_of(world.config(), arm)).normalize(),
    };
    (tip - jaws * JAW_CENTRE_OFFSET_M, jaws)
}

/// The angle between the right's jaw centre, seen from the left's, and the left's jaws, at `time_s`.
fn right_seen_along_the_left_jaws(
    skill: &knotlab_hw::skill::Skill,
    world: &SimWorld,
    time_s: f64,
) -> (f64, Vector3<f64>) {
    let (left, jaws) = jaws_at(skill, world, ArmName::Left, time_s);
    let (right, _) = jaws_at(skill, world, ArmName::Right, time_s);
    ((right - left).normalize().dot(&jaws).acos(), jaws)
}

/// The right's bearing from the left's jaws just before they turn from `wound` (their direction as
/// the long end is wound round them) and as they first point `to`.
fn bearing_across_the_turn(
    skill: &knotlab_hw::skill::Skill,
    world: &SimWorld,
    wound: Vector3<f64>,
    to: Vector3<f64>,
) -> (f64, f64) {
    let times: Vec<f64> = (0..(skill.duration_s() * 100.0) as usize).map(|i| i as f64 * 0.01).collect();
    let jaws = |t: f64| right_seen_along_the_left_jaws(skill, world, t).1;
    let arrived =
        *times.iter().find(|t| jaws(**t).dot(&to) > 0.9998).expect("the left's jaws turn to the tail");
    let turning = *times
        .iter()
        .rev()
        .filter(|t| **t < arrived)
        .find(|t| jaws(**t).dot(&wound) > 0.9998)
        .expect("from the way they were wound round");
    let bearing = |t: f64| right_seen_along_the_left_jaws(skill, world, t).0;
    (bearing(turning), bearing(arrived))
}

/// Fetching the tail as one body, the right keeps its bearing from the left's jaws as they turn;
/// following their shift only, it does not.
#[test]
fn fetching_the_tail_as_one_body_the_right_turns_with_the_left_jaws() {
    use knotlab_scenarios::expert::LeftFetch;
    let world = SimWorld::new(scene(), Rig::shipped().expect("the shipped rig")).expect("the scene builds");
    let geometry = coils_on_the_left();
    let fetch = geometry.left_fetches.clone().expect("the left fetches the tail");
    assert!(fetch.as_one_body);
    let wound = Vector3::from(geometry.left_jaw_direction.expect("a jaw direction")).normalize();
    let to = Vector3::from(fetch.jaw_direction).normalize();
    // As one body: the right keeps its bearing from the left's jaws as they turn to the tail.
    let skill = plan_instrument_tie(&world, &geometry, &Variation::none());
    let (before, after) = bearing_across_the_turn(&skill, &world, wound, to);
    println!(
        "as one body: the right {before:.3} rad from the left's jaws before their turn, {after:.3} after"
    );
    assert!((before - after).abs() < 0.05, "{before} rad before the turn, {after} rad after");
    // Following their shift only, it does not.
    let shifted = TieGeometry { left_fetches: Some(LeftFetch { as_one_body: false, ..fetch }), ..geometry };
    let skill = plan_instrument_tie(&world, &shifted, &Variation::none());
    let (before, after) = bearing_across_the_turn(&skill, &world, wound, to);
    println!("following the shift: {before:.3} rad before, {after:.3} after");
    assert!((before - after).abs() > 0.2, "{before} rad before the turn, {after} rad after");
}

/// During the fetch the right follows the left's shift by the share told or stands at the offset given
/// beside its jaws, and with `hinge_along_tail` the left's hinge lies along the tail.
#[test]
fn fetching_the_tail_the_right_follows_as_told_and_the_hinge_can_lie_along_the_tail() {
    use knotlab_hw::skill::Orientation;
    use knotlab_scenarios::expert::LeftFetch;
    let world = SimWorld::new(scene(), Rig::shipped().expect("the shipped rig")).expect("the scene builds");
    let shipped = TieGeometry::default();
    let fetch = shipped.left_fetches.clone().expect("the shipped left fetches the tail");
    assert_eq!((fetch.right_follows, fetch.hinge_along_tail), (1.0, false));
    let with = |fetch: LeftFetch| {
        let geometry = TieGeometry { left_fetches: Some(fetch), ..shipped.clone() };
        plan_instrument_tie(&world, &geometry, &Variation::none())
    };
    // The fetch: from the left's opening to take the tail to its closing on it.
    let fetch_window = |skill: &knotlab_hw::skill::Skill| {
        let left = skill.track(ArmName::Left).expect("the left");
        let opened = left.jaw.iter().find(|k| k.jaw_rad == shipped.take_tail_jaw_rad).expect("opens").time_s;
        let closed = left.jaw.iter().find(|k| k.time_s > opened && k.jaw_rad == 0.0).expect("closes").time_s;
        (opened, closed)
    };
    // How far the right's jaws go during the fetch.
    let right_moves_m = |skill: &knotlab_hw::skill::Skill| {
        let (from, to) = fetch_window(skill);
        let right = skill.track(ArmName::Right).expect("the right");
        let inside: Vec<Vector3<f64>> = right
            .poses
            .iter()
            .filter(|k| k.time_s >= from && k.time_s <= to)
            .map(|k| Vector3::from(k.world_position_m))
            .collect();
        inside.iter().map(|p| (p - inside[0]).norm()).fold(0.0, f64::max)
    };
    let all = right_moves_m(&with(fetch.clone()));
    let half = right_moves_m(&with(LeftFetch { right_follows: 0.5, ..fetch.clone() }));
    let none = right_moves_m(&with(LeftFetch { right_follows: 0.0, ..fetch.clone() }));
    println!("the right moves {:.1}, {:.1}, {:.1} mm", all * 1e3, half * 1e3, none * 1e3);
    assert!(all > 0.02, "the shipped right follows the left's shift: {all} m");
    assert!((half - 0.5 * all).abs() < 0.002, "half: {half} m of {all} m");
    assert!(none < 1e-6, "it stays: {none} m");
    // Beside the left's jaws instead: from the end of the fetch (before the left comes onto the
    // tail, 0.8 s, then closes, 0.4 s) to its closing, the right's jaw centre stands that far from
    // the left's (in the stitch frame).
    let offset_m = [-0.015, 0.0, 0.012];
    let beside = with(LeftFetch { right_beside_m: Some(offset_m), ..fetch.clone() });
    let (_, closed) = fetch_window(&beside);
    let centre_at = |arm: ArmName, time_s: f64| {
        let poses = &beside.track(arm).expect("the arm").poses;
        let key = poses.iter().rev().find(|k| k.time_s <= time_s + 1e-9).expect("a key");
        let tip = Vector3::from(key.world_position_m);
        let along = match key.orientation {
            Orientation::Frame { quaternion_xyzw: [x, y, z, w] } => {
                nalgebra::UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, y, z))
                    * Vector3::z()
            }
            Orientation::JawDirection { direction } => Vector3::from(direction).normalize(),
            Orientation::AlongShaft => (tip - trocar_of(world.config(), arm)).normalize(),
        };
        tip - along * knotlab_sim::world::JAW_CENTRE_OFFSET_M
    };
    let asked = world.tissue().world_from_tissue.rotation * Vector3::from(offset_m);
    for time_s in [closed - 1.25, closed - 0.8, closed] {
        let apart = centre_at(ArmName::Right, time_s) - centre_at(ArmName::Left, time_s);
        assert!(
            (apart - asked).norm() < 1e-3,
            "at {time_s} s the right stands {apart:?} from the left, not {asked:?}"
        );
    }

    // The hinge along the tail: the left holds a whole frame to the tail, its hinge (the frame's y)
    // across the jaws along the line from the entry point to the assist's jaws; without it the left
    // only points its jaws.
    let entry = world.tissue().hole_m(world.physics(), knotlab_sim::tissue::Flap::A);
    let jaws = world.tissue().world_from_tissue.rotation * Vector3::from(fetch.jaw_direction).normalize();
    let offset_m = knotlab_sim::world::JAW_CENTRE_OFFSET_M;
    let assist = (world.world_from_tip(ArmName::Assist) * nalgebra::Point3::new(0.0, 0.0, -offset_m)).coords;
    let tail = assist - entry;
    let across = (tail - jaws * tail.dot(&jaws)).normalize();
    let last_fetch_pose = |skill: &knotlab_hw::skill::Skill| {
        let (_, closed) = fetch_window(skill);
        let left = skill.track(ArmName::Left).expect("the left");
        left.poses.iter().rev().find(|k| k.time_s <= closed).expect("a pose").orientation
    };
    match last_fetch_pose(&with(LeftFetch { hinge_along_tail: true, ..fetch.clone() })) {
        Orientation::Frame { quaternion_xyzw: [x, y, z, w] } => {
            let q = nalgebra::UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, y, z));
            let (hinge, pointing) = (q * Vector3::y(), q * Vector3::z());
            assert!(pointing.dot(&jaws) > 0.999, "the jaws point {pointing:?}, not {jaws:?}");
            assert!(hinge.dot(&across).abs() > 0.999, "the hinge {hinge:?} is not along {across:?}");
        }
        other => panic!("the left holds {other:?}, not a frame"),
    }
    assert!(
        matches!(last_fetch_pose(&with(fetch)), Orientation::JawDirection { .. }),
        "the shipped left points its jaws"
    );
}

/// A run-down force stops and holds each pulling arm, the right draws to the point given, a presented
/// tail is taken short by the distance told, and a slower draw lengthens the plan by the difference.
#[test]
fn the_draw_and_the_run_down_go_as_the_geometry_says() {
    use knotlab_hw::skill::ForceAction;
    let world = SimWorld::new(scene(), Rig::shipped().expect("the shipped rig")).expect("the scene builds");
    let plan = |geometry: &TieGeometry| plan_instrument_tie(&world, geometry, &Variation::none());
    let shipped = plan(&TieGeometry::default());
    let end_s = |skill: &knotlab_hw::skill::Skill| {
        skill.tracks.iter().filter_map(|t| t.poses.last()).map(|k| k.time_s).fold(0.0, f64::max)
    };

    // A run-down force: each pulling arm stops where its gauge reads it and holds to its track's end.
    let stopping = plan(&TieGeometry { run_down_force_n: Some(2.5), ..TieGeometry::default() });
    for arm in [ArmName::Left, ArmName::Right] {
        let named = |skill: &knotlab_hw::skill::Skill, name: &str| {
            let track = skill.track(arm).expect("the arm pulls");
            track.events.iter().filter(|e| e.name == name).cloned().collect::<Vec<_>>()
        };
        assert!(named(&shipped, "run-down force").is_empty(), "{arm}: none unless asked");
        let stop = named(&stopping, "run-down force");
        assert_eq!(stop.len(), 1, "{arm}: one run-down stop");
        assert_eq!((stop[0].threshold_n, stop[0].action), (2.5, ForceAction::Hold));
        let set = &named(&stopping, "set force")[0];
        assert!(stop[0].from_s < set.from_s, "{arm}: the stop starts with the run-down, before the pulls");
        let last_key_s = stopping.track(arm).and_then(|t| t.poses.last()).map(|k| k.time_s);
        assert_eq!(Some(stop[0].until_s), last_key_s, "{arm}: held to the end");
    }

    // The right drawing to a point of the stitch frame: its jaw centre goes there (its tip within the
    // jaw-centre offset of it); the shipped right stays where it wound.
    let point = [0.02, -0.02, 0.012];
    let world_point = world.tissue().world_from_tissue * nalgebra::Point3::from(Vector3::from(point));
    let nearest_m = |skill: &knotlab_hw::skill::Skill| {
        let right = skill.track(ArmName::Right).expect("the right");
        right
            .poses
            .iter()
            .map(|k| (Vector3::from(k.world_position_m) - world_point.coords).norm())
            .fold(f64::INFINITY, f64::min)
    };
    let drawing = plan(&TieGeometry { right_draws_to_m: Some(point), ..TieGeometry::default() });
    let offset_m = knotlab_sim::world::JAW_CENTRE_OFFSET_M;
    assert!(nearest_m(&drawing) <= offset_m + 1e-3, "{} m", nearest_m(&drawing));
    assert!(nearest_m(&shipped) > offset_m + 5e-3, "{} m", nearest_m(&shipped));

    // A presented tail taken short: where the left's jaws start closing on it, they are that much
    // further back along themselves than taken at their centre.
    let closing_on_tail_m = |take_short_m: f64| {
        let geometry =
            TieGeometry { left_fetches: None, tail_take_short_m: take_short_m, ..TieGeometry::default() };
        let skill = plan(&geometry);
        let left = skill.track(ArmName::Left).expect("the left");
        // The jaw's closings: the second is on the tail (the first on the winding).
        let starts: Vec<f64> = left
            .jaw
            .windows(2)
            .filter(|w| w[1].jaw_rad == 0.0 && w[0].jaw_rad > 0.0)
            .map(|w| w[0].time_s)
            .collect();
        assert!(starts.len() >= 2, "{:?}", left.jaw);
        let target = left.target_at(starts[1]).expect("a target");
        target.world_position_m
    };
    let moved_m = (closing_on_tail_m(0.004) - closing_on_tail_m(0.0)).norm();
    assert!((moved_m - 0.004).abs() < 1e-4, "{moved_m} m");

    // A slower draw lengthens the plan by the difference.
    let slow = plan(&TieGeometry { draw_s: 4.0, ..TieGeometry::default() });
    let longer_s = end_s(&slow) - end_s(&shipped);
    assert!((2.7..3.5).contains(&longer_s), "{longer_s} s longer for a 2.8 s slower draw");
}

/// Before the draw the right carries the long end through the given points in order while the left holds
/// the tail still; the base plan's right goes nowhere near them.
#[test]
fn before_the_draw_the_right_carries_the_long_end_through_the_points_given() {
    let world = SimWorld::new(scene(), Rig::shipped().expect("the shipped rig")).expect("the scene builds");
    let route = [[0.005, -0.012, 0.042], [0.025, -0.01, 0.042]];
    let geometry = TieGeometry { right_before_draw_m: route.to_vec(), ..TieGeometry::default() };
    let skill = plan_instrument_tie(&world, &geometry, &Variation::none());
    let shipped = plan_instrument_tie(&world, &TieGeometry::default(), &Variation::none());
    // When the right's jaw centre first comes within 1 mm of a route point.
    let reached_s = |skill: &knotlab_hw::skill::Skill, p: [f64; 3]| {
        let world_point = world.tissue().world_from_tissue * nalgebra::Point3::from(Vector3::from(p));
        first_reaches(skill.track(ArmName::Right).expect("the right"), &world_point.coords)
    };
    let first_s = reached_s(&skill, route[0]).expect("the right goes to the first point");
    let second_s = reached_s(&skill, route[1]).expect("the right goes to the second point");
    assert!(first_s < second_s, "in order: {first_s} s, {second_s} s");
    assert!(reached_s(&shipped, route[1]).is_none(), "the shipped right does not go there");
    // Meanwhile the left holds the tail still; it draws back only afterwards.
    let left = skill.track(ArmName::Left).expect("the left");
    let at = |t: f64| Vector3::from(left.target_at(t).expect("a target").world_position_m);
    assert!((at(second_s) - at(first_s)).norm() < 1e-4, "the left moved while the right went round");
    let end_s = left.poses.last().expect("poses").time_s;
    assert!((at(end_s) - at(second_s)).norm() > 0.01, "the left draws and pulls afterwards");
}

/// The left runs down through the given points in order once the right is down, each leg taking the
/// run-down's time.
#[test]
fn the_left_runs_down_through_the_points_given_after_the_right_has_run_down() {
    let world = SimWorld::new(scene(), Rig::shipped().expect("the shipped rig")).expect("the scene builds");
    let via = [[0.01, 0.02, 0.05], [0.0, 0.03, 0.06]];
    let geometry = TieGeometry { left_run_down_via_m: via.to_vec(), ..TieGeometry::default() };
    let skill = plan_instrument_tie(&world, &geometry, &Variation::none());
    let shipped = plan_instrument_tie(&world, &TieGeometry::default(), &Variation::none());
    let reached_s = |skill: &knotlab_hw::skill::Skill, arm: ArmName, p: [f64; 3]| {
        let world_point = world.tissue().world_from_tissue * nalgebra::Point3::from(Vector3::from(p));
        first_reaches(skill.track(arm).expect("the arm runs down"), &world_point.coords)
    };
    let first_s = reached_s(&skill, ArmName::Left, via[0]).expect("the left goes to the first point");
    let second_s = reached_s(&skill, ArmName::Left, via[1]).expect("the left goes to the second point");
    let end_s =
        reached_s(&skill, ArmName::Left, geometry.left_run_down_to_m).expect("and on to its run-down's end");
    assert!(first_s < second_s && second_s < end_s, "in order: {first_s} s, {second_s} s, {end_s} s");
    assert!(reached_s(&shipped, ArmName::Left, via[0]).is_none(), "the shipped left does not go there");
    // The right makes its run-down in the left's first leg: it is down before the left goes on.
    let right_s =
        reached_s(&skill, ArmName::Right, geometry.right_run_down_to_m).expect("the right runs down");
    assert!(
        right_s < second_s,
        "the right is down at {right_s} s, the left at its second point at {second_s} s"
    );
    // Each leg takes the run-down's time: the plan is two legs longer.
    let last_s = |skill: &knotlab_hw::skill::Skill| {
        skill.track(ArmName::Left).and_then(|t| t.poses.last()).map(|k| k.time_s)
    };
    let longer_s = last_s(&skill).expect("poses") - last_s(&shipped).expect("poses");
    assert!(
        (longer_s - 2.0 * geometry.run_down_s).abs() < 0.5,
        "{longer_s} s longer for two legs of {} s",
        geometry.run_down_s
    );
}

/// The right runs down through the given points in order before its run-down's end, each leg taking the
/// run-down's time.
#[test]
fn the_right_runs_down_through_the_points_given_before_its_run_downs_end() {
    let world = SimWorld::new(scene(), Rig::shipped().expect("the shipped rig")).expect("the scene builds");
    let via = [[0.03, -0.02, 0.05], [0.02, -0.03, 0.04]];
    let geometry = TieGeometry { right_run_down_via_m: via.to_vec(), ..TieGeometry::default() };
    let skill = plan_instrument_tie(&world, &geometry, &Variation::none());
    let shipped = plan_instrument_tie(&world, &TieGeometry::default(), &Variation::none());
    let reached_s = |skill: &knotlab_hw::skill::Skill, p: [f64; 3]| {
        let world_point = world.tissue().world_from_tissue * nalgebra::Point3::from(Vector3::from(p));
        first_reaches(skill.track(ArmName::Right).expect("the right runs down"), &world_point.coords)
    };
    let first_s = reached_s(&skill, via[0]).expect("the right goes to the first point");
    let second_s = reached_s(&skill, via[1]).expect("the right goes to the second point");
    let end_s = reached_s(&skill, geometry.right_run_down_to_m).expect("and on to its run-down's end");
    assert!(first_s < second_s && second_s < end_s, "in order: {first_s} s, {second_s} s, {end_s} s");
    assert!(reached_s(&shipped, via[0]).is_none(), "the shipped right does not go there");
    // Each leg takes the run-down's time: the right is down two legs later than the shipped one.
    let shipped_end_s =
        reached_s(&shipped, geometry.right_run_down_to_m).expect("the shipped right runs down");
    assert!(
        (end_s - shipped_end_s - 2.0 * geometry.run_down_s).abs() < 0.5,
        "down at {end_s} s, the shipped right at {shipped_end_s} s, legs of {} s",
        geometry.run_down_s
    );
}

/// For the second throw the assist takes the tail the distance told from its end and closes on it before
/// the left opens, drawing it to the point given only once the left is open.
#[test]
fn for_the_second_throw_the_assist_takes_the_tail_near_its_end_and_draws_it_where_told() {
    use knotlab_scenarios::expert::{SecondThrow, plan_second_throw};
    let world = SimWorld::new(scene(), Rig::shipped().expect("the shipped rig")).expect("the scene builds");
    let line = world.thread_centreline();
    // 6 mm of thread back from the tail's free end (the last point of the centreline).
    let expected = from_tail_end(&line, 0.006).expect("a tail longer than 6 mm");
    let held_to = [0.0, 0.05, 0.04];
    let held_to_world = world.tissue().world_from_tissue * nalgebra::Point3::from(Vector3::from(held_to));
    let second = SecondThrow {
        tail_hold_from_end_m: Some(0.006),
        tail_held_to_m: Some(held_to),
        assist_presents: true,
        ..SecondThrow::default()
    };
    let geometry = TieGeometry { second_throw: Some(second), ..TieGeometry::default() };
    let skill = plan_second_throw(&world, &geometry, &Variation::none()).expect("a second throw");
    let assist = skill.track(ArmName::Assist).expect("the assist");
    let took_s =
        first_reaches(assist, &expected).expect("the assist's jaws go to the tail 6 mm from its end");
    let drew_s = first_reaches(assist, &held_to_world.coords).expect("then to where the tail is drawn");
    assert!(drew_s > took_s, "drawn after it is taken: {took_s} s, {drew_s} s");
    // The assist's jaws close on it before the left opens, and the draw starts once the left is open.
    let closed_s = assist.jaw.iter().find(|k| k.jaw_rad == 0.0).map(|k| k.time_s).expect("closes");
    let left = skill.track(ArmName::Left).expect("the left");
    let opened_s = left.jaw.iter().find(|k| k.jaw_rad > 0.0).map(|k| k.time_s).expect("the left opens");
    assert!(took_s < closed_s && closed_s < opened_s, "{took_s} s, {closed_s} s, {opened_s} s");
    assert!(drew_s > opened_s, "{drew_s} s, {opened_s} s");
}

/// Told to let go first, the left opens on the tail at the end of the first throw while the right keeps
/// the needle, each pull holding until the left is open; otherwise both stay shut.
#[test]
fn the_left_lets_go_of_the_first_throw_before_the_second_when_told() {
    use knotlab_scenarios::expert::SecondThrow;
    let world = SimWorld::new(scene(), Rig::shipped().expect("the shipped rig")).expect("the scene builds");
    let first = |left_lets_go_first: bool| {
        let second =
            SecondThrow { tail_hold_from_end_m: Some(0.006), left_lets_go_first, ..SecondThrow::default() };
        let geometry = TieGeometry { second_throw: Some(second), ..TieGeometry::default() };
        plan_instrument_tie(&world, &geometry, &Variation::none())
    };
    let last_jaw = |skill: &knotlab_hw::skill::Skill, arm: ArmName| {
        skill.track(arm).expect("the arm").jaw.last().expect("jaw keys").jaw_rad
    };
    // Held: both keep their jaws shut on the ends to the end of the first throw.
    let held = first(false);
    assert_eq!((last_jaw(&held, ArmName::Left), last_jaw(&held, ArmName::Right)), (0.0, 0.0));
    // Let go: the left opens on the tail, the right keeps the needle, and each pull's hold lasts until
    // the left's jaws are open.
    let let_go = first(true);
    assert!(last_jaw(&let_go, ArmName::Left) >= SimWorld::JAW_OPEN_RAD - 1e-9);
    assert_eq!(last_jaw(&let_go, ArmName::Right), 0.0);
    let left = let_go.track(ArmName::Left).expect("the left");
    let opened_s = left.jaw.last().expect("jaw keys").time_s;
    for arm in [ArmName::Left, ArmName::Right] {
        let track = let_go.track(arm).expect("the arm");
        let set = track.events.iter().find(|e| e.name == "set force").expect("a set force");
        assert!(
            set.until_s >= opened_s,
            "{arm}: the hold ends at {} s, the jaws open at {opened_s} s",
            set.until_s
        );
    }
}

/// With `tail_held_taut` the assist draws the tail only its share of the tail's length from the entry;
/// untold, it draws it to the point given.
#[test]
fn the_assist_draws_the_tail_no_further_than_its_share_of_the_tail_when_told() {
    use knotlab_scenarios::expert::tail::tail_length_to;
    use knotlab_scenarios::expert::{SecondThrow, plan_second_throw};
    let world = SimWorld::new(scene(), Rig::shipped().expect("the shipped rig")).expect("the scene builds");
    let entry = world.tissue().hole_m(world.physics(), knotlab_sim::tissue::Flap::A);
    let held_to = [0.0, 0.08, 0.06];
    let held_to_world =
        (world.tissue().world_from_tissue * nalgebra::Point3::from(Vector3::from(held_to))).coords;
    let length_m = tail_length_to(&world, 0.006).expect("a tail longer than 6 mm");
    let out = held_to_world - entry;
    assert!(out.norm() > 0.5 * length_m, "the point is within half the tail: {} m, {length_m} m", out.norm());
    let drawn_to = |taut: Option<f64>| {
        let second = SecondThrow {
            tail_hold_from_end_m: Some(0.006),
            tail_held_to_m: Some(held_to),
            tail_held_taut: taut,
            ..SecondThrow::default()
        };
        let geometry = TieGeometry { second_throw: Some(second), ..TieGeometry::default() };
        let skill = plan_second_throw(&world, &geometry, &Variation::none()).expect("a second throw");
        let assist = skill.track(ArmName::Assist).expect("the assist");
        // Where the assist's jaws stand as they let go of the tail: where it was drawn to.
        let closed_s = assist.jaw.iter().find(|k| k.jaw_rad == 0.0).expect("it takes the tail").time_s;
        let opened_s =
            assist.jaw.iter().find(|k| k.time_s > closed_s && k.jaw_rad > 0.0).expect("lets go").time_s;
        assist
            .poses
            .iter()
            .rfind(|k| k.time_s > closed_s && k.time_s <= opened_s)
            .map(|k| Vector3::from(k.world_position_m))
            .expect("a pose")
    };
    let offset_m = knotlab_sim::world::JAW_CENTRE_OFFSET_M;
    let untold = drawn_to(None);
    assert!((untold - held_to_world).norm() < offset_m + 1e-3, "drawn to the point: {untold:?}");
    let half = drawn_to(Some(0.5));
    let expected = entry + out * (0.5 * length_m / out.norm());
    println!("the tail {:.1} mm; drawn {:.1} mm from the entry", length_m * 1e3, (half - entry).norm() * 1e3);
    assert!((half - expected).norm() < offset_m + 1e-3, "drawn to {half:?}, not {expected:?}");
}

/// The assist offers the tail end the distance told beside the take point, not ahead of the left's jaws,
/// with its hinge along that offset so the thread crosses them.
#[test]
fn the_assist_offers_the_tail_end_beside_the_left_jaws_along_their_hinge() {
    use knotlab_hw::skill::Orientation;
    use knotlab_scenarios::expert::{SecondThrow, plan_second_throw};
    let world = SimWorld::new(scene(), Rig::shipped().expect("the shipped rig")).expect("the scene builds");
    let winding_point = [0.0, -0.01, 0.028];
    let second = SecondThrow {
        tail_hold_from_end_m: Some(0.006),
        assist_presents: true,
        tail_end_offered_m: Some(0.008),
        winding_point_m: winding_point,
        left_jaw_direction: Some([1.0, 0.0, 0.0]),
        ..SecondThrow::default()
    };
    let geometry = TieGeometry { second_throw: Some(second), ..TieGeometry::default() };
    let skill = plan_second_throw(&world, &geometry, &Variation::none()).expect("a second throw");
    // The point ahead of the left's jaws where the tail is to be taken.
    let world_from_stitch = world.tissue().world_from_tissue;
    let jaws = world_from_stitch.rotation * Vector3::x();
    let tail_point = (world_from_stitch * nalgebra::Point3::from(Vector3::from(winding_point))).coords
        + jaws * geometry.tail_ahead_m;
    // Where the assist holds still as the left closes on the tail (the left's last closing).
    let left = skill.track(ArmName::Left).expect("the left");
    let closing_s = left
        .jaw
        .windows(2)
        .rev()
        .find(|w| w[1].jaw_rad == 0.0 && w[0].jaw_rad > 0.0)
        .map(|w| w[0].time_s)
        .expect("the left closes on the tail");
    let assist = skill.track(ArmName::Assist).expect("the assist");
    let pose = assist.poses.iter().rev().find(|k| k.time_s <= closing_s).expect("a pose");
    let Orientation::Frame { quaternion_xyzw: [x, y, z, w] } = pose.orientation else {
        panic!("the assist holds a whole frame: {:?}", pose.orientation)
    };
    let rotation = nalgebra::UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, y, z));
    let jaw_centre = Vector3::from(pose.world_position_m)
        - rotation * Vector3::z() * knotlab_sim::world::JAW_CENTRE_OFFSET_M;
    let beside = jaw_centre - tail_point;
    assert!((beside.norm() - 0.008).abs() < 1e-3, "{} m from the take point", beside.norm());
    assert!(beside.dot(&jaws).abs() < 1e-3, "beside the left's jaws, not ahead: {beside:?}");
    // Its hinge (the tip frame's y) runs along that offset, so the thread crosses the left's jaws.
    let hinge = rotation * Vector3::y();
    assert!(hinge.dot(&beside.normalize()) > 0.99, "{hinge:?} {beside:?}");
}

/// The point `from_end_m` of thread back from the tail's free end (the centreline's last point).
fn from_tail_end(line: &[Vector3<f64>], mut from_end_m: f64) -> Option<Vector3<f64>> {
    for at in (1..line.len()).rev() {
        let step = line[at] - line[at - 1];
        if from_end_m <= step.norm() {
            return Some(line[at] - step.normalize() * from_end_m);
        }
        from_end_m -= step.norm();
    }
    None
}

/// When `track`'s jaw centre first comes within 1 mm of `point_m` (its tip within the jaw-centre
/// offset and 1 mm).
fn first_reaches(track: &knotlab_hw::skill::Track, point_m: &Vector3<f64>) -> Option<f64> {
    let offset_m = knotlab_sim::world::JAW_CENTRE_OFFSET_M;
    track
        .poses
        .iter()
        .find(|k| (Vector3::from(k.world_position_m) - point_m).norm() <= offset_m + 1e-3)
        .map(|k| k.time_s)
}

/// With `tail_brought_to_m` the assist brings the tail to the point given before the left opens to fetch
/// it, and the left fetches its share of the way there; the base plan's assist does not go there.
#[test]
fn once_wound_the_assist_brings_the_tail_where_told_before_the_left_fetches_it() {
    let world = SimWorld::new(scene(), Rig::shipped().expect("the shipped rig")).expect("the scene builds");
    let to_m = [0.0, 0.02, 0.03];
    let geometry = TieGeometry { tail_brought_to_m: Some(to_m), ..TieGeometry::default() };
    let skill = plan_instrument_tie(&world, &geometry, &Variation::none());
    let track = |arm| skill.track(arm).expect("the arm");
    let point = (world.tissue().world_from_tissue * nalgebra::Point3::from(Vector3::from(to_m))).coords;
    let brought_s = first_reaches(track(ArmName::Assist), &point).expect("the assist brings the tail");
    let opened_s = track(ArmName::Left)
        .jaw
        .iter()
        .find(|k| k.jaw_rad == geometry.take_tail_jaw_rad && k.time_s > 1.0)
        .expect("the left opens to take the tail")
        .time_s;
    assert!(brought_s <= opened_s, "brought at {brought_s} s, the left opened at {opened_s} s");
    // ... and the left fetches it there: its share of the way from the entry to the tail brought.
    let entry = world.tissue().hole_m(world.physics(), knotlab_sim::tissue::Flap::A);
    let along = geometry.left_fetches.as_ref().expect("the shipped fetch").along_tail;
    let on_tail = entry + (point - entry) * along;
    assert!(first_reaches(track(ArmName::Left), &on_tail).is_some_and(|t| t > opened_s));
    let shipped = plan_instrument_tie(&world, &TieGeometry::default(), &Variation::none());
    assert_eq!(first_reaches(shipped.track(ArmName::Assist).expect("the assist"), &point), None);
}

/// A winding pitch makes the right end its winding pitch times turns further along the left's jaws, from
/// the same start, and no further apart anywhere.
#[test]
fn the_winding_advances_along_the_jaws_by_its_pitch() {
    let world = SimWorld::new(scene(), Rig::shipped().expect("the shipped rig")).expect("the scene builds");
    let flat = TieGeometry::default();
    let pitch_m = 0.003;
    let helix = TieGeometry { winding_pitch_m: pitch_m, ..flat.clone() };
    let (flat_plan, helix_plan) = (
        plan_instrument_tie(&world, &flat, &Variation::none()),
        plan_instrument_tie(&world, &helix, &Variation::none()),
    );
    let right = |skill: &knotlab_hw::skill::Skill| skill.track(ArmName::Right).expect("the right").clone();
    let (flat_right, helix_right) = (right(&flat_plan), right(&helix_plan));
    let at = |track: &knotlab_hw::skill::Track, t: f64| {
        Vector3::from(track.target_at(t).expect("a target").world_position_m)
    };
    // The two plans part only in the winding: the right ends it `pitch * turns` further along the
    // left's jaws (they point at the right's trocar), and goes on from there.
    let winding_point =
        world.tissue().world_from_tissue * nalgebra::Point3::from(Vector3::from(flat.winding_point_m));
    let jaws = (trocar_of(world.config(), ArmName::Right) - winding_point.coords).normalize();
    let apart = |t: f64| at(&helix_right, t) - at(&flat_right, t);
    let widest = flat_right
        .poses
        .iter()
        .map(|k| apart(k.time_s))
        .max_by(|a, b| a.norm().total_cmp(&b.norm()))
        .expect("poses");
    let advance_m = pitch_m * flat.winding_turns;
    assert!(
        (widest.norm() - advance_m).abs() < 5e-4,
        "{} m apart at most, {advance_m} m expected",
        widest.norm()
    );
    assert!(widest.normalize().dot(&jaws) > 0.99, "apart along {widest:?}, not the jaws {jaws:?}");
    assert!(apart(0.0).norm() < 1e-9, "the same start");
}

/// A throw wound on the assist's jaws starts with a hand-over: the assist takes the tail's end before the
/// left lets go, the left retakes it further up before the assist opens, and only the assist winds.
#[test]
fn a_second_throw_on_the_assists_jaws_begins_with_the_tail_handed_over_and_taken_back() {
    use knotlab_scenarios::expert::{SecondThrow, plan_second_throw, plan_tail_hand_over};
    let world = SimWorld::new(scene(), Rig::shipped().expect("the shipped rig")).expect("the scene builds");
    let winding_point = [-0.012, 0.01, 0.028];
    let second = SecondThrow {
        tail_hold_from_end_m: Some(0.004),
        left_retakes_from_end_m: Some(0.017),
        assist_presents: true,
        winding_point_m: winding_point,
        left_jaw_direction: Some([-1.0, 0.0, 0.0]),
        ..SecondThrow::default()
    };
    let with = |second: SecondThrow| TieGeometry { second_throw: Some(second), ..TieGeometry::default() };
    let geometry = with(second.clone());
    let none = Variation::none();
    // Only a throw wound on the assist's jaws has a hand-over of its own.
    assert!(
        plan_tail_hand_over(&world, &with(SecondThrow { left_retakes_from_end_m: None, ..second }), &none)
            .is_none()
    );
    let line = world.thread_centreline();
    // The hand-over: the assist closes on the tail 4 mm from its end, then the left lets go.
    let hand_over = plan_tail_hand_over(&world, &geometry, &none).expect("a hand-over");
    let assist = hand_over.track(ArmName::Assist).expect("the assist");
    let left = hand_over.track(ArmName::Left).expect("the left");
    let took_s =
        first_reaches(assist, &from_tail_end(&line, 0.004).expect("a tail")).expect("goes to the tail's end");
    let closed_s = assist.jaw.iter().find(|k| k.jaw_rad == 0.0).map(|k| k.time_s).expect("closes");
    let opened_s = left.jaw.iter().find(|k| k.jaw_rad > 0.0).map(|k| k.time_s).expect("the left opens");
    assert!(took_s < closed_s && closed_s < opened_s, "{took_s} s, {closed_s} s, {opened_s} s");
    // Then (planned on the world as the hand-over leaves it; here, as it is) the left closes on the
    // tail 17 mm from its end, the assist lets go, and the assist's jaws, not the left's, go to the
    // winding point.
    let skill = plan_second_throw(&world, &geometry, &none).expect("a second throw");
    let assist = skill.track(ArmName::Assist).expect("the assist");
    let left = skill.track(ArmName::Left).expect("the left");
    let retake_s =
        first_reaches(left, &from_tail_end(&line, 0.017).expect("a tail")).expect("the left retakes");
    let left_closed_s =
        left.jaw.iter().find(|k| k.jaw_rad == 0.0 && k.time_s >= retake_s).map(|k| k.time_s).expect("closes");
    let assist_opened_s = assist.jaw.iter().find(|k| k.jaw_rad > 0.0).map(|k| k.time_s).expect("opens");
    assert!(
        retake_s < left_closed_s && left_closed_s < assist_opened_s,
        "{retake_s} s, {left_closed_s} s, {assist_opened_s} s"
    );
    let winding_world =
        world.tissue().world_from_tissue * nalgebra::Point3::from(Vector3::from(winding_point));
    let wound_s = first_reaches(assist, &winding_world.coords).expect("the assist goes to the winding point");
    assert!(wound_s > assist_opened_s, "{wound_s} s after {assist_opened_s} s");
    assert!(first_reaches(left, &winding_world.coords).is_none(), "the left stays away");
}

/// The second throw presents the tail `tail_ahead_m` ahead of the left's jaws: 4 mm ahead and taken 4 mm
/// short, the left closes where it wound; untold, it moves on along its jaws as in the first throw.
#[test]
fn the_second_throw_presents_the_tail_as_far_ahead_of_the_left_jaws_as_told() {
    use knotlab_scenarios::expert::{SecondThrow, plan_second_throw};
    let world = SimWorld::new(scene(), Rig::shipped().expect("the shipped rig")).expect("the scene builds");
    let winding_point = [0.022, 0.01, 0.03];
    let jaws = Vector3::new(1.0, 0.0, -0.3).normalize();
    // Where the left's jaw centre is as it closes on the tail, from where it wound (stitch frame is
    // the world turned: the tissue is level).
    let closes_at = |tail_ahead_m: Option<f64>| {
        let second = SecondThrow {
            tail_hold_from_end_m: Some(0.008),
            assist_presents: true,
            tail_end_offered_m: Some(0.004),
            tail_ahead_m,
            tail_take_short_m: Some(0.004),
            winding_point_m: winding_point,
            left_jaw_direction: Some(jaws.into()),
            ..SecondThrow::default()
        };
        // Wound round jaws open as far as they open to take the tail (and let go of it before): the
        // left's first closing after it lets go is on the presented tail.
        let geometry = TieGeometry {
            winding_jaw_rad: 0.6,
            take_tail_jaw_rad: 0.6,
            second_throw: Some(second),
            ..TieGeometry::default()
        };
        let skill = plan_second_throw(&world, &geometry, &Variation::none()).expect("a second throw");
        let jaw = &skill.track(ArmName::Left).expect("the left").jaw;
        let opened = jaw.iter().position(|k| (k.jaw_rad - 0.6).abs() < 1e-9).expect("opened");
        let closed = jaw[opened..].iter().find(|k| k.jaw_rad < 0.6).expect("closes on the tail");
        let closing_s = jaw[opened..].iter().rev().find(|k| k.time_s < closed.time_s).expect("a key").time_s;
        let (centre, _) = jaws_at(&skill, &world, ArmName::Left, closing_s);
        let wound_at =
            (world.tissue().world_from_tissue * nalgebra::Point3::from(Vector3::from(winding_point))).coords;
        world.tissue().world_from_tissue.rotation.inverse() * (centre - wound_at)
    };
    // Presented 4 mm ahead of the jaw centre and taken 4 mm short of it: the left closes where it
    // wound, without moving on to the tail.
    let in_place = closes_at(Some(0.004));
    assert!(in_place.norm() < 1e-6, "{} m from the winding point", in_place.norm());
    // As the first throw (12 mm ahead), it goes on 8 mm along its jaws to the tail.
    let moved = closes_at(None);
    assert!((moved - jaws * 0.008).norm() < 1e-6, "moved {moved:?}");
}

//! The rules of skill synthesis, on a synthetic demonstration learned with the shipped pattern: the
//! force-controlled primitive goes on to 125 % of its line and comes back, stopping at the recorded
//! force and opening the jaw when the demonstration's opened, and (on the shipped recording, whose
//! pull is held before the jaws open) goes on as soon as it comes to rest; no primitive starts before the primitives it waits for are done, and a
//! longer one delays those that wait; a skill made at a moved stitch is the nominal one moved, and an
//! instrument starting turned otherwise than its first key is turned by the way in; the fluid method
//! regenerates the 2D primitive; the replay baseline plays the demonstration back.

use std::path::Path;

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};

use knotlab_hw::kinematics::TipTarget;
use knotlab_hw::rig::ArmName;
use knotlab_hw::skill::{ForceAction, Orientation, Skill, Track};
use knotlab_learner::demonstration::{Demonstration, load_demonstration};
use knotlab_learner::fluid::ObstacleMask;
use knotlab_learner::pattern::load_pattern;
use knotlab_learner::primitive::{ForcePrimitive, KnowledgeBase, Primitive, learn};
use knotlab_learner::synthesis::site::pose_isometry;
use knotlab_learner::synthesis::{
    AT_REST_M, ApproachSettings, Method, PrimitiveSettings, REACH_MARGIN_M, Reach, ReplaySettings, Schedule,
    Site, StartPose, Synthesis, Trocars, prepend_approach, relocation, replay, synthesize, takes,
};
use knotlab_learner::synthetic::{SyntheticSettings, canonical_demonstration};

fn learned(seed: u64) -> (KnowledgeBase, Demonstration) {
    let pattern =
        load_pattern(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenarios/patterns/knot_tying.toml"))
            .expect("the shipped pattern loads");
    let (demo, _) = canonical_demonstration(&SyntheticSettings::canonical(seed, 100.0));
    (learn(&demo, &pattern).expect("the synthetic demonstration is learned"), demo)
}

/// The shipped demonstration (the scripted expert's recording) learned with the shipped pattern.
fn shipped_learned() -> (KnowledgeBase, Demonstration) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let demo =
        load_demonstration(&root.join("scenarios/demos/instrument-tie")).expect("the shipped demonstration");
    let pattern =
        load_pattern(&root.join("scenarios/patterns/knot_tying.toml")).expect("the shipped pattern");
    (learn(&demo, &pattern).expect("the shipped demonstration is learned"), demo)
}

fn trocars(world_from_stitch: &Isometry3<f64>) -> Trocars {
    // Trocars 8 cm above the stitch, spread as the scene's are.
    let at = |x: f64, y: f64| world_from_stitch.transform_point(&nalgebra::Point3::new(x, y, 0.08)).coords;
    Trocars(vec![
        (ArmName::Left, at(-0.08, 0.12)),
        (ArmName::Right, at(-0.08, -0.12)),
        (ArmName::Assist, at(0.12, 0.1)),
    ])
}

/// Every instrument starts where the demonstration's did, relative to `world_from_stitch`.
fn starts(kb: &KnowledgeBase, demo: &Demonstration, world_from_stitch: &Isometry3<f64>) -> Vec<StartPose> {
    let moved = relocation(&pose_isometry(&kb.world_from_stitch), world_from_stitch);
    demo.instruments
        .iter()
        .map(|r| {
            let s = &r.samples[0];
            let world_from_tip = Isometry3::from_parts(Translation3::from(s.position_m), s.world_from_tip());
            StartPose { arm: r.instrument, world_from_tip: moved * world_from_tip }
        })
        .collect()
}

fn make(
    kb: &KnowledgeBase,
    demo: &Demonstration,
    method: Method,
    world_from_stitch: Isometry3<f64>,
) -> Synthesis {
    make_within(kb, demo, method, world_from_stitch, None)
}

/// [`make`] with the instruments' reach.
fn make_within(
    kb: &KnowledgeBase,
    demo: &Demonstration,
    method: Method,
    world_from_stitch: Isometry3<f64>,
    reach: Option<Reach<'_>>,
) -> Synthesis {
    let trocars = trocars(&world_from_stitch);
    let starts = starts(kb, demo, &world_from_stitch);
    let site = Site { new_world_from_stitch: world_from_stitch, trocars: &trocars, starts: &starts, reach };
    let mut free = |_: &str, _: ArmName, _: &_, region: &knotlab_learner::fluid::GridRegion| {
        Ok(ObstacleMask::free(region.n))
    };
    synthesize(kb, method, &site, &PrimitiveSettings::default(), &mut free).expect("synthesis")
}

fn track(skill: &Skill, arm: ArmName) -> &Track {
    skill.track(arm).unwrap_or_else(|| panic!("a track for {arm}"))
}

fn position(track: &Track, t: f64) -> Vector3<f64> {
    track.target_at(t).expect("keys").world_position_m
}

fn nominal(kb: &KnowledgeBase) -> Isometry3<f64> {
    pose_isometry(&kb.world_from_stitch)
}

/// A force-controlled primitive drives on to 125 % of its line and back with its jaw held closed; its
/// events stop the tip at the recorded maximum force and open the jaw as long after the start as the
/// demonstration's opened, or at that force if it comes later.
#[test]
fn a_force_controlled_primitive_goes_on_to_125_percent_and_comes_back_opening_at_the_recorded_force() {
    let (kb, demo) = learned(31);
    let made = make(&kb, &demo, Method::Dmp, nominal(&kb));
    let settings = PrimitiveSettings::default();
    {
        let (name, arm) = ("R5", ArmName::Right);
        let Some(Primitive::Force(p)) = kb.primitive(name) else { panic!("{name} is force-controlled") };
        let slot = made.schedule.slot(name).expect("scheduled");
        let t = track(&made.skill, arm);
        assert_force_events(t, p, slot.new_s);
        // Along the line from the start to where the demonstration came to rest: on to 125 %, back to 100 %.
        let world = nominal(&kb);
        let start = world * nalgebra::Point3::from(Vector3::from(p.start_pose.position_m));
        let end = world * nalgebra::Point3::from(Vector3::from(p.line_end_m));
        let line = end - start;
        let progress = |x: Vector3<f64>| (x - start.coords).dot(&line) / line.norm_squared();
        let samples: Vec<f64> =
            (0..=1000).map(|k| slot.new_s.0 + (slot.new_s.1 - slot.new_s.0) * k as f64 / 1000.0).collect();
        let furthest = samples.iter().map(|&s| progress(position(t, s))).fold(f64::MIN, f64::max);
        assert!(
            (furthest - settings.force_elongation).abs() < 0.03,
            "{name}: reaches {furthest:.3} of its line (the rule: {})",
            settings.force_elongation
        );
        let back = position(t, slot.new_s.1);
        assert!((back - end.coords).norm() < 1e-9, "{name}: comes back to the line's end");
        // Closed until the window ends, open after it.
        assert_eq!(t.jaw_at(slot.new_s.0 + 0.5), Some(p.jaw.from_rad), "{name}: holds while pulling");
        assert!((t.jaw_at(slot.new_s.1).unwrap() - p.jaw.to_rad).abs() < 1e-12, "{name}: open at the end");
    }
}

/// A force-controlled primitive whose demonstration held its pull before letting go (the shipped
/// recording's R5 comes to rest with the knot snug and holds it there for seconds before the jaws
/// open) goes on along its line as soon as the demonstrated movement comes to rest, while the other
/// instruments still hold what they held, not after the hold; it stops at the recorded force and
/// lets go when the demonstration did.
#[test]
fn a_pull_held_before_letting_go_goes_on_from_its_rest() {
    let (kb, demo) = shipped_learned();
    let Some(Primitive::Force(p)) = kb.primitive("R5") else { panic!("R5 is force-controlled") };
    let world = nominal(&kb);
    let made = make(&kb, &demo, Method::Fluid, world);
    let slot = made.schedule.slot("R5").expect("scheduled");
    let t = track(&made.skill, ArmName::Right);
    let start = world * nalgebra::Point3::from(Vector3::from(p.start_pose.position_m));
    let end = world * nalgebra::Point3::from(Vector3::from(p.line_end_m));
    let line = end - start;
    let progress = |x: Vector3<f64>| (x - start.coords).dot(&line) / line.norm_squared();
    // Where the demonstrated right came to rest, and how long it held there before its jaws opened.
    let right = demo.instruments.iter().find(|r| r.instrument == ArmName::Right).expect("a right");
    let rest_s = right
        .samples
        .iter()
        .rev()
        .filter(|s| s.time_s >= p.start_s && s.time_s <= p.end_s)
        .take_while(|s| (Vector3::from(s.position_m) - end.coords).norm() <= AT_REST_M)
        .last()
        .map(|s| s.time_s)
        .expect("R5 ends at rest");
    let held_s = p.start_s + p.jaw.at_s - rest_s;
    assert!(held_s > 2.0, "the demonstration held its pull {held_s:.2} s before letting go");
    // On to 125 % of its line a quarter of the pull's time after it came to rest, long before the
    // demonstrated hold ends; still there as the hold ends.
    let settings = PrimitiveSettings::default();
    let pulled_s = rest_s - p.start_s;
    for at_s in
        [slot.new_s.0 + settings.force_elongation * pulled_s + 0.01, slot.new_s.0 + (p.end_s - p.start_s)]
    {
        let reached = progress(position(t, at_s));
        assert!(
            (reached - settings.force_elongation).abs() < 0.01,
            "{:.2} s into the slot the pull is at {reached:.3} of its line (expected {})",
            at_s - slot.new_s.0,
            settings.force_elongation
        );
    }
    assert_force_events(t, p, slot.new_s);
}

/// `t`'s events for the force-controlled `p` in its slot `slot_s`: named `p`, the tip held from the
/// recorded maximum force to the slot's end; `p` "lets go", the jaw opened from as long into the
/// slot as the demonstration's opened, at that force or with the hold.
fn assert_force_events(t: &Track, p: &ForcePrimitive, slot_s: (f64, f64)) {
    let event = |name: &str| t.events.iter().find(|e| e.name == name).expect("a force event");
    let hold = event(&p.name);
    assert_eq!(hold.threshold_n, p.max_force_n);
    assert_eq!((hold.from_s, hold.until_s), slot_s);
    assert_eq!(hold.action, ForceAction::Hold);
    let lets_go = event(&format!("{} lets go", p.name));
    assert_eq!(lets_go.threshold_n, p.max_force_n);
    assert_eq!((lets_go.from_s, lets_go.until_s), (slot_s.0 + p.jaw.at_s, slot_s.1));
    assert_eq!(lets_go.fires_with.as_deref(), Some(p.name.as_str()));
    assert_eq!(lets_go.action, ForceAction::OpenJaw { jaw_rad: p.jaw.to_rad });
}

/// An instrument that starts turned otherwise than the demonstration's first key, moved, turns it
/// (the scene's right holds the needle along its shaft; at a turned and tilted site the moved
/// demonstration's first frame is bent tens of degrees from that) is turned by the way in, at its
/// pace, before the skill starts: the skill's first key is the tip where it is, turned as that first
/// key. Started as the instrument is, the skill would turn it in its first tenth of a second, which
/// the arm follows joint by joint at full speed, its tip swinging centimetres out and back.
#[test]
fn an_instrument_starting_turned_otherwise_is_turned_by_the_way_in() {
    let (kb, demo) = shipped_learned();
    let world = nominal(&kb)
        * UnitQuaternion::from_axis_angle(&Vector3::z_axis(), (-23.5f64).to_radians())
        * UnitQuaternion::from_axis_angle(&Vector3::x_axis(), (-13.7f64).to_radians());
    let trocars = trocars(&world);
    let mut starts = starts(&kb, &demo, &world);
    // The right starts with its jaws along its shaft, as the scene puts it.
    let trocar = trocars.of(ArmName::Right).expect("a right trocar");
    for start in starts.iter_mut().filter(|s| s.arm == ArmName::Right) {
        let tip = start.world_from_tip.translation.vector;
        let along = UnitQuaternion::rotation_between(&Vector3::z(), &(tip - trocar)).expect("a shaft");
        start.world_from_tip.rotation = along;
    }
    let site = Site { new_world_from_stitch: world, trocars: &trocars, starts: &starts, reach: None };
    let mut free = |_: &str, _: ArmName, _: &_, region: &knotlab_learner::fluid::GridRegion| {
        Ok(ObstacleMask::free(region.n))
    };
    let mut skill = synthesize(&kb, Method::Fluid, &site, &PrimitiveSettings::default(), &mut free)
        .expect("synthesis")
        .skill;
    let settings = ApproachSettings::default();
    let lead_s = prepend_approach(&mut skill, &starts, &settings);
    let right = track(&skill, ArmName::Right);
    let frame = |k: &knotlab_hw::skill::PoseKey| match k.orientation {
        Orientation::Frame { quaternion_xyzw: [x, y, z, w] } => {
            Some(UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, y, z)))
        }
        _ => None,
    };
    let first = right.poses.iter().find(|k| k.time_s >= lead_s - 1e-9).expect("a key after the way in");
    let turn = frame(first).expect("the first key is a frame").angle_to(&along_shaft_of(&starts));
    assert!(turn > 0.3, "the demonstration's first frame, moved, is turned {turn:.2} rad from the start");
    assert!(
        lead_s >= turn / settings.turn_rad_per_s - 1e-6,
        "the way in ({lead_s:.2} s) makes the {turn:.2} rad turn at its pace"
    );
    // From the way in's end on, the tip turns no faster than a hand does.
    let keys: Vec<_> =
        right.poses.iter().filter(|k| k.time_s >= lead_s - 1e-9 && k.time_s <= lead_s + 1.0).collect();
    for pair in keys.windows(2) {
        let (a, b) = (frame(pair[0]), frame(pair[1]));
        let (Some(a), Some(b)) = (a, b) else { panic!("{:.3} s: a key without a frame", pair[1].time_s) };
        let rate = a.angle_to(&b) / (pair[1].time_s - pair[0].time_s);
        assert!(rate < 1.0, "{:.3} s: the tip turns at {rate:.2} rad/s", pair[1].time_s);
    }
}

/// The right's start frame in `starts`.
fn along_shaft_of(starts: &[StartPose]) -> UnitQuaternion<f64> {
    starts.iter().find(|s| s.arm == ArmName::Right).expect("a right").world_from_tip.rotation
}

/// A force-controlled pull that would leave the instrument's reach stops where the reach ends, short
/// of 125 % of its line (here the right reaches 110 % of R5's line, less the 2 mm margin), and still
/// comes back to the line's end; with the reach ending before the line's end it pulls to the end, as
/// demonstrated.
#[test]
fn a_force_controlled_pull_stops_where_the_instruments_reach_ends() {
    let (kb, demo) = learned(31);
    let world = nominal(&kb);
    let Some(Primitive::Force(p)) = kb.primitive("R5") else { panic!("R5 is force-controlled") };
    let start = world * nalgebra::Point3::from(Vector3::from(p.start_pose.position_m));
    let end = world * nalgebra::Point3::from(Vector3::from(p.line_end_m));
    let line = end - start;
    let progress = |x: Vector3<f64>| (x - start.coords).dot(&line) / line.norm_squared();
    for (reaches_to, furthest_expected) in [(1.1, 1.1 - REACH_MARGIN_M / line.norm()), (0.9, 1.0)] {
        let reaches = |arm: ArmName, target: &TipTarget| {
            arm != ArmName::Right || progress(target.world_position_m) <= reaches_to
        };
        let made = make_within(&kb, &demo, Method::Fluid, world, Some(Reach(&reaches)));
        let slot = made.schedule.slot("R5").expect("scheduled");
        let t = track(&made.skill, ArmName::Right);
        let furthest = (0..=1000)
            .map(|k| slot.new_s.0 + (slot.new_s.1 - slot.new_s.0) * k as f64 / 1000.0)
            .map(|s| progress(position(t, s)))
            .fold(f64::MIN, f64::max);
        assert!(
            (furthest - furthest_expected).abs() < 0.005,
            "reaching {reaches_to} of the line, the pull went to {furthest:.4} (expected {furthest_expected:.4})"
        );
        assert!((position(t, slot.new_s.1) - end.coords).norm() < 1e-9, "back to the line's end");
    }
}

/// No primitive starts before the ones it waits for end, one taking 3 s longer delays those waiting by
/// 3 s, and the right moves no more before its first primitive than it did in the demonstration.
#[test]
fn no_primitive_starts_before_those_it_waits_for_and_a_longer_one_delays_them() {
    let (kb, demo) = learned(32);
    assert!(!kb.dependencies.is_empty(), "the pattern's `after`s become dependencies");
    let made = make(&kb, &demo, Method::Dmp, nominal(&kb));
    for d in &kb.dependencies {
        let (p, q) = (made.schedule.slot(&d.primitive).unwrap(), made.schedule.slot(&d.after).unwrap());
        assert!(
            p.new_s.0 >= q.new_s.1 + d.pause_s - 1e-9,
            "{} starts before {} allows",
            d.primitive,
            d.after
        );
    }
    // R2 waits for L1: L1 taking 3 s longer delays R2 (and everything after it) by 3 s.
    let slower = Schedule::plan(&kb, |p: &Primitive| {
        let (a, b) = p.span_s();
        if p.name() == "L1" { b - a + 3.0 } else { b - a }
    })
    .unwrap();
    let plain = Schedule::plan(&kb, |p: &Primitive| p.span_s().1 - p.span_s().0).unwrap();
    for name in ["R2", "L2", "L3", "L4", "A1", "L5", "R3", "L6", "R4", "R5"] {
        let delay = slower.slot(name).unwrap().new_s.0 - plain.slot(name).unwrap().new_s.0;
        assert!((delay - 3.0).abs() < 1e-9, "{name} delayed by {delay} s");
    }
    // At the demonstration's own pace the plan is the demonstration's timing.
    for slot in &plain.slots {
        assert!(
            (slot.new_s.0 - slot.demo_s.0).abs() < 1e-9,
            "{}: {:?} vs {:?}",
            slot.name,
            slot.new_s,
            slot.demo_s
        );
    }
    // The skill's right instrument holds still until R2 is due (it has no primitive before).
    let right = track(&made.skill, ArmName::Right);
    let r2 = made.schedule.slot("R2").unwrap().new_s.0;
    let first = position(right, 0.0);
    let before = position(right, r2 - 1.0);
    let moved_before: f64 = demo
        .instrument(ArmName::Right)
        .unwrap()
        .samples
        .iter()
        .take_while(|s| s.time_s < r2 - 1.0)
        .map(|s| (s.position_m - demo.instrument(ArmName::Right).unwrap().samples[0].position_m).norm())
        .fold(0.0, f64::max);
    assert!(
        (before - first).norm() <= moved_before + 1e-3,
        "the right moved before R2 more than demonstrated"
    );
}

/// A fluid or DMP skill made at a moved stitch is the nominal skill moved, within 0.2 mm, with the same
/// timing and jaw keys: shifted and turned about the tissue's normal, and shifted and tilted about the
/// wound (a wound on a sloped surface).
#[test]
fn a_skill_made_at_a_moved_stitch_is_the_nominal_skill_moved() {
    let (kb, demo) = learned(33);
    let here = nominal(&kb);
    let turned = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 25f64.to_radians());
    let wound = nalgebra::Unit::new_normalize(here.rotation * Vector3::x());
    let tilted = UnitQuaternion::from_axis_angle(&wound, 15f64.to_radians());
    for (site, rotation) in [("turned", turned), ("tilted", tilted)] {
        let shift = Vector3::new(0.02, -0.015, 0.01);
        // The motion turns about the stitch.
        let there = Isometry3::from_parts(
            Translation3::from(here.translation.vector + shift),
            rotation * here.rotation,
        );
        let moved = relocation(&here, &there);
        for method in [Method::Fluid, Method::Dmp] {
            let a = make(&kb, &demo, method, here);
            let b = make(&kb, &demo, method, there);
            for (ta, tb) in a.skill.tracks.iter().zip(&b.skill.tracks) {
                assert_eq!(ta.poses.len(), tb.poses.len(), "{site}, {method}: {} keys", ta.arm);
                for (ka, kb_) in ta.poses.iter().zip(&tb.poses) {
                    let pa = moved.transform_point(&Vector3::from(ka.world_position_m).into()).coords;
                    let err = (pa - Vector3::from(kb_.world_position_m)).norm();
                    assert!(
                        err < 2e-4,
                        "{site}, {method} {} at {:.2} s: {err:.2e} m from the nominal key moved",
                        ta.arm,
                        ka.time_s
                    );
                    assert!((ka.time_s - kb_.time_s).abs() < 1e-9);
                }
                assert_eq!(ta.jaw, tb.jaw);
            }
        }
    }
}

/// Fluid and DMP skills at the demonstration's site follow the demonstrated winding in shape and pace
/// (under 3 mm at worst), and the fluid run has a finite, non-flat pressure field.
#[test]
fn the_fluid_regenerates_the_winding_and_dmp_reproduces_it() {
    let (kb, demo) = learned(34);
    let Some(Primitive::TwoD(r2)) = kb.primitive("R2") else { panic!("R2 is 2D") };
    let world = nominal(&kb);
    let demonstrated: Vec<(f64, Vector3<f64>)> = demo
        .instrument(ArmName::Right)
        .unwrap()
        .samples
        .iter()
        .filter(|s| s.time_s >= r2.start_s && s.time_s <= r2.end_s)
        .map(|s| (s.time_s, s.position_m))
        .collect();
    for method in [Method::Fluid, Method::Dmp] {
        let made = make(&kb, &demo, method, world);
        assert_eq!(made.fluid.len(), usize::from(method == Method::Fluid), "{method}: fluid runs");
        if let Some((_, inst)) = made.fluid.first() {
            // The stirred fluid has a pressure field (finite, not flat) beside its velocity.
            let p = &inst.cell_pressure_m2ps2;
            assert_eq!(p.len(), inst.region.n * inst.region.n);
            assert!(p.iter().all(|x| x.is_finite()));
            let (lo, hi) = p.iter().fold((f64::MAX, f64::MIN), |(a, b), x| (a.min(*x), b.max(*x)));
            assert!(hi - lo > 0.0, "a flat pressure field");
        }
        let slot = made.schedule.slot("R2").unwrap();
        let right = track(&made.skill, ArmName::Right);
        // At the demonstration's own site the new path is where the hand was, when it was there:
        // shape and pace are kept, within about a fluid cell (0.8 mm here) or the DMP's fit.
        let errors: Vec<f64> = demonstrated
            .iter()
            .map(|(t, d)| (position(right, slot.new_s.0 + (t - r2.start_s)) - d).norm())
            .collect();
        let worst = errors.iter().copied().fold(0.0, f64::max);
        let mean = errors.iter().sum::<f64>() / errors.len() as f64;
        eprintln!("{method}: {:.2} mm at worst, {:.2} mm on average", worst * 1e3, mean * 1e3);
        assert!(
            worst < 3e-3 && mean < 1.5e-3,
            "{method}: {:.2} mm at worst, {:.2} mm on average",
            worst * 1e3,
            mean * 1e3
        );
    }
}

/// Replay plays every instrument's recorded positions and jaws back moved by the site's motion, and
/// refuses a NaN key period.
#[test]
fn replay_plays_the_demonstration_back_moved() {
    let (kb, demo) = learned(35);
    let here = nominal(&kb);
    let motion = Isometry3::new(Vector3::new(0.01, 0.02, 0.0), Vector3::new(0.0, 0.0, 0.3));
    let skill =
        replay(&demo, &motion, &trocars(&(motion * here)), &ReplaySettings { key_period_s: 0.0 }).unwrap();
    for record in &demo.instruments {
        let t = track(&skill, record.instrument);
        for s in record.samples.iter().step_by(37) {
            let expected = motion.transform_point(&s.position_m.into()).coords;
            assert!((position(t, s.time_s) - expected).norm() < 1e-12);
            assert!((t.jaw_at(s.time_s).unwrap() - s.jaw_rad).abs() < 1e-12);
        }
    }
    assert!(replay(&demo, &motion, &trocars(&here), &ReplaySettings { key_period_s: f64::NAN }).is_err());
}

/// A key moved from the demonstration keeps its frame where the wrist is bent: commanded by the jaws'
/// direction alone, the fluid and DMP skills rolled the right's jaws otherwise than recorded at the
/// canonical stitch and tore the needle out of them (17.4 and 26.5 N).
#[test]
fn keys_moved_from_the_demonstration_keep_its_frame_where_the_wrist_is_bent() {
    let (kb, demo) = learned(36);
    let world_from_stitch = Isometry3::new(Vector3::new(0.01, -0.02, 0.0), Vector3::new(0.0, 0.0, 0.4));
    let made = make(&kb, &demo, Method::Fluid, world_from_stitch);
    let moved = relocation(&nominal(&kb), &world_from_stitch);
    let trocars = trocars(&world_from_stitch);
    let (mut frames, mut checked) = (0, 0);
    for record in &demo.instruments {
        let t = track(&made.skill, record.instrument);
        let trocar = trocars.of(record.instrument).unwrap();
        for key in &t.poses {
            let Orientation::Frame { quaternion_xyzw: [x, y, z, w] } = key.orientation else { continue };
            frames += 1;
            // A key on the demonstration's clock (before the first force-controlled primitive,
            // the schedule keeps it) at one of its samples: that sample's frame, moved.
            let Some(s) = record.samples.iter().find(|s| (s.time_s - key.time_s).abs() < 1e-9) else {
                continue;
            };
            let tip = moved.transform_point(&s.position_m.into()).coords;
            if (Vector3::from(key.world_position_m) - tip).norm() > 1e-9 {
                continue; // a primitive's own key, not the demonstration's
            }
            let recorded = moved.rotation * s.world_from_tip();
            let commanded = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, y, z));
            assert!(commanded.angle_to(&recorded) < 1e-9, "{} at {} s", record.instrument, key.time_s);
            let bend = (recorded * Vector3::z()).angle(&(tip - trocar));
            assert!((0.05..=1.25).contains(&bend), "a frame only where the wrist is bent within reach");
            checked += 1;
        }
    }
    assert!(checked >= 20, "{checked} keys at the demonstration's samples of {frames} frames");
}

/// An instrument that waited in the demonstration until its first primitive (the assist holding the
/// tail's end) waits where it is at a turned site, with the frame it has there, until that primitive,
/// which starts from there: the demonstration's pose moved to the site is another (the trocar turns the
/// shaft), and going to it dragged the tail off where the left takes it (on the workspace map's trial 1
/// it lay 6 mm from the left's closing jaws). The other instruments are the same.
#[test]
fn an_instrument_that_waited_in_the_demonstration_waits_where_it_is() {
    let (kb, demo) = learned(34);
    let here = nominal(&kb);
    let turn = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 25f64.to_radians());
    let there = Isometry3::from_parts(Translation3::from(here.translation.vector), turn * here.rotation);
    let trocars = trocars(&there);
    let moved_starts = starts(&kb, &demo, &there);
    // The assist where this site's trocar puts it: 3 mm off the moved pose and its shaft turned 0.2 rad.
    let mut site_starts = moved_starts.clone();
    let assist = site_starts.iter_mut().find(|s| s.arm == ArmName::Assist).expect("an assist");
    let twist = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), 0.2);
    assist.world_from_tip = Isometry3::from_parts(
        Translation3::from(assist.world_from_tip.translation.vector + Vector3::new(0.003, 0.0, 0.0)),
        twist * assist.world_from_tip.rotation,
    );
    let held = assist.world_from_tip;
    let mut free = |_: &str, _: ArmName, _: &_, region: &knotlab_learner::fluid::GridRegion| {
        Ok(ObstacleMask::free(region.n))
    };
    let made = |starts: &[StartPose], free: &mut knotlab_learner::synthesis::ObstacleSource<'_>| {
        let site = Site { new_world_from_stitch: there, trocars: &trocars, starts, reach: None };
        synthesize(&kb, Method::Fluid, &site, &PrimitiveSettings::default(), free).expect("synthesis")
    };
    let (plain, moved) = (made(&moved_starts, &mut free), made(&site_starts, &mut free));
    let a1 = moved.schedule.slot("A1").expect("A1").new_s.0;
    let assist = track(&moved.skill, ArmName::Assist);
    let before: Vec<_> = assist.poses.iter().filter(|k| k.time_s <= a1).collect();
    assert!(!before.is_empty());
    for key in before {
        let at = (Vector3::from(key.world_position_m) - held.translation.vector).norm();
        assert!(at < 1e-9, "the assist at {:.2} s is {at:.2e} m from where it holds the tail", key.time_s);
        let Orientation::Frame { quaternion_xyzw: [x, y, z, w] } = key.orientation else {
            panic!("a frame: {:?}", key.orientation)
        };
        let q = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, y, z));
        assert!(
            q.angle_to(&held.rotation) < 1e-9,
            "turned {} rad at {:.2} s",
            q.angle_to(&held.rotation),
            key.time_s
        );
    }
    // After A1 starts it goes where A1 ends, as the demonstration moved to the site has it.
    let a1_end = moved.schedule.slot("A1").expect("A1").new_s.1;
    let end_there = position(track(&plain.skill, ArmName::Assist), a1_end);
    assert!((position(assist, a1_end) - end_there).norm() < 1e-9);
    // The other instruments, started where the demonstration had them, are the same either way.
    for arm in [ArmName::Left, ArmName::Right] {
        assert_eq!(track(&plain.skill, arm), track(&moved.skill, arm), "{arm}");
    }
}

/// The takes of the knot-tying task are the left's L4 alone (down onto the tail, after which its jaws
/// hold it; L5 goes on with the tail held): L1 ends with jaws that then close on nothing, and the
/// assist and the right hold what they hold from the start.
#[test]
fn the_only_take_is_the_left_going_down_onto_the_tail() {
    let (kb, demo) = learned(35);
    let found = takes(&kb, &demo);
    assert_eq!(found.len(), 1, "{found:?}");
    let take = &found[0];
    assert_eq!(
        (take.instrument, take.primitive.as_str(), take.next.as_deref()),
        (ArmName::Left, "L4", Some("L5"))
    );
    let Some(Primitive::Linear(l4)) = kb.primitive("L4") else { panic!("L4 is linear") };
    let centre = take.stitch_jaw_centre_m(0.005);
    let tip = Vector3::from(l4.end_pose.position_m);
    assert!(((tip - centre).norm() - 0.005).abs() < 1e-12);
}

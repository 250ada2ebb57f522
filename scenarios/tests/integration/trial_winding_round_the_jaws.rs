//! The winding at a turned and tilted site goes round the left's jaws as its wrist can hold them.

use knotlab_hw::rig::{ArmName, Rig};
use knotlab_hw::skill::Orientation;
use knotlab_learner::primitive::Primitive;
use knotlab_learner::synthesis::winding::{WINDING_AIMED_FROM_RAD, winding_aim};
use knotlab_learner::synthesis::{Method, Trocars};
use knotlab_scenarios::trial::{Learned, StitchMove, synthesize_for};
use knotlab_sim::scene::parse_scene;
use knotlab_sim::world::{SimWorld, trocar_of};
use nalgebra::{UnitQuaternion, Vector3};

use super::common;

/// The angle between the axis the right circles about while it winds (R2) and the left's commanded
/// jaws when the winding starts, rad, for the skill synthesized at the stitch moved by `stitch`.
fn winding_off_the_jaws_rad(learned: &Learned, stitch: StitchMove) -> f64 {
    let mut scene =
        parse_scene(include_str!("../../default.toml"), "default.toml").expect("the nominal scene");
    stitch.apply(&mut scene);
    let world = SimWorld::new(scene, Rig::shipped().expect("the rig")).expect("the moved world");
    let made = synthesize_for(&world, learned, Method::Fluid).expect("the skill at the site");
    let span = made.spans.iter().find(|s| s.name == "R2").expect("the winding R2").skill_s;
    let track = |arm| made.skill.tracks.iter().find(|t| t.arm == arm).expect("a track");
    let loop_m: Vec<Vector3<f64>> = track(ArmName::Right)
        .poses
        .iter()
        .filter(|k| k.time_s >= span.0 && k.time_s <= span.1)
        .map(|k| Vector3::from(k.world_position_m))
        .collect();
    assert!(loop_m.len() > 20, "{} keys in the winding", loop_m.len());
    // The loop's axis: the sum of the areas its chords sweep about their centre.
    let centre = loop_m.iter().sum::<Vector3<f64>>() / loop_m.len() as f64;
    let area: Vector3<f64> = loop_m.windows(2).map(|w| (w[0] - centre).cross(&(w[1] - centre))).sum();
    let left = track(ArmName::Left);
    let at_start =
        left.poses.iter().rev().find(|k| k.time_s <= span.0).expect("the left's key at R2's start");
    let Orientation::Frame { quaternion_xyzw: [x, y, z, w] } = at_start.orientation else {
        panic!("the left holds a frame in the loop: {:?}", at_start.orientation);
    };
    let jaws = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, y, z)) * Vector3::z();
    let off = area.angle(&jaws);
    off.min(std::f64::consts::PI - off)
}

/// Guards the winding's aim: at the site of trial 19 of `knotlab mc --preset workspace --seed 1`
/// (shifted 3 cm across, turned -21.3 degrees, tilted -11.8 degrees) the left's demonstrated frame in
/// the loop is bent further from its shaft than its wrist reaches and is turned back 26 degrees; the
/// right, winding round the jaws where the demonstration had them, circled an axis 26 degrees off the
/// jaws it was to wind round, and the long end's turns round them never passed half a turn (no
/// knot). Turned with the jaws, the loop circles them as closely as at the nominal site.
#[test]
fn at_a_turned_site_the_winding_circles_the_jaws_as_they_are_held() {
    let learned = common::shipped_learned();
    let nominal = winding_off_the_jaws_rad(&learned, StitchMove::default());
    let turned = winding_off_the_jaws_rad(
        &learned,
        StitchMove {
            offset_m: Vector3::new(-0.002790, 0.029912, 0.006401),
            rotate_rad: -0.372059,
            tilt_rad: -0.206757,
        },
    );
    assert!(nominal < 10f64.to_radians(), "at the nominal site {:.1} degrees", nominal.to_degrees());
    assert!(
        turned < nominal + 3f64.to_radians(),
        "at the turned site the winding circles {:.1} degrees off the left's jaws (nominal site: {:.1})",
        turned.to_degrees(),
        nominal.to_degrees()
    );
}

/// Guards the winding's aim to the sites that need it: at the corners of the default randomization
/// (the stitch shifted 1 cm along x and y, turned 10 degrees either way) the left's frame in the
/// loop is turned back less than `WINDING_AIMED_FROM_RAD` (or not at all), and the winding is made
/// about the jaws as the demonstration held them; at trial 19's site it is turned.
#[test]
fn the_winding_is_aimed_only_where_the_left_frame_is_turned_back_far() {
    let learned = common::shipped_learned();
    let winding = learned
        .knowledge
        .instruments
        .iter()
        .flat_map(|ip| &ip.primitives)
        .find_map(|p| match p {
            Primitive::TwoD(t) if t.name == "R2" => Some(t),
            _ => None,
        })
        .expect("the winding R2");
    let aim_rad = |stitch: StitchMove| {
        let mut scene =
            parse_scene(include_str!("../../default.toml"), "default.toml").expect("the nominal scene");
        stitch.apply(&mut scene);
        let world = SimWorld::new(scene, Rig::shipped().expect("the rig")).expect("the moved world");
        let trocars = Trocars(
            [ArmName::Left, ArmName::Right, ArmName::Assist]
                .into_iter()
                .map(|a| (a, trocar_of(world.config(), a)))
                .collect(),
        );
        let world_from_stitch = world.tissue().world_from_tissue;
        let aim = winding_aim(&learned.knowledge, winding, &world_from_stitch, &trocars).expect("the aim");
        aim.rotation.angle()
    };
    let mut largest_rad = 0.0f64;
    for x in [-0.01, 0.01] {
        for y in [-0.01, 0.01] {
            for turn in [-0.17, 0.0, 0.17] {
                let stitch =
                    StitchMove { offset_m: Vector3::new(x, y, 0.0), rotate_rad: turn, tilt_rad: 0.0 };
                let a = aim_rad(stitch);
                largest_rad = largest_rad.max(a);
            }
        }
    }
    assert_eq!(largest_rad, 0.0, "a winding within the default randomization turned");
    let far = aim_rad(StitchMove {
        offset_m: Vector3::new(-0.002790, 0.029912, 0.006401),
        rotate_rad: -0.372059,
        tilt_rad: -0.206757,
    });
    assert!(far >= WINDING_AIMED_FROM_RAD, "at trial 19's site the winding turned {far} rad");
}

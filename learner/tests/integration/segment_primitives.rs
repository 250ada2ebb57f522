//! Primitive extraction into the knowledge base: everything relative to the stitch frame (moving the
//! whole demonstration moves nothing in the knowledge base), each type's contents against what the
//! synthetic expert did, the 2D primitive through the fluid solver, and the JSON file's round trip and
//! errors.

use std::path::Path;

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};

use knotlab_learner::features::detect;
use knotlab_learner::fluid::{GridRegion, InstantiateSettings, ObstacleMask, instantiate};
use knotlab_learner::pattern::{TaskPattern, load_pattern};
use knotlab_learner::primitive::{
    JawActionKind, KB_FORMAT_VERSION, KnowledgeBase, Primitive, extract, load_knowledge_base,
    parse_knowledge_base, write_knowledge_base,
};
use knotlab_learner::segment::decompose;
use knotlab_learner::synthetic::{GroundTruth, SyntheticSettings, canonical_demonstration};

fn pattern() -> TaskPattern {
    load_pattern(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenarios/patterns/knot_tying.toml"))
        .expect("the shipped pattern loads")
}

fn learn(settings: &SyntheticSettings) -> (KnowledgeBase, GroundTruth) {
    let p = pattern();
    let (demo, truth) = canonical_demonstration(settings);
    let features = detect(&demo, &p.detector).expect("features");
    let decomposition = decompose(&p, &features).expect("decomposition");
    (extract(&demo, &p, &features, &decomposition).expect("extraction"), truth)
}

fn v(a: [f64; 3]) -> Vector3<f64> {
    Vector3::from(a)
}

/// Moving the whole demonstration to another stitch pose changes nothing in the knowledge base but that
/// pose: the same primitives, spans and stitch-frame contents.
#[test]
fn the_knowledge_base_is_the_same_wherever_the_demonstration_was_made() {
    let here = SyntheticSettings::canonical(21, 100.0);
    let there = SyntheticSettings {
        world_from_stitch: Isometry3::from_parts(
            Translation3::new(0.31, -0.12, 0.87),
            UnitQuaternion::from_euler_angles(0.4, -0.25, 2.1),
        ),
        ..here.clone()
    };
    let (a, _) = learn(&here);
    let (b, _) = learn(&there);
    assert_ne!(a.world_from_stitch, b.world_from_stitch);
    let names = |kb: &KnowledgeBase| -> Vec<String> {
        kb.instruments.iter().flat_map(|i| i.primitives.iter().map(|p| p.name().to_owned())).collect()
    };
    assert_eq!(names(&a), names(&b));
    let close = |x: [f64; 3], y: [f64; 3], tol: f64, what: &str| {
        assert!((v(x) - v(y)).norm() < tol, "{what}: {x:?} vs {y:?}");
    };
    for (pa, pb) in
        a.instruments.iter().flat_map(|i| &i.primitives).zip(b.instruments.iter().flat_map(|i| &i.primitives))
    {
        let (sa, sb) = (pa.span_s(), pb.span_s());
        assert!(
            (sa.0 - sb.0).abs() < 1e-6 && (sa.1 - sb.1).abs() < 1e-6,
            "{}: spans {sa:?} {sb:?}",
            pa.name()
        );
        match (pa, pb) {
            (Primitive::Linear(x), Primitive::Linear(y)) => {
                close(x.start_pose.position_m, y.start_pose.position_m, 1e-9, &x.name);
                close(x.end_pose.position_m, y.end_pose.position_m, 1e-9, &x.name);
                let (qa, qb) = (x.end_pose.quaternion_xyzw, y.end_pose.quaternion_xyzw);
                let dot: f64 = qa.iter().zip(qb).map(|(p, q)| p * q).sum();
                assert!(dot.abs() > 1.0 - 1e-9, "{}: orientation in the stitch frame", x.name);
            }
            (Primitive::TwoD(x), Primitive::TwoD(y)) => {
                close(x.plane.origin_m, y.plane.origin_m, 1e-9, "plane origin");
                assert!(v(x.plane.axis_x).cross(&v(y.plane.axis_x)).norm() < 1e-6, "plane axes");
                assert_eq!(x.path_m.len(), y.path_m.len());
            }
            (Primitive::Force(x), Primitive::Force(y)) => {
                close(x.force_direction, y.force_direction, 1e-6, "force direction");
                assert!((x.max_force_n - y.max_force_n).abs() < 1e-9);
            }
            (Primitive::Synchronized(x), Primitive::Synchronized(y)) => {
                close(x.mapping[25].position_plane_m, y.mapping[25].position_plane_m, 1e-8, "mapping");
            }
            _ => panic!("{} changed type", pa.name()),
        }
    }
}

/// Each primitive type holds what the synthetic expert did: linear reaches and a bell-shaped retreat, a
/// planar two-turn winding, the pull's force and jaw opening, and a synchronized mapping.
#[test]
fn each_primitive_holds_what_the_expert_did() {
    let (kb, truth) = learn(&SyntheticSettings::canonical(22, 100.0));
    let get = |name: &str| kb.primitive(name).unwrap_or_else(|| panic!("no {name}"));
    // Linear: the left reaches the winding point (where L3 starts), and the assist's retreat is the
    // script's 3.35 cm straight line with a bell-shaped speed profile.
    let (Primitive::Linear(l1), Primitive::Linear(l3), Primitive::Linear(a1)) =
        (get("L1"), get("L3"), get("A1"))
    else {
        panic!("L1, L3, A1 are linear");
    };
    close_to(v(l1.end_pose.position_m), v(l3.start_pose.position_m), 0.001, "L1 ends where L3 starts");
    let retreat: f64 = (v(a1.end_pose.position_m) - v(a1.start_pose.position_m)).norm();
    let script: f64 = Vector3::new(0.01, 0.02, 0.025).norm();
    assert!((retreat - script).abs() < 0.001, "A1 length {retreat}");
    assert!(a1.max_deviation_m < 0.0005, "A1 is straight: {}", a1.max_deviation_m);
    let speeds: Vec<f64> = a1.speed_profile.iter().map(|p| p.speed_mps).collect();
    let peak = speeds.iter().copied().fold(0.0, f64::max);
    let (first, last) = (speeds[0], speeds[speeds.len() - 1]);
    assert!(first < 0.2 * peak && last < 0.2 * peak && speeds[25] > 0.8 * peak, "bell-shaped: {speeds:?}");

    // 2D: two turns in a plane.
    let Primitive::TwoD(r2) = get("R2") else { panic!("R2 is 2d") };
    assert!((r2.turns.abs() - 2.0).abs() < 0.3, "R2 turns {}", r2.turns);
    assert!(r2.rms_out_of_plane_m < 0.0005, "R2 is planar: {}", r2.rms_out_of_plane_m);
    assert_eq!(r2.path_m.len(), r2.speed_mps.len());
    for w in r2.path_m.windows(2).take(r2.path_m.len() - 2) {
        let step = ((w[1][0] - w[0][0]).powi(2) + (w[1][1] - w[0][1]).powi(2)).sqrt();
        assert!((step - r2.step_m).abs() < 1e-4, "equal arc-length steps: {step}");
    }

    // Force: the right pulls along +(-0.2, -1, 0.3) of the stitch frame; the force on it points back.
    let Primitive::Force(r5) = get("R5") else { panic!("R5 is force") };
    assert!((0.85..1.2).contains(&r5.max_force_n), "R5 max force {}", r5.max_force_n);
    let pull = Vector3::new(-0.2, -1.0, 0.3).normalize();
    assert!(v(r5.force_direction).dot(&-pull) > 0.95, "force direction {:?}", r5.force_direction);
    assert_eq!(r5.jaw.action, JawActionKind::Open);
    assert!(r5.jaw.to_rad > 0.5, "the jaws open: {:?}", r5.jaw);
    let line_end = v(r5.line_end_m) - v(r5.start_pose.position_m);
    assert!(line_end.normalize().dot(&pull) > 0.99 && (line_end.norm() - 0.03).abs() < 0.002, "{line_end:?}");
    let true_r5 = truth.primitives.iter().find(|t| t.name == "R5").unwrap();
    assert!((r5.end_s - true_r5.end_s).abs() < 0.05);

    // Synchronized: the mapping runs through the reference's whole path; the left stays near the loop.
    let Primitive::Synchronized(l2) = get("L2") else { panic!("L2 is synchronized") };
    assert_eq!(l2.reference, "R2");
    assert_eq!(l2.mapping.first().unwrap().phase, 0.0);
    assert!((l2.mapping.last().unwrap().phase - 1.0).abs() < 1e-9);
    assert!(l2.mapping.windows(2).all(|w| w[1].phase >= w[0].phase), "phase increases");
    let jaws = v(l2.mapping[25].position_plane_m);
    assert!(jaws.xy().norm() < 0.01 && jaws.z.abs() < 0.01, "the left's jaws inside the loops: {jaws:?}");
}

fn close_to(a: Vector3<f64>, b: Vector3<f64>, tol: f64, what: &str) {
    assert!((a - b).norm() < tol, "{what}: {a:?} vs {b:?}");
}

/// The learned 2D primitive instantiates through the fluid solver in place, the particle ending within
/// three cells of the path's end.
#[test]
fn the_two_d_primitive_goes_through_the_fluid_solver() {
    let (kb, _) = learn(&SyntheticSettings::canonical(23, 100.0));
    let Some(Primitive::TwoD(r2)) = kb.primitive("R2") else { panic!("R2 is 2d") };
    let world_from_stitch = knotlab_learner::demonstration::StitchPose {
        position_m: kb.world_from_stitch.position_m,
        quaternion_xyzw: kb.world_from_stitch.quaternion_xyzw,
    }
    .world_from_stitch();
    let demo = r2.planar_demonstration(&world_from_stitch).unwrap();
    assert_eq!(demo.path.points_m.len(), r2.path_m.len());
    assert!(demo.path.speed_mps.iter().all(|s| *s > 0.0));
    // Instantiate in place on a 40 x 40 grid around the path: the particle follows the demonstration.
    let (lo, hi) = demo.path.points_m.iter().fold(
        (nalgebra::Vector2::repeat(f64::INFINITY), nalgebra::Vector2::repeat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.inf(p), hi.sup(p)),
    );
    let side = (hi - lo).max() + 0.012;
    let n = 40;
    let region =
        GridRegion::new((lo + hi) / 2.0 - nalgebra::Vector2::repeat(side / 2.0), side / n as f64, n).unwrap();
    let result = instantiate(
        &demo,
        &Isometry3::identity(),
        &region,
        &ObstacleMask::free(n),
        &InstantiateSettings::default(),
    )
    .unwrap();
    let end = result.points.last().unwrap().plane_m;
    let demo_end = demo.path.points_m.last().unwrap();
    assert!(
        (end - demo_end).norm() < 3.0 * region.cell_m,
        "the particle ends where the path does: {end:?} vs {demo_end:?}"
    );
    let on_plane = demo.plane.to_world(&end);
    assert!((demo.plane.to_plane(&on_plane) - end).norm() < 1e-12);
}

/// The knowledge base file reads back identical; a bad version, a non-unit frame or a wrong type is
/// refused naming where it is, and version 1 and 2 files still read.
#[test]
fn the_knowledge_base_file_round_trips_and_refuses_bad_files() {
    let (kb, _) = learn(&SyntheticSettings::canonical(24, 100.0));
    let path = std::env::temp_dir().join(format!("knotlab-kb-{}.json", std::process::id()));
    write_knowledge_base(&path, &kb).unwrap();
    let back = load_knowledge_base(&path).unwrap();
    std::fs::remove_file(&path).ok();
    assert!(back == kb, "the knowledge base reads back identical");

    let text = serde_json::to_string_pretty(&kb).unwrap();
    let version = format!("\"format_version\": {KB_FORMAT_VERSION}");
    let e =
        parse_knowledge_base(&text.replacen(&version, "\"format_version\": 9", 1), "kb.json").unwrap_err();
    let line = text.lines().position(|l| l.contains("\"format_version\"")).unwrap() + 1;
    assert!(e.to_string().starts_with(&format!("kb.json:{line}: format_version: 9 is not supported")), "{e}");
    // A path key's frame that is no rotation is named, not commanded.
    let mut value = serde_json::to_value(&kb).unwrap();
    value["instruments"][1]["path"][4]["quaternion_xyzw"] = serde_json::json!([0.0, 0.0, 0.0, 0.0]);
    let e = parse_knowledge_base(&serde_json::to_string_pretty(&value).unwrap(), "kb.json").unwrap_err();
    assert!(
        e.to_string().starts_with(
            "kb.json: instruments[1].path[4].quaternion_xyzw: [0.0, 0.0, 0.0, 0.0] is not a unit quaternion"
        ),
        "{e}"
    );
    // A version 2 file (path keys without frames) still reads.
    let mut v2 = kb.clone();
    v2.format_version = 2;
    v2.instruments.iter_mut().flat_map(|i| &mut i.path).for_each(|k| k.quaternion_xyzw = None);
    let text2 = serde_json::to_string_pretty(&v2).unwrap();
    assert!(text2.matches("quaternion_xyzw").count() < text.matches("quaternion_xyzw").count(), "no frames");
    assert!(
        parse_knowledge_base(&text2, "v2.json").unwrap() == v2,
        "a version 2 file reads as it was written"
    );
    // A version 1 file (no jaw points, paths or dependencies) still reads.
    let mut old = kb.clone();
    old.format_version = 1;
    old.dependencies.clear();
    for i in &mut old.instruments {
        i.jaw.clear();
        i.path.clear();
    }
    let mut value = serde_json::to_value(&old).unwrap();
    value.as_object_mut().unwrap().remove("dependencies");
    for i in value["instruments"].as_array_mut().unwrap() {
        i.as_object_mut().unwrap().remove("jaw");
        i.as_object_mut().unwrap().remove("path");
    }
    let v1 = parse_knowledge_base(&serde_json::to_string_pretty(&value).unwrap(), "v1.json").unwrap();
    assert!(v1 == old, "a version 1 file reads as it was written");
    let bad = text.replacen("\"max_force_n\": ", "\"max_force_n\": \"a lot\", \"x\": ", 1);
    let e = parse_knowledge_base(&bad, "kb.json").unwrap_err();
    let line = bad.lines().position(|l| l.contains("a lot")).unwrap() + 1;
    let message = e.to_string();
    // Inside a primitive (tagged by its type) the parser reports the line where the primitive ends.
    assert!(e.to_string().starts_with("kb.json:"), "{message}");
    let reported: usize = message.split(':').nth(1).unwrap().parse().unwrap();
    assert!(reported >= line && reported <= bad.lines().count(), "{message}");
    assert!(message.contains(": instruments[1].primitives[3].max_force_n: invalid type"), "{message}");
}

/// A knowledge base that fits the schema but cannot make a skill is refused naming each field, where it
/// used to run (an empty instrument list exited 0) or loop: a primitive's pose that is no rotation, no
/// instruments, a dependency on a primitive that does not exist and a pause its primitives' times do
/// not give, a 2D path spaced 0 m apart, an empty speed profile and one that runs backwards.
#[test]
fn a_knowledge_base_that_cannot_make_a_skill_is_refused_naming_each_field() {
    let (kb, _) = learn(&SyntheticSettings::canonical(24, 100.0));
    let good = serde_json::to_value(&kb).unwrap();
    let find = |want: &str| -> (usize, usize) {
        for (i, ip) in kb.instruments.iter().enumerate() {
            if let Some(j) = ip.primitives.iter().position(|p| p.type_name() == want) {
                return (i, j);
            }
        }
        panic!("no {want} primitive");
    };
    let refused = |value: &serde_json::Value, field: &str, reason: &str| {
        let e = parse_knowledge_base(&serde_json::to_string_pretty(value).unwrap(), "kb.json").unwrap_err();
        let message = e.to_string();
        assert!(message.starts_with("kb.json: "), "{message}");
        assert!(message.contains(&format!("{field}: {reason}")), "want '{field}: {reason}' in: {message}");
    };
    let (i, j) = find("linear");
    let mut v = good.clone();
    v["instruments"][i]["primitives"][j]["start_pose"]["quaternion_xyzw"] =
        serde_json::json!([0.0, 0.0, 0.5, 0.5]);
    refused(
        &v,
        &format!("instruments[{i}].primitives[{j}].start_pose.quaternion_xyzw"),
        "[0.0, 0.0, 0.5, 0.5] is not a unit quaternion",
    );
    let mut v = good.clone();
    v["instruments"] = serde_json::json!([]);
    refused(&v, "instruments", "is empty");
    let mut v = good.clone();
    assert!(!kb.dependencies.is_empty(), "the skill has dependencies to break");
    v["dependencies"][0]["after"] = serde_json::json!("no_such_primitive");
    refused(&v, "dependencies[0].after", "\"no_such_primitive\" is no primitive of this skill");
    let mut v = good.clone();
    v["dependencies"][0]["pause_s"] = serde_json::json!(-5.0);
    refused(&v, "dependencies[0].pause_s", "-5 s, but the primitives' times give");
    let (i2, j2) = find("2d");
    let mut v = good.clone();
    v["instruments"][i2]["primitives"][j2]["step_m"] = serde_json::json!(0.0);
    refused(&v, &format!("instruments[{i2}].primitives[{j2}].step_m"), "0 is not within 0.0001 to 0.01 m");
    let mut v = good.clone();
    v["instruments"][i]["primitives"][j]["speed_profile"] = serde_json::json!([]);
    refused(
        &v,
        &format!("instruments[{i}].primitives[{j}].speed_profile"),
        "0 points; 1 to 1000000 are allowed",
    );
    let mut v = good.clone();
    let backwards: Vec<serde_json::Value> =
        (0..100_000).map(|k| serde_json::json!({"s_m": 1.0 - k as f64 * 1e-5, "speed_mps": 0.01})).collect();
    v["instruments"][i]["primitives"][j]["speed_profile"] = serde_json::Value::Array(backwards);
    refused(
        &v,
        &format!("instruments[{i}].primitives[{j}].speed_profile[1].s_m"),
        "0.99999 where finite values not below the one before are allowed",
    );
    // The learned file itself has none of these problems.
    assert!(
        knotlab_learner::primitive::check::problems(&kb).is_empty(),
        "{:?}",
        knotlab_learner::primitive::check::problems(&kb)
    );
}

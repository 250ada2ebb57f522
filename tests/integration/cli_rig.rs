//! `knotlab rig ...` end to end: the binary as a user runs it.

use super::common;

use serde_json::Value;

use common::{json, knotlab};

/// `rig check` accepts the shipped rig: four arms with their joints and limits and the models agreeing, in
/// JSON and in text.
#[test]
fn rig_check_validates_the_shipped_rig() {
    let (code, v) = json(&["rig", "check", "--json"]);
    assert_eq!(code, 0);
    assert_eq!(v["ok"], true);
    let arms: Vec<&str> = v["arms"].as_array().unwrap().iter().map(|a| a["name"].as_str().unwrap()).collect();
    assert_eq!(arms, ["left", "right", "assist", "camera"]);
    assert_eq!(v["arms"][0]["joints"].as_array().unwrap().len(), 10);
    assert_eq!(v["arms"][3]["joints"].as_array().unwrap().len(), 6);
    let j2 = &v["arms"][0]["joints"][1];
    assert!((j2["lower_rad"].as_f64().unwrap() - (-92f64).to_radians()).abs() < 1e-12);
    assert!(v["model_agreement"].as_f64().unwrap() < 1e-9);
    let (code, text, _) = knotlab(&["rig", "check"]);
    assert_eq!(code, 0);
    assert!(text.contains("OK") && text.contains("arm camera (endoscope)"), "{text}");
}

/// `rig check --urdf` fails on a non-finite joint origin, naming the file, the joint and the field.
#[test]
fn rig_check_names_the_broken_element_of_a_urdf_file() {
    let dir = std::env::temp_dir().join(format!("knotlab-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("broken.urdf");
    let text = knotlab_hw::rig::DEFAULT_URDF.replacen(
        "<origin xyz=\"0.0 0.0 0.4318\"",
        "<origin xyz=\"0.0 nan 0.4318\"",
        1,
    );
    std::fs::write(&path, text).unwrap();
    let (code, _, stderr) = knotlab(&["rig", "check", "--urdf", path.to_str().unwrap()]);
    assert_eq!(code, 1);
    assert!(
        stderr.contains("broken.urdf") && stderr.contains("joint 'left_wrist_pitch', origin.xyz: not finite"),
        "{stderr}"
    );
    let (code, v) = json(&["rig", "check", "--json", "--urdf", path.to_str().unwrap()]);
    assert_eq!((code, &v["ok"]), (1, &Value::Bool(false)));
    assert!(v["error"].as_str().unwrap().contains("left_wrist_pitch"));
    std::fs::remove_dir_all(&dir).ok();
}

/// IK through the command line, then FK of its answer through the command line: the tip comes back.
#[test]
fn rig_ik_then_fk_returns_to_the_target() {
    let tip = [0.02, -0.01, 0.94];
    let tip_arg = format!("{},{},{}", tip[0], tip[1], tip[2]);
    let (code, v) = json(&[
        "rig",
        "ik",
        "--arm",
        "left",
        "--trocar",
        "-0.08,0.12,1.02",
        "--tip",
        &tip_arg,
        "--jaw-dir",
        "0.4,-0.3,-1",
        "--json",
    ]);
    assert_eq!(code, 0, "{v}");
    for key in ["tip_error_m", "orientation_error_rad", "trocar_distance_m"] {
        assert!(v["residuals"][key].as_f64().unwrap() < 1e-6, "{key}: {v}");
    }
    let joints: Vec<String> =
        v["joints_rad"].as_object().unwrap().values().map(|x| x.as_f64().unwrap().to_string()).collect();
    assert_eq!(joints.len(), 10);
    let (code, fk) = json(&["rig", "fk", "--arm", "left", "--joints", &joints.join(","), "--json"]);
    assert_eq!(code, 0);
    let reached: Vec<f64> =
        fk["tip"]["position_m"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
    for (a, b) in reached.iter().zip(tip) {
        assert!((a - b).abs() < 1e-9, "{reached:?} vs {tip:?}");
    }
    // Every link of the arm is listed, and nothing of the other arms.
    let names: Vec<&str> =
        fk["links"].as_array().unwrap().iter().map(|l| l["name"].as_str().unwrap()).collect();
    assert!(names.contains(&"left_link6") && names.contains(&"left_jaw_2") && names.contains(&"left_tip"));
    assert!(names.iter().all(|n| n.starts_with("left_")));
}

/// `rig ik` fails with exit code 1 and a specific message for a tip too close to the trocar, an insertion
/// depth out of range and a jaw direction given for the camera.
#[test]
fn rig_ik_reports_typed_errors() {
    let (code, v) = json(&[
        "rig",
        "ik",
        "--arm",
        "left",
        "--trocar",
        "-0.08,0.12,1.02",
        "--tip",
        "-0.08,0.12,1.0195",
        "--json",
    ]);
    assert_eq!(code, 1);
    assert_eq!(v["ok"], false);
    assert!(v["error"].as_str().unwrap().contains("closer than the 0.001 m allowed"), "{v}");
    let (code, _, stderr) =
        knotlab(&["rig", "ik", "--arm", "right", "--trocar", "-0.08,-0.12,1.02", "--tip", "0,0,0.5"]);
    assert_eq!(code, 1);
    assert!(stderr.contains("right arm: insertion depth"), "{stderr}");
    let (code, _, stderr) = knotlab(&[
        "rig",
        "ik",
        "--arm",
        "camera",
        "--trocar",
        "0,0,1",
        "--tip",
        "0,0,0.9",
        "--jaw-dir",
        "0,0,1",
    ]);
    assert_eq!(code, 1);
    assert!(stderr.contains("--jaw-dir"), "{stderr}");
}

/// `rig fk` and `rig ik` name an unknown arm, a non-numeric joint, the wrong number of joints, a joint
/// beyond its limit (99 rad was put through the kinematics) and a short vector, usage errors exiting 2.
#[test]
fn bad_arguments_are_named() {
    let (code, _, stderr) = knotlab(&["rig", "fk", "--arm", "middle", "--joints", "0,0,0,0,0,0"]);
    assert_eq!(code, 2);
    assert!(stderr.contains("unknown arm 'middle'"), "{stderr}");
    let (code, _, stderr) = knotlab(&["rig", "fk", "--arm", "left", "--joints", "0,0,x"]);
    assert_eq!(code, 2);
    assert!(stderr.contains("--joints") && stderr.contains("'x' is not a number"), "{stderr}");
    let (code, _, stderr) = knotlab(&["rig", "fk", "--arm", "camera", "--joints", "0,0,0,0,0,0,0,0,0,0"]);
    assert_eq!(code, 1);
    assert!(stderr.contains("camera arm takes 6 values"), "{stderr}");
    let (code, _, stderr) = knotlab(&["rig", "fk", "--arm", "left", "--joints", "99,0,0,0,0,0"]);
    assert_eq!(code, 1);
    assert!(stderr.contains("--joints: axis 1 = 99 rad is outside its limits"), "{stderr}");
    let (code, _, stderr) = knotlab(&["rig", "fk", "--arm", "left", "--joints", "0,0,0,0,0,0,0,0,0,7"]);
    assert_eq!(code, 1);
    assert!(stderr.contains("--joints: jaw = 7 rad is outside its limits"), "{stderr}");
    let (code, _, stderr) = knotlab(&["rig", "ik", "--arm", "left", "--trocar", "0,0", "--tip", "0,0,1"]);
    assert_eq!(code, 2);
    assert!(stderr.contains("--trocar") && stderr.contains("expected 3"), "{stderr}");
}

//! Rig configs: the shipped examples parse; malformed files are refused naming the file, line, key and
//! reason; combinations that cannot work are listed key by key; a sim rig needs the simulator.

use super::rigs;

use knotlab_hw::rig::ArmName;
use knotlab_hw::rig_config::{
    Backend, LayoutName, RigBuildError, RigConfigError, build_rig, load_rig_config, parse_rig_config,
};

const SIM: &str = include_str!("../../../scenarios/rigs/sim.toml");
const MELFA: &str = include_str!("../../../scenarios/rigs/melfa.toml");
const LAB: &str = include_str!("../../../scenarios/rigs/lab.toml");

fn schema(text: &str) -> (usize, String, String) {
    match parse_rig_config(text, "rig.toml") {
        Err(RigConfigError::Schema { file, line, key, reason }) => {
            assert_eq!(file, "rig.toml");
            (line, key, reason)
        }
        other => panic!("expected a schema error, got {other:?}"),
    }
}

fn problems(text: &str) -> Vec<(String, String)> {
    match parse_rig_config(text, "rig.toml") {
        Err(RigConfigError::Invalid { problems, .. }) => problems,
        other => panic!("expected problems, got {other:?}"),
    }
}

fn has(problems: &[(String, String)], key: &str, words: &str) -> bool {
    problems.iter().any(|(k, r)| k == key && r.contains(words))
}

/// The shipped sim and MELFA rig configs parse, with their arms' backends, layout and controller address.
#[test]
fn the_shipped_rig_configs_parse() {
    let sim = parse_rig_config(SIM, "scenarios/rigs/sim.toml").unwrap();
    assert_eq!(sim.arms.iter().count(), 4);
    assert!(sim.arms.iter().all(|(_, a)| a.servo.backend == Backend::Sim));
    let melfa = parse_rig_config(MELFA, "scenarios/rigs/melfa.toml").unwrap();
    let left = melfa.arms.left.as_ref().unwrap();
    assert_eq!(left.servo.backend, Backend::Melfa);
    assert_eq!(left.servo.layout, Some(LayoutName::H7));
    assert_eq!(left.servo.controller.unwrap().to_string(), "192.168.0.21:10000");
    assert!(melfa.arms.camera.is_none());
    // The lab's: every device real.
    let lab = parse_rig_config(LAB, "scenarios/rigs/lab.toml").unwrap();
    assert_eq!(lab.pedals.backend, Backend::Gamepad);
    for (name, arm) in lab.arms.iter() {
        assert_eq!(arm.servo.backend, Backend::Melfa, "{name}");
        assert_eq!(arm.instrument.as_ref().map(|d| d.backend), Some(Backend::Canopen), "{name}");
        assert_eq!(arm.force.map(|d| d.backend), Some(Backend::NetFt), "{name}");
    }
    assert_eq!(knotlab_hw::gate::real_devices(&lab).len(), 9);
}

/// An unknown key or a misspelt arm is refused naming its line and the unknown field; a misspelt arm's
/// error lists the valid arm names.
#[test]
fn an_unknown_key_is_named_with_its_line() {
    let text =
        "description = \"x\"\n[arms.left]\nservo = { backend = \"dummy\" }\ntrocar = [0.0, 0.0, 1.0]\n";
    let (line, key, reason) = schema(text);
    assert_eq!(line, 4, "{key}: {reason}");
    assert!(reason.contains("unknown field `trocar`"), "{reason}");
    let text = "description = \"x\"\n[arms.lft]\nservo = { backend = \"dummy\" }\n";
    let (line, _, reason) = schema(text);
    assert_eq!(line, 2);
    assert!(reason.contains("unknown field `lft`") && reason.contains("left"), "{reason}");
}

/// A bad layout, an address without a port, an unknown backend or a negative watchdog count is refused
/// naming the key and line, and the accepted values where there are some.
#[test]
fn bad_values_are_named_with_key_and_line() {
    let text = "description = \"x\"\n\n[arms.left]\ntrocar_m = [0.0, 0.0, 1.0]\nservo = { backend = \"melfa\", controller = \"192.168.0.21:10000\", layout = \"h8\" }\n";
    let (line, key, reason) = schema(text);
    assert_eq!((line, key.as_str()), (5, "arms.left.servo.layout"), "{reason}");
    assert!(reason.contains("h7") && reason.contains("pre-h7"), "{reason}");

    let text = "description = \"x\"\n[arms.left]\ntrocar_m = [0.0, 0.0, 1.0]\nservo = { backend = \"melfa\", controller = \"192.168.0.21\" }\n";
    let (line, key, reason) = schema(text);
    assert_eq!((line, key.as_str()), (4, "arms.left.servo.controller"), "{reason}");
    assert!(reason.contains("socket address"), "{reason}");

    let text = "description = \"x\"\n[arms.left]\nservo = { backend = \"ros\" }\n";
    let (_, key, reason) = schema(text);
    assert_eq!(key, "arms.left.servo.backend");
    assert!(reason.contains("sim") && reason.contains("melfa") && reason.contains("dummy"), "{reason}");

    let text = "description = \"x\"\n[controller]\nwatchdog_cycles = -3\n";
    let (line, key, _) = schema(text);
    assert_eq!((line, key.as_str()), (3, "controller.watchdog_cycles"));
}

/// A trocar given four coordinates is refused with its line, key and the counts, not read as its first
/// three.
#[test]
fn a_trocar_of_four_numbers_is_refused_with_its_line() {
    let text = MELFA.replace("trocar_m = [-0.08, -0.12, 1.02]", "trocar_m = [-0.08, -0.12, 1.02, 0.0]");
    let line = text.lines().position(|l| l == "trocar_m = [-0.08, -0.12, 1.02, 0.0]").unwrap() + 1;
    let (l, key, reason) = schema(&text);
    assert_eq!(
        (l, key.as_str(), reason.as_str()),
        (line, "arms.right.trocar_m", "4 values where exactly 3 are allowed")
    );
}

/// Malformed TOML is refused naming the line of the syntax error.
#[test]
fn broken_toml_names_its_line() {
    let (line, key, _) = schema("description = \"x\"\n[arms.left\nservo = 1\n");
    assert_eq!((line, key.as_str()), (2, "(syntax)"));
}

/// A rig config with many unworkable combinations lists every problem key by key, not just the first,
/// its message starting with the file and the first key.
#[test]
fn combinations_that_cannot_work_are_listed_key_by_key() {
    let text = r#"
description = "everything wrong"
[controller]
speed_scale = 1.5
[arms.left]
servo = { backend = "melfa" }
instrument = { backend = "melfa" }
[arms.right]
servo = { backend = "sim", cycle_s = 0.0035 }
[arms.assist]
trocar_m = [0.1, 0.1, 1.02]
servo = { backend = "melfa", controller = "127.0.0.1:10003", cycle_s = 0.0035, max_lost = 0 }
[arms.camera]
servo = { backend = "dummy" }
force = { backend = "dummy" }
[pedals]
backend = "sim"
"#;
    let p = problems(text);
    assert!(has(&p, "controller.speed_scale", "not in (0, 1]"), "{p:?}");
    assert!(has(&p, "arms.left.servo.controller", "needs the controller's address"), "{p:?}");
    assert!(has(&p, "arms.left.instrument.backend", "cannot use backend \"melfa\""), "{p:?}");
    assert!(has(&p, "arms.left.trocar_m", "needed"), "{p:?}");
    assert!(has(&p, "arms.right.servo.cycle_s", "only for backend \"melfa\""), "{p:?}");
    assert!(has(&p, "arms.assist.servo.max_lost", "at least 1"), "{p:?}");
    assert!(has(&p, "arms.assist.servo.cycle_s", "differs from the left arm's"), "{p:?}");
    assert!(has(&p, "arms.camera.force", "endoscope"), "{p:?}");
    assert!(has(&p, "arms.camera.trocar_m", "needed"), "{p:?}");
    assert!(has(&p, "arms", "mixes sim and melfa"), "{p:?}");
    assert!(has(&p, "pedals.backend", "use dummy"), "{p:?}");
    // Each problem at its line: the file's 1-based line of the key.
    let line = text.lines().position(|l| l.trim_start().starts_with("speed_scale")).expect("speed_scale") + 1;
    let text = parse_rig_config(text, "rig.toml").unwrap_err().to_string();
    let first = format!("rig.toml:{line}: controller.speed_scale: 1.5 is not in (0, 1]; ");
    assert!(text.starts_with(&first), "{text}");
}

/// A rig config that cannot be read is refused naming its path.
#[test]
fn a_missing_file_is_named() {
    let error = load_rig_config(std::path::Path::new("no/such/rig.toml")).unwrap_err();
    assert!(error.to_string().starts_with("no/such/rig.toml: cannot read:"), "{error}");
}

/// Building a sim rig without the simulator is refused, pointing to knotlab-sim.
#[test]
fn a_sim_rig_needs_the_simulator() {
    let config = parse_rig_config(SIM, "sim.toml").unwrap();
    let error = build_rig(&config, &rigs::rig(), None).err().expect("refused without a scene");
    assert!(matches!(&error, RigBuildError::NeedsSimulator { key } if key == "arms"), "{error}");
    assert!(error.to_string().contains("knotlab-sim"), "{error}");
}

/// A rig of dummy devices builds with its force, master and pedal handles and its own period, the arm
/// at its ready joints.
#[test]
fn a_dummy_rig_builds_with_its_handles() {
    let text = r#"
description = "dummies"
[controller]
period_s = 0.002
[arms.left]
trocar_m = [-0.08, 0.12, 1.02]
servo = { backend = "dummy" }
instrument = { backend = "dummy" }
force = { backend = "dummy" }
[masters.left]
backend = "dummy"
"#;
    let config = parse_rig_config(text, "dummy.toml").unwrap();
    let built = build_rig(&config, &rigs::rig(), None).unwrap();
    assert!(built.handles.force(ArmName::Left).is_some());
    assert_eq!(built.handles.masters.len(), 1);
    let (controller, handles) = built.into_controller().unwrap();
    assert_eq!(controller.period_s(), 0.002);
    assert!(handles.pedals.is_some());
    let record = controller.record();
    let left = record.arm(ArmName::Left).unwrap();
    assert_eq!(left.measured.arm_rad, ArmName::Left.ready_joints().arm_rad);
}

//! A failed preview blocks a real backend: a rig with MELFA arms refuses the skill unless the override
//! is given, naming the real devices; a rig of simulated and dummy devices is never blocked; a preview
//! that passed opens the gate everywhere.

use std::path::Path;

use knotlab_hw::gate::{PreviewOutcome, may_execute, real_devices};
use knotlab_hw::rig_config::parse_rig_config;

fn rig(file: &str) -> knotlab_hw::rig_config::RigConfig {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenarios/rigs").join(file);
    let text = std::fs::read_to_string(&path).expect("the shipped rig config reads");
    parse_rig_config(&text, &path.display().to_string()).expect("the shipped rig config parses")
}

/// A failed preview refuses a MELFA rig's run, naming the reason, every real servo and the override; the
/// explicit override or a passed preview lets it run.
#[test]
fn a_failed_preview_blocks_a_real_backend_unless_overridden() {
    let melfa = rig("melfa.toml");
    let failed = PreviewOutcome { passed: false, reason: "knot: no_knot".into() };
    let refused = may_execute(&melfa, &failed, false).expect_err("a MELFA rig is gated");
    assert_eq!(refused.reason, "knot: no_knot");
    for device in ["left.servo", "right.servo", "assist.servo"] {
        assert!(refused.devices.contains(device), "{refused}");
    }
    assert!(refused.to_string().contains("override"), "{refused}");
    assert!(may_execute(&melfa, &failed, true).is_ok(), "the explicit override opens the gate");
    let passed = PreviewOutcome { passed: true, reason: String::new() };
    assert!(may_execute(&melfa, &passed, false).is_ok());
}

/// A rig of simulated devices has no real devices and may run even after a failed preview.
#[test]
fn a_simulated_rig_is_never_gated() {
    let sim = rig("sim.toml");
    assert!(real_devices(&sim).is_empty());
    let failed = PreviewOutcome { passed: false, reason: "unreachable".into() };
    assert!(may_execute(&sim, &failed, false).is_ok());
}

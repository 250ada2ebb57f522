//! The gate between a preview and a real robot: a skill whose preview in the simulator failed is not
//! executed on a rig that drives real hardware, unless the operator overrides it explicitly. A rig of
//! simulated and dummy devices only is never gated (its run is a preview itself).

use crate::rig_config::{Backend, RigConfig};

/// What the preview found.
#[derive(Clone, Debug, PartialEq)]
pub struct PreviewOutcome {
    /// Whether the skill passed: reachable, within limits, no fault, the knot tied.
    pub passed: bool,
    /// What failed (empty when it passed).
    pub reason: String,
}

/// Why a skill is not executed.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error(
    "the preview failed ({reason}): not executed on the real devices of {devices}; give the explicit override to execute anyway"
)]
pub struct ExecutionRefused {
    /// What failed in the preview.
    pub reason: String,
    /// The real devices, `arm.device` (`left.servo`).
    pub devices: String,
}

/// The rig's devices that drive real hardware, as `arm.device`.
pub fn real_devices(config: &RigConfig) -> Vec<String> {
    let mut out = Vec::new();
    for (arm, a) in config.arms.iter() {
        let devices = [
            ("servo", Some(a.servo.backend)),
            ("instrument", a.instrument.as_ref().map(|d| d.backend)),
            ("force", a.force.map(|d| d.backend)),
        ];
        for (name, backend) in devices {
            if backend.is_some_and(|b| !matches!(b, Backend::Sim | Backend::Dummy)) {
                out.push(format!("{arm}.{name}"));
            }
        }
    }
    out
}

/// Whether a skill whose preview gave `preview` may run on `config`'s devices.
pub fn may_execute(
    config: &RigConfig,
    preview: &PreviewOutcome,
    override_failed_preview: bool,
) -> Result<(), ExecutionRefused> {
    let real = real_devices(config);
    if preview.passed || override_failed_preview || real.is_empty() {
        return Ok(());
    }
    Err(ExecutionRefused { reason: preview.reason.clone(), devices: real.join(", ") })
}

//! The controller's tuning (each arm's model and trocar are [`crate::arm_setup::ArmSetup`]).

/// The controller's tuning.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ControllerParams {
    /// A device whose readings stay stale for this many cycles in a row faults the run.
    pub watchdog_cycles: u32,
    /// Fraction of each joint's rated speed the controller may command (0, 1]; a larger IK step is
    /// clamped to it.
    pub speed_scale: f64,
    /// Force fed back to the master device steering an arm, per newton on the instrument (0: none). The
    /// console frame is taken as aligned with the world.
    pub force_feedback_scale: f64,
}

impl Default for ControllerParams {
    /// 100 stale cycles (Mitsubishi's own figure for a lost link), half the rated joint speeds, no
    /// force feedback.
    fn default() -> Self {
        Self { watchdog_cycles: 100, speed_scale: 0.5, force_feedback_scale: 0.0 }
    }
}

impl ControllerParams {
    /// Every field out of range, with its name and reason.
    pub fn problems(&self) -> Vec<(&'static str, String)> {
        let mut problems = Vec::new();
        if self.watchdog_cycles == 0 {
            problems.push(("watchdog_cycles", "must be at least 1".to_owned()));
        }
        if !(self.speed_scale > 0.0 && self.speed_scale <= 1.0) {
            problems.push(("speed_scale", format!("{} is not in (0, 1]", self.speed_scale)));
        }
        if !(self.force_feedback_scale.is_finite() && self.force_feedback_scale >= 0.0) {
            problems
                .push(("force_feedback_scale", format!("{} is not a gain >= 0", self.force_feedback_scale)));
        }
        problems
    }
}

//! Teleoperation, as on a surgical console: while no skill runs, each master handle steers its
//! instrument. The handle's motion since it was engaged, turned into the world by `world_from_console`
//! and scaled down by `scale`, moves the tip from where it was at engagement; the handle's rotation
//! since then turns the whole tip frame alike (the wrist keeps its configuration: no roll flips); the
//! gripper sets the jaw. Holding the clutch pedal
//! disengages: the hand can move the handle back without moving the instrument, and on release the
//! motion counts from there. A running skill blocks manual input; when it ends the masters engage
//! afresh, so the instruments do not jump.

use nalgebra::{IsometryMatrix3, Rotation3};

use crate::kinematics::{TipOrientation, TipTarget};

/// How the masters steer the instruments.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TeleopSettings {
    /// Tip motion per handle motion (motion scaling; a console's typical 1:3 is 0.33).
    pub scale: f64,
    /// The assignable pedal that clutches (0-based).
    pub clutch_pedal: usize,
    /// The console's axes in the world (how the surgeon's view maps onto the patient).
    pub world_from_console: Rotation3<f64>,
    /// Jaw opening per gripper opening.
    pub jaw_per_gripper: f64,
}

impl Default for TeleopSettings {
    /// Scale 1:3, the first assignable pedal clutches, console axes = world axes, jaw = gripper.
    fn default() -> Self {
        Self {
            scale: 1.0 / 3.0,
            clutch_pedal: 0,
            world_from_console: Rotation3::identity(),
            jaw_per_gripper: 1.0,
        }
    }
}

impl TeleopSettings {
    /// The first bad field and why.
    pub fn problem(&self) -> Option<(&'static str, String)> {
        if !(self.scale.is_finite() && self.scale > 0.0 && self.scale <= 10.0) {
            return Some(("scale", format!("must be within 0..10, got {}", self.scale)));
        }
        if self.clutch_pedal >= crate::device::pedals::ASSIGNABLE_PEDALS {
            return Some(("clutch_pedal", format!("there is no assignable pedal {}", self.clutch_pedal)));
        }
        if !(self.jaw_per_gripper.is_finite() && self.jaw_per_gripper >= 0.0) {
            return Some(("jaw_per_gripper", format!("must be >= 0, got {}", self.jaw_per_gripper)));
        }
        None
    }
}

/// Where a master and its instrument were when the master engaged.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Engagement {
    /// The handle, console frame.
    pub console_from_handle: IsometryMatrix3<f64>,
    /// The tip, world frame.
    pub world_from_tip: IsometryMatrix3<f64>,
}

impl Engagement {
    /// The tip target for the handle now at `console_from_handle`.
    pub fn target(&self, settings: &TeleopSettings, console_from_handle: &IsometryMatrix3<f64>) -> TipTarget {
        let w = settings.world_from_console;
        let moved = console_from_handle.translation.vector - self.console_from_handle.translation.vector;
        let position = self.world_from_tip.translation.vector + w * moved * settings.scale;
        // The handle's turn since engagement, expressed in the world, applied to the tip.
        let turn_console = console_from_handle.rotation * self.console_from_handle.rotation.inverse();
        let turn_world = w * turn_console * w.inverse();
        let rotation = turn_world * self.world_from_tip.rotation;
        TipTarget { world_position_m: position, orientation: TipOrientation::Frame(rotation) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Translation3, Vector3};

    /// A handle's move and turn reach the tip scaled and turned into the world frame, and settings with a
    /// zero scale or a clutch pedal that does not exist are refused.
    #[test]
    fn the_handle_moves_the_tip_scaled_and_turned_into_the_world() {
        let settings = TeleopSettings {
            world_from_console: Rotation3::from_axis_angle(&Vector3::z_axis(), std::f64::consts::FRAC_PI_2),
            ..TeleopSettings::default()
        };
        let tip = IsometryMatrix3::from_parts(Translation3::new(0.0, 0.0, 1.0), Rotation3::identity());
        let engaged = Engagement { console_from_handle: IsometryMatrix3::identity(), world_from_tip: tip };
        let handle = IsometryMatrix3::from_parts(Translation3::new(0.09, 0.0, 0.0), Rotation3::identity());
        let target = engaged.target(&settings, &handle);
        // 9 cm along the console's x is 3 cm along the world's y (the console turned a quarter).
        assert!((target.world_position_m - Vector3::new(0.0, 0.03, 1.0)).norm() < 1e-12);
        // A handle turned 0.2 rad about the console's x turns the tip 0.2 rad about the world's y.
        let turned = IsometryMatrix3::from_parts(
            Translation3::identity(),
            Rotation3::from_axis_angle(&Vector3::x_axis(), 0.2),
        );
        let TipOrientation::Frame(r) = engaged.target(&settings, &turned).orientation else {
            panic!("a frame")
        };
        let expected = Rotation3::from_axis_angle(&Vector3::y_axis(), 0.2);
        assert!(r.angle_to(&expected) < 1e-12, "{r:?}");
        assert!(TeleopSettings { scale: 0.0, ..settings }.problem().is_some());
        assert!(TeleopSettings { clutch_pedal: 99, ..settings }.problem().is_some());
        assert!(settings.problem().is_none());
    }
}

//! A gamepad as a surgeon's console at a desk: a master device and the foot pedals. A stick is not a
//! position device, so the handle is rate-controlled: the left stick moves it in the console's x and y,
//! the triggers down (left) and up (right), at up to [`GamepadMapping::speed_mps`] at full deflection;
//! the South button (A, cross) held closes the gripper. The pedals: East (B, circle) is the clutch
//! (assignable 0), North (Y, triangle) the skill pedal (assignable 1), Select/Back the emergency stop.
//!
//! The mapping ([`GamepadMapping`]) is plain code, tested without a gamepad; the driver that reads a real
//! one (`gilrs`, a thread polling it) is built with the `gamepad` feature.

#[cfg(feature = "gamepad")]
pub mod driver;

use nalgebra::{IsometryMatrix3, Translation3, Vector3};

use super::master::MasterState;
use super::pedals::PedalState;

/// What the gamepad shows at a moment: sticks in -1..1 (x right, y up), triggers in 0..1, buttons.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GamepadInput {
    /// The left stick.
    pub left_stick: [f32; 2],
    /// The left trigger.
    pub left_trigger: f32,
    /// The right trigger.
    pub right_trigger: f32,
    /// South (A, cross).
    pub south: bool,
    /// East (B, circle).
    pub east: bool,
    /// North (Y, triangle).
    pub north: bool,
    /// Select (Back, Share).
    pub select: bool,
    /// A gamepad is connected.
    pub connected: bool,
}

/// How the gamepad's input becomes a handle and pedals.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GamepadMapping {
    /// Handle speed at full deflection, m/s.
    pub speed_mps: f64,
    /// Deflections below this are none.
    pub deadzone: f32,
    /// The gripper's opening when South is not held, rad.
    pub gripper_open_rad: f64,
    /// The handle stays within this distance of the console's origin, m.
    pub reach_m: f64,
}

impl Default for GamepadMapping {
    /// 5 cm/s at full deflection, 0.1 dead zone, gripper open 0.6 rad, within 20 cm.
    fn default() -> Self {
        Self { speed_mps: 0.05, deadzone: 0.1, gripper_open_rad: 0.6, reach_m: 0.2 }
    }
}

impl GamepadMapping {
    fn axis(&self, x: f32) -> f64 {
        if x.abs() < self.deadzone || !x.is_finite() { 0.0 } else { f64::from(x.clamp(-1.0, 1.0)) }
    }

    /// The handle's velocity in the console's frame, m/s.
    pub fn velocity_mps(&self, input: &GamepadInput) -> Vector3<f64> {
        let [x, y] = input.left_stick;
        let z = self.axis(input.right_trigger) - self.axis(input.left_trigger);
        Vector3::new(self.axis(x), self.axis(y), z) * self.speed_mps
    }

    /// The handle after `dt_s` at `input`, from `position_m` (kept within the reach).
    pub fn advance(&self, position_m: Vector3<f64>, input: &GamepadInput, dt_s: f64) -> Vector3<f64> {
        let next = position_m + self.velocity_mps(input) * dt_s.max(0.0);
        let r = next.norm();
        if r > self.reach_m { next * (self.reach_m / r) } else { next }
    }

    /// The master's reading with the handle at `position_m`.
    pub fn master_state(&self, position_m: Vector3<f64>, input: &GamepadInput) -> MasterState {
        MasterState {
            console_from_handle: IsometryMatrix3::from_parts(
                Translation3::from(position_m),
                Default::default(),
            ),
            gripper_rad: if input.south { 0.0 } else { self.gripper_open_rad },
            buttons: u32::from(input.south),
            fresh: true,
        }
    }

    /// The pedals the buttons stand for.
    pub fn pedal_state(&self, input: &GamepadInput) -> PedalState {
        let mut pedals = PedalState { emergency_stop: input.select, ..PedalState::default() };
        pedals.assignable[0] = input.east;
        pedals.assignable[1] = input.north;
        pedals
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The sticks move the handle at a rate, never inside the dead zone or past the reach; the buttons close
    /// the gripper and press the emergency stop and assignable pedals.
    #[test]
    fn sticks_move_the_handle_at_a_rate_and_buttons_are_the_pedals() {
        let m = GamepadMapping::default();
        let input = GamepadInput { left_stick: [1.0, -0.5], right_trigger: 0.5, ..GamepadInput::default() };
        let p = m.advance(Vector3::zeros(), &input, 0.2);
        assert!((p - Vector3::new(0.01, -0.005, 0.005)).norm() < 1e-12, "{p:?}");
        // Inside the dead zone nothing moves; the reach bounds the handle.
        let still = GamepadInput { left_stick: [0.05, -0.05], ..GamepadInput::default() };
        assert_eq!(m.advance(p, &still, 1.0), p);
        let far = m.advance(Vector3::zeros(), &GamepadInput { left_stick: [1.0, 0.0], ..input }, 100.0);
        assert!((far.norm() - m.reach_m).abs() < 1e-12);
        let held =
            GamepadInput { south: true, east: true, north: false, select: true, ..GamepadInput::default() };
        assert_eq!(m.master_state(p, &held).gripper_rad, 0.0);
        assert_eq!(m.master_state(p, &GamepadInput::default()).gripper_rad, 0.6);
        let pedals = m.pedal_state(&held);
        assert!(pedals.emergency_stop && pedals.assignable[0] && !pedals.assignable[1]);
    }
}

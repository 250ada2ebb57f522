//! The gamepad driver (feature `gamepad`): a thread owns the `gilrs` context and keeps the first
//! connected gamepad's state; the master and the pedals read it each cycle. The handle is integrated
//! over wall-clock time (a person at a desk moves in real time, whatever the simulation's pace).

use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use gilrs::{Axis, Button, Gilrs};
use nalgebra::Vector3;

use super::{GamepadInput, GamepadMapping};
use crate::device::{
    DeviceError, DeviceId, DeviceKind, ForceFeedback, MasterDevice, MasterState, PedalState, Pedals,
};

fn lock(state: &Mutex<GamepadInput>) -> std::sync::MutexGuard<'_, GamepadInput> {
    state.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// The state the polling thread keeps.
#[derive(Clone, Debug, Default)]
pub struct SharedGamepad(Arc<Mutex<GamepadInput>>);

impl SharedGamepad {
    /// Starts the thread that polls the gamepads (every 2 ms). Fails when `gilrs` cannot start.
    pub fn open() -> Result<Self, DeviceError> {
        let shared = Self::default();
        let state = shared.0.clone();
        let (ready_tx, ready_rx) = std::sync::mpsc::channel();
        std::thread::Builder::new()
            .name("knotlab-gamepad".into())
            .spawn(move || {
                let mut gilrs = match Gilrs::new() {
                    Ok(g) => {
                        let _ = ready_tx.send(Ok(()));
                        g
                    }
                    Err(e) => {
                        let _ = ready_tx.send(Err(e.to_string()));
                        return;
                    }
                };
                loop {
                    while gilrs.next_event().is_some() {}
                    let input =
                        gilrs.gamepads().next().map_or(GamepadInput::default(), |(_, pad)| GamepadInput {
                            left_stick: [pad.value(Axis::LeftStickX), pad.value(Axis::LeftStickY)],
                            left_trigger: pad.button_data(Button::LeftTrigger2).map_or(0.0, |d| d.value()),
                            right_trigger: pad.button_data(Button::RightTrigger2).map_or(0.0, |d| d.value()),
                            south: pad.is_pressed(Button::South),
                            east: pad.is_pressed(Button::East),
                            north: pad.is_pressed(Button::North),
                            select: pad.is_pressed(Button::Select),
                            connected: pad.is_connected(),
                        });
                    *lock(&state) = input;
                    std::thread::sleep(Duration::from_millis(2));
                }
            })
            .map_err(|e| DeviceError::Protocol {
                device: DeviceId::shared(DeviceKind::Pedals),
                reason: format!("cannot start the gamepad thread: {e}"),
            })?;
        let reason = match ready_rx.recv() {
            Ok(Ok(())) => return Ok(shared),
            Ok(Err(reason)) => format!("gilrs: {reason}"),
            Err(_) => "the gamepad thread ended before it started".to_owned(),
        };
        Err(DeviceError::Protocol { device: DeviceId::shared(DeviceKind::Pedals), reason })
    }

    fn get(&self) -> GamepadInput {
        *lock(&self.0)
    }
}

/// A master device on a gamepad.
pub struct GamepadMaster {
    shared: SharedGamepad,
    mapping: GamepadMapping,
    position_m: Vector3<f64>,
    last: Option<Instant>,
}

impl GamepadMaster {
    /// A master reading `shared`, the handle at the console's origin.
    pub fn new(shared: SharedGamepad, mapping: GamepadMapping) -> Self {
        Self { shared, mapping, position_m: Vector3::zeros(), last: None }
    }
}

impl MasterDevice for GamepadMaster {
    fn read(&mut self) -> Result<MasterState, DeviceError> {
        let input = self.shared.get();
        let now = Instant::now();
        let dt = self.last.map_or(0.0, |t| now.duration_since(t).as_secs_f64());
        self.last = Some(now);
        self.position_m = self.mapping.advance(self.position_m, &input, dt);
        Ok(self.mapping.master_state(self.position_m, &input))
    }

    fn write(&mut self, _feedback: &ForceFeedback) -> Result<(), DeviceError> {
        Ok(())
    }
}

/// The foot pedals on a gamepad's buttons.
pub struct GamepadPedals {
    shared: SharedGamepad,
    mapping: GamepadMapping,
}

impl GamepadPedals {
    /// Pedals reading `shared`.
    pub fn new(shared: SharedGamepad, mapping: GamepadMapping) -> Self {
        Self { shared, mapping }
    }
}

impl Pedals for GamepadPedals {
    fn read(&mut self) -> Result<PedalState, DeviceError> {
        Ok(self.mapping.pedal_state(&self.shared.get()))
    }
}

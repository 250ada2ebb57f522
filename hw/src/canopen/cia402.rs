//! The CiA 402 drive state machine: the state read from the statusword (object 0x6041), the
//! controlword (0x6040) commands that move between states, the way up to Operation Enabled, and the
//! drive's own side of the transitions (for the emulator).
//!
//! | state | statusword, masked | reached by |
//! |---|---|---|
//! | Not Ready to Switch On | `x0xx 0000` (0x4F: 0x00) | power on; goes on by itself |
//! | Switch On Disabled | `x1xx 0000` (0x4F: 0x40) | disable voltage, quick stop, fault reset |
//! | Ready to Switch On | `x01x 0001` (0x6F: 0x21) | shutdown (0x06) |
//! | Switched On | `x01x 0011` (0x6F: 0x23) | switch on (0x07) |
//! | Operation Enabled | `x01x 0111` (0x6F: 0x27) | enable operation (0x0F) |
//! | Quick Stop Active | `x00x 0111` (0x6F: 0x07) | quick stop (0x02) |
//! | Fault Reaction Active | `x0xx 1111` (0x4F: 0x0F) | a fault |
//! | Fault | `x0xx 1000` (0x4F: 0x08) | the fault reaction's end |

/// A drive's state.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DriveState {
    /// Initialising; it goes on to Switch On Disabled by itself.
    NotReadyToSwitchOn,
    /// No power to the motor; waits for shutdown.
    SwitchOnDisabled,
    /// Ready; waits for switch on.
    ReadyToSwitchOn,
    /// Power stage on, no torque; waits for enable operation.
    SwitchedOn,
    /// The drive follows its set-points.
    OperationEnabled,
    /// Stopping at its quick-stop deceleration.
    QuickStopActive,
    /// Reacting to a fault.
    FaultReactionActive,
    /// Faulted; waits for fault reset.
    Fault,
}

/// A controlword command.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Command {
    /// 0x06: to Ready to Switch On.
    Shutdown,
    /// 0x07: to Switched On.
    SwitchOn,
    /// 0x0F: to Operation Enabled.
    EnableOperation,
    /// 0x07 from Operation Enabled: back to Switched On.
    DisableOperation,
    /// 0x00: to Switch On Disabled.
    DisableVoltage,
    /// 0x02: to Quick Stop Active.
    QuickStop,
    /// 0x80 (its rising edge): from Fault to Switch On Disabled.
    FaultReset,
}

impl Command {
    /// The controlword (bits 0-3 and 7; the mode-specific bits left 0).
    pub fn controlword(self) -> u16 {
        match self {
            Command::Shutdown => 0x0006,
            Command::SwitchOn | Command::DisableOperation => 0x0007,
            Command::EnableOperation => 0x000F,
            Command::DisableVoltage => 0x0000,
            Command::QuickStop => 0x0002,
            Command::FaultReset => 0x0080,
        }
    }
}

impl DriveState {
    /// The state a statusword says (None: a pattern CiA 402 does not define).
    pub fn of_statusword(sw: u16) -> Option<Self> {
        let (m4f, m6f) = (sw & 0x4F, sw & 0x6F);
        Some(match (m4f, m6f) {
            (0x00, _) => DriveState::NotReadyToSwitchOn,
            (0x40, _) => DriveState::SwitchOnDisabled,
            (0x0F, _) => DriveState::FaultReactionActive,
            (0x08, _) => DriveState::Fault,
            (_, 0x21) => DriveState::ReadyToSwitchOn,
            (_, 0x23) => DriveState::SwitchedOn,
            (_, 0x27) => DriveState::OperationEnabled,
            (_, 0x07) => DriveState::QuickStopActive,
            _ => return None,
        })
    }

    /// The statusword a drive in this state reports (bits 0-6; bit 4, voltage enabled, where the power
    /// stage is on; bit 9, remote, always).
    pub fn statusword(self) -> u16 {
        let remote = 0x0200;
        remote
            | match self {
                DriveState::NotReadyToSwitchOn => 0x0000,
                DriveState::SwitchOnDisabled => 0x0040,
                DriveState::ReadyToSwitchOn => 0x0031,
                DriveState::SwitchedOn => 0x0033,
                DriveState::OperationEnabled => 0x0037,
                DriveState::QuickStopActive => 0x0017,
                DriveState::FaultReactionActive => 0x001F,
                DriveState::Fault => 0x0008,
            }
    }

    /// The command that takes a drive in this state one step towards Operation Enabled (None: there
    /// already, or it must wait: initialising or reacting to a fault).
    pub fn towards_operation(self) -> Option<Command> {
        match self {
            DriveState::SwitchOnDisabled => Some(Command::Shutdown),
            DriveState::ReadyToSwitchOn => Some(Command::SwitchOn),
            DriveState::SwitchedOn => Some(Command::EnableOperation),
            DriveState::Fault => Some(Command::FaultReset),
            DriveState::QuickStopActive => Some(Command::DisableVoltage),
            DriveState::OperationEnabled
            | DriveState::NotReadyToSwitchOn
            | DriveState::FaultReactionActive => None,
        }
    }

    /// The drive's own side: the state after it receives `controlword` (the last one before it being
    /// `previous`, for the fault reset's rising edge).
    pub fn after(self, controlword: u16, previous: u16) -> Self {
        let low = controlword & 0x0F;
        let enable_voltage = low & 0x2 != 0;
        let quick_stop_off = low & 0x4 != 0; // bit 2 low means quick stop
        match self {
            DriveState::Fault if controlword & 0x80 != 0 && previous & 0x80 == 0 => {
                DriveState::SwitchOnDisabled
            }
            DriveState::Fault | DriveState::FaultReactionActive | DriveState::NotReadyToSwitchOn => self,
            _ if !enable_voltage => DriveState::SwitchOnDisabled,
            DriveState::OperationEnabled if !quick_stop_off => DriveState::QuickStopActive,
            DriveState::QuickStopActive => self,
            _ if !quick_stop_off => DriveState::SwitchOnDisabled,
            // bits 0-3: 0110 shutdown, 0111 switch on / disable operation, 1111 enable operation
            _ => match (self, low) {
                (_, 0x6 | 0xE) => DriveState::ReadyToSwitchOn,
                (DriveState::ReadyToSwitchOn | DriveState::OperationEnabled, 0x7) => DriveState::SwitchedOn,
                (DriveState::SwitchedOn, 0x7) => DriveState::SwitchedOn,
                (DriveState::SwitchedOn | DriveState::OperationEnabled, 0xF) => DriveState::OperationEnabled,
                (DriveState::ReadyToSwitchOn, 0xF) => DriveState::SwitchedOn,
                _ => self,
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every state's statusword reads back as the state; the commands towards Operation Enabled, as a
    /// drive answers them, get there from Switch On Disabled and from Fault; disable voltage and quick
    /// stop leave it as CiA 402 says.
    #[test]
    fn the_state_machine_reaches_operation_enabled_and_leaves_it() {
        let all = [
            DriveState::NotReadyToSwitchOn,
            DriveState::SwitchOnDisabled,
            DriveState::ReadyToSwitchOn,
            DriveState::SwitchedOn,
            DriveState::OperationEnabled,
            DriveState::QuickStopActive,
            DriveState::FaultReactionActive,
            DriveState::Fault,
        ];
        for state in all {
            assert_eq!(DriveState::of_statusword(state.statusword()), Some(state), "{state:?}");
        }
        assert_eq!(DriveState::of_statusword(0x0250), Some(DriveState::SwitchOnDisabled));
        assert_eq!(DriveState::of_statusword(0x0061), None);
        for start in [DriveState::SwitchOnDisabled, DriveState::Fault] {
            let (mut state, mut previous, mut steps) = (start, 0u16, Vec::new());
            while let Some(command) = state.towards_operation() {
                let cw = command.controlword();
                state = state.after(cw, previous);
                previous = cw;
                steps.push(command);
                assert!(steps.len() < 6, "{steps:?}");
            }
            assert_eq!(state, DriveState::OperationEnabled, "from {start:?}: {steps:?}");
        }
        let on = DriveState::OperationEnabled;
        assert_eq!(on.after(Command::DisableVoltage.controlword(), 0x0F), DriveState::SwitchOnDisabled);
        assert_eq!(on.after(Command::QuickStop.controlword(), 0x0F), DriveState::QuickStopActive);
        assert_eq!(on.after(Command::DisableOperation.controlword(), 0x0F), DriveState::SwitchedOn);
        assert_eq!(on.after(Command::Shutdown.controlword(), 0x0F), DriveState::ReadyToSwitchOn);
        // A fault reset is its rising edge: held high it does nothing more.
        assert_eq!(DriveState::Fault.after(0x80, 0x80), DriveState::Fault);
    }
}

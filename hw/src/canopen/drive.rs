//! The instrument's four motors (roll, pitch, yaw, jaw) as CiA 402 drives on CAN: one
//! [`InstrumentDrive`].
//!
//! - [`CanopenDrive::connect`] configures each node by SDO: cyclic synchronous position mode (read
//!   back from the mode display), its heartbeat, the PDO mapping read back (RPDO1 controlword and
//!   target position, TPDO1 statusword and position actual), the software limits read back; starts the
//!   nodes (NMT) and walks each drive's state machine to Operation Enabled, its target set where it
//!   stands so that nothing jumps. A node that aborts a transfer, or does not answer, is named with the
//!   object and CiA 301's reason.
//! - Each `write` sends every node's RPDO1 (enable operation, the target in counts) and then SYNC;
//!   each `read` takes the TPDO1s that answered it (the first read gives the positions read at start,
//!   fresh: the controller takes its first set-point from them). Joints become motor angles through the coupling
//!   matrix (the cables couple the wrist's and the jaw's motors) and counts through each motor's counts
//!   per radian.
//! - An EMCY from a node, or a statusword showing Fault, faults the device naming the node and the
//!   error; a node whose heartbeat has not come for `heartbeat_timeout_s` faults it as a link down.
//! - `shutdown` takes every drive down (shutdown, disable voltage) and the nodes to pre-operational.

use std::time::{Duration, Instant};

use nalgebra::{Matrix4, Vector4};

use crate::device::{DeviceError, DeviceId, DeviceKind, InstrumentDrive, InstrumentState};
use crate::kinematics::ToolJoints;
use crate::rig::ArmName;

use super::bus::CanTransport;
use super::cia402::{Command, DriveState};
use super::dictionary::{self as od, MODE_CSP, emcy_reason};
use super::frame::{CanFrame, CobId};
use super::sdo::{Object, SdoRequest, SdoResponse, abort_reason};

/// The four axes, in the order of the nodes.
pub const AXES: [&str; 4] = ["roll", "pitch", "yaw", "jaw"];

/// How the instrument's drives are wired.
#[derive(Clone, Debug, PartialEq)]
pub struct CanopenConfig {
    /// The instrument it moves (names the device in errors).
    pub arm: ArmName,
    /// The node ids of the roll, pitch, yaw and jaw drives.
    pub nodes: [u8; 4],
    /// Each motor's encoder counts per radian of the motor (the gear's ratio included).
    pub counts_per_rad: [f64; 4],
    /// Motor angles from joint angles: motor = coupling x (roll, pitch, yaw, jaw), rad.
    pub coupling: Matrix4<f64>,
    /// The heartbeat each node is asked to send, ms.
    pub heartbeat_ms: u16,
    /// A node unheard of for this long has dropped out, s.
    pub heartbeat_timeout_s: f64,
    /// How long to wait for an SDO answer, s.
    pub sdo_timeout_s: f64,
    /// The following error window each drive is given, counts (0: not watched).
    pub following_error_counts: u32,
}

impl CanopenConfig {
    /// Nodes `nodes`, `counts_per_rad` on every motor, no coupling, a 10 ms heartbeat given up after
    /// 50 ms, SDO answers waited for 0.1 s, no following error window.
    pub fn new(arm: ArmName, nodes: [u8; 4], counts_per_rad: f64) -> Self {
        Self {
            arm,
            nodes,
            counts_per_rad: [counts_per_rad; 4],
            coupling: Matrix4::identity(),
            heartbeat_ms: 10,
            heartbeat_timeout_s: 0.05,
            sdo_timeout_s: 0.1,
            following_error_counts: 0,
        }
    }
}

/// A session with the instrument's four drives.
pub struct CanopenDrive {
    config: CanopenConfig,
    device: DeviceId,
    bus: Box<dyn CanTransport>,
    joints_from_motors: Matrix4<f64>,
    positions_counts: [i32; 4],
    heard: [Instant; 4],
    limits_counts: [[i32; 2]; 4],
    down: bool,
    /// The positions read at start have not been given yet (the first read's are new).
    unread: bool,
}

impl CanopenDrive {
    /// Configures and enables the drives on `bus`.
    pub fn connect(bus: Box<dyn CanTransport>, config: CanopenConfig) -> Result<Self, DeviceError> {
        let device = DeviceId::of_arm(DeviceKind::InstrumentDrive, config.arm);
        let fault = |reason: String| DeviceError::Fault { device, reason };
        let joints_from_motors = config.coupling.try_inverse().ok_or_else(|| {
            fault(format!("the coupling matrix {:?} cannot be inverted", config.coupling.as_slice()))
        })?;
        if config.counts_per_rad.iter().any(|c| !(c.is_finite() && *c != 0.0)) {
            return Err(fault(format!(
                "counts per radian {:?}: each finite and not 0",
                config.counts_per_rad
            )));
        }
        let mut drive = Self {
            device,
            bus,
            joints_from_motors,
            positions_counts: [0; 4],
            heard: [Instant::now(); 4],
            limits_counts: [[0; 2]; 4],
            down: false,
            unread: true,
            config,
        };
        for k in 0..4 {
            drive.configure(k)?;
        }
        drive.send(CobId::Nmt, &[0x01, 0])?;
        for k in 0..4 {
            drive.enable(k)?;
        }
        drive.heard = [Instant::now(); 4];
        Ok(drive)
    }

    /// Each drive's software limits as it reported them, counts (roll, pitch, yaw, jaw).
    pub fn limits_counts(&self) -> [[i32; 2]; 4] {
        self.limits_counts
    }

    fn name(&self, k: usize) -> String {
        format!("node {} ({})", self.config.nodes[k], AXES[k])
    }

    fn send(&mut self, cob: CobId, data: &[u8]) -> Result<(), DeviceError> {
        let frame = cob
            .frame(data)
            .map_err(|e| DeviceError::Protocol { device: self.device, reason: e.to_string() })?;
        self.bus.send(&frame).map_err(|e| DeviceError::Fault { device: self.device, reason: e.to_string() })
    }

    /// One SDO exchange with drive `k`; frames of other kinds that come meanwhile are looked at.
    fn sdo(&mut self, k: usize, request: SdoRequest) -> Result<u32, DeviceError> {
        let node = self.config.nodes[k];
        let object = match request {
            SdoRequest::Read { object } | SdoRequest::Write { object, .. } => object,
        };
        let what = format!("{} object 0x{:04X}:{:02X}", self.name(k), object.index, object.subindex);
        let frame = request
            .frame(node)
            .map_err(|e| DeviceError::Protocol { device: self.device, reason: e.to_string() })?;
        self.bus
            .send(&frame)
            .map_err(|e| DeviceError::Fault { device: self.device, reason: e.to_string() })?;
        let start = Instant::now();
        loop {
            while let Some(frame) = self.receive()? {
                if CobId::of(frame.id()) != Some(CobId::SdoResponse(node)) {
                    self.look_at(&frame)?;
                    continue;
                }
                let bad = |reason: String| DeviceError::Protocol {
                    device: self.device,
                    reason: format!("{what}: {reason}"),
                };
                return match SdoResponse::decode(frame.data()).map_err(|e| bad(e.to_string()))? {
                    SdoResponse::Abort { code, .. } => Err(DeviceError::Fault {
                        device: self.device,
                        reason: format!("{what}: the drive refused it: 0x{code:08X}, {}", abort_reason(code)),
                    }),
                    SdoResponse::Value { object: o, .. } | SdoResponse::Written { object: o }
                        if o != object =>
                    {
                        Err(bad(format!("the answer names 0x{:04X}:{:02X}", o.index, o.subindex)))
                    }
                    SdoResponse::Value { value, .. } => Ok(value),
                    SdoResponse::Written { .. } => Ok(0),
                };
            }
            if start.elapsed().as_secs_f64() > self.config.sdo_timeout_s {
                return Err(DeviceError::Fault {
                    device: self.device,
                    reason: format!("{what}: no SDO answer within {} s", self.config.sdo_timeout_s),
                });
            }
            std::thread::sleep(Duration::from_micros(200));
        }
    }

    fn write_sdo(&mut self, k: usize, object: Object, value: u32, len: u8) -> Result<(), DeviceError> {
        self.sdo(k, SdoRequest::Write { object, value, len }).map(|_| ())
    }

    fn read_sdo(&mut self, k: usize, object: Object) -> Result<u32, DeviceError> {
        self.sdo(k, SdoRequest::Read { object })
    }

    fn configure(&mut self, k: usize) -> Result<(), DeviceError> {
        self.write_sdo(k, od::MODES_OF_OPERATION, u32::from(MODE_CSP), 1)?;
        let mode = self.read_sdo(k, od::MODES_OF_OPERATION_DISPLAY)? as u8;
        if mode != MODE_CSP {
            return Err(DeviceError::Fault {
                device: self.device,
                reason: format!(
                    "{}: mode of operation {mode}, not {MODE_CSP} (cyclic synchronous position)",
                    self.name(k)
                ),
            });
        }
        self.write_sdo(k, od::HEARTBEAT_PRODUCER, u32::from(self.config.heartbeat_ms), 2)?;
        self.write_sdo(k, od::FOLLOWING_ERROR_WINDOW, self.config.following_error_counts, 4)?;
        let mappings = [(od::RPDO1_MAPPING, od::RPDO1, "RPDO1"), (od::TPDO1_MAPPING, od::TPDO1, "TPDO1")];
        for (objects, expected, pdo) in mappings {
            for (object, want) in objects.iter().zip(expected) {
                let got = self.read_sdo(k, *object)?;
                if got != want {
                    return Err(DeviceError::Fault {
                        device: self.device,
                        reason: format!(
                            "{}: {pdo} maps 0x{got:08X} where this driver needs 0x{want:08X}",
                            self.name(k)
                        ),
                    });
                }
            }
        }
        for (b, object) in od::SOFTWARE_LIMITS.iter().enumerate() {
            self.limits_counts[k][b] = self.read_sdo(k, *object)? as i32;
        }
        Ok(())
    }

    fn enable(&mut self, k: usize) -> Result<(), DeviceError> {
        let here = self.read_sdo(k, od::POSITION_ACTUAL)? as i32;
        self.write_sdo(k, od::TARGET_POSITION, here as u32, 4)?;
        self.positions_counts[k] = here;
        for _ in 0..8 {
            let sw = self.read_sdo(k, od::STATUSWORD)? as u16;
            let state = DriveState::of_statusword(sw).ok_or_else(|| DeviceError::Protocol {
                device: self.device,
                reason: format!("{}: statusword 0x{sw:04X} is no CiA 402 state", self.name(k)),
            })?;
            match state.towards_operation() {
                None if state == DriveState::OperationEnabled => return Ok(()),
                None => std::thread::sleep(Duration::from_millis(1)),
                Some(command) => self.write_sdo(k, od::CONTROLWORD, u32::from(command.controlword()), 2)?,
            }
        }
        Err(DeviceError::Fault {
            device: self.device,
            reason: format!("{}: did not reach Operation Enabled", self.name(k)),
        })
    }

    fn receive(&mut self) -> Result<Option<CanFrame>, DeviceError> {
        self.bus.try_recv().map_err(|e| DeviceError::Fault { device: self.device, reason: e.to_string() })
    }

    /// Takes a frame that is not an SDO answer: a TPDO, an EMCY or a heartbeat; whether it was a TPDO.
    fn look_at(&mut self, frame: &CanFrame) -> Result<bool, DeviceError> {
        let Some(cob) = CobId::of(frame.id()) else { return Ok(false) };
        let data = frame.data();
        let index = |node: u8| self.config.nodes.iter().position(|n| *n == node);
        match cob {
            CobId::Emcy(node) if data.len() >= 2 => {
                if let Some(k) = index(node) {
                    let code = u16::from_le_bytes([data[0], data[1]]);
                    if code != 0 {
                        return Err(DeviceError::Fault {
                            device: self.device,
                            reason: format!(
                                "{}: emergency 0x{code:04X} ({})",
                                self.name(k),
                                emcy_reason(code)
                            ),
                        });
                    }
                }
            }
            CobId::Heartbeat(node) => {
                if let Some(k) = index(node) {
                    self.heard[k] = Instant::now();
                }
            }
            CobId::Tpdo(1, node) if data.len() >= 6 => {
                if let Some(k) = index(node) {
                    self.heard[k] = Instant::now();
                    let sw = u16::from_le_bytes([data[0], data[1]]);
                    if matches!(
                        DriveState::of_statusword(sw),
                        Some(DriveState::Fault | DriveState::FaultReactionActive)
                    ) {
                        return Err(DeviceError::Fault {
                            device: self.device,
                            reason: format!(
                                "{}: the drive is in Fault (statusword 0x{sw:04X})",
                                self.name(k)
                            ),
                        });
                    }
                    self.positions_counts[k] = i32::from_le_bytes([data[2], data[3], data[4], data[5]]);
                    return Ok(true);
                }
            }
            _ => {}
        }
        Ok(false)
    }
}

impl InstrumentDrive for CanopenDrive {
    fn read(&mut self) -> Result<InstrumentState, DeviceError> {
        if self.down {
            return Err(DeviceError::Closed { device: self.device });
        }
        let mut fresh = 0;
        while let Some(frame) = self.receive()? {
            fresh += usize::from(self.look_at(&frame)?);
        }
        for k in 0..4 {
            let silent_s = self.heard[k].elapsed().as_secs_f64();
            if silent_s > self.config.heartbeat_timeout_s {
                return Err(DeviceError::LinkDown {
                    device: self.device,
                    lost: 0,
                    detail: format!("{}: heartbeat lost, nothing for {silent_s:.3} s", self.name(k)),
                });
            }
        }
        let motors =
            Vector4::from_fn(|k, _| f64::from(self.positions_counts[k]) / self.config.counts_per_rad[k]);
        let j = self.joints_from_motors * motors;
        let first = std::mem::take(&mut self.unread);
        Ok(InstrumentState {
            joints: ToolJoints { roll_rad: j[0], pitch_rad: j[1], yaw_rad: j[2], jaw_rad: j[3] },
            fresh: first || fresh >= 4,
        })
    }

    fn write(&mut self, joints: &ToolJoints) -> Result<(), DeviceError> {
        if self.down {
            return Err(DeviceError::Closed { device: self.device });
        }
        let j = Vector4::new(joints.roll_rad, joints.pitch_rad, joints.yaw_rad, joints.jaw_rad);
        let motors = self.config.coupling * j;
        for k in 0..4 {
            let counts = (motors[k] * self.config.counts_per_rad[k]).round();
            if !(counts.is_finite() && counts.abs() <= f64::from(i32::MAX)) {
                return Err(DeviceError::Fault {
                    device: self.device,
                    reason: format!(
                        "{}: target {} rad is beyond the drive's counts",
                        self.name(k),
                        motors[k]
                    ),
                });
            }
            let mut pdo = [0u8; 6];
            pdo[0..2].copy_from_slice(&Command::EnableOperation.controlword().to_le_bytes());
            pdo[2..6].copy_from_slice(&(counts as i32).to_le_bytes());
            self.send(CobId::Rpdo(1, self.config.nodes[k]), &pdo)?;
        }
        self.send(CobId::Sync, &[])
    }

    fn shutdown(&mut self) -> Result<(), DeviceError> {
        if self.down {
            return Ok(());
        }
        self.down = true;
        let mut first = None;
        for k in 0..4 {
            for command in [Command::Shutdown, Command::DisableVoltage] {
                if let Err(e) = self.write_sdo(k, od::CONTROLWORD, u32::from(command.controlword()), 2) {
                    first.get_or_insert(e);
                    break;
                }
            }
        }
        self.send(CobId::Nmt, &[0x80, 0])?;
        first.map_or(Ok(()), Err)
    }
}

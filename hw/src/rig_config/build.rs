//! From a rig config to devices and a controller. Every joint driver is wrapped in its limit
//! decorators (position and velocity from the rig's URDF, and a per-cycle step limit where the config
//! asks), so a bad command is refused before it reaches any backend.

use nalgebra::Vector3;

use crate::controller::{ArmSetup, Controller, ControllerError, ControllerParams};
use crate::device::clock::PacedByDevices;
use crate::device::dummy::{
    DummyArmServo, DummyForceSensor, DummyInstrumentDrive, DummyMaster, DummyPedals, ForceHandle,
    MasterHandle, PedalHandle, VirtualClock,
};
use crate::device::{
    ArmDevices, ArmServo, CycleClock, DeviceError, DeviceId, DeviceKind, DeviceSet, ForceSensor,
    InstrumentDrive, MasterDevice, Pedals, PositionLimit, StepLimit, VelocityLimit,
};
use crate::kinematics::{ArmJoints, Tool};
use crate::melfa::{CR750_CYCLE_S, Layout, MelfaArm, MelfaConfig};
use crate::netft::{NetFtConfig, NetFtSensor};
use crate::rig::{ArmName, Rig};

use super::schema::{Backend, ForceConfig, InstrumentConfig, RigConfig};
use crate::canopen::bus::CanTransport;
use crate::canopen::drive::{CanopenConfig, CanopenDrive};
use crate::canopen::udp::UdpCan;

/// The simulated scene as a source of devices; the `sim` crate implements it, so `hw` needs no
/// simulator. Every device it hands out acts on the same scene, and its clock steps that scene.
pub trait SimulatedScene {
    /// The simulation's step, s.
    fn period_s(&self) -> f64;
    /// The arm's servo.
    fn arm_servo(&mut self, arm: ArmName) -> Box<dyn ArmServo>;
    /// The arm's instrument motors.
    fn instrument_drive(&mut self, arm: ArmName) -> Box<dyn InstrumentDrive>;
    /// The arm's strain gauges.
    fn force_sensor(&mut self, arm: ArmName) -> Box<dyn ForceSensor>;
    /// The clock that steps the scene once per cycle.
    fn clock(&mut self) -> Box<dyn CycleClock>;
    /// The scene's trocar for the arm, world frame, m.
    fn world_trocar_m(&self, arm: ArmName) -> Vector3<f64>;
    /// Where the arm stands in the scene now (dummy devices of a sim rig start there).
    fn joints(&self, arm: ArmName) -> ArmJoints;
}

/// Why a rig config could not be turned into devices.
#[derive(Debug, thiserror::Error)]
pub enum RigBuildError {
    /// A `sim` device without a simulated scene to take it from.
    #[error("{key}: backend \"sim\" needs the simulated scene: build this rig through knotlab-sim's backend")]
    NeedsSimulator {
        /// The key that asked for it.
        key: String,
    },
    /// The config has problems (see [`RigConfig::problems`]).
    #[error("{}", problems.iter().map(|(k, r)| format!("{k}: {r}")).collect::<Vec<_>>().join("; "))]
    Invalid {
        /// (key, reason) for each problem.
        problems: Vec<(String, String)>,
    },
    /// A device could not be opened (a MELFA controller that does not answer).
    #[error("{key}: {source}")]
    Device {
        /// The device's key.
        key: String,
        /// Why.
        source: DeviceError,
    },
}

/// Opens the gamepad once for every device on it.
#[derive(Default)]
struct GamepadOpener {
    #[cfg(feature = "gamepad")]
    shared: Option<crate::device::gamepad::driver::SharedGamepad>,
}

impl GamepadOpener {
    #[cfg(feature = "gamepad")]
    fn shared(&mut self, key: &str) -> Result<crate::device::gamepad::driver::SharedGamepad, RigBuildError> {
        if let Some(s) = &self.shared {
            return Ok(s.clone());
        }
        let s = crate::device::gamepad::driver::SharedGamepad::open()
            .map_err(|source| RigBuildError::Device { key: key.to_owned(), source })?;
        self.shared = Some(s.clone());
        Ok(s)
    }

    #[cfg(feature = "gamepad")]
    fn pedals(&mut self, key: &str) -> Result<Box<dyn Pedals>, RigBuildError> {
        use crate::device::gamepad::{GamepadMapping, driver::GamepadPedals};
        Ok(Box::new(GamepadPedals::new(self.shared(key)?, GamepadMapping::default())))
    }

    #[cfg(feature = "gamepad")]
    fn master(&mut self, key: &str) -> Result<Box<dyn MasterDevice>, RigBuildError> {
        use crate::device::gamepad::{GamepadMapping, driver::GamepadMaster};
        Ok(Box::new(GamepadMaster::new(self.shared(key)?, GamepadMapping::default())))
    }

    #[cfg(not(feature = "gamepad"))]
    fn pedals(&mut self, key: &str) -> Result<Box<dyn Pedals>, RigBuildError> {
        Err(Self::not_built(key))
    }

    #[cfg(not(feature = "gamepad"))]
    fn master(&mut self, key: &str) -> Result<Box<dyn MasterDevice>, RigBuildError> {
        Err(Self::not_built(key))
    }

    #[cfg(not(feature = "gamepad"))]
    fn not_built(key: &str) -> RigBuildError {
        RigBuildError::Invalid {
            problems: vec![(
                key.to_owned(),
                "backend \"gamepad\" needs knotlab built with the `gamepad` feature (cargo build --features gamepad; Linux needs libudev-dev)".to_owned(),
            )],
        }
    }
}

/// The handles of the dummy input devices, to press pedals and set forces from a test or a user
/// interface.
#[derive(Clone, Debug, Default)]
pub struct DummyHandles {
    /// The pedals, if dummy.
    pub pedals: Option<PedalHandle>,
    /// Dummy force sensors by arm.
    pub forces: Vec<(ArmName, ForceHandle)>,
    /// Dummy master devices by the arm they steer.
    pub masters: Vec<(ArmName, MasterHandle)>,
}

impl DummyHandles {
    /// The dummy force sensor of one arm.
    pub fn force(&self, arm: ArmName) -> Option<&ForceHandle> {
        self.forces.iter().find(|(a, _)| *a == arm).map(|(_, h)| h)
    }
}

/// A rig's devices, ready for a controller.
pub struct BuiltRig {
    /// The devices.
    pub devices: DeviceSet,
    /// Each arm's model and trocar.
    pub setups: Vec<ArmSetup>,
    /// The controller's tuning.
    pub params: ControllerParams,
    /// Handles of the dummy inputs.
    pub handles: DummyHandles,
}

impl BuiltRig {
    /// A controller for these devices (reads every device once).
    pub fn into_controller(self) -> Result<(Controller, DummyHandles), ControllerError> {
        let controller = Controller::new(self.devices, &self.setups, self.params)?;
        Ok((controller, self.handles))
    }
}

fn need_sim<'a>(
    sim: &'a mut Option<&mut dyn SimulatedScene>,
    key: String,
) -> Result<&'a mut dyn SimulatedScene, RigBuildError> {
    match sim {
        Some(s) => Ok(&mut **s),
        None => Err(RigBuildError::NeedsSimulator { key }),
    }
}

/// Connects the CiA 402 drives a `canopen` instrument names.
fn canopen_drive(arm: ArmName, at: &str, device: &InstrumentConfig) -> Result<CanopenDrive, RigBuildError> {
    let missing = |field: &str| RigBuildError::Invalid {
        problems: vec![(format!("{at}.instrument.{field}"), "missing".into())],
    };
    let nodes = device.nodes.ok_or_else(|| missing("nodes"))?;
    let counts = device.counts_per_rad.ok_or_else(|| missing("counts_per_rad"))?;
    let mut config = CanopenConfig::new(arm, nodes, 1.0);
    config.counts_per_rad = counts;
    if let Some(rows) = device.coupling {
        config.coupling = nalgebra::Matrix4::from_fn(|r, c| rows[r][c]);
    }
    if let Some(t) = device.heartbeat_timeout_s {
        config.heartbeat_timeout_s = t;
    }
    if let Some(w) = device.following_error_counts {
        config.following_error_counts = w;
    }
    let device_error = |reason: String| RigBuildError::Device {
        key: format!("{at}.instrument"),
        source: DeviceError::Fault { device: DeviceId::of_arm(DeviceKind::InstrumentDrive, arm), reason },
    };
    let transport: Box<dyn CanTransport> = match (&device.interface, device.udp) {
        #[cfg(target_os = "linux")]
        (Some(interface), _) => Box::new(
            crate::canopen::socketcan::SocketCan::open(interface).map_err(|e| device_error(e.to_string()))?,
        ),
        #[cfg(not(target_os = "linux"))]
        (Some(interface), _) => {
            return Err(device_error(format!("SocketCAN interface \"{interface}\": SocketCAN is Linux's")));
        }
        (None, Some(udp)) => {
            let local = if udp.ip().is_loopback() {
                std::net::SocketAddr::new(udp.ip(), 0)
            } else {
                std::net::SocketAddr::new(std::net::Ipv4Addr::UNSPECIFIED.into(), 0)
            };
            Box::new(UdpCan::connect(local, udp).map_err(|e| device_error(e.to_string()))?)
        }
        (None, None) => return Err(missing("interface")),
    };
    CanopenDrive::connect(transport, config)
        .map_err(|source| RigBuildError::Device { key: format!("{at}.instrument"), source })
}

/// Connects the Net F/T box a `netft` force sensor names.
fn netft_sensor(arm: ArmName, at: &str, device: &ForceConfig) -> Result<NetFtSensor, RigBuildError> {
    let missing = |field: &str| RigBuildError::Invalid {
        problems: vec![(format!("{at}.force.{field}"), "missing".into())],
    };
    let address = device.address.ok_or_else(|| missing("address"))?;
    let counts = device.counts_per_force.ok_or_else(|| missing("counts_per_force"))?;
    let mut config = NetFtConfig::new(arm, address, counts);
    if let Some(bind) = device.bind {
        config.bind = bind;
    }
    if let Some([roll, pitch, yaw]) = device.shaft_from_sensor_rpy_rad {
        config.shaft_from_sensor = nalgebra::Rotation3::from_euler_angles(roll, pitch, yaw);
    }
    if let Some(t) = device.stall_timeout_s {
        config.stall_timeout_s = t;
    }
    NetFtSensor::connect(config)
        .map_err(|source| RigBuildError::Device { key: format!("{at}.force"), source })
}

/// Builds the devices of `config` for `rig`; `sim` supplies the `sim` devices.
pub fn build_rig(
    config: &RigConfig,
    rig: &Rig,
    mut sim: Option<&mut dyn SimulatedScene>,
) -> Result<BuiltRig, RigBuildError> {
    let problems = config.problems();
    if !problems.is_empty() {
        return Err(RigBuildError::Invalid { problems });
    }
    let uses_sim = config.arms.iter().any(|(_, a)| {
        a.servo.backend == Backend::Sim
            || a.instrument.as_ref().is_some_and(|d| d.backend == Backend::Sim)
            || a.force.is_some_and(|d| d.backend == Backend::Sim)
    });
    let melfa_cycle = config
        .arms
        .iter()
        .find(|(_, a)| a.servo.backend == Backend::Melfa)
        .map(|(_, a)| a.servo.cycle_s.unwrap_or(CR750_CYCLE_S));
    let clock: Box<dyn CycleClock> = if uses_sim {
        need_sim(&mut sim, "arms".into())?.clock()
    } else if let Some(period_s) = melfa_cycle {
        Box::new(PacedByDevices { period_s })
    } else if config.controller.real_time {
        Box::new(VirtualClock::real_time(config.controller.period_s))
    } else {
        Box::new(VirtualClock::new(config.controller.period_s))
    };
    let period_s = clock.period_s();
    let mut handles = DummyHandles::default();
    let mut arms = Vec::new();
    let mut setups = Vec::new();
    for (name, arm) in config.arms.iter() {
        let at = format!("arms.{name}");
        let model = rig.arm(name).model;
        let start = match &sim {
            Some(s) => s.joints(name),
            None => name.ready_joints(),
        };
        let servo_id = DeviceId::of_arm(DeviceKind::ArmServo, name);
        let mut servo: Box<dyn ArmServo> = match arm.servo.backend {
            Backend::Sim => need_sim(&mut sim, format!("{at}.servo"))?.arm_servo(name),
            Backend::Dummy => Box::new(DummyArmServo::new(start.arm_rad)),
            backend @ (Backend::Gamepad | Backend::NetFt | Backend::Canopen) => {
                return Err(RigBuildError::Invalid {
                    problems: vec![(
                        format!("{at}.servo.backend"),
                        format!("an arm servo cannot use backend \"{}\"", backend.as_str()),
                    )],
                });
            }
            Backend::Melfa => {
                let s = &arm.servo;
                let controller = s.controller.ok_or_else(|| RigBuildError::Invalid {
                    problems: vec![(format!("{at}.servo.controller"), "missing".into())],
                })?;
                let mut melfa = MelfaConfig::new(name, controller, &model.limits)
                    .with_cycle(s.cycle_s.unwrap_or(CR750_CYCLE_S), &model.limits);
                melfa.layout = s.layout.map_or(Layout::H7, Layout::from);
                if let Some(bind) = s.bind {
                    melfa.bind = bind;
                }
                if let Some(t) = s.receive_timeout_s {
                    melfa.receive_timeout_s = t;
                }
                if let Some(n) = s.max_lost {
                    melfa.max_lost = n;
                }
                let driver = MelfaArm::connect(melfa)
                    .map_err(|source| RigBuildError::Device { key: format!("{at}.servo"), source })?;
                Box::new(driver)
            }
        };
        if let Some(step) = arm.max_step_rad {
            servo = Box::new(StepLimit::arm(servo, servo_id, [step; 6]));
        }
        servo = Box::new(VelocityLimit::arm(servo, servo_id, model.limits, period_s));
        servo = Box::new(PositionLimit::arm(servo, servo_id, model.limits));

        let instrument = match (&arm.instrument, &model.tool) {
            (Some(device), Tool::Instrument { limits, .. }) => {
                let id = DeviceId::of_arm(DeviceKind::InstrumentDrive, name);
                let mut drive: Box<dyn InstrumentDrive> = match device.backend {
                    Backend::Sim => need_sim(&mut sim, format!("{at}.instrument"))?.instrument_drive(name),
                    Backend::Canopen => Box::new(canopen_drive(name, &at, device)?),
                    _ => Box::new(DummyInstrumentDrive::new(start.tool)),
                };
                drive = Box::new(VelocityLimit::instrument(drive, id, limits, period_s));
                Some(Box::new(PositionLimit::instrument(drive, id, limits)) as Box<dyn InstrumentDrive>)
            }
            _ => None,
        };
        let force: Option<Box<dyn ForceSensor>> = match &arm.force {
            Some(device) if device.backend == Backend::Sim => {
                Some(need_sim(&mut sim, format!("{at}.force"))?.force_sensor(name))
            }
            Some(device) if device.backend == Backend::NetFt => {
                Some(Box::new(netft_sensor(name, &at, device)?))
            }
            Some(_) => {
                let sensor = DummyForceSensor::new();
                handles.forces.push((name, sensor.handle()));
                Some(Box::new(sensor))
            }
            None => None,
        };
        let world_trocar_m = match (arm.trocar_m, &sim) {
            (Some(t), _) => Vector3::from(t),
            (None, Some(s)) => s.world_trocar_m(name),
            (None, None) => return Err(RigBuildError::NeedsSimulator { key: format!("{at}.trocar_m") }),
        };
        setups.push(ArmSetup { arm: name, model, world_trocar_m });
        arms.push((name, ArmDevices { servo, instrument, force }));
    }
    let mut gamepad = GamepadOpener::default();
    let pedals: Box<dyn Pedals> = match config.pedals.backend {
        Backend::Gamepad => gamepad.pedals("pedals.backend")?,
        _ => {
            let pedals = DummyPedals::new();
            handles.pedals = Some(pedals.handle());
            Box::new(pedals)
        }
    };
    let mut masters: Vec<(ArmName, Box<dyn MasterDevice>)> = Vec::new();
    for (name, master) in [(ArmName::Left, &config.masters.left), (ArmName::Right, &config.masters.right)] {
        match master.map(|m| m.backend) {
            Some(Backend::Gamepad) => {
                masters.push((name, gamepad.master(&format!("masters.{name}.backend"))?))
            }
            Some(_) => {
                let device = DummyMaster::new();
                handles.masters.push((name, device.handle()));
                masters.push((name, Box::new(device)));
            }
            None => {}
        }
    }
    Ok(BuiltRig {
        devices: DeviceSet { arms, pedals, masters, clock },
        setups,
        params: config.controller.params(),
        handles,
    })
}

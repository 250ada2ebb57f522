//! The simulated scene as devices: `knotlab-hw`'s device traits implemented for [`SimWorld`], so the
//! controller that runs on the robots runs unchanged on the simulation.
//!
//! Every device shares one scene behind a mutex: arm servos and instrument drives write into the arm's
//! joint command, read the joints as the links stand; force sensors read the instrument's contact and
//! grasp forces, turned into the shaft frame; the clock steps the scene once per control cycle, so the
//! cycle is the scene's `solver.dt_s` (1 ms in `scenarios/default.toml`). A rig config picks these with
//! `backend = "sim"`; [`SimBackend`] is the [`SimulatedScene`] that `build_rig` takes them from.

use std::sync::{Arc, Mutex, MutexGuard};

use knotlab_hw::device::dummy::lock_handle;
use knotlab_hw::device::{
    ArmServo, ArmServoState, CycleClock, DeviceError, DeviceId, DeviceKind, ForceReading, ForceSensor,
    InstrumentDrive, InstrumentState,
};
use knotlab_hw::kinematics::{ArmJoints, ToolJoints};
use knotlab_hw::rig::ArmName;
use knotlab_hw::rig_config::SimulatedScene;
use nalgebra::{Rotation3, Vector3};

use crate::world::SimWorld;

/// A simulated scene shared by the devices made from it.
#[derive(Clone)]
pub struct SimBackend {
    world: Arc<Mutex<SimWorld>>,
}

impl SimBackend {
    /// Takes the scene.
    pub fn new(world: SimWorld) -> Self {
        Self { world: Arc::new(Mutex::new(world)) }
    }

    /// The scene, locked (to inspect it between cycles).
    pub fn world(&self) -> MutexGuard<'_, SimWorld> {
        lock_handle(&self.world)
    }

    /// An arm servo of the scene.
    pub fn arm_servo(&self, arm: ArmName) -> SimArmServo {
        SimArmServo { world: self.world.clone(), arm }
    }

    /// An instrument drive of the scene.
    pub fn instrument_drive(&self, arm: ArmName) -> SimInstrumentDrive {
        SimInstrumentDrive { world: self.world.clone(), arm }
    }

    /// A force sensor of the scene.
    pub fn force_sensor(&self, arm: ArmName) -> SimForceSensor {
        SimForceSensor { world: self.world.clone(), arm }
    }

    /// The clock that steps the scene.
    pub fn clock(&self) -> SimClock {
        let period_s = self.world().config.solver.dt_s;
        SimClock { world: self.world.clone(), period_s }
    }
}

/// The six axes of one simulated arm.
pub struct SimArmServo {
    world: Arc<Mutex<SimWorld>>,
    arm: ArmName,
}

impl ArmServo for SimArmServo {
    fn read(&mut self) -> Result<ArmServoState, DeviceError> {
        let world = lock_handle(&self.world);
        Ok(ArmServoState { joints_rad: world.arm(self.arm).actual().arm_rad, fresh: true })
    }

    fn write(&mut self, joints_rad: &[f64; 6]) -> Result<(), DeviceError> {
        let mut world = lock_handle(&self.world);
        let command = ArmJoints { arm_rad: *joints_rad, ..world.arm(self.arm).command };
        world.command(self.arm, command);
        Ok(())
    }
}

/// The roll, wrist and jaw motors of one simulated instrument.
pub struct SimInstrumentDrive {
    world: Arc<Mutex<SimWorld>>,
    arm: ArmName,
}

impl InstrumentDrive for SimInstrumentDrive {
    fn read(&mut self) -> Result<InstrumentState, DeviceError> {
        let world = lock_handle(&self.world);
        Ok(InstrumentState { joints: world.arm(self.arm).actual().tool, fresh: true })
    }

    fn write(&mut self, joints: &ToolJoints) -> Result<(), DeviceError> {
        let mut world = lock_handle(&self.world);
        let command = ArmJoints { tool: *joints, ..world.arm(self.arm).command };
        world.command(self.arm, command);
        Ok(())
    }
}

/// The strain gauges of one simulated instrument: the scene's contact and grasp forces on it, in the
/// shaft frame (which rolls with the instrument).
pub struct SimForceSensor {
    world: Arc<Mutex<SimWorld>>,
    arm: ArmName,
}

impl ForceSensor for SimForceSensor {
    fn read(&mut self) -> Result<ForceReading, DeviceError> {
        let world = lock_handle(&self.world);
        let sim_arm = world.arm(self.arm);
        let joints = sim_arm.actual();
        let model = &world.rig.arm(self.arm).model;
        let world_from_shaft = model.world_from_flange(&joints).rotation
            * Rotation3::from_axis_angle(&Vector3::z_axis(), joints.tool.roll_rad);
        Ok(ForceReading { shaft_force_n: world_from_shaft.inverse() * sim_arm.force_n, fresh: true })
    }
}

/// Steps the scene once per control cycle.
pub struct SimClock {
    world: Arc<Mutex<SimWorld>>,
    period_s: f64,
}

impl CycleClock for SimClock {
    fn period_s(&self) -> f64 {
        self.period_s
    }

    fn tick(&mut self) -> Result<(), DeviceError> {
        lock_handle(&self.world).step().map_err(|e| DeviceError::Fault {
            device: DeviceId::shared(DeviceKind::Clock),
            reason: format!("the simulation went unhealthy: {e}"),
        })
    }
}

impl SimulatedScene for SimBackend {
    fn period_s(&self) -> f64 {
        self.world().config.solver.dt_s
    }

    fn arm_servo(&mut self, arm: ArmName) -> Box<dyn ArmServo> {
        Box::new(SimBackend::arm_servo(self, arm))
    }

    fn instrument_drive(&mut self, arm: ArmName) -> Box<dyn InstrumentDrive> {
        Box::new(SimBackend::instrument_drive(self, arm))
    }

    fn force_sensor(&mut self, arm: ArmName) -> Box<dyn ForceSensor> {
        Box::new(SimBackend::force_sensor(self, arm))
    }

    fn clock(&mut self) -> Box<dyn CycleClock> {
        Box::new(SimBackend::clock(self))
    }

    fn world_trocar_m(&self, arm: ArmName) -> Vector3<f64> {
        let trocars = &self.world().config.trocars;
        Vector3::from(match arm {
            ArmName::Left => trocars.left,
            ArmName::Right => trocars.right,
            ArmName::Assist => trocars.assist,
            ArmName::Camera => trocars.camera,
        })
    }

    fn joints(&self, arm: ArmName) -> ArmJoints {
        self.world().arm(arm).actual()
    }
}

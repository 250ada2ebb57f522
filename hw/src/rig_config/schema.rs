//! The rig config's contents, and the checks that name each key.

use std::net::SocketAddr;

use serde::{Deserialize, Serialize};

use crate::controller::ControllerParams;
use crate::melfa::Layout;
use crate::rig::ArmName;

/// A whole rig config.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct RigConfig {
    /// A line saying what the rig is.
    pub description: String,
    /// The controller's tuning and, for rigs of dummy devices, the clock.
    #[serde(default)]
    pub controller: ControllerSection,
    /// The arms that take part.
    #[serde(default)]
    pub arms: Arms,
    /// The foot pedals.
    #[serde(default = "DeviceConfig::dummy")]
    pub pedals: DeviceConfig,
    /// Master devices, by the arm each steers.
    #[serde(default)]
    pub masters: Masters,
}

/// The controller's tuning.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct ControllerSection {
    /// Stale cycles in a row that fault the run.
    pub watchdog_cycles: u32,
    /// Fraction of the rated joint speeds the controller may command, (0, 1].
    pub speed_scale: f64,
    /// Force fed back to a master device per newton on its instrument.
    pub force_feedback_scale: f64,
    /// The cycle of a rig of dummy devices only, s (sim and melfa rigs take their backend's).
    pub period_s: f64,
    /// A rig of dummy devices runs in real time (sleeps each cycle) rather than as fast as it can.
    pub real_time: bool,
}

impl Default for ControllerSection {
    fn default() -> Self {
        let p = ControllerParams::default();
        Self {
            watchdog_cycles: p.watchdog_cycles,
            speed_scale: p.speed_scale,
            force_feedback_scale: p.force_feedback_scale,
            period_s: 0.001,
            real_time: false,
        }
    }
}

impl ControllerSection {
    /// The controller parameters.
    pub fn params(&self) -> ControllerParams {
        ControllerParams {
            watchdog_cycles: self.watchdog_cycles,
            speed_scale: self.speed_scale,
            force_feedback_scale: self.force_feedback_scale,
        }
    }
}

/// The arms, each optional.
#[derive(Clone, Debug, Default, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Arms {
    /// The left instrument arm.
    pub left: Option<ArmConfig>,
    /// The right instrument arm.
    pub right: Option<ArmConfig>,
    /// The assisting instrument arm.
    pub assist: Option<ArmConfig>,
    /// The endoscope arm.
    pub camera: Option<ArmConfig>,
}

impl Arms {
    /// The configured arms in [`ArmName::ALL`] order.
    pub fn iter(&self) -> impl Iterator<Item = (ArmName, &ArmConfig)> {
        ArmName::ALL
            .into_iter()
            .zip([&self.left, &self.right, &self.assist, &self.camera])
            .filter_map(|(name, arm)| arm.as_ref().map(|a| (name, a)))
    }
}

/// Master devices, each optional.
#[derive(Clone, Debug, Default, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Masters {
    /// The master steering the left arm.
    pub left: Option<DeviceConfig>,
    /// The master steering the right arm.
    pub right: Option<DeviceConfig>,
}

/// Which backend drives a device.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Backend {
    /// The simulated scene (knotlab-sim).
    Sim,
    /// A Mitsubishi MELFA controller over UDP (arm servos only).
    Melfa,
    /// A dummy driver (perfect joints; inputs set through handles).
    Dummy,
    /// A gamepad (masters and pedals only; the `gamepad` feature).
    Gamepad,
    /// An ATI Net F/T box over RDT (force sensors only).
    #[serde(rename = "netft")]
    NetFt,
    /// CiA 402 drives on CAN (instrument drives only).
    Canopen,
}

impl Backend {
    /// The name in the file.
    pub fn as_str(self) -> &'static str {
        match self {
            Backend::Sim => "sim",
            Backend::Melfa => "melfa",
            Backend::Dummy => "dummy",
            Backend::Gamepad => "gamepad",
            Backend::NetFt => "netft",
            Backend::Canopen => "canopen",
        }
    }
}

/// A device with nothing to configure but its backend.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct DeviceConfig {
    /// Its backend.
    pub backend: Backend,
}

impl DeviceConfig {
    /// A dummy device.
    pub fn dummy() -> Self {
        Self { backend: Backend::Dummy }
    }
}

/// The MELFA packet layouts by their names in the file.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum LayoutName {
    /// Software H7 and later (196 bytes).
    H7,
    /// Software H6 and older (64 bytes).
    PreH7,
}

impl From<LayoutName> for Layout {
    fn from(name: LayoutName) -> Self {
        match name {
            LayoutName::H7 => Layout::H7,
            LayoutName::PreH7 => Layout::PreH7,
        }
    }
}

/// An arm's servo: its backend and, for `melfa`, how to reach the controller.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ServoConfig {
    /// Its backend.
    pub backend: Backend,
    /// melfa: the controller's address, "ip:port" (port 10000 on a real controller).
    pub controller: Option<SocketAddr>,
    /// melfa: the local address to send from (default: any, or loopback for a loopback controller).
    pub bind: Option<SocketAddr>,
    /// melfa: the controller software's packet layout (default h7).
    pub layout: Option<LayoutName>,
    /// melfa: the controller's cycle, s (default 0.00711, CR750; 0.0035 for CR800).
    pub cycle_s: Option<f64>,
    /// melfa: how long to wait for each reply, s (default two cycles).
    pub receive_timeout_s: Option<f64>,
    /// melfa: replies lost in a row after which the link is down (default 100).
    pub max_lost: Option<u32>,
}

/// One arm.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ArmConfig {
    /// The trocar point, world frame, m (default with a sim servo: the scene's).
    pub trocar_m: Option<[f64; 3]>,
    /// A per-cycle step limit on every axis, rad (a [`crate::device::StepLimit`] around the servo).
    pub max_step_rad: Option<f64>,
    /// The six axes.
    pub servo: ServoConfig,
    /// The instrument's motors (not for the camera arm).
    pub instrument: Option<InstrumentConfig>,
    /// The instrument's strain gauges (not for the camera arm).
    pub force: Option<ForceConfig>,
}

/// An instrument's motors: their backend and, for `canopen`, the bus and the drives.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct InstrumentConfig {
    /// Its backend.
    pub backend: Backend,
    /// canopen: the SocketCAN interface the drives are on, for example "can0" (Linux; one of
    /// `interface` and `udp`).
    pub interface: Option<String>,
    /// canopen: CAN frames over UDP to this address, "ip:port" (`knotlab canopen-emulator`; one of
    /// `interface` and `udp`).
    pub udp: Option<SocketAddr>,
    /// canopen: the node ids of the roll, pitch, yaw and jaw drives (1 to 127, distinct).
    pub nodes: Option<[u8; 4]>,
    /// canopen: each motor's encoder counts per radian of the motor, the gear's ratio included.
    pub counts_per_rad: Option<[f64; 4]>,
    /// canopen: motor angles from joint angles, row by row: motor = coupling x (roll, pitch, yaw,
    /// jaw) (default: the identity, no cable coupling).
    pub coupling: Option<[[f64; 4]; 4]>,
    /// canopen: a node unheard of for this long has dropped out, s (default 0.05).
    pub heartbeat_timeout_s: Option<f64>,
    /// canopen: the following error window each drive is given, counts (default 0: not watched).
    pub following_error_counts: Option<u32>,
}

impl InstrumentConfig {
    /// Motors of `backend` with nothing else to configure.
    pub fn of(backend: Backend) -> Self {
        Self {
            backend,
            interface: None,
            udp: None,
            nodes: None,
            counts_per_rad: None,
            coupling: None,
            heartbeat_timeout_s: None,
            following_error_counts: None,
        }
    }
}

/// An instrument's force sensor: its backend and, for `netft`, how to reach and read the box.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ForceConfig {
    /// Its backend.
    pub backend: Backend,
    /// netft: the box's address, "ip:port" (port 49152 on a real box).
    pub address: Option<SocketAddr>,
    /// netft: the local address to receive on (default: any, or loopback for a loopback box).
    pub bind: Option<SocketAddr>,
    /// netft: the calibration's counts per newton (the box's configuration page lists it).
    pub counts_per_force: Option<f64>,
    /// netft: the sensor's frame in the shaft frame, as roll, pitch and yaw about the shaft frame's
    /// fixed x, y and z, rad (default 0, 0, 0: the same frame).
    pub shaft_from_sensor_rpy_rad: Option<[f64; 3]>,
    /// netft: no record for this long and the stream has stalled, s (default 0.1).
    pub stall_timeout_s: Option<f64>,
}

impl ForceConfig {
    /// A force sensor of `backend` with nothing else to configure.
    pub fn of(backend: Backend) -> Self {
        Self {
            backend,
            address: None,
            bind: None,
            counts_per_force: None,
            shaft_from_sensor_rpy_rad: None,
            stall_timeout_s: None,
        }
    }
}

struct Problems(Vec<(String, String)>);

impl Problems {
    fn add(&mut self, key: impl Into<String>, reason: impl Into<String>) {
        self.0.push((key.into(), reason.into()));
    }

    fn backend(&mut self, key: String, backend: Backend, allowed: &[Backend], what: &str) {
        if !allowed.contains(&backend) {
            let names: Vec<&str> = allowed.iter().map(|b| b.as_str()).collect();
            self.add(
                key,
                format!("{what} cannot use backend \"{}\": use {}", backend.as_str(), names.join(" or ")),
            );
        }
    }

    /// Each of `fields` (name, given) that is given although `backend` is not `wanted`.
    fn only_for(&mut self, at: &str, backend: Backend, wanted: Backend, fields: &[(&str, bool)]) {
        if backend == wanted {
            return;
        }
        for (field, given) in fields {
            if *given {
                self.add(format!("{at}.{field}"), format!("only for backend \"{}\"", wanted.as_str()));
            }
        }
    }

    fn positive(&mut self, key: String, value: Option<f64>) {
        if let Some(v) = value
            && !(v.is_finite() && v > 0.0)
        {
            self.add(key, format!("{v} must be a positive number"));
        }
    }
}

/// The problems of an instrument's canopen settings.
fn instrument_problems(p: &mut Problems, at: &str, d: &InstrumentConfig) {
    let fields = [
        ("interface", d.interface.is_some()),
        ("udp", d.udp.is_some()),
        ("nodes", d.nodes.is_some()),
        ("counts_per_rad", d.counts_per_rad.is_some()),
        ("coupling", d.coupling.is_some()),
        ("heartbeat_timeout_s", d.heartbeat_timeout_s.is_some()),
        ("following_error_counts", d.following_error_counts.is_some()),
    ];
    p.only_for(at, d.backend, Backend::Canopen, &fields);
    if d.backend != Backend::Canopen {
        return;
    }
    match (&d.interface, d.udp) {
        (None, None) => p.add(
            format!("{at}.interface"),
            "backend \"canopen\" needs the bus: a SocketCAN interface (interface = \"can0\") or a CAN-over-UDP \
             address (udp = \"ip:port\")",
        ),
        (Some(_), Some(_)) => p.add(format!("{at}.udp"), "one bus: either interface or udp, not both"),
        _ => {}
    }
    if let Some(name) = &d.interface
        && let Err(reason) = interface_name_problem(name)
    {
        p.add(format!("{at}.interface"), reason);
    }
    match d.nodes {
        None => p.add(
            format!("{at}.nodes"),
            "backend \"canopen\" needs the roll, pitch, yaw and jaw drives' node ids",
        ),
        Some(nodes) => {
            if let Some(bad) = nodes.iter().find(|n| !(1..=127).contains(*n)) {
                p.add(format!("{at}.nodes"), format!("node {bad}: CANopen nodes are 1 to 127"));
            }
            let mut sorted = nodes;
            sorted.sort_unstable();
            if sorted.windows(2).any(|w| w[0] == w[1]) {
                p.add(format!("{at}.nodes"), format!("{nodes:?}: each drive its own node"));
            }
        }
    }
    match d.counts_per_rad {
        None => {
            p.add(format!("{at}.counts_per_rad"), "backend \"canopen\" needs each motor's counts per radian")
        }
        Some(c) if c.iter().any(|x| !(x.is_finite() && *x != 0.0)) => {
            p.add(format!("{at}.counts_per_rad"), format!("{c:?}: each finite and not 0"));
        }
        Some(_) => {}
    }
    if let Some(rows) = d.coupling {
        let m = nalgebra::Matrix4::from_fn(|r, c| rows[r][c]);
        if m.iter().any(|x| !x.is_finite()) || m.try_inverse().is_none() {
            p.add(
                format!("{at}.coupling"),
                "must be finite and invertible (each joint reachable from the motors)",
            );
        }
    }
    p.positive(format!("{at}.heartbeat_timeout_s"), d.heartbeat_timeout_s);
}

/// Why `name` cannot be a network interface's name (Linux's rule: 1 to 15 bytes, no '/', no
/// white space); on other systems, that SocketCAN is Linux's.
fn interface_name_problem(name: &str) -> Result<(), String> {
    if !cfg!(target_os = "linux") {
        return Err(format!(
            "\"{name}\": SocketCAN is Linux's; on this system use udp (a CAN-over-UDP gateway)"
        ));
    }
    if name.is_empty() || name.len() > 15 || name.contains('/') || name.chars().any(char::is_whitespace) {
        return Err(format!(
            "\"{name}\": an interface's name is 1 to 15 bytes without '/' or white space, like \"can0\""
        ));
    }
    Ok(())
}

/// The problems of a force sensor's netft settings.
fn force_problems(p: &mut Problems, at: &str, force: &ForceConfig) {
    let netft_fields = [
        ("address", force.address.is_some()),
        ("bind", force.bind.is_some()),
        ("counts_per_force", force.counts_per_force.is_some()),
        ("shaft_from_sensor_rpy_rad", force.shaft_from_sensor_rpy_rad.is_some()),
        ("stall_timeout_s", force.stall_timeout_s.is_some()),
    ];
    p.only_for(at, force.backend, Backend::NetFt, &netft_fields);
    if force.backend != Backend::NetFt {
        return;
    }
    if force.address.is_none() {
        p.add(format!("{at}.address"), "backend \"netft\" needs the box's address, \"ip:port\" (port 49152)");
    }
    match force.counts_per_force {
        None => p.add(
            format!("{at}.counts_per_force"),
            "backend \"netft\" needs the calibration's counts per newton (the box's configuration page lists it)",
        ),
        value => p.positive(format!("{at}.counts_per_force"), value),
    }
    p.positive(format!("{at}.stall_timeout_s"), force.stall_timeout_s);
    if let Some(rpy) = force.shaft_from_sensor_rpy_rad
        && rpy.iter().any(|x| !x.is_finite())
    {
        p.add(format!("{at}.shaft_from_sensor_rpy_rad"), "not finite");
    }
}

impl RigConfig {
    /// Every value out of range or combination that cannot work, as (key, reason).
    pub fn problems(&self) -> Vec<(String, String)> {
        let mut p = Problems(Vec::new());
        for (field, reason) in self.controller.params().problems() {
            p.add(format!("controller.{field}"), reason);
        }
        p.positive("controller.period_s".into(), Some(self.controller.period_s));
        if self.arms.iter().next().is_none() {
            p.add("arms", "no arm is configured");
        }
        let mut melfa_cycles = Vec::new();
        for (name, arm) in self.arms.iter() {
            let at = format!("arms.{name}");
            let servo = &arm.servo;
            p.backend(
                format!("{at}.servo.backend"),
                servo.backend,
                &[Backend::Sim, Backend::Melfa, Backend::Dummy],
                "an arm servo",
            );
            let melfa_fields = [
                ("controller", servo.controller.is_some()),
                ("bind", servo.bind.is_some()),
                ("layout", servo.layout.is_some()),
                ("cycle_s", servo.cycle_s.is_some()),
                ("receive_timeout_s", servo.receive_timeout_s.is_some()),
                ("max_lost", servo.max_lost.is_some()),
            ];
            if servo.backend == Backend::Melfa {
                if servo.controller.is_none() {
                    p.add(
                        format!("{at}.servo.controller"),
                        "backend \"melfa\" needs the controller's address, \"ip:port\"",
                    );
                }
                p.positive(format!("{at}.servo.cycle_s"), servo.cycle_s);
                p.positive(format!("{at}.servo.receive_timeout_s"), servo.receive_timeout_s);
                if servo.max_lost == Some(0) {
                    p.add(format!("{at}.servo.max_lost"), "must be at least 1");
                }
                melfa_cycles.push((name, servo.cycle_s.unwrap_or(crate::melfa::CR750_CYCLE_S)));
            } else {
                p.only_for(&format!("{at}.servo"), servo.backend, Backend::Melfa, &melfa_fields);
            }
            if let Some(t) = arm.trocar_m
                && t.iter().any(|x| !x.is_finite())
            {
                p.add(format!("{at}.trocar_m"), "not finite");
            }
            if arm.trocar_m.is_none() && servo.backend != Backend::Sim {
                p.add(format!("{at}.trocar_m"), "needed: only a sim servo takes the trocar from the scene");
            }
            p.positive(format!("{at}.max_step_rad"), arm.max_step_rad);
            let devices = [
                (
                    "instrument",
                    arm.instrument.as_ref().map(|d| d.backend),
                    &[Backend::Sim, Backend::Dummy, Backend::Canopen][..],
                ),
                ("force", arm.force.map(|d| d.backend), &[Backend::Sim, Backend::Dummy, Backend::NetFt][..]),
            ];
            for (field, backend, allowed) in devices {
                let Some(backend) = backend else { continue };
                if !name.carries_instrument() {
                    p.add(
                        format!("{at}.{field}"),
                        "the camera arm carries the endoscope: it has no instrument motors or strain gauges",
                    );
                }
                let what = if field == "force" { "a force sensor" } else { "an instrument drive" };
                p.backend(format!("{at}.{field}.backend"), backend, allowed, what);
            }
            if let Some(force) = &arm.force {
                force_problems(&mut p, &format!("{at}.force"), force);
            }
            if let Some(instrument) = &arm.instrument {
                instrument_problems(&mut p, &format!("{at}.instrument"), instrument);
            }
        }
        p.backend(
            "pedals.backend".into(),
            self.pedals.backend,
            &[Backend::Dummy, Backend::Gamepad],
            "the pedals",
        );
        for (name, master) in [("left", &self.masters.left), ("right", &self.masters.right)] {
            if let Some(m) = master {
                p.backend(
                    format!("masters.{name}.backend"),
                    m.backend,
                    &[Backend::Dummy, Backend::Gamepad],
                    "a master device",
                );
            }
        }
        let uses = |b: Backend| {
            self.arms.iter().any(|(_, a)| {
                a.servo.backend == b
                    || a.instrument.as_ref().is_some_and(|d| d.backend == b)
                    || a.force.is_some_and(|d| d.backend == b)
            })
        };
        if uses(Backend::Sim) && uses(Backend::Melfa) {
            p.add(
                "arms",
                "mixes sim and melfa devices: the simulation's step and the MELFA controller's cycle cannot both pace the loop",
            );
        }
        if let Some((first, cycle)) = melfa_cycles.first()
            && let Some((other, c)) = melfa_cycles.iter().find(|(_, c)| c != cycle)
        {
            p.add(
                format!("arms.{other}.servo.cycle_s"),
                format!("{c} s differs from the {first} arm's {cycle} s: all MELFA controllers of a rig share one cycle"),
            );
        }
        p.0
    }
}

//! An emulator of a MELFA controller's side of real-time external control: it speaks the MXT protocol
//! on UDP and moves an [`EmulatedArm`].
//!
//! - NULL is answered with the current joints and the monitor data asked for; MOVE (SendType JOINT,
//!   the controller running `MXT 1,...` in joint mode) moves the arm, then is answered the same way;
//!   END ends the session and [`Emulator::run`] returns.
//! - `dat` in a reply holds what RecvType asked for: JOINT the last command, FJOINT the filtered
//!   joints; the H7 slots likewise, FB_JOINT being the filtered joints (an ideal servo) and the POSE
//!   types the flange in the arm's base frame (mm; a, b, c about fixed x, y, z). Pulses and motor
//!   currents are not modelled: those slots come back typed NULL.
//! - A command out of range or stepping faster than the axis can move faults the controller, as the
//!   real one does: it stops answering and `run` returns [`EmulatorError::Fault`].
//! - Paced, it answers at the next cycle boundary (as the controller does, 7.11 ms apart); unpaced
//!   (for tests), at once, one cycle of motion per packet.
//! - The first sender is the session's PC; packets from others are ignored. It binds loopback addresses
//!   only, unless `allow_remote` is given.

mod arm;

pub use arm::{ArmFault, EmulatedArm};

use std::io::ErrorKind;
use std::net::{SocketAddr, UdpSocket};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use nalgebra::UnitQuaternion;

use crate::kinematics::JointLimit;

use super::codec::{MAX_DATAGRAM, MAX_LEN};
use super::packet::{Command, Data, DataType, Layout, Monitor, Packet, Pose};

/// Which replies the emulator drops (to test the driver's loss handling).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum DropPolicy {
    /// Answer everything.
    #[default]
    Never,
    /// Drop every Nth reply (N >= 1).
    Every(u32),
    /// Answer the first N replies, drop every one after.
    AllAfter(u64),
}

/// How the emulator behaves.
#[derive(Clone, Debug, PartialEq)]
pub struct EmulatorConfig {
    /// The packet layout it speaks.
    pub layout: Layout,
    /// The controller's cycle, s.
    pub cycle_s: f64,
    /// The MXT filter time constant, s (0: none).
    pub filter_s: f64,
    /// Where the arm stands at first, rad.
    pub initial_joints_rad: [f64; 6],
    /// Joint limits (range and speed).
    pub limits: [JointLimit; 6],
    /// Which replies to drop.
    pub drop: DropPolicy,
    /// Answer at cycle boundaries (true) or at once (false).
    pub pace: bool,
    /// Give up after this long without a packet, s (None: wait for ever).
    pub idle_timeout_s: Option<f64>,
}

/// What a session did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct EmulatorReport {
    /// Packets received from the session's PC.
    pub packets: u64,
    /// NULL commands.
    pub nulls: u64,
    /// MOVE commands.
    pub moves: u64,
    /// Replies sent.
    pub replies_sent: u64,
    /// Replies dropped on purpose.
    pub replies_dropped: u64,
    /// Packets that could not be decoded or were not understood.
    pub malformed: u64,
    /// Packets from addresses other than the session's PC.
    pub foreign: u64,
    /// Whether the session ended with END.
    pub ended: bool,
    /// The arm's filtered joints at the end, rad.
    pub final_joints_rad: [f64; 6],
    /// Controller cycles the arm moved through.
    pub cycles: u64,
    /// The first problems met (at most 20), each naming the packet.
    pub problems: Vec<String>,
}

/// Why an emulator stopped or could not start.
#[derive(Debug, thiserror::Error)]
pub enum EmulatorError {
    /// A non-loopback address without `allow_remote`.
    #[error(
        "refusing to bind {addr}: not a loopback address (the emulator listens on loopback only unless remote access is allowed explicitly)"
    )]
    RemoteRefused {
        /// The address.
        addr: SocketAddr,
    },
    /// The configuration is unusable.
    #[error("emulator configuration: {0}")]
    Config(String),
    /// An operating-system error.
    #[error("{action}: {source}")]
    Io {
        /// What it was doing.
        action: String,
        /// The error.
        source: std::io::Error,
    },
    /// The arm faulted (over speed, out of range): the controller stopped answering.
    #[error("controller fault: {fault}")]
    Fault {
        /// Why.
        fault: ArmFault,
        /// The session so far.
        report: Box<EmulatorReport>,
    },
    /// No packet for too long.
    #[error("no packet for {seconds:.3} s: giving up")]
    Idle {
        /// How long, s.
        seconds: f64,
        /// The session so far.
        report: Box<EmulatorReport>,
    },
}

/// A MELFA controller emulator bound to a UDP socket.
pub struct Emulator {
    socket: UdpSocket,
    config: EmulatorConfig,
    arm: EmulatedArm,
    stop: Arc<AtomicBool>,
}

/// How often the receive loop looks at the stop flag, s.
const POLL_S: f64 = 0.05;
const MAX_PROBLEMS: usize = 20;

impl Emulator {
    /// Binds `addr` (loopback only unless `allow_remote`).
    pub fn bind(addr: SocketAddr, allow_remote: bool, config: EmulatorConfig) -> Result<Self, EmulatorError> {
        if !addr.ip().is_loopback() && !allow_remote {
            return Err(EmulatorError::RemoteRefused { addr });
        }
        if !(config.cycle_s.is_finite() && config.cycle_s > 0.0) {
            return Err(EmulatorError::Config(format!("cycle {} s is not a period", config.cycle_s)));
        }
        if !(config.filter_s.is_finite() && config.filter_s >= 0.0) {
            return Err(EmulatorError::Config(format!("filter {} s is not a time >= 0", config.filter_s)));
        }
        if config.drop == DropPolicy::Every(0) {
            return Err(EmulatorError::Config(
                "dropping every 0th reply means nothing: use 1 or more".into(),
            ));
        }
        let io = |action: String| move |source| EmulatorError::Io { action, source };
        let socket = UdpSocket::bind(addr).map_err(io(format!("binding {addr}")))?;
        socket
            .set_read_timeout(Some(Duration::from_secs_f64(POLL_S)))
            .map_err(io("setting the receive time-out".to_owned()))?;
        let arm = EmulatedArm::new(config.initial_joints_rad, config.limits, config.cycle_s, config.filter_s);
        Ok(Self { socket, config, arm, stop: Arc::new(AtomicBool::new(false)) })
    }

    /// The address it listens on.
    pub fn local_addr(&self) -> Result<SocketAddr, EmulatorError> {
        self.socket
            .local_addr()
            .map_err(|source| EmulatorError::Io { action: "reading the local address".into(), source })
    }

    /// A flag that, once set, makes [`Emulator::run`] return (within 50 ms).
    pub fn stop_flag(&self) -> Arc<AtomicBool> {
        self.stop.clone()
    }

    /// Runs [`Emulator::run`] on a thread of its own.
    pub fn spawn(self) -> std::thread::JoinHandle<Result<EmulatorReport, EmulatorError>> {
        std::thread::spawn(move || self.run())
    }

    /// Serves one session: until END (Ok), the stop flag (Ok, `ended` false), a fault or the idle
    /// time-out.
    pub fn run(mut self) -> Result<EmulatorReport, EmulatorError> {
        let mut report = EmulatorReport { final_joints_rad: self.arm.filtered_rad(), ..Default::default() };
        let mut rx = vec![0_u8; MAX_DATAGRAM];
        let mut tx = [0_u8; MAX_LEN];
        let mut peer: Option<SocketAddr> = None;
        let mut last_packet = Instant::now();
        let mut clock: Option<(Instant, u64)> = None;
        let mut replies_due: u64 = 0;
        loop {
            if self.stop.load(Ordering::Relaxed) {
                return Ok(report);
            }
            let (n, from) = match self.socket.recv_from(&mut rx) {
                Ok(got) => got,
                Err(e) if matches!(e.kind(), ErrorKind::WouldBlock | ErrorKind::TimedOut) => {
                    let idle = last_packet.elapsed().as_secs_f64();
                    if let Some(limit) = self.config.idle_timeout_s
                        && idle > limit
                    {
                        return Err(EmulatorError::Idle { seconds: idle, report: Box::new(report) });
                    }
                    continue;
                }
                Err(e)
                    if e.kind() == ErrorKind::ConnectionRefused || e.kind() == ErrorKind::ConnectionReset =>
                {
                    continue;
                }
                Err(source) => return Err(EmulatorError::Io { action: "receiving".into(), source }),
            };
            last_packet = Instant::now();
            let peer_addr = *peer.get_or_insert(from);
            if from != peer_addr {
                report.foreign += 1;
                continue;
            }
            report.packets += 1;
            let packet = match Packet::decode(&rx[..n], self.config.layout) {
                Ok(p) => p,
                Err(e) => {
                    report.malformed += 1;
                    let problem = format!("packet {} from {from}: {e}", report.packets);
                    note(&mut report, problem);
                    continue;
                }
            };
            match packet.command {
                Command::End => {
                    report.ended = true;
                    return Ok(report);
                }
                Command::Null => report.nulls += 1,
                Command::Move => {
                    report.moves += 1;
                    match (packet.send_type, packet.data) {
                        (DataType::Joint, Data::Joint(j)) => {
                            let joints = std::array::from_fn(|i| f64::from(j[i]));
                            if let Err(fault) = self.arm.command(joints) {
                                report.final_joints_rad = self.arm.filtered_rad();
                                return Err(EmulatorError::Fault { fault, report: Box::new(report) });
                            }
                        }
                        (other, _) => {
                            report.malformed += 1;
                            let problem = format!(
                                "packet {} (CCount {}): MOVE with SendType {} ({other:?}): the emulator runs MXT in joint mode (SendType 2, JOINT); taken as NULL",
                                report.packets,
                                packet.c_count,
                                other.code()
                            );
                            note(&mut report, problem);
                        }
                    }
                }
            }
            let cycles = self.wait_for_cycle(&mut clock);
            self.arm.advance(cycles);
            report.cycles += u64::from(cycles);
            report.final_joints_rad = self.arm.filtered_rad();
            replies_due += 1;
            let drop = match self.config.drop {
                DropPolicy::Never => false,
                DropPolicy::Every(n) => replies_due.is_multiple_of(u64::from(n.max(1))),
                DropPolicy::AllAfter(k) => replies_due > k,
            };
            if drop {
                report.replies_dropped += 1;
                continue;
            }
            let reply = self.reply(&packet, cycles);
            let len = reply.encode(self.config.layout, &mut tx);
            match self.socket.send_to(&tx[..len], peer_addr) {
                Ok(_) => report.replies_sent += 1,
                Err(source) => {
                    return Err(EmulatorError::Io { action: format!("replying to {peer_addr}"), source });
                }
            }
        }
    }

    /// Paced: sleeps until the next cycle boundary and returns the boundaries passed since the last
    /// packet (at least 1). Unpaced: 1.
    fn wait_for_cycle(&self, clock: &mut Option<(Instant, u64)>) -> u32 {
        if !self.config.pace {
            return 1;
        }
        let now = Instant::now();
        let (start, done) = *clock.get_or_insert((now, 0));
        let due = ((now - start).as_secs_f64() / self.config.cycle_s).floor() as u64 + 1;
        let boundary = start + Duration::from_secs_f64(due as f64 * self.config.cycle_s);
        let now = Instant::now();
        if boundary > now {
            std::thread::sleep(boundary - now);
        }
        *clock = Some((start, due));
        u32::try_from(due.saturating_sub(done).max(1)).unwrap_or(u32::MAX)
    }

    fn monitor(&self, kind: DataType) -> (DataType, Data) {
        let joints = |q: [f64; 6]| {
            Data::Joint([
                q[0] as f32,
                q[1] as f32,
                q[2] as f32,
                q[3] as f32,
                q[4] as f32,
                q[5] as f32,
                0.0,
                0.0,
            ])
        };
        match kind {
            DataType::Joint => (kind, joints(self.arm.command_rad())),
            DataType::FilteredJoint | DataType::FeedbackJoint => (kind, joints(self.arm.filtered_rad())),
            DataType::Pose | DataType::FilteredPose | DataType::FeedbackPose => {
                let flange = self.arm.base_from_flange();
                let t = flange.translation.vector * 1000.0;
                let (a, b, c) = UnitQuaternion::from_rotation_matrix(&flange.rotation).euler_angles();
                let pose = Pose {
                    xyz_mm: [t.x as f32, t.y as f32, t.z as f32],
                    abc_rad: [a as f32, b as f32, c as f32],
                    l1_l2: [0.0; 2],
                    flags: [0; 2],
                };
                (kind, Data::Pose(pose))
            }
            _ => (DataType::Null, Data::None),
        }
    }

    fn reply(&self, request: &Packet, cycles: u32) -> Packet {
        let (send_type, data) = self.monitor(request.recv_type);
        let mut monitors = [Monitor::EMPTY; 3];
        for (slot, asked) in monitors.iter_mut().zip(&request.monitors) {
            let (kind, data) = self.monitor(asked.kind);
            *slot = Monitor { kind, data };
        }
        Packet {
            command: request.command,
            send_type,
            recv_type: request.recv_type,
            data,
            io: request.io,
            t_count: u16::try_from(cycles.saturating_sub(1)).unwrap_or(u16::MAX),
            c_count: request.c_count,
            monitors,
        }
    }
}

fn note(report: &mut EmulatorReport, problem: String) {
    if report.problems.len() < MAX_PROBLEMS {
        report.problems.push(problem);
    }
}

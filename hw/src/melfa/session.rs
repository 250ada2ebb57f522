//! The MXT session driver: one MELFA controller as an [`ArmServo`].
//!
//! - [`MelfaArm::connect`] sends NULL (asking for monitor data) until a reply comes; its joints seed
//!   the set-point.
//! - Each cycle `write` sends MOVE with the joints (SendType JOINT) and the next CCount, the step from
//!   the previous set-point clamped per joint; `read` waits for the reply up to the receive time-out
//!   (about two cycles). A cycle whose `read` finds no MOVE outstanding sends NULL instead: the link
//!   stays alive and monitor data still comes.
//! - A reply that does not come in time is a loss: `read` returns the last joints marked stale. After
//!   `max_lost` losses in a row the link is down: `read` and `write` fail with
//!   [`DeviceError::LinkDown`]. Replies that come late are thrown away before the next exchange.
//! - [`MelfaArm::end`] (or `shutdown`) sends END: the robot program's MXT instruction returns.
//!
//! Measured joints: encoder feedback (FB_JOINT, monitor slot 1) with the H7 layout; the joints after
//! the controller's filter (FJOINT, `dat`) before H7. The set-point is seeded with FJOINT.

use std::io::ErrorKind;
use std::net::{SocketAddr, UdpSocket};
use std::time::{Duration, Instant};

use crate::device::{ArmServo, ArmServoState, DeviceError, DeviceId, DeviceKind, LimitError, LinkStats};
use crate::kinematics::JointLimit;
use crate::rig::ArmName;

use super::codec::{MAX_DATAGRAM, MAX_LEN};
use super::packet::{Command, Data, DataType, Layout, Packet};
use super::{CR750_CYCLE_S, MAX_LOST_REPLIES};

/// How to reach one MELFA controller.
#[derive(Clone, Debug, PartialEq)]
pub struct MelfaConfig {
    /// The arm it drives (names the device in errors).
    pub arm: ArmName,
    /// The controller's address (port 10000 on a real controller).
    pub controller: SocketAddr,
    /// The local address to bind (port 0: any).
    pub bind: SocketAddr,
    /// The controller software's packet layout.
    pub layout: Layout,
    /// The controller's cycle, s (7.11 ms CR750, 3.5 ms CR800).
    pub cycle_s: f64,
    /// How long to wait for a reply, s (about two cycles).
    pub receive_timeout_s: f64,
    /// Replies lost in a row after which the link is down.
    pub max_lost: u32,
    /// Largest step per cycle per axis, rad; larger steps are clamped (the controller faults on
    /// over-speed steps).
    pub max_step_rad: [f64; 6],
}

impl MelfaConfig {
    /// A CR750 controller with the H7 layout, a two-cycle receive time-out, 100 losses to link down, and
    /// each axis's step limited to its rated speed over one cycle. Binds the loopback address when the
    /// controller is on it, any address otherwise.
    pub fn new(arm: ArmName, controller: SocketAddr, limits: &[JointLimit; 6]) -> Self {
        let bind = if controller.ip().is_loopback() {
            SocketAddr::new(controller.ip(), 0)
        } else {
            SocketAddr::new(std::net::Ipv4Addr::UNSPECIFIED.into(), 0)
        };
        Self {
            arm,
            controller,
            bind,
            layout: Layout::H7,
            cycle_s: CR750_CYCLE_S,
            receive_timeout_s: 2.0 * CR750_CYCLE_S,
            max_lost: MAX_LOST_REPLIES,
            max_step_rad: max_steps(limits, CR750_CYCLE_S),
        }
    }

    /// The same with another cycle (the step limits and time-out follow it).
    pub fn with_cycle(mut self, cycle_s: f64, limits: &[JointLimit; 6]) -> Self {
        self.cycle_s = cycle_s;
        self.receive_timeout_s = 2.0 * cycle_s;
        self.max_step_rad = max_steps(limits, cycle_s);
        self
    }
}

/// Each axis's rated speed over one cycle, rad.
pub fn max_steps(limits: &[JointLimit; 6], cycle_s: f64) -> [f64; 6] {
    limits.map(|l| l.max_velocity_rad_s * cycle_s)
}

/// Monitor data asked for in every packet: `dat` gets the filtered joints; with H7 the slots get encoder
/// feedback joints, the filtered pose and the feedback motor currents.
const RECV_TYPE: DataType = DataType::FilteredJoint;
const MONITORS: [DataType; 3] = [DataType::FeedbackJoint, DataType::FilteredPose, DataType::FeedbackCurrent];

/// A session with one MELFA controller.
pub struct MelfaArm {
    config: MelfaConfig,
    device: DeviceId,
    socket: UdpSocket,
    tx: [u8; MAX_LEN],
    rx: Box<[u8]>,
    c_count: u32,
    /// A packet went out and its reply has not been read.
    outstanding: bool,
    /// The last exchange lost its reply: late replies may be waiting.
    after_loss: bool,
    joints_rad: [f64; 6],
    last_sent_rad: [f64; 6],
    last_reply: Option<Packet>,
    stats: LinkStats,
    down: bool,
    ended: bool,
}

impl MelfaArm {
    /// Opens the session: binds, sends NULL until the controller answers (at most `max_lost` tries, one
    /// receive time-out each) and seeds the set-point with the joints it reports.
    pub fn connect(config: MelfaConfig) -> Result<Self, DeviceError> {
        let device = DeviceId::of_arm(DeviceKind::ArmServo, config.arm);
        let io = |action: String| move |source| DeviceError::Io { device, action, source };
        if !(config.receive_timeout_s > 0.0 && config.receive_timeout_s.is_finite()) || config.max_lost == 0 {
            return Err(DeviceError::Fault {
                device,
                reason: format!(
                    "receive time-out {} s and max_lost {} must be positive",
                    config.receive_timeout_s, config.max_lost
                ),
            });
        }
        let socket = UdpSocket::bind(config.bind).map_err(io(format!("binding {}", config.bind)))?;
        socket.connect(config.controller).map_err(io(format!("connecting to {}", config.controller)))?;
        socket
            .set_read_timeout(Some(Duration::from_secs_f64(config.receive_timeout_s)))
            .map_err(io("setting the receive time-out".to_owned()))?;
        let mut arm = Self {
            device,
            socket,
            tx: [0; MAX_LEN],
            rx: vec![0; MAX_DATAGRAM].into_boxed_slice(),
            c_count: 0,
            outstanding: false,
            after_loss: false,
            joints_rad: [0.0; 6],
            last_sent_rad: [0.0; 6],
            last_reply: None,
            stats: LinkStats::default(),
            down: false,
            ended: false,
            config,
        };
        loop {
            arm.send(Command::Null, None)?;
            if arm.receive()? {
                break;
            }
        }
        let seed = arm.last_reply.as_ref().and_then(Packet::joints_rad).unwrap_or(arm.joints_rad);
        arm.last_sent_rad = seed;
        arm.stats = LinkStats::default();
        Ok(arm)
    }

    /// The session's configuration.
    pub fn config(&self) -> &MelfaConfig {
        &self.config
    }

    /// The last reply received.
    pub fn last_reply(&self) -> Option<&Packet> {
        self.last_reply.as_ref()
    }

    /// The local address the session sends from.
    pub fn local_addr(&self) -> Result<SocketAddr, DeviceError> {
        self.socket.local_addr().map_err(|source| DeviceError::Io {
            device: self.device,
            action: "reading the local address".to_owned(),
            source,
        })
    }

    /// Sends END (once); the session accepts no more commands.
    pub fn end(&mut self) -> Result<(), DeviceError> {
        if self.ended {
            return Ok(());
        }
        self.ended = true;
        self.send(Command::End, None)
    }

    fn usable(&self) -> Result<(), DeviceError> {
        if self.ended {
            return Err(DeviceError::Closed { device: self.device });
        }
        if self.down {
            return Err(self.link_down());
        }
        Ok(())
    }

    fn link_down(&self) -> DeviceError {
        DeviceError::LinkDown {
            device: self.device,
            lost: self.stats.lost_in_a_row,
            detail: format!(
                "MELFA controller at {}, receive time-out {:.4} s",
                self.config.controller, self.config.receive_timeout_s
            ),
        }
    }

    fn send(&mut self, command: Command, joints_rad: Option<[f64; 6]>) -> Result<(), DeviceError> {
        if self.after_loss {
            self.discard_late_replies()?;
        }
        let mut packet = Packet::command(command, RECV_TYPE, MONITORS, self.c_count);
        if let Some(j) = joints_rad {
            packet.send_type = DataType::Joint;
            packet.data = Data::Joint([
                j[0] as f32,
                j[1] as f32,
                j[2] as f32,
                j[3] as f32,
                j[4] as f32,
                j[5] as f32,
                0.0,
                0.0,
            ]);
        }
        let len = packet.encode(self.config.layout, &mut self.tx);
        let sent = self.socket.send(&self.tx[..len]);
        self.c_count = self.c_count.wrapping_add(1);
        match sent {
            Ok(_) => {}
            // Nobody listening yet (ICMP port unreachable from an earlier packet): the reply will be
            // lost, and counted as such.
            Err(e) if e.kind() == ErrorKind::ConnectionRefused => {}
            Err(source) => {
                return Err(DeviceError::Io {
                    device: self.device,
                    action: format!("sending {command:?} to {}", self.config.controller),
                    source,
                });
            }
        }
        self.outstanding = command != Command::End;
        self.stats.exchanges += 1;
        Ok(())
    }

    /// Throws away datagrams already waiting (replies that came after their time-out).
    fn discard_late_replies(&mut self) -> Result<(), DeviceError> {
        let device = self.device;
        let io = |action: &str| {
            let action = action.to_owned();
            move |source| DeviceError::Io { device, action, source }
        };
        self.socket.set_nonblocking(true).map_err(io("switching to non-blocking"))?;
        while let Ok(_n) = self.socket.recv(&mut self.rx) {
            self.stats.late_discarded += 1;
        }
        self.socket.set_nonblocking(false).map_err(io("switching back to blocking"))?;
        self.after_loss = false;
        Ok(())
    }

    /// Waits for the reply to the outstanding packet. True when it came; false for a loss.
    fn receive(&mut self) -> Result<bool, DeviceError> {
        self.outstanding = false;
        let deadline = Instant::now() + Duration::from_secs_f64(self.config.receive_timeout_s);
        match self.socket.recv(&mut self.rx) {
            Ok(n) => {
                let packet =
                    Packet::decode(&self.rx[..n], self.config.layout).map_err(|e| DeviceError::Protocol {
                        device: self.device,
                        reason: format!("reply from {}: {e}", self.config.controller),
                    })?;
                let filtered = packet.joints_rad().ok_or_else(|| DeviceError::Protocol {
                    device: self.device,
                    reason: format!(
                        "reply from {}: dat holds {:?} (SendType {}), not the joints asked for (RecvType {})",
                        self.config.controller,
                        packet.send_type,
                        packet.send_type.code(),
                        RECV_TYPE.code()
                    ),
                })?;
                self.joints_rad = match self.config.layout {
                    Layout::H7 => packet.monitor_joints_rad(DataType::FeedbackJoint).unwrap_or(filtered),
                    Layout::PreH7 => filtered,
                };
                self.last_reply = Some(packet);
                self.stats.lost_in_a_row = 0;
                Ok(true)
            }
            Err(e)
                if matches!(
                    e.kind(),
                    ErrorKind::WouldBlock | ErrorKind::TimedOut | ErrorKind::ConnectionRefused
                ) =>
            {
                // A refused packet fails at once: wait out the time-out so every loss takes as long.
                let now = Instant::now();
                if deadline > now {
                    std::thread::sleep(deadline - now);
                }
                self.stats.lost_total += 1;
                self.stats.lost_in_a_row += 1;
                self.after_loss = true;
                if self.stats.lost_in_a_row >= self.config.max_lost {
                    self.down = true;
                    return Err(self.link_down());
                }
                Ok(false)
            }
            Err(source) => Err(DeviceError::Io {
                device: self.device,
                action: format!("receiving from {}", self.config.controller),
                source,
            }),
        }
    }
}

impl ArmServo for MelfaArm {
    fn read(&mut self) -> Result<ArmServoState, DeviceError> {
        self.usable()?;
        if !self.outstanding {
            self.stats.keep_alives += 1;
            self.send(Command::Null, None)?;
        }
        let fresh = self.receive()?;
        Ok(ArmServoState { joints_rad: self.joints_rad, fresh })
    }

    fn write(&mut self, joints_rad: &[f64; 6]) -> Result<(), DeviceError> {
        self.usable()?;
        if let Some(i) = joints_rad.iter().position(|q| !q.is_finite()) {
            return Err(LimitError::NotFinite {
                device: self.device,
                joint: crate::kinematics::JointId::Arm(i as u8 + 1),
            }
            .into());
        }
        if self.outstanding {
            self.receive()?;
        }
        let mut clamped = false;
        let target: [f64; 6] = std::array::from_fn(|i| {
            let max = self.config.max_step_rad[i];
            let step = joints_rad[i] - self.last_sent_rad[i];
            let limited = step.clamp(-max, max);
            clamped |= limited != step;
            self.last_sent_rad[i] + limited
        });
        if clamped {
            self.stats.clamped += 1;
        }
        self.send(Command::Move, Some(target))?;
        self.last_sent_rad = target;
        Ok(())
    }

    fn link_stats(&self) -> Option<LinkStats> {
        Some(self.stats)
    }

    fn shutdown(&mut self) -> Result<(), DeviceError> {
        self.end()
    }
}

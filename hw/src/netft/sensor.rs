//! The Net F/T driver: one box as a [`ForceSensor`].
//!
//! - [`NetFtSensor::connect`] binds, asks the box for its real-time stream and waits for the first
//!   record (up to `stall_timeout_s`).
//! - Each `read` takes every record that has come since the last (without waiting), keeps the newest
//!   and counts the ones lost from the gaps in their RDT sequence; one that comes out of order is
//!   thrown away. No record this cycle: the last reading, marked stale. No record for
//!   `stall_timeout_s`: the stream has stalled and `read` fails with [`DeviceError::LinkDown`].
//! - A record whose status is not 0 is the box reporting an error: [`DeviceError::Fault`] with the
//!   status word.
//! - Counts become newtons by the calibration's counts per force; the force turns from the sensor's
//!   frame into the shaft's by `shaft_from_sensor`.
//! - `zero` sends the box's set-bias command: the box takes its present reading as zero.
//! - `shutdown` stops the stream.

use std::io::ErrorKind;
use std::net::{SocketAddr, UdpSocket};
use std::time::{Duration, Instant};

use nalgebra::{Rotation3, Vector3};

use crate::device::{DeviceError, DeviceId, DeviceKind, ForceReading, ForceSensor};
use crate::rig::ArmName;

use super::rdt::{RECORD_LEN, RdtCommand, Record, Request};

/// How to reach one Net F/T box and read it.
#[derive(Clone, Debug, PartialEq)]
pub struct NetFtConfig {
    /// The instrument it measures (names the device in errors).
    pub arm: ArmName,
    /// The box's address (port 49152 on a real box).
    pub address: SocketAddr,
    /// The local address to bind (port 0: any).
    pub bind: SocketAddr,
    /// The calibration's counts per newton.
    pub counts_per_force: f64,
    /// The sensor's frame in the shaft frame (the shaft frame of [`crate::device::force_sensor`]).
    pub shaft_from_sensor: Rotation3<f64>,
    /// No record for this long and the stream has stalled, s.
    pub stall_timeout_s: f64,
}

impl NetFtConfig {
    /// A box at `address` with a calibration of `counts_per_force`, its frame the shaft's, a stall
    /// after 0.1 s (a hundred records at the box's 1 kHz). Binds the loopback address when the box is
    /// on it, any address otherwise.
    pub fn new(arm: ArmName, address: SocketAddr, counts_per_force: f64) -> Self {
        let bind = if address.ip().is_loopback() {
            SocketAddr::new(address.ip(), 0)
        } else {
            SocketAddr::new(std::net::Ipv4Addr::UNSPECIFIED.into(), 0)
        };
        Self {
            arm,
            address,
            bind,
            counts_per_force,
            shaft_from_sensor: Rotation3::identity(),
            stall_timeout_s: 0.1,
        }
    }
}

/// What the stream has done.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct NetFtStats {
    /// Records received and used.
    pub records: u64,
    /// Records lost (gaps in the RDT sequence).
    pub lost: u64,
    /// Records that came out of order, thrown away.
    pub out_of_order: u64,
    /// Reads that found no new record.
    pub stale_reads: u64,
}

/// A session with one Net F/T box.
pub struct NetFtSensor {
    config: NetFtConfig,
    device: DeviceId,
    socket: UdpSocket,
    last_sequence: Option<u32>,
    last_record_at: Instant,
    force_n: Vector3<f64>,
    stats: NetFtStats,
    stopped: bool,
    /// The first record, taken at start, has not been given yet.
    unread: bool,
}

impl NetFtSensor {
    /// Opens the session: binds, asks for the stream and waits for its first record.
    pub fn connect(config: NetFtConfig) -> Result<Self, DeviceError> {
        let device = DeviceId::of_arm(DeviceKind::ForceSensor, config.arm);
        if !(config.counts_per_force.is_finite() && config.counts_per_force > 0.0) {
            return Err(DeviceError::Fault {
                device,
                reason: format!("counts per force {}: must be a positive number", config.counts_per_force),
            });
        }
        if !(config.stall_timeout_s.is_finite() && config.stall_timeout_s > 0.0) {
            return Err(DeviceError::Fault {
                device,
                reason: format!("stall time-out {} s: must be a positive number", config.stall_timeout_s),
            });
        }
        let io = |action: String| move |source| DeviceError::Io { device, action, source };
        let socket = UdpSocket::bind(config.bind).map_err(io(format!("binding {}", config.bind)))?;
        socket.connect(config.address).map_err(io(format!("connecting to {}", config.address)))?;
        let mut sensor = Self {
            device,
            socket,
            last_sequence: None,
            last_record_at: Instant::now(),
            force_n: Vector3::zeros(),
            stats: NetFtStats::default(),
            stopped: false,
            unread: true,
            config,
        };
        sensor.request(RdtCommand::StartRealTime)?;
        // The first record, waited for.
        sensor
            .socket
            .set_read_timeout(Some(Duration::from_secs_f64(sensor.config.stall_timeout_s)))
            .map_err(io("setting the receive time-out".to_owned()))?;
        let mut buf = [0u8; 64];
        let first = sensor.socket.recv(&mut buf);
        sensor.socket.set_nonblocking(true).map_err(io("making the socket non-blocking".to_owned()))?;
        match first {
            Ok(len) => sensor.take(&buf[..len])?,
            Err(e) if matches!(e.kind(), ErrorKind::WouldBlock | ErrorKind::TimedOut) => {
                return Err(DeviceError::Timeout { device, waited_s: sensor.config.stall_timeout_s });
            }
            Err(source) => {
                return Err(DeviceError::Io {
                    device,
                    action: format!("receiving from {}", sensor.config.address),
                    source,
                });
            }
        }
        sensor.stats = NetFtStats { records: 1, ..NetFtStats::default() };
        Ok(sensor)
    }

    /// The session's configuration.
    pub fn config(&self) -> &NetFtConfig {
        &self.config
    }

    /// What the stream has done so far.
    pub fn stats(&self) -> NetFtStats {
        self.stats
    }

    /// The local address the session receives on.
    pub fn local_addr(&self) -> Result<SocketAddr, DeviceError> {
        self.socket.local_addr().map_err(|source| DeviceError::Io {
            device: self.device,
            action: "reading the local address".to_owned(),
            source,
        })
    }

    fn request(&self, command: RdtCommand) -> Result<(), DeviceError> {
        let bytes = Request { command, sample_count: 0 }.encode();
        self.socket.send(&bytes).map(|_| ()).map_err(|source| DeviceError::Io {
            device: self.device,
            action: format!("sending {command:?} to {}", self.config.address),
            source,
        })
    }

    /// Takes one datagram: a record in sequence becomes the reading.
    fn take(&mut self, bytes: &[u8]) -> Result<(), DeviceError> {
        let record = Record::decode(bytes).map_err(|e| DeviceError::Protocol {
            device: self.device,
            reason: format!("from {}: {e}", self.config.address),
        })?;
        if let Some(last) = self.last_sequence {
            let ahead = record.rdt_sequence.wrapping_sub(last);
            // Behind (or repeated): a late record; the newer one is already in.
            if ahead == 0 || ahead > u32::MAX / 2 {
                self.stats.out_of_order += 1;
                return Ok(());
            }
            self.stats.lost += u64::from(ahead - 1);
        }
        if record.status != 0 {
            return Err(DeviceError::Fault {
                device: self.device,
                reason: format!("the box at {} reports status 0x{:08x}", self.config.address, record.status),
            });
        }
        self.last_sequence = Some(record.rdt_sequence);
        self.last_record_at = Instant::now();
        self.stats.records += 1;
        let sensor_force = Vector3::new(record.counts[0], record.counts[1], record.counts[2]).map(f64::from)
            / self.config.counts_per_force;
        self.force_n = self.config.shaft_from_sensor * sensor_force;
        Ok(())
    }
}

impl ForceSensor for NetFtSensor {
    fn read(&mut self) -> Result<ForceReading, DeviceError> {
        if self.stopped {
            return Err(DeviceError::Closed { device: self.device });
        }
        let mut buf = [0u8; 2 * RECORD_LEN];
        let before = self.stats.records;
        loop {
            match self.socket.recv(&mut buf) {
                Ok(len) => self.take(&buf[..len])?,
                Err(e) if e.kind() == ErrorKind::WouldBlock => break,
                Err(source) => {
                    return Err(DeviceError::Io {
                        device: self.device,
                        action: format!("receiving from {}", self.config.address),
                        source,
                    });
                }
            }
        }
        let fresh = std::mem::take(&mut self.unread) || self.stats.records > before;
        if !fresh {
            self.stats.stale_reads += 1;
            let waited_s = self.last_record_at.elapsed().as_secs_f64();
            if waited_s > self.config.stall_timeout_s {
                return Err(DeviceError::LinkDown {
                    device: self.device,
                    lost: 0,
                    detail: format!(
                        "the stream from {} stalled: no record for {waited_s:.3} s (more than {} s)",
                        self.config.address, self.config.stall_timeout_s
                    ),
                });
            }
        }
        Ok(ForceReading { shaft_force_n: self.force_n, fresh })
    }

    fn zero(&mut self) -> Result<(), DeviceError> {
        self.request(RdtCommand::SetBias)
    }

    fn shutdown(&mut self) -> Result<(), DeviceError> {
        if self.stopped {
            return Ok(());
        }
        self.stopped = true;
        self.request(RdtCommand::Stop)
    }
}

impl Drop for NetFtSensor {
    fn drop(&mut self) {
        // The box streams until told to stop.
        if !self.stopped {
            self.request(RdtCommand::Stop).ok();
        }
    }
}

//! An emulator of a Net F/T box's RDT side: it answers requests on UDP and streams records of a force
//! you set.
//!
//! - Start real-time streaming (0x0002) streams records to the asker at `rate_hz`, `sample_count` of
//!   them (0: until stopped); stop (0x0000) ends the stream; set bias (0x0042) takes the present
//!   reading as zero.
//! - `drop_fraction` of the records are dropped on purpose (which ones, from `seed`): their RDT
//!   sequence numbers are used, so the driver sees the gaps, as it would on a lossy network.
//! - [`NetFtEmulator::stall`] stops the stream without a word, as a box whose cable was pulled;
//!   [`NetFtEmulator::set_wrench`] changes the force streamed.
//! - It binds loopback addresses only, unless `allow_remote` is given.

use std::io::ErrorKind;
use std::net::{SocketAddr, UdpSocket};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use super::rdt::{RdtCommand, Record, Request};

/// How the emulated box behaves.
#[derive(Clone, Debug, PartialEq)]
pub struct NetFtEmulatorConfig {
    /// Where it listens (port 49152 on a real box; 0: any free port).
    pub bind: SocketAddr,
    /// Listen on an address other than loopback.
    pub allow_remote: bool,
    /// Records a second while streaming.
    pub rate_hz: f64,
    /// Counts per newton of its calibration.
    pub counts_per_force: f64,
    /// Counts per newton-metre.
    pub counts_per_torque: f64,
    /// The force and torque it measures: Fx, Fy, Fz (N), Tx, Ty, Tz (N m), its own frame.
    pub wrench: [f64; 6],
    /// The fraction of records dropped on purpose (0 to 1).
    pub drop_fraction: f64,
    /// Which records are dropped.
    pub seed: u64,
}

impl NetFtEmulatorConfig {
    /// A box on `bind` streaming 1,000 records a second of zero force, at 1,000,000 counts per newton
    /// and per newton-metre (a Nano17's order), dropping none.
    pub fn new(bind: SocketAddr) -> Self {
        Self {
            bind,
            allow_remote: false,
            rate_hz: 1000.0,
            counts_per_force: 1.0e6,
            counts_per_torque: 1.0e6,
            wrench: [0.0; 6],
            drop_fraction: 0.0,
            seed: 0,
        }
    }
}

/// What the box did.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct NetFtReport {
    /// Requests received.
    pub requests: u64,
    /// Records sent.
    pub records_sent: u64,
    /// Records dropped on purpose (their sequence numbers skipped).
    pub records_dropped: u64,
    /// Set-bias requests.
    pub biases: u64,
    /// Datagrams that were not requests (each named in `problems`, the first 20).
    pub malformed: u64,
    /// What was wrong with them.
    pub problems: Vec<String>,
}

/// Why the emulator could not start or stopped.
#[derive(Debug, thiserror::Error)]
pub enum NetFtEmulatorError {
    /// A non-loopback address without `allow_remote`.
    #[error(
        "refusing to bind {addr}: not a loopback address (the emulator listens on loopback only unless remote access is allowed explicitly)"
    )]
    RemoteRefused {
        /// The address.
        addr: SocketAddr,
    },
    /// The configuration is unusable.
    #[error("Net F/T emulator: {0}")]
    Config(String),
    /// An operating-system error.
    #[error("{action}: {source}")]
    Io {
        /// What it was doing.
        action: String,
        /// The error.
        source: std::io::Error,
    },
}

struct Shared {
    stop: AtomicBool,
    stall: AtomicBool,
    wrench: Mutex<[f64; 6]>,
}

/// A running emulated box (its thread stops when this is stopped or dropped).
pub struct NetFtEmulator {
    addr: SocketAddr,
    shared: Arc<Shared>,
    thread: Option<JoinHandle<Result<NetFtReport, NetFtEmulatorError>>>,
}

/// A small deterministic generator (SplitMix64) for which records to drop.
struct Coin(u64);

impl Coin {
    fn uniform(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }
}

impl NetFtEmulator {
    /// Binds and starts the box's thread.
    pub fn start(config: NetFtEmulatorConfig) -> Result<Self, NetFtEmulatorError> {
        if !config.allow_remote && !config.bind.ip().is_loopback() {
            return Err(NetFtEmulatorError::RemoteRefused { addr: config.bind });
        }
        let positive = [
            ("rate_hz", config.rate_hz),
            ("counts_per_force", config.counts_per_force),
            ("counts_per_torque", config.counts_per_torque),
        ];
        for (name, value) in positive {
            if !(value.is_finite() && value > 0.0) {
                return Err(NetFtEmulatorError::Config(format!("{name} {value}: must be a positive number")));
            }
        }
        if !(0.0..=1.0).contains(&config.drop_fraction) {
            return Err(NetFtEmulatorError::Config(format!(
                "drop_fraction {}: 0 to 1",
                config.drop_fraction
            )));
        }
        if config.rate_hz > 10_000.0 {
            return Err(NetFtEmulatorError::Config(format!("rate_hz {}: at most 10000", config.rate_hz)));
        }
        let io = |action: String| move |source| NetFtEmulatorError::Io { action, source };
        let socket = UdpSocket::bind(config.bind).map_err(io(format!("binding {}", config.bind)))?;
        let addr = socket.local_addr().map_err(io("reading the local address".to_owned()))?;
        let shared = Arc::new(Shared {
            stop: AtomicBool::new(false),
            stall: AtomicBool::new(false),
            wrench: Mutex::new(config.wrench),
        });
        let inner = Arc::clone(&shared);
        let thread = std::thread::Builder::new()
            .name("netft-emulator".to_owned())
            .spawn(move || serve(&socket, &config, &inner))
            .map_err(io("starting the emulator's thread".to_owned()))?;
        Ok(Self { addr, shared, thread: Some(thread) })
    }

    /// Where it listens.
    pub fn local_addr(&self) -> SocketAddr {
        self.addr
    }

    /// Changes the force and torque it measures.
    pub fn set_wrench(&self, wrench: [f64; 6]) {
        if let Ok(mut w) = self.shared.wrench.lock() {
            *w = wrench;
        }
    }

    /// Stalls the stream (true) or lets it go on (false).
    pub fn stall(&self, stalled: bool) {
        self.shared.stall.store(stalled, Ordering::SeqCst);
    }

    /// Stops the box and says what it did.
    pub fn stop(mut self) -> Result<NetFtReport, NetFtEmulatorError> {
        self.finish()
    }

    fn finish(&mut self) -> Result<NetFtReport, NetFtEmulatorError> {
        self.shared.stop.store(true, Ordering::SeqCst);
        match self.thread.take() {
            Some(thread) => thread.join().unwrap_or_else(|_| {
                Err(NetFtEmulatorError::Config("the emulator's thread panicked".to_owned()))
            }),
            None => Ok(NetFtReport::default()),
        }
    }
}

impl Drop for NetFtEmulator {
    fn drop(&mut self) {
        self.finish().ok();
    }
}

/// Until stopped: answers requests and streams.
fn serve(
    socket: &UdpSocket,
    config: &NetFtEmulatorConfig,
    shared: &Shared,
) -> Result<NetFtReport, NetFtEmulatorError> {
    let io = |action: &str| {
        let action = action.to_owned();
        move |source| NetFtEmulatorError::Io { action, source }
    };
    let period = Duration::from_secs_f64(1.0 / config.rate_hz);
    socket
        .set_read_timeout(Some(period.min(Duration::from_millis(5))))
        .map_err(io("setting the receive time-out"))?;
    let mut report = NetFtReport::default();
    let mut coin = Coin(config.seed);
    // (where to, records still to send; None: endless)
    let mut stream: Option<(SocketAddr, Option<u32>)> = None;
    let (mut rdt_sequence, mut ft_sequence) = (0u32, 0u32);
    let mut bias = [0i32; 6];
    let mut next_send = Instant::now();
    let mut buf = [0u8; 64];
    let counts = |wrench: &[f64; 6]| -> [i32; 6] {
        std::array::from_fn(|k| {
            let per = if k < 3 { config.counts_per_force } else { config.counts_per_torque };
            (wrench[k] * per).round().clamp(f64::from(i32::MIN), f64::from(i32::MAX)) as i32
        })
    };
    while !shared.stop.load(Ordering::SeqCst) {
        match socket.recv_from(&mut buf) {
            Ok((len, from)) => match Request::decode(&buf[..len]) {
                Ok(request) => {
                    report.requests += 1;
                    match request.command {
                        RdtCommand::StartRealTime => {
                            let count = (request.sample_count > 0).then_some(request.sample_count);
                            stream = Some((from, count));
                            next_send = Instant::now();
                        }
                        RdtCommand::Stop => stream = None,
                        RdtCommand::SetBias => {
                            report.biases += 1;
                            let wrench = shared.wrench.lock().map(|w| *w).unwrap_or(config.wrench);
                            bias = counts(&wrench);
                        }
                    }
                }
                Err(e) => {
                    report.malformed += 1;
                    if report.problems.len() < 20 {
                        report.problems.push(format!("from {from}: {e}"));
                    }
                }
            },
            Err(e) if matches!(e.kind(), ErrorKind::WouldBlock | ErrorKind::TimedOut) => {}
            Err(source) => {
                return Err(NetFtEmulatorError::Io { action: "receiving a request".to_owned(), source });
            }
        }
        let Some((to, remaining)) = stream else { continue };
        if shared.stall.load(Ordering::SeqCst) {
            next_send = Instant::now();
            continue;
        }
        // The records due since the last, at most ten at once after a pause.
        let mut due = 0;
        while Instant::now() >= next_send && due < 10 {
            next_send += period;
            due += 1;
        }
        for _ in 0..due {
            rdt_sequence = rdt_sequence.wrapping_add(1);
            ft_sequence = ft_sequence.wrapping_add(1);
            let wrench = shared.wrench.lock().map(|w| *w).unwrap_or(config.wrench);
            let raw = counts(&wrench);
            let record = Record {
                rdt_sequence,
                ft_sequence,
                status: 0,
                counts: std::array::from_fn(|k| raw[k].saturating_sub(bias[k])),
            };
            if config.drop_fraction > 0.0 && coin.uniform() < config.drop_fraction {
                report.records_dropped += 1;
            } else {
                socket.send_to(&record.encode(), to).map_err(io("sending a record"))?;
                report.records_sent += 1;
            }
        }
        if let Some(left) = remaining {
            let left = left.saturating_sub(due);
            stream = (left > 0).then_some((to, Some(left)));
        }
    }
    Ok(report)
}

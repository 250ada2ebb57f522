//! An emulator of the instrument's CiA 402 drives: a set of nodes on one bus, each with the objects of
//! [`super::dictionary`], the state machine of [`super::cia402`] and a first-order motor.
//!
//! - NMT start, stop, pre-operational and reset; a boot-up message at start and a heartbeat every
//!   producer time (10 ms unless written).
//! - Expedited SDO reads and writes of its objects; an object it does not have, a read-only one
//!   written or a mode other than cyclic synchronous position is refused with CiA 301's abort code.
//! - While operational: RPDO1 (controlword, target position) sets its commands; each SYNC moves the
//!   motor towards the target (a first-order lag of `time_constant_s`) when the drive is Operation
//!   Enabled, then TPDO1 (statusword, position actual) answers.
//! - A position further than the following error window from its target faults the drive and sends
//!   EMCY 0x8611; [`CanopenEmulator::drop_out`] silences a node (no answers, no heartbeat), as a node
//!   whose cable was pulled.
//! - It runs on its own thread, reading the bus as frames come.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use super::bus::CanTransport;
use super::cia402::DriveState;
use super::dictionary::{self as od, MODE_CSP};
use super::frame::{CanFrame, CobId};
use super::sdo::{Object, SdoRequest, SdoResponse};

/// How one emulated drive behaves.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NodeConfig {
    /// Its node id (1 to 127).
    pub node: u8,
    /// Where its motor stands at power-on, counts.
    pub position_counts: i32,
    /// Software position limits, counts.
    pub limits_counts: [i32; 2],
    /// The motor's lag, s.
    pub time_constant_s: f64,
    /// Whether it has cyclic synchronous position mode (without, writing that mode is refused).
    pub supports_csp: bool,
}

impl NodeConfig {
    /// Node `node` at 0 counts, limits of +-1,000,000 counts, a 5 ms motor, with CSP.
    pub fn new(node: u8) -> Self {
        Self {
            node,
            position_counts: 0,
            limits_counts: [-1_000_000, 1_000_000],
            time_constant_s: 0.005,
            supports_csp: true,
        }
    }
}

/// The emulated drives.
#[derive(Clone, Debug, PartialEq)]
pub struct CanopenEmulatorConfig {
    /// Its nodes.
    pub nodes: Vec<NodeConfig>,
    /// The time between SYNCs the motors move by, s.
    pub sync_period_s: f64,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Nmt {
    PreOperational,
    Operational,
    Stopped,
}

struct Node {
    config: NodeConfig,
    nmt: Nmt,
    state: DriveState,
    controlword: u16,
    mode: u8,
    target: i32,
    position: f64,
    window: u32,
    heartbeat_ms: u16,
    next_heartbeat: Instant,
    silent: bool,
    fault_now: bool,
}

impl Node {
    fn new(config: NodeConfig) -> Self {
        Self {
            config,
            nmt: Nmt::PreOperational,
            state: DriveState::NotReadyToSwitchOn,
            controlword: 0,
            mode: 0,
            target: config.position_counts,
            position: f64::from(config.position_counts),
            window: 0,
            heartbeat_ms: 10,
            next_heartbeat: Instant::now(),
            silent: false,
            fault_now: false,
        }
    }

    fn statusword(&self) -> u16 {
        self.state.statusword()
    }

    fn read(&self, o: Object) -> Result<(u32, u8), u32> {
        Ok(match o {
            od::HEARTBEAT_PRODUCER => (u32::from(self.heartbeat_ms), 2),
            od::CONTROLWORD => (u32::from(self.controlword), 2),
            od::STATUSWORD => (u32::from(self.statusword()), 2),
            od::MODES_OF_OPERATION | od::MODES_OF_OPERATION_DISPLAY => (u32::from(self.mode), 1),
            od::POSITION_ACTUAL => (self.position.round() as i32 as u32, 4),
            od::TARGET_POSITION => (self.target as u32, 4),
            od::FOLLOWING_ERROR_WINDOW => (self.window, 4),
            o if o == od::SOFTWARE_LIMITS[0] => (self.config.limits_counts[0] as u32, 4),
            o if o == od::SOFTWARE_LIMITS[1] => (self.config.limits_counts[1] as u32, 4),
            o if o == od::RPDO1_MAPPING[0] => (od::RPDO1[0], 4),
            o if o == od::RPDO1_MAPPING[1] => (od::RPDO1[1], 4),
            o if o == od::TPDO1_MAPPING[0] => (od::TPDO1[0], 4),
            o if o == od::TPDO1_MAPPING[1] => (od::TPDO1[1], 4),
            _ => return Err(0x0602_0000),
        })
    }

    fn write(&mut self, o: Object, value: u32) -> Result<(), u32> {
        match o {
            od::HEARTBEAT_PRODUCER => self.heartbeat_ms = value as u16,
            od::CONTROLWORD => self.command(value as u16),
            od::MODES_OF_OPERATION if value as u8 == MODE_CSP && self.config.supports_csp => {
                self.mode = MODE_CSP
            }
            od::MODES_OF_OPERATION => return Err(0x0609_0030),
            od::TARGET_POSITION => self.target = value as i32,
            od::FOLLOWING_ERROR_WINDOW => self.window = value,
            od::STATUSWORD | od::MODES_OF_OPERATION_DISPLAY | od::POSITION_ACTUAL => return Err(0x0601_0002),
            o if od::SOFTWARE_LIMITS.contains(&o)
                || od::RPDO1_MAPPING.contains(&o)
                || od::TPDO1_MAPPING.contains(&o) =>
            {
                return Err(0x0601_0002);
            }
            _ => return Err(0x0602_0000),
        }
        Ok(())
    }

    fn command(&mut self, controlword: u16) {
        self.state = self.state.after(controlword, self.controlword);
        self.controlword = controlword;
    }
}

/// A running set of emulated drives (its thread stops when this is stopped or dropped).
pub struct CanopenEmulator {
    nodes: Arc<Mutex<Vec<Node>>>,
    stop: Arc<AtomicBool>,
    thread: Option<JoinHandle<()>>,
}

impl CanopenEmulator {
    /// Starts the drives on `transport`: each sends its boot-up message.
    pub fn start(mut transport: Box<dyn CanTransport>, config: CanopenEmulatorConfig) -> Self {
        let nodes: Vec<Node> = config.nodes.iter().map(|c| Node::new(*c)).collect();
        for node in &nodes {
            if let Ok(frame) = CobId::Heartbeat(node.config.node).frame(&[0x00]) {
                transport.send(&frame).ok();
            }
        }
        let nodes = Arc::new(Mutex::new(nodes));
        let stop = Arc::new(AtomicBool::new(false));
        let (inner, halt) = (Arc::clone(&nodes), Arc::clone(&stop));
        let dt_s = config.sync_period_s;
        let thread = std::thread::Builder::new()
            .name("canopen-emulator".into())
            .spawn(move || {
                while !halt.load(Ordering::SeqCst) {
                    let busy = match inner.lock() {
                        Ok(mut nodes) => serve(transport.as_mut(), &mut nodes, dt_s),
                        Err(_) => return,
                    };
                    if !busy {
                        std::thread::sleep(Duration::from_micros(200));
                    }
                }
            })
            .ok();
        Self { nodes, stop, thread }
    }

    fn with_node(&self, node: u8, f: impl FnOnce(&mut Node)) {
        if let Ok(mut nodes) = self.nodes.lock()
            && let Some(n) = nodes.iter_mut().find(|n| n.config.node == node)
        {
            f(n);
        }
    }

    /// Silences a node: it answers nothing and its heartbeat stops.
    pub fn drop_out(&self, node: u8) {
        self.with_node(node, |n| n.silent = true);
    }

    /// Makes a node's next SYNC find a following error.
    pub fn following_error(&self, node: u8) {
        self.with_node(node, |n| n.fault_now = true);
    }

    /// Each node's drive state and position, counts.
    pub fn nodes(&self) -> Vec<(u8, DriveState, i32)> {
        self.nodes
            .lock()
            .map(|nodes| nodes.iter().map(|n| (n.config.node, n.state, n.position.round() as i32)).collect())
            .unwrap_or_default()
    }

    /// Stops the drives' thread.
    pub fn stop(mut self) {
        self.halt();
    }

    fn halt(&mut self) {
        self.stop.store(true, Ordering::SeqCst);
        if let Some(thread) = self.thread.take() {
            thread.join().ok();
        }
    }
}

impl Drop for CanopenEmulator {
    fn drop(&mut self) {
        self.halt();
    }
}

/// Handles every frame that has come and the heartbeats due; whether there was anything.
fn serve(transport: &mut dyn CanTransport, nodes: &mut [Node], dt_s: f64) -> bool {
    let mut busy = false;
    let mut out: Vec<CanFrame> = Vec::new();
    while let Ok(Some(frame)) = transport.try_recv() {
        busy = true;
        let Some(cob) = CobId::of(frame.id()) else { continue };
        let data = frame.data();
        match cob {
            CobId::Nmt if data.len() == 2 => {
                for n in nodes.iter_mut().filter(|n| data[1] == 0 || data[1] == n.config.node) {
                    match data[0] {
                        0x01 => n.nmt = Nmt::Operational,
                        0x02 => n.nmt = Nmt::Stopped,
                        0x80 => n.nmt = Nmt::PreOperational,
                        0x81 | 0x82 => {
                            let silent = n.silent;
                            *n = Node::new(n.config);
                            n.silent = silent;
                        }
                        _ => {}
                    }
                }
            }
            CobId::SdoRequest(id) => {
                let Some(n) = nodes.iter_mut().find(|n| n.config.node == id && !n.silent) else { continue };
                let response = match SdoRequest::decode(data) {
                    Ok(SdoRequest::Read { object }) => match n.read(object) {
                        Ok((value, len)) => SdoResponse::Value { object, value, len },
                        Err(code) => SdoResponse::Abort { object, code },
                    },
                    Ok(SdoRequest::Write { object, value, .. }) => match n.write(object, value) {
                        Ok(()) => SdoResponse::Written { object },
                        Err(code) => SdoResponse::Abort { object, code },
                    },
                    Err(_) => {
                        SdoResponse::Abort { object: Object { index: 0, subindex: 0 }, code: 0x0504_0001 }
                    }
                };
                if let Ok(frame) = response.frame(id) {
                    out.push(frame);
                }
            }
            CobId::Rpdo(1, id) if data.len() >= 6 => {
                if let Some(n) = nodes.iter_mut().find(|n| n.config.node == id && n.nmt == Nmt::Operational) {
                    n.command(u16::from_le_bytes([data[0], data[1]]));
                    n.target = i32::from_le_bytes([data[2], data[3], data[4], data[5]]);
                }
            }
            CobId::Sync => {
                for n in nodes.iter_mut().filter(|n| !n.silent && n.nmt == Nmt::Operational) {
                    if n.state == DriveState::OperationEnabled {
                        let alpha = 1.0 - (-dt_s / n.config.time_constant_s.max(1e-9)).exp();
                        n.position += (f64::from(n.target) - n.position) * alpha;
                        let off = (f64::from(n.target) - n.position).abs();
                        if n.fault_now || (n.window > 0 && off > f64::from(n.window)) {
                            n.fault_now = false;
                            n.state = DriveState::Fault;
                            let code = od::EMCY_FOLLOWING_ERROR.to_le_bytes();
                            if let Ok(frame) =
                                CobId::Emcy(n.config.node).frame(&[code[0], code[1], 0x20, 0, 0, 0, 0, 0])
                            {
                                out.push(frame);
                            }
                        }
                    }
                    let mut pdo = [0u8; 6];
                    pdo[0..2].copy_from_slice(&n.statusword().to_le_bytes());
                    pdo[2..6].copy_from_slice(&(n.position.round() as i32).to_le_bytes());
                    if let Ok(frame) = CobId::Tpdo(1, n.config.node).frame(&pdo) {
                        out.push(frame);
                    }
                }
            }
            _ => {}
        }
    }
    let now = Instant::now();
    for n in nodes.iter_mut() {
        if n.state == DriveState::NotReadyToSwitchOn {
            n.state = DriveState::SwitchOnDisabled;
        }
        if !n.silent && n.heartbeat_ms > 0 && now >= n.next_heartbeat {
            n.next_heartbeat = now + Duration::from_millis(u64::from(n.heartbeat_ms));
            let state = match n.nmt {
                Nmt::Operational => 0x05,
                Nmt::PreOperational => 0x7F,
                Nmt::Stopped => 0x04,
            };
            if let Ok(frame) = CobId::Heartbeat(n.config.node).frame(&[state]) {
                out.push(frame);
            }
        }
    }
    for frame in &out {
        transport.send(frame).ok();
    }
    busy
}

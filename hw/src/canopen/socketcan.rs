//! CAN frames through Linux's SocketCAN: the lab's transport, on a CAN adapter's interface (`can0`)
//! or a virtual one (`vcan0`, where frames one socket sends reach every other socket on it).
//!
//! CANopen uses classic data frames with 11-bit identifiers; anything else on the bus (another
//! device's extended identifiers, remote frames, error frames) is not for the drives and is passed
//! over. The interface's bit rate is set outside (`ip link set can0 type can bitrate 1000000`).

use std::io::ErrorKind;

use socketcan::{CanSocket, EmbeddedFrame, Id, Socket, StandardId};

use super::bus::{CanTransport, TransportError};
use super::frame::CanFrame;

/// Linux's ENOBUFS: a CAN interface's transmit queue is full.
const ENOBUFS: i32 = 105;

/// A raw CAN socket bound to one interface, reading without waiting.
pub struct SocketCan {
    socket: CanSocket,
    interface: String,
}

impl SocketCan {
    /// Opens `interface` (for example `can0` or `vcan0`).
    pub fn open(interface: &str) -> Result<Self, TransportError> {
        let named = |e: std::io::Error| TransportError(format!("SocketCAN interface \"{interface}\": {e}"));
        let socket = CanSocket::open(interface).map_err(named)?;
        socket.set_nonblocking(true).map_err(named)?;
        Ok(Self { socket, interface: interface.to_owned() })
    }

    /// The interface's name.
    pub fn interface(&self) -> &str {
        &self.interface
    }
}

/// A frame as SocketCAN's.
pub fn to_socketcan(frame: &CanFrame) -> Result<socketcan::CanFrame, TransportError> {
    let id = StandardId::new(frame.id())
        .ok_or_else(|| TransportError(format!("CAN identifier 0x{:x}: at most 0x7ff", frame.id())))?;
    socketcan::CanFrame::new(id, frame.data())
        .ok_or_else(|| TransportError(format!("{} data bytes: at most 8", frame.data().len())))
}

/// SocketCAN's frame as a CANopen frame (None: not a classic data frame with an 11-bit identifier).
pub fn from_socketcan(frame: &socketcan::CanFrame) -> Option<CanFrame> {
    match frame {
        socketcan::CanFrame::Data(data) => match data.id() {
            Id::Standard(id) => CanFrame::new(id.as_raw(), data.data()).ok(),
            Id::Extended(_) => None,
        },
        socketcan::CanFrame::Remote(_) | socketcan::CanFrame::Error(_) => None,
    }
}

impl CanTransport for SocketCan {
    fn send(&mut self, frame: &CanFrame) -> Result<(), TransportError> {
        let frame = to_socketcan(frame)?;
        self.socket.write_frame(&frame).map_err(|e| {
            let why = if e.raw_os_error() == Some(ENOBUFS) || e.kind() == ErrorKind::WouldBlock {
                // Nobody acknowledges the frames (no node, no terminator).
                format!("{e} (the transmit queue is full: is any node on the bus, and the bus terminated?)")
            } else {
                e.to_string()
            };
            TransportError(format!("sending on SocketCAN interface \"{}\": {why}", self.interface))
        })
    }

    fn try_recv(&mut self) -> Result<Option<CanFrame>, TransportError> {
        loop {
            match self.socket.read_frame() {
                Ok(frame) => {
                    if let Some(frame) = from_socketcan(&frame) {
                        return Ok(Some(frame));
                    }
                }
                Err(e) if e.kind() == ErrorKind::WouldBlock => return Ok(None),
                Err(e) if e.kind() == ErrorKind::Interrupted => continue,
                Err(e) => {
                    return Err(TransportError(format!(
                        "receiving on SocketCAN interface \"{}\": {e}",
                        self.interface
                    )));
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use socketcan::ExtendedId;

    /// A CANopen frame becomes SocketCAN's and back unchanged; frames CANopen does not use are
    /// passed over.
    #[test]
    fn frames_convert_both_ways_and_foreign_frames_are_passed_over() {
        let frame = CanFrame::new(0x60C, &[0x40, 0x41, 0x60, 0, 0, 0, 0, 0]).expect("an SDO request");
        let theirs = to_socketcan(&frame).expect("converted");
        assert_eq!(theirs.id(), Id::Standard(StandardId::new(0x60C).expect("an id")));
        assert_eq!(from_socketcan(&theirs), Some(frame));
        let sync = CanFrame::new(0x80, &[]).expect("SYNC");
        assert_eq!(from_socketcan(&to_socketcan(&sync).expect("converted")), Some(sync));
        let extended =
            socketcan::CanFrame::new(ExtendedId::new(0x18FF_0001).expect("an id"), &[1]).expect("a frame");
        assert_eq!(from_socketcan(&extended), None);
        let remote = socketcan::CanFrame::new_remote(StandardId::new(0x70C).expect("an id"), 1)
            .expect("a remote frame");
        assert_eq!(from_socketcan(&remote), None);
    }

    /// An interface that is not there is named in the error.
    #[test]
    fn a_missing_interface_is_named() {
        let error = SocketCan::open("nocan7").err().expect("no such interface");
        assert!(error.0.contains("SocketCAN interface \"nocan7\""), "{error}");
    }
}

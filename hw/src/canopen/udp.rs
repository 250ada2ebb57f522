//! CAN frames over UDP, for an emulator in another process (`knotlab canopen-emulator`): each frame
//! one datagram of 13 bytes, as SocketCAN lays a classic frame out but big-endian: the identifier (4
//! bytes), the data length (1 byte), eight data bytes (the unused ones 0). Two participants, each
//! sending to the other.

use std::io::ErrorKind;
use std::net::{SocketAddr, UdpSocket};

use super::bus::{CanTransport, TransportError};
use super::frame::CanFrame;

/// Bytes in a datagram.
pub const DATAGRAM_LEN: usize = 13;

/// A frame's datagram.
pub fn encode(frame: &CanFrame) -> [u8; DATAGRAM_LEN] {
    let mut out = [0; DATAGRAM_LEN];
    out[0..4].copy_from_slice(&u32::from(frame.id()).to_be_bytes());
    out[4] = frame.data().len() as u8;
    out[5..5 + frame.data().len()].copy_from_slice(frame.data());
    out
}

/// A datagram's frame.
pub fn decode(bytes: &[u8]) -> Result<CanFrame, TransportError> {
    if bytes.len() != DATAGRAM_LEN {
        return Err(TransportError(format!("a CAN datagram has {DATAGRAM_LEN} bytes, not {}", bytes.len())));
    }
    let id = u32::from_be_bytes([bytes[0], bytes[1], bytes[2], bytes[3]]);
    let len = usize::from(bytes[4]);
    if len > 8 {
        return Err(TransportError(format!("a CAN datagram's length byte {len}: at most 8")));
    }
    let id =
        u16::try_from(id).map_err(|_| TransportError(format!("CAN identifier 0x{id:x}: at most 0x7ff")))?;
    CanFrame::new(id, &bytes[5..5 + len]).map_err(|e| TransportError(e.to_string()))
}

/// One side of a CAN-over-UDP link.
pub struct UdpCan {
    socket: UdpSocket,
    /// Where frames go (None: nobody has spoken yet to a listener).
    peer: Option<SocketAddr>,
    /// A listener sends to whoever sent last.
    listens: bool,
}

impl UdpCan {
    /// Binds `local` and sends to `peer`; receives without waiting.
    pub fn connect(local: SocketAddr, peer: SocketAddr) -> Result<Self, TransportError> {
        let socket = UdpSocket::bind(local).map_err(|e| TransportError(format!("binding {local}: {e}")))?;
        socket.set_nonblocking(true).map_err(|e| TransportError(format!("{local}: {e}")))?;
        Ok(Self { socket, peer: Some(peer), listens: false })
    }

    /// Binds `local` and answers whoever sends to it (the emulator's side); what it sends before
    /// anyone has spoken goes nowhere.
    pub fn listen(local: SocketAddr) -> Result<Self, TransportError> {
        let socket = UdpSocket::bind(local).map_err(|e| TransportError(format!("binding {local}: {e}")))?;
        socket.set_nonblocking(true).map_err(|e| TransportError(format!("{local}: {e}")))?;
        Ok(Self { socket, peer: None, listens: true })
    }

    /// The address it receives on.
    pub fn local_addr(&self) -> Result<SocketAddr, TransportError> {
        self.socket.local_addr().map_err(|e| TransportError(e.to_string()))
    }

    /// Sends to `peer` from now on (an emulator answers whoever spoke last).
    pub fn set_peer(&mut self, peer: SocketAddr) {
        self.peer = Some(peer);
    }
}

impl CanTransport for UdpCan {
    fn send(&mut self, frame: &CanFrame) -> Result<(), TransportError> {
        let Some(peer) = self.peer else { return Ok(()) };
        match self.socket.send_to(&encode(frame), peer) {
            Ok(_) => Ok(()),
            // A listener's peer that has gone: its frames go nowhere, as on a bus nobody reads.
            Err(e) if self.listens && e.kind() == ErrorKind::ConnectionRefused => Ok(()),
            Err(e) => Err(TransportError(format!("sending to {peer}: {e}"))),
        }
    }

    fn try_recv(&mut self) -> Result<Option<CanFrame>, TransportError> {
        let mut buf = [0u8; 64];
        loop {
            match self.socket.recv_from(&mut buf) {
                Ok((len, from)) => {
                    if self.listens {
                        self.peer = Some(from);
                    }
                    return decode(&buf[..len]).map(Some);
                }
                Err(e) if e.kind() == ErrorKind::WouldBlock => return Ok(None),
                // A peer not yet listening (ICMP port unreachable) is not a frame.
                Err(e) if e.kind() == ErrorKind::ConnectionRefused => continue,
                Err(e) => return Err(TransportError(format!("receiving: {e}"))),
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A frame goes over loopback UDP and comes back the same; a bad datagram is named.
    #[test]
    fn frames_cross_loopback_udp() {
        let any: SocketAddr = "127.0.0.1:0".parse().expect("an address");
        let mut a = UdpCan::connect(any, any).expect("bound");
        let mut b = UdpCan::connect(any, a.local_addr().expect("a's address")).expect("bound");
        a.set_peer(b.local_addr().expect("b's address"));
        let frame = CanFrame::new(0x605, &[0x40, 0x41, 0x60, 0, 0, 0, 0, 0]).expect("a frame");
        b.send(&frame).expect("sent");
        let start = std::time::Instant::now();
        let got = loop {
            if let Some(f) = a.try_recv().expect("received") {
                break f;
            }
            assert!(start.elapsed().as_secs() < 2, "nothing came");
        };
        assert_eq!(got, frame);
        assert_eq!(encode(&frame)[0..5], [0, 0, 6, 5, 8]);
        assert!(decode(&[0; 12]).is_err());
        let mut long = encode(&frame);
        long[4] = 9;
        assert!(decode(&long).unwrap_err().0.contains("at most 8"));
    }
}

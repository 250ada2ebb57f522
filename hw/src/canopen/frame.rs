//! A classic CAN frame (11-bit identifier, up to eight data bytes) and CANopen's pre-defined
//! connection set: an identifier is a function code plus the node's id (1 to 127).
//!
//! | object | COB-ID |
//! |---|---|
//! | NMT | 0x000 |
//! | SYNC | 0x080 |
//! | EMCY | 0x080 + node |
//! | TPDO1..4 | 0x180, 0x280, 0x380, 0x480 + node |
//! | RPDO1..4 | 0x200, 0x300, 0x400, 0x500 + node |
//! | SDO, server to client | 0x580 + node |
//! | SDO, client to server | 0x600 + node |
//! | heartbeat | 0x700 + node |

/// Largest 11-bit identifier.
pub const MAX_ID: u16 = 0x7ff;

/// A CAN frame with an 11-bit identifier.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CanFrame {
    id: u16,
    len: u8,
    data: [u8; 8],
}

/// A frame that cannot be made.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum FrameError {
    /// An identifier beyond 11 bits.
    #[error("CAN identifier 0x{0:x}: at most 0x7ff (11 bits)")]
    Id(u16),
    /// More than eight data bytes.
    #[error("{0} data bytes: a classic CAN frame has at most 8")]
    Length(usize),
    /// A node id outside 1 to 127.
    #[error("node {0}: CANopen nodes are 1 to 127")]
    Node(u8),
}

impl CanFrame {
    /// A frame of `data` with identifier `id`.
    pub fn new(id: u16, data: &[u8]) -> Result<Self, FrameError> {
        if id > MAX_ID {
            return Err(FrameError::Id(id));
        }
        if data.len() > 8 {
            return Err(FrameError::Length(data.len()));
        }
        let mut bytes = [0; 8];
        bytes[..data.len()].copy_from_slice(data);
        Ok(Self { id, len: data.len() as u8, data: bytes })
    }

    /// Its identifier.
    pub fn id(&self) -> u16 {
        self.id
    }

    /// Its data bytes.
    pub fn data(&self) -> &[u8] {
        &self.data[..usize::from(self.len)]
    }
}

/// What a COB-ID carries, with its node where it has one.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CobId {
    /// Network management (to every node).
    Nmt,
    /// The SYNC that clocks the PDOs.
    Sync,
    /// A node's emergency message.
    Emcy(u8),
    /// A node's transmit PDO 1 to 4 (from the node).
    Tpdo(u8, u8),
    /// A node's receive PDO 1 to 4 (to the node).
    Rpdo(u8, u8),
    /// An SDO response (from the node's server).
    SdoResponse(u8),
    /// An SDO request (to the node's server).
    SdoRequest(u8),
    /// A node's heartbeat (its NMT state).
    Heartbeat(u8),
}

fn node(n: u8) -> Result<u16, FrameError> {
    if (1..=127).contains(&n) { Ok(u16::from(n)) } else { Err(FrameError::Node(n)) }
}

impl CobId {
    /// Its 11-bit identifier.
    pub fn id(self) -> Result<u16, FrameError> {
        let pdo = |base: u16, k: u8, n: u8| -> Result<u16, FrameError> {
            if !(1..=4).contains(&k) {
                return Err(FrameError::Id(base));
            }
            Ok(base + 0x100 * u16::from(k - 1) + node(n)?)
        };
        Ok(match self {
            CobId::Nmt => 0x000,
            CobId::Sync => 0x080,
            CobId::Emcy(n) => 0x080 + node(n)?,
            CobId::Tpdo(k, n) => pdo(0x180, k, n)?,
            CobId::Rpdo(k, n) => pdo(0x200, k, n)?,
            CobId::SdoResponse(n) => 0x580 + node(n)?,
            CobId::SdoRequest(n) => 0x600 + node(n)?,
            CobId::Heartbeat(n) => 0x700 + node(n)?,
        })
    }

    /// What an identifier carries (None: not in the pre-defined connection set).
    pub fn of(id: u16) -> Option<Self> {
        let (function, n) = (id & 0x780, (id & 0x7f) as u8);
        match (function, n) {
            (0x000, 0) => Some(CobId::Nmt),
            (0x080, 0) => Some(CobId::Sync),
            (_, 0) => None,
            (0x080, n) => Some(CobId::Emcy(n)),
            (0x180 | 0x280 | 0x380 | 0x480, n) => {
                Some(CobId::Tpdo(((function - 0x180) / 0x100 + 1) as u8, n))
            }
            (0x200 | 0x300 | 0x400 | 0x500, n) => {
                Some(CobId::Rpdo(((function - 0x200) / 0x100 + 1) as u8, n))
            }
            (0x580, n) => Some(CobId::SdoResponse(n)),
            (0x600, n) => Some(CobId::SdoRequest(n)),
            (0x700, n) => Some(CobId::Heartbeat(n)),
            _ => None,
        }
    }

    /// A frame of `data` to or from this object.
    pub fn frame(self, data: &[u8]) -> Result<CanFrame, FrameError> {
        CanFrame::new(self.id()?, data)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every object of the pre-defined connection set maps to its identifier and back.
    #[test]
    fn cob_ids_are_the_predefined_connection_set() {
        let cases = [
            (CobId::Nmt, 0x000),
            (CobId::Sync, 0x080),
            (CobId::Emcy(5), 0x085),
            (CobId::Tpdo(1, 5), 0x185),
            (CobId::Tpdo(4, 127), 0x4ff),
            (CobId::Rpdo(1, 5), 0x205),
            (CobId::Rpdo(2, 1), 0x301),
            (CobId::SdoResponse(5), 0x585),
            (CobId::SdoRequest(5), 0x605),
            (CobId::Heartbeat(5), 0x705),
        ];
        for (cob, id) in cases {
            assert_eq!(cob.id(), Ok(id), "{cob:?}");
            assert_eq!(CobId::of(id), Some(cob), "0x{id:03x}");
        }
        assert_eq!(CobId::Emcy(0).id(), Err(FrameError::Node(0)));
        assert_eq!(CobId::Heartbeat(128).id(), Err(FrameError::Node(128)));
        assert_eq!(CanFrame::new(0x800, &[]), Err(FrameError::Id(0x800)));
        assert_eq!(CanFrame::new(1, &[0; 9]), Err(FrameError::Length(9)));
        assert_eq!(CanFrame::new(0x605, &[1, 2, 3]).map(|f| f.data().to_vec()), Ok(vec![1, 2, 3]));
    }
}

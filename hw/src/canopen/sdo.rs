//! Expedited SDO transfers: one object (an index and a subindex of the node's object dictionary) of up
//! to four bytes read or written in one request and one response of eight bytes.
//!
//! | byte | request, write (download) | request, read (upload) | response |
//! |---|---|---|---|
//! | 0 | 0x23, 0x27, 0x2B, 0x2F (4, 3, 2, 1 bytes) | 0x40 | 0x60 written; 0x43, 0x47, 0x4B, 0x4F read (4, 3, 2, 1 bytes); 0x80 abort |
//! | 1..3 | index (little-endian), subindex | the same | the same |
//! | 4..8 | the value, little-endian | 0 | the value read, or the abort code |

use super::frame::{CanFrame, CobId, FrameError};

/// An object of the dictionary.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Object {
    /// Its index.
    pub index: u16,
    /// Its subindex.
    pub subindex: u8,
}

/// An SDO request from the client.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SdoRequest {
    /// Write `len` bytes (1 to 4) of `value`.
    Write {
        /// The object.
        object: Object,
        /// The value, its low bytes used.
        value: u32,
        /// How many bytes.
        len: u8,
    },
    /// Read the object.
    Read {
        /// The object.
        object: Object,
    },
}

/// An SDO response from the server.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SdoResponse {
    /// The write was done.
    Written {
        /// The object.
        object: Object,
    },
    /// The value read.
    Value {
        /// The object.
        object: Object,
        /// The value.
        value: u32,
        /// Its length in bytes (1 to 4).
        len: u8,
    },
    /// The transfer was refused.
    Abort {
        /// The object.
        object: Object,
        /// Why (CiA 301's abort code).
        code: u32,
    },
}

/// A frame that is not an expedited SDO of this kind.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum SdoError {
    /// Not eight bytes.
    #[error("an SDO frame has 8 bytes, not {0}")]
    Length(usize),
    /// A command byte this client does not use (segmented or block transfers).
    #[error("SDO command byte 0x{0:02x}: not an expedited read, write, their answers or an abort")]
    Command(u8),
    /// A write of no bytes or more than four.
    #[error("an expedited SDO writes 1 to 4 bytes, not {0}")]
    Size(u8),
    /// The frame could not be made.
    #[error(transparent)]
    Frame(#[from] FrameError),
}

/// What an abort code means (CiA 301), for messages.
pub fn abort_reason(code: u32) -> &'static str {
    match code {
        0x0503_0000 => "toggle bit not alternated",
        0x0504_0000 => "SDO protocol timed out",
        0x0504_0001 => "command specifier not valid or unknown",
        0x0601_0000 => "unsupported access to an object",
        0x0601_0001 => "attempt to read a write-only object",
        0x0601_0002 => "attempt to write a read-only object",
        0x0602_0000 => "object does not exist in the object dictionary",
        0x0604_0041 => "object cannot be mapped to the PDO",
        0x0607_0010 => "data type does not match, length of service parameter does not match",
        0x0609_0011 => "subindex does not exist",
        0x0609_0030 => "invalid value for parameter",
        0x0609_0031 => "value of parameter written too high",
        0x0609_0032 => "value of parameter written too low",
        0x0800_0000 => "general error",
        0x0800_0020 => "data cannot be transferred or stored to the application",
        0x0800_0022 => "data cannot be transferred because of the present device state",
        _ => "an abort code CiA 301 does not list",
    }
}

/// A transfer's eight bytes as its command byte, its object and its data (little-endian).
fn split(bytes: &[u8]) -> Result<(u8, Object, u32), SdoError> {
    let &[command, index_lo, index_hi, subindex, d0, d1, d2, d3] = bytes else {
        return Err(SdoError::Length(bytes.len()));
    };
    let object = Object { index: u16::from_le_bytes([index_lo, index_hi]), subindex };
    Ok((command, object, u32::from_le_bytes([d0, d1, d2, d3])))
}

/// The data length an expedited transfer's command byte gives (its bits 2 and 3: the bytes unused).
fn expedited_len(command: u8) -> u8 {
    4 - ((command >> 2) & 0x3)
}

fn with_header(command: u8, object: Object, value: u32) -> [u8; 8] {
    let mut out = [0; 8];
    out[0] = command;
    out[1..3].copy_from_slice(&object.index.to_le_bytes());
    out[3] = object.subindex;
    out[4..8].copy_from_slice(&value.to_le_bytes());
    out
}

fn mask(value: u32, len: u8) -> u32 {
    if len >= 4 { value } else { value & ((1u32 << (8 * u32::from(len))) - 1) }
}

impl SdoRequest {
    /// Its eight bytes.
    pub fn encode(&self) -> Result<[u8; 8], SdoError> {
        Ok(match *self {
            SdoRequest::Write { object, value, len } => {
                if !(1..=4).contains(&len) {
                    return Err(SdoError::Size(len));
                }
                with_header(0x23 | ((4 - len) << 2), object, mask(value, len))
            }
            SdoRequest::Read { object } => with_header(0x40, object, 0),
        })
    }

    /// The frame to node `node`'s server.
    pub fn frame(&self, node: u8) -> Result<CanFrame, SdoError> {
        Ok(CobId::SdoRequest(node).frame(&self.encode()?)?)
    }

    /// A request from its bytes.
    pub fn decode(bytes: &[u8]) -> Result<Self, SdoError> {
        let (command, object, value) = split(bytes)?;
        match command {
            0x40 => Ok(SdoRequest::Read { object }),
            c @ (0x23 | 0x27 | 0x2B | 0x2F) => {
                let len = expedited_len(c);
                Ok(SdoRequest::Write { object, value: mask(value, len), len })
            }
            c => Err(SdoError::Command(c)),
        }
    }
}

impl SdoResponse {
    /// Its eight bytes.
    pub fn encode(&self) -> Result<[u8; 8], SdoError> {
        Ok(match *self {
            SdoResponse::Written { object } => with_header(0x60, object, 0),
            SdoResponse::Value { object, value, len } => {
                if !(1..=4).contains(&len) {
                    return Err(SdoError::Size(len));
                }
                with_header(0x43 | ((4 - len) << 2), object, mask(value, len))
            }
            SdoResponse::Abort { object, code } => with_header(0x80, object, code),
        })
    }

    /// The frame from node `node`'s server.
    pub fn frame(&self, node: u8) -> Result<CanFrame, SdoError> {
        Ok(CobId::SdoResponse(node).frame(&self.encode()?)?)
    }

    /// A response from its bytes.
    pub fn decode(bytes: &[u8]) -> Result<Self, SdoError> {
        let (command, object, value) = split(bytes)?;
        match command {
            0x60 => Ok(SdoResponse::Written { object }),
            0x80 => Ok(SdoResponse::Abort { object, code: value }),
            c @ (0x43 | 0x47 | 0x4B | 0x4F) => {
                let len = expedited_len(c);
                Ok(SdoResponse::Value { object, value: mask(value, len), len })
            }
            c => Err(SdoError::Command(c)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The command bytes and little-endian fields of CiA 301: writing the mode of operation (0x6060,
    /// one byte) and reading the statusword (0x6041); an abort and its reason.
    #[test]
    fn expedited_transfers_are_laid_out_as_cia_301_says() {
        let mode = Object { index: 0x6060, subindex: 0 };
        let write = SdoRequest::Write { object: mode, value: 8, len: 1 };
        assert_eq!(write.encode(), Ok([0x2F, 0x60, 0x60, 0x00, 8, 0, 0, 0]));
        assert_eq!(SdoRequest::decode(&write.encode().unwrap()), Ok(write));
        let four =
            SdoRequest::Write { object: Object { index: 0x607A, subindex: 0 }, value: 0x1234_5678, len: 4 };
        assert_eq!(four.encode(), Ok([0x23, 0x7A, 0x60, 0x00, 0x78, 0x56, 0x34, 0x12]));
        let status = Object { index: 0x6041, subindex: 0 };
        let read = SdoRequest::Read { object: status };
        assert_eq!(read.encode(), Ok([0x40, 0x41, 0x60, 0x00, 0, 0, 0, 0]));
        let value = SdoResponse::Value { object: status, value: 0x0237, len: 2 };
        assert_eq!(value.encode(), Ok([0x4B, 0x41, 0x60, 0x00, 0x37, 0x02, 0, 0]));
        assert_eq!(SdoResponse::decode(&value.encode().unwrap()), Ok(value));
        let abort = SdoResponse::Abort { object: mode, code: 0x0609_0030 };
        assert_eq!(abort.encode(), Ok([0x80, 0x60, 0x60, 0x00, 0x30, 0x00, 0x09, 0x06]));
        assert_eq!(SdoResponse::decode(&abort.encode().unwrap()), Ok(abort));
        assert_eq!(SdoResponse::Value { object: status, value: 1, len: 0 }.encode(), Err(SdoError::Size(0)));
        assert_eq!(SdoResponse::decode(&[0x4B, 0x41, 0x60]), Err(SdoError::Length(3)));
        assert_eq!(abort_reason(0x0609_0030), "invalid value for parameter");
        assert_eq!(SdoRequest::Write { object: mode, value: 1, len: 5 }.encode(), Err(SdoError::Size(5)));
        assert_eq!(SdoRequest::decode(&[0x21, 0, 0, 0, 0, 0, 0, 0]), Err(SdoError::Command(0x21)));
        assert_eq!(read.frame(3).map(|f| f.id()), Ok(0x603));
    }
}

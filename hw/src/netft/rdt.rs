//! The RDT wire format (all fields big-endian):
//!
//! | request, 8 bytes | |
//! |---|---|
//! | 0..2 | header, always 0x1234 |
//! | 2..4 | command: 0x0000 stop streaming, 0x0002 start real-time streaming, 0x0042 set the software bias |
//! | 4..8 | sample count: records to send, 0 for an endless stream |
//!
//! | record, 36 bytes | |
//! |---|---|
//! | 0..4 | RDT sequence: one more for each record the box sends (a gap is a lost record) |
//! | 4..8 | F/T sequence: the box's own sample counter |
//! | 8..12 | status: 0 when healthy, else the box's error bits |
//! | 12..36 | Fx, Fy, Fz, Tx, Ty, Tz as signed counts (newtons and newton-metres times the calibration's counts per force and per torque) |

/// The request's first two bytes.
pub const HEADER: u16 = 0x1234;
/// Bytes in a request.
pub const REQUEST_LEN: usize = 8;
/// Bytes in a record.
pub const RECORD_LEN: usize = 36;

/// What a request asks the box to do.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RdtCommand {
    /// Stop streaming (0x0000).
    Stop,
    /// Start real-time streaming (0x0002).
    StartRealTime,
    /// Take the present reading as zero (0x0042).
    SetBias,
}

impl RdtCommand {
    /// The command's code on the wire.
    pub fn code(self) -> u16 {
        match self {
            RdtCommand::Stop => 0x0000,
            RdtCommand::StartRealTime => 0x0002,
            RdtCommand::SetBias => 0x0042,
        }
    }

    /// The command of a code, if it is one of these.
    pub fn from_code(code: u16) -> Option<Self> {
        match code {
            0x0000 => Some(RdtCommand::Stop),
            0x0002 => Some(RdtCommand::StartRealTime),
            0x0042 => Some(RdtCommand::SetBias),
            _ => None,
        }
    }
}

/// A request to the box.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Request {
    /// What to do.
    pub command: RdtCommand,
    /// Records to send (0: until stopped).
    pub sample_count: u32,
}

/// One record from the box.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Record {
    /// The record's number in the stream.
    pub rdt_sequence: u32,
    /// The box's sample counter.
    pub ft_sequence: u32,
    /// 0 when healthy.
    pub status: u32,
    /// Fx, Fy, Fz, Tx, Ty, Tz in counts.
    pub counts: [i32; 6],
}

/// A datagram that is not a request or a record.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum RdtError {
    /// Of the wrong length.
    #[error("{what}: {len} bytes, an RDT {what} has {expected}")]
    Length {
        /// Request or record.
        what: &'static str,
        /// Its length.
        len: usize,
        /// The right length.
        expected: usize,
    },
    /// A request whose header is not 0x1234.
    #[error("request: header 0x{0:04x}, not 0x1234")]
    Header(u16),
    /// A request of a command this does not know.
    #[error("request: command 0x{0:04x} (known: 0x0000 stop, 0x0002 start real-time, 0x0042 set bias)")]
    Command(u16),
}

impl Request {
    /// The request's bytes.
    pub fn encode(&self) -> [u8; REQUEST_LEN] {
        let mut out = [0; REQUEST_LEN];
        out[0..2].copy_from_slice(&HEADER.to_be_bytes());
        out[2..4].copy_from_slice(&self.command.code().to_be_bytes());
        out[4..8].copy_from_slice(&self.sample_count.to_be_bytes());
        out
    }

    /// A request from its bytes.
    pub fn decode(bytes: &[u8]) -> Result<Self, RdtError> {
        if bytes.len() != REQUEST_LEN {
            return Err(RdtError::Length { what: "request", len: bytes.len(), expected: REQUEST_LEN });
        }
        let header = u16::from_be_bytes([bytes[0], bytes[1]]);
        if header != HEADER {
            return Err(RdtError::Header(header));
        }
        let code = u16::from_be_bytes([bytes[2], bytes[3]]);
        let command = RdtCommand::from_code(code).ok_or(RdtError::Command(code))?;
        let sample_count = u32::from_be_bytes([bytes[4], bytes[5], bytes[6], bytes[7]]);
        Ok(Self { command, sample_count })
    }
}

impl Record {
    /// The record's bytes.
    pub fn encode(&self) -> [u8; RECORD_LEN] {
        let mut out = [0; RECORD_LEN];
        out[0..4].copy_from_slice(&self.rdt_sequence.to_be_bytes());
        out[4..8].copy_from_slice(&self.ft_sequence.to_be_bytes());
        out[8..12].copy_from_slice(&self.status.to_be_bytes());
        for (k, c) in self.counts.iter().enumerate() {
            out[12 + 4 * k..16 + 4 * k].copy_from_slice(&c.to_be_bytes());
        }
        out
    }

    /// A record from its bytes.
    pub fn decode(bytes: &[u8]) -> Result<Self, RdtError> {
        if bytes.len() != RECORD_LEN {
            return Err(RdtError::Length { what: "record", len: bytes.len(), expected: RECORD_LEN });
        }
        let word = |at: usize| [bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]];
        Ok(Self {
            rdt_sequence: u32::from_be_bytes(word(0)),
            ft_sequence: u32::from_be_bytes(word(4)),
            status: u32::from_be_bytes(word(8)),
            counts: std::array::from_fn(|k| i32::from_be_bytes(word(12 + 4 * k))),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The bytes are the manual's: a start request, and a record of known fields.
    #[test]
    fn requests_and_records_are_laid_out_as_the_box_sends_them() {
        let start = Request { command: RdtCommand::StartRealTime, sample_count: 0 };
        assert_eq!(start.encode(), [0x12, 0x34, 0x00, 0x02, 0, 0, 0, 0]);
        assert_eq!(Request::decode(&start.encode()), Ok(start));
        let bias = Request { command: RdtCommand::SetBias, sample_count: 7 };
        assert_eq!(bias.encode(), [0x12, 0x34, 0x00, 0x42, 0, 0, 0, 7]);
        let record = Record {
            rdt_sequence: 1,
            ft_sequence: 0x0102_0304,
            status: 0,
            counts: [-1, 2, 1_000_000, 0, 0, -3],
        };
        let bytes = record.encode();
        assert_eq!(&bytes[0..12], &[0, 0, 0, 1, 1, 2, 3, 4, 0, 0, 0, 0]);
        assert_eq!(&bytes[12..16], &[0xff, 0xff, 0xff, 0xff]);
        assert_eq!(&bytes[20..24], &1_000_000i32.to_be_bytes());
        assert_eq!(Record::decode(&bytes), Ok(record));
        assert_eq!(
            Record::decode(&bytes[..35]),
            Err(RdtError::Length { what: "record", len: 35, expected: 36 })
        );
        assert_eq!(Request::decode(&[0x12, 0x35, 0, 2, 0, 0, 0, 0]), Err(RdtError::Header(0x1235)));
        assert_eq!(Request::decode(&[0x12, 0x34, 0, 9, 0, 0, 0, 0]), Err(RdtError::Command(9)));
    }
}

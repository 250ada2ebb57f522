//! Bytes on the wire: encoding and decoding of both MXT packet layouts, little-endian, packed as the C
//! struct (the original header's `long` is 32 bits). Allocation-free; decoding never panics, whatever
//! the bytes, and names the field and offset of anything it refuses.
//!
//! | offset | size | field |
//! |---|---|---|
//! | 0 | 2 | Command |
//! | 2 | 2 | SendType |
//! | 4 | 2 | RecvType |
//! | 6 | 2 | reserve |
//! | 8 | 40 | dat |
//! | 48 | 2 x 5 | SendIOType, RecvIOType, BitTop, BitMask, IoData |
//! | 58 | 2 | TCount |
//! | 60 | 4 | CCount (end of the pre-H7 layout: 64 bytes) |
//! | 64, 108, 152 | 2 + 2 + 40 each | RecvType1..3, reserve1..3, dat1..3 (H7: 196 bytes) |
//!
//! The 40-byte union: POSE is x, y, z, a, b, c, l1, l2 (f32) and sflg1, sflg2 (u32); JOINT is j1..j8
//! (f32) then 8 zero bytes; PULSE and the currents are eight i32 then 8 zero bytes.

use super::packet::{Command, Data, DataType, Io, Layout, Monitor, Packet, Pose};

/// Offset of `dat`.
pub const DAT: usize = 8;
/// Size of a data union.
pub const DAT_LEN: usize = 40;
/// Offsets of RecvType1..3; each slot's data follows 4 bytes later.
pub const MONITOR_SLOTS: [usize; 3] = [64, 108, 152];
/// The largest packet (H7).
pub const MAX_LEN: usize = 196;

/// Bytes a receive buffer holds: the largest UDP datagram, so that an oversized one is measured
/// whole (and refused by its real size) rather than cut to the buffer.
pub const MAX_DATAGRAM: usize = 65_536;

/// Why bytes are not an MXT packet.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum PacketError {
    /// The datagram's size is not the layout's.
    #[error("packet is {got} bytes; the {} layout has {expected}{}", layout.as_str(), length_hint(*layout, *got))]
    Length {
        /// The layout expected.
        layout: Layout,
        /// Its size.
        expected: usize,
        /// The datagram's size.
        got: usize,
    },
    /// A field holds a value the protocol does not define.
    #[error("{field} (offset {offset}) is {value}: expected {expected}")]
    Field {
        /// The field's name.
        field: &'static str,
        /// Its byte offset.
        offset: usize,
        /// What it holds.
        value: u16,
        /// What it may hold.
        expected: &'static str,
    },
    /// A float in a data union is NaN or infinite.
    #[error("{union}.{field} (offset {offset}) is not a finite number")]
    NotFinite {
        /// The union ("dat", "dat1", ...).
        union: &'static str,
        /// The field ("j3", "x", ...).
        field: &'static str,
        /// Its byte offset.
        offset: usize,
    },
}

fn length_hint(layout: Layout, got: usize) -> String {
    let other = match layout {
        Layout::H7 => Layout::PreH7,
        Layout::PreH7 => Layout::H7,
    };
    if got == other.packet_len() {
        format!(
            " (it is the {} layout's size: does the controller's software match the configured layout?)",
            other.as_str()
        )
    } else {
        String::new()
    }
}

fn put_u16(buf: &mut [u8], at: usize, v: u16) {
    buf[at..at + 2].copy_from_slice(&v.to_le_bytes());
}

fn put_u32(buf: &mut [u8], at: usize, v: u32) {
    buf[at..at + 4].copy_from_slice(&v.to_le_bytes());
}

fn get_u16(bytes: &[u8], at: usize) -> u16 {
    u16::from_le_bytes([bytes[at], bytes[at + 1]])
}

fn get_u32(bytes: &[u8], at: usize) -> u32 {
    u32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]])
}

fn encode_data(data: &Data, slot: &mut [u8]) {
    slot.fill(0);
    match data {
        Data::None => {}
        Data::Pose(p) => {
            let floats = [
                p.xyz_mm[0],
                p.xyz_mm[1],
                p.xyz_mm[2],
                p.abc_rad[0],
                p.abc_rad[1],
                p.abc_rad[2],
                p.l1_l2[0],
                p.l1_l2[1],
            ];
            for (i, f) in floats.iter().enumerate() {
                put_u32(slot, 4 * i, f.to_bits());
            }
            put_u32(slot, 32, p.flags[0]);
            put_u32(slot, 36, p.flags[1]);
        }
        Data::Joint(j) => {
            for (i, f) in j.iter().enumerate() {
                put_u32(slot, 4 * i, f.to_bits());
            }
        }
        Data::Pulse(v) | Data::Current(v) => {
            for (i, x) in v.iter().enumerate() {
                put_u32(slot, 4 * i, *x as u32);
            }
        }
    }
}

const JOINT_NAMES: [&str; 8] = ["j1", "j2", "j3", "j4", "j5", "j6", "j7", "j8"];
const POSE_NAMES: [&str; 8] = ["x", "y", "z", "a", "b", "c", "l1", "l2"];

fn floats(
    slot: &[u8],
    union: &'static str,
    base: usize,
    names: &[&'static str; 8],
) -> Result<[f32; 8], PacketError> {
    let mut out = [0.0_f32; 8];
    for (i, v) in out.iter_mut().enumerate() {
        *v = f32::from_bits(get_u32(slot, 4 * i));
        if !v.is_finite() {
            return Err(PacketError::NotFinite { union, field: names[i], offset: base + 4 * i });
        }
    }
    Ok(out)
}

fn decode_data(kind: DataType, slot: &[u8], union: &'static str, base: usize) -> Result<Data, PacketError> {
    let ints = || std::array::from_fn(|i| get_u32(slot, 4 * i) as i32);
    Ok(match kind {
        DataType::Null => Data::None,
        DataType::Pose | DataType::FilteredPose | DataType::FeedbackPose => {
            let f = floats(slot, union, base, &POSE_NAMES)?;
            Data::Pose(Pose {
                xyz_mm: [f[0], f[1], f[2]],
                abc_rad: [f[3], f[4], f[5]],
                l1_l2: [f[6], f[7]],
                flags: [get_u32(slot, 32), get_u32(slot, 36)],
            })
        }
        DataType::Joint | DataType::FilteredJoint | DataType::FeedbackJoint => {
            Data::Joint(floats(slot, union, base, &JOINT_NAMES)?)
        }
        DataType::Pulse | DataType::FilteredPulse | DataType::FeedbackPulse => Data::Pulse(ints()),
        DataType::CommandCurrent | DataType::FeedbackCurrent => Data::Current(ints()),
    })
}

const DATA_TYPES: &str = "a data type 0..=11";
const IO_TYPES: &str = "0 none, 1 output or 2 input";

fn data_type(bytes: &[u8], field: &'static str, offset: usize) -> Result<DataType, PacketError> {
    let value = get_u16(bytes, offset);
    DataType::from_code(value).ok_or(PacketError::Field { field, offset, value, expected: DATA_TYPES })
}

fn io_type(bytes: &[u8], field: &'static str, offset: usize) -> Result<u16, PacketError> {
    let value = get_u16(bytes, offset);
    if value <= 2 { Ok(value) } else { Err(PacketError::Field { field, offset, value, expected: IO_TYPES }) }
}

impl Packet {
    /// Writes the packet into `buf` in `layout` and returns its length (64 or 196). Reserve fields are
    /// zero; the pre-H7 layout leaves the monitor slots out.
    pub fn encode(&self, layout: Layout, buf: &mut [u8; MAX_LEN]) -> usize {
        let len = layout.packet_len();
        buf[..len].fill(0);
        put_u16(buf, 0, self.command.code());
        put_u16(buf, 2, self.send_type.code());
        put_u16(buf, 4, self.recv_type.code());
        encode_data(&self.data, &mut buf[DAT..DAT + DAT_LEN]);
        put_u16(buf, 48, self.io.send_type);
        put_u16(buf, 50, self.io.recv_type);
        put_u16(buf, 52, self.io.bit_top);
        put_u16(buf, 54, self.io.bit_mask);
        put_u16(buf, 56, self.io.data);
        put_u16(buf, 58, self.t_count);
        put_u32(buf, 60, self.c_count);
        if layout == Layout::H7 {
            for (monitor, &at) in self.monitors.iter().zip(&MONITOR_SLOTS) {
                put_u16(buf, at, monitor.kind.code());
                encode_data(&monitor.data, &mut buf[at + 4..at + 4 + DAT_LEN]);
            }
        }
        len
    }

    /// Reads a packet of `layout` from a datagram.
    pub fn decode(bytes: &[u8], layout: Layout) -> Result<Self, PacketError> {
        if bytes.len() != layout.packet_len() {
            return Err(PacketError::Length { layout, expected: layout.packet_len(), got: bytes.len() });
        }
        let code = get_u16(bytes, 0);
        let command = Command::from_code(code).ok_or(PacketError::Field {
            field: "Command",
            offset: 0,
            value: code,
            expected: "0 NULL, 1 MOVE or 255 END",
        })?;
        let send_type = data_type(bytes, "SendType", 2)?;
        let recv_type = data_type(bytes, "RecvType", 4)?;
        let data = decode_data(send_type, &bytes[DAT..DAT + DAT_LEN], "dat", DAT)?;
        let io = Io {
            send_type: io_type(bytes, "SendIOType", 48)?,
            recv_type: io_type(bytes, "RecvIOType", 50)?,
            bit_top: get_u16(bytes, 52),
            bit_mask: get_u16(bytes, 54),
            data: get_u16(bytes, 56),
        };
        let mut monitors = [Monitor::EMPTY; 3];
        if layout == Layout::H7 {
            const FIELDS: [(&str, &str); 3] =
                [("RecvType1", "dat1"), ("RecvType2", "dat2"), ("RecvType3", "dat3")];
            for ((slot, &at), (field, union)) in monitors.iter_mut().zip(&MONITOR_SLOTS).zip(FIELDS) {
                let kind = data_type(bytes, field, at)?;
                let data = decode_data(kind, &bytes[at + 4..at + 4 + DAT_LEN], union, at + 4)?;
                *slot = Monitor { kind, data };
            }
        }
        Ok(Packet {
            command,
            send_type,
            recv_type,
            data,
            io,
            t_count: get_u16(bytes, 58),
            c_count: get_u32(bytes, 60),
            monitors,
        })
    }
}

//! The MXT packet decoder on random datagrams and on valid packets' encodings with bytes, fields,
//! floats or the length changed, in both layouts.

use proptest::collection::vec;
use proptest::prelude::*;
use proptest::sample::{Index, select};

use knotlab_hw::melfa::codec::{DAT, MAX_LEN, MONITOR_SLOTS};
use knotlab_hw::melfa::{Command, Data, DataType, Io, Layout, Monitor, Packet, Pose};

use super::{cases, fuzz, isolated, outcome};

/// A layout.
fn layout() -> impl Strategy<Value = Layout> {
    select(&[Layout::H7, Layout::PreH7][..])
}

/// A finite f32.
fn finite() -> impl Strategy<Value = f32> {
    prop_oneof![-1e4f32..1e4f32, select(&[0.0, -0.0, f32::MAX, f32::MIN, f32::MIN_POSITIVE, 1e-45][..])]
}

/// Data of the type `kind` says.
fn data(kind: DataType) -> BoxedStrategy<Data> {
    match kind {
        DataType::Null => Just(Data::None).boxed(),
        DataType::Pose | DataType::FilteredPose | DataType::FeedbackPose => (
            [finite(), finite(), finite()],
            [finite(), finite(), finite()],
            [finite(), finite()],
            any::<[u32; 2]>(),
        )
            .prop_map(|(xyz_mm, abc_rad, l1_l2, flags)| Data::Pose(Pose { xyz_mm, abc_rad, l1_l2, flags }))
            .boxed(),
        DataType::Joint | DataType::FilteredJoint | DataType::FeedbackJoint => {
            vec(finite(), 8).prop_map(|j| Data::Joint(std::array::from_fn(|i| j[i]))).boxed()
        }
        DataType::Pulse | DataType::FilteredPulse | DataType::FeedbackPulse => {
            any::<[i32; 8]>().prop_map(Data::Pulse).boxed()
        }
        DataType::CommandCurrent | DataType::FeedbackCurrent => {
            any::<[i32; 8]>().prop_map(Data::Current).boxed()
        }
    }
}

/// A data type and data of that type.
fn typed_data() -> impl Strategy<Value = (DataType, Data)> {
    (0u16..=11).prop_flat_map(|code| {
        let kind = DataType::from_code(code).expect("codes 0..=11 are data types");
        (Just(kind), data(kind))
    })
}

/// A valid packet.
fn packet() -> impl Strategy<Value = Packet> {
    let command = select(&[Command::Null, Command::Move, Command::End][..]);
    let recv = (0u16..=11).prop_map(|c| DataType::from_code(c).expect("a data type"));
    let io = (0u16..=2, 0u16..=2, any::<u16>(), any::<u16>(), any::<u16>()).prop_map(
        |(send_type, recv_type, bit_top, bit_mask, data)| Io {
            send_type,
            recv_type,
            bit_top,
            bit_mask,
            data,
        },
    );
    let monitor = || typed_data().prop_map(|(kind, data)| Monitor { kind, data });
    (command, typed_data(), recv, io, any::<u16>(), any::<u32>(), [monitor(), monitor(), monitor()]).prop_map(
        |(command, (send_type, data), recv_type, io, t_count, c_count, monitors)| Packet {
            command,
            send_type,
            recv_type,
            data,
            io,
            t_count,
            c_count,
            monitors,
        },
    )
}

/// A change to a datagram's bytes.
#[derive(Debug, Clone)]
enum ByteMutation {
    /// One byte set.
    Byte(Index, u8),
    /// One bit flipped.
    Bit(Index, u8),
    /// A 16-bit field (command, a type code, an I/O type) set, little-endian.
    Field(usize, u16),
    /// A float of a data union set to these bits (NaN, infinities, subnormal, any).
    Float(usize, Index, u32),
    /// The datagram cut at a byte.
    Truncate(Index),
    /// Bytes appended.
    Extend(Vec<u8>),
}

fn byte_mutation() -> impl Strategy<Value = ByteMutation> {
    let fields = [0usize, 2, 4, 48, 50, MONITOR_SLOTS[0], MONITOR_SLOTS[1], MONITOR_SLOTS[2]];
    let unions = [DAT, MONITOR_SLOTS[0] + 4, MONITOR_SLOTS[1] + 4, MONITOR_SLOTS[2] + 4];
    let special =
        vec![f32::NAN.to_bits(), f32::INFINITY.to_bits(), f32::NEG_INFINITY.to_bits(), 0x7fc0_0001, !0, 1];
    let bits = prop_oneof![select(special), any::<u32>()];
    prop_oneof![
        3 => (any::<Index>(), any::<u8>()).prop_map(|(i, b)| ByteMutation::Byte(i, b)),
        2 => (any::<Index>(), 0u8..8).prop_map(|(i, b)| ByteMutation::Bit(i, b)),
        3 => (select(fields.to_vec()), prop_oneof![0u16..=12, Just(255), any::<u16>()])
            .prop_map(|(at, v)| ByteMutation::Field(at, v)),
        3 => (select(unions.to_vec()), any::<Index>(), bits).prop_map(|(at, k, b)| ByteMutation::Float(at, k, b)),
        1 => any::<Index>().prop_map(ByteMutation::Truncate),
        1 => vec(any::<u8>(), 1..200).prop_map(ByteMutation::Extend),
    ]
}

impl ByteMutation {
    fn apply(&self, bytes: &mut Vec<u8>) {
        match self {
            ByteMutation::Byte(i, b) if !bytes.is_empty() => {
                let at = i.index(bytes.len());
                bytes[at] = *b;
            }
            ByteMutation::Bit(i, bit) if !bytes.is_empty() => {
                let at = i.index(bytes.len());
                bytes[at] ^= 1 << bit;
            }
            ByteMutation::Field(at, v) if at + 2 <= bytes.len() => {
                bytes[*at..at + 2].copy_from_slice(&v.to_le_bytes());
            }
            ByteMutation::Float(union, k, b) => {
                let at = union + 4 * k.index(8);
                if at + 4 <= bytes.len() {
                    bytes[at..at + 4].copy_from_slice(&b.to_le_bytes());
                }
            }
            ByteMutation::Truncate(i) => bytes.truncate(i.index(bytes.len() + 1)),
            ByteMutation::Extend(more) => bytes.extend_from_slice(more),
            _ => {}
        }
    }
}

/// The decoder never panics on a random datagram (any length, biased to the layouts' 64 and 196
/// bytes), and names what it refuses.
#[test]
fn mxt_decoder_survives_random_datagrams() {
    isolated(|| {
        let bytes = prop_oneof![
            vec(any::<u8>(), 0..400),
            vec(any::<u8>(), 64),
            vec(any::<u8>(), 196),
            vec(prop_oneof![Just(0u8), Just(0xff), any::<u8>()], 196),
        ];
        fuzz("mxt/raw", 4 * cases(), (bytes, layout()), |(bytes, layout)| {
            outcome(Packet::decode(bytes, *layout))
        });
    });
}

/// The decoder reads every valid packet's encoding, and never panics on one with bytes, bits, type
/// codes, floats (NaN, infinities) or the length changed; it names what it refuses.
#[test]
fn mxt_decoder_survives_mutated_encodings() {
    isolated(|| {
        fuzz(
            "mxt/mutated",
            4 * cases(),
            (packet(), layout(), vec(byte_mutation(), 0..=3)),
            |(packet, layout, mutations)| {
                let mut buf = [0u8; MAX_LEN];
                let len = packet.encode(*layout, &mut buf);
                let mut bytes = buf[..len].to_vec();
                if mutations.is_empty() {
                    let decoded = Packet::decode(&bytes, *layout);
                    assert!(decoded.is_ok(), "a valid packet's encoding decodes: {decoded:?}");
                }
                mutations.iter().for_each(|m| m.apply(&mut bytes));
                outcome(Packet::decode(&bytes, *layout))
            },
        );
    });
}

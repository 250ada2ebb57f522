//! Byte-exact encoding and decoding of both MXT packet layouts, against bytes written out by hand from
//! the layout table of shared/reference/melfa-mxt.md (little-endian; f32 bit patterns: 0.5 = 3F000000,
//! -1.0 = BF800000, 0.25 = 3E800000, 2.0 = 40000000, -0.125 = BE000000, 1.5 = 3FC00000, 100.0 =
//! 42C80000, -50.0 = C2480000, 300.5 = 43964000, -0.5 = BF000000, 1.0 = 3F800000, 0.75 = 3F400000,
//! -2.5 = C0200000). Malformed packets are refused naming the field; no input panics the decoder.

use knotlab_hw::melfa::codec::MAX_LEN;
use knotlab_hw::melfa::{Command, Data, DataType, Io, Layout, Monitor, Packet, PacketError, Pose};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Bytes from whitespace-separated hex pairs.
fn hex(text: &str) -> Vec<u8> {
    text.split_whitespace().map(|b| u8::from_str_radix(b, 16).expect("a hex byte")).collect()
}

fn encode(packet: &Packet, layout: Layout) -> Vec<u8> {
    let mut buf = [0_u8; MAX_LEN];
    let n = packet.encode(layout, &mut buf);
    buf[..n].to_vec()
}

const ZEROS_40: &str = "00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00
                        00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00";

/// A MOVE command in the H7 layout: joints in dat, every I/O field set, three monitor requests.
fn h7_move_bytes() -> Vec<u8> {
    hex(&format!(
        "01 00  02 00  05 00  00 00
         00 00 00 3F  00 00 80 BF  00 00 80 3E  00 00 00 40  00 00 00 BE  00 00 C0 3F  00 00 00 00  00 00 00 00
         00 00 00 00 00 00 00 00
         01 00  02 00  10 00  FF FF  A5 00  03 00  04 03 02 01
         08 00 00 00 {ZEROS_40}
         04 00 00 00 {ZEROS_40}
         0B 00 00 00 {ZEROS_40}"
    ))
}

fn h7_move_packet() -> Packet {
    Packet {
        command: Command::Move,
        send_type: DataType::Joint,
        recv_type: DataType::FilteredJoint,
        data: Data::Joint([0.5, -1.0, 0.25, 2.0, -0.125, 1.5, 0.0, 0.0]),
        io: Io { send_type: 1, recv_type: 2, bit_top: 16, bit_mask: 0xFFFF, data: 0x00A5 },
        t_count: 3,
        c_count: 0x0102_0304,
        monitors: [
            Monitor { kind: DataType::FeedbackJoint, data: Data::None },
            Monitor { kind: DataType::FilteredPose, data: Data::None },
            Monitor { kind: DataType::FeedbackCurrent, data: Data::None },
        ],
    }
}

/// A MOVE command in the H7 layout encodes to exactly the 196 hand-written bytes of the layout table.
#[test]
fn h7_move_command_encodes_byte_for_byte() {
    let bytes = h7_move_bytes();
    assert_eq!(bytes.len(), 196, "the hand-written packet has the H7 size");
    assert_eq!(encode(&h7_move_packet(), Layout::H7), bytes);
}

/// The hand-written H7 MOVE bytes decode to the packet field by field, monitor requests as zeros of the
/// requested type.
#[test]
fn h7_move_command_decodes_field_by_field() {
    let packet = Packet::decode(&h7_move_bytes(), Layout::H7).unwrap();
    let mut expected = h7_move_packet();
    // Monitor requests carry zero data, which decodes as zeros of the requested type.
    expected.monitors[0].data = Data::Joint([0.0; 8]);
    expected.monitors[1].data = Data::Pose(Pose::default());
    expected.monitors[2].data = Data::Current([0; 8]);
    assert_eq!(packet, expected);
}

/// A reply in the H7 layout: filtered joints in dat, feedback joints, a filtered pose with flags, and
/// motor currents in the slots.
fn h7_reply_bytes() -> Vec<u8> {
    hex(
        "01 00  05 00  05 00  00 00
         00 00 40 3F  00 00 20 C0  00 00 00 00  00 00 80 3F  00 00 00 00  00 00 00 BF  00 00 00 00  00 00 00 00
         00 00 00 00 00 00 00 00
         00 00  00 00  00 00  00 00  00 00  00 00  2A 00 00 00
         08 00 00 00
         00 00 00 3F  00 00 80 BF  00 00 80 3E  00 00 00 40  00 00 00 BE  00 00 C0 3F  00 00 00 00  00 00 00 00
         00 00 00 00 00 00 00 00
         04 00 00 00
         00 00 C8 42  00 00 48 C2  00 40 96 43  00 00 00 3F  00 00 00 BF  00 00 80 3F  00 00 00 00  00 00 00 00
         07 00 00 00  00 00 10 00
         0B 00 00 00
         01 00 00 00  FE FF FF FF  03 00 00 00  00 00 00 00  00 00 00 00  00 00 00 00  00 00 00 00  00 00 00 00
         00 00 00 00 00 00 00 00"
    )
}

fn h7_reply_packet() -> Packet {
    Packet {
        command: Command::Move,
        send_type: DataType::FilteredJoint,
        recv_type: DataType::FilteredJoint,
        data: Data::Joint([0.75, -2.5, 0.0, 1.0, 0.0, -0.5, 0.0, 0.0]),
        io: Io::default(),
        t_count: 0,
        c_count: 42,
        monitors: [
            Monitor {
                kind: DataType::FeedbackJoint,
                data: Data::Joint([0.5, -1.0, 0.25, 2.0, -0.125, 1.5, 0.0, 0.0]),
            },
            Monitor {
                kind: DataType::FilteredPose,
                data: Data::Pose(Pose {
                    xyz_mm: [100.0, -50.0, 300.5],
                    abc_rad: [0.5, -0.5, 1.0],
                    l1_l2: [0.0, 0.0],
                    flags: [7, 0x0010_0000],
                }),
            },
            Monitor { kind: DataType::FeedbackCurrent, data: Data::Current([1, -2, 3, 0, 0, 0, 0, 0]) },
        ],
    }
}

/// An H7 reply with joints, a pose with flags and motor currents decodes to its fields and encodes back
/// to the same bytes, its filtered and feedback joints read out in radians.
#[test]
fn h7_reply_round_trips_byte_for_byte() {
    let bytes = h7_reply_bytes();
    assert_eq!(bytes.len(), 196);
    let packet = Packet::decode(&bytes, Layout::H7).unwrap();
    assert_eq!(packet, h7_reply_packet());
    assert_eq!(encode(&h7_reply_packet(), Layout::H7), bytes);
    assert_eq!(packet.joints_rad().unwrap(), [0.75, -2.5, 0.0, 1.0, 0.0, -0.5]);
    assert_eq!(
        packet.monitor_joints_rad(DataType::FeedbackJoint).unwrap(),
        [0.5, -1.0, 0.25, 2.0, -0.125, 1.5]
    );
}

/// NULL and END in the 64-byte pre-H7 layout.
#[test]
fn pre_h7_null_and_end_encode_byte_for_byte() {
    let null = hex(&format!(
        "00 00  00 00  05 00  00 00
         {ZEROS_40}
         00 00  00 00  00 00  00 00  00 00  00 00  07 00 00 00"
    ));
    assert_eq!(null.len(), 64);
    let packet = Packet::command(Command::Null, DataType::FilteredJoint, [DataType::Null; 3], 7);
    assert_eq!(encode(&packet, Layout::PreH7), null);
    assert_eq!(Packet::decode(&null, Layout::PreH7).unwrap(), packet);

    let end = hex(&format!(
        "FF 00  00 00  00 00  00 00
         {ZEROS_40}
         00 00  00 00  00 00  00 00  00 00  00 00  FF FF FF FF"
    ));
    let packet = Packet::command(Command::End, DataType::Null, [DataType::Null; 3], u32::MAX);
    assert_eq!(encode(&packet, Layout::PreH7), end);
    assert_eq!(Packet::decode(&end, Layout::PreH7).unwrap(), packet);
}

/// The pre-H7 layout is the first 64 bytes of the H7 one: monitor slots are left out on encoding.
#[test]
fn pre_h7_move_is_the_h7_prefix() {
    let h7 = h7_move_bytes();
    let pre = encode(&h7_move_packet(), Layout::PreH7);
    assert_eq!(pre, h7[..64].to_vec());
    let decoded = Packet::decode(&pre, Layout::PreH7).unwrap();
    assert_eq!(decoded.monitors, [Monitor::EMPTY; 3]);
    assert_eq!(decoded.data, h7_move_packet().data);
}

/// A packet of the wrong size is refused with its length and the layout's, a pre-H7 packet decoded as H7
/// hinting at the other layout.
#[test]
fn wrong_sizes_are_refused_with_a_hint_at_the_other_layout() {
    let pre = encode(&h7_move_packet(), Layout::PreH7);
    let error = Packet::decode(&pre, Layout::H7).unwrap_err();
    assert_eq!(error, PacketError::Length { layout: Layout::H7, expected: 196, got: 64 });
    let text = error.to_string();
    assert!(text.contains("64 bytes") && text.contains("pre-h7"), "{text}");
    let error = Packet::decode(&[0_u8; 63], Layout::PreH7).unwrap_err();
    assert!(error.to_string().contains("63 bytes; the pre-h7 layout has 64"), "{error}");
}

/// Unknown command, data-type and I/O-type codes are refused naming the field, its offset and the value,
/// in the header and in a monitor slot alike.
#[test]
fn unknown_codes_are_refused_naming_field_and_offset() {
    let mut bytes = h7_move_bytes();
    bytes[0] = 7;
    let error = Packet::decode(&bytes, Layout::H7).unwrap_err();
    assert!(matches!(error, PacketError::Field { field: "Command", offset: 0, value: 7, .. }), "{error:?}");

    let mut bytes = h7_move_bytes();
    bytes[4] = 12;
    let error = Packet::decode(&bytes, Layout::H7).unwrap_err();
    assert!(matches!(error, PacketError::Field { field: "RecvType", offset: 4, value: 12, .. }), "{error:?}");

    let mut bytes = h7_move_bytes();
    bytes[108] = 99;
    let error = Packet::decode(&bytes, Layout::H7).unwrap_err();
    assert!(
        matches!(error, PacketError::Field { field: "RecvType2", offset: 108, value: 99, .. }),
        "{error:?}"
    );

    let mut bytes = h7_move_bytes();
    bytes[50] = 3;
    let error = Packet::decode(&bytes, Layout::H7).unwrap_err();
    assert!(error.to_string().contains("RecvIOType (offset 50) is 3"), "{error}");
}

/// A NaN joint in a packet's data is refused naming the union, the joint and its offset.
#[test]
fn non_finite_joints_are_refused_naming_the_joint() {
    let mut bytes = h7_move_bytes();
    // j3 at offset 8 + 2 * 4 = 16: a quiet NaN.
    bytes[16..20].copy_from_slice(&[0x00, 0x00, 0xC0, 0x7F]);
    let error = Packet::decode(&bytes, Layout::H7).unwrap_err();
    assert_eq!(error, PacketError::NotFinite { union: "dat", field: "j3", offset: 16 });
    assert!(error.to_string().contains("dat.j3 (offset 16)"), "{error}");
}

/// Random bytes of any plausible or implausible size and codes never panic the decoder, in either layout.
#[test]
fn random_bytes_never_panic_the_decoder() {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let mut decoded = 0;
    for _ in 0..20_000 {
        let len = [63, 64, 65, 195, 196, 197, 0, 1][rng.random_range(0..8)];
        let mut bytes: Vec<u8> = (0..len).map(|_| rng.random()).collect();
        // Plausible codes half the time, so decoding gets past the type fields into the data.
        if len >= 64 && rng.random_bool(0.5) {
            bytes[0] = [0, 1, 255][rng.random_range(0..3)];
            bytes[1] = 0;
            let mut fields = vec![(2, 12), (4, 12), (48, 3), (50, 3)];
            if len >= 196 {
                fields.extend([(64, 12), (108, 12), (152, 12)]);
            }
            for (at, codes) in fields {
                bytes[at] = rng.random_range(0..codes);
                bytes[at + 1] = 0;
            }
        }
        for layout in [Layout::H7, Layout::PreH7] {
            decoded += usize::from(Packet::decode(&bytes, layout).is_ok());
        }
    }
    assert!(decoded > 0, "some random packets decode");
}

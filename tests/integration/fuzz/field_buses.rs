//! The lab's other wire formats: Net F/T's RDT requests and records, CAN frames over UDP, and
//! CANopen's SDO transfers, each decoder on random bytes (biased to its own length) and on valid
//! encodings with bytes changed, cut or extended.

use proptest::collection::vec;
use proptest::prelude::*;
use proptest::sample::Index;

use knotlab_hw::canopen::CanFrame;
use knotlab_hw::canopen::sdo::{Object, SdoRequest, SdoResponse};
use knotlab_hw::canopen::udp;
use knotlab_hw::netft::rdt::{RECORD_LEN, REQUEST_LEN, Record, Request};

use super::{cases, fuzz, isolated, outcome};

/// Random bytes: any length below 64, or exactly `len`, some all zeros or all ones.
fn bytes(len: usize) -> impl Strategy<Value = Vec<u8>> {
    prop_oneof![
        vec(any::<u8>(), 0..64),
        vec(any::<u8>(), len),
        vec(prop_oneof![Just(0u8), Just(0xff), any::<u8>()], len),
    ]
}

/// Up to three changes: a byte set, the bytes cut at an index, bytes appended.
fn mutate(mut bytes: Vec<u8>, changes: &[(u8, Index, u8)]) -> Vec<u8> {
    for (kind, at, value) in changes {
        match kind % 3 {
            0 if !bytes.is_empty() => {
                let i = at.index(bytes.len());
                bytes[i] = *value;
            }
            1 => bytes.truncate(at.index(bytes.len() + 1)),
            _ => bytes.extend(std::iter::repeat_n(*value, usize::from(value % 5) + 1)),
        }
    }
    bytes
}

fn changes() -> impl Strategy<Value = Vec<(u8, Index, u8)>> {
    vec((any::<u8>(), any::<Index>(), any::<u8>()), 0..=3)
}

/// The RDT request and record decoders never panic on random or changed datagrams; a valid record's
/// encoding decodes.
#[test]
fn rdt_decoders_survive_random_and_mutated_datagrams() {
    isolated(|| {
        fuzz("rdt-request/raw", 2 * cases(), bytes(REQUEST_LEN), |bytes| outcome(Request::decode(bytes)));
        fuzz("rdt-record/raw", 2 * cases(), bytes(RECORD_LEN), |bytes| outcome(Record::decode(bytes)));
        let record = (any::<[u32; 3]>(), any::<[i32; 6]>()).prop_map(|([rdt, ft, status], counts)| Record {
            rdt_sequence: rdt,
            ft_sequence: ft,
            status,
            counts,
        });
        fuzz("rdt/mutated", 2 * cases(), (record, changes()), |(record, changes)| {
            let bytes = record.encode().to_vec();
            if changes.is_empty() {
                assert_eq!(Record::decode(&bytes).as_ref(), Ok(record), "a valid record decodes");
            }
            outcome(Record::decode(&mutate(bytes, changes)))
        });
    });
}

/// The CAN-over-UDP datagram decoder and the SDO decoders never panic on random or changed bytes; a
/// valid frame's datagram and a valid transfer decode to themselves.
#[test]
fn can_datagram_and_sdo_decoders_survive_random_and_mutated_bytes() {
    isolated(|| {
        fuzz("can-udp/raw", 2 * cases(), bytes(udp::DATAGRAM_LEN), |bytes| outcome(udp::decode(bytes)));
        let frame = (0u16..=0x7ff, vec(any::<u8>(), 0..=8))
            .prop_map(|(id, data)| CanFrame::new(id, &data).expect("an 11-bit id and at most 8 bytes"));
        fuzz("can-udp/mutated", 2 * cases(), (frame, changes()), |(frame, changes)| {
            let bytes = udp::encode(frame).to_vec();
            if changes.is_empty() {
                assert_eq!(udp::decode(&bytes).as_ref(), Ok(frame), "a valid datagram decodes");
            }
            outcome(udp::decode(&mutate(bytes, changes)))
        });
        fuzz("sdo-request/raw", 2 * cases(), bytes(8), |bytes| outcome(SdoRequest::decode(bytes)));
        fuzz("sdo-response/raw", 2 * cases(), bytes(8), |bytes| outcome(SdoResponse::decode(bytes)));
        let object = (any::<u16>(), any::<u8>()).prop_map(|(index, subindex)| Object { index, subindex });
        let request = (object, any::<u32>(), 1u8..=4).prop_map(|(object, value, len)| {
            let value = if len == 4 { value } else { value & ((1 << (8 * u32::from(len))) - 1) };
            SdoRequest::Write { object, value, len }
        });
        fuzz("sdo/mutated", 2 * cases(), (request, changes()), |(request, changes)| {
            let bytes = request.encode().expect("a valid transfer").to_vec();
            if changes.is_empty() {
                assert_eq!(SdoRequest::decode(&bytes).as_ref(), Ok(request), "a valid transfer decodes");
            }
            outcome(SdoRequest::decode(&mutate(bytes, changes)))
        });
    });
}

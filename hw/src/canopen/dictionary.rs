//! The objects of a CiA 402 drive this driver and the emulator use, and the PDO mapping they agree on.

use super::sdo::Object;

const fn object(index: u16, subindex: u8) -> Object {
    Object { index, subindex }
}

/// Heartbeat producer time, ms (u16).
pub const HEARTBEAT_PRODUCER: Object = object(0x1017, 0);
/// RPDO1's first and second mapped objects (u32: index, subindex, bits).
pub const RPDO1_MAPPING: [Object; 2] = [object(0x1600, 1), object(0x1600, 2)];
/// TPDO1's first and second mapped objects.
pub const TPDO1_MAPPING: [Object; 2] = [object(0x1A00, 1), object(0x1A00, 2)];
/// Controlword (u16).
pub const CONTROLWORD: Object = object(0x6040, 0);
/// Statusword (u16).
pub const STATUSWORD: Object = object(0x6041, 0);
/// Modes of operation (i8).
pub const MODES_OF_OPERATION: Object = object(0x6060, 0);
/// Modes of operation display (i8).
pub const MODES_OF_OPERATION_DISPLAY: Object = object(0x6061, 0);
/// Position actual value, counts (i32).
pub const POSITION_ACTUAL: Object = object(0x6064, 0);
/// Following error window, counts (u32; 0: not watched).
pub const FOLLOWING_ERROR_WINDOW: Object = object(0x6065, 0);
/// Target position, counts (i32).
pub const TARGET_POSITION: Object = object(0x607A, 0);
/// Software position limits, min and max, counts (i32).
pub const SOFTWARE_LIMITS: [Object; 2] = [object(0x607D, 1), object(0x607D, 2)];

/// Cyclic synchronous position mode.
pub const MODE_CSP: u8 = 8;

/// A mapping entry: the object's index, subindex and length in bits.
pub const fn mapping(o: Object, bits: u8) -> u32 {
    ((o.index as u32) << 16) | ((o.subindex as u32) << 8) | bits as u32
}

/// RPDO1: controlword, target position.
pub const RPDO1: [u32; 2] = [mapping(CONTROLWORD, 16), mapping(TARGET_POSITION, 32)];
/// TPDO1: statusword, position actual value.
pub const TPDO1: [u32; 2] = [mapping(STATUSWORD, 16), mapping(POSITION_ACTUAL, 32)];

/// EMCY error code of a following error (CiA 402).
pub const EMCY_FOLLOWING_ERROR: u16 = 0x8611;

/// What an EMCY error code means, for messages.
pub fn emcy_reason(code: u16) -> &'static str {
    match code {
        0x0000 => "error reset or no error",
        0x8611 => "following error",
        0x8612 => "reference limit",
        0x2310 => "continuous over-current",
        0x3210 => "DC link over-voltage",
        0x4310 => "drive temperature",
        0x5530 => "EEPROM",
        0x8130 => "heartbeat or life guard error",
        0xFF00..=0xFFFF => "device-specific",
        _ => "an error code this driver does not name",
    }
}

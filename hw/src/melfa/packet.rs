//! The MELFA real-time external control ("MXT") packet, as typed Rust values. The byte layout is in
//! [`super::codec`]; the reference is shared/reference/melfa-mxt.md.

/// Which packet layout the controller's software speaks.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Layout {
    /// Software H7 and later: 196 bytes, with three more monitor slots.
    H7,
    /// Software H6 and older: the first 64 bytes only.
    PreH7,
}

impl Layout {
    /// The packet's size in bytes.
    pub const fn packet_len(self) -> usize {
        match self {
            Layout::H7 => 196,
            Layout::PreH7 => 64,
        }
    }

    /// The name used in configuration files and on the command line.
    pub const fn as_str(self) -> &'static str {
        match self {
            Layout::H7 => "h7",
            Layout::PreH7 => "pre-h7",
        }
    }
}

impl std::str::FromStr for Layout {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "h7" => Ok(Layout::H7),
            "pre-h7" => Ok(Layout::PreH7),
            other => Err(format!("unknown MELFA packet layout '{other}': expected h7 or pre-h7")),
        }
    }
}

/// The packet's command (offset 0).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Command {
    /// 0: no motion command; the reply still carries monitor data (a keep-alive).
    Null,
    /// 1: move to the command in `dat`.
    Move,
    /// 255: end real-time control; the robot program's MXT instruction returns.
    End,
}

impl Command {
    /// The code on the wire.
    pub const fn code(self) -> u16 {
        match self {
            Command::Null => 0,
            Command::Move => 1,
            Command::End => 255,
        }
    }

    /// From the code on the wire.
    pub const fn from_code(code: u16) -> Option<Self> {
        match code {
            0 => Some(Command::Null),
            1 => Some(Command::Move),
            255 => Some(Command::End),
            _ => None,
        }
    }
}

/// What a data union holds (SendType, RecvType, RecvType1..3).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DataType {
    /// 0: nothing.
    Null,
    /// 1: Cartesian pose, command value.
    Pose,
    /// 2: joints, command value.
    Joint,
    /// 3: motor pulses, command value.
    Pulse,
    /// 4: pose after the controller's filter.
    FilteredPose,
    /// 5: joints after the controller's filter.
    FilteredJoint,
    /// 6: pulses after the controller's filter.
    FilteredPulse,
    /// 7: pose from encoder feedback (H7+).
    FeedbackPose,
    /// 8: joints from encoder feedback (H7+).
    FeedbackJoint,
    /// 9: pulses from encoder feedback (H7+).
    FeedbackPulse,
    /// 10: commanded motor current, % (H7+).
    CommandCurrent,
    /// 11: feedback motor current, % (H7+).
    FeedbackCurrent,
}

impl DataType {
    /// The code on the wire.
    pub const fn code(self) -> u16 {
        match self {
            DataType::Null => 0,
            DataType::Pose => 1,
            DataType::Joint => 2,
            DataType::Pulse => 3,
            DataType::FilteredPose => 4,
            DataType::FilteredJoint => 5,
            DataType::FilteredPulse => 6,
            DataType::FeedbackPose => 7,
            DataType::FeedbackJoint => 8,
            DataType::FeedbackPulse => 9,
            DataType::CommandCurrent => 10,
            DataType::FeedbackCurrent => 11,
        }
    }

    /// From the code on the wire.
    pub const fn from_code(code: u16) -> Option<Self> {
        Some(match code {
            0 => DataType::Null,
            1 => DataType::Pose,
            2 => DataType::Joint,
            3 => DataType::Pulse,
            4 => DataType::FilteredPose,
            5 => DataType::FilteredJoint,
            6 => DataType::FilteredPulse,
            7 => DataType::FeedbackPose,
            8 => DataType::FeedbackJoint,
            9 => DataType::FeedbackPulse,
            10 => DataType::CommandCurrent,
            11 => DataType::FeedbackCurrent,
            _ => return None,
        })
    }

    /// Whether the union holds joints for this type.
    pub const fn is_joint(self) -> bool {
        matches!(self, DataType::Joint | DataType::FilteredJoint | DataType::FeedbackJoint)
    }
}

/// A Cartesian pose in the union.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Pose {
    /// x, y, z, mm.
    pub xyz_mm: [f32; 3],
    /// a, b, c: rotations about the fixed x, y, z axes, rad.
    pub abc_rad: [f32; 3],
    /// Additional axes l1, l2.
    pub l1_l2: [f32; 2],
    /// Structure flags (arm configuration) sflg1, sflg2.
    pub flags: [u32; 2],
}

/// A data union's contents, as its type code says.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Data {
    /// Nothing (type 0): the 40 bytes are zero.
    #[default]
    None,
    /// A pose (types 1, 4, 7).
    Pose(Pose),
    /// Joints j1..j8, rad (types 2, 5, 8).
    Joint([f32; 8]),
    /// Pulses p1..p8 (types 3, 6, 9).
    Pulse([i32; 8]),
    /// Motor currents, % (types 10, 11).
    Current([i32; 8]),
}

/// The I/O part of the packet.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Io {
    /// SendIOType: 0 none, 1 output signal, 2 input signal.
    pub send_type: u16,
    /// RecvIOType: same codes.
    pub recv_type: u16,
    /// First I/O bit number.
    pub bit_top: u16,
    /// Output mask (command direction).
    pub bit_mask: u16,
    /// I/O value.
    pub data: u16,
}

/// One of the three extra monitor slots (H7+): the type asked for (command) or returned (reply), and
/// the data.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Monitor {
    /// RecvTypeN ([`DataType::Null`] for an unused slot).
    pub kind: DataType,
    /// datN.
    pub data: Data,
}

/// One MXT packet. In a command `send_type` types `data` and `recv_type` asks for the reply's `data`;
/// in a reply `send_type` says what `data` holds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Packet {
    /// Command.
    pub command: Command,
    /// SendType: what `data` holds.
    pub send_type: DataType,
    /// RecvType: the monitor type asked for in the reply's `data`.
    pub recv_type: DataType,
    /// dat.
    pub data: Data,
    /// The I/O fields.
    pub io: Io,
    /// TCount: in a reply, cycles without communication.
    pub t_count: u16,
    /// CCount: the packet counter.
    pub c_count: u32,
    /// RecvType1..3 and dat1..3 (H7+; ignored by the pre-H7 layout).
    pub monitors: [Monitor; 3],
}

impl Monitor {
    /// An unused slot.
    pub const EMPTY: Self = Self { kind: DataType::Null, data: Data::None };
}

impl Packet {
    /// A command with no data, asking for `recv_type` (and, H7+, `monitors`) in the reply.
    pub fn command(command: Command, recv_type: DataType, monitors: [DataType; 3], c_count: u32) -> Self {
        Self {
            command,
            send_type: DataType::Null,
            recv_type,
            data: Data::None,
            io: Io::default(),
            t_count: 0,
            c_count,
            monitors: monitors.map(|kind| Monitor { kind, data: Data::None }),
        }
    }

    /// The joints in `data` as f64, if it holds joints (j1..j6).
    pub fn joints_rad(&self) -> Option<[f64; 6]> {
        match self.data {
            Data::Joint(j) if self.send_type.is_joint() => Some(std::array::from_fn(|i| f64::from(j[i]))),
            _ => None,
        }
    }

    /// The joints in the first monitor slot of type `kind`, as f64.
    pub fn monitor_joints_rad(&self, kind: DataType) -> Option<[f64; 6]> {
        self.monitors.iter().find(|m| m.kind == kind).and_then(|m| match m.data {
            Data::Joint(j) => Some(std::array::from_fn(|i| f64::from(j[i]))),
            _ => None,
        })
    }
}

//! The parts of Rerun's SDK (`re_sdk` and its types) the recordings use, under one name.

pub use re_sdk::{RecordingStream, RecordingStreamBuilder};
pub use re_sdk_types::archetypes::{
    Arrows3D, Boxes3D, Capsules3D, Image, LineStrips3D, Points3D, Scalars, TextDocument, TextLog,
};
pub use re_sdk_types::components::Color;
pub use re_sdk_types::datatypes::Quaternion;

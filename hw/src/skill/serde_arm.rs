//! Arm names in skill files as their command-line names ("left", "right", "assist", "camera").

use serde::{Deserialize, Deserializer, Serializer};

use crate::rig::ArmName;

/// Writes the arm's name.
pub fn serialize<S: Serializer>(arm: &ArmName, serializer: S) -> Result<S::Ok, S::Error> {
    serializer.serialize_str(arm.as_str())
}

/// Reads an arm's name.
pub fn deserialize<'de, D: Deserializer<'de>>(deserializer: D) -> Result<ArmName, D::Error> {
    let name = String::deserialize(deserializer)?;
    name.parse().map_err(serde::de::Error::custom)
}

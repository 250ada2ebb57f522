//! Reading a rig config: TOML syntax, then the schema (unknown keys, wrong types, with the key's path
//! and line), then the checks (every problem, with its key).

use std::path::Path;

use super::schema::RigConfig;

/// Why a rig config was refused (`Invalid`: values out of range or combinations that cannot work).
pub type RigConfigError = crate::toml_file::TomlFileError;

/// Parses rig config TOML; `file` names it in errors.
pub fn parse_rig_config(text: &str, file: &str) -> Result<RigConfig, RigConfigError> {
    crate::toml_file::parse_checked(text, file, RigConfig::problems)
}

/// Reads and parses a rig config file.
pub fn load_rig_config(path: &Path) -> Result<RigConfig, RigConfigError> {
    crate::toml_file::load_checked(path, RigConfig::problems)
}

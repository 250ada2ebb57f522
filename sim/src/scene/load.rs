//! Reading a scene file: TOML syntax, then the schema (unknown keys, wrong types, with the key's path),
//! then the ranges (every value out of range, with its key).

use std::path::Path;

use super::config::SceneConfig;

/// Why a scene file was refused (`Invalid`: every value out of range, with its key).
pub type SceneError = knotlab_hw::toml_file::TomlFileError;

/// Parses scene TOML; `file` names it in errors.
pub fn parse_scene(text: &str, file: &str) -> Result<SceneConfig, SceneError> {
    knotlab_hw::toml_file::parse_checked(text, file, SceneConfig::range_problems)
}

/// Reads and parses a scene file.
pub fn load_scene(path: &Path) -> Result<SceneConfig, SceneError> {
    knotlab_hw::toml_file::load_checked(path, SceneConfig::range_problems)
}

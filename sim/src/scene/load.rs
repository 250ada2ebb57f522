//! Reading a scene file: TOML syntax, then the schema (unknown keys, wrong types, with the key's path),
//! then the ranges (every value out of range, with its key).

use std::path::Path;

use knotlab_hw::toml_file::key_line;

use super::config::SceneConfig;
use crate::thread::ThreadModel;

/// Why a scene file was refused (`Invalid`: every value out of range, with its key).
pub type SceneError = knotlab_hw::toml_file::TomlFileError;

/// The keys of `[thread]` only the rope reads.
const ROPE_KEYS: [&str; 8] = [
    "axial_stiffness_n",
    "rope_substeps",
    "rope_spacing_radii",
    "rope_inertial_mass_kg_per_m",
    "rope_radius_at_metal_m",
    "rope_direct_bending",
    "rope_constraint_passes",
    "rope_contacts_both_ways",
];

/// The keys of `[thread]` only the chain reads.
const CHAIN_KEYS: [&str; 2] = ["twist_free", "bend_damping_n_m_s_per_rad"];

/// Parses scene TOML; `file` names it in errors.
pub fn parse_scene(text: &str, file: &str) -> Result<SceneConfig, SceneError> {
    let config = knotlab_hw::toml_file::parse_checked(text, file, SceneConfig::range_problems)?;
    model_keys(text, file, &config)?;
    Ok(config)
}

/// Reads and parses a scene file.
pub fn load_scene(path: &Path) -> Result<SceneConfig, SceneError> {
    let file = path.display().to_string();
    let text =
        std::fs::read_to_string(path).map_err(|error| SceneError::Read { file: file.clone(), error })?;
    parse_scene(&text, &file)
}

/// Refuses a key of `[thread]` that the chosen suture model does not read (`thread.model`), naming
/// it and its line, and a chain without its joints' damping.
fn model_keys(text: &str, file: &str, config: &SceneConfig) -> Result<(), SceneError> {
    let Ok(table) = text.parse::<toml::Table>() else { return Ok(()) };
    let Some(thread) = table.get("thread").and_then(toml::Value::as_table) else { return Ok(()) };
    let (model, other, foreign) = match config.thread.model {
        ThreadModel::Chain => ("chain", "rope", &ROPE_KEYS[..]),
        ThreadModel::Rope => ("rope", "chain", &CHAIN_KEYS[..]),
    };
    let refuse = |key: &str, reason: String| SceneError::Schema {
        file: file.to_owned(),
        line: key_line(text, &format!("thread.{key}")),
        key: format!("thread.{key}"),
        reason,
    };
    if let Some(key) = foreign.iter().find(|k| thread.contains_key(**k)) {
        return Err(refuse(
            key,
            format!(
                "only the {other} model reads it; thread.model = \"{model}\" would ignore it (remove it)"
            ),
        ));
    }
    if config.thread.model == ThreadModel::Chain && !thread.contains_key("bend_damping_n_m_s_per_rad") {
        return Err(SceneError::Schema {
            file: file.to_owned(),
            // The model's line, or the table's where the model is left to its default.
            line: key_line(text, "thread.model"),
            key: "thread.bend_damping_n_m_s_per_rad".to_owned(),
            reason: "missing: the chain's joints need it".to_owned(),
        });
    }
    Ok(())
}

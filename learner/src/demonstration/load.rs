//! Reading a demonstration directory: `demo.toml` first (format version, schema, values), then each
//! instrument's CSV file it lists, every one checked row by row.

use std::path::Path;

use super::csv::parse_samples;
use super::error::DemoError;
use super::metadata::{METADATA_FILE, parse_metadata};
use super::{Demonstration, InstrumentRecord};

/// Reads and validates the demonstration in directory `dir`. Errors name the file (its path under
/// `dir`), the line and the field.
pub fn load_demonstration(dir: &Path) -> Result<Demonstration, DemoError> {
    read_demonstration_dir(dir, |name| {
        let path = dir.join(name);
        let file = path.display().to_string();
        std::fs::read_to_string(&path).map(|text| (file.clone(), text)).map_err(|error| DemoError::Io {
            file,
            action: "cannot read",
            error,
        })
    })
}

/// Reads a demonstration through `read`, which maps a file name inside the directory to the name to
/// report in errors and the file's text (a test or an archive reader can hand in files from memory).
pub fn read_demonstration_dir(
    dir: &Path,
    read: impl Fn(&str) -> Result<(String, String), DemoError>,
) -> Result<Demonstration, DemoError> {
    if !dir.is_dir() && dir.exists() {
        return Err(DemoError::format(
            dir.display().to_string(),
            0,
            "(directory)",
            "a demonstration is a directory holding demo.toml and one CSV file per instrument",
        ));
    }
    let (meta_name, meta_text) = read(METADATA_FILE)?;
    let meta = parse_metadata(&meta_text, &meta_name)?;
    let mut instruments = Vec::with_capacity(meta.instruments.len());
    for entry in &meta.instruments {
        let (name, text) = read(&entry.file)?;
        let samples = parse_samples(&text, &name, entry.samples, meta.metadata.sample_rate_hz)?;
        instruments.push(InstrumentRecord { instrument: entry.instrument, samples });
    }
    Ok(Demonstration { metadata: meta.metadata, instruments })
}

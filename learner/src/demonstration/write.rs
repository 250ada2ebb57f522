//! Writing a demonstration directory: validated first, then `demo.toml` and one CSV file per
//! instrument, every number printed so that it reads back to the same bits.

use std::path::Path;

use super::Demonstration;
use super::csv::write_samples;
use super::error::DemoError;
use super::metadata::{METADATA_FILE, render_metadata};

/// Writes `demo` into directory `dir` (created if missing; files of the same names are replaced).
/// Refuses, before writing anything, data the loader would refuse.
pub fn write_demonstration(dir: &Path, demo: &Demonstration) -> Result<(), DemoError> {
    demo.validate()?;
    std::fs::create_dir_all(dir).map_err(|error| DemoError::Io {
        file: dir.display().to_string(),
        action: "cannot create directory",
        error,
    })?;
    let io_error = |path: &Path| {
        let file = path.display().to_string();
        move |error| DemoError::Io { file, action: "cannot write", error }
    };
    let write = |name: &str, text: String| {
        let path = dir.join(name);
        std::fs::write(&path, text).map_err(io_error(&path))
    };
    for record in &demo.instruments {
        let path = dir.join(record.file_name());
        let file = std::fs::File::create(&path).map_err(io_error(&path))?;
        write_samples(std::io::BufWriter::new(file), &record.samples).map_err(io_error(&path))?;
    }
    // The metadata last: a directory whose writing was interrupted has no demo.toml, or one that
    // counts samples its CSV files do hold.
    write(METADATA_FILE, render_metadata(demo))
}

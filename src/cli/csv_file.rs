//! The CSV files commands write: a header, then one serde record a row (fields in the header's order).

use std::path::Path;

use anyhow::Context;

/// Writes `rows` to `path` as CSV under `header` (written even when there are no rows).
pub fn write_rows<R: serde::Serialize>(
    path: &Path,
    header: &[&str],
    rows: impl IntoIterator<Item = R>,
) -> anyhow::Result<()> {
    let context = || format!("writing {}", path.display());
    let mut writer = csv::WriterBuilder::new().has_headers(false).from_path(path).with_context(context)?;
    writer.write_record(header).with_context(context)?;
    for row in rows {
        writer.serialize(row).with_context(context)?;
    }
    writer.flush().with_context(context)
}

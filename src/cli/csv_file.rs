//! The CSV files commands write: a header, then one serde record a row (fields in the header's order);
//! and the line a record read from a text stands on.

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

/// The 1-based line of `text` on which the record `reader` has just read ends. (The reader's own line
/// count, and the position it gives a record, pass over the blank lines and comments before it.)
pub fn line_of_record(text: &str, reader: &csv::Reader<&[u8]>) -> usize {
    let end = usize::try_from(reader.position().byte()).map_or(text.len(), |b| b.min(text.len()));
    text.get(..end).unwrap_or(text).trim_end_matches(['\n', '\r']).matches('\n').count() + 1
}

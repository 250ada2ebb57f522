//! Reading a centreline from a CSV file (on the csv crate): `x,y,z` per line (metres), a header line
//! allowed first, blank lines and `#` comments skipped. Every problem names the file, the line and the
//! reason.

use std::path::Path;

use nalgebra::Vector3;
use thiserror::Error;

use super::centreline::{MAX_POINTS, MIN_POINTS};

/// What is wrong with one line (or, for too few points, with the file as a whole at its last line).
#[derive(Debug, Clone, PartialEq, Error)]
pub enum LineProblem {
    /// Not three fields.
    #[error("expected 3 comma-separated numbers x,y,z, found {found} field(s)")]
    FieldCount {
        /// Fields found.
        found: usize,
    },
    /// A field is not a number.
    #[error("{axis} = '{text}' is not a number")]
    NotANumber {
        /// Which coordinate.
        axis: char,
        /// The field as written.
        text: String,
    },
    /// A field is NaN or infinite.
    #[error("{axis} = '{text}' is not finite")]
    NotFinite {
        /// Which coordinate.
        axis: char,
        /// The field as written.
        text: String,
    },
    /// The point equals the one before it.
    #[error("repeats the point on line {previous_line}: consecutive points must differ")]
    Duplicate {
        /// Line of the point it repeats.
        previous_line: usize,
    },
    /// The CSV reader could not read the line (it reads any field count of UTF-8 text, so this names
    /// what it said rather than dropping the rest of the file).
    #[error("unreadable: {reason}")]
    Unreadable {
        /// What the reader said.
        reason: String,
    },
    /// More points than a centreline may have.
    #[error("point {count}: a centreline may have at most {MAX_POINTS} points")]
    TooManyPoints {
        /// The point this line would add.
        count: usize,
    },
    /// The file ends before enough points.
    #[error("end of file after only {count} point(s); a centreline needs at least {MIN_POINTS}")]
    TooFewPoints {
        /// Points read.
        count: usize,
    },
}

/// A centreline file that could not be read.
#[derive(Debug, Error)]
pub enum CsvError {
    /// The file could not be read.
    #[error("{path}: cannot read: {reason}")]
    Io {
        /// The file.
        path: String,
        /// Why (in the message, not a `source`: said once).
        reason: std::io::Error,
    },
    /// A line is malformed.
    #[error("{path}: line {line}: {problem}")]
    Line {
        /// The file.
        path: String,
        /// Line number, from 1.
        line: usize,
        /// What is wrong.
        problem: LineProblem,
    },
}

/// Parses CSV text into points; a problem comes with its line number (from 1).
pub fn parse_points(text: &str) -> Result<Vec<Vector3<f64>>, (usize, LineProblem)> {
    let mut points: Vec<Vector3<f64>> = Vec::new();
    let mut previous_line = 0;
    let mut seen_content = false;
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(false)
        .flexible(true)
        .trim(csv::Trim::All)
        .comment(Some(b'#'))
        .from_reader(text.as_bytes());
    let mut record = csv::StringRecord::new();
    let mut lines = LineCounter::new(text);
    loop {
        match reader.read_record(&mut record) {
            Ok(true) => {}
            Ok(false) => break,
            Err(e) => {
                let line = e.position().map_or(0, |p| p.line() as usize);
                return Err((line, LineProblem::Unreadable { reason: e.to_string() }));
            }
        }
        // The record's own line (the reader's count, and the position it starts at, pass over the blank
        // lines and comments before it): the lines of the text up to the record's end.
        let end = usize::try_from(reader.position().byte()).map_or(text.len(), |b| b.min(text.len()));
        let line =
            lines.newlines_before(text.get(..end).unwrap_or(text).trim_end_matches(['\n', '\r']).len()) + 1;
        let fields: Vec<&str> = record.iter().collect();
        // A line of spaces, or a comment after them.
        if fields == [""] || fields.first().is_some_and(|f| f.starts_with('#')) {
            continue;
        }
        let first = !seen_content;
        seen_content = true;
        // A header: the first line with content, none of whose fields is a number.
        if first && fields.iter().all(|f| f.parse::<f64>().is_err()) {
            continue;
        }
        if fields.len() != 3 {
            return Err((line, LineProblem::FieldCount { found: fields.len() }));
        }
        let mut xyz = [0.0; 3];
        for ((value, text), axis) in xyz.iter_mut().zip(&fields).zip(['x', 'y', 'z']) {
            *value = match text.parse::<f64>() {
                Ok(v) if v.is_finite() => v,
                Ok(_) => return Err((line, LineProblem::NotFinite { axis, text: (*text).to_owned() })),
                Err(_) => return Err((line, LineProblem::NotANumber { axis, text: (*text).to_owned() })),
            };
        }
        if points.len() == MAX_POINTS {
            return Err((line, LineProblem::TooManyPoints { count: MAX_POINTS + 1 }));
        }
        let p = Vector3::from(xyz);
        if points.last() == Some(&p) {
            return Err((line, LineProblem::Duplicate { previous_line }));
        }
        points.push(p);
        previous_line = line;
    }
    if points.len() < MIN_POINTS {
        return Err((text.lines().count().max(1), LineProblem::TooFewPoints { count: points.len() }));
    }
    Ok(points)
}

/// Newlines in a text before a byte offset, counted from the last offset asked (forwards or
/// backwards), so that asking at each record costs the bytes between records, not the whole text.
struct LineCounter<'a> {
    bytes: &'a [u8],
    at: usize,
    newlines: usize,
}

impl<'a> LineCounter<'a> {
    fn new(text: &'a str) -> Self {
        Self { bytes: text.as_bytes(), at: 0, newlines: 0 }
    }

    fn newlines_before(&mut self, offset: usize) -> usize {
        let count = |from: usize, to: usize| self.bytes[from..to].iter().filter(|&&b| b == b'\n').count();
        if offset >= self.at {
            self.newlines += count(self.at, offset);
        } else {
            self.newlines -= count(offset, self.at);
        }
        self.at = offset;
        self.newlines
    }
}

/// Reads a centreline file.
pub fn read_points(path: &Path) -> Result<Vec<Vector3<f64>>, CsvError> {
    let name = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|reason| CsvError::Io { path: name.clone(), reason })?;
    parse_points(&text).map_err(|(line, problem)| CsvError::Line { path: name, line, problem })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A header line, blank lines, `#` comments and CRLF endings are skipped and every data line is read.
    #[test]
    fn header_blank_lines_and_comments() {
        let text = "x, y, z\n\n0,0,0\n# a comment\n1,0,0\r\n1,1,0\n0,1,0.5\n\n";
        let points = parse_points(text).expect("valid");
        assert_eq!(points.len(), 4);
        assert_eq!(points[3], Vector3::new(0.0, 1.0, 0.5));
    }

    /// Each malformed centreline is refused with the number of its bad line and the reason: field count, not
    /// a number, not finite, duplicate, too few points, or a second header.
    #[test]
    fn each_problem_names_its_line() {
        let cases = [
            ("0,0,0\n1,0,0\n1,1\n", 3, LineProblem::FieldCount { found: 2 }),
            ("x,y,z\n0,0,0\n1,zero,0\n", 3, LineProblem::NotANumber { axis: 'y', text: "zero".into() }),
            ("0,0,0\n\n1,0,NaN\n", 3, LineProblem::NotFinite { axis: 'z', text: "NaN".into() }),
            ("0,0,0\n1,0,0\n\n1.0,0,0\n", 4, LineProblem::Duplicate { previous_line: 2 }),
            ("x,y,z\n0,0,0\n1,0,0\n2,0,0\n", 4, LineProblem::TooFewPoints { count: 3 }),
            ("", 1, LineProblem::TooFewPoints { count: 0 }),
            // A second header-like line is not a header.
            ("x,y,z\nx,y,z\n", 2, LineProblem::NotANumber { axis: 'x', text: "x".into() }),
        ];
        for (text, line, problem) in cases {
            assert_eq!(parse_points(text), Err((line, problem)), "{text:?}");
        }
    }
}

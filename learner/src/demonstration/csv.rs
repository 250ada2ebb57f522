//! One instrument's CSV file (on the csv crate, one serde record a row): a header naming the
//! columns, then one sample per line. Reading checks every row (field count, numbers, NaN, the grasp word, time increasing, unit quaternions) and names the
//! line and the column of the first problem; writing prints every number so it reads back to the same
//! bits.

use ::csv::{ReaderBuilder, StringRecord, WriterBuilder};
use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

use super::error::DemoError;
use super::{GraspState, Sample};

/// The columns of format version 1, in the order this knotlab writes them. A reader finds them by
/// name; further columns are ignored.
pub const COLUMNS: [&str; 13] =
    ["time_s", "x_m", "y_m", "z_m", "qx", "qy", "qz", "qw", "jaw_rad", "grasp", "fx_n", "fy_n", "fz_n"];

/// A step between two samples longer than this many nominal sample periods is a gap in the recording.
pub const MAX_GAP_PERIODS: f64 = 10.0;

/// How far a quaternion's norm may be from 1.
pub const QUATERNION_NORM_TOLERANCE: f64 = 1e-3;

/// The jaw angle's allowed range, rad.
pub const JAW_RANGE_RAD: (f64, f64) = (-0.5, std::f64::consts::PI);

/// How far from the world's origin an instrument tip may be, m (the rig's workspace spans about 2 m).
pub const MAX_POSITION_M: f64 = 10.0;

/// How fast an instrument tip may move between two samples, m/s (a surgeon's hand moves an
/// instrument's tip at well under 0.5 m/s; the shipped demonstration at most 0.18 m/s). A path's
/// length, and with it what the features resample along it, is bounded by this times its duration.
pub const MAX_TIP_SPEED_M_S: f64 = 5.0;

/// One sample as a CSV row, its columns named as in [`COLUMNS`].
#[derive(Debug, Serialize, Deserialize)]
struct Row {
    time_s: f64,
    x_m: f64,
    y_m: f64,
    z_m: f64,
    qx: f64,
    qy: f64,
    qz: f64,
    qw: f64,
    jaw_rad: f64,
    grasp: String,
    fx_n: f64,
    fy_n: f64,
    fz_n: f64,
}

impl Row {
    fn of(s: &Sample) -> Self {
        let (p, q, f) = (s.position_m, s.quaternion_xyzw, s.force_n);
        Self {
            time_s: s.time_s,
            x_m: p.x,
            y_m: p.y,
            z_m: p.z,
            qx: q[0],
            qy: q[1],
            qz: q[2],
            qw: q[3],
            jaw_rad: s.jaw_rad,
            grasp: s.grasp.as_str().to_owned(),
            fx_n: f.x,
            fy_n: f.y,
            fz_n: f.z,
        }
    }
}

/// Writes a sample list as CSV into `out`: the header, then one row a sample, every line ended by a
/// newline and every number in the shortest form that reads back to the same bits.
pub fn write_samples(out: impl std::io::Write, samples: &[Sample]) -> std::io::Result<()> {
    let mut writer = WriterBuilder::new().has_headers(false).from_writer(out);
    writer.write_record(COLUMNS)?;
    for s in samples {
        writer.serialize(Row::of(s))?;
    }
    writer.flush()
}

/// Parses one instrument's CSV text; `file` names it in errors, `expected_samples` is the count the
/// metadata gives, `sample_rate_hz` the nominal rate.
pub fn parse_samples(
    text: &str,
    file: &str,
    expected_samples: usize,
    sample_rate_hz: f64,
) -> Result<Vec<Sample>, DemoError> {
    let err = |line: usize, field: &str, reason: String| DemoError::format(file, line, field, reason);
    if text.is_empty() {
        return Err(err(1, "(header)", "empty file".to_owned()));
    }
    check_lines(text, file)?;
    let mut reader = ReaderBuilder::new().has_headers(true).flexible(true).from_reader(text.as_bytes());
    let unreadable = |line: usize, e: ::csv::Error| err(line, "(row)", format!("unreadable: {e}"));
    let header: Vec<String> =
        reader.headers().map_err(|e| unreadable(1, e))?.iter().map(|h| h.trim().to_owned()).collect();
    for (k, name) in header.iter().enumerate() {
        if header[..k].contains(name) {
            return Err(err(1, name, "column appears twice".to_owned()));
        }
    }
    for column in COLUMNS {
        if !header.iter().any(|h| h == column) {
            return Err(err(1, column, format!("missing column (the header has: {})", header.join(","))));
        }
    }
    let header_record = StringRecord::from(header.clone());

    // Room for the rows the text can hold (one per line), whatever the metadata claims.
    let mut samples = Vec::with_capacity(expected_samples.min(text.lines().count()));
    let mut record = StringRecord::new();
    let mut line = 1;
    loop {
        match reader.read_record(&mut record) {
            Ok(false) => break,
            Ok(true) => {}
            Err(e) => return Err(unreadable(line + 1, e)),
        }
        // Every line holds one row (no blank lines, no quoted line breaks: `check_lines`).
        line = record.position().map_or(line + 1, |p| p.line() as usize);
        if record.len() != header.len() {
            let missing = COLUMNS.iter().find(|c| header.iter().position(|h| h == *c) >= Some(record.len()));
            return Err(err(
                line,
                missing.copied().unwrap_or("(row)"),
                format!("{} fields, the header has {}", record.len(), header.len()),
            ));
        }
        record.trim();
        let row: Row = record.deserialize(Some(&header_record)).map_err(|e| {
            let field = match e.kind() {
                ::csv::ErrorKind::Deserialize { err, .. } => err.field(),
                _ => None,
            };
            let column = field.and_then(|i| header.get(i as usize)).map_or("(row)", String::as_str);
            let text = field.and_then(|i| record.get(i as usize)).unwrap_or("");
            err(line, column, format!("not a number: '{text}'"))
        })?;
        samples.push(sample_of(row, line, &err)?);
    }
    if samples.len() < expected_samples {
        return Err(err(
            line + 1,
            "(rows)",
            format!(
                "the file ends after {} samples, demo.toml says {expected_samples}: truncated",
                samples.len()
            ),
        ));
    }
    if samples.len() > expected_samples {
        return Err(err(
            expected_samples + 2,
            "(rows)",
            format!("{} samples, demo.toml says {expected_samples}", samples.len()),
        ));
    }
    validate_samples(&samples, file, sample_rate_hz)?;
    Ok(samples)
}

/// The checks the CSV reader does not make, on the text itself: the header is a whole line, no line
/// is blank (the reader would pass over it), and the file ends with a newline (one that does not was
/// cut inside its last row). A cut row names the field it ends in.
fn check_lines(text: &str, file: &str) -> Result<(), DemoError> {
    let err = |line: usize, field: &str, reason: String| DemoError::format(file, line, field, reason);
    let ends_with_newline = text.ends_with('\n');
    let lines: Vec<&str> = text.strip_suffix('\n').unwrap_or(text).split('\n').collect();
    let trim = |l: &str| l.strip_suffix('\r').unwrap_or(l).to_owned();
    let header: Vec<String> = trim(lines[0]).split(',').map(|h| h.trim().to_owned()).collect();
    if !ends_with_newline && lines.len() == 1 {
        return Err(err(1, "(header)", "the file ends inside its header line: truncated".to_owned()));
    }
    for (k, raw) in lines.iter().enumerate().skip(1) {
        let line = k + 1;
        let row = trim(raw);
        if line == lines.len() && !ends_with_newline {
            // The field the file ends in (a required one, or the header's name of another).
            let cut = row.split(',').count() - 1;
            let field = COLUMNS
                .iter()
                .find(|c| header.iter().position(|h| h == *c) == Some(cut))
                .copied()
                .unwrap_or_else(|| header.get(cut).map_or("(row)", String::as_str));
            return Err(err(
                line,
                field,
                format!(
                    "the file ends inside this row ({} of {} fields, no final newline): truncated",
                    cut + 1,
                    header.len()
                ),
            ));
        }
        if row.trim().is_empty() {
            return Err(err(line, "(row)", "empty line".to_owned()));
        }
    }
    Ok(())
}

/// A row's sample, its grasp one of its words (the numbers are checked with the whole list, by
/// [`validate_samples`], on the lines they came from: no line is blank).
fn sample_of(
    row: Row,
    line: usize,
    err: &impl Fn(usize, &str, String) -> DemoError,
) -> Result<Sample, DemoError> {
    let grasp = GraspState::parse(&row.grasp).ok_or_else(|| {
        err(line, "grasp", format!("'{}' is not one of open, holding, closed_empty", row.grasp))
    })?;
    Ok(Sample {
        time_s: row.time_s,
        position_m: Vector3::new(row.x_m, row.y_m, row.z_m),
        quaternion_xyzw: [row.qx, row.qy, row.qz, row.qw],
        jaw_rad: row.jaw_rad,
        grasp,
        force_n: Vector3::new(row.fx_n, row.fy_n, row.fz_n),
    })
}

/// Checks a sample list: at least two samples, finite values, time strictly increasing without gaps,
/// unit quaternions, jaw angles in range, and a spacing that agrees with the nominal rate. Errors name
/// the line the sample has in the CSV file (sample `k` on line `k + 2`).
pub fn validate_samples(samples: &[Sample], file: &str, sample_rate_hz: f64) -> Result<(), DemoError> {
    let err = |line: usize, field: &str, reason: String| DemoError::format(file, line, field, reason);
    if samples.len() < 2 {
        return Err(err(
            samples.len() + 2,
            "(rows)",
            format!("need at least 2 samples, got {}", samples.len()),
        ));
    }
    let max_gap_s = MAX_GAP_PERIODS / sample_rate_hz;
    for (k, s) in samples.iter().enumerate() {
        let line = k + 2;
        let values = [
            ("time_s", s.time_s),
            ("x_m", s.position_m.x),
            ("y_m", s.position_m.y),
            ("z_m", s.position_m.z),
            ("qx", s.quaternion_xyzw[0]),
            ("qy", s.quaternion_xyzw[1]),
            ("qz", s.quaternion_xyzw[2]),
            ("qw", s.quaternion_xyzw[3]),
            ("jaw_rad", s.jaw_rad),
            ("fx_n", s.force_n.x),
            ("fy_n", s.force_n.y),
            ("fz_n", s.force_n.z),
        ];
        if let Some((name, x)) = values.iter().find(|(_, x)| !x.is_finite()) {
            return Err(err(
                line,
                name,
                if x.is_nan() { "NaN".to_owned() } else { format!("not finite: {x}") },
            ));
        }
        if k > 0 {
            let previous = samples[k - 1].time_s;
            if s.time_s <= previous {
                return Err(err(
                    line,
                    "time_s",
                    format!(
                        "{} is not after the previous sample's {previous} (line {}): time must increase",
                        s.time_s,
                        line - 1
                    ),
                ));
            }
            if s.time_s - previous > max_gap_s {
                return Err(err(
                    line,
                    "time_s",
                    format!(
                        "a gap of {:.4} s after the previous sample (more than {MAX_GAP_PERIODS} periods at {sample_rate_hz} Hz)",
                        s.time_s - previous
                    ),
                ));
            }
        }
        for (name, x) in [("x_m", s.position_m.x), ("y_m", s.position_m.y), ("z_m", s.position_m.z)] {
            if x.abs() > MAX_POSITION_M {
                return Err(err(
                    line,
                    name,
                    format!(
                        "{x} m is beyond the workspace: an instrument tip lies within ±{MAX_POSITION_M} m"
                    ),
                ));
            }
        }
        if k > 0 {
            let before = &samples[k - 1];
            let speed = (s.position_m - before.position_m).norm() / (s.time_s - before.time_s);
            if speed > MAX_TIP_SPEED_M_S {
                return Err(err(
                    line,
                    "x_m,y_m,z_m",
                    format!(
                        "the tip moved at {speed:.3} m/s since the previous sample (line {}): at most {MAX_TIP_SPEED_M_S} m/s",
                        line - 1
                    ),
                ));
            }
        }
        let norm = s.quaternion_xyzw.iter().map(|x| x * x).sum::<f64>().sqrt();
        if (norm - 1.0).abs() > QUATERNION_NORM_TOLERANCE {
            return Err(err(line, "qx,qy,qz,qw", format!("not a unit quaternion (norm {norm:.6})")));
        }
        if !(JAW_RANGE_RAD.0..=JAW_RANGE_RAD.1).contains(&s.jaw_rad) {
            return Err(err(
                line,
                "jaw_rad",
                format!("{} outside [{}, {}] rad", s.jaw_rad, JAW_RANGE_RAD.0, JAW_RANGE_RAD.1),
            ));
        }
    }
    let mut steps: Vec<f64> = samples.windows(2).map(|w| w[1].time_s - w[0].time_s).collect();
    steps.sort_by(f64::total_cmp);
    let median_step_s = steps[steps.len() / 2];
    let nominal_s = 1.0 / sample_rate_hz;
    if !(0.8 * nominal_s..=1.25 * nominal_s).contains(&median_step_s) {
        return Err(err(
            0,
            "time_s",
            format!(
                "the samples are {median_step_s:.6} s apart (median), but sample_rate_hz = {sample_rate_hz} in demo.toml says {nominal_s:.6} s"
            ),
        ));
    }
    Ok(())
}

//! One instrument's CSV file: a header naming the columns, then one sample per line. Reading checks
//! every row (field count, numbers, NaN, the grasp word, time increasing, unit quaternions) and names the
//! line and the column of the first problem; writing prints every number so it reads back to the same
//! bits.

use nalgebra::Vector3;

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

/// The CSV text of a sample list, header included, every line ended by a newline.
pub fn render_samples(samples: &[Sample]) -> String {
    let mut out = String::with_capacity(samples.len() * 200 + 100);
    out.push_str(&COLUMNS.join(","));
    out.push('\n');
    for s in samples {
        let p = s.position_m;
        let q = s.quaternion_xyzw;
        let f = s.force_n;
        out.push_str(&format!(
            "{:?},{:?},{:?},{:?},{:?},{:?},{:?},{:?},{:?},{},{:?},{:?},{:?}\n",
            s.time_s,
            p.x,
            p.y,
            p.z,
            q[0],
            q[1],
            q[2],
            q[3],
            s.jaw_rad,
            s.grasp.as_str(),
            f.x,
            f.y,
            f.z
        ));
    }
    out
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
    let ends_with_newline = text.ends_with('\n');
    let lines: Vec<&str> = text.strip_suffix('\n').unwrap_or(text).split('\n').collect();
    let last_line = lines.len();
    let trim = |l: &str| l.strip_suffix('\r').unwrap_or(l).to_owned();

    let header: Vec<String> = trim(lines[0]).split(',').map(|h| h.trim().to_owned()).collect();
    if !ends_with_newline && last_line == 1 {
        return Err(err(1, "(header)", "the file ends inside its header line: truncated".to_owned()));
    }
    for (k, name) in header.iter().enumerate() {
        if header[..k].contains(name) {
            return Err(err(1, name, "column appears twice".to_owned()));
        }
    }
    let mut index = [0usize; COLUMNS.len()];
    for (slot, column) in index.iter_mut().zip(COLUMNS) {
        *slot = header.iter().position(|h| h == column).ok_or_else(|| {
            err(1, column, format!("missing column (the header has: {})", header.join(",")))
        })?;
    }

    let mut samples = Vec::with_capacity(expected_samples.min(10_000_000));
    for (k, raw) in lines.iter().enumerate().skip(1) {
        let line = k + 1;
        let is_last = line == last_line;
        let row = trim(raw);
        let fields: Vec<&str> = row.split(',').collect();
        if is_last && !ends_with_newline {
            // The field the file ends in (a required one, or the header's name of another).
            let cut = fields.len() - 1;
            let field = COLUMNS
                .iter()
                .zip(index)
                .find(|(_, i)| *i == cut)
                .map_or_else(|| header.get(cut).map_or("(row)", String::as_str), |(c, _)| c);
            return Err(err(
                line,
                field,
                format!(
                    "the file ends inside this row ({} of {} fields, no final newline): truncated",
                    fields.len(),
                    header.len()
                ),
            ));
        }
        if row.trim().is_empty() {
            return Err(err(line, "(row)", "empty line".to_owned()));
        }
        if fields.len() != header.len() {
            let missing = COLUMNS.iter().zip(index).find(|(_, i)| *i >= fields.len()).map(|(c, _)| *c);
            return Err(err(
                line,
                missing.unwrap_or("(row)"),
                format!("{} fields, the header has {}", fields.len(), header.len()),
            ));
        }
        let number = |c: usize| -> Result<f64, DemoError> {
            let text = fields[index[c]].trim();
            let x: f64 =
                text.parse().map_err(|_| err(line, COLUMNS[c], format!("not a number: '{text}'")))?;
            if x.is_nan() {
                return Err(err(line, COLUMNS[c], "NaN".to_owned()));
            }
            if !x.is_finite() {
                return Err(err(line, COLUMNS[c], format!("not finite: {text}")));
            }
            Ok(x)
        };
        let grasp_text = fields[index[9]].trim();
        let grasp = GraspState::parse(grasp_text).ok_or_else(|| {
            err(line, "grasp", format!("'{grasp_text}' is not one of open, holding, closed_empty"))
        })?;
        samples.push(Sample {
            time_s: number(0)?,
            position_m: Vector3::new(number(1)?, number(2)?, number(3)?),
            quaternion_xyzw: [number(4)?, number(5)?, number(6)?, number(7)?],
            jaw_rad: number(8)?,
            grasp,
            force_n: Vector3::new(number(10)?, number(11)?, number(12)?),
        });
    }
    if samples.len() < expected_samples {
        return Err(err(
            last_line + 1,
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

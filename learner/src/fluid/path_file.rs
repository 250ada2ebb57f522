//! Reading a 2D primitive's path from a CSV file: `x_m,y_m,speed_mps` per line in plane
//! coordinates, a header line, blank lines and `#` comments allowed. Problems name the line.

use nalgebra::Vector2;

use super::path::SpeedPath;

/// Most points a path file may hold.
pub const MAX_PATH_POINTS: usize = 1_000_000;

/// Why a path file's text is not a path: the 1-based line (0 for the path as a whole) and what is
/// wrong.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{}{reason}", if *line == 0 { String::new() } else { format!("{line}: ") })]
pub struct PathFileError {
    /// 1-based line, 0 when the problem is the whole path's (too few points, no length).
    pub line: usize,
    /// What is wrong.
    pub reason: String,
}

/// Parses a path file's text.
pub fn parse_speed_path(text: &str) -> Result<SpeedPath, PathFileError> {
    let (mut points, mut speeds) = (Vec::new(), Vec::new());
    for (number, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') || line.chars().next().is_some_and(char::is_alphabetic) {
            continue;
        }
        let problem = |reason: String| PathFileError { line: number + 1, reason };
        let values = line
            .split(',')
            .map(|item| match item.trim().parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(v),
                Ok(_) => Err(problem(format!("'{}' is not a finite number", item.trim()))),
                Err(_) => Err(problem(format!("'{}' is not a number", item.trim()))),
            })
            .collect::<Result<Vec<f64>, _>>()?;
        let [x, y, v] = values[..] else {
            return Err(problem(format!("expected x_m,y_m,speed_mps, got {} numbers", values.len())));
        };
        if points.len() == MAX_PATH_POINTS {
            return Err(problem(format!("more than {MAX_PATH_POINTS} points")));
        }
        points.push(Vector2::new(x, y));
        speeds.push(v);
    }
    SpeedPath::new(points, speeds).map_err(|e| PathFileError { line: 0, reason: e.to_string() })
}

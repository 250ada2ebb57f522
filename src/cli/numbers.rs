//! Parsing comma-separated numbers from the command line.

use nalgebra::Vector3;

/// A comma-separated list of numbers (an alias, so that clap takes it as one value).
pub type Numbers = Vec<f64>;

/// Parses `a,b,c,...` into finite numbers.
pub fn parse_list(text: &str) -> Result<Vec<f64>, String> {
    text.split(',')
        .map(|item| {
            let item = item.trim();
            match item.parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(v),
                Ok(_) => Err(format!("'{item}' is not a finite number")),
                Err(_) => Err(format!("'{item}' is not a number")),
            }
        })
        .collect()
}

/// Parses `x,y,z`.
pub fn parse_vector3(text: &str) -> Result<Vector3<f64>, String> {
    match parse_list(text)?.as_slice() {
        [x, y, z] => Ok(Vector3::new(*x, *y, *z)),
        other => Err(format!("expected 3 comma-separated numbers x,y,z, got {}", other.len())),
    }
}

//! The fluid path file parser (`knotlab fluid primitive --path-file`) on a mutated double loop and raw
//! text.

use std::f64::consts::TAU;
use std::sync::Arc;

use knotlab_learner::fluid::path_file::parse_speed_path;

use super::mutate::{mutated_text, raw_text};
use super::{cases, fuzz, isolated};

/// A double loop of 120 points, 12 mm across, at 20 mm/s, with a header and a comment.
fn seeds() -> Vec<Arc<str>> {
    let mut text = String::from("# a double loop\nx_m,y_m,speed_mps\n");
    for i in 0..120 {
        let t = 2.0 * TAU * f64::from(i) / 120.0;
        let r = if i < 60 { 0.012 } else { 0.008 };
        text += &format!("{},{},0.02\n", r * t.cos(), r * t.sin());
    }
    vec![Arc::from(text)]
}

fn parse(text: &str) -> Result<(), String> {
    parse_speed_path(text).map(|_| ()).map_err(|e| e.to_string())
}

/// The path parser never panics on a mutated path file (numbers, fields, lines, bytes) or on raw text,
/// and names the problem of what it refuses.
#[test]
fn fluid_path_parser_survives_mutated_and_random_input() {
    isolated(|| {
        let seeds = seeds();
        for text in &seeds {
            assert!(parse(text).is_ok(), "the seed parses: {:?}", parse(text).err());
        }
        fuzz("fluid-path/text", cases(), mutated_text(seeds.clone()), |(_, text)| parse(text));
        fuzz("fluid-path/raw", cases(), raw_text(seeds), |text| parse(text));
    });
}

//! The centreline CSV parser on mutated torus knots and raw text, and the knot classifier on what it
//! reads and on generated point sets (degenerate, huge, tiny, nearly repeated).

use std::f64::consts::TAU;
use std::sync::Arc;

use nalgebra::Vector3;
use proptest::collection::vec;
use proptest::prelude::*;
use proptest::sample::select;

use knotlab_sim::knot::classify;
use knotlab_sim::knot::csv::parse_points;

use super::mutate::{mutated_text, raw_text};
use super::{Outcome, cases, fuzz, isolated, outcome};

/// The classifier runs on centrelines of at most this many points (to keep the cases quick).
const MAX_CLASSIFIED: usize = 2000;

/// A centreline CSV with a header: the (2, q) torus knot of `n` points, 2 mm across, 0.8 m up.
fn torus_csv(q: f64, n: usize) -> String {
    let mut text = String::from("x,y,z\n");
    for i in 0..n {
        let t = TAU * i as f64 / n as f64;
        let r = 2.0 + (q * t).cos();
        let (x, y, z) = (r * (2.0 * t).cos(), r * (2.0 * t).sin(), (q * t).sin());
        text += &format!("{},{},{}\n", x * 0.002, y * 0.002, 0.8 + z * 0.002);
    }
    text
}

/// A trefoil, a cinquefoil, and a trefoil with comments, blank lines and CRLF endings.
fn seeds() -> Vec<Arc<str>> {
    let commented = format!("# a trefoil\n\n{}", torus_csv(3.0, 60).replace('\n', "\r\n"));
    [torus_csv(3.0, 200), torus_csv(5.0, 250), commented].into_iter().map(Arc::from).collect()
}

/// Parses `text`; the line problem's message is the error's.
fn parse(text: &str) -> Result<Vec<Vector3<f64>>, String> {
    parse_points(text).map_err(|(_, problem)| problem.to_string())
}

/// Parses `text` and classifies what it reads (up to [`MAX_CLASSIFIED`] points).
fn parse_and_classify(text: &str) -> Outcome {
    let points = parse(text)?;
    if points.len() > MAX_CLASSIFIED {
        return Ok(());
    }
    outcome(classify(&points))
}

/// The centreline parser never panics on a mutated torus knot CSV (numbers, fields, lines, bytes) or
/// on raw text, and names the problem of what it refuses.
#[test]
fn knot_csv_parser_survives_mutated_and_random_input() {
    isolated(|| {
        let seeds = seeds();
        for text in &seeds {
            assert!(parse(text).is_ok(), "the seed parses: {:?}", parse(text).err());
        }
        fuzz("knot-csv/text", 2 * cases(), mutated_text(seeds.clone()), |(_, text)| parse(text).map(|_| ()));
        fuzz("knot-csv/raw", 2 * cases(), raw_text(seeds), |text| parse(text).map(|_| ()));
    });
}

/// A coordinate: ordinary, or one a classifier's arithmetic must survive.
fn coordinate() -> impl Strategy<Value = f64> {
    prop_oneof![
        6 => -1.0..1.0f64,
        1 => select(&[0.0, -0.0, 1e300, -1e300, 1e-300, 5e-324, f64::MAX, f64::MIN, f64::MIN_POSITIVE][..]),
    ]
}

/// A point set: random points, points on one line, a torus knot scaled or perturbed, or one with a
/// point repeated further on.
fn point_set() -> impl Strategy<Value = Vec<[f64; 3]>> {
    let torus = |q: f64, n: usize| -> Vec<[f64; 3]> {
        (0..n)
            .map(|i| {
                let t = TAU * i as f64 / n as f64;
                let r = 2.0 + (q * t).cos();
                [r * (2.0 * t).cos(), r * (2.0 * t).sin(), (q * t).sin()]
            })
            .collect()
    };
    prop_oneof![
        3 => vec([coordinate(), coordinate(), coordinate()], 0..300),
        1 => (vec(-1.0..1.0f64, 4..200), coordinate()).prop_map(|(ts, s)| ts.iter().map(|t| [t * s, 2.0 * t * s, 0.0]).collect()),
        2 => (select(&[3.0, 5.0, 7.0][..]), 4..400usize, select(&[1.0, 1e-300, 1e300, 1e-9][..]), vec(-1e-12..1e-12f64, 3))
            .prop_map(move |(q, n, scale, jitter)| torus(q, n)
                .into_iter()
                .enumerate()
                .map(|(i, p)| std::array::from_fn(|a| (p[a] + jitter[a] * (i % 3) as f64) * scale))
                .collect()),
        1 => (select(&[3.0, 5.0][..]), 8..200usize, any::<proptest::sample::Index>(), any::<proptest::sample::Index>())
            .prop_map(move |(q, n, a, b)| {
                let mut points = torus(q, n);
                let (a, b) = (a.index(n), b.index(n));
                if a.abs_diff(b) > 1 {
                    points[b] = points[a];
                }
                points
            }),
    ]
}

/// The classifier never panics on what the parser reads from a mutated knot CSV or on generated point
/// sets (random, collinear, 1e300 or 1e-300 across, a point repeated), and names what it refuses.
#[test]
fn knot_classifier_survives_parsed_and_generated_centrelines() {
    isolated(|| {
        fuzz("knot-classify/text", cases() / 10, mutated_text(seeds()), |(_, text)| parse_and_classify(text));
        fuzz("knot-classify/points", cases() / 10, point_set(), |points| {
            let text: String = std::iter::once("x,y,z\n".to_owned())
                .chain(points.iter().map(|p| format!("{:e},{:e},{:e}\n", p[0], p[1], p[2])))
                .collect();
            parse_and_classify(&text)
        });
    });
}

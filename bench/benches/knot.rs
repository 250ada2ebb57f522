//! Benchmark: classifying a 200-point thread's centreline (target: at most 1 ms), and a 10,000-point
//! one (target: under 1 s).
//!
//! `cargo bench -p knotlab-bench --bench knot` times one `classify` call (13 projection directions,
//! closure, crossings, reduction, determinant, vote) per thread shape with divan, each call on the
//! next of 32 seeded perturbations of the thread; the long centrelines (a random walk, heavily
//! knotted, and a helix of 100 turns, an unknot whose pictures along its axis cross thousands of
//! times) once each.

use std::f64::consts::{PI, TAU};
use std::hint::black_box;

use knotlab_sim::knot::classify;
use nalgebra::Vector3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

type V = Vector3<f64>;

const POINTS: usize = 200;
const VARIANTS: usize = 32;

/// Resamples a polyline to `n` points evenly spaced along its length.
fn resample(points: &[V], n: usize) -> Vec<V> {
    let mut arc = vec![0.0];
    for w in points.windows(2) {
        arc.push(arc[arc.len() - 1] + (w[1] - w[0]).norm());
    }
    let total = arc[arc.len() - 1];
    let mut seg = 0;
    (0..n)
        .map(|i| {
            let s = total * i as f64 / (n - 1) as f64;
            while seg + 2 < arc.len() && arc[seg + 1] < s {
                seg += 1;
            }
            let f = ((s - arc[seg]) / (arc[seg + 1] - arc[seg])).clamp(0.0, 1.0);
            points[seg] + (points[seg + 1] - points[seg]) * f
        })
        .collect()
}

/// A 4 mm trefoil: the (2, 3) torus knot cut open on its rim.
fn trefoil() -> Vec<V> {
    (0..POINTS)
        .map(|i| {
            let t = TAU * i as f64 / POINTS as f64;
            let r = 2.0 + (3.0 * t).cos();
            V::new(r * (2.0 * t).cos(), r * (2.0 * t).sin(), (3.0 * t).sin()) * 0.001
        })
        .collect()
}

/// A square knot as a suture ties it: two opposite throws (3 half-twists each) stacked over the
/// bite, the ends leaving upward; about 3 cm of thread.
fn square_suture() -> Vec<V> {
    let mut points = vec![V::new(-4.0, 9.0, 0.0), V::new(-1.5, 3.9, 0.0)];
    let twist = |points: &mut Vec<V>, y: f64, k: f64, strand: f64, from_west: bool| {
        for i in 0..=40 {
            let f = f64::from(i) / 40.0;
            let x = if from_west { -1.0 + 2.0 * f } else { 1.0 - 2.0 * f };
            let phi = strand * PI + k * PI * (x + 1.0) / 2.0;
            points.push(V::new(x, y + 0.5 * phi.cos(), 0.5 * phi.sin()));
        }
    };
    // Upper throw west-top to east-bottom, down the east side, lower throw east-top to west-bottom,
    // the bite, lower throw east-bottom to west-top, up the west side, upper throw to east-top.
    twist(&mut points, 3.0, -3.0, 0.0, true);
    points.extend([V::new(1.5, 2.1, 0.0), V::new(1.5, 0.9, 0.0)]);
    twist(&mut points, 0.0, 3.0, 1.0, false);
    points.extend([
        V::new(-1.5, -0.9, 0.0),
        V::new(-1.5, -3.0, 0.0),
        V::new(1.5, -3.0, 0.0),
        V::new(1.5, -0.9, 0.0),
    ]);
    twist(&mut points, 0.0, 3.0, 0.0, false);
    points.extend([V::new(-1.5, 0.9, 0.0), V::new(-1.5, 2.1, 0.0)]);
    twist(&mut points, 3.0, -3.0, 1.0, true);
    points.extend([V::new(1.5, 3.9, 0.0), V::new(4.0, 9.0, 0.0)]);
    resample(&points, POINTS).into_iter().map(|p| p * 0.001).collect()
}

/// An untied 10 cm thread lying in loose waves.
fn untied() -> Vec<V> {
    (0..POINTS)
        .map(|i| {
            let x = 0.1 * i as f64 / POINTS as f64;
            V::new(x, 0.01 * (x * 90.0).sin(), 0.002 * (x * 40.0).cos())
        })
        .collect()
}

fn main() {
    divan::main();
}

/// The shapes timed.
const SHAPES: [&str; 3] = ["trefoil", "square suture", "untied thread"];

/// One `classify` call on the next perturbation of `shape`.
#[divan::bench(args = SHAPES)]
fn classify_centreline(bencher: divan::Bencher, shape: &str) {
    let points = match shape {
        "trefoil" => trefoil(),
        "square suture" => square_suture(),
        _ => untied(),
    };
    let mut rng = ChaCha8Rng::seed_from_u64(20_261_124);
    let variants: Vec<Vec<V>> = (0..VARIANTS)
        .map(|_| points.iter().map(|p| p + V::from_fn(|_, _| rng.random_range(-1e-5..1e-5))).collect())
        .collect();
    bencher
        .with_inputs(knotlab_bench::round_robin(variants.len()))
        .bench_local_values(|i| classify(black_box(&variants[i])));
}

/// The long centrelines timed.
const LONG: [&str; 2] = ["random walk", "helix"];

/// One `classify` call on a 10,000-point centreline.
#[divan::bench(args = LONG, sample_count = 5, sample_size = 1)]
fn classify_10000_points(bencher: divan::Bencher, shape: &str) {
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let points: Vec<V> = match shape {
        "random walk" => {
            let mut walk = vec![V::zeros()];
            for _ in 1..10_000 {
                let last = walk[walk.len() - 1];
                walk.push(last + V::from_fn(|_, _| rng.random_range(-1e-3..1e-3)));
            }
            walk
        }
        _ => (0..10_000)
            .map(|k| {
                let t = TAU * k as f64 / 100.0;
                V::new(0.01 * t.cos(), 0.01 * t.sin(), 1e-6 * k as f64)
            })
            .collect(),
    };
    bencher.bench_local(|| classify(black_box(&points)));
}

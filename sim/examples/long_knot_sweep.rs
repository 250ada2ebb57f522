//! The long overhand knots of `knotlab validate` (the (2, 2n+1) torus knots, n the braid's turns)
//! tightened at one friction after another on a scene's suture: the shortening seated and at the
//! ramp's end, how many samples the knot slid in and over which `n^2 h / e`, and the median (and
//! range) of the pull over the law's force among them (Jawed et al. 2015):
//!
//! ```text
//! cargo run --release -p knotlab-sim --example long_knot_sweep [SCENE [TURNS [RAMP_S [MU ...]]]]
//! ```
//!
//! SCENE defaults to `scenarios/default.toml`, TURNS to 2, RAMP_S (how long the pull takes to rise
//! from the seating load to the tightest, s) to 60, the frictions to the paper's fit 0.119 and 0.5.

use knotlab_sim::scene::parse_scene;
use knotlab_sim::validation::SutureUnderTest;
use knotlab_sim::validation::long_knot::tighten;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let path = args.first().cloned().unwrap_or_else(|| "scenarios/default.toml".to_owned());
    let turns = match args.get(1).map(|a| a.parse::<usize>()) {
        None => 2,
        Some(Ok(n)) if (1..=6).contains(&n) => n,
        Some(_) => {
            eprintln!("long_knot_sweep: TURNS must be a whole number from 1 to 6, got {:?}", args[1]);
            std::process::exit(2);
        }
    };
    let ramp_s = match args.get(2).map(|a| a.parse::<f64>()) {
        None => 60.0,
        Some(Ok(s)) if s.is_finite() && s > 0.0 && s <= 3600.0 => s,
        Some(_) => {
            eprintln!("long_knot_sweep: RAMP_S must be seconds in (0, 3600], got {:?}", args[2]);
            std::process::exit(2);
        }
    };
    let frictions: Vec<f64> = if args.len() > 3 {
        args[3..]
            .iter()
            .map(|a| match a.parse::<f64>() {
                Ok(mu) if mu.is_finite() && mu > 0.0 => mu,
                _ => {
                    eprintln!("long_knot_sweep: MU must be a friction coefficient > 0, got {a:?}");
                    std::process::exit(2);
                }
            })
            .collect()
    } else {
        vec![0.119, 0.5]
    };
    let text = match std::fs::read_to_string(&path) {
        Ok(t) => t,
        Err(e) => {
            eprintln!("long_knot_sweep: cannot read {path}: {e}");
            std::process::exit(2);
        }
    };
    let scene = match parse_scene(&text, &path) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("long_knot_sweep: {e}");
            std::process::exit(2);
        }
    };
    let suture = match SutureUnderTest::from_scene(&scene) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("long_knot_sweep: {path}: {e}");
            std::process::exit(2);
        }
    };
    println!(
        "| turns | mu | seated e, mm | end e, mm | sliding samples | n2h/e sampled | pull over the law's force: median (range) |"
    );
    println!("|---|---|---|---|---|---|---|");
    for mu in frictions {
        match tighten(&suture, turns, mu, ramp_s) {
            Ok(t) => {
                let ratios: Vec<f64> = t.sliding.iter().map(|s| s.force_n / s.law_n).collect();
                let (lo, hi) = ratios
                    .iter()
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), r| (a.min(*r), b.max(*r)));
                let (slo, shi) = t.sliding.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), s| {
                    (a.min(s.n2h_over_e), b.max(s.n2h_over_e))
                });
                println!(
                    "| {turns} | {mu} | {:.1} | {:.1} | {} | {slo:.4}-{shi:.4} | {:.3} ({lo:.3}-{hi:.3}) |",
                    t.seated_m * 1e3,
                    t.end_m * 1e3,
                    t.sliding.len(),
                    t.median_ratio()
                );
            }
            Err(void) => println!("| {turns} | {mu} | | | | | {void} |"),
        }
    }
}

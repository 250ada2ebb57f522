//! Validation of the Navier-Stokes solver against Ghia, Ghia and Shin (1982): the lid-driven cavity at
//! n = 128 run to its steady state, centreline velocities within 0.02 (Re 100) and 0.03 (Re 1000) of the
//! table in scenarios/reference/ghia1982-cavity.csv (a copy of shared/reference), and the divergence
//! after every step below the pressure solve's tolerance.

use std::path::PathBuf;

use knotlab_learner::fluid::{CavityConfig, GHIA_U_Y, GHIA_V_X, run_cavity};

/// One row of the reference table: profile, coordinate, value at Re 100, value at Re 1000.
struct Row {
    profile: String,
    coord: f64,
    re100: f64,
    re1000: f64,
}

fn reference() -> Vec<Row> {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../scenarios/reference/ghia1982-cavity.csv");
    let text = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("the Ghia table {} is needed beside the repository: {e}", path.display()));
    let mut rows = Vec::new();
    for (number, line) in text.lines().enumerate() {
        if line.starts_with('#') || line.starts_with("profile") || line.trim().is_empty() {
            continue;
        }
        let fields: Vec<&str> = line.split(',').collect();
        assert_eq!(fields.len(), 4, "{}:{}: {line}", path.display(), number + 1);
        let number = |s: &str| s.trim().parse::<f64>().unwrap_or_else(|e| panic!("line {}: {e}", number + 1));
        rows.push(Row {
            profile: fields[0].to_owned(),
            coord: number(fields[1]),
            re100: number(fields[2]),
            re1000: number(fields[3]),
        });
    }
    assert_eq!(rows.len(), 34, "17 u and 17 v stations expected");
    rows
}

/// Runs the cavity at `re` on 128 x 128 cells and returns the largest error against Ghia et al.
fn validate(re: f64, tolerance: f64) {
    let config = CavityConfig::new(re, 128);
    let mut steps = 0;
    let mut worst_divergence = 0.0f64;
    let run = run_cavity(&config, |step| {
        steps += 1;
        assert!(
            step.max_divergence_per_s <= config.divergence_tol,
            "step {steps}: divergence {:.3e} above the tolerance {:.1e}",
            step.max_divergence_per_s,
            config.divergence_tol
        );
        worst_divergence = worst_divergence.max(step.max_divergence_per_s);
    })
    .expect("cavity run");
    assert!(
        run.steady,
        "Re {re}: no steady state by t = {} (last acceleration {})",
        config.max_time, run.final_acceleration
    );
    assert_eq!(steps, run.steps);
    // The independent check: the final field's divergence, measured again.
    assert!(run.sim.max_divergence() <= config.divergence_tol);
    let mut worst = (0.0f64, String::new());
    for row in reference() {
        let want = if re == 100.0 { row.re100 } else { row.re1000 };
        let got = match row.profile.as_str() {
            "u" => run.u_centreline(row.coord),
            "v" => run.v_centreline(row.coord),
            other => panic!("unknown profile {other}"),
        };
        let error = (got - want).abs();
        if error > worst.0 {
            worst = (error, format!("{} at {}: {got:.5} against {want:.5}", row.profile, row.coord));
        }
    }
    println!(
        "Re {re}, n 128: {} steps (+{} on coarser grids), t = {:.2}, largest error {:.4} ({}), largest divergence {:.2e}",
        run.steps,
        run.coarse_steps,
        run.sim.time_s(),
        worst.0,
        worst.1,
        worst_divergence
    );
    assert!(worst.0 <= tolerance, "Re {re}: largest error {:.4} > {tolerance}: {}", worst.0, worst.1);
}

/// The lid-driven cavity at Re 100 on 128 cells reaches a steady state within 0.02 of Ghia et al.'s
/// centreline velocities, its divergence below the tolerance after every step.
#[test]
fn ghia_re100_at_128_within_0_02() {
    validate(100.0, 0.02);
}

/// The lid-driven cavity at Re 1000 on 128 cells reaches a steady state within 0.03 of Ghia et al.'s
/// centreline velocities, its divergence below the tolerance after every step.
#[test]
fn ghia_re1000_at_128_within_0_03() {
    validate(1000.0, 0.03);
}

/// The built-in stations `GHIA_U_Y` and `GHIA_V_X` are exactly the coordinates of the reference table.
#[test]
fn the_built_in_stations_are_ghias() {
    let rows = reference();
    let u: Vec<f64> = rows.iter().filter(|r| r.profile == "u").map(|r| r.coord).collect();
    let v: Vec<f64> = rows.iter().filter(|r| r.profile == "v").map(|r| r.coord).collect();
    assert_eq!(u, GHIA_U_Y.to_vec());
    assert_eq!(v, GHIA_V_X.to_vec());
}

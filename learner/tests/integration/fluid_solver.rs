//! The Navier-Stokes solver's parts: the obstacle rule and its repair, the two pressure solvers against
//! each other, the divergence left after every step with obstacles and stirring presets, determinism, and
//! the errors for bad input and an unconverged pressure solve.

use knotlab_learner::fluid::flags::Flags;
use knotlab_learner::fluid::pressure::{DirectSolver, SorSolver, max_residual};
use knotlab_learner::fluid::{
    Component, DonorCell, FacePreset, FluidError, FluidParams, FluidSim, ObstacleMask, PressureSolverKind,
    Walls,
};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn params(solver: PressureSolverKind) -> FluidParams {
    FluidParams {
        viscosity_m2ps: 0.01,
        donor_cell: DonorCell::Fixed(0.9),
        tau: 0.5,
        divergence_tol_per_s: 1e-7,
        solver,
        max_sor_iterations: 100_000,
    }
}

/// A mask with random boxes and single cells, repaired.
fn random_mask(n: usize, seed: u64) -> ObstacleMask {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut mask = ObstacleMask::free(n);
    for _ in 0..6 {
        let (w, h) = (rng.random_range(1..6), rng.random_range(1..6));
        let (i0, j0) = (rng.random_range(2..n - 8), rng.random_range(2..n - 8));
        for j in j0..j0 + h {
            for i in i0..i0 + w {
                mask.set(i, j, true);
            }
        }
    }
    for _ in 0..10 {
        mask.set(rng.random_range(0..n), rng.random_range(0..n), true);
    }
    mask.repaired().mask
}

/// Repair grows a lone obstacle cell to a 2 x 2 block and a one-cell wall to two cells thick, never frees
/// a blocked cell, and leaves a mask the flags accept where before they refused it.
#[test]
fn repair_grows_obstacles_until_no_cell_has_fluid_on_opposite_sides() {
    let mut mask = ObstacleMask::free(10);
    mask.set(3, 3, true); // a lone cell
    for j in 0..10 {
        mask.set(7, j, true); // a one-cell wall across the grid
    }
    assert_eq!(mask.violations().len(), 11);
    assert!(matches!(Flags::new(&mask, 0.1), Err(FluidError::Invalid { field, .. }) if field == "mask"));
    let repair = mask.repaired();
    assert!(repair.mask.violations().is_empty());
    // Never shrinks: every blocked cell stays blocked.
    assert!(mask.blocked.iter().zip(&repair.mask.blocked).all(|(before, after)| !before || *after));
    // The lone cell became a 2 x 2 block, the wall two cells thick.
    for (i, j) in [(3, 3), (4, 3), (3, 4), (4, 4)] {
        assert!(repair.mask.get(i, j), "({i}, {j}) not blocked");
    }
    assert!((0..10).all(|j| repair.mask.get(8, j)));
    assert_eq!(repair.added_cells, repair.mask.count_blocked() - mask.count_blocked());
    assert_eq!(repair.added_cells, 3 + 10);
    assert!(Flags::new(&repair.mask, 0.1).is_ok());
}

/// Repaired random masks have no violations and no boundary cell with fluid on two opposite sides.
#[test]
fn random_masks_repair_to_valid_flags() {
    for seed in 0..200 {
        let mask = random_mask(24, seed);
        assert!(mask.violations().is_empty(), "seed {seed}");
        let flags = Flags::new(&mask, 0.01).expect("valid flags");
        for &(_, sides) in &flags.boundary {
            assert_ne!(sides & 3, 3, "north and south");
            assert_ne!(sides & 12, 12, "east and west");
        }
    }
}

/// On random obstacle masks the SOR and direct pressure solvers each reach their tolerance and agree up
/// to one constant per connected fluid region.
#[test]
fn sor_and_direct_agree_and_reach_their_tolerance() {
    for seed in 0..5 {
        let mask = random_mask(32, seed);
        let flags = Flags::new(&mask, 1.0 / 32.0).expect("flags");
        let grid = flags.grid;
        let mut rng = ChaCha8Rng::seed_from_u64(100 + seed);
        // A compatible right-hand side: the divergence of a random face field that is zero on walls and
        // obstacles.
        let mut f = vec![0.0; grid.len()];
        let mut g = vec![0.0; grid.len()];
        for k in 0..grid.len() {
            if flags.u_fluid[k] {
                f[k] = rng.random_range(-1.0..1.0);
            }
            if flags.v_fluid[k] {
                g[k] = rng.random_range(-1.0..1.0);
            }
        }
        let mut rhs = vec![0.0; grid.len()];
        knotlab_learner::fluid::momentum::compute_rhs(&flags, &f, &g, 0.01, &mut rhs);
        let mut p_direct = vec![0.0; grid.len()];
        DirectSolver::new(&flags).expect("factor").solve(&flags, &rhs, &mut p_direct);
        let direct_residual = max_residual(&flags, &rhs, &p_direct);
        let scale = rhs.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        assert!(direct_residual <= 1e-9 * scale, "seed {seed}: direct residual {direct_residual:.3e}");
        let mut p_sor = vec![0.0; grid.len()];
        let tol = 1e-8 * scale;
        let solve = SorSolver::new(&flags).solve(&flags, &rhs, &mut p_sor, tol, 100_000);
        assert!(
            solve.max_residual_per_s2 <= tol,
            "seed {seed}: SOR stopped at {:.3e}",
            solve.max_residual_per_s2
        );
        assert!(solve.iterations > 10);
        // Same pressure up to one constant per connected fluid region.
        let mut offset = vec![None; flags.regions];
        let mut worst = 0.0f64;
        for k in 0..grid.len() {
            if flags.fluid[k] {
                let r = flags.region[k] as usize;
                let c = *offset[r].get_or_insert(p_sor[k] - p_direct[k]);
                worst = worst.max((p_sor[k] - p_direct[k] - c).abs());
            }
        }
        let p_scale = p_direct.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        assert!(
            worst <= 1e-5 * p_scale,
            "seed {seed}: pressures differ by {worst:.3e} (scale {p_scale:.3e})"
        );
    }
}

/// A stirred flow around random obstacles: both solvers keep the divergence below the tolerance after
/// every step, measured from the velocities.
#[test]
fn every_step_leaves_the_divergence_below_the_tolerance() {
    for solver in [PressureSolverKind::Sor, PressureSolverKind::Direct] {
        let mask = random_mask(32, 7);
        let mut sim =
            FluidSim::new(&mask, 1.0 / 32.0, Walls { top_u_mps: 1.0, ..Walls::default() }, params(solver))
                .expect("sim");
        let flags = sim.flags().clone();
        let faces: Vec<usize> = (0..flags.grid.len()).filter(|&k| flags.u_fluid[k]).take(400).collect();
        for step in 0..40 {
            let k = faces[(step * 7) % faces.len()];
            let presets = vec![FacePreset { component: Component::U, index: k, velocity_mps: 0.5 }];
            let report = sim.step_with_presets(sim.stable_dt(), presets).expect("step");
            assert!(
                report.max_divergence_per_s <= 1e-7,
                "{solver:?} step {step}: {}",
                report.max_divergence_per_s
            );
            assert!(report.pressure_iterations >= 1);
        }
        // Away from the preset face the field is still divergence-free.
        assert!(sim.time_s() > 0.0);
    }
}

/// Two runs of the same flow give the same velocities and pressures bit for bit, and the flow does move.
#[test]
fn the_same_input_gives_the_same_bits() {
    let run = || {
        let mask = random_mask(24, 3);
        let mut sim = FluidSim::new(
            &mask,
            0.01,
            Walls { top_u_mps: 0.1, ..Walls::default() },
            params(PressureSolverKind::Direct),
        )
        .expect("sim");
        for _ in 0..30 {
            sim.step(sim.stable_dt()).expect("step");
        }
        (sim.u().to_vec(), sim.v().to_vec(), sim.p().to_vec())
    };
    let (a, b) = (run(), run());
    assert!(a.0.iter().zip(&b.0).all(|(x, y)| x.to_bits() == y.to_bits()));
    assert!(a.1.iter().zip(&b.1).all(|(x, y)| x.to_bits() == y.to_bits()));
    assert!(a.2.iter().zip(&b.2).all(|(x, y)| x.to_bits() == y.to_bits()));
    assert!(a.0.iter().any(|x| *x != 0.0), "the flow moved");
}

/// An SOR pressure solve cut off at 2 sweeps is a `PressureNotConverged` error naming the solver, not a
/// step taken with the divergence left in.
#[test]
fn an_unconverged_pressure_solve_is_an_error_not_a_silent_step() {
    let mut p = params(PressureSolverKind::Sor);
    p.max_sor_iterations = 2;
    let mut sim =
        FluidSim::new(&ObstacleMask::free(32), 1.0 / 32.0, Walls { top_u_mps: 1.0, ..Walls::default() }, p)
            .expect("sim");
    let error = (0..5).find_map(|_| sim.step(sim.stable_dt()).err()).expect("SOR with 2 sweeps must fail");
    match error {
        FluidError::PressureNotConverged {
            solver, divergence_per_s, tolerance_per_s, iterations, ..
        } => {
            assert_eq!(solver, "sor");
            assert_eq!(iterations, 2);
            assert!(divergence_per_s > tolerance_per_s);
        }
        other => panic!("unexpected error {other}"),
    }
}

/// A fluid pocket enclosed by obstacles is solved as a second region with the divergence in tolerance,
/// and, undriven, stays at rest.
#[test]
fn an_enclosed_fluid_pocket_is_solved_too() {
    // A ring of obstacles encloses a 4 x 4 pocket: two fluid regions, each pressure fixed separately.
    let mut mask = ObstacleMask::free(16);
    for k in 4..10 {
        for (i, j) in [(k, 4), (k, 5), (k, 9), (k, 8), (4, k), (5, k), (9, k), (8, k)] {
            mask.set(i, j, true);
        }
    }
    let flags = Flags::new(&mask, 1.0 / 16.0).expect("flags");
    assert_eq!(flags.regions, 2);
    let mut sim = FluidSim::new(
        &mask,
        1.0 / 16.0,
        Walls { top_u_mps: 1.0, ..Walls::default() },
        params(PressureSolverKind::Direct),
    )
    .expect("sim");
    for _ in 0..20 {
        let report = sim.step(sim.stable_dt()).expect("step");
        assert!(report.max_divergence_per_s <= 1e-7);
    }
    // Nothing drives the pocket: it stays at rest.
    let grid = sim.grid();
    for j in 7..=8 {
        for i in 7..=8 {
            assert_eq!(sim.u()[grid.idx(i, j)], 0.0);
        }
    }
}

/// A tau above 1 and a NaN viscosity are refused naming the field; a donor-cell factor of 2, a wrong-size
/// or full mask, a negative step and a preset on a wall face are refused too.
#[test]
fn bad_parameters_name_the_field() {
    let mut p = params(PressureSolverKind::Direct);
    p.tau = 1.5;
    let err = FluidSim::new(&ObstacleMask::free(8), 0.1, Walls::default(), p).expect_err("tau > 1");
    assert!(err.to_string().starts_with("tau:"), "{err}");
    let mut p = params(PressureSolverKind::Direct);
    p.viscosity_m2ps = f64::NAN;
    let err = FluidSim::new(&ObstacleMask::free(8), 0.1, Walls::default(), p).expect_err("NaN viscosity");
    assert!(err.to_string().starts_with("viscosity_m2ps:"), "{err}");
    let mut p = params(PressureSolverKind::Direct);
    p.donor_cell = DonorCell::Fixed(2.0);
    assert!(FluidSim::new(&ObstacleMask::free(8), 0.1, Walls::default(), p).is_err());
    assert!(ObstacleMask::new(8, vec![false; 63]).is_err());
    let full = ObstacleMask { n: 8, blocked: vec![true; 64] };
    assert!(FluidSim::new(&full, 0.1, Walls::default(), params(PressureSolverKind::Direct)).is_err());
    let mut sim =
        FluidSim::new(&ObstacleMask::free(8), 0.1, Walls::default(), params(PressureSolverKind::Direct))
            .expect("sim");
    assert!(sim.step(-1.0).is_err());
    // A preset on a wall face is refused.
    let wall_face = sim.grid().idx(0, 3);
    let preset = FacePreset { component: Component::U, index: wall_face, velocity_mps: 1.0 };
    assert!(sim.set_presets(vec![preset]).is_err());
}

//! The shipped scene variants are the nominal scene with another suture, so that runs on them
//! compare on the suture alone.
//!
//! `scenarios/chain.toml` is the nominal scene with the suture as Rapier's capsule chain: one
//! friction for all (0.15), 0.25 m long, held in the tissue by 0.05 N a flap, no rope substeps or
//! spacing, inertial mass, constraint passes or radius at metal (the chain has none of them), Rapier's solver at the 8 substeps of 4 sweeps its joints need
//! (the rope leaves Rapier only the needle and the flaps: 2 of 1), nothing else changed, so that the
//! chain's tests run in the nominal operating scene.
//!
//! `scenarios/polypropylene-3-0.toml` is the nominal scene with a measured 3-0 polypropylene suture:
//! its thread's size (pushed at it by metal as by everything else), stiffness and weight, the rope's
//! substeps, inertial mass, constraint passes and bending solve (as its own table in docs/validation.md was measured), and the randomization's
//! bending stiffness.
//!
//! `scenarios/real-weight.toml` is the nominal scene with 12 cm of suture at a 3-0 suture's weight:
//! its length, segments (of the nominal's length) and mass.
//!
//! `scenarios/real-diameter.toml` is the nominal scene with the suture at its real diameter in its
//! knots: its radius, the rope's bending solve and constraint passes that diameter needs, and the
//! rope's substeps and inertial mass as its table in docs/validation.md was measured.

use knotlab_sim::scene::parse_scene;
use knotlab_sim::thread::ThreadModel;

/// `chain.toml` differs from `default.toml` only in its suture: the thread model, friction and length,
/// the rope's keys and solver passes, and stitch slide friction.
#[test]
fn the_chain_scene_differs_from_the_nominal_one_only_in_the_suture() {
    let nominal = parse_scene(include_str!("../../default.toml"), "default.toml").expect("the shipped scene");
    let mut chain = parse_scene(include_str!("../../chain.toml"), "chain.toml").expect("the chain scene");
    assert_eq!(nominal.thread.model, ThreadModel::Rope);
    assert_eq!(nominal.thread.friction_on_itself, Some(0.5));
    assert_eq!((nominal.thread.length_m, nominal.stitch.slide_friction_n), (0.2, 0.6));
    assert_eq!(nominal.thread.rope_substeps, Some(12));
    assert_eq!(nominal.thread.rope_spacing_radii, Some(3.0));
    assert_eq!(nominal.thread.rope_radius_at_metal_m, Some(0.0001125));
    assert_eq!(
        (nominal.thread.rope_inertial_mass_kg_per_m, nominal.thread.rope_constraint_passes),
        (Some(0.15), Some(2))
    );
    assert_eq!((nominal.solver.solver_iterations, nominal.solver.pgs_iterations_per_substep), (2, 1));
    assert_eq!(chain.thread.model, ThreadModel::Chain);
    assert_eq!(chain.thread.friction_on_itself, None);
    assert_eq!((chain.thread.length_m, chain.stitch.slide_friction_n), (0.25, 0.05));
    assert_eq!(chain.thread.rope_substeps, None);
    assert_eq!(chain.thread.rope_spacing_radii, None);
    assert_eq!(chain.thread.rope_radius_at_metal_m, None);
    assert_eq!(chain.thread.axial_stiffness_n, None);
    assert_eq!((chain.solver.solver_iterations, chain.solver.pgs_iterations_per_substep), (8, 4));
    // The chain's own keys, which a rope scene may not give.
    assert_eq!((chain.thread.twist_free, chain.thread.bend_damping_n_m_s_per_rad), (false, 2e-7));
    chain.thread.twist_free = nominal.thread.twist_free;
    chain.thread.bend_damping_n_m_s_per_rad = nominal.thread.bend_damping_n_m_s_per_rad;
    chain.thread.model = ThreadModel::Rope;
    chain.thread.friction_on_itself = nominal.thread.friction_on_itself;
    chain.thread.length_m = nominal.thread.length_m;
    chain.thread.rope_substeps = nominal.thread.rope_substeps;
    chain.thread.rope_spacing_radii = nominal.thread.rope_spacing_radii;
    chain.thread.rope_radius_at_metal_m = nominal.thread.rope_radius_at_metal_m;
    chain.thread.rope_inertial_mass_kg_per_m = nominal.thread.rope_inertial_mass_kg_per_m;
    chain.thread.rope_constraint_passes = nominal.thread.rope_constraint_passes;
    chain.thread.axial_stiffness_n = nominal.thread.axial_stiffness_n;
    chain.solver.solver_iterations = nominal.solver.solver_iterations;
    chain.solver.pgs_iterations_per_substep = nominal.solver.pgs_iterations_per_substep;
    chain.stitch.slide_friction_n = nominal.stitch.slide_friction_n;
    assert_eq!(chain, nominal, "every other setting as in default.toml");
}

/// `polypropylene-3-0.toml` differs from `default.toml` only in the 3-0 polypropylene suture's settings
/// and its bending-stiffness draw.
#[test]
fn the_polypropylene_scene_differs_from_the_nominal_one_only_in_the_suture() {
    let nominal = parse_scene(include_str!("../../default.toml"), "default.toml").expect("the shipped scene");
    let mut pp = parse_scene(include_str!("../../polypropylene-3-0.toml"), "polypropylene-3-0.toml")
        .expect("the polypropylene scene");
    assert_eq!((pp.thread.radius_m, pp.thread.mass_kg), (0.0001125, 7.2e-6));
    assert_eq!(pp.thread.rope_radius_at_metal_m, None);
    let ei = pp.thread.bend_stiffness_n_m_per_rad * pp.thread.segment_length_m();
    assert!((ei - 5.0e-7).abs() < 1e-15, "EI {ei:e} N m²");
    assert_eq!((pp.thread.rope_substeps, pp.thread.rope_direct_bending), (Some(12), true));
    assert_eq!(
        (pp.thread.rope_inertial_mass_kg_per_m, pp.thread.rope_constraint_passes),
        (Some(0.67), Some(1))
    );
    assert_eq!(pp.randomization.thread_bend_stiffness, [1.25e-4, 3.0e-4]);
    pp.thread.radius_m = nominal.thread.radius_m;
    pp.thread.rope_radius_at_metal_m = nominal.thread.rope_radius_at_metal_m;
    pp.thread.mass_kg = nominal.thread.mass_kg;
    pp.thread.bend_stiffness_n_m_per_rad = nominal.thread.bend_stiffness_n_m_per_rad;
    pp.thread.rope_substeps = nominal.thread.rope_substeps;
    pp.thread.rope_direct_bending = nominal.thread.rope_direct_bending;
    pp.thread.rope_inertial_mass_kg_per_m = nominal.thread.rope_inertial_mass_kg_per_m;
    pp.thread.rope_constraint_passes = nominal.thread.rope_constraint_passes;
    pp.randomization.thread_bend_stiffness = nominal.randomization.thread_bend_stiffness;
    pp.description = nominal.description.clone();
    assert_eq!(pp, nominal, "every other setting as in default.toml");
}

/// `real-diameter.toml` differs from `default.toml` only in the thread's radius, the rope's bending
/// solve, its constraint passes, substeps and inertial mass.
#[test]
fn the_real_diameter_scene_differs_from_the_nominal_one_only_in_the_suture() {
    let nominal = parse_scene(include_str!("../../default.toml"), "default.toml").expect("the shipped scene");
    let mut real = parse_scene(include_str!("../../real-diameter.toml"), "real-diameter.toml")
        .expect("the real-diameter scene");
    assert_eq!(real.thread.radius_m, 0.0001125);
    assert_eq!(real.thread.rope_radius_at_metal_m, Some(real.thread.radius_m));
    assert_eq!((real.thread.rope_direct_bending, real.thread.rope_constraint_passes), (true, Some(4)));
    assert_eq!((real.thread.rope_substeps, real.thread.rope_inertial_mass_kg_per_m), (Some(6), Some(0.67)));
    real.thread.radius_m = nominal.thread.radius_m;
    real.thread.rope_substeps = nominal.thread.rope_substeps;
    real.thread.rope_inertial_mass_kg_per_m = nominal.thread.rope_inertial_mass_kg_per_m;
    real.thread.rope_direct_bending = nominal.thread.rope_direct_bending;
    real.thread.rope_constraint_passes = nominal.thread.rope_constraint_passes;
    real.description = nominal.description.clone();
    assert_eq!(real, nominal, "every other setting as in default.toml");
}

/// `real-weight.toml` differs from `default.toml` only in the thread's length (its segments as long as
/// the nominal's) and its weight, 47.5 mg/m.
#[test]
fn the_real_weight_scene_differs_from_the_nominal_one_only_in_the_suture() {
    let nominal = parse_scene(include_str!("../../default.toml"), "default.toml").expect("the shipped scene");
    let mut light = parse_scene(include_str!("../../real-weight.toml"), "real-weight.toml")
        .expect("the real-weight scene");
    assert_eq!((light.thread.length_m, light.thread.segments), (0.12, 48));
    assert_eq!(light.thread.segment_length_m(), nominal.thread.segment_length_m());
    let weight_kg_per_m = light.thread.mass_kg / light.thread.length_m;
    assert!((weight_kg_per_m - 4.75e-5).abs() < 1e-12, "{weight_kg_per_m} kg/m");
    light.thread.length_m = nominal.thread.length_m;
    light.thread.segments = nominal.thread.segments;
    light.thread.mass_kg = nominal.thread.mass_kg;
    light.description = nominal.description.clone();
    assert_eq!(light, nominal, "every other setting as in default.toml");
}

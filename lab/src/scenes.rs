//! The scenes the experiments start from, compiled in, and the chain made finer. (The shipped
//! nominal scene is `knotlab_bench::shipped_scene`.)

use knotlab_bench::scene_or_exit;

/// The capsule chain's scene (`scenarios/chain.toml`, compiled in: the nominal scene with Rapier's
/// chain as the suture, and Rapier's solver at the 8 substeps of 4 sweeps its joints need) for the
/// chain's benchmarks; exits with the scene's error if it does not parse.
pub fn chain_scene() -> knotlab_sim::scene::SceneConfig {
    scene_or_exit(include_str!("../../scenarios/chain.toml"), "scenarios/chain.toml")
}

/// `scenarios/short-suture-friction-0.5.toml` (the two-throw expert's scene, the laid knots'), or
/// exit with its error.
pub fn short_suture_scene() -> knotlab_sim::scene::SceneConfig {
    scene_or_exit(
        include_str!("../../scenarios/short-suture-friction-0.5.toml"),
        "scenarios/short-suture-friction-0.5.toml",
    )
}

/// The shipped solver and thread with segments `k` times shorter: the bending stiffness and damping
/// per joint scaled by `k` (the same per length), the solver's iterations by `iterations`.
pub fn finer_thread(
    solver: &knotlab_sim::physics::SolverParams,
    thread: &knotlab_sim::thread::ThreadParams,
    k: usize,
    iterations: usize,
) -> (knotlab_sim::physics::SolverParams, knotlab_sim::thread::ThreadParams) {
    let strand = knotlab_sim::thread::ThreadParams {
        segments: k * thread.segments,
        bend_stiffness_n_m_per_rad: k as f64 * thread.bend_stiffness_n_m_per_rad,
        bend_damping_n_m_s_per_rad: k as f64 * thread.bend_damping_n_m_s_per_rad,
        ..*thread
    };
    (
        knotlab_sim::physics::SolverParams {
            solver_iterations: iterations * solver.solver_iterations,
            ..*solver
        },
        strand,
    )
}

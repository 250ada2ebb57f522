//! Benchmark: the virtual obstacles of one 62,500-subcell grid (50 x 50 cells of 5 x 5 subcells),
//! the left arm's tip over the default plane of scenarios/default.toml (6 cm square, 2 cm above the
//! stitch), checked against the other three arms, the gantry, the table and the patient.
//!
//! `cargo bench -p knotlab-bench --bench obstacles --features gpu` prints the CPU backend's median time
//! on 1 and 2 threads (target: at most 20 ms on 2 cores) with a per-subcell breakdown, then, on the
//! best adapter wgpu finds (high-performance preference; its name printed), the GPU backend's upload,
//! kernel (host-timed and by GPU timestamps when the device has them; target on a real GPU: at most
//! 1 ms) and readback, and whether the two grids agree. Without `--features gpu` the GPU part says it
//! was not built. `KNOTLAB_BENCH_SECONDS` sets the time spent per measurement (default 3).

use std::error::Error;
use std::time::{Duration, Instant};

use knotlab_hw::rig::{ArmName, Rig};
use knotlab_learner::obstacles::cpu::thread_pool;
use knotlab_learner::obstacles::obb::Obb;
use knotlab_learner::obstacles::{
    ArmState, CellVerdict, CollisionWorld, GridPlane, GridRequest, GridResult, PreparedGrid,
    SubcellOrientation, compute_cpu,
};
use knotlab_sim::scene::{SceneConfig, parse_scene};
use knotlab_sim::world::SimWorld;
use nalgebra::{IsometryMatrix3, Rotation3, Vector3};

const SCENE: &str = include_str!("../../scenarios/default.toml");

/// Median, 10th and 90th percentile of `f`'s wall time in ms, over as many runs as fit in the budget
/// (at least 3, at most 200), after one warm-up run.
fn time_ms(budget: Duration, mut f: impl FnMut()) -> (f64, f64, f64, usize) {
    f();
    let start = Instant::now();
    let mut samples = Vec::new();
    while samples.len() < 3 || (start.elapsed() < budget && samples.len() < 200) {
        let t = Instant::now();
        f();
        samples.push(t.elapsed().as_secs_f64() * 1e3);
    }
    summary(samples)
}

fn summary(mut samples: Vec<f64>) -> (f64, f64, f64, usize) {
    samples.sort_by(f64::total_cmp);
    let at = |q: f64| samples[((samples.len() - 1) as f64 * q).round() as usize];
    (at(0.5), at(0.1), at(0.9), samples.len())
}

/// The scene's arms where it starts them, its obstacles, and the default plane (as `knotlab obstacles`).
fn setup(scene: &SceneConfig) -> Result<(CollisionWorld, GridPlane), Box<dyn Error>> {
    let sim = SimWorld::new(scene.clone(), Rig::shipped()?)?;
    let t = &scene.trocars;
    let trocar = |name| match name {
        ArmName::Left => t.left,
        ArmName::Right => t.right,
        ArmName::Assist => t.assist,
        ArmName::Camera => t.camera,
    };
    let states: Vec<ArmState> = ArmName::ALL
        .iter()
        .map(|&name| ArmState { name, trocar_m: Vector3::from(trocar(name)), joints: sim.arm(name).command })
        .collect();
    let mut world = CollisionWorld::from_rig(sim.rig(), &states)?;
    for (k, o) in scene.obstacles.iter().enumerate() {
        world.add_obstacle(&format!("obstacles[{k}]"), o.centre_m.into(), o.half_extents_m.into())?;
    }
    let wound = Rotation3::from_axis_angle(&Vector3::z_axis(), scene.tissue.yaw_rad);
    let stitch = Vector3::from(scene.tissue.centre_m) + wound * Vector3::new(scene.stitch.along_m, 0.0, 0.0);
    let plane = GridPlane::centred(
        stitch + Vector3::z() * 0.02,
        wound * Vector3::x(),
        wound * Vector3::y(),
        0.06,
        50,
        5,
    )?;
    Ok((world, plane))
}

fn counts(r: &GridResult) -> String {
    format!(
        "{} cells blocked ({} colliding, {} unreachable)",
        r.cells_blocked(),
        r.count(CellVerdict::Collides),
        r.count(CellVerdict::Unreachable)
    )
}

fn main() -> Result<(), Box<dyn Error>> {
    let budget = Duration::from_secs_f64(
        std::env::var("KNOTLAB_BENCH_SECONDS").ok().and_then(|s| s.parse().ok()).unwrap_or(3.0),
    );
    let scene = parse_scene(SCENE, "scenarios/default.toml")?;
    let (world, plane) = setup(&scene)?;
    let request = GridRequest { arm: ArmName::Left, plane, orientation: SubcellOrientation::AlongShaft };
    let grid = PreparedGrid::new(&world, &request)?;
    let n = plane.subcell_count();
    println!(
        "virtual obstacles: arm left, {} x {} cells of {} x {} subcells = {n} subcells; {} moving boxes, {} \
         environment boxes (3 arms, gantry, table, patient), {} self pairs",
        plane.cells,
        plane.cells,
        plane.subcells,
        plane.subcells,
        grid.moving.len(),
        grid.environment.len(),
        grid.self_pairs.len()
    );

    // CPU: the whole grid on 1 and 2 threads.
    let mut cpu_result = None;
    for threads in [1, 2] {
        let pool = thread_pool(threads)?;
        let (median, p10, p90, runs) = time_ms(budget, || {
            cpu_result = Some(pool.install(|| compute_cpu(&grid, false)));
        });
        println!(
            "cpu {threads} thread{}: median {median:.1} ms (p10 {p10:.1}, p90 {p90:.1}, {runs} runs){}",
            if threads == 1 { "" } else { "s" },
            if threads == 2 { "  [target: at most 20 ms on 2 cores]" } else { "" }
        );
    }
    let cpu_result = cpu_result.ok_or("no CPU run")?;
    println!(
        "cpu grid: {}; {} subcells collision-tested",
        counts(&cpu_result),
        cpu_result.subcells_collision_tested
    );

    // Where one thread's time goes, per subcell.
    let side = plane.side();
    let tips: Vec<Vector3<f64>> = (0..n).map(|k| grid.subcell_tip_m(k % side, k / side)).collect();
    let (ik_ms, ..) = time_ms(budget / 3, || {
        for tip in &tips {
            std::hint::black_box(grid.solve(tip));
        }
    });
    let joints: Vec<_> = tips.iter().filter_map(|t| grid.solve(t)).collect();
    let mut posed = vec![Obb::new(&IsometryMatrix3::identity(), Vector3::zeros()); grid.moving.len()];
    let (fk_ms, ..) = time_ms(budget / 3, || {
        for j in &joints {
            grid.pose_moving(j, &mut posed);
            std::hint::black_box(&posed);
        }
    });
    println!(
        "cpu per subcell, 1 thread: IK {:.0} ns (knotlab-hw's solve_tip), forward kinematics and boxes {:.0} ns",
        ik_ms * 1e6 / n as f64,
        fk_ms * 1e6 / joints.len().max(1) as f64
    );
    box_tests(&grid, &joints, budget);
    gpu(&grid, &cpu_result, budget)
}

/// A box as parry wants it: its pose and cuboid.
fn parry_box(obb: &Obb) -> (rapier3d::prelude::Pose, rapier3d::parry::shape::Cuboid) {
    use rapier3d::prelude::{Pose, Rotation, Vector};
    let q = nalgebra::UnitQuaternion::from_matrix(&obb.rotation);
    let c = obb.centre_m;
    let h = obb.half_extents_m;
    (
        Pose::from_parts(Vector::new(c.x, c.y, c.z), Rotation::from_xyzw(q.i, q.j, q.k, q.w)),
        rapier3d::parry::shape::Cuboid::new(Vector::new(h.x, h.y, h.z)),
    )
}

/// The box pairs one subcell in 25 meets whose bounding spheres overlap (the pairs the narrow phase
/// sees), tested with the backend's separating-axis test and with parry's cuboid test.
fn box_tests(grid: &PreparedGrid, joints: &[knotlab_hw::kinematics::ArmJoints], budget: Duration) {
    let mut pairs = Vec::new();
    let mut posed = vec![Obb::new(&IsometryMatrix3::identity(), Vector3::zeros()); grid.moving.len()];
    for j in joints.iter().step_by(25) {
        grid.pose_moving(j, &mut posed);
        let near = |a: &Obb, b: &Obb| {
            (a.centre_m - b.centre_m).norm() <= a.bounding_radius_m() + b.bounding_radius_m()
        };
        for (m, p) in grid.moving.iter().zip(&posed) {
            if m.tests_environment {
                pairs.extend(grid.environment.iter().filter(|e| near(p, &e.obb)).map(|e| (*p, e.obb)));
            }
        }
        pairs.extend(
            grid.self_pairs
                .iter()
                .filter(|(a, b)| near(&posed[*a], &posed[*b]))
                .map(|(a, b)| (posed[*a], posed[*b])),
        );
    }
    let parry: Vec<_> = pairs.iter().map(|(a, b)| (parry_box(a), parry_box(b))).collect();
    let (own_ms, ..) = time_ms(budget / 3, || {
        for (a, b) in &pairs {
            std::hint::black_box(a.intersects(b));
        }
    });
    let (parry_ms, ..) = time_ms(budget / 3, || {
        for ((pa, ca), (pb, cb)) in &parry {
            let pos12 = pa.inverse() * *pb;
            std::hint::black_box(rapier3d::parry::query::details::intersection_test_cuboid_cuboid(
                &pos12, ca, cb,
            ));
        }
    });
    let disagree = pairs
        .iter()
        .zip(&parry)
        .filter(|((a, b), ((pa, ca), (pb, cb)))| {
            a.intersects(b)
                != rapier3d::parry::query::details::intersection_test_cuboid_cuboid(
                    &(pa.inverse() * *pb),
                    ca,
                    cb,
                )
        })
        .count();
    let n = pairs.len().max(1) as f64;
    println!(
        "box test over {} sphere-overlapping pairs: own separating-axis test {:.1} ns/pair, parry's cuboid test \
         {:.1} ns/pair (relative pose included); verdicts differ on {disagree}",
        pairs.len(),
        own_ms * 1e6 / n,
        parry_ms * 1e6 / n
    );
}

#[cfg(feature = "gpu")]
fn gpu(grid: &PreparedGrid, cpu: &GridResult, budget: Duration) -> Result<(), Box<dyn Error>> {
    use knotlab_learner::obstacles::gpu::{GpuContext, GpuKernel, compute_gpu};
    let start = Instant::now();
    let ctx = match GpuContext::new() {
        Ok(ctx) => ctx,
        Err(e) => {
            println!("gpu: none ({e})");
            return Ok(());
        }
    };
    let kernel = GpuKernel::new(&ctx)?;
    println!(
        "gpu adapter: {} (device and kernel set up in {:.0} ms)",
        ctx.describe(),
        start.elapsed().as_secs_f64() * 1e3
    );
    let job = kernel.upload(&ctx, grid)?;
    let first = Instant::now();
    job.dispatch(&ctx, &kernel)?;
    println!(
        "gpu first dispatch (the driver may compile the kernel here): {:.0} ms",
        first.elapsed().as_secs_f64() * 1e3
    );
    let mut stamps = Vec::new();
    let (kernel_ms, k10, k90, runs) = time_ms(budget, || {
        if let Ok((_, Some(g))) = job.dispatch(&ctx, &kernel) {
            stamps.push(g);
        }
    });
    let stamped = if stamps.is_empty() {
        "no GPU timestamps on this device".to_owned()
    } else {
        let (m, p10, p90, _) = summary(stamps);
        format!("by GPU timestamps {m:.3} ms (p10 {p10:.3}, p90 {p90:.3})")
    };
    println!(
        "gpu kernel: host-timed median {kernel_ms:.3} ms (p10 {k10:.3}, p90 {k90:.3}, {runs} runs); {stamped}  \
         [target on a real GPU: at most 1 ms]"
    );
    let mut totals = Vec::new();
    let mut uploads = Vec::new();
    let mut readbacks = Vec::new();
    let mut last = None;
    let (total_ms, ..) = time_ms(budget, || {
        if let Ok((result, t)) = compute_gpu(&ctx, &kernel, grid, false) {
            totals.push(t.total_ms());
            uploads.push(t.upload_ms);
            readbacks.push(t.readback_ms);
            last = Some(result);
        }
    });
    let (upload, ..) = summary(uploads);
    let (readback, ..) = summary(readbacks);
    println!(
        "gpu whole grid: median {total_ms:.3} ms wall = upload {upload:.3} ms + kernel + readback {readback:.3} ms"
    );
    let result = last.ok_or("no GPU run succeeded")?;
    println!(
        "gpu grid: {}; cells differing from the CPU grid: {}",
        counts(&result),
        result.cells.iter().zip(&cpu.cells).filter(|(a, b)| a != b).count()
    );
    Ok(())
}

#[cfg(not(feature = "gpu"))]
fn gpu(_: &PreparedGrid, _: &GridResult, _: Duration) -> Result<(), Box<dyn Error>> {
    println!("gpu: not built (cargo bench -p knotlab-bench --bench obstacles --features gpu)");
    Ok(())
}

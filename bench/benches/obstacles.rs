//! Benchmark: the virtual obstacles of one 62,500-subcell grid (50 x 50 cells of 5 x 5 subcells),
//! the left arm's tip over the default plane of scenarios/default.toml (6 cm square, 2 cm above the
//! stitch), checked against the other three arms, the gantry, the table and the patient.
//!
//! `cargo bench -p knotlab-bench --bench obstacles --features gpu` times with divan the CPU backend
//! on 1 and 2 threads (target: at most 20 ms on 2 cores), where one thread's time goes (IK, forward
//! kinematics, box tests: its own and parry's), and, on the best adapter wgpu finds, the GPU kernel
//! (host-timed, with GPU timestamps where the device has them; target on a real GPU: at most 1 ms)
//! and the whole GPU grid with its upload and readback, and whether the GPU's grid agrees with the
//! CPU's. Without `--features gpu` the GPU benchmarks are not built.

use std::error::Error;

use knotlab_hw::rig::{ArmName, Rig};
use knotlab_learner::obstacles::cpu::thread_pool;
use knotlab_learner::obstacles::obb::Obb;
use knotlab_learner::obstacles::{
    ArmState, CellVerdict, CollisionWorld, GridPlane, GridRequest, GridResult, PreparedGrid,
    SubcellOrientation, compute_cpu,
};
use knotlab_sim::scene::{SceneConfig, parse_scene};
use knotlab_sim::world::SimWorld;
use nalgebra::{IsometryMatrix3, Vector3};

const SCENE: &str = include_str!("../../scenarios/default.toml");

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
    let world_from_tissue = knotlab_sim::tissue::Tissue::frame(&scene.tissue);
    let wound = world_from_tissue.rotation.to_rotation_matrix();
    let stitch = (world_from_tissue * nalgebra::Point3::new(scene.stitch.along_m, 0.0, 0.0)).coords;
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

/// The left arm's grid over the default plane, prepared, with every subcell's tip target and the
/// joints that reach those reachable.
struct Bench {
    grid: PreparedGrid,
    tips: Vec<Vector3<f64>>,
    joints: Vec<knotlab_hw::kinematics::ArmJoints>,
}

fn prepared() -> Bench {
    let scene = parse_scene(SCENE, "scenarios/default.toml").expect("the shipped scene");
    let (world, plane) = setup(&scene).expect("the scene's collision world");
    let request = GridRequest { arm: ArmName::Left, plane, orientation: SubcellOrientation::AlongShaft };
    let grid = PreparedGrid::new(&world, &request).expect("the grid");
    let side = plane.side();
    let tips: Vec<Vector3<f64>> =
        (0..plane.subcell_count()).map(|k| grid.subcell_tip_m(k % side, k / side)).collect();
    let joints = tips.iter().filter_map(|t| grid.solve(t)).collect();
    Bench { grid, tips, joints }
}

fn main() {
    divan::main();
}

/// The whole grid on the CPU backend, on 1 and 2 threads (target: at most 20 ms on 2 cores).
#[divan::bench(args = [1, 2], sample_count = 20, sample_size = 1)]
fn cpu_grid(bencher: divan::Bencher, threads: usize) {
    let b = prepared();
    let pool = thread_pool(threads).expect("a thread pool");
    let result = pool.install(|| compute_cpu(&b.grid, false));
    println!("cpu grid: {}; {} subcells collision-tested", counts(&result), result.subcells_collision_tested);
    bencher.bench_local(|| pool.install(|| compute_cpu(&b.grid, false)));
}

/// Where one thread's time goes: the trocar-constrained IK of every subcell's tip (knotlab-hw's
/// `solve_tip`), counted per subcell.
#[divan::bench(sample_count = 10, sample_size = 1)]
fn ik_per_subcell(bencher: divan::Bencher) {
    let b = prepared();
    bencher.counter(divan::counter::ItemsCount::new(b.tips.len())).bench_local(|| {
        for tip in &b.tips {
            std::hint::black_box(b.grid.solve(tip));
        }
    });
}

/// ... the forward kinematics and the moving boxes posed at every reachable subcell, counted per
/// subcell.
#[divan::bench(sample_count = 10, sample_size = 1)]
fn forward_kinematics_and_boxes_per_subcell(bencher: divan::Bencher) {
    let b = prepared();
    let mut posed = vec![Obb::new(&IsometryMatrix3::identity(), Vector3::zeros()); b.grid.moving.len()];
    bencher.counter(divan::counter::ItemsCount::new(b.joints.len())).bench_local(|| {
        for j in &b.joints {
            b.grid.pose_moving(j, &mut posed);
            std::hint::black_box(&posed);
        }
    });
}

/// The box pairs one subcell in 25 meets whose bounding spheres overlap (the pairs the narrow phase
/// sees), with the backend's own separating-axis test, counted per pair.
#[divan::bench(sample_count = 20, sample_size = 1)]
fn box_test_own(bencher: divan::Bencher) {
    let b = prepared();
    let pairs = box_pairs(&b.grid, &b.joints);
    let parry: Vec<_> = pairs.iter().map(|(a, b)| (parry_box(a), parry_box(b))).collect();
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
    println!("box tests: {} pairs; the own test and parry's differ on {disagree}", pairs.len());
    bencher.counter(divan::counter::ItemsCount::new(pairs.len())).bench_local(|| {
        for (a, b) in &pairs {
            std::hint::black_box(a.intersects(b));
        }
    });
}

/// ... with parry's cuboid test (the relative pose included), counted per pair.
#[divan::bench(sample_count = 20, sample_size = 1)]
fn box_test_parry(bencher: divan::Bencher) {
    let b = prepared();
    let parry: Vec<_> =
        box_pairs(&b.grid, &b.joints).iter().map(|(a, b)| (parry_box(a), parry_box(b))).collect();
    bencher.counter(divan::counter::ItemsCount::new(parry.len())).bench_local(|| {
        for ((pa, ca), (pb, cb)) in &parry {
            let pos12 = pa.inverse() * *pb;
            std::hint::black_box(rapier3d::parry::query::details::intersection_test_cuboid_cuboid(
                &pos12, ca, cb,
            ));
        }
    });
}

/// The box pairs one subcell in 25 meets whose bounding spheres overlap.
fn box_pairs(grid: &PreparedGrid, joints: &[knotlab_hw::kinematics::ArmJoints]) -> Vec<(Obb, Obb)> {
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
    pairs
}

/// The kernel alone on the best adapter wgpu finds (its name printed; target on a real GPU: at most
/// 1 ms), host-timed, with the GPU's own timestamps printed when the device has them, and whether
/// its grid agrees with the CPU's.
#[cfg(feature = "gpu")]
#[divan::bench(sample_count = 50, sample_size = 1)]
fn gpu_kernel(bencher: divan::Bencher) {
    use knotlab_learner::obstacles::gpu::{GpuContext, GpuKernel, compute_gpu};
    let b = prepared();
    let ctx = match GpuContext::new() {
        Ok(ctx) => ctx,
        Err(e) => {
            println!("gpu: none ({e})");
            return;
        }
    };
    let kernel = GpuKernel::new(&ctx).expect("the kernel");
    println!("gpu adapter: {}", ctx.describe());
    let cpu = compute_cpu(&b.grid, false);
    let (gpu, _) = compute_gpu(&ctx, &kernel, &b.grid, false).expect("a GPU grid");
    println!(
        "gpu grid: {}; cells differing from the CPU grid: {}",
        counts(&gpu),
        gpu.cells.iter().zip(&cpu.cells).filter(|(a, b)| a != b).count()
    );
    let job = kernel.upload(&ctx, &b.grid).expect("the upload");
    job.dispatch(&ctx, &kernel).expect("a first dispatch (the driver may compile the kernel here)");
    let mut stamps = Vec::new();
    bencher.bench_local(|| {
        if let Ok((_, Some(gpu_ms))) = job.dispatch(&ctx, &kernel) {
            stamps.push(gpu_ms);
        }
    });
    stamps.sort_by(f64::total_cmp);
    match stamps.get(stamps.len() / 2) {
        Some(median) => println!("gpu kernel by GPU timestamps: median {median:.3} ms"),
        None => println!("gpu kernel: no GPU timestamps on this device"),
    }
}

/// The whole grid on the GPU backend: upload, kernel, readback.
#[cfg(feature = "gpu")]
#[divan::bench(sample_count = 50, sample_size = 1)]
fn gpu_whole_grid(bencher: divan::Bencher) {
    use knotlab_learner::obstacles::gpu::{GpuContext, GpuKernel, compute_gpu};
    let b = prepared();
    let Ok(ctx) = GpuContext::new() else { return };
    let kernel = GpuKernel::new(&ctx).expect("the kernel");
    bencher.bench_local(|| compute_gpu(&ctx, &kernel, &b.grid, false).expect("a GPU grid"));
}

//! A knot laid by hand over the stitch, snugged by its free ends and put to the evaluator's holding
//! test: what a well-laid knot does in the scene's thread, apart from any expert. The thread is laid
//! (no instrument holds it) as [`crate::reef::loose_knot`]'s square knot or as a surgeon's knot (two
//! double helices) a few millimetres over the wound, the tail's strand from the entry point and the
//! long end's from the exit point, the long end's spare thread straight on beyond its free end. Both
//! free ends are pulled out, each alongside its own standing part (the tail's over its flap, the long
//! end's over the other), until the knot is snug; then they are let go and the holding test pulls
//! the wound open ([`knotlab_sim::evaluate::hold`]). If such a knot cannot keep the wound within the
//! evaluator's gap, no expert's can (`cargo bench -p knotlab-lab --bench laid_knot`).

use knotlab_hw::rig::Rig;
use nalgebra::{Isometry3, Point3, Vector3};
use rapier3d::prelude::*;

use crate::reef::loose_knot;
use knotlab_sim::convert::to_rapier;
use knotlab_sim::evaluate::{hold, knot_now};
use knotlab_sim::knot::KnotType;
use knotlab_sim::physics::Physics;
use knotlab_sim::scene::SceneConfig;
use knotlab_sim::tissue::{Flap, Tissue};
use knotlab_sim::world::{SimWorld, WorldError};

/// Which knot is laid.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LaidKnotKind {
    /// [`crate::reef::loose_knot`]'s square knot: two bights collaring each other.
    Square,
    /// A surgeon's knot, the knot the evaluator accepts: the tail and the long end wound round each
    /// other twice, then once the other way; laid as two double helices across the wound,
    /// the first (two turns) at the knot's height, the second (one turn, the other hand) above it.
    SurgeonsKnot,
    /// The surgeon's knot's first throw alone (a double throw, the knot the scripted expert leaves
    /// before a second throw): the tail and the long end wound round each other twice across the
    /// wound, at the knot's height, each end going on straight beyond.
    SurgeonsThrow,
}

/// How the knot is laid and snugged.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LaidKnotParams {
    /// Which knot.
    pub kind: LaidKnotKind,
    /// The loose knot's features this far apart (red's legs twice this apart), m; for the surgeon's
    /// knot, each helix runs this far either side of the wound's line.
    pub spread_m: f64,
    /// The strands cross this far above and below each other, m; for the surgeon's knot, the
    /// helices' radius.
    pub lift_m: f64,
    /// The knot's plane this far over the tissue's surface, m.
    pub height_m: f64,
    /// Straight strand from the knot to the tail's free end, m.
    pub free_end_m: f64,
    /// Each free end pulled out with this force, N ...
    pub snug_n: f64,
    /// ... for this long, s (ramped up over the first half), ...
    pub snug_s: f64,
    /// ... every segment's velocity damped at this rate meanwhile, 1/s (the slack drawn in slowly),
    /// ...
    pub snug_damping_per_s: f64,
    /// ... and each flap pushed towards the other with this force, N (as a surgeon's assistant holds
    /// the wound closed while the knot is drawn tight; 0: the thread alone closes it).
    pub closing_n: f64,
}

impl Default for LaidKnotParams {
    /// A 3 mm spread, 1.5 mm lift, 3 mm over the tissue (the knot about as wide as the stitch), a 20
    /// mm tail (room for it on a 0.2 m suture); snugged at 1 N for 2 s under 200/s damping, as the
    /// reef trial snugs its knots; the flaps not held.
    fn default() -> Self {
        Self {
            kind: LaidKnotKind::Square,
            spread_m: 0.003,
            lift_m: 0.0015,
            height_m: 0.003,
            free_end_m: 0.02,
            snug_n: 1.0,
            snug_s: 2.0,
            snug_damping_per_s: 200.0,
            closing_n: 0.0,
        }
    }
}

/// What the trial measured.
#[derive(Clone, Debug, PartialEq)]
pub struct LaidKnotOutcome {
    /// The knot as laid, ...
    pub knot_laid: KnotType,
    /// ... as snugged, ...
    pub knot_snug: KnotType,
    /// ... and after the holding test.
    pub knot_after: KnotType,
    /// The knot's lowest crossing over the tissue as snugged, m (none for no knot).
    pub height_snug_m: Option<f64>,
    /// The wound's gap as snugged, m, ...
    pub gap_snug_m: f64,
    /// ... and after the holding test, m (none: the thread went unstable).
    pub gap_after_m: Option<f64>,
}

/// The thread's path, needle end first (world frame): the long end's spare thread, blue from its
/// free end to its standing part, down to the exit point, under the wound, up from the entry point,
/// red from its standing part to its free end. `None` if the thread is too short for it.
pub fn laid_knot_layout(
    config: &SceneConfig,
    tissue: &Tissue,
    physics: &Physics,
    params: &LaidKnotParams,
) -> Option<Vec<Vector3<f64>>> {
    let path = match params.kind {
        LaidKnotKind::Square => square_knot_path(tissue, physics, params),
        LaidKnotKind::SurgeonsKnot => surgeons_knot_path(tissue, physics, params),
        LaidKnotKind::SurgeonsThrow => surgeons_throw_path(tissue, physics, params),
    };
    with_spare_thread(path, config.thread.length_m)
}

/// The long end's spare thread straight on beyond its free end (the path's start), so that the path
/// is as long as the thread; `None` if the thread is too short for it.
fn with_spare_thread(mut path: Vec<Vector3<f64>>, length_m: f64) -> Option<Vec<Vector3<f64>>> {
    let used_m: f64 = path.windows(2).map(|w| (w[1] - w[0]).norm()).sum();
    let spare_m = length_m - used_m;
    if spare_m <= 0.0 || path.len() < 2 {
        return None;
    }
    let outward = (path[0] - path[1]).normalize();
    path.insert(0, path[0] + outward * spare_m);
    Some(path)
}

/// The surgeon's knot's path (world frame, the long end's free end first): in the tissue frame, the
/// tail runs from the entry point up into a double helix along -y at the knot's height (two turns
/// round the long end, which runs the other way), then up and back along +y in a single helix of
/// the other hand above it, and out over its flap; the long end the same the other way round, down
/// to the exit point. (Laid, the thread classifies as `surgeons_knot`:
/// `lab/tests/integration/laid_knot_lays_its_knot_through_the_stitch.rs`.)
fn surgeons_knot_path(tissue: &Tissue, physics: &Physics, params: &LaidKnotParams) -> Vec<Vector3<f64>> {
    let stitch = tissue.stitch_points_m(physics).map(|(_, p)| p);
    surgeons_knot_through(&tissue.world_from_tissue, stitch, params)
}

/// `surgeons_knot_path` through given stitch points (world frame: the exit, the exit's deep
/// point, the entry's deep point, the entry) in a tissue whose frame is `world_from_tissue`.
pub fn surgeons_knot_through(
    world_from_tissue: &Isometry3<f64>,
    stitch: [Vector3<f64>; 4],
    params: &LaidKnotParams,
) -> Vec<Vector3<f64>> {
    let (y, r, low) = (params.spread_m, params.lift_m, params.height_m);
    let high = low + 3.0 * r;
    let past = 0.5 * y;
    let helix = |y0: f64, y1: f64, z: f64, turns: f64, phase: f64| -> Vec<Vector3<f64>> {
        (0..=HELIX_POINTS)
            .map(|k| {
                let t = k as f64 / HELIX_POINTS as f64;
                let a = phase + std::f64::consts::TAU * turns * t;
                Vector3::new(r * a.cos(), y0 + (y1 - y0) * t, z + r * a.sin())
            })
            .collect()
    };
    let world = |p: Vector3<f64>| (world_from_tissue * Point3::from(p)).coords;
    let pi = std::f64::consts::PI;
    let mut long_end = vec![Vector3::new(0.0, -y - past - params.free_end_m, high)];
    long_end.extend(helix(-y, y + past, high, 1.0, pi));
    long_end.extend(helix(y, -y, low, 2.0, pi));
    let mut tail = helix(y, -y, low, 2.0, 0.0);
    tail.extend(helix(-y - past, y, high, 1.0, 0.0));
    tail.push(Vector3::new(0.0, y + params.free_end_m, high));
    let mut path: Vec<Vector3<f64>> = long_end.into_iter().map(world).collect();
    path.extend(stitch);
    path.extend(tail.into_iter().map(world));
    path
}

/// The surgeon's knot's first throw alone (world frame, the long end's free end first): the double
/// helix of [`surgeons_knot_path`], each end straight on beyond it at the knot's height.
fn surgeons_throw_path(tissue: &Tissue, physics: &Physics, params: &LaidKnotParams) -> Vec<Vector3<f64>> {
    let stitch = tissue.stitch_points_m(physics).map(|(_, p)| p);
    surgeons_throw_through(&tissue.world_from_tissue, stitch, params)
}

/// `surgeons_throw_path` through given stitch points, as [`surgeons_knot_through`].
pub fn surgeons_throw_through(
    world_from_tissue: &Isometry3<f64>,
    stitch: [Vector3<f64>; 4],
    params: &LaidKnotParams,
) -> Vec<Vector3<f64>> {
    let (y, r, low) = (params.spread_m, params.lift_m, params.height_m);
    let beyond = 0.5 * y + params.free_end_m;
    let helix = |phase: f64| -> Vec<Vector3<f64>> {
        (0..=HELIX_POINTS)
            .map(|k| {
                let t = k as f64 / HELIX_POINTS as f64;
                let a = phase + std::f64::consts::TAU * 2.0 * t;
                Vector3::new(r * a.cos(), y - 2.0 * y * t, low + r * a.sin())
            })
            .collect()
    };
    let world = |p: Vector3<f64>| (world_from_tissue * Point3::from(p)).coords;
    let mut long_end = vec![Vector3::new(0.0, y + beyond, low)];
    long_end.extend(helix(std::f64::consts::PI));
    let mut tail = helix(0.0);
    tail.push(Vector3::new(0.0, -y - beyond, low));
    let mut path: Vec<Vector3<f64>> = long_end.into_iter().map(world).collect();
    path.extend(stitch);
    path.extend(tail.into_iter().map(world));
    path
}

/// Points along each helix of the laid surgeon's knot.
const HELIX_POINTS: usize = 40;

/// The square knot's path (world frame, the long end's free end first).
fn square_knot_path(tissue: &Tissue, physics: &Physics, params: &LaidKnotParams) -> Vec<Vector3<f64>> {
    let s = params.spread_m;
    let knot = loose_knot(s, params.lift_m, params.free_end_m);
    // The reef's frame in the tissue's: its x (blue's standing part's side) across the wound towards
    // the exit's flap (-y), its y along the wound, its z up; lifted to the knot's height.
    let tissue_from_reef = Isometry3::from_parts(
        nalgebra::Translation3::new(0.0, 0.0, params.height_m),
        nalgebra::UnitQuaternion::from_rotation_matrix(&nalgebra::Rotation3::from_basis_unchecked(&[
            -Vector3::y(),
            Vector3::x(),
            Vector3::z(),
        ])),
    );
    let world = |p: Vector3<f64>| (tissue.world_from_tissue * tissue_from_reef * Point3::from(p)).coords;
    let in_reef = |p: Vector3<f64>| (tissue.world_from_tissue * tissue_from_reef).inverse() * Point3::from(p);
    let (exit, entry) = (tissue.hole_m(physics, Flap::B), tissue.hole_m(physics, Flap::A));
    let (deep_exit, deep_entry) = (tissue.deep_m(physics, Flap::B), tissue.deep_m(physics, Flap::A));
    // Each standing part leaves the knot along its line and runs down to its point once past it:
    // red's (along reef y = s, towards -x) where the entry point lies across the wound; blue's
    // (along y = 0.4 s, z = -lift, from +x) outside red's bend (reef x = 2.5 s) or the exit's line.
    let entry_x = in_reef(entry).x.min(-1.5 * s);
    let exit_x = in_reef(exit).x.max(2.5 * s);
    let red_leg = Vector3::new(entry_x, knot.red[1].y, knot.red[1].z);
    let blue_leg = Vector3::new(exit_x, knot.blue[1].y, knot.blue[1].z);
    let mut path: Vec<Vector3<f64>> = Vec::new();
    // Blue from its free end back to where its standing part turns down.
    path.extend(knot.blue[1..].iter().rev().map(|p| world(*p)));
    path.push(world(blue_leg));
    path.extend([exit, deep_exit, deep_entry, entry]);
    path.push(world(red_leg));
    path.extend(knot.red[1..].iter().map(|p| world(*p)));
    path
}

/// Lays the knot over the stitch of `config`'s scene and snugs it by its free ends (then lets them
/// go): the world ready for the holding test, and the knot as it was laid. An error if the scene
/// cannot be built, its thread is too short for the knot, or the thread went unstable.
pub fn lay_and_snug(
    config: SceneConfig,
    rig: Rig,
    params: &LaidKnotParams,
) -> Result<(SimWorld, KnotType), LaidKnotError> {
    let mut too_short = false;
    let mut world = SimWorld::with_thread_laid(config, rig, |config, tissue, physics| {
        laid_knot_layout(config, tissue, physics, params).unwrap_or_else(|| {
            too_short = true;
            knotlab_sim::suture::layout::start_layout(config, tissue, physics)
        })
    })?;
    if too_short {
        return Err(LaidKnotError::ThreadTooShort);
    }
    let knot_laid = knot_now(&world).map_or(KnotType::Unknown, |k| k.knot);
    let Some(chain) = world.suture().as_chain() else { return Err(LaidKnotError::NotTheChain) };
    let segments = chain.thread().segments.clone();
    let (long_end, tail) = (segments[0], segments[segments.len() - 1]);
    // Each free end out alongside its own standing part: the tail over its flap (+y), the long end
    // over the other (-y), level with the tissue.
    let across = world.tissue().world_from_tissue.rotation * Vector3::y();
    let damp = |world: &mut SimWorld, per_s: f64| {
        for h in &segments {
            world.physics_mut().bodies[*h].set_linear_damping(per_s);
        }
    };
    damp(&mut world, params.snug_damping_per_s);
    let steps = (params.snug_s / world.config().solver.dt_s).round() as usize;
    for step in 0..steps {
        let f = params.snug_n * (2.0 * step as f64 / steps as f64).min(1.0);
        for (h, sign) in [(tail, 1.0), (long_end, -1.0)] {
            push(&mut world, h, across * (f * sign));
        }
        for flap in Flap::ALONG_THREAD {
            let h = world.tissue().flaps[flap.index()];
            push(&mut world, h, across * (-flap.side() * params.closing_n));
        }
        world.step().map_err(|_| LaidKnotError::Unstable)?;
    }
    let flaps = world.tissue().flaps;
    for h in [tail, long_end].into_iter().chain(flaps) {
        world.physics_mut().bodies[h].reset_forces(true);
    }
    let linear_damping_per_s = world.config().thread.linear_damping_per_s;
    damp(&mut world, linear_damping_per_s);
    Ok((world, knot_laid))
}

/// [`lay_and_snug`], then the holding test with the scene's evaluation parameters. `None` in
/// `gap_after_m` if the thread went unstable in it.
pub fn run_laid_knot(
    config: SceneConfig,
    rig: Rig,
    params: &LaidKnotParams,
) -> Result<LaidKnotOutcome, LaidKnotError> {
    let (mut world, knot_laid) = lay_and_snug(config, rig, params)?;
    let snug = knot_now(&world);
    let knot_snug = snug.as_ref().map_or(KnotType::Unknown, |k| k.knot);
    let height_snug_m = snug.and_then(|k| k.height_m);
    let gap_snug_m = world.wound_gap_m();
    let evaluation = world.config().evaluation.clone();
    let gap_after_m = hold(&mut world, &evaluation);
    Ok(LaidKnotOutcome {
        knot_laid,
        knot_snug,
        knot_after: knot_now(&world).map_or(KnotType::Unknown, |k| k.knot),
        height_snug_m,
        gap_snug_m,
        gap_after_m,
    })
}

/// Sets the force on `body` to `force_n` (world frame, N) for the next step.
fn push(world: &mut SimWorld, body: RigidBodyHandle, force_n: Vector3<f64>) {
    let body = &mut world.physics_mut().bodies[body];
    body.reset_forces(true);
    body.add_force(to_rapier(&force_n), true);
}

/// Why a laid-knot trial could not run.
#[derive(Debug, thiserror::Error)]
pub enum LaidKnotError {
    /// The scene does not build.
    #[error(transparent)]
    World(#[from] WorldError),
    /// The scene's thread is shorter than the knot's path.
    #[error("thread.length_m: too short for the laid knot's path")]
    ThreadTooShort,
    /// The scene's suture is not the capsule chain, whose segments the knot is snugged by.
    #[error("thread.model: the laid knot is snugged in the capsule chain (\"chain\")")]
    NotTheChain,
    /// The thread went unstable while the knot was snugged.
    #[error("the thread went unstable while the knot was snugged")]
    Unstable,
}

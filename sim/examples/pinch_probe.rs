//! The pull that draws the nominal suture through two flat parts closer together than its thickness,
//! at 6, 12 and 24 substeps:
//!
//! ```text
//! cargo run --release -p knotlab-sim --example pinch_probe
//! ```
//!
//! Two kinematic plates 10 mm square lie either side of a straight 40 mm strand of the default
//! scene's rope, their faces a fraction of the thread's diameter apart (1.1, 0.95, 0.9, 0.85, 0.8,
//! 0.7), with the scene's friction on metal. One end is held back with 0.02 N; after 1 s the other is
//! pulled harder and harder (0.02 to 10 N over 5 s) until the held end has moved 1 mm. A squeezed
//! thread should slide at a pull set by the squeeze and the friction, whatever the substep.

use knotlab_sim::rope::Ropes;
use knotlab_sim::rope::rigid::RigidContacts;
use knotlab_sim::scene::parse_scene;
use knotlab_sim::validation::suture::SutureUnderTest;
use nalgebra::Vector3;
use rapier3d::prelude::*;

/// The held end's pull, N.
const HOLD_N: f64 = 0.02;
/// The largest pull tried, N.
const MAX_N: f64 = 10.0;

/// The pull at which the strand slid through plates `gap_diameters` of its diameter apart, stepped
/// in `substeps`; `None` if it held to [`MAX_N`].
fn slides_at_n(suture: &SutureUnderTest, substeps: usize, gap_diameters: f64) -> Option<f64> {
    let params = knotlab_sim::rope::RopeParams { substeps, ..suture.params };
    let gap_m = 2.0 * params.radius_m * gap_diameters;
    let mut bodies = RigidBodySet::new();
    let mut colliders = ColliderSet::new();
    let half_thickness_m = 0.0025;
    let mut plates = Vec::new();
    for side in [1.0, -1.0] {
        let centre = Vector::new(0.0, 0.0, side * (0.5 * gap_m + half_thickness_m));
        let body = bodies.insert(RigidBodyBuilder::kinematic_position_based().translation(centre).build());
        let plate = ColliderBuilder::cuboid(0.005, 0.005, half_thickness_m)
            .friction(suture.friction_on_metal)
            .build();
        plates.push((colliders.insert_with_parent(plate, body, &mut bodies), 0..0));
    }
    let mut ropes = Ropes::new(params);
    let strand = ropes
        .add_strand_along(&[Vector3::new(-0.02, 0.0, 0.0), Vector3::new(0.02, 0.0, 0.0)], suture.spacing_m);
    let mut contacts =
        RigidContacts { colliders: plates, friction: suture.friction_on_metal, ..Default::default() };
    let (held, pulled) = (strand.start, strand.end - 1);
    let dt_s = suture.dt_s;
    ropes.force_n[held] = -Vector3::x() * HOLD_N;
    ropes.force_n[pulled] = Vector3::x() * HOLD_N;
    for _ in 0..(1.0 / dt_s).round() as usize {
        contacts.step(&mut ropes, dt_s, &bodies, &colliders);
    }
    let start_m = ropes.x[held].x;
    let ramp = (5.0 / dt_s).round() as usize;
    for k in 0..ramp {
        let pull_n = HOLD_N * (MAX_N / HOLD_N).powf(k as f64 / ramp as f64);
        ropes.force_n[pulled] = Vector3::x() * pull_n;
        contacts.step(&mut ropes, dt_s, &bodies, &colliders);
        if ropes.x[held].x - start_m > 0.001 {
            return Some(pull_n);
        }
    }
    None
}

fn main() {
    let extra: Vec<String> = std::env::args().skip(1).collect();
    if !extra.is_empty() {
        eprintln!(
            "pinch_probe: takes no arguments, got {extra:?} (usage: cargo run --release -p knotlab-sim --example pinch_probe)"
        );
        std::process::exit(2);
    }
    let scene = match parse_scene(include_str!("../../scenarios/default.toml"), "default.toml") {
        Ok(scene) => scene,
        Err(e) => {
            eprintln!("pinch_probe: the shipped scene: {e}");
            std::process::exit(1);
        }
    };
    let suture = match SutureUnderTest::from_scene(&scene) {
        Ok(suture) => suture,
        Err(e) => {
            eprintln!("pinch_probe: {e}");
            std::process::exit(1);
        }
    };
    println!(
        "the nominal suture ({:.2} mm across, friction on metal {}), drawn through two plates:",
        2e3 * suture.params.radius_m,
        suture.friction_on_metal
    );
    println!("| gap / diameter | 6 substeps | 12 substeps | 24 substeps |");
    println!("|---|---|---|---|");
    for gap_diameters in [1.1, 0.95, 0.9, 0.85, 0.8, 0.7] {
        let cells: Vec<String> = [6, 12, 24]
            .iter()
            .map(|&n| match slides_at_n(&suture, n, gap_diameters) {
                Some(pull_n) => format!("{pull_n:.3} N"),
                None => format!("held to {MAX_N} N"),
            })
            .collect();
        println!("| {gap_diameters} | {} |", cells.join(" | "));
    }
}

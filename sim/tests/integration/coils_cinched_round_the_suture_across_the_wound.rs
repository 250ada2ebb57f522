//! Regression: the scripted expert's coils cinched in the wound's gap. The suture between the exit and
//! entry points was laid straight across the wound on the surface (the stitch's depth was never used),
//! so the coils slid down the tail past the entry point and round that part. The suture now runs under
//! the wound at the stitch's depth.

use crate::common::chain;
use knotlab_hw::rig::Rig;
use knotlab_sim::scene::parse_scene;
use knotlab_sim::world::SimWorld;
use nalgebra::Point3;

/// The suture between the stitch points crosses the wound once, under the surface at the stitch's depth, not
/// straight across the surface.
#[test]
fn the_suture_crosses_the_wound_at_the_stitch_depth() {
    let scene =
        parse_scene(include_str!("../../../scenarios/chain.toml"), "chain.toml").expect("shipped scene");
    let depth_m = scene.stitch.depth_m;
    let mut w = SimWorld::new(scene, Rig::shipped().expect("shipped rig")).expect("the shipped scene builds");
    for _ in 0..300 {
        w.step().expect("healthy step");
    }
    let tissue_from_world = w.tissue().world_from_tissue.inverse();
    let line: Vec<_> =
        w.thread_centreline().iter().map(|p| (tissue_from_world * Point3::from(*p)).coords).collect();
    // Where the thread crosses the wound's centre plane (y = 0) between the two stitch points.
    let inside = chain(w.suture()).stitch().segments_inside().expect("the thread is through the stitch");
    let crossing_z: Vec<f64> = inside
        .filter_map(|i| {
            let (a, b) = (line.get(i)?, line.get(i + 1)?);
            (a.y * b.y <= 0.0 && a.y != b.y).then(|| a.z + (b.z - a.z) * a.y / (a.y - b.y))
        })
        .collect();
    assert_eq!(crossing_z.len(), 1, "the suture crosses the wound once: {crossing_z:?}");
    assert!(crossing_z[0] < -0.7 * depth_m, "it crosses {:.2} mm under the surface", -1e3 * crossing_z[0]);
}

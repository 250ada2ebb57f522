//! The simulated scene at one instant ([`SceneShapes`]) as Rerun entities: each arm's links (boxes and
//! capsules, in the arm's colour), the tissue (flaps, pad, stitch holes), the thread as a polyline and
//! as its capsules, and the needle.

use std::collections::BTreeMap;

use nalgebra::Vector3;

use knotlab_sim::shapes::{Owner, SceneShapes, Solid, SolidShape};

use super::Recording;
use super::convert::{arm_color, quaternion, v3, z_onto};
use super::sdk;

/// Boxes and capsules gathered for one entity.
#[derive(Default)]
struct Solids {
    box_centres: Vec<[f32; 3]>,
    box_halves: Vec<[f32; 3]>,
    box_rotations: Vec<sdk::Quaternion>,
    capsule_starts: Vec<[f32; 3]>,
    capsule_rotations: Vec<sdk::Quaternion>,
    capsule_lengths: Vec<f32>,
    capsule_radii: Vec<f32>,
}

impl Solids {
    fn add(&mut self, solid: &Solid) {
        let rotation = &solid.world_from_solid.rotation;
        match solid.shape {
            SolidShape::Cuboid { half_extents_m } => {
                self.box_centres.push(v3(&solid.world_from_solid.translation.vector));
                self.box_halves.push(v3(&half_extents_m));
                self.box_rotations.push(quaternion(rotation));
            }
            SolidShape::Capsule { a_m, b_m, radius_m } => {
                let (a, b) = (solid.world_point(&a_m), solid.world_point(&b_m));
                self.push_capsule(&a, &b, radius_m);
            }
            SolidShape::Ball { radius_m } => {
                let centre = solid.world_point(&Vector3::zeros());
                self.push_capsule(&centre, &centre, radius_m);
            }
        }
    }

    fn push_capsule(&mut self, a: &Vector3<f64>, b: &Vector3<f64>, radius_m: f64) {
        self.capsule_starts.push(v3(a));
        self.capsule_rotations.push(z_onto(&(b - a)));
        self.capsule_lengths.push((b - a).norm() as f32);
        self.capsule_radii.push(radius_m as f32);
    }

    fn log(self, recording: &Recording, path: &str, color: sdk::Color) -> anyhow::Result<()> {
        if !self.box_centres.is_empty() {
            recording.log(
                format!("{path}/boxes"),
                &sdk::Boxes3D::from_centers_and_half_sizes(self.box_centres, self.box_halves)
                    .with_quaternions(self.box_rotations)
                    .with_colors([color]),
            )?;
        }
        if !self.capsule_starts.is_empty() {
            recording.log(
                format!("{path}/capsules"),
                &sdk::Capsules3D::from_lengths_and_radii(self.capsule_lengths, self.capsule_radii)
                    .with_translations(self.capsule_starts)
                    .with_quaternions(self.capsule_rotations)
                    .with_colors([color]),
            )?;
        }
        Ok(())
    }
}

/// Which arm a link belongs to, by its URDF name's prefix; fixed parts (gantry, table) are `rig`.
fn arm_of(link: &str) -> &str {
    ["left", "right", "assist", "camera"]
        .into_iter()
        .find(|arm| link.starts_with(&format!("{arm}_")))
        .unwrap_or("rig")
}

/// Logs the robots' links (`scene/robots/<arm>`).
pub fn log_robots(recording: &Recording, scene: &SceneShapes) -> anyhow::Result<()> {
    let mut arms: BTreeMap<&str, Solids> = BTreeMap::new();
    for solid in &scene.solids {
        if let Owner::Link(name) = &solid.owner {
            arms.entry(arm_of(name)).or_default().add(solid);
        }
    }
    for (arm, solids) in arms {
        solids.log(recording, &format!("scene/robots/{arm}"), arm_color(arm))?;
    }
    Ok(())
}

/// Logs the tissue, the thread and the needle (`scene/tissue/...`, `scene/thread`, `scene/needle`) and
/// the wound gap (`plots/wound_gap_m`).
pub fn log_suture(recording: &Recording, scene: &SceneShapes) -> anyhow::Result<()> {
    let (mut flaps, mut pad) = (Solids::default(), Solids::default());
    for solid in &scene.solids {
        match solid.owner {
            Owner::Flap => flaps.add(solid),
            Owner::Pad => pad.add(solid),
            Owner::Link(_) | Owner::Other => {}
        }
    }
    flaps.log(recording, "scene/tissue/flaps", sdk::Color::from_rgb(220, 120, 150))?;
    pad.log(recording, "scene/tissue/pad", sdk::Color::from_rgb(200, 180, 140))?;
    recording.log(
        "scene/tissue/holes",
        &sdk::Points3D::new(scene.holes_m.iter().map(v3))
            .with_radii([0.0006_f32])
            .with_colors([sdk::Color::from_rgb(20, 160, 60)]),
    )?;
    let thread: Vec<[f32; 3]> = scene.thread_m.iter().map(v3).collect();
    let thread_color = sdk::Color::from_rgb(40, 90, 220);
    recording.log(
        "scene/thread",
        &sdk::LineStrips3D::new([thread])
            .with_radii([scene.thread_radius_m as f32])
            .with_colors([thread_color]),
    )?;
    let mut capsules = Solids::default();
    for w in scene.thread_m.windows(2) {
        capsules.push_capsule(&w[0], &w[1], scene.thread_radius_m);
    }
    capsules.log(recording, "scene/thread/segments", thread_color)?;
    let needle: Vec<[f32; 3]> = scene.needle_m.iter().map(v3).collect();
    recording.log(
        "scene/needle",
        &sdk::LineStrips3D::new([needle])
            .with_radii([scene.needle_radius_m as f32])
            .with_colors([sdk::Color::from_rgb(200, 30, 30)]),
    )?;
    recording.log("plots/wound_gap_m", &sdk::Scalars::single(scene.wound_gap_m))?;
    Ok(())
}

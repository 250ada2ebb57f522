//! [`super::wound`]'s trial with the scene's own tissue: the flaps are Rapier's bodies (each on its
//! prismatic joint and spring, [`crate::tissue`]), the rope lies on them and on the pad through
//! [`super::rigid`]'s contacts and passes the stitch through four points fixed in the flaps
//! ([`super::rigid::Guide`]), and what it does to the flaps is applied to them before each of
//! Rapier's steps. The first step of the rope towards being the scene's thread: the coupling that
//! the instruments, the needle and the grasps will use, checked against the flaps `wound` integrates
//! by hand.

use nalgebra::Vector3;
use rapier3d::prelude::*;

use super::rigid::{Guide, RigidContacts, nearest_on_rope};
use super::wound::{SPACING_M, WoundOutcome, WoundTrialParams, length_m, observe, thread_between_m};
use super::{RopeParams, Ropes};
use crate::knot::legs::free_ends;
use crate::laid_knot::{LaidKnotParams, surgeons_knot_through};
use crate::physics::Physics;
use crate::scene::SceneConfig;
use crate::tissue::{Flap, Tissue};

/// Lays `knot` (a surgeon's knot) over the stitch of `config`'s tissue, built in Rapier; snugs it
/// by its free ends, lets go and runs the holding test, as [`super::wound::laid_surgeons_knot_in_wound`]
/// does with its own flaps. The rope steps with the scene's solver step.
pub fn laid_surgeons_knot_in_tissue(
    rope: RopeParams,
    config: &SceneConfig,
    knot: &LaidKnotParams,
    trial: &WoundTrialParams,
) -> WoundOutcome {
    let mut physics = Physics::new(&config.solver);
    let tissue = Tissue::build(&mut physics, &config.tissue, &config.stitch);
    let dt_s = config.solver.dt_s;
    let points = [
        (Flap::B, tissue.hole_m(&physics, Flap::B)),
        (Flap::B, tissue.deep_m(&physics, Flap::B)),
        (Flap::A, tissue.deep_m(&physics, Flap::A)),
        (Flap::A, tissue.hole_m(&physics, Flap::A)),
    ];
    let path = surgeons_knot_through(&tissue.world_from_tissue, points.map(|(_, p)| p), knot);
    let mut ropes = Ropes::new(rope);
    let strand = ropes.add_strand_along(&path, SPACING_M);
    let last = strand.end - 1;
    let guides: Vec<Guide> = points
        .iter()
        .map(|(flap, point)| {
            let nearest = strand
                .clone()
                .min_by(|a, b| (ropes.x[*a] - point).norm().total_cmp(&(ropes.x[*b] - point).norm()))
                .unwrap_or(strand.start);
            let body = tissue.flap(*flap);
            let pose = physics.bodies[body].position();
            let local = pose.inverse_transform_point(Vector::new(point.x, point.y, point.z));
            Guide {
                body,
                local_m: Vector3::new(local.x, local.y, local.z),
                at: nearest_on_rope(&ropes, point, nearest, last),
            }
        })
        .collect();
    let mut touched: Vec<ColliderHandle> = tissue.flap_colliders.to_vec();
    touched.extend(physics.bodies[tissue.pad].colliders().iter().copied());
    let mut contacts = RigidContacts {
        colliders: touched.iter().map(|c| (*c, 0..0)).collect(),
        friction: trial.tissue_friction,
        guides,
        ..Default::default()
    };
    let up = tissue.world_from_tissue.rotation * Vector3::z();
    let across = tissue.world_from_tissue.rotation * Vector3::y();
    let weight: Vec<Vector3<f64>> = (0..ropes.x.len())
        .map(|p| if ropes.w[p] > 0.0 { -up * (trial.weight_per_m_n * SPACING_M) } else { Vector3::zeros() })
        .collect();
    let through_m =
        |contacts: &RigidContacts| [contacts.guides[0].at * SPACING_M, contacts.guides[3].at * SPACING_M];
    let inside_m = |ropes: &Ropes, contacts: &RigidContacts| {
        thread_between_m(ropes, contacts.guides[0].at, contacts.guides[3].at)
    };
    let free_ends_now = |ropes: &Ropes, through: [f64; 2]| {
        free_ends(&ropes.polyline(0), through[0], through[1], 2.5 * ropes.params.radius_m)
    };
    let frame = tissue.world_from_tissue;
    let knot_laid = observe(&ropes, through_m(&contacts), &frame).0;
    let length_laid_m = length_m(&ropes);
    let flaps = tissue.flaps;
    let label =
        move |h: RigidBodyHandle| if flaps.contains(&h) { "tissue flap" } else { "tissue" }.to_owned();
    let step = |ropes: &mut Ropes, contacts: &mut RigidContacts, physics: &mut Physics| {
        let inside = contacts.between_guides();
        for (_, exempt) in &mut contacts.colliders {
            *exempt = inside.clone();
        }
        contacts.step(ropes, dt_s, &physics.bodies, &physics.colliders);
        contacts.apply_impulses(&mut physics.bodies);
        // A step whose bodies went bad ends the trial's motion; the outcome shows it.
        physics.step(&label).is_ok()
    };
    let snug_steps = (knot.snug_s / dt_s).round() as usize;
    for k in 0..snug_steps {
        ropes.force_n.copy_from_slice(&weight);
        let f = knot.snug_n * (2.0 * k as f64 / snug_steps as f64).min(1.0);
        ropes.force_n[last] += across * f;
        ropes.force_n[strand.start] -= across * f;
        if !step(&mut ropes, &mut contacts, &mut physics) {
            break;
        }
    }
    let gap_snug_m = tissue.gap_m(&physics);
    let inside_snug_m = inside_m(&ropes, &contacts);
    let through_snug_m = through_m(&contacts);
    let length_snug_m = length_m(&ropes);
    let (knot_snug, height_snug_m, loop_snug_m) = observe(&ropes, through_snug_m, &frame);
    let free_ends_snug_m = free_ends_now(&ropes, through_snug_m);
    ropes.force_n.copy_from_slice(&weight);
    for flap in Flap::ALONG_THREAD {
        let outward = frame.rotation * Vector3::new(0.0, flap.side(), 0.0) * trial.holding_load_n;
        let body = &mut physics.bodies[tissue.flaps[flap.index()]];
        body.add_force(Vector::new(outward.x, outward.y, outward.z), true);
    }
    for _ in 0..(trial.settle_s / dt_s).round() as usize {
        if !step(&mut ropes, &mut contacts, &mut physics) {
            break;
        }
    }
    let through_after_m = through_m(&contacts);
    let (knot_after, height_after_m, loop_after_m) = observe(&ropes, through_after_m, &frame);
    WoundOutcome {
        knot_laid,
        knot_snug,
        knot_after,
        gap_snug_m,
        gap_after_m: tissue.gap_m(&physics),
        inside_snug_m,
        inside_after_m: inside_m(&ropes, &contacts),
        through_snug_m,
        through_after_m,
        free_ends_snug_m,
        free_ends_after_m: free_ends_now(&ropes, through_after_m),
        height_m: [height_snug_m, height_after_m],
        loop_outside_m: [loop_snug_m, loop_after_m],
        length_m: [length_laid_m, length_snug_m, length_m(&ropes)],
        particles: ropes.x.len(),
    }
}

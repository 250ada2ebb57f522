//! [`super::wound`]'s trial with the scene's own tissue: the flaps are Rapier's bodies (each on its
//! prismatic joint and spring, [`knotlab_sim::tissue`]), the rope lies on them and on the pad through
//! [`knotlab_sim::rope::rigid`]'s contacts and passes the stitch through four points fixed in the flaps
//! ([`knotlab_sim::rope::rigid::Guide`]), and what it does to the flaps is applied to them before each of
//! Rapier's steps. The first step of the rope towards being the scene's thread: the coupling that
//! the instruments, the needle and the grasps will use, checked against the flaps `wound` integrates
//! by hand.

use nalgebra::Vector3;
use rapier3d::prelude::*;

use crate::laid_knot::{LaidKnotParams, surgeons_knot_through};
use crate::wound::{Moment, SPACING_M, WoundOutcome, WoundTrialParams, length_m, observe, thread_between_m};
use knotlab_sim::convert::to_rapier;
use knotlab_sim::physics::Physics;
use knotlab_sim::rope::rigid::{Guide, RigidContacts};
use knotlab_sim::rope::{RopeParams, Ropes};
use knotlab_sim::scene::SceneConfig;
use knotlab_sim::tissue::{Flap, Tissue};

/// Lays `knot` (a surgeon's knot) over the stitch of `config`'s tissue, built in Rapier; snugs it
/// by its free ends, lets go and runs the holding test, as [`crate::wound::laid_surgeons_knot_in_wound`]
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
    let points = tissue.stitch_points_m(&physics);
    let path = surgeons_knot_through(&tissue.world_from_tissue, points.map(|(_, p)| p), knot);
    let mut ropes = Ropes::new(rope);
    let strand = ropes.add_strand_along(&path, SPACING_M);
    let guides: Vec<Guide> = points
        .iter()
        .map(|(flap, point)| {
            let body = tissue.flap(*flap);
            Guide::threaded(&ropes, strand.clone(), body, physics.bodies[body].position(), point)
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
        ropes.force_n[strand.end - 1] += across * f;
        ropes.force_n[strand.start] -= across * f;
        if !step(&mut ropes, &mut contacts, &mut physics) {
            break;
        }
    }
    let snug = Moment::take(
        &ropes,
        through_m(&contacts),
        &frame,
        inside_m(&ropes, &contacts),
        tissue.gap_m(&physics),
    );
    ropes.force_n.copy_from_slice(&weight);
    for flap in Flap::ALONG_THREAD {
        let outward = frame.rotation * Vector3::new(0.0, flap.side(), 0.0) * trial.holding_load_n;
        let body = &mut physics.bodies[tissue.flaps[flap.index()]];
        body.add_force(to_rapier(&outward), true);
    }
    for _ in 0..(trial.settle_s / dt_s).round() as usize {
        if !step(&mut ropes, &mut contacts, &mut physics) {
            break;
        }
    }
    let after = Moment::take(
        &ropes,
        through_m(&contacts),
        &frame,
        inside_m(&ropes, &contacts),
        tissue.gap_m(&physics),
    );
    WoundOutcome::from_moments(knot_laid, length_laid_m, snug, after, ropes.x.len())
}

//! The suture drawn between two flat parts closer together than its thickness: the pull at which it
//! slides through them. Not yet a row of the suite: a thread squeezed below its diameter at metal
//! still holds by a pull that grows as the square of the substeps (its section does not give), so
//! the figure has no converged value to set beside a reference. `sim/examples/pinch_probe.rs`
//! prints its table; the sim's tests hold it where it does converge.

use nalgebra::Vector3;
use rapier3d::prelude::*;

use super::SutureUnderTest;
use crate::rope::rigid::RigidContacts;
use crate::rope::{RopeParams, Ropes};

/// The held end's pull, N.
pub const HOLD_N: f64 = 0.02;

/// The pull at which a straight 40 mm strand of `suture`'s rope (with `params` in place of the
/// suture's own: another substep or radius) slides through two kinematic plates 10 mm square whose
/// faces lie `gap_m` apart, with the suture's friction on metal. One end is held back with
/// [`HOLD_N`]; after 1 s the other is pulled harder and harder (from [`HOLD_N`] to `max_n` over 5 s,
/// geometrically) until the held end has moved 1 mm. `None` if it held to `max_n`.
pub fn slides_at_n(suture: &SutureUnderTest, params: RopeParams, gap_m: f64, max_n: f64) -> Option<f64> {
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
        let pull_n = HOLD_N * (max_n / HOLD_N).powf(k as f64 / ramp as f64);
        ropes.force_n[pulled] = Vector3::x() * pull_n;
        contacts.step(&mut ropes, dt_s, &bodies, &colliders);
        if ropes.x[held].x - start_m > 0.001 {
            return Some(pull_n);
        }
    }
    None
}

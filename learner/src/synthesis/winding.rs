//! A winding aimed round the jaws it winds round. A 2D primitive that another instrument follows
//! (the right's R2, the long end wound round the left's jaws, which L2 holds in the loop) was made
//! about the jaws as the demonstration held them. At a turned or tilted stitch the follower's wrist
//! may not bend that far from its shaft, which runs through a trocar that did not move with the
//! stitch: its frame is turned back to the wrist's reach ([`recorded_orientation`]), and a winding
//! moved with the stitch would circle an axis that is no longer the jaws' (26 degrees off at the
//! workspace map's trial 19, where the long end's turns round the jaws never passed half a turn).
//! So where that frame is turned back by [`WINDING_AIMED_FROM_RAD`] or more, the winding and its
//! follower are turned together about the follower's tip by the turn its frame is given: the loop
//! goes round the jaws as they will be, and the follower's own path, which starts at that tip, stays
//! where it was.

use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};

use knotlab_hw::rig::ArmName;
use knotlab_hw::skill::Orientation;

use super::orientation::recorded_orientation;
use super::{SynthesisError, Trocars};
use crate::primitive::{KnowledgeBase, PathKey, Primitive, TwoDPrimitive};

/// The least turn of the follower's frame for which the winding is aimed with it, rad: a frame turned
/// back less is wound round closely enough as the demonstration had it. Within the default
/// randomization the left's frame is turned back at one corner only (shifted 1 cm along x and y,
/// turned 10 degrees clockwise: by 10.9 degrees), and its winding is left as demonstrated.
pub const WINDING_AIMED_FROM_RAD: f64 = 12.0 * std::f64::consts::PI / 180.0;

/// The follower's demonstrated key at `time_s`: the last at or before it (the first where none is).
fn key_at(path: &[PathKey], time_s: f64) -> Option<&PathKey> {
    path.iter().take_while(|k| k.time_s <= time_s + 1e-9).last().or(path.first())
}

/// The rigid turn (world frame) that aims `winding`, made at `world_from_stitch`, round the jaws of
/// the instrument that follows it (its synchronized primitive's), as the wrist of that instrument,
/// its shaft through its trocar in `trocars`, can hold them when the winding starts: the identity
/// where no instrument follows the winding, its key has no frame, or its wrist reaches the
/// demonstrated frame or one less than [`WINDING_AIMED_FROM_RAD`] from it.
pub fn winding_aim(
    kb: &KnowledgeBase,
    winding: &TwoDPrimitive,
    world_from_stitch: &Isometry3<f64>,
    trocars: &Trocars,
) -> Result<Isometry3<f64>, SynthesisError> {
    for ip in &kb.instruments {
        let follows = ip.primitives.iter().any(|p| match p {
            Primitive::Synchronized(s) => s.reference == winding.name,
            _ => false,
        });
        if !follows {
            continue;
        }
        let arm: ArmName = ip.instrument.parse().map_err(|e| SynthesisError::Invalid {
            field: format!("{}.instrument", ip.instrument),
            reason: format!("{e}"),
        })?;
        let Some(key) = key_at(&ip.path, winding.start_s) else { continue };
        let Some([x, y, z, w]) = key.quaternion_xyzw else { continue };
        let asked = world_from_stitch.rotation
            * UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, y, z));
        let tip_m = world_from_stitch.transform_point(&Point3::from(Vector3::from(key.position_m))).coords;
        let Orientation::Frame { quaternion_xyzw: [x, y, z, w] } =
            recorded_orientation(&asked, &tip_m, &trocars.of(arm)?)
        else {
            continue;
        };
        let given = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, y, z));
        let turn = given * asked.inverse();
        if turn.angle() < WINDING_AIMED_FROM_RAD {
            continue;
        }
        return Ok(Translation3::from(tip_m) * turn * Translation3::from(-tip_m));
    }
    Ok(Isometry3::identity())
}

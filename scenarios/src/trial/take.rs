//! A take aimed where the thread lies: the primitive that brings an instrument's open jaws round the
//! thread ([`knotlab_learner::synthesis::takes`]; the left's L4 down onto the tail) is moved, with the
//! instrument's next primitive (which starts with the thread held), so that the jaws close on the
//! thread where it lies in this scene once settled, not where the demonstration had it relative to the
//! stitch. That is what the expert does (it looks where the tail lies before going down onto it), and
//! what a lab does with the endoscope's view of the thread; here the scene is settled in a copy of the
//! world, every instrument held where it starts, and the thread read from it.

use nalgebra::{Isometry3, Vector3};

use knotlab_hw::geometry::segment_closest_parameters;
use knotlab_learner::synthesis::{PrimitiveOffset, SynthesisError, takes};
use knotlab_sim::grasp::JAW_CENTRE_OFFSET_M;
use knotlab_sim::world::SimWorld;

use super::Learned;

/// How long the copy of the scene settles before the thread is read, s: the tail laid at the start
/// with a loop of slack has sagged onto its rest by 1 s (take_probe, particle 150 from 1 s to 15 s, when
/// the left goes down onto it: 0.15 mm at the workspace map's trial 1 with the assist waiting, 1 mm at
/// its trial 11, within the jaws' 1.6 mm reach).
pub const SETTLE_S: f64 = 1.5;

/// Farthest the settled thread may lie from where the demonstration's jaws closed for the take to be
/// aimed at it, m; further, the take stays as the method puts it.
pub const TAKE_REACH_M: f64 = 0.01;

/// The point of the polyline `points` nearest `to`.
fn nearest_on(points: &[Vector3<f64>], to: &Vector3<f64>) -> Option<Vector3<f64>> {
    points
        .windows(2)
        .map(|w| {
            let d = w[1] - w[0];
            let (s, _) = segment_closest_parameters(&w[0], &d, to, &Vector3::zeros());
            w[0] + d * s
        })
        .min_by(|a, b| (a - to).norm().total_cmp(&(b - to).norm()))
}

/// The offsets (stitch frame) that aim each take of `learned` at the thread of `world`'s scene once
/// settled, for a skill made at `world_from_stitch` (each take's primitive and the instrument's next
/// one by the same offset). None for a take with no thread within [`TAKE_REACH_M`].
pub fn take_offsets(
    world: &SimWorld,
    learned: &Learned,
    world_from_stitch: &Isometry3<f64>,
) -> Result<Vec<PrimitiveOffset>, SynthesisError> {
    let found = takes(&learned.knowledge, &learned.demonstration);
    if found.is_empty() {
        return Ok(Vec::new());
    }
    let settle = |reason: String| SynthesisError::Invalid { field: "take".to_owned(), reason };
    let mut settled = SimWorld::new(world.config().clone(), world.rig().clone())
        .map_err(|e| settle(format!("the scene to settle: {e}")))?;
    let steps = (SETTLE_S / world.config().solver.dt_s).ceil() as usize;
    for _ in 0..steps {
        settled.step().map_err(|e| settle(format!("settling the scene: {e}")))?;
    }
    let thread = settled.thread_centreline();
    let mut offsets = Vec::new();
    for take in found {
        let closed_m =
            world_from_stitch * nalgebra::Point3::from(take.stitch_jaw_centre_m(JAW_CENTRE_OFFSET_M));
        let Some(lies_m) = nearest_on(&thread, &closed_m.coords) else { continue };
        let by_m = lies_m - closed_m.coords;
        if by_m.norm() > TAKE_REACH_M {
            continue;
        }
        let stitch_offset_m = world_from_stitch.rotation.inverse() * by_m;
        offsets.push(PrimitiveOffset { name: take.primitive.clone(), stitch_offset_m });
        if let Some(next) = take.next {
            offsets.push(PrimitiveOffset { name: next, stitch_offset_m });
        }
    }
    Ok(offsets)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The nearest point of a polyline lies on its nearest segment, between its ends.
    #[test]
    fn the_nearest_point_of_a_polyline_is_on_its_nearest_segment() {
        let line = [Vector3::new(0.0, 0.0, 0.0), Vector3::new(1.0, 0.0, 0.0), Vector3::new(1.0, 1.0, 0.0)];
        let p = nearest_on(&line, &Vector3::new(0.4, 0.3, 0.0)).expect("a point");
        assert!((p - Vector3::new(0.4, 0.0, 0.0)).norm() < 1e-12, "{p}");
        let q = nearest_on(&line, &Vector3::new(1.5, 0.8, 0.2)).expect("a point");
        assert!((q - Vector3::new(1.0, 0.8, 0.0)).norm() < 1e-12, "{q}");
        assert!(nearest_on(&line[..1], &Vector3::zeros()).is_none());
    }
}

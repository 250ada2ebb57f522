//! What the knowledge base keeps of the demonstration's timing besides the primitives: the jaws over
//! the whole demonstration (reduced to where they start and stop moving) and which primitive waits for
//! which other instrument's.

use knotlab_hw::rig::ArmName;

use nalgebra::{Isometry3, Vector3};

use super::{Dependency, JawPoint, PathKey};
use crate::demonstration::InstrumentRecord;
use crate::pattern::{PrimitiveSpec, TaskPattern};
use crate::segment::Decomposition;

/// Spacing of the demonstrated path's keys, s.
pub const PATH_PERIOD_S: f64 = 0.1;

/// The tip's path every [`PATH_PERIOD_S`] (and the last sample), in the stitch frame.
pub fn path_keys(record: &InstrumentRecord, stitch_from_world: &Isometry3<f64>) -> Vec<PathKey> {
    let mut keys = Vec::new();
    let mut next = f64::NEG_INFINITY;
    let last = record.samples.len().saturating_sub(1);
    for (k, s) in record.samples.iter().enumerate() {
        if s.time_s + 1e-9 < next && k != last {
            continue;
        }
        next = s.time_s + PATH_PERIOD_S;
        let p = stitch_from_world.transform_point(&s.position_m.into()).coords;
        let stitch_from_tip = stitch_from_world.rotation * s.world_from_tip();
        let d: Vector3<f64> = stitch_from_tip * Vector3::z();
        let q = stitch_from_tip.quaternion();
        keys.push(PathKey {
            time_s: s.time_s,
            position_m: p.into(),
            jaw_direction: d.into(),
            quaternion_xyzw: Some([q.i, q.j, q.k, q.w]),
        });
    }
    keys
}

/// Below this change between two samples the jaw is at rest (sensor noise), rad.
pub const JAW_REST_RAD: f64 = 0.005;

/// The jaw's samples where it starts or stops moving, with the first and the last: linear between
/// them, they retrace each opening and closing.
pub fn jaw_points(record: &InstrumentRecord) -> Vec<JawPoint> {
    let s = &record.samples;
    let point = |k: usize| JawPoint { time_s: s[k].time_s, jaw_rad: s[k].jaw_rad };
    let moving = |k: usize| k + 1 < s.len() && (s[k + 1].jaw_rad - s[k].jaw_rad).abs() > JAW_REST_RAD;
    let mut points = Vec::new();
    for k in 0..s.len() {
        if k == 0 || k + 1 == s.len() || moving(k) != moving(k - 1) {
            points.push(point(k));
        }
    }
    points
}

/// The primitives of `instrument` with both ends on features, with the index of each end.
fn spans(pattern: &TaskPattern, instrument: ArmName) -> Vec<(&PrimitiveSpec, usize, usize)> {
    let Some(ip) = pattern.instrument(instrument) else { return Vec::new() };
    ip.primitives
        .iter()
        .filter_map(|p| {
            let from = ip.element_index(p.from.as_deref()?)?;
            let to = ip.element_index(p.to.as_deref()?)?;
            Some((p, from, to))
        })
        .collect()
}

/// Every cross-instrument `after` of the pattern as a wait between primitives: the feature that waits
/// belongs to the first primitive of its instrument that ends at or after it; the feature waited for
/// to the last primitive of the other instrument that starts at or before it. The pause is the
/// demonstration's, between the one's end and the other's start.
pub fn dependencies(pattern: &TaskPattern, decomposition: &Decomposition) -> Vec<Dependency> {
    let mut out: Vec<Dependency> = Vec::new();
    for ip in &pattern.instruments {
        let own = spans(pattern, ip.instrument);
        for (fi, element) in ip.elements.iter().enumerate() {
            let Some((waits, _, _)) = own.iter().find(|(_, _, to)| *to >= fi) else { continue };
            for g in &element.after {
                let Some((other, gi)) = pattern.find_element(g) else { continue };
                if other == ip.instrument {
                    continue;
                }
                let Some((after, _, _)) =
                    spans(pattern, other).into_iter().rev().find(|(_, from, _)| *from <= gi)
                else {
                    continue;
                };
                let (Some(p), Some(q)) =
                    (decomposition.segment(&waits.name), decomposition.segment(&after.name))
                else {
                    continue;
                };
                if out.iter().any(|d| d.primitive == p.name && d.after == q.name) {
                    continue;
                }
                out.push(Dependency {
                    primitive: p.name.clone(),
                    after: q.name.clone(),
                    pause_s: p.start_s - q.end_s,
                });
            }
        }
    }
    out
}

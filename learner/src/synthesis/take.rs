//! Takes: where an instrument's open jaws, brought round the thread by a linear primitive, close on it
//! (the left's L4 down onto the tail, then its grasp). At a moved site the thread need not lie where
//! the demonstration had it relative to the stitch (the tail hangs from the assist's jaws, which the
//! trocar turns with the site, and sags as the tissue tilts), so the trial aims a take at the thread
//! where it lies, as the expert looks where the tail lies before going down onto it; this module says
//! which primitives are takes and where the demonstration's jaws closed.

use nalgebra::{Isometry3, Point3, Vector3};

use knotlab_hw::rig::ArmName;

use crate::demonstration::{Demonstration, GraspState};
use crate::primitive::{KnowledgeBase, Primitive};

use super::site::pose_isometry;

/// A take in the knowledge base.
#[derive(Clone, Debug, PartialEq)]
pub struct Take {
    /// The instrument.
    pub instrument: ArmName,
    /// The linear primitive that brings its open jaws round the thread.
    pub primitive: String,
    /// The instrument's next primitive, which starts with the thread held (none: the take is its last).
    pub next: Option<String>,
    /// The tip's pose at the primitive's end, `stitch_from_tip`.
    pub stitch_from_tip: Isometry3<f64>,
}

impl Take {
    /// Where the jaws hold what they close on, stitch frame, m: `jaw_centre_offset_m` behind the tip
    /// along its z.
    pub fn stitch_jaw_centre_m(&self, jaw_centre_offset_m: f64) -> Vector3<f64> {
        (self.stitch_from_tip * Point3::new(0.0, 0.0, -jaw_centre_offset_m)).coords
    }
}

/// The takes of `kb`, learned from `demo`: each linear primitive ending with its instrument's jaws open,
/// after which (before the instrument's next primitive starts) the demonstration's jaws came to hold
/// something they did not hold at the primitive's end.
pub fn takes(kb: &KnowledgeBase, demo: &Demonstration) -> Vec<Take> {
    let mut found = Vec::new();
    for ip in &kb.instruments {
        let Ok(arm) = ip.instrument.parse::<ArmName>() else { continue };
        let Some(record) = demo.instrument(arm) else { continue };
        let mut primitives: Vec<&Primitive> = ip.primitives.iter().collect();
        primitives.sort_by(|a, b| a.span_s().0.total_cmp(&b.span_s().0));
        for (k, p) in primitives.iter().enumerate() {
            let Primitive::Linear(line) = p else { continue };
            let next = primitives.get(k + 1);
            let until_s = next.map_or(f64::INFINITY, |n| n.span_s().0);
            let state_at =
                |t: f64| record.samples.iter().take_while(|s| s.time_s <= t).last().map(|s| s.grasp);
            let held_at_end = state_at(line.end_s) == Some(GraspState::Holding);
            let takes_hold = record
                .samples
                .iter()
                .any(|s| s.time_s > line.end_s && s.time_s < until_s && s.grasp == GraspState::Holding);
            if !held_at_end && takes_hold {
                found.push(Take {
                    instrument: arm,
                    primitive: line.name.clone(),
                    next: next.map(|n| n.name().to_owned()),
                    stitch_from_tip: pose_isometry(&line.end_pose),
                });
            }
        }
    }
    found
}

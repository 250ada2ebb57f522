//! The replay baseline: the demonstration itself, every recorded tip pose and jaw angle, rigidly moved to
//! the new stitch frame and played back open-loop on the demonstration's clock (the tip's whole frame
//! where the wrist is bent within its reach: [`super::orientation::recorded_orientation`]). It knows
//! nothing of primitives, obstacles or forces: what it does at the demonstration's own site shows
//! whether the recording captured what matters; what it does elsewhere is the baseline other methods
//! must beat.

use nalgebra::{Isometry3, UnitQuaternion};

use knotlab_hw::skill::{JawKey, PoseKey, Skill, Track};

use crate::demonstration::Demonstration;

use super::orientation::recorded_orientation;
use super::{SynthesisError, Trocars};

/// How the demonstration is played back.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReplaySettings {
    /// A pose key every this many seconds of the recording (the controller interpolates between them);
    /// every change of the jaw is kept.
    pub key_period_s: f64,
}

impl Default for ReplaySettings {
    /// A pose key every 0.2 s. Keys at every 10 ms sample make the arm chase the measured jaw
    /// direction's small wobbles where the wrist is nearly straight (where a small change of direction
    /// is a large turn of the roll): the left then strays up to 4 cm from the recorded path on its way to
    /// the winding point. At 0.2 s it strays about 1 cm there (in free space) and within 0.3 mm of
    /// the recorded path elsewhere.
    fn default() -> Self {
        Self { key_period_s: 0.2 }
    }
}

/// The demonstration moved by `new_world_from_demo_world`, as a skill starting at 0 s (the first
/// sample's time). The tips are commanded by their recorded frame (turned back to the wrist's reach
/// where it is bent further), or along the shaft where the wrist is nearly straight
/// ([`super::orientation::recorded_orientation`]), the shafts through `trocars`.
pub fn replay(
    demo: &Demonstration,
    new_world_from_demo_world: &Isometry3<f64>,
    trocars: &Trocars,
    settings: &ReplaySettings,
) -> Result<Skill, SynthesisError> {
    if !(settings.key_period_s.is_finite() && settings.key_period_s >= 0.0) {
        return Err(SynthesisError::Invalid {
            field: "key_period_s".into(),
            reason: format!("{} is not a period (s >= 0)", settings.key_period_s),
        });
    }
    let t0 = demo
        .instruments
        .iter()
        .filter_map(|r| r.samples.first().map(|s| s.time_s))
        .fold(f64::INFINITY, f64::min);
    let mut tracks = Vec::new();
    for record in &demo.instruments {
        if record.samples.is_empty() {
            return Err(SynthesisError::Empty {
                what: format!("the {} instrument's samples", record.instrument),
            });
        }
        let trocar = trocars.of(record.instrument)?;
        let mut poses = Vec::with_capacity(record.samples.len());
        let mut jaw = Vec::with_capacity(record.samples.len());
        let mut next_key_s = f64::NEG_INFINITY;
        let last = record.samples.len() - 1;
        for (k, s) in record.samples.iter().enumerate() {
            let time_s = s.time_s - t0;
            if jaw.last().is_none_or(|j: &JawKey| j.jaw_rad != s.jaw_rad) || k == last {
                jaw.push(JawKey { time_s, jaw_rad: s.jaw_rad });
            }
            if time_s < next_key_s && k != last {
                continue;
            }
            next_key_s = time_s + settings.key_period_s;
            let position = new_world_from_demo_world.transform_point(&s.position_m.into());
            let rotation: UnitQuaternion<f64> = new_world_from_demo_world.rotation * s.world_from_tip();
            poses.push(PoseKey {
                time_s,
                world_position_m: position.coords.into(),
                orientation: recorded_orientation(&rotation, &position.coords, &trocar),
            });
        }
        tracks.push(Track { arm: record.instrument, poses, jaw, events: Vec::new() });
    }
    Ok(Skill { name: format!("replay of {}", demo.metadata.description), tracks })
}

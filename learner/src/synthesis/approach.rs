//! The way in: a synthesized skill's first keys are where the demonstration's instruments were, which is
//! not where this scene's instruments are (an instrument parked by its trocar does not move with the
//! stitch). Each instrument first goes from where it is to its skill's first pose in a minimum-jerk move
//! (orientation slerped), and the whole skill starts once the slowest has arrived.

use nalgebra::{Isometry3, UnitQuaternion, Vector3};

use knotlab_hw::rig::ArmName;
use knotlab_hw::skill::profile::min_jerk;
use knotlab_hw::skill::{Orientation, PoseKey, Skill};

/// Where an instrument is when the skill is to start.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StartPose {
    /// The instrument.
    pub arm: ArmName,
    /// Its tip, `world_from_tip`.
    pub world_from_tip: Isometry3<f64>,
}

/// How the way in is made.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ApproachSettings {
    /// Mean tip speed, m/s.
    pub speed_mps: f64,
    /// Mean turning speed, rad/s.
    pub turn_rad_per_s: f64,
    /// Closer than this (and turned less than `min_turn_rad`) the instrument needs no way in, m.
    pub min_distance_m: f64,
    /// See `min_distance_m`, rad.
    pub min_turn_rad: f64,
    /// Keys per way in.
    pub keys: usize,
}

impl Default for ApproachSettings {
    /// 2 cm/s and 0.5 rad/s on average (a careful hand), none below 0.5 mm and 0.02 rad, 40 keys.
    fn default() -> Self {
        Self { speed_mps: 0.02, turn_rad_per_s: 0.5, min_distance_m: 5e-4, min_turn_rad: 0.02, keys: 40 }
    }
}

fn key_pose(key: &PoseKey) -> (Vector3<f64>, Option<UnitQuaternion<f64>>) {
    let p = Vector3::from(key.world_position_m);
    let q = match key.orientation {
        Orientation::Frame { quaternion_xyzw: [x, y, z, w] } => {
            Some(UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, y, z)))
        }
        _ => None,
    };
    (p, q)
}

/// Prepends to every track of `skill` whose instrument is in `starts` a way in from where it is; returns
/// how long the way in lasts (every key and event of the skill is delayed by it).
pub fn prepend_approach(skill: &mut Skill, starts: &[StartPose], settings: &ApproachSettings) -> f64 {
    let mut ways: Vec<(usize, Vec<PoseKey>)> = Vec::new();
    let mut lead_s = 0.0f64;
    for (t, track) in skill.tracks.iter().enumerate() {
        let Some(start) = starts.iter().find(|s| s.arm == track.arm) else { continue };
        let Some(first) = track.poses.first() else { continue };
        let (to_p, to_q) = key_pose(first);
        let from_p = start.world_from_tip.translation.vector;
        let from_q = start.world_from_tip.rotation;
        let distance = (to_p - from_p).norm();
        let turn = to_q.map_or(0.0, |q| from_q.angle_to(&q));
        if distance < settings.min_distance_m && turn < settings.min_turn_rad {
            continue;
        }
        let duration = (distance / settings.speed_mps).max(turn / settings.turn_rad_per_s).max(0.2);
        lead_s = lead_s.max(duration);
        let n = settings.keys.max(2);
        let keys = (0..n)
            .map(|k| {
                let s = min_jerk(k as f64 / (n - 1) as f64);
                let q = to_q.map_or(from_q, |q| from_q.slerp(&q, s));
                let q = q.quaternion();
                PoseKey {
                    time_s: duration * k as f64 / (n - 1) as f64,
                    world_position_m: from_p.lerp(&to_p, s).into(),
                    orientation: Orientation::Frame { quaternion_xyzw: [q.i, q.j, q.k, q.w] },
                }
            })
            .collect();
        ways.push((t, keys));
    }
    if lead_s == 0.0 {
        return 0.0;
    }
    for track in &mut skill.tracks {
        for key in &mut track.poses {
            key.time_s += lead_s;
        }
        for key in &mut track.jaw {
            key.time_s += lead_s;
        }
        for event in &mut track.events {
            event.from_s += lead_s;
            event.until_s += lead_s;
        }
    }
    for (t, mut keys) in ways {
        // The way in ends where the track's first key is, once the slowest has arrived.
        let duration = keys.last().map_or(0.0, |k| k.time_s);
        // Not below zero: `duration * k / (n - 1)` can round above the duration `lead_s` came from,
        // which put the slowest way's first key at -2e-16 s (a skill the controller refuses).
        let shift = (lead_s - duration).max(0.0);
        for key in &mut keys {
            key.time_s += shift;
        }
        keys.pop();
        let track = &mut skill.tracks[t];
        keys.append(&mut track.poses);
        track.poses = keys;
    }
    lead_s
}

#[cfg(test)]
mod tests {
    use super::*;
    use knotlab_hw::skill::{JawKey, Track};

    fn frame_key(time_s: f64, x: f64) -> PoseKey {
        PoseKey {
            time_s,
            world_position_m: [x, 0.0, 1.0],
            orientation: Orientation::Frame { quaternion_xyzw: [0.0, 0.0, 0.0, 1.0] },
        }
    }

    /// An instrument starting 4 cm away gets a 2 s way in at 2 cm/s and every track's keys wait for it;
    /// one already at its first key gets no way in, only the wait.
    #[test]
    fn a_far_instrument_comes_in_and_everything_waits_for_it() {
        let mut skill = Skill {
            name: "t".into(),
            tracks: vec![
                Track {
                    arm: ArmName::Left,
                    poses: vec![frame_key(0.0, 0.0), frame_key(1.0, 0.01)],
                    jaw: vec![JawKey { time_s: 0.5, jaw_rad: 0.0 }],
                    events: Vec::new(),
                },
                Track {
                    arm: ArmName::Right,
                    poses: vec![frame_key(0.0, 0.1)],
                    jaw: Vec::new(),
                    events: Vec::new(),
                },
            ],
        };
        let starts = [
            StartPose { arm: ArmName::Left, world_from_tip: Isometry3::translation(-0.04, 0.0, 1.0) },
            StartPose { arm: ArmName::Right, world_from_tip: Isometry3::translation(0.1, 0.0, 1.0) },
        ];
        let lead = prepend_approach(&mut skill, &starts, &ApproachSettings::default());
        assert!((lead - 2.0).abs() < 1e-9, "4 cm at 2 cm/s: {lead}");
        let left = &skill.tracks[0];
        assert_eq!(left.poses[0].world_position_m, [-0.04, 0.0, 1.0]);
        assert!(left.poses.windows(2).all(|w| w[1].time_s > w[0].time_s));
        assert_eq!(left.jaw[0].time_s, 2.5);
        let right = &skill.tracks[1];
        assert_eq!(right.poses.len(), 1, "already there: no way in");
        assert_eq!(right.poses[0].time_s, 2.0);
        skill.check().unwrap();
    }
}

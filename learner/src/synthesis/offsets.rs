//! A synthesized skill with each primitive moved by an offset of its own (stitch frame): what a
//! residual or black-box method adds to the paper's. An instrument's pose keys within a primitive's
//! span move by its offset; between two of the instrument's primitives the offset blends linearly from
//! the one to the next; before its first it is the first's, after its last the last's.

use nalgebra::{UnitQuaternion, Vector3};

use knotlab_hw::rig::ArmName;
use knotlab_hw::skill::Skill;

use super::SynthesisError;

/// Where a primitive runs in a skill.
#[derive(Clone, Debug, PartialEq)]
pub struct PrimitiveSpan {
    /// The primitive.
    pub name: String,
    /// Its instrument.
    pub arm: ArmName,
    /// Its start and end in the skill, s.
    pub skill_s: (f64, f64),
}

/// How far one primitive moves, stitch frame, m.
#[derive(Clone, Debug, PartialEq)]
pub struct PrimitiveOffset {
    /// The primitive.
    pub name: String,
    /// Its offset, m.
    pub stitch_offset_m: Vector3<f64>,
}

/// The offset at `time_s` of an instrument whose primitives are `spans` (in time order) with offsets
/// (their start, end and offset, world frame).
fn offset_at(spans: &[(f64, f64, Vector3<f64>)], time_s: f64) -> Vector3<f64> {
    let Some(first) = spans.first() else { return Vector3::zeros() };
    if time_s <= first.1 {
        return first.2;
    }
    for w in spans.windows(2) {
        let (a, b) = (&w[0], &w[1]);
        if time_s <= a.1 {
            return a.2;
        }
        if time_s < b.0 {
            let f = (time_s - a.1) / (b.0 - a.1);
            return a.2.lerp(&b.2, f);
        }
        if time_s <= b.1 {
            return b.2;
        }
    }
    spans[spans.len() - 1].2
}

/// Moves `skill`'s primitives by `offsets` (stitch frame, turned into the world by
/// `world_from_stitch`); a primitive without an offset stays. Every offset must name a primitive of
/// `spans` and be finite.
pub fn offset_primitives(
    skill: &mut Skill,
    spans: &[PrimitiveSpan],
    offsets: &[PrimitiveOffset],
    world_from_stitch: &UnitQuaternion<f64>,
) -> Result<(), SynthesisError> {
    for o in offsets {
        if !spans.iter().any(|s| s.name == o.name) {
            let names: Vec<&str> = spans.iter().map(|s| s.name.as_str()).collect();
            return Err(SynthesisError::Invalid {
                field: format!("offsets.{}", o.name),
                reason: format!("no such primitive (the skill's: {})", names.join(", ")),
            });
        }
        if !o.stitch_offset_m.iter().all(|x| x.is_finite()) {
            return Err(SynthesisError::Invalid {
                field: format!("offsets.{}", o.name),
                reason: format!("{:?} is not finite", o.stitch_offset_m.as_slice()),
            });
        }
    }
    for track in &mut skill.tracks {
        let mut mine: Vec<(f64, f64, Vector3<f64>)> = spans
            .iter()
            .filter(|s| s.arm == track.arm)
            .map(|s| {
                let by =
                    offsets.iter().find(|o| o.name == s.name).map_or(Vector3::zeros(), |o| o.stitch_offset_m);
                (s.skill_s.0, s.skill_s.1, world_from_stitch * by)
            })
            .collect();
        mine.sort_by(|a, b| a.0.total_cmp(&b.0));
        if mine.iter().all(|s| s.2 == Vector3::zeros()) {
            continue;
        }
        for key in &mut track.poses {
            let by = offset_at(&mine, key.time_s);
            for (x, d) in key.world_position_m.iter_mut().zip(by.iter()) {
                *x += d;
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Inside a primitive its offset, between two a blend, before the first the first's, after the
    /// last the last's.
    #[test]
    fn offsets_hold_within_primitives_and_blend_between_them() {
        let (a, b) = (Vector3::new(1.0, 0.0, 0.0), Vector3::new(0.0, 2.0, 0.0));
        let spans = [(1.0, 2.0, a), (4.0, 5.0, b)];
        assert_eq!(offset_at(&spans, 0.0), a);
        assert_eq!(offset_at(&spans, 1.5), a);
        assert_eq!(offset_at(&spans, 3.0), Vector3::new(0.5, 1.0, 0.0));
        assert_eq!(offset_at(&spans, 4.5), b);
        assert_eq!(offset_at(&spans, 9.0), b);
        assert_eq!(offset_at(&[], 1.0), Vector3::zeros());
    }

    /// A primitive's offset moves its instrument's keys, turned into the world by the stitch's
    /// rotation; another instrument's keys stay; an offset naming no primitive is refused by name.
    #[test]
    fn an_offset_moves_its_primitives_keys_in_the_stitch_frame() {
        use knotlab_hw::skill::{PoseKey, Track};
        let track = |arm| Track {
            arm,
            poses: (0..=4)
                .map(|k| PoseKey {
                    time_s: k as f64,
                    world_position_m: [0.0; 3],
                    orientation: Default::default(),
                })
                .collect(),
            jaw: Vec::new(),
            events: Vec::new(),
        };
        let mut skill =
            Skill { name: "test".into(), tracks: vec![track(ArmName::Left), track(ArmName::Right)] };
        let spans = [
            PrimitiveSpan { name: "L1".into(), arm: ArmName::Left, skill_s: (1.0, 2.0) },
            PrimitiveSpan { name: "R1".into(), arm: ArmName::Right, skill_s: (1.0, 2.0) },
        ];
        let offsets = [PrimitiveOffset { name: "L1".into(), stitch_offset_m: Vector3::new(0.001, 0.0, 0.0) }];
        let quarter = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), std::f64::consts::FRAC_PI_2);
        offset_primitives(&mut skill, &spans, &offsets, &quarter).expect("offsets");
        for key in &skill.tracks[0].poses {
            let [x, y, z] = key.world_position_m;
            assert!(x.abs() < 1e-15 && (y - 0.001).abs() < 1e-15 && z == 0.0, "{key:?}");
        }
        assert!(skill.tracks[1].poses.iter().all(|k| k.world_position_m == [0.0; 3]));
        let unknown = [PrimitiveOffset { name: "L9".into(), stitch_offset_m: Vector3::zeros() }];
        let error = offset_primitives(&mut skill, &spans, &unknown, &quarter).expect_err("no L9");
        assert!(error.to_string().contains("L9") && error.to_string().contains("L1, R1"), "{error}");
    }
}

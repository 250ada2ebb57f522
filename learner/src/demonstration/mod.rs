//! A recorded demonstration: what each instrument's devices read while a surgeon (or the scripted
//! expert) performed the task. Plain data, no physics engine: per instrument, time-stamped tip pose, jaw
//! angle, grasp state and measured force, plus metadata (scene, stitch pose, sample rate, source).
//!
//! On disk a demonstration is a directory: `demo.toml` (the metadata) and one CSV file per instrument
//! (`left.csv`, `right.csv`, `assist.csv`), documented for readers without knotlab in `FORMAT.md` beside
//! this file. [`write_demonstration`] writes one, [`load_demonstration`] reads and validates one: a
//! truncated file, a missing column, a NaN, time that does not increase or an unknown format version is
//! an error naming the file, the line and the field ([`DemoError`]).

pub mod csv;
pub mod error;
pub mod load;
pub mod metadata;
pub mod write;

pub use error::DemoError;
pub use load::{load_demonstration, read_demonstration_dir};
pub use write::write_demonstration;

use nalgebra::{Isometry3, Quaternion, Translation3, UnitQuaternion, Vector3};

use knotlab_hw::rig::ArmName;

/// The version of the on-disk format this knotlab writes and reads.
pub const FORMAT_VERSION: u32 = 1;

/// The lowest sample rate a demonstration may have, Hz.
pub const MIN_SAMPLE_RATE_HZ: f64 = 100.0;

/// What an instrument's jaws were doing at a sample.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum GraspState {
    /// Jaws open: nothing held.
    Open,
    /// Jaws closed on something (thread, needle, tissue).
    Holding,
    /// Jaws closed on nothing.
    ClosedEmpty,
}

impl GraspState {
    /// All three, in a fixed order.
    pub const ALL: [GraspState; 3] = [GraspState::Open, GraspState::Holding, GraspState::ClosedEmpty];

    /// The word in the CSV files: `open`, `holding`, `closed_empty`.
    pub fn as_str(self) -> &'static str {
        match self {
            GraspState::Open => "open",
            GraspState::Holding => "holding",
            GraspState::ClosedEmpty => "closed_empty",
        }
    }

    /// The state a word names.
    pub fn parse(word: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|g| g.as_str() == word)
    }
}

/// One sample of one instrument. Positions and forces are in the world frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// Time since the recording started, s.
    pub time_s: f64,
    /// Tip position (the point between the jaws), world frame, m.
    pub position_m: Vector3<f64>,
    /// Tip orientation, `world_from_tip` as a unit quaternion `x, y, z, w` (tip z along the jaws).
    pub quaternion_xyzw: [f64; 4],
    /// Angle between the jaws, rad (0 closed).
    pub jaw_rad: f64,
    /// What the jaws hold.
    pub grasp: GraspState,
    /// Force measured on the instrument (what the environment exerts on it), world frame, N.
    pub force_n: Vector3<f64>,
}

impl Sample {
    /// The tip orientation as a rotation, `world_from_tip`.
    pub fn world_from_tip(&self) -> UnitQuaternion<f64> {
        let [x, y, z, w] = self.quaternion_xyzw;
        UnitQuaternion::from_quaternion(Quaternion::new(w, x, y, z))
    }
}

/// The samples of one instrument, in increasing time.
#[derive(Clone, Debug, PartialEq)]
pub struct InstrumentRecord {
    /// Which instrument (left, right or assist).
    pub instrument: ArmName,
    /// The samples.
    pub samples: Vec<Sample>,
}

impl InstrumentRecord {
    /// The CSV file name of this instrument inside a demonstration directory (`left.csv`).
    pub fn file_name(&self) -> String {
        format!("{}.csv", self.instrument.as_str())
    }

    /// Time of the first and the last sample, s (`None` without samples).
    pub fn time_span_s(&self) -> Option<(f64, f64)> {
        Some((self.samples.first()?.time_s, self.samples.last()?.time_s))
    }

    /// The sample nearest in time to `time_s` (the earlier of two equally near; `None` without
    /// samples or for a time that is not a number).
    pub fn sample_nearest(&self, time_s: f64) -> Option<&Sample> {
        if time_s.is_nan() {
            return None;
        }
        self.samples.iter().min_by(|a, b| (a.time_s - time_s).abs().total_cmp(&(b.time_s - time_s).abs()))
    }
}

/// The stitch frame in the world: where the task was performed. Everything learned from the
/// demonstration is stored relative to it, so it can be moved to another site.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StitchPose {
    /// Origin of the stitch frame in the world, m.
    pub position_m: [f64; 3],
    /// `world_from_stitch` rotation as a unit quaternion `x, y, z, w` (x along the wound, y across it
    /// towards the tail's flap, z out of the tissue).
    pub quaternion_xyzw: [f64; 4],
}

impl StitchPose {
    /// The identity: the stitch frame is the world frame.
    pub fn identity() -> Self {
        Self { position_m: [0.0; 3], quaternion_xyzw: [0.0, 0.0, 0.0, 1.0] }
    }

    /// A pose from a rigid transform.
    pub fn from_isometry(world_from_stitch: &Isometry3<f64>) -> Self {
        let t = world_from_stitch.translation.vector;
        let q = world_from_stitch.rotation.quaternion();
        Self { position_m: [t.x, t.y, t.z], quaternion_xyzw: [q.i, q.j, q.k, q.w] }
    }

    /// The transform `world_from_stitch` (the quaternion normalised).
    pub fn world_from_stitch(&self) -> Isometry3<f64> {
        let [x, y, z, w] = self.quaternion_xyzw;
        Isometry3::from_parts(
            Translation3::from(Vector3::from(self.position_m)),
            UnitQuaternion::from_quaternion(Quaternion::new(w, x, y, z)),
        )
    }
}

/// What the demonstration is and where it came from.
#[derive(Clone, Debug, PartialEq)]
pub struct Metadata {
    /// The format version the data follows ([`FORMAT_VERSION`] when written by this knotlab).
    pub format_version: u32,
    /// Who performed it: `scripted expert`, `teleoperation`, `synthetic`, ...
    pub source: String,
    /// The scene file it was recorded in (a path as given to the recorder; empty when none).
    pub scene: String,
    /// The seed of the recording's random draws, if any.
    pub seed: Option<u64>,
    /// The nominal sample rate, Hz (at least [`MIN_SAMPLE_RATE_HZ`]).
    pub sample_rate_hz: f64,
    /// The stitch frame in the world.
    pub stitch: StitchPose,
    /// Free text.
    pub description: String,
}

/// A demonstration: metadata and one record per instrument.
#[derive(Clone, Debug, PartialEq)]
pub struct Demonstration {
    /// What it is.
    pub metadata: Metadata,
    /// The instruments, each once.
    pub instruments: Vec<InstrumentRecord>,
}

impl Demonstration {
    /// The record of one instrument.
    pub fn instrument(&self, name: ArmName) -> Option<&InstrumentRecord> {
        self.instruments.iter().find(|r| r.instrument == name)
    }

    /// From the earliest to the latest sample of any instrument, s (0 without samples).
    pub fn duration_s(&self) -> f64 {
        let spans: Vec<(f64, f64)> =
            self.instruments.iter().filter_map(InstrumentRecord::time_span_s).collect();
        let start = spans.iter().map(|s| s.0).fold(f64::INFINITY, f64::min);
        let end = spans.iter().map(|s| s.1).fold(f64::NEG_INFINITY, f64::max);
        if spans.is_empty() { 0.0 } else { end - start }
    }

    /// The latest sample time of any instrument, s (`None` without samples).
    pub fn end_time_s(&self) -> Option<f64> {
        self.instruments.iter().filter_map(|r| r.time_span_s().map(|s| s.1)).reduce(f64::max)
    }

    /// Checks what the loader checks, on data in memory (before writing, or after building one):
    /// errors name the instrument's file, the sample's line as it would be written, and the field.
    pub fn validate(&self) -> Result<(), DemoError> {
        metadata::validate_metadata(&self.metadata, metadata::METADATA_FILE)?;
        let mut seen = Vec::new();
        if self.instruments.is_empty() {
            return Err(DemoError::format(metadata::METADATA_FILE, 0, "instrument", "no instruments"));
        }
        for record in &self.instruments {
            if !record.instrument.carries_instrument() {
                return Err(DemoError::format(
                    metadata::METADATA_FILE,
                    0,
                    "instrument.name",
                    "'camera' is the endoscope, not an instrument",
                ));
            }
            if seen.contains(&record.instrument) {
                return Err(DemoError::format(
                    metadata::METADATA_FILE,
                    0,
                    "instrument.name",
                    format!("'{}' appears twice", record.instrument),
                ));
            }
            seen.push(record.instrument);
            csv::validate_samples(&record.samples, &record.file_name(), self.metadata.sample_rate_hz)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The sample nearest a time is found, a tie goes to the earlier, a time past either end finds that end,
    /// and a NaN time or an empty record finds none.
    #[test]
    fn the_sample_nearest_a_time_is_found_and_ties_go_to_the_earlier() {
        let at = |time_s: f64| Sample {
            time_s,
            position_m: Vector3::new(time_s, 0.0, 0.0),
            quaternion_xyzw: [0.0, 0.0, 0.0, 1.0],
            jaw_rad: 0.0,
            grasp: GraspState::Open,
            force_n: Vector3::zeros(),
        };
        let record =
            InstrumentRecord { instrument: ArmName::Left, samples: vec![at(0.0), at(0.01), at(0.02)] };
        assert_eq!(record.sample_nearest(0.012).map(|s| s.time_s), Some(0.01));
        assert_eq!(record.sample_nearest(0.015).map(|s| s.time_s), Some(0.01));
        assert_eq!(record.sample_nearest(-5.0).map(|s| s.time_s), Some(0.0));
        assert_eq!(record.sample_nearest(9.0).map(|s| s.time_s), Some(0.02));
        assert!(record.sample_nearest(f64::NAN).is_none());
        assert!(
            InstrumentRecord { instrument: ArmName::Left, samples: vec![] }.sample_nearest(0.0).is_none()
        );
    }
}

//! The verdict of one knot-tying trial, as Monte Carlo tallies it: success, or failure with one mode.

use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

use super::classify::{Classification, KnotType};
use super::tightness::{DownLimits, KnotPlacement, TissueSurface};

/// Why a trial failed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FailureMode {
    /// The thread holds no knot.
    NoKnot,
    /// A knot, but not one the task accepts (a granny for a square, say).
    WrongKnotType,
    /// The right knot, not down on the tissue at the stitch.
    KnotNotDown,
    /// The knot was down but did not hold once the instruments let go.
    KnotSlipped,
    /// The simulated thread blew up or tunnelled through itself.
    ThreadUnstable,
    /// The skill's collision preview found an arm's link against something (the trial's
    /// `TrialRun::verdict`): on real devices it would not run.
    Collision,
    /// A motion's target was out of the arms' reach in the kinematic preview, or (Monte Carlo) the
    /// trial could not be set up.
    Unreachable,
    /// A device reported a fault.
    DeviceFault,
}

impl FailureMode {
    /// Every mode, in a fixed order.
    pub const ALL: [FailureMode; 8] = [
        FailureMode::NoKnot,
        FailureMode::WrongKnotType,
        FailureMode::KnotNotDown,
        FailureMode::KnotSlipped,
        FailureMode::ThreadUnstable,
        FailureMode::Collision,
        FailureMode::Unreachable,
        FailureMode::DeviceFault,
    ];

    /// The snake_case name (as serde writes it).
    pub fn name(self) -> &'static str {
        match self {
            FailureMode::NoKnot => "no_knot",
            FailureMode::WrongKnotType => "wrong_knot_type",
            FailureMode::KnotNotDown => "knot_not_down",
            FailureMode::KnotSlipped => "knot_slipped",
            FailureMode::ThreadUnstable => "thread_unstable",
            FailureMode::Collision => "collision",
            FailureMode::Unreachable => "unreachable",
            FailureMode::DeviceFault => "device_fault",
        }
    }
}

/// The outcome of one trial: serialises as `"success"` or `{"failure": "knot_not_down"}`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Verdict {
    /// The accepted knot, down on the tissue (and, once the simulator tests it, holding).
    Success,
    /// A failure, with its mode.
    Failure(FailureMode),
}

impl Verdict {
    /// `"success"` or the failure mode's name: one label per tally bucket.
    pub fn label(self) -> &'static str {
        match self {
            Verdict::Success => "success",
            Verdict::Failure(mode) => mode.name(),
        }
    }
}

/// Where the knot must end up: the tissue surface and the stitch point on it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StitchSite {
    /// The tissue surface near the stitch.
    pub surface: TissueSurface,
    /// The stitch point (where the knot should sit), m.
    pub stitch_m: Vector3<f64>,
}

/// The topology-and-tightness part of a verdict: no knot, a knot not in `accepted`, a knot not down,
/// or success. (Slipping, instability, collisions, reach and faults are decided by the simulator.)
pub fn judge(
    classification: &Classification,
    accepted: &[KnotType],
    site: &StitchSite,
    limits: &DownLimits,
) -> Verdict {
    if classification.knot == KnotType::Unknot {
        return Verdict::Failure(FailureMode::NoKnot);
    }
    if !accepted.contains(&classification.knot) {
        return Verdict::Failure(FailureMode::WrongKnotType);
    }
    let down = classification
        .span
        .as_ref()
        .is_some_and(|span| KnotPlacement::measure(span, &site.surface, &site.stitch_m).is_down(limits));
    if down { Verdict::Success } else { Verdict::Failure(FailureMode::KnotNotDown) }
}

#[cfg(test)]
mod tests {
    use serde::de::IntoDeserializer;

    use super::*;

    /// Every failure mode's name and the success verdict's read back through serde as themselves, and the
    /// eight failure modes' names are distinct.
    #[test]
    fn names_are_snake_case_and_distinct() {
        for mode in FailureMode::ALL {
            let de: serde::de::value::StrDeserializer<'_, serde::de::value::Error> =
                mode.name().into_deserializer();
            assert_eq!(FailureMode::deserialize(de), Ok(mode));
            assert_eq!(Verdict::Failure(mode).label(), mode.name());
        }
        assert_eq!(Verdict::Success.label(), "success");
        let de: serde::de::value::StrDeserializer<'_, serde::de::value::Error> =
            "success".into_deserializer();
        assert_eq!(Verdict::deserialize(de), Ok(Verdict::Success));
        let mut names: Vec<&str> = FailureMode::ALL.iter().map(|m| m.name()).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), 8);
    }
}

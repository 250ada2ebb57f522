//! The kinds of feature found in a demonstration, with the names a task pattern uses for them.

use std::fmt;

/// What a feature is. The magnitude a [`super::Feature`] carries depends on the kind (see each).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum FeatureKind {
    /// The tip starts to move after a rest. Magnitude: the path length of the motion, m.
    MotionStart,
    /// The tip comes to rest. Magnitude: the path length of the motion that ends, m.
    MotionStop,
    /// A peak of the tip's tangential acceleration above the threshold. Magnitude: m/s^2.
    Acceleration,
    /// A peak of the tip's tangential deceleration above the threshold. Magnitude: m/s^2 (positive).
    Deceleration,
    /// The path's curvature changes sign in its locally fitted plane. Magnitude: the smaller of the two
    /// curvatures either side, 1/m.
    Inflection,
    /// The tip's direction has turned through a full turn in its plane since the motion started, the
    /// last inflection or the last loop. Magnitude: the loop's diameter, m.
    Loop,
    /// The measured force rises above the onset threshold. Magnitude: the peak of that force episode, N.
    ForceOnset,
    /// The largest force of an episode. Magnitude: that force, N.
    ForcePeak,
    /// The force falls below the release threshold. Magnitude: the peak of the episode that ends, N.
    ForceRelease,
    /// The jaws open. Magnitude: the angle they open to, rad.
    JawOpen,
    /// The jaws close. Magnitude: the angle they close from, rad.
    JawClose,
}

impl FeatureKind {
    /// Every kind, in a fixed order.
    pub const ALL: [FeatureKind; 11] = [
        FeatureKind::MotionStart,
        FeatureKind::MotionStop,
        FeatureKind::Acceleration,
        FeatureKind::Deceleration,
        FeatureKind::Inflection,
        FeatureKind::Loop,
        FeatureKind::ForceOnset,
        FeatureKind::ForcePeak,
        FeatureKind::ForceRelease,
        FeatureKind::JawOpen,
        FeatureKind::JawClose,
    ];

    /// The name in task patterns and reports (`motion_start`, `loop`, ...).
    pub fn as_str(self) -> &'static str {
        match self {
            FeatureKind::MotionStart => "motion_start",
            FeatureKind::MotionStop => "motion_stop",
            FeatureKind::Acceleration => "acceleration",
            FeatureKind::Deceleration => "deceleration",
            FeatureKind::Inflection => "inflection",
            FeatureKind::Loop => "loop",
            FeatureKind::ForceOnset => "force_onset",
            FeatureKind::ForcePeak => "force_peak",
            FeatureKind::ForceRelease => "force_release",
            FeatureKind::JawOpen => "jaw_open",
            FeatureKind::JawClose => "jaw_close",
        }
    }

    /// The kind a name denotes.
    pub fn parse(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|k| k.as_str() == name)
    }

    /// The unit of the magnitude.
    pub fn magnitude_unit(self) -> &'static str {
        match self {
            FeatureKind::MotionStart | FeatureKind::MotionStop | FeatureKind::Loop => "m",
            FeatureKind::Acceleration | FeatureKind::Deceleration => "m/s^2",
            FeatureKind::Inflection => "1/m",
            FeatureKind::ForceOnset | FeatureKind::ForcePeak | FeatureKind::ForceRelease => "N",
            FeatureKind::JawOpen | FeatureKind::JawClose => "rad",
        }
    }
}

impl fmt::Display for FeatureKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

//! The checks a skill must pass before it runs; every bad field is named with its path
//! (`tracks[1].poses[3].time_s`).

use std::fmt;

use nalgebra::Vector3;

use super::keys::Orientation;
use super::{ForceAction, Skill};

/// One thing wrong with a skill.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SkillProblem {
    /// The field's path.
    pub path: String,
    /// What is wrong.
    pub reason: String,
}

impl fmt::Display for SkillProblem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.path, self.reason)
    }
}

/// A skill that cannot run, with every problem found.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("skill '{name}': {}", problems.iter().map(ToString::to_string).collect::<Vec<_>>().join("; "))]
pub struct SkillError {
    /// The skill's name.
    pub name: String,
    /// What is wrong.
    pub problems: Vec<SkillProblem>,
}

struct Problems(Vec<SkillProblem>);

impl Problems {
    fn add(&mut self, path: impl Into<String>, reason: impl Into<String>) {
        self.0.push(SkillProblem { path: path.into(), reason: reason.into() });
    }

    /// Times must be finite, not negative, and strictly increasing.
    fn times(&mut self, path: &str, times: impl Iterator<Item = f64>) {
        let mut previous: Option<f64> = None;
        for (i, t) in times.enumerate() {
            if !t.is_finite() || t < 0.0 {
                self.add(format!("{path}[{i}].time_s"), format!("{t} is not a time from the start (s >= 0)"));
            } else if let Some(p) = previous
                && t <= p
            {
                self.add(
                    format!("{path}[{i}].time_s"),
                    format!("{t} s is not after the previous key ({p} s)"),
                );
            }
            previous = Some(t);
        }
    }
}

impl Skill {
    /// Checks the skill: at most one track per arm, at least one pose per track, times increasing,
    /// finite values, sensible orientations, event windows and thresholds, nothing the endoscope
    /// cannot do.
    pub fn check(&self) -> Result<(), SkillError> {
        let mut p = Problems(Vec::new());
        for (t, track) in self.tracks.iter().enumerate() {
            let at = format!("tracks[{t}]");
            if self.tracks[..t].iter().any(|other| other.arm == track.arm) {
                p.add(format!("{at}.arm"), format!("a second track for the {} arm", track.arm));
            }
            if track.poses.is_empty() {
                p.add(format!("{at}.poses"), "a track needs at least one pose");
            }
            p.times(&format!("{at}.poses"), track.poses.iter().map(|k| k.time_s));
            for (k, key) in track.poses.iter().enumerate() {
                let kp = format!("{at}.poses[{k}]");
                if key.world_position_m.iter().any(|x| !x.is_finite()) {
                    p.add(format!("{kp}.world_position_m"), "not finite");
                }
                match key.orientation {
                    Orientation::AlongShaft => {}
                    _ if !track.arm.carries_instrument() => p.add(
                        format!("{kp}.orientation"),
                        "the endoscope looks along its shaft: only along_shaft is possible",
                    ),
                    Orientation::JawDirection { direction } => {
                        let v = Vector3::from(direction);
                        let usable = v.norm() > 1e-9;
                        if !usable {
                            p.add(format!("{kp}.orientation.direction"), "zero or not finite");
                        }
                    }
                    Orientation::Frame { quaternion_xyzw } => {
                        let n = quaternion_xyzw.iter().map(|x| x * x).sum::<f64>().sqrt();
                        let unit = (n - 1.0).abs() <= 1e-6;
                        if !unit {
                            p.add(
                                format!("{kp}.orientation.quaternion_xyzw"),
                                format!("not a unit quaternion (norm {n})"),
                            );
                        }
                    }
                }
            }
            p.times(&format!("{at}.jaw"), track.jaw.iter().map(|k| k.time_s));
            if !track.arm.carries_instrument() && !track.jaw.is_empty() {
                p.add(format!("{at}.jaw"), "the endoscope has no jaw");
            }
            for (k, key) in track.jaw.iter().enumerate() {
                if !key.jaw_rad.is_finite() || key.jaw_rad < 0.0 {
                    p.add(
                        format!("{at}.jaw[{k}].jaw_rad"),
                        format!("{} is not an opening (rad >= 0)", key.jaw_rad),
                    );
                }
            }
            for (e, event) in track.events.iter().enumerate() {
                let ep = format!("{at}.events[{e}]");
                if !track.arm.carries_instrument() {
                    p.add(&ep, "the endoscope has no force sensor");
                }
                if !(event.from_s.is_finite() && event.until_s.is_finite() && 0.0 <= event.from_s)
                    || event.until_s < event.from_s
                {
                    p.add(
                        format!("{ep}.until_s"),
                        format!(
                            "window {}..{} s is not a time window from the start",
                            event.from_s, event.until_s
                        ),
                    );
                }
                if !(event.threshold_n.is_finite() && event.threshold_n > 0.0) {
                    p.add(
                        format!("{ep}.threshold_n"),
                        format!("{} is not a force above zero (N)", event.threshold_n),
                    );
                }
                if !(event.sustain_s.is_finite() && event.sustain_s >= 0.0) {
                    p.add(
                        format!("{ep}.sustain_s"),
                        format!("{} is not a duration (s >= 0)", event.sustain_s),
                    );
                }
                if let Some(name) = &event.fires_with {
                    let elsewhere = self.tracks.iter().enumerate().any(|(other, o)| {
                        o.events.iter().any(|e| &e.name == name && (other != t || e.name != event.name))
                    });
                    if !elsewhere {
                        p.add(
                            format!("{ep}.fires_with"),
                            format!("no other event (of this track or another) is named {name:?}"),
                        );
                    }
                }
                if let ForceAction::OpenJaw { jaw_rad } = event.action
                    && !(jaw_rad.is_finite() && jaw_rad >= 0.0)
                {
                    p.add(format!("{ep}.action.jaw_rad"), format!("{jaw_rad} is not an opening (rad >= 0)"));
                }
                if let ForceAction::Give { set_force_n, rate_m_per_n_s } = event.action {
                    if !(set_force_n.is_finite() && set_force_n > 0.0) {
                        p.add(
                            format!("{ep}.action.set_force_n"),
                            format!("{set_force_n} is not a force above zero (N)"),
                        );
                    }
                    if !(rate_m_per_n_s.is_finite() && rate_m_per_n_s > 0.0) {
                        p.add(
                            format!("{ep}.action.rate_m_per_n_s"),
                            format!("{rate_m_per_n_s} is not a rate above zero (m/(N s))"),
                        );
                    }
                }
            }
        }
        if p.0.is_empty() { Ok(()) } else { Err(SkillError { name: self.name.clone(), problems: p.0 }) }
    }
}

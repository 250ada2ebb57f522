//! A demonstration as an episode's commands: each instrument's recorded tip poses and jaw openings,
//! taken at the episode's control rate, turned into the velocities, turn rates and openings that
//! carry the targets from one recorded sample to the next.

use knotlab_hw::rig::ArmName;
use knotlab_learner::demonstration::{Demonstration, Sample};

use super::{ARMS, EpisodeError, EpisodeSettings, TipCommand};

/// The commands that play `demo` back at `settings.control_hz` (its samples every `1 / control_hz`
/// s, which must be a whole number of its sample periods), from its first sample to its last.
pub fn demonstration_commands(
    demo: &Demonstration,
    settings: &EpisodeSettings,
) -> Result<Vec<[TipCommand; 3]>, EpisodeError> {
    let dt_s = 1.0 / settings.control_hz;
    let samples: Vec<&[Sample]> = ARMS
        .iter()
        .map(|arm| {
            demo.instruments.iter().find(|i| i.instrument == *arm).map(|i| i.samples.as_slice()).ok_or_else(
                || EpisodeError::Settings {
                    field: "demonstration",
                    reason: format!("it has no {arm} instrument"),
                },
            )
        })
        .collect::<Result<_, _>>()?;
    let rate_hz = demo.metadata.sample_rate_hz;
    let every = rate_hz * dt_s;
    if !(every.is_finite() && every >= 1.0 && (every - every.round()).abs() < 1e-9 * every) {
        return Err(EpisodeError::Settings {
            field: "control_hz",
            reason: format!(
                "{}: the demonstration's {rate_hz} Hz samples are not a whole number to a step",
                settings.control_hz
            ),
        });
    }
    let every = every.round() as usize;
    let len = samples.iter().map(|s| s.len()).min().unwrap_or(0);
    let command = |arm: ArmName, a: &Sample, b: &Sample| -> Result<TipCommand, EpisodeError> {
        if !(0.0..=settings.max_jaw_rad).contains(&b.jaw_rad) {
            return Err(EpisodeError::Command {
                arm,
                field: "jaw_rad",
                value: format!("{} (the sample at {} s)", b.jaw_rad, b.time_s),
                reason: format!("0 to {} rad", settings.max_jaw_rad),
            });
        }
        let turn = b.world_from_tip() * a.world_from_tip().inverse();
        Ok(TipCommand {
            world_velocity_mps: (b.position_m - a.position_m) / dt_s,
            world_turn_rad_s: turn.scaled_axis() / dt_s,
            jaw_rad: b.jaw_rad,
        })
    };
    let mut out = Vec::new();
    let mut k = 0;
    while k + every < len {
        let [l, r, a] = [0, 1, 2].map(|i| command(ARMS[i], &samples[i][k], &samples[i][k + every]));
        out.push([l?, r?, a?]);
        k += every;
    }
    Ok(out)
}

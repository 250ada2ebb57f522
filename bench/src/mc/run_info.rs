//! `run.json`: what a Monte Carlo directory holds (scene, preset, seed, trials, methods, shard), written
//! when a run starts. A rerun into the same directory must ask for the same run (it resumes it); shards
//! of one run differ only in their shard, which is what `knotlab mc merge` checks.

use std::path::Path;
use std::str::FromStr;

use knotlab_sim::scene::{Randomization, SceneConfig};
use serde::{Deserialize, Serialize};

use super::McError;

/// The format line of `run.json`.
pub const RUN_FORMAT: &str = "knotlab-mc-run 2";

/// Which trials a run does: trial `t` when `t % count == index` (`--shard index/count`, index from 0).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Shard {
    /// This shard, 0 to `count - 1`.
    pub index: u64,
    /// How many shards the run is cut into.
    pub count: u64,
}

impl Shard {
    /// Whether the shard does trial `trial`.
    pub fn holds(&self, trial: u64) -> bool {
        trial % self.count == self.index
    }
}

impl std::fmt::Display for Shard {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

impl FromStr for Shard {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let bad = || format!("{s:?}: a shard is I/N with 0 <= I < N, e.g. 0/4");
        let (i, n) = s.split_once('/').ok_or_else(bad)?;
        let (index, count): (u64, u64) =
            (i.trim().parse().map_err(|_| bad())?, n.trim().parse().map_err(|_| bad())?);
        if count == 0 || index >= count {
            return Err(bad());
        }
        Ok(Self { index, count })
    }
}

/// The contents of `run.json`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RunInfo {
    /// [`RUN_FORMAT`].
    pub format: String,
    /// The scene file.
    pub scene: String,
    /// The preset applied to its randomization, if any.
    pub preset: Option<String>,
    /// FNV-1a (64 bit, hex) of the scene as drawn from (preset applied), serialized as JSON: two runs
    /// from different scene contents under the same file name are told apart.
    pub scene_fingerprint: String,
    /// FNV-1a (64 bit, hex) of the learned skill and the demonstration it came from
    /// ([`skill_fingerprint`]): two runs of different skills are told apart.
    pub skill_fingerprint: String,
    /// What each trial draws from (for the reader).
    pub randomization: Randomization,
    /// The run's seed.
    pub seed: u64,
    /// Trials 0 to N-1 (of the whole run, not of the shard).
    pub trials: u64,
    /// The methods, each run on every trial.
    pub methods: Vec<String>,
    /// Each trial's skill stopped at this time, s.
    pub until_s: Option<f64>,
    /// The shard, if the run is cut into shards.
    pub shard: Option<Shard>,
}

/// FNV-1a, 64 bit, of some bytes, as 16 hex digits.
fn fnv1a(bytes: impl IntoIterator<Item = u8>) -> String {
    let hash = bytes
        .into_iter()
        .fold(0xcbf2_9ce4_8422_2325_u64, |h, b| (h ^ u64::from(b)).wrapping_mul(0x100_0000_01b3));
    format!("{hash:016x}")
}

/// FNV-1a, 64 bit, of the scene's JSON.
pub fn scene_fingerprint(scene: &SceneConfig) -> String {
    fnv1a(serde_json::to_string(scene).unwrap_or_default().into_bytes())
}

/// FNV-1a, 64 bit, of what a run's trials play: the knowledge base's JSON and the demonstration's
/// samples as its CSV files hold them (the replay method plays the demonstration itself).
pub fn skill_fingerprint(learned: &knotlab_scenarios::trial::Learned) -> String {
    let mut bytes = serde_json::to_string(&learned.knowledge).unwrap_or_default().into_bytes();
    for instrument in &learned.demonstration.instruments {
        // Writing into memory does not fail.
        knotlab_learner::demonstration::csv::write_samples(&mut bytes, &instrument.samples).ok();
    }
    fnv1a(bytes)
}

impl RunInfo {
    /// Where it is kept in a run directory.
    pub fn path(dir: &Path) -> std::path::PathBuf {
        dir.join("run.json")
    }

    /// The directory's `run.json`, `None` if there is none.
    pub fn read(dir: &Path) -> Result<Option<RunInfo>, McError> {
        let path = Self::path(dir);
        let file = path.display().to_string();
        let text = match std::fs::read_to_string(&path) {
            Ok(t) => t,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
            Err(e) => return Err(McError::Results { file, reason: e.to_string() }),
        };
        let info: RunInfo = serde_json::from_str(&text)
            .map_err(|e| McError::Results { file: file.clone(), reason: e.to_string() })?;
        if info.format != RUN_FORMAT {
            return Err(McError::Results {
                file,
                reason: format!("format \"{}\": this knotlab reads \"{RUN_FORMAT}\"", info.format),
            });
        }
        Ok(Some(info))
    }

    /// Writes it to the directory.
    pub fn write(&self, dir: &Path) -> Result<(), McError> {
        let path = Self::path(dir);
        let text = serde_json::to_string_pretty(self)
            .map_err(|e| McError::Results { file: path.display().to_string(), reason: e.to_string() })?;
        std::fs::write(&path, text + "\n")
            .map_err(|e| McError::Results { file: path.display().to_string(), reason: e.to_string() })
    }

    /// The first field in which `other` asks for a different run, as `field: this vs that`; `None`
    /// when they are the same run. The number of trials counts only with `with_trials`: a trial is the
    /// same whatever the number of trials, so a resumed run may ask for more (or fewer).
    pub fn difference(&self, other: &RunInfo, with_trials: bool) -> Option<String> {
        let pairs = [
            ("scene", self.scene.clone(), other.scene.clone()),
            ("preset", shown(&self.preset), shown(&other.preset)),
            ("scene_fingerprint", self.scene_fingerprint.clone(), other.scene_fingerprint.clone()),
            ("skill_fingerprint", self.skill_fingerprint.clone(), other.skill_fingerprint.clone()),
            ("seed", self.seed.to_string(), other.seed.to_string()),
            ("trials", self.trials.to_string(), other.trials.to_string()),
            ("methods", self.methods.join(","), other.methods.join(",")),
            ("until_s", shown(&self.until_s), shown(&other.until_s)),
            (
                "shard",
                self.shard.map_or("none".to_owned(), |s| s.to_string()),
                other.shard.map_or("none".to_owned(), |s| s.to_string()),
            ),
        ];
        pairs
            .into_iter()
            .filter(|(field, _, _)| with_trials || *field != "trials")
            .find(|(_, a, b)| a != b)
            .map(|(field, a, b)| format!("{field}: {a} here, {b} asked"))
    }
}

/// A value, or `none`, as a person reads it.
fn shown<T: std::fmt::Display>(value: &Option<T>) -> String {
    value.as_ref().map_or("none".to_owned(), ToString::to_string)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A shard such as `1/3` parses and holds every third trial, malformed shards are refused, and every
    /// trial falls in exactly one shard of a run.
    #[test]
    fn shards_parse_and_split_the_trials() {
        let s: Shard = "1/3".parse().expect("shard");
        assert_eq!(s, Shard { index: 1, count: 3 });
        assert_eq!((0..9).filter(|t| s.holds(*t)).collect::<Vec<_>>(), vec![1, 4, 7]);
        for bad in ["3/3", "1", "a/2", "0/0", "-1/2"] {
            assert!(bad.parse::<Shard>().is_err(), "{bad}");
        }
        // Every trial in exactly one shard.
        let shards: Vec<Shard> = (0..4).map(|i| Shard { index: i, count: 4 }).collect();
        assert!((0..100).all(|t| shards.iter().filter(|s| s.holds(t)).count() == 1));
    }
}

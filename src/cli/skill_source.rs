//! Where a command's skill comes from: a knowledge base file, or the demonstration learned from here and
//! now with a task pattern (shared by `run`, `mc` and `session`).

use std::path::PathBuf;

use anyhow::Context;
use clap::Args;

use knotlab_learner::demonstration::load_demonstration;
use knotlab_learner::pattern::load_pattern;
use knotlab_learner::primitive::{learn, load_knowledge_base};
use knotlab_scenarios::trial::Learned;

#[derive(Debug, Args)]
pub struct SkillSource {
    /// The knowledge base (`knotlab learn --out FILE`); without it the demonstration is learned from
    /// here and now with `--pattern`.
    #[arg(long)]
    pub skill: Option<PathBuf>,
    /// The demonstration (learned from without `--skill`; played back by `--method replay`).
    #[arg(long, default_value = "scenarios/demos/instrument-tie")]
    pub demo: PathBuf,
    /// The task pattern (used without `--skill`).
    #[arg(long, default_value = "scenarios/patterns/knot_tying.toml")]
    pub pattern: PathBuf,
}

impl SkillSource {
    /// The knowledge base and the demonstration.
    pub fn learned(&self) -> anyhow::Result<Learned> {
        let demonstration = load_demonstration(&self.demo)?;
        let knowledge = match &self.skill {
            Some(path) => load_knowledge_base(path)?,
            None => {
                let pattern = load_pattern(&self.pattern)?;
                learn(&demonstration, &pattern).with_context(|| {
                    format!("learning from {} with {}", self.demo.display(), self.pattern.display())
                })?
            }
        };
        Ok(Learned { knowledge, demonstration })
    }
}

//! Where a command's skill comes from: a knowledge base file, or the demonstration learned from here and
//! now with a task pattern (shared by `run`, `mc` and `session`).

use std::path::PathBuf;

use anyhow::Context;
use clap::Args;

use knotlab_learner::primitive::{learn, load_knowledge_base};
use knotlab_scenarios::trial::Learned;

use knotlab_scenarios::shipped;

#[derive(Debug, Args)]
pub struct SkillSource {
    /// The knowledge base (`knotlab learn --out FILE`); without it the demonstration is learned from
    /// here and now with `--pattern`.
    #[arg(long)]
    pub skill: Option<PathBuf>,
    /// The demonstration (learned from without `--skill`; played back by `--method replay`)
    /// [default: the shipped scenarios/demos/instrument-tie, built in].
    #[arg(long)]
    pub demo: Option<PathBuf>,
    /// The task pattern (used without `--skill`) [default: the shipped
    /// scenarios/patterns/knot_tying.toml, built in].
    #[arg(long)]
    pub pattern: Option<PathBuf>,
}

impl SkillSource {
    /// The knowledge base and the demonstration.
    pub fn learned(&self) -> anyhow::Result<Learned> {
        let demonstration = shipped::demonstration(self.demo.as_deref())?;
        let knowledge = match &self.skill {
            Some(path) => load_knowledge_base(path)?,
            None => {
                let pattern = shipped::pattern(self.pattern.as_deref())?;
                learn(&demonstration, &pattern).with_context(|| {
                    format!(
                        "learning from {} with {}",
                        shipped::demo_name(self.demo.as_deref()),
                        shipped::name(self.pattern.as_deref(), &shipped::PATTERN)
                    )
                })?
            }
        };
        Ok(Learned { knowledge, demonstration })
    }
}

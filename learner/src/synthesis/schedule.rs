//! The synthesized skill's clock. Each primitive keeps the pause the demonstration made before it:
//! after its instrument's previous primitive, and after every primitive of another instrument it waits
//! for (the knowledge base's dependencies, from the pattern's `after`); it starts when the last of these
//! allows. A synchronized primitive runs when its reference does. Jaw movements between primitives keep
//! their distance to the primitive that follows (the grasp before a pull), or to the one before if none
//! follows.

use std::collections::HashMap;

use knotlab_hw::rig::ArmName;

use super::SynthesisError;
use crate::primitive::{KnowledgeBase, Primitive};

/// One primitive on the demonstration's clock and on the new one.
#[derive(Clone, Debug, PartialEq)]
pub struct Slot {
    /// The primitive.
    pub name: String,
    /// Its instrument.
    pub instrument: ArmName,
    /// Start and end in the demonstration, s.
    pub demo_s: (f64, f64),
    /// Start and end in the skill, s.
    pub new_s: (f64, f64),
}

/// Every primitive's slot.
#[derive(Clone, Debug, PartialEq)]
pub struct Schedule {
    /// In the demonstration's start order.
    pub slots: Vec<Slot>,
}

fn instrument_of(name: &str, field: &str) -> Result<ArmName, SynthesisError> {
    name.parse().map_err(|e| SynthesisError::Invalid { field: field.to_owned(), reason: format!("{e}") })
}

impl Schedule {
    /// Plans the clock; `duration_s` gives each primitive's new duration (synchronized ones are not asked).
    pub fn plan(kb: &KnowledgeBase, duration_s: impl Fn(&Primitive) -> f64) -> Result<Self, SynthesisError> {
        let mut items: Vec<(ArmName, &Primitive)> = Vec::new();
        for (i, ip) in kb.instruments.iter().enumerate() {
            let arm = instrument_of(&ip.instrument, &format!("instruments[{i}].instrument"))?;
            items.extend(ip.primitives.iter().map(|p| (arm, p)));
        }
        // Demonstration start order; a synchronized primitive after its reference.
        items.sort_by(|a, b| {
            let sync = |p: &Primitive| matches!(p, Primitive::Synchronized(_));
            a.1.span_s().0.total_cmp(&b.1.span_s().0).then(sync(a.1).cmp(&sync(b.1)))
        });
        let mut done: HashMap<String, Slot> = HashMap::new();
        let mut last_of: HashMap<ArmName, String> = HashMap::new();
        let mut slots = Vec::new();
        for (arm, p) in items {
            let (start, end) = p.span_s();
            let new_s = if let Primitive::Synchronized(s) = p {
                let reference = done.get(&s.reference).ok_or_else(|| SynthesisError::Invalid {
                    field: format!("{}.reference", s.name),
                    reason: format!("'{}' is no 2D primitive before it", s.reference),
                })?;
                reference.new_s
            } else {
                let mut t = start;
                let mut bounded = false;
                if let Some(prev) = last_of.get(&arm).and_then(|n| done.get(n)) {
                    t = prev.new_s.1 + (start - prev.demo_s.1);
                    bounded = true;
                }
                for dep in kb.dependencies.iter().filter(|d| d.primitive == p.name()) {
                    let q = done.get(&dep.after).ok_or_else(|| SynthesisError::Invalid {
                        field: "dependencies".to_owned(),
                        reason: format!(
                            "{} waits for '{}', which does not come before it",
                            dep.primitive, dep.after
                        ),
                    })?;
                    let allowed = q.new_s.1 + dep.pause_s;
                    t = if bounded { t.max(allowed) } else { allowed };
                    bounded = true;
                }
                let d = duration_s(p);
                if !(d.is_finite() && d > 0.0) {
                    return Err(SynthesisError::Invalid {
                        field: format!("{}.duration", p.name()),
                        reason: format!("{d} s is no duration"),
                    });
                }
                (t.max(0.0), t.max(0.0) + d)
            };
            let slot = Slot { name: p.name().to_owned(), instrument: arm, demo_s: (start, end), new_s };
            if !matches!(p, Primitive::Synchronized(_)) {
                last_of.insert(arm, slot.name.clone());
            }
            done.insert(slot.name.clone(), slot.clone());
            slots.push(slot);
        }
        Ok(Self { slots })
    }

    /// A primitive's slot.
    pub fn slot(&self, name: &str) -> Option<&Slot> {
        self.slots.iter().find(|s| s.name == name)
    }

    /// Where a moment of the demonstration (of `instrument`, outside its primitives or inside one) falls
    /// on the new clock.
    pub fn map_time(&self, instrument: ArmName, t_s: f64) -> f64 {
        let own: Vec<&Slot> = self.slots.iter().filter(|s| s.instrument == instrument).collect();
        if let Some(s) = own.iter().find(|s| s.demo_s.0 <= t_s && t_s <= s.demo_s.1) {
            let (d, n) = (s.demo_s.1 - s.demo_s.0, s.new_s.1 - s.new_s.0);
            let f = if d > 0.0 { (t_s - s.demo_s.0) / d } else { 0.0 };
            return s.new_s.0 + f * n;
        }
        if let Some(next) =
            own.iter().filter(|s| s.demo_s.0 > t_s).min_by(|a, b| a.demo_s.0.total_cmp(&b.demo_s.0))
        {
            return next.new_s.0 - (next.demo_s.0 - t_s);
        }
        match own.iter().max_by(|a, b| a.demo_s.1.total_cmp(&b.demo_s.1)) {
            Some(last) => last.new_s.1 + (t_s - last.demo_s.1),
            None => t_s,
        }
    }
}

//! Watches the thread for passing through itself during a run. A knot is made of strands that block
//! each other; a strand that tunnels through another (a solver failure under load) can tie or untie a
//! knot that real thread could not. Each step, the pairs of non-neighbouring segments that Rapier's
//! broad phase found close are judged by a [`TunnellingMonitor`].

use std::collections::HashMap;

use rapier3d::prelude::*;

use crate::physics::Physics;
use crate::thread::Thread;
use crate::tunnelling::TunnellingMonitor;

/// One strand passing through another.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SelfCrossing {
    /// When, s of simulated time.
    pub time_s: f64,
    /// The two segments, needle end counting from 0.
    pub segments: (usize, usize),
}

/// The thread's self-crossings so far. Moving the thread by hand between steps (`Thread::lay_straight`,
/// `lay_along`) looks like passes: experiments that do so should not read the count.
#[derive(Clone, Debug)]
pub struct ThreadWatch {
    monitor: TunnellingMonitor,
    segment_of: HashMap<ColliderHandle, usize>,
    /// Every crossing seen, in order.
    pub crossings: Vec<SelfCrossing>,
}

impl ThreadWatch {
    /// Watches `thread`'s segments in `physics`; pairs closer than `watch_m` beyond touching are judged.
    pub fn new(physics: &Physics, thread: &Thread, watch_m: f64) -> Self {
        let segment_of = thread
            .segments
            .iter()
            .enumerate()
            .flat_map(|(i, h)| physics.bodies[*h].colliders().iter().map(move |c| (*c, i)))
            .collect();
        Self { monitor: TunnellingMonitor::new(watch_m), segment_of, crossings: Vec::new() }
    }

    /// Judges the pairs after a step at `time_s`; returns how many crossed.
    pub fn update(&mut self, physics: &Physics, thread: &Thread, radius_m: f64, time_s: f64) -> usize {
        let mut pairs: Vec<(usize, usize)> = physics
            .narrow_phase
            .contact_pairs()
            .filter_map(|p| Some((*self.segment_of.get(&p.collider1)?, *self.segment_of.get(&p.collider2)?)))
            .map(|(i, j)| (i.min(j), i.max(j)))
            .filter(|(i, j)| j - i >= 2)
            .collect();
        // The broad phase's order follows its internal storage: sorted, the watch does not depend on it.
        pairs.sort_unstable();
        let capsules = thread.capsules(physics, radius_m);
        let new = self.monitor.update(&capsules, pairs.into_iter());
        self.crossings.extend(self.monitor.flipped.iter().map(|&segments| SelfCrossing { time_s, segments }));
        new
    }
}

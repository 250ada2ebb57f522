//! Watches the thread for passing through itself during a run. A knot is made of strands that block
//! each other; a strand that tunnels through another (a solver failure under load) can tie or untie a
//! knot that real thread could not. Both suture models are judged by one test, the swept one of
//! [`crate::crossing`]: the capsule chain's centreline (through its joints) after each step, here;
//! the rope's particles after each of its substeps, by the rope itself, its passes recorded here
//! ([`ThreadWatch::record`]), so both models' crossings are read in one place.

use crate::crossing::CrossingWatch;
use crate::physics::Physics;
use crate::thread::Thread;

/// One strand passing through another.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SelfCrossing {
    /// When, s of simulated time.
    pub time_s: f64,
    /// The two segments, needle end counting from 0.
    pub segments: (usize, usize),
}

/// A stretch beyond which the suture's stretch is counted apart ([`Stretch::over_5_percent_s`]), a
/// fraction of a segment's rest length: at 5 % a 0.2 m suture would be a centimetre longer, a knot's
/// loop several of its diameters wider.
pub const STRETCH_NOTED: f64 = 0.05;

/// The suture at its most stretched: how far its most stretched segment (the chain: its widest
/// joint gap) reached beyond its rest length, as a fraction of it, and when; and how long it was
/// stretched beyond [`STRETCH_NOTED`] in all.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Stretch {
    /// The stretch, a fraction of the segment's rest length.
    pub ratio: f64,
    /// When, s of simulated time.
    pub time_s: f64,
    /// The simulated time over which the suture was stretched beyond [`STRETCH_NOTED`], s (the
    /// steps after which it was, each counted for its length).
    pub over_5_percent_s: f64,
}

/// The thread's self-crossings and its largest stretch so far. Moving the thread by hand between steps (`Thread::lay_straight`,
/// `lay_along`) looks like passes: experiments that do so should not read the count.
#[derive(Clone, Debug, Default)]
pub struct ThreadWatch {
    /// The chain's watch.
    swept: CrossingWatch,
    /// The chain's segments as pairs of points of its centreline.
    segments: Vec<[usize; 2]>,
    /// Every pair of the chain's segments that are not neighbours.
    pairs: Vec<(usize, usize)>,
    /// Every crossing seen, in order.
    pub crossings: Vec<SelfCrossing>,
    /// The largest stretch seen after a step.
    most_stretched: Option<Stretch>,
    /// When the last step the stretch was noted after ended, s.
    stretch_noted_s: f64,
}

impl ThreadWatch {
    /// Watches the chain `thread`'s segments. (The rope finds its own passes: its watch starts
    /// empty, [`Default`], and they are [`Self::record`]ed.)
    pub fn new(thread: &Thread) -> Self {
        let n = thread.segments.len();
        let segments = (0..n).map(|k| [k, k + 1]).collect();
        let pairs = (0..n).flat_map(|i| (i + 2..n).map(move |j| (i, j))).collect();
        Self { swept: CrossingWatch::default(), segments, pairs, crossings: Vec::new(), ..Self::default() }
    }

    /// Notes the suture's stretch after the step that ended at `time_s`.
    pub fn note_stretch(&mut self, time_s: f64, ratio: f64) {
        let step_s = time_s - self.stretch_noted_s;
        self.stretch_noted_s = time_s;
        let over_s = if ratio > STRETCH_NOTED { step_s } else { 0.0 };
        self.most_stretched = Some(match self.most_stretched {
            None => Stretch { ratio, time_s, over_5_percent_s: over_s },
            Some(s) if ratio > s.ratio => {
                Stretch { ratio, time_s, over_5_percent_s: s.over_5_percent_s + over_s }
            }
            Some(s) => Stretch { over_5_percent_s: s.over_5_percent_s + over_s, ..s },
        });
    }

    /// The largest stretch seen after a step (none before the first step).
    pub fn most_stretched(&self) -> Option<Stretch> {
        self.most_stretched
    }

    /// Records passes another watch found at `time_s` (the rope's, by segment pairs).
    pub fn record(&mut self, time_s: f64, passes: &[(usize, usize)]) {
        self.crossings.extend(passes.iter().map(|&segments| SelfCrossing { time_s, segments }));
    }

    /// Judges the chain's move over the step that ended at `time_s`; returns how many passes it
    /// made.
    pub fn update(&mut self, physics: &Physics, thread: &Thread, radius_m: f64, time_s: f64) -> usize {
        if self.segments.len() != thread.segments.len() || self.segments.is_empty() {
            return 0;
        }
        // The centreline through the joints: each joint midway between the ends of the capsules
        // it joins.
        let capsules = thread.capsules(physics, radius_m);
        let mut x = Vec::with_capacity(capsules.len() + 1);
        x.push(capsules[0].a_m);
        x.extend(capsules.windows(2).map(|c| 0.5 * (c[0].b_m + c[1].a_m)));
        x.push(capsules[capsules.len() - 1].b_m);
        self.swept.start_step(&x);
        self.swept.look(&x, &self.segments, &self.pairs, radius_m);
        let passes = self.swept.crossed().to_vec();
        self.record(time_s, &passes);
        passes.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The stretch noted keeps the largest reading and when it came, and adds up the steps after
    /// which the suture was stretched beyond 5 %, each for its length.
    #[test]
    fn the_stretch_keeps_the_largest_and_adds_up_the_time_beyond_five_percent() {
        let mut watch = ThreadWatch::default();
        assert_eq!(watch.most_stretched(), None);
        for (time_s, ratio) in [(0.001, 0.08), (0.002, 0.01), (0.004, 0.3), (0.005, 0.06), (0.006, 0.02)] {
            watch.note_stretch(time_s, ratio);
        }
        let s = watch.most_stretched().expect("noted");
        assert_eq!((s.ratio, s.time_s), (0.3, 0.004));
        // 1 ms at 8 %, 2 ms at 30 % (the step from 2 to 4 ms), 1 ms at 6 %.
        assert!((s.over_5_percent_s - 0.004).abs() < 1e-12, "{s:?}");
    }
}

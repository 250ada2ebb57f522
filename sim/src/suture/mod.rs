//! The suture: one interface over its two models, peers behind it. The XPBD rope ([`crate::rope`],
//! the nominal suture: knots hold in it) and Rapier's capsule chain ([`crate::thread`]) each step,
//! give their centreline and where they pass the stitch, are held and let go by the jaws
//! ([`Hold`]), slip, push the instruments and the flaps, and are watched for passing through
//! themselves. The world holds one [`Suture`]; nothing outside this module asks which model it is.
//!
//! - `chain`: the capsule chain, its stitch joints and its contact filter.
//! - `rope`: the rope as the jaws see it (what they let through, its grip).
//! - `hold`: what a pair of jaws holds.
//! - [`layout`]: where the thread lies at the start of the task (each model laid its own way).

mod chain;
mod hold;
pub mod layout;
mod rope;

use std::ops::RangeInclusive;

use nalgebra::{IsometryMatrix3, Vector3};
use rapier3d::prelude::*;

pub use chain::{ChainSuture, HELD_CLEARANCE_M};
pub use hold::Hold;
pub use rope::{JAW_CLEAR_M, SLIP_OUT_FACTOR};

use crate::convert::to_rapier;
use crate::grasp::{Grasp, JAW_CENTRE_OFFSET_M, JawFaces};
use crate::hooks::ContactFilter;
use crate::needle::Needle;
use crate::physics::Physics;
use crate::rope::suture::SceneRope;
use crate::scene::SceneConfig;
use crate::stitch::StitchEvent;
use crate::thread::ThreadModel;
use crate::thread_watch::{SelfCrossing, Stretch, ThreadWatch};
use crate::tissue::{Flap, Tissue};
use crate::tunnelling::Capsule;

/// The scene's suture, with its needle and its self-crossing watch.
pub struct Suture {
    model: Model,
    needle: Needle,
    watch: ThreadWatch,
    radius_m: f64,
}

// One suture a world, held in place: the variants' sizes cost nothing.
#[allow(clippy::large_enum_variant)]
enum Model {
    Chain(ChainSuture),
    Rope(rope::RopeSuture),
}

/// What the suture needs to know of one arm's jaws this step.
pub struct JawsNow<'a> {
    /// The jaws' colliders (none for the endoscope).
    pub colliders: &'a [ColliderHandle],
    /// What they hold.
    pub hold: Option<&'a Hold>,
    /// Their tip's pose as the links stand this step.
    pub world_from_tip: IsometryMatrix3<f64>,
    /// The jaws' radius, m (`None` without jaws).
    pub radius_m: Option<f64>,
    /// Told to close, or closing now.
    pub closing: bool,
    /// Their hold slipped and they have not reopened since.
    pub slipped: bool,
    /// They closed on nothing and have not reopened since.
    pub closed_empty: bool,
    /// Open at least half way.
    pub open: bool,
}

/// How a hold fared in a step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum HoldCheck {
    /// It holds.
    Held,
    /// The thread began to slide through the jaws, which go on holding it.
    Slid {
        /// The pull, N.
        force_n: f64,
    },
    /// The pull tore it out of the jaws.
    SlippedOut {
        /// The pull, N.
        force_n: f64,
    },
}

impl Suture {
    /// Whether the suture `config` asks for makes its own contacts with the rig's moving links (the
    /// rope does, in its own solver): then Rapier has nothing to do with those links but carry
    /// the needle in jaws.
    pub fn makes_own_link_contacts(config: &SceneConfig) -> bool {
        config.thread.model == ThreadModel::Rope
    }

    /// The scene's suture laid along `layout` (world frame, needle end first), through the
    /// stitch where it passes its points, touching the instruments' colliders `instruments`, held
    /// by none of the `arms` arms' jaws.
    pub fn build(
        config: &SceneConfig,
        layout: &[Vector3<f64>],
        physics: &mut Physics,
        tissue: &mut Tissue,
        instruments: &[ColliderHandle],
        arms: usize,
    ) -> Self {
        let (model, needle, watch) = match config.thread.model {
            ThreadModel::Chain => {
                let (chain, needle) = ChainSuture::build(config, layout, physics, tissue);
                let watch = ThreadWatch::new(chain.thread());
                (Model::Chain(chain), needle, watch)
            }
            ThreadModel::Rope => {
                let (mut rope, needle) = SceneRope::build(
                    &config.thread,
                    &config.needle,
                    layout,
                    physics,
                    tissue,
                    &config.tissue,
                    instruments,
                );
                if let Some(stitch) = &mut rope.stitch {
                    stitch.slide_friction_n = config.stitch.slide_friction_n;
                }
                (Model::Rope(rope::RopeSuture::new(rope, arms)), needle, ThreadWatch::default())
            }
        };
        Self { model, needle, watch, radius_m: config.thread.radius_m }
    }

    /// The chain, if the suture is the chain (for experiments on that model).
    pub fn as_chain(&self) -> Option<&ChainSuture> {
        match &self.model {
            Model::Chain(chain) => Some(chain),
            Model::Rope(_) => None,
        }
    }

    /// The rope, if the suture is the rope (for experiments on that model).
    pub fn as_rope(&self) -> Option<&SceneRope> {
        match &self.model {
            Model::Chain(_) => None,
            Model::Rope(rope) => Some(&rope.rope),
        }
    }

    /// The needle.
    pub fn needle(&self) -> &Needle {
        &self.needle
    }

    /// The needle's arc in the world, swage first, m.
    pub fn needle_points_m(&self, physics: &Physics) -> Vec<Vector3<f64>> {
        let carrier = match &self.model {
            Model::Chain(chain) => chain.first_segment(),
            Model::Rope(_) => None,
        };
        self.needle.world_points_m(physics, carrier)
    }

    /// The distance between neighbouring points of the centreline, m: the chain's segment length or
    /// the rope's particle spacing.
    pub fn spacing_m(&self) -> f64 {
        match &self.model {
            Model::Chain(chain) => chain.thread().segment_length_m,
            Model::Rope(rope) => rope.rope.spacing_m,
        }
    }

    /// The centreline, needle end first, m: the chain's segment ends or the rope's particles.
    pub fn centreline(&self, physics: &Physics) -> Vec<Vector3<f64>> {
        match &self.model {
            Model::Chain(chain) => chain.centreline(physics),
            Model::Rope(rope) => rope.rope.centreline(),
        }
    }

    /// Where `flap`'s stitch point sits on the suture: the arc length from the needle end, m
    /// (`None` while the thread is not through it).
    pub fn arc_at_m(&self, physics: &Physics, tissue: &Tissue, flap: Flap) -> Option<f64> {
        match &self.model {
            Model::Chain(chain) => chain.arc_at_m(physics, tissue, flap),
            Model::Rope(rope) => rope.rope.arc_at_m(flap),
        }
    }

    /// The points of the centreline in the tissue, from the exit's to the entry's, with one
    /// either side for the chain.
    pub fn inside(&self) -> Option<RangeInclusive<usize>> {
        match &self.model {
            Model::Chain(chain) => chain.inside(),
            Model::Rope(rope) => rope.rope.inside(),
        }
    }

    /// Which points of the suture touch which of `links` (name, body) now: `(point from the
    /// needle end, link name)`, sorted. The chain's segments in an active contact with a link's
    /// colliders; the rope's particles within its radius of them.
    pub fn touching(&self, physics: &Physics, links: &[(String, RigidBodyHandle)]) -> Vec<(usize, String)> {
        match &self.model {
            Model::Chain(chain) => chain.touching(physics, links),
            Model::Rope(rope) => {
                let mut found: Vec<(usize, String)> = links
                    .iter()
                    .flat_map(|(name, body)| {
                        rope.rope
                            .particles_touching(physics, *body)
                            .into_iter()
                            .map(move |p| (p, name.clone()))
                    })
                    .collect();
                found.sort();
                found
            }
        }
    }

    /// The suture as capsules of `radius_m`, needle end first: the chain's segments, or the rope's
    /// centreline from particle to particle.
    pub fn capsules(&self, physics: &Physics, radius_m: f64) -> Vec<Capsule> {
        match &self.model {
            Model::Chain(chain) => chain.thread().capsules(physics, radius_m),
            Model::Rope(rope) => {
                let mut capsules = centreline_capsules(&rope.rope.centreline());
                for c in &mut capsules {
                    c.radius_m = radius_m;
                }
                capsules
            }
        }
    }

    /// How far the suture is stretched where it is stretched most, as a fraction of its length
    /// there: the widest gap in a joint of the chain over a segment's length, or the rope's most
    /// stretched segment beyond its rest length.
    pub fn max_stretch_ratio(&self, physics: &Physics) -> f64 {
        match &self.model {
            Model::Chain(chain) => chain.thread().max_stretch_ratio(physics),
            Model::Rope(rope) => rope.rope.ropes.max_stretch_ratio(),
        }
    }

    /// The suture at its most stretched so far (none before the first step).
    pub fn most_stretched(&self) -> Option<Stretch> {
        self.watch.most_stretched()
    }

    /// Every time the suture passed through itself, in order.
    pub fn self_crossings(&self) -> &[SelfCrossing] {
        &self.watch.crossings
    }

    /// The thread's ends leaving a flap, in order (the chain's stitch reports them).
    pub fn stitch_events(&self) -> &[StitchEvent] {
        match &self.model {
            Model::Chain(chain) => chain.stitch_events(),
            Model::Rope(_) => &[],
        }
    }

    /// What to call `body` in a report of an unhealthy step, if it is the suture's.
    pub fn body_name(&self, body: RigidBodyHandle) -> Option<String> {
        match &self.model {
            Model::Chain(chain) => {
                chain.segments().iter().position(|s| *s == body).map(|i| format!("thread segment {i}"))
            }
            Model::Rope(_) => None,
        }
    }

    /// Whether jaws at `world_from_tip` opened `jaw_rad`, of radius `jaw_radius_m`, squeeze the
    /// suture between them ([`Grasp::squeeze`]).
    pub fn squeezed(
        &self,
        physics: &Physics,
        world_from_tip: &IsometryMatrix3<f64>,
        jaw_rad: f64,
        jaw_radius_m: f64,
    ) -> bool {
        let capsules = match &self.model {
            Model::Chain(chain) => chain.capsules(physics),
            Model::Rope(rope) => centreline_capsules(&rope.rope.centreline()),
        };
        Grasp::squeeze(&capsules, world_from_tip, JAW_CENTRE_OFFSET_M, jaw_rad, jaw_radius_m, self.radius_m)
    }

    /// Closes jaws on `clevis` at `world_from_tip` (radius `jaw_radius_m`) on what lies between
    /// them: the needle or a segment of the chain on a fixed joint, or else a run of the rope in
    /// their grip of `grip_force_n`.
    pub fn try_grasp(
        &mut self,
        physics: &mut Physics,
        clevis: RigidBodyHandle,
        world_from_tip: &IsometryMatrix3<f64>,
        jaw_radius_m: Option<f64>,
        grip_force_n: f64,
    ) -> Option<Hold> {
        let needle = self.needle_points_m(physics);
        let (capsules, segments) = match &self.model {
            Model::Chain(chain) => (chain.capsules(physics), chain.segments()),
            Model::Rope(_) => (Vec::new(), &[][..]),
        };
        let joint = Grasp::try_close(
            physics,
            &capsules,
            segments,
            &needle,
            self.needle.body,
            clevis,
            world_from_tip,
            JAW_CENTRE_OFFSET_M,
        );
        if let Some(grasp) = joint {
            return Some(Hold::joint(grasp));
        }
        let Model::Rope(rope) = &mut self.model else { return None };
        let faces = jaw_radius_m.map(|r| JawFaces::of(world_from_tip, r, self.radius_m));
        rope.try_grip(physics, clevis, world_from_tip, faces.as_ref(), grip_force_n)
    }

    /// Lets go of what arm `a`'s jaws hold. The rope stays let through the jaws until they are
    /// clear of what they held (with `needle_out`, the swaged end of a needle they held too).
    pub fn release(&mut self, a: usize, hold: Hold, physics: &mut Physics, needle_out: bool) {
        match &mut self.model {
            Model::Chain(_) => {
                if let Some(grasp) = hold.joint_grasp() {
                    grasp.release(physics);
                }
            }
            Model::Rope(rope) => {
                if let Some(grasp) = rope.release(a, hold, needle_out) {
                    grasp.release(physics);
                }
            }
        }
    }

    /// Checks a grip the thread can slide through (the rope's; `None` for a hold on a joint):
    /// whether it slid or was torn out over the last step of `dt_s`.
    pub fn check_grip(
        &mut self,
        hold: &mut Hold,
        physics: &Physics,
        dt_s: f64,
        grip_force_n: f64,
    ) -> Option<HoldCheck> {
        match &mut self.model {
            Model::Chain(_) => None,
            Model::Rope(rope) => rope.check_grip(hold, physics, dt_s, grip_force_n),
        }
    }

    /// Checks a hold on a joint (`None` for a grip): pulled harder than `grip_force_n` (the
    /// needle: `needle_grip_force_n`), it slips out.
    pub fn check_joint(
        hold: &Hold,
        physics: &Physics,
        grip_force_n: f64,
        needle_grip_force_n: f64,
    ) -> Option<HoldCheck> {
        let grasp = hold.joint_grasp()?;
        let force_n = grasp.force_n(physics);
        let grip = if grasp.on_needle { needle_grip_force_n } else { grip_force_n };
        Some(if force_n > grip { HoldCheck::SlippedOut { force_n } } else { HoldCheck::Held })
    }

    /// Gives the rope's needle to the jaws (`held`), or to the rope when none hold it.
    pub fn hand_over_needle(&mut self, physics: &mut Physics, held: bool) {
        if let Model::Rope(rope) = &mut self.model {
            rope.rope.set_needle_held(physics, held);
        }
    }

    /// Before Rapier's step of `dt_s`, the jaws as `jaws` says (by arm): the chain's contact
    /// filter for the step; the rope lets the jaws pass what they hold and steps among the bodies.
    pub fn before_step(
        &mut self,
        physics: &mut Physics,
        tissue: &Tissue,
        jaws: &[JawsNow],
        dt_s: f64,
    ) -> ContactFilter {
        match &mut self.model {
            Model::Chain(chain) => chain.contact_filter(physics, tissue, jaws),
            Model::Rope(rope) => {
                rope.clear_jaws(physics, jaws, self.radius_m);
                rope.rope.step(physics, dt_s);
                ContactFilter::default()
            }
        }
    }

    /// After Rapier's step that ended at `time_s`: the watch judges the step and notes the
    /// stretch, the chain's stitch follows the thread.
    pub fn after_step(&mut self, physics: &mut Physics, tissue: &Tissue, time_s: f64) {
        match &mut self.model {
            Model::Chain(chain) => chain.after_step(physics, tissue, &mut self.watch, time_s),
            Model::Rope(rope) => self.watch.record(time_s, rope.rope.ropes.crossed_last_step()),
        }
        let ratio = self.max_stretch_ratio(physics);
        self.watch.note_stretch(time_s, ratio);
    }

    /// Adds the suture's pull on an instrument (its `bodies`, its jaws' `hold`) over the last step
    /// of `dt_s` to `total_n`: through a joint hold, and the rope's contacts and grip.
    pub fn add_pull(
        &self,
        total_n: &mut Vector3<f64>,
        hold: Option<&Hold>,
        bodies: &[RigidBodyHandle],
        physics: &Physics,
        dt_s: f64,
    ) {
        if let Some(grasp) = hold.and_then(Hold::joint_grasp) {
            *total_n += grasp.force_vector_n(physics);
        }
        if let Model::Rope(rope) = &self.model {
            rope.add_pull(total_n, hold, bodies, dt_s);
        }
    }

    /// Pulls each flap away from the wound with `outward_n` more (negative: less), N: a load on
    /// the rope's slides while it runs through them, else a force on the flaps' bodies.
    pub fn pull_flaps_open(&mut self, physics: &mut Physics, tissue: &Tissue, outward_n: f64) {
        if let Model::Rope(rope) = &mut self.model
            && let Some(stitch) = rope.rope.stitch.as_mut()
        {
            for load in &mut stitch.load_n {
                *load += outward_n;
            }
            return;
        }
        for flap in Flap::ALONG_THREAD {
            let outward = tissue.world_from_tissue.rotation * Vector3::new(0.0, flap.side(), 0.0);
            let f = outward * outward_n;
            let body = &mut physics.bodies[tissue.flaps[flap.index()]];
            body.add_force(to_rapier(&f), true);
        }
    }

    /// Takes the thread out of the tissue.
    pub fn unstitch(&mut self, physics: &mut Physics) {
        match &mut self.model {
            Model::Chain(chain) => chain.unstitch(physics),
            Model::Rope(rope) => rope.rope.unstitch(physics),
        }
    }
}

/// The centreline's segments as capsules of no radius.
fn centreline_capsules(points: &[Vector3<f64>]) -> Vec<Capsule> {
    points.windows(2).map(|w| Capsule { a_m: w[0], b_m: w[1], radius_m: 0.0 }).collect()
}

//! A suture as an XPBD rope (position-based dynamics in small steps): particles joined by
//! inextensible segments (solved directly along each strand), a suture's bending stiffness, and
//! capsule contacts between all non-neighbouring segments with Coulomb friction solved on
//! positions (below the static bound a contact's slip is undone entirely, so a wrap holds without
//! creeping). The alternative to Rapier's capsule chain ([`crate::thread`]), chosen in the scene
//! file (`thread.model = "rope"`, [`suture`]): the chain lets every laid knot slip, the more so the
//! better its solver converges (`docs/notebook/knot-tying-notes.md`); this rope holds a square
//! knot, and a surgeon's knot over the wound within 0.2 mm where a rope without bending stiffness
//! lets it open 2-7 mm (`cargo bench -p knotlab-lab --bench rope_knot`). [`rigid`]
//! couples it to Rapier's bodies, [`grasp`] to jaws; `stretch` and `bend` solve a strand's lengths
//! and its bending joints at once; its knot trials are in the lab crate (`knotlab_lab::trials`).

mod bend;
mod broad_phase;
mod contact;
pub mod grasp;
pub mod rigid;
pub mod slides;
mod stretch;
pub mod suture;

use std::ops::Range;

use nalgebra::Vector3;
use rapier3d::math::Pose;
use rapier3d::prelude::RigidBodyHandle;

/// What the rope lies in: before the rope's own constraints in each substep it puts the particles it
/// holds where it holds them; after them and the rope's contacts with itself, it resolves the rope
/// against its bodies (contacts, reactions) and steps itself; where that pushed the rope, the
/// rope's contacts with itself are solved once more.
pub trait Surroundings {
    /// Before the rope's constraints in a substep of `h_s` seconds: puts each particle a body holds where the body
    /// holds it at the substep's end, and marks it in `held` (as `ropes.x`). The rope's lengths,
    /// joints and contacts then leave the held particles there and move the others, and what
    /// they would have moved a held particle by is the pull on its body
    /// ([`Ropes::unheld_m`]). None by default.
    fn hold(&mut self, _ropes: &mut Ropes, _held: &mut [bool], _h_s: f64) {}

    /// After the rope's lengths and joints were solved with the held particles pinned: unmarks in
    /// `held` the particles of any hold that the pull on them ([`Ropes::unheld_m`]) would make
    /// slip, and says whether it did (the solve is then done again with them free). None by
    /// default.
    fn slipping(&mut self, _ropes: &Ropes, _held: &mut [bool], _h_s: f64) -> bool {
        false
    }

    /// When [`Self::slipping`] let holds go, before the rope's lengths and joints are solved again
    /// with their particles free: puts those particles where the rope's own motion carries them,
    /// moved by the hold's friction over the substep (so that the solve answers the friction, as
    /// it does a force). None by default: they start where they were held.
    fn start_slipping(&mut self, _ropes: &mut Ropes, _h_s: f64) {}

    /// Whether the last [`Self::after`] pushed particles of the rope (out of a body, say): the
    /// rope's contacts with itself are then solved once more, so that a push leaving two strands
    /// overlapping does not carry one through the other in the next substep. No by default.
    fn pushed_the_rope(&self) -> bool {
        false
    }

    /// The pose now of `body`, if these surroundings move it within the step (the flaps on their
    /// slides): the rope's contacts with its colliders are then solved where it is, and what they
    /// push it with comes back through [`Self::pushed`]. None by default.
    fn pose_of(&self, _body: RigidBodyHandle) -> Option<Pose> {
        None
    }

    /// The inverse mass, 1/kg, with which `body` answers a push along `direction` (a unit vector), if
    /// these surroundings move it ([`Self::pose_of`]): a contact then moves the particle and the
    /// body by their masses. 0 by default: the body goes where it goes, whatever the rope does.
    fn inverse_mass_along(&self, _body: RigidBodyHandle, _direction: &Vector3<f64>) -> f64 {
        0.0
    }

    /// The rope gave `body` this impulse, N s (world frame), in the current substep of `h_s`
    /// seconds: a body these surroundings move takes it at once. Nothing by default.
    fn pushed(&mut self, _body: RigidBodyHandle, _impulse_n_s: Vector3<f64>, _h_s: f64) {}

    /// After the rope's constraints in a substep of `h_s` seconds that started from `x_prev`.
    fn after(&mut self, ropes: &mut Ropes, x_prev: &[Vector3<f64>], h_s: f64);
}

/// Empty space.
impl Surroundings for () {
    fn after(&mut self, _: &mut Ropes, _: &[Vector3<f64>], _: f64) {}
}

/// Surroundings that may be gone (a stitch the thread was taken out of).
impl<S: Surroundings> Surroundings for Option<S> {
    fn hold(&mut self, ropes: &mut Ropes, held: &mut [bool], h_s: f64) {
        if let Some(s) = self {
            s.hold(ropes, held, h_s);
        }
    }

    fn slipping(&mut self, ropes: &Ropes, held: &mut [bool], h_s: f64) -> bool {
        self.as_mut().is_some_and(|s| s.slipping(ropes, held, h_s))
    }

    fn start_slipping(&mut self, ropes: &mut Ropes, h_s: f64) {
        if let Some(s) = self {
            s.start_slipping(ropes, h_s);
        }
    }

    fn pushed_the_rope(&self) -> bool {
        self.as_ref().is_some_and(|s| s.pushed_the_rope())
    }

    fn pose_of(&self, body: RigidBodyHandle) -> Option<Pose> {
        self.as_ref().and_then(|s| s.pose_of(body))
    }

    fn inverse_mass_along(&self, body: RigidBodyHandle, direction: &Vector3<f64>) -> f64 {
        self.as_ref().map_or(0.0, |s| s.inverse_mass_along(body, direction))
    }

    fn pushed(&mut self, body: RigidBodyHandle, impulse_n_s: Vector3<f64>, h_s: f64) {
        if let Some(s) = self {
            s.pushed(body, impulse_n_s, h_s);
        }
    }

    fn after(&mut self, ropes: &mut Ropes, x_prev: &[Vector3<f64>], h_s: f64) {
        if let Some(s) = self {
            s.after(ropes, x_prev, h_s);
        }
    }
}

/// The rope's material and how it is integrated.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RopeParams {
    /// Collision radius, m: the rope's section against itself (its knots' crossings lie two of it
    /// apart) and against the tissue, and against metal unless [`Self::metal_radius_m`] says
    /// otherwise.
    pub radius_m: f64,
    /// The radius at which metal (the instruments, the needle: the colliders of
    /// [`rigid::RigidContacts`] but its `at_collision_radius`) pushes the rope, m
    /// ([`Self::radius_at_metal_m`]); `None`: the collision radius. The rope's section does not
    /// give: drawn into a gap narrower than its diameter, it is pushed back by two bodies' overlap
    /// every substep, a pull that grows as the square of the substeps
    /// (`sim/examples/pinch_probe.rs`). The suture's own radius here lets it pass between metal
    /// parts where a real one passes (a 3-0 suture past jaws shut on a 0.6 mm needle, 0.78 mm
    /// apart) while its knots keep the coarser section the spacing resolves.
    pub metal_radius_m: Option<f64>,
    /// Mass per metre, kg/m: far heavier than suture (3-0 polypropylene is about 3e-5 kg/m), so
    /// that a 1 N pull moves a particle by a small part of its spacing in a substep; with
    /// [`Self::damping_per_s`] the rope moves quasi-statically. (At a tenth of it, 0.3 mm spacing,
    /// 40 substeps, the rope stretched 4-5 % under 1 N and a wrap held a tenth of what it holds.)
    pub mass_per_m_kg: f64,
    /// Static friction coefficient of the rope on itself.
    pub static_friction: f64,
    /// Kinetic friction coefficient of the rope on itself.
    pub kinetic_friction: f64,
    /// Substeps per step.
    pub substeps: usize,
    /// Passes over the segments' lengths in each substep: Gauss-Seidel sweeps, or with
    /// [`Self::direct_stretch`] exact projections of each strand (Newton steps).
    pub stretch_iterations: usize,
    /// Whether each strand's lengths are solved directly (`stretch::project_strand`) instead of
    /// by Gauss-Seidel.
    pub direct_stretch: bool,
    /// Whether each strand's bending joints are solved at once (`bend`: exact for the substep's
    /// implicit spring) instead of by one Gauss-Seidel pass, which leaves a stiff, finely divided
    /// rope too soft (the joints' compliance small against their particles' inverse masses).
    pub direct_bending: bool,
    /// Passes over the lengths and the joints together in each substep, the joints' multipliers
    /// carried from pass to pass (XPBD's accumulated `λ`), so that more passes converge on the
    /// substep's implicit step for both at once rather than on whichever was solved last. One pass
    /// is enough while the particles are heavy against the joints' stiffness; a rope at a real
    /// suture's mass needs more (four put the elastica's large deflections within 2 %, where one
    /// leaves them 4-8 % off). The lengths' multipliers are carried as well (solved directly; the
    /// Gauss-Seidel fallback carries none, and each of its passes after the first stiffens an
    /// elastic rope's lengths towards inextensible).
    pub constraint_passes: usize,
    /// Passes over the contacts after each pass over the lengths and joints. More let friction
    /// act closer to its coefficient: the reef trial's square knot of string at friction 0.5
    /// (`knotlab_lab::trials::reef`, 0.3 N on its standing parts for 1 s, its free ends let go)
    /// draws 1.52 mm apart with one, 1.11 mm of it in the last half second, and 0.34 mm with four,
    /// 0.085 mm in the last half second.
    pub contact_passes: usize,
    /// Whether the contacts are solved from either end of the candidate pairs in turn, one
    /// substep from the first pair, the next from the last ([`contact::solve_contacts`]). Solved
    /// always from the first, each contact starting from where the pairs before it left the
    /// particles, the solve pulls a knot along the rope towards the strand's first particle: the
    /// surgeon's double throw held by 1 N on each end creeps 15 mm/s that way and runs off the end
    /// (`knotlab validate`'s `knot_creep`). Solved both ways (the default) it stays; a string's
    /// wrap then needs more contact passes to hold what the capstan equation says it holds
    /// (`docs/validation.md`, "A knot creeping along its rope").
    pub contacts_both_ways: bool,
    /// Velocity damping, 1/s.
    pub damping_per_s: f64,
    /// Pairs of segments closer than this beyond touching are watched for contact, m; they are
    /// sought anew once a particle has moved half this since they were last sought.
    pub contact_margin_m: f64,
    /// Bending stiffness EI, N m² (0: a string). Each joint between two segments resists its
    /// turn as a compliant XPBD constraint on the difference of the segments' directions. With its
    /// free ends slack a string's knot presses on itself only as hard as its loop pulls it; a stiff
    /// rope's bends keep pressing, and its friction holds the knot. The default, 1e-7,
    /// is below a 3-0 monofilament's (polypropylene, 0.2 mm: about 3e-7).
    pub bending_stiffness_n_m2: f64,
    /// Axial stiffness EA, N: a segment stretches by its length times F / EA under a pull F, as a
    /// compliant XPBD constraint (infinite: inextensible, the default). Suture is elastic: a 3-0
    /// polypropylene's EA is about 160 N (E 4.0 GPa over a 0.225 mm section), a braided silk's some
    /// 150-350 N. Inextensible and held by a position-controlled instrument, a rope whose knot jams
    /// takes the whole draw in one step: a grip read 1.9 N, then 6.5 N, and slipped. Elastic, the
    /// rope is held exactly where bodies hold it ([`rigid`]); inextensible, it is held softly (its
    /// held particles solved with the rest and put back), which leaves their segments stretched by
    /// the pull.
    pub axial_stiffness_n: f64,
}

impl RopeParams {
    /// The radius at which metal pushes the rope, m: [`Self::metal_radius_m`], or the collision
    /// radius.
    pub fn radius_at_metal_m(&self) -> f64 {
        self.metal_radius_m.unwrap_or(self.radius_m)
    }
}

impl Default for RopeParams {
    fn default() -> Self {
        Self {
            radius_m: 0.0002,
            metal_radius_m: None,
            mass_per_m_kg: 0.67,
            static_friction: 1.0,
            kinetic_friction: 0.8,
            substeps: 20,
            stretch_iterations: 1,
            direct_stretch: true,
            direct_bending: false,
            constraint_passes: 1,
            contact_passes: 1,
            contacts_both_ways: true,
            damping_per_s: 100.0,
            contact_margin_m: 0.001,
            bending_stiffness_n_m2: 1e-7,
            axial_stiffness_n: f64::INFINITY,
        }
    }
}

/// Ropes (strands) and their state.
#[derive(Clone, Debug)]
pub struct Ropes {
    /// The material.
    pub params: RopeParams,
    /// Particle positions, m (strand after strand, each from its first end).
    pub x: Vec<Vector3<f64>>,
    /// Particle velocities, m/s.
    pub v: Vec<Vector3<f64>>,
    /// Inverse masses, 1/kg (0: pinned).
    pub w: Vec<f64>,
    /// External force on each particle for the next step, N.
    pub force_n: Vec<Vector3<f64>>,
    /// Each strand's particles.
    pub strands: Vec<Range<usize>>,
    /// Segments (particle pairs).
    segments: Vec<[usize; 2]>,
    /// Segment pairs near enough to touch (found anew at a step's start once a particle has moved
    /// half the contact margin since they were last found).
    candidates: Vec<(usize, usize)>,
    /// Which candidates may touch ([`contact::Watch`]).
    watch: contact::Watch,
    /// The positions at the start of the substep (kept to spare allocating them anew).
    x_prev: Vec<Vector3<f64>>,
    /// The direct stretch solver's working space.
    stretch_scratch: stretch::Scratch,
    /// The direct bending solver's working space.
    bend_scratch: bend::Scratch,
    /// Each segment's length multiplier accumulated over the substep's passes so far.
    stretch_lambda: Vec<f64>,
    /// Each segment's rest length, m (as `segments`: the segments of strand `s` from particle `a` on
    /// are `a - s` on).
    rest_m: Vec<f64>,
    /// The bending constraints' constants.
    bends: Bends,
    /// Contacts that touched in the last substep.
    pub contacts_last: usize,
    /// The particles held by the surroundings this substep ([`Surroundings::hold`]).
    held: Vec<bool>,
    /// The inverse masses the substep's solve uses: [`Self::w`], held particles 0.
    w_solve: Vec<f64>,
    /// What the substep's solve would have moved each held particle by, times its mass, kg m (0
    /// for the free ones).
    held_pull: Vec<Vector3<f64>>,
    /// Where each particle was carried by its velocity and force in the substep, before a body
    /// held it, m.
    x_free: Vec<Vector3<f64>>,
    /// The particles as the surroundings held them, before the solve, m.
    x_held: Vec<Vector3<f64>>,
    /// The watch for strands passing through each other.
    crossing: crate::crossing::CrossingWatch,
    /// Whether this substep's contacts are solved from the last candidate pair to the first
    /// ([`contact::solve_contacts`]); turned over every substep where
    /// [`RopeParams::contacts_both_ways`], else never.
    contacts_backward: bool,
}

/// The bending constraints' constants ([`Ropes::solve_bending`]), worked out once for a rope, its
/// bending stiffness and its substep.
#[derive(Clone, Debug, Default)]
struct Bends {
    /// The bending stiffness's and the substep's bits and the number of segments they were worked
    /// out for.
    key: (u64, u64, usize),
    joints: Vec<Bend>,
    /// Each joint's multiplier accumulated over the substep's passes so far.
    lambda: Vec<Vector3<f64>>,
}

/// One joint between two segments `a b` and `b c`: their rest lengths, the turn's gradients and the
/// compliance over the substep.
#[derive(Clone, Copy, Debug)]
struct Bend {
    p: [usize; 3],
    l1: f64,
    l2: f64,
    g: [f64; 3],
    compliance: f64,
}

impl Bends {
    fn new(ropes: &Ropes, h_s: f64, key: (u64, u64, usize)) -> Self {
        let ei = ropes.params.bending_stiffness_n_m2;
        let mut joints = Vec::new();
        for (s, range) in ropes.strands.iter().enumerate() {
            // Strand s's segments follow those of the strands before it, one fewer than their
            // particles each: the segment from particle a is a - s.
            for b in range.start + 1..range.end.saturating_sub(1) {
                let (a, c) = (b - 1, b + 1);
                let l1 = ropes.rest_m[a - s];
                let l2 = ropes.rest_m[b - s];
                if l1 <= 0.0 || l2 <= 0.0 {
                    continue;
                }
                let stiffness = ei / (0.5 * (l1 + l2));
                let compliance = 1.0 / (stiffness * h_s * h_s);
                let g = [1.0 / l1, -(1.0 / l1 + 1.0 / l2), 1.0 / l2];
                joints.push(Bend { p: [a, b, c], l1, l2, g, compliance });
            }
        }
        let lambda = vec![Vector3::zeros(); joints.len()];
        Self { key, joints, lambda }
    }
}

impl Ropes {
    /// No strands yet.
    pub fn new(params: RopeParams) -> Self {
        Self {
            params,
            x: Vec::new(),
            v: Vec::new(),
            w: Vec::new(),
            force_n: Vec::new(),
            strands: Vec::new(),
            segments: Vec::new(),
            candidates: Vec::new(),
            watch: contact::Watch::default(),
            x_prev: Vec::new(),
            stretch_scratch: stretch::Scratch::default(),
            bend_scratch: bend::Scratch::default(),
            stretch_lambda: Vec::new(),
            rest_m: Vec::new(),
            bends: Bends::default(),
            contacts_last: 0,
            held: Vec::new(),
            w_solve: Vec::new(),
            held_pull: Vec::new(),
            x_free: Vec::new(),
            x_held: Vec::new(),
            crossing: crate::crossing::CrossingWatch::default(),
            contacts_backward: false,
        }
    }

    /// Adds a strand along `path` with particles `spacing_m` apart (chords of the path; at least two
    /// particles: a spacing that is not positive and finite lays two). Returns its particle
    /// range.
    pub fn add_strand_along(&mut self, path: &[Vector3<f64>], spacing_m: f64) -> Range<usize> {
        let length_m: f64 = path.windows(2).map(|w| (w[1] - w[0]).norm()).sum();
        let spacing_m = if spacing_m > 0.0 && spacing_m.is_finite() { spacing_m } else { length_m.max(1e-6) };
        let count = ((length_m / spacing_m).floor() as usize + 1).max(2);
        self.add_strand(&crate::chords::chord_points(path, spacing_m, count))
    }

    /// Adds a strand through `points` (its particles, at rest; each segment's rest length is its
    /// length as laid; each particle weighs the rope's mass per metre times half its two segments).
    /// Returns its particle range.
    pub fn add_strand(&mut self, points: &[Vector3<f64>]) -> Range<usize> {
        let start = self.x.len();
        for (k, p) in points.iter().enumerate() {
            let before = if k > 0 { (p - points[k - 1]).norm() } else { 0.0 };
            let after = if k + 1 < points.len() { (points[k + 1] - p).norm() } else { 0.0 };
            let mass_kg = self.params.mass_per_m_kg * 0.5 * (before + after);
            self.x.push(*p);
            self.v.push(Vector3::zeros());
            self.w.push(if mass_kg > 0.0 { 1.0 / mass_kg } else { 0.0 });
            self.force_n.push(Vector3::zeros());
        }
        let range = start..self.x.len();
        for i in start..range.end.saturating_sub(1) {
            let rest = (self.x[i + 1] - self.x[i]).norm();
            self.segments.push([i, i + 1]);
            self.rest_m.push(rest);
        }
        self.strands.push(range.clone());
        range
    }

    /// The particles of the strand `particle` belongs to, if any.
    pub fn strand_holding(&self, particle: usize) -> Option<Range<usize>> {
        self.strands.iter().find(|s| s.contains(&particle)).cloned()
    }

    /// Which way the rope runs through the run `run` of one strand (from its first particle
    /// towards its last, over a neighbour either side where the strand has one); `None` for an
    /// empty run or a strand standing on one point.
    pub fn way_through(&self, run: &Range<usize>) -> Option<Vector3<f64>> {
        let strand = self.strand_holding(run.start)?;
        let before = run.start.saturating_sub(1).max(strand.start);
        let after = run.end.min(strand.end - 1);
        (self.x[after] - self.x[before]).try_normalize(1e-12)
    }

    /// The strand a particle belongs to.
    fn strand_of(&self, particle: usize) -> usize {
        self.strands.iter().position(|r| r.contains(&particle)).unwrap_or(usize::MAX)
    }

    /// Advances by `dt_s` in empty space, applying `force_n` throughout.
    pub fn step(&mut self, dt_s: f64) {
        self.step_in(dt_s, &mut ());
    }

    /// Advances by `dt_s` in `surroundings`, applying `force_n` throughout.
    pub fn step_in(&mut self, dt_s: f64, surroundings: &mut dyn Surroundings) {
        let mut watch = std::mem::take(&mut self.watch);
        let mut crossing = std::mem::take(&mut self.crossing);
        crossing.start_step(&self.x);
        let mut x_prev = std::mem::take(&mut self.x_prev);
        let h = dt_s / self.params.substeps as f64;
        for _ in 0..self.params.substeps {
            // Checked each substep: a rope moving half the margin within a step would otherwise
            // meet pairs the search at its start did not take.
            if !watch.still_covers(self) {
                self.find_candidates();
                watch.found(self);
                crossing.candidates_changed(self.candidates.len());
            }
            // The contacts are solved one after another, each from where the last left the
            // particles: always in one order, that order pulls a knot along the rope
            // ([`RopeParams::contacts_both_ways`]).
            self.contacts_backward = self.params.contacts_both_ways && !self.contacts_backward;
            x_prev.clone_from(&self.x);
            for i in 0..self.x.len() {
                if self.w[i] > 0.0 {
                    self.v[i] += self.force_n[i] * (self.w[i] * h);
                    self.x[i] += self.v[i] * h;
                }
            }
            // The held particles where their bodies hold them, and pinned for the solve: the
            // lengths next to them hold, and the pull on them is the solve's reaction there.
            let n = self.x.len();
            let mut held = std::mem::take(&mut self.held);
            held.clear();
            held.resize(n, false);
            self.x_free.clone_from(&self.x);
            surroundings.hold(self, &mut held, h);
            self.held = held;
            self.x_held.clone_from(&self.x);
            self.solve_held(h, &mut watch, &x_prev);
            // A hold that would slip under that pull lets its particles go for the substep: solved
            // again with them free, they are put back afterwards, and the hold gives way. The
            // surroundings read the pull on the held particles as they stand, so from a copy.
            let mut held = self.held.clone();
            let slipping = surroundings.slipping(self, &mut held, h);
            self.held = held;
            if slipping {
                self.x.clone_from(&self.x_held);
                surroundings.start_slipping(self, h);
                self.solve_held(h, &mut watch, &x_prev);
            }
            surroundings.after(self, &x_prev, h);
            // The rope's contacts with itself have the last word: a body's push (the jaws', the
            // tissue's) that left two strands overlapping would carry one through the other in
            // the next substep.
            if surroundings.pushed_the_rope() {
                std::mem::swap(&mut self.w, &mut self.w_solve);
                contact::solve_contacts(self, &mut watch, &x_prev, true, contact::Friction::OwnPush);
                std::mem::swap(&mut self.w, &mut self.w_solve);
            }
            let damp = 1.0 / (1.0 + h * self.params.damping_per_s);
            for ((v, x), x_prev) in self.v.iter_mut().zip(&self.x).zip(&x_prev) {
                *v = (x - x_prev) / h * damp;
            }
            crossing.look(&self.x, &self.segments, &self.candidates, self.params.radius_m);
        }
        self.watch = watch;
        self.crossing = crossing;
        self.x_prev = x_prev;
    }

    /// The lengths, joints and contacts solved over a substep of `h_s` seconds that started from
    /// `x_prev`, with the held particles pinned, the pull on them summed anew. Each pass solves the
    /// contacts after the lengths and joints, their pushes and friction summed over the passes
    /// (the contacts move the held particles no more than the lengths do).
    fn solve_held(&mut self, h_s: f64, watch: &mut contact::Watch, x_prev: &[Vector3<f64>]) {
        let n = self.x.len();
        self.w_solve.clone_from(&self.w);
        for (w, held) in self.w_solve.iter_mut().zip(&self.held) {
            if *held {
                *w = 0.0;
            }
        }
        self.held_pull.clear();
        self.held_pull.resize(n, Vector3::zeros());
        std::mem::swap(&mut self.w, &mut self.w_solve);
        let bending = self.params.bending_stiffness_n_m2 > 0.0;
        if bending {
            self.start_bending(h_s);
        }
        self.stretch_lambda.clear();
        self.stretch_lambda.resize(self.rest_m.len(), 0.0);
        watch.start_substep();
        for _ in 0..self.params.constraint_passes.max(1) {
            for _ in 0..self.params.stretch_iterations {
                self.solve_stretch(h_s);
            }
            if bending {
                self.solve_bending();
            }
            for contact_pass in 0..self.params.contact_passes.max(1) {
                self.contacts_last = contact::solve_contacts(
                    self,
                    watch,
                    x_prev,
                    contact_pass == 0,
                    contact::Friction::Summed,
                );
            }
        }
        std::mem::swap(&mut self.w, &mut self.w_solve);
    }

    /// Readies the joints for a substep of `h_s` seconds: their constants (worked out anew when the
    /// stiffness, the substep or the rope changed), their multipliers at zero and, solved a strand
    /// at once, their matrices factored for the inverse masses as they stand (the held particles
    /// pinned), which every pass over the substep shares.
    fn start_bending(&mut self, h_s: f64) {
        let key = (self.params.bending_stiffness_n_m2.to_bits(), h_s.to_bits(), self.rest_m.len());
        if self.bends.key != key {
            self.bends = Bends::new(self, h_s, key);
        }
        self.bends.lambda.iter_mut().for_each(|l| *l = Vector3::zeros());
        if self.params.direct_bending {
            // A run it cannot factor (every particle pinned, no compliance) cannot move either.
            bend::factor(&self.bends.joints, &self.w, &mut self.bend_scratch);
        }
    }

    /// One XPBD pass over the joints: at joint `b` between segments `a b` and `b c` (rest lengths
    /// `l1`, `l2`) the constraint `C = (x_c - x_b)/l2 - (x_b - x_a)/l1` (the turn, about the angle for
    /// a small one) with stiffness `EI / l̄`, `l̄` their mean: the energy of a rod's curvature
    /// `|C|/l̄` over `l̄`. Each pass moves the joint's multiplier by `Δλ = -(C + α̃ λ) / (w + α̃)`
    /// (XPBD); the constraint is linear in the positions, so the first pass from `λ = 0` is a
    /// substep's implicit spring for each joint alone; with [`RopeParams::direct_bending`] the
    /// strand's joints are solved together ([`bend`]).
    fn solve_bending(&mut self) {
        let Bends { joints, lambda, .. } = &mut self.bends;
        if self.params.direct_bending {
            bend::project(joints, lambda, &mut self.x, &self.w, &mut self.bend_scratch, &mut self.held_pull);
            return;
        }
        for (bend, lambda) in joints.iter().zip(lambda.iter_mut()) {
            let [a, b, c] = bend.p;
            let g = bend.g;
            let turn = (self.x[c] - self.x[b]) / bend.l2 - (self.x[b] - self.x[a]) / bend.l1;
            let weight: f64 = (0..3).map(|k| self.w[bend.p[k]] * g[k] * g[k]).sum();
            let dlambda = -(turn + *lambda * bend.compliance) / (weight + bend.compliance);
            *lambda += dlambda;
            for (p, g) in bend.p.into_iter().zip(g) {
                if self.w[p] == 0.0 {
                    self.held_pull[p] += dlambda * g;
                }
                self.x[p] += dlambda * (self.w[p] * g);
            }
        }
    }

    fn solve_stretch(&mut self, h_s: f64) {
        // Each segment's compliance over the substep, per metre of its rest length (XPBD's
        // alpha / h^2 with alpha = length / EA).
        let ea = self.params.axial_stiffness_n;
        let compliance_per_m = if ea.is_finite() && ea > 0.0 { 1.0 / (ea * h_s * h_s) } else { 0.0 };
        let mut singular = false;
        if self.params.direct_stretch {
            for (s, range) in self.strands.iter().enumerate() {
                // Strand s's segments follow those of the strands before it, one fewer than their
                // particles each.
                let first_segment = range.start - s;
                let count = range.len().saturating_sub(1);
                singular |= !stretch::project_strand(
                    &mut self.x[range.clone()],
                    &self.w[range.clone()],
                    &self.rest_m[first_segment..first_segment + count],
                    compliance_per_m,
                    &mut self.stretch_lambda[first_segment..first_segment + count],
                    &mut self.stretch_scratch,
                    &mut self.held_pull[range.clone()],
                );
            }
            if !singular {
                return;
            }
        }
        for k in 0..self.segments.len() {
            let ([a, b], rest) = (self.segments[k], self.rest_m[k]);
            let (wa, wb) = (self.w[a], self.w[b]);
            let wsum = wa + wb;
            if wsum == 0.0 {
                continue;
            }
            let wsum = wsum + rest * compliance_per_m;
            let d = self.x[b] - self.x[a];
            let len = d.norm();
            if len < 1e-12 {
                continue;
            }
            let n = d / len;
            let c = len - rest;
            self.x[a] += n * (wa * c / wsum);
            self.x[b] -= n * (wb * c / wsum);
            // A pinned end's share, as a mass times the move: the pull on what pins it.
            if wa == 0.0 {
                self.held_pull[a] += n * (c / wsum);
            }
            if wb == 0.0 {
                self.held_pull[b] -= n * (c / wsum);
            }
        }
    }

    /// The segment pairs that may touch during the next step: not neighbours in one strand, their
    /// boxes within two radii and the margin of each other.
    fn find_candidates(&mut self) {
        let reach = self.params.radius_m + 0.5 * self.params.contact_margin_m;
        let strand_of: Vec<usize> = (0..self.x.len()).map(|p| self.strand_of(p)).collect();
        let segments = &self.segments;
        self.candidates = broad_phase::candidate_pairs(&self.x, segments, reach, |i, j| {
            let ([a, b], [c, _]) = (segments[i], segments[j]);
            strand_of[a] == strand_of[c] && c <= b + 1
        });
    }

    /// Where particle `p` would have gone in the last substep had no body held it
    /// ([`Surroundings::hold`]), m: carried by its velocity and force, then moved by the solve of the
    /// lengths as the pull on it over its mass. A body holding it there gives it the difference
    /// (times its mass, over the substep) as an impulse. Its place, for a particle not held.
    pub fn unheld_m(&self, p: usize) -> Vector3<f64> {
        if !self.held.get(p).copied().unwrap_or(false) {
            return self.x[p];
        }
        let pull = self.held_pull.get(p).copied().unwrap_or_else(Vector3::zeros);
        self.x_free[p] + pull * self.w.get(p).copied().unwrap_or(0.0)
    }

    /// The segment pairs (by segment index, smaller first) that passed through each other in the
    /// last step ([`crate::crossing`]): a solver failure, never real thread.
    pub fn crossed_last_step(&self) -> &[(usize, usize)] {
        self.crossing.crossed()
    }

    /// How far the most stretched segment reaches beyond its rest length, as a fraction of it (0
    /// when none is stretched).
    pub fn max_stretch_ratio(&self) -> f64 {
        self.segments
            .iter()
            .zip(&self.rest_m)
            .map(|([a, b], rest)| ((self.x[*b] - self.x[*a]).norm() - rest) / rest)
            .fold(0.0, f64::max)
    }

    /// The strand's polyline, m.
    pub fn polyline(&self, strand: usize) -> Vec<Vector3<f64>> {
        self.x[self.strands[strand].clone()].to_vec()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A strand is laid at its particle spacing, and a zero, negative or non-finite spacing lays just its two
    /// ends, every position finite.
    #[test]
    fn a_strand_is_laid_at_its_spacing_and_a_bad_spacing_lays_two_particles() {
        let path = [Vector3::zeros(), Vector3::new(0.003, 0.0, 0.0)];
        let mut ropes = Ropes::new(RopeParams::default());
        assert_eq!(ropes.add_strand_along(&path, 0.0003).len(), 11);
        for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert_eq!(ropes.add_strand_along(&path, bad).len(), 2, "spacing {bad}");
        }
        assert!(ropes.x.iter().all(|p| p.iter().all(|c| c.is_finite())));
    }

    /// A strand laid along `path` with its particles `spacing_radii` apart, string (no bending
    /// stiffness), left to itself for 20 ms: the contacts it found in the last substep and how far
    /// its particles moved, m.
    fn left_alone(spacing_radii: f64, path: &[Vector3<f64>]) -> (usize, f64) {
        let params = RopeParams { bending_stiffness_n_m2: 0.0, ..RopeParams::default() };
        let spacing_m = spacing_radii * params.radius_m;
        let mut ropes = Ropes::new(params);
        ropes.add_strand_along(path, spacing_m);
        let laid = ropes.x.clone();
        for _ in 0..20 {
            ropes.step(0.001);
        }
        let moved_m = ropes.x.iter().zip(&laid).map(|(x, laid)| (x - laid).norm()).fold(0.0, f64::max);
        (ropes.contacts_last, moved_m)
    }

    /// Guards the least spacing a scene may ask for (`crate::thread::ROPE_SPACING_RADII_RANGE`): a
    /// strand laid there, straight or curved round another of its size (its axis two radii from the
    /// other's, three quarters of a turn), touches nothing of itself and lies still; laid closer
    /// (0.9 radii straight, 1 radius curved), its segments three along touch and push it apart.
    #[test]
    fn a_strand_at_the_least_spacing_allowed_lies_still_straight_and_curved_tight() {
        let radius_m = RopeParams::default().radius_m;
        let straight = [Vector3::zeros(), Vector3::new(0.02, 0.0, 0.0)];
        let curved: Vec<_> = (0..=270)
            .map(|deg| {
                let a = f64::from(deg).to_radians();
                Vector3::new(a.cos(), a.sin(), 0.0) * (2.0 * radius_m)
            })
            .collect();
        let least = crate::thread::ROPE_SPACING_RADII_RANGE.0;
        for (what, path, closer) in [("straight", &straight[..], 0.9), ("curved", &curved[..], 1.0)] {
            let (contacts, moved_m) = left_alone(least, path);
            assert!(
                contacts == 0 && moved_m < 1e-12,
                "{what} at {least} radii: {contacts} contacts, moved {moved_m:e} m"
            );
            let (contacts, moved_m) = left_alone(closer, path);
            assert!(
                contacts > 0 && moved_m > 1e-6,
                "{what} at {closer} radii: {contacts} contacts, moved {moved_m:e} m"
            );
        }
    }

    /// A strand bent at a right angle in its middle, left to itself for 0.2 s: how far its ends
    /// lie apart, as a fraction of its length.
    fn straightened(bending_stiffness_n_m2: f64) -> f64 {
        let params = RopeParams { bending_stiffness_n_m2, ..RopeParams::default() };
        let mut ropes = Ropes::new(params);
        let path = [Vector3::new(-0.003, 0.0, 0.0), Vector3::zeros(), Vector3::new(0.0, 0.003, 0.0)];
        let strand = ropes.add_strand_along(&path, 0.0003);
        for _ in 0..200 {
            ropes.step(0.001);
        }
        (ropes.x[strand.end - 1] - ropes.x[strand.start]).norm() / 0.006
    }

    /// A strand with bending stiffness straightens from a right-angle bend within 0.2 s while one without
    /// stays bent as laid.
    #[test]
    fn a_stiff_strand_straightens_and_a_string_stays_bent() {
        // At rest the ends lie 0.71 of the length apart.
        let (stiff, string) = (straightened(1e-7), straightened(0.0));
        assert!(stiff > 0.9, "the stiff strand's ends lie {stiff:.3} of its length apart");
        assert!(
            (string - 0.5f64.sqrt()).abs() < 0.01,
            "the string's ends lie {string:.3} of its length apart"
        );
    }

    /// Guards the contact search within a step: a strand thrown at another at 5 m/s (5 mm a step,
    /// a quarter of a millimetre a substep, against a 1 mm margin) from 2 mm off, beyond the
    /// search's reach at the step's start, meets it and stays on its own side, where a search made
    /// only at the start of each step let it through unseen.
    #[test]
    fn a_strand_faster_than_the_margin_a_step_is_still_met() {
        let params =
            RopeParams { substeps: 20, contact_margin_m: 0.001, damping_per_s: 0.0, ..RopeParams::default() };
        let mut ropes = Ropes::new(params);
        let line = |x: f64, z: f64| -> Vec<Vector3<f64>> {
            (0..=20).map(|k| Vector3::new(x, -0.005 + 0.0005 * k as f64, z)).collect()
        };
        let still = ropes.add_strand(&line(0.0, 0.0));
        let thrown = ropes.add_strand(&line(-0.002, 0.0));
        for p in still {
            ropes.w[p] = 0.0;
        }
        for p in thrown.clone() {
            ropes.v[p] = Vector3::new(5.0, 0.0, 0.0);
        }
        ropes.step(0.001);
        let farthest = thrown.map(|p| ropes.x[p].x).fold(f64::NEG_INFINITY, f64::max);
        assert!(farthest < -0.0003, "the thrown strand reached x = {farthest:.5} m");
    }

    /// The bending joints' compliance halves as stiffness doubles and falls fourfold as the substep doubles.
    #[test]
    fn the_bending_constants_follow_the_stiffness_and_the_substep() {
        let mut ropes = Ropes::new(RopeParams::default());
        ropes.add_strand_along(&[Vector3::zeros(), Vector3::new(0.003, 0.001, 0.0)], 0.0003);
        ropes.step(0.001);
        let first = ropes.bends.joints[0].compliance;
        assert!(first > 0.0 && first.is_finite(), "compliance {first}");
        // Twice as stiff: half the compliance; then substeps twice as long: a quarter of that.
        ropes.params.bending_stiffness_n_m2 *= 2.0;
        ropes.step(0.001);
        let stiffer = ropes.bends.joints[0].compliance;
        assert!((stiffer - first / 2.0).abs() < 1e-12 * first, "{stiffer} against {first}");
        ropes.step(0.002);
        let longer = ropes.bends.joints[0].compliance;
        assert!((longer - first / 8.0).abs() < 1e-12 * first, "{longer} against {first}");
    }

    /// A 30 mm strand along x, its first particle pinned and its last pulled along x with 1 N for
    /// 0.5 s: how much longer than laid it is, m.
    fn stretched_under_1_n(axial_stiffness_n: f64) -> f64 {
        let mut ropes = Ropes::new(RopeParams { axial_stiffness_n, ..RopeParams::default() });
        let strand = ropes.add_strand_along(&[Vector3::zeros(), Vector3::new(0.03, 0.0, 0.0)], 0.0003);
        ropes.w[strand.start] = 0.0;
        ropes.force_n[strand.end - 1] = Vector3::x();
        for _ in 0..500 {
            ropes.step(0.001);
        }
        let line = ropes.polyline(0);
        line.windows(2).map(|p| (p[1] - p[0]).norm()).sum::<f64>() - 0.03
    }

    /// Guards the direct solve at a real suture's mass: a 50 mm strand of 3-0 polypropylene (36 mg/m,
    /// EA 160 N) held at one end and pulled along itself with 2 N stretches by F / EA, 1.25 %, within
    /// a hundredth of that, with one pass or four. The pull flings its end particle (a fraction of a
    /// microgram) metres in a substep before the lengths put it back; a projection that refused to
    /// move a particle that far fell back on Gauss-Seidel and the strand stretched 865-fold. With
    /// four passes each length's multiplier is carried from pass to pass: not carried, each pass
    /// after the first took most of the stretch back.
    #[test]
    fn a_light_elastic_strand_pulled_hard_stretches_by_its_pull_over_its_axial_stiffness() {
        for constraint_passes in [1, 4] {
            let params = RopeParams {
                radius_m: 0.0001125,
                mass_per_m_kg: 3.6e-5,
                substeps: 12,
                axial_stiffness_n: 160.0,
                damping_per_s: 1.0,
                constraint_passes,
                ..RopeParams::default()
            };
            let mut ropes = Ropes::new(params);
            let strand = ropes.add_strand_along(&[Vector3::zeros(), Vector3::new(0.05, 0.0, 0.0)], 0.0003375);
            ropes.w[strand.start] = 0.0;
            ropes.force_n[strand.end - 1] = Vector3::x() * 2.0;
            let length =
                |ropes: &Ropes| ropes.polyline(0).windows(2).map(|p| (p[1] - p[0]).norm()).sum::<f64>();
            let laid_m = length(&ropes);
            for _ in 0..50 {
                ropes.step(0.001);
            }
            let strain = length(&ropes) / laid_m - 1.0;
            assert!((strain - 0.0125).abs() < 1.25e-4, "{constraint_passes} passes: strain {strain}");
        }
    }

    /// Surroundings holding one particle where it is, which read the pull on it when asked
    /// whether it slips.
    struct HoldOne {
        particle: usize,
        at_m: Vector3<f64>,
        pull_read_m: Vector3<f64>,
    }

    impl Surroundings for HoldOne {
        fn hold(&mut self, ropes: &mut Ropes, held: &mut [bool], _h_s: f64) {
            ropes.x[self.particle] = self.at_m;
            held[self.particle] = true;
        }

        fn slipping(&mut self, ropes: &Ropes, _held: &mut [bool], _h_s: f64) -> bool {
            self.pull_read_m = ropes.unheld_m(self.particle) - ropes.x[self.particle];
            false
        }

        fn after(&mut self, _: &mut Ropes, _: &[Vector3<f64>], _: f64) {}
    }

    /// Guards what a hold reads when it is asked whether it slips: the pull on its particle (where
    /// the solve would have taken it), towards the pull on the strand. Read while the held
    /// particles were taken out of the rope for the asking, it was nothing, and no hold could
    /// slip there.
    #[test]
    fn a_hold_asked_whether_it_slips_reads_the_pull_on_its_particle() {
        let params = RopeParams { axial_stiffness_n: 100.0, ..RopeParams::default() };
        let mut ropes = Ropes::new(params);
        let strand = ropes.add_strand_along(&[Vector3::zeros(), Vector3::new(0.03, 0.0, 0.0)], 0.0003);
        ropes.force_n[strand.end - 1] = Vector3::x();
        let mut hold =
            HoldOne { particle: strand.start, at_m: Vector3::zeros(), pull_read_m: Vector3::zeros() };
        for _ in 0..20 {
            ropes.step_in(0.001, &mut hold);
        }
        let pull = hold.pull_read_m;
        assert!(pull.x > 0.0 && pull.x > 100.0 * pull.yz().norm(), "the hold read a pull of {pull:?} m");
    }

    /// A strand of axial stiffness 100 N stretches 1 % under a 1 N pull, within a tenth, and an inextensible
    /// one stretches by under 10 µm.
    #[test]
    fn an_elastic_strand_stretches_by_its_pull_over_its_axial_stiffness() {
        // EA = 100 N: 1 N stretches 30 mm by 0.3 mm (1 %); inextensible, by nothing to speak of.
        let elastic = stretched_under_1_n(100.0);
        assert!((elastic - 0.0003).abs() < 0.00003, "stretched {:.4} mm", elastic * 1e3);
        let stiff = stretched_under_1_n(f64::INFINITY);
        assert!(stiff.abs() < 0.00001, "stretched {:.5} mm", stiff * 1e3);
    }
}

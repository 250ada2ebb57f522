//! The tie's geometry: where the expert puts things in the stitch frame and how hard it pulls
//! ([`TieGeometry`], the settings an expert file gives), how the left goes to the tail
//! ([`LeftFetch`]), and a second throw's differences from the first ([`SecondThrow`]).

mod second_throw;

pub use second_throw::SecondThrow;

/// Where the expert puts things, in the stitch frame (m), and how hard it pulls. Its default is the base
/// plan (listed in `scenarios/experts/base.toml`), whose values an expert file's missing keys take; the
/// shipped plan is `scenarios/experts/instrument-tie.toml`.
#[derive(Clone, Debug, PartialEq, serde::Deserialize, serde::Serialize)]
#[serde(default, deny_unknown_fields)]
pub struct TieGeometry {
    /// The left's jaw centre while the long end is wound around its jaws.
    pub winding_point_m: [f64; 3],
    /// Distance of the right's jaws from the left's jaw axis while winding, m.
    pub winding_radius_m: f64,
    /// The winding starts this far (about the left's jaw axis) before the point opposite the exit,
    /// where the long end runs straight over the jaws, rad.
    pub winding_lead_rad: f64,
    /// The winding first moves this way (made perpendicular to the axis): it picks the sense of the
    /// turns about the left's jaws.
    pub winding_towards: [f64; 3],
    /// If set, the left takes its coils to the tail instead of the assist bringing the tail.
    pub left_fetches: Option<LeftFetch>,
    /// The assist presents the tail to the left's jaws where they wound, as in the paper's task,
    /// instead of the left fetching it: `left_fetches` is then not used (a file cannot unset it, the
    /// base plan fetches). Meant for a first throw that forms flat, the jaws level along the wound
    /// (a fetch with the jaws turned down draws the tail straight through the coils). Tried with
    /// the second throw's winding on a 47 mm tail: two turns reached the jaws and
    /// the left took the tail, but its free end lay back along the jaws inside the coils
    /// (`knotlab knot draw-through`: no knot).
    pub assist_presents: bool,
    /// Where the left's jaws point while the long end is wound around them (stitch frame); `None`: at
    /// the right's trocar, so that the right's shaft circles them at a distance.
    pub left_jaw_direction: Option<[f64; 3]>,
    /// While winding, the right's jaws turn this fraction of the way from along its shaft, which
    /// reaches back past the circle to where the long end leaves the coils for the exit, to at
    /// right angles to the left's jaws (its shaft's direction with the part along them taken out).
    pub right_jaws_across_winding: f64,
    /// The winding circles this far behind the left's jaw centre (towards its wrist), m; less if the
    /// thread in the right's jaws would pass through the left's wrist there ([`super::clearance`]).
    pub winding_behind_m: f64,
    /// The winding advances this far along the left's jaws (towards their tips; negative: towards
    /// the wrist) per turn, m: a helix, not a circle. (Tried so that the second turn
    /// would close over the long end's knot leg, which decides the throw's hand; the turn slid along
    /// the jaws as a whole instead.)
    pub winding_pitch_m: f64,
    /// How long the winding takes, s (slow enough for the arm to follow the circle).
    pub winding_s: f64,
    /// Turns of the winding (a surgeon's knot: 2).
    pub winding_turns: f64,
    /// If set, the right keeps the long end's tension while it winds: its tip gives way along the
    /// thread when its gauge reads more than this, and comes back towards the circle when less, N
    /// ([`knotlab_hw::skill::ForceAction::Give`]). A suture at its real weight does not drape over
    /// the jaws as a heavy one does; what lays it on them is the tension the winding keeps, and a
    /// circle that asks for more thread than the long end has tears the tail from the assist
    /// unless the right gives. Where the left fetches the tail, the plan then ends with the coils
    /// wound and the fetch is planned from the world the wind leaves ([`super::plan_after_wind`]).
    pub winding_give_force_n: Option<f64>,
    /// ... giving (and coming back) this fast per newton over (under) it, m/(N s).
    pub winding_give_rate_m_per_n_s: f64,
    /// ... and, where the throw goes on in the same plan (the assist presents the tail, or a second
    /// throw's left holds it already), kept this long after the wind, s: then the track takes over
    /// at once.
    pub winding_give_after_s: f64,
    /// The left's jaws are open this far while the long end is wound round them, rad: coils wound
    /// tight round closed jaws are stretched when the jaws open to take the tail.
    pub winding_jaw_rad: f64,
    /// The assist presents the tail this far ahead of the left's jaw centre, along its jaws, m.
    pub tail_ahead_m: f64,
    /// ... and the left's jaw centre stops this far short of it, m: jaws open 0.6 rad leave the
    /// thread room between them only in their front 3.6 mm (capsules 3 mm thick), so a tail at the
    /// jaw centre is pinched by both and squeezed out as they close.
    pub tail_take_short_m: f64,
    /// If set, the assist, holding the tail near its end, offers it across the left's open jaws
    /// instead of swinging it taut: its jaw centre this far beside the point ahead of the left's
    /// jaws, along their hinge, its own hinge along theirs, so that the thread runs from its jaws
    /// between the left's, m. The left then takes the tail that close to the assist's grip.
    pub tail_end_offered_m: Option<f64>,
    /// If not empty, the assist takes the tail along these points (stitch frame) instead of the swing.
    pub tail_via_m: Vec<[f64; 3]>,
    /// Where the assist's jaws point along the tail's route (stitch frame); `None`: along its shaft.
    pub assist_jaw_direction: Option<[f64; 3]>,
    /// The tail's swing about the entry point leans this way off the shortest arc (stitch frame).
    pub tail_swing_lean: [f64; 3],
    /// After winding, the right moves this much towards the left's jaws to loosen the coils, m.
    pub loosen_m: f64,
    /// ... and this much back along the left's jaws, drawing the coils towards their hinge, m.
    pub coils_back_m: f64,
    /// The left opens its jaws this far to take the tail, rad. Opened only part way (0.5 rad), 3 of
    /// seeds 0-7 kept a coil on the jaws after the draw (a single throw; the jaws likely closed on it
    /// with the tail); at 0.8 rad none did.
    pub take_tail_jaw_rad: f64,
    /// The assist first draws the tail this much tauter, m.
    pub tail_tension_m: f64,
    /// The assist holds the tail this far beyond the point the left's jaws close on, m.
    pub tail_beyond_m: f64,
    /// While the right winds, the assist moves the tail this fraction of the way to the entry
    /// point, giving thread.
    pub tail_give_fraction: f64,
    /// Once the right has wound, the assist brings the tail it holds here (stitch frame) before the
    /// left fetches it; `None`: it stays. Held far out while the right winds (held near, the tail
    /// was caught in the turn and torn from the assist's jaws, 32 N), brought near the stitch for the
    /// take: the long end reaches no further with the turn round the left's jaws
    /// ([`super::turn_thread`]), and taken far from its end, the tail's bight must be drawn through
    /// the turn. (Tried: on the way the assist lost the tail in every run, at 15-62 N.)
    pub tail_brought_to_m: Option<[f64; 3]>,
    /// First the knot is run down onto the wound: the left draws the tail up and out over the tail's
    /// flap to here, while the right takes its jaws, and the knot just under them, down to
    /// `right_run_down_to_m`. With both ends pulled from above (left (0, 0.01, 0.045),
    /// right (0, -0.015, 0.045)) the knot was cinched about 8 mm under the jaws, 28-38 mm up with
    /// 122-152 mm of thread between it and the stitch; the knot is there because the right's jaws,
    /// which hold the needle, are only a few centimetres of thread from the coils.
    pub left_run_down_to_m: [f64; 3],
    /// Where the right's jaws go meanwhile: low over the long end's flap.
    pub right_run_down_to_m: [f64; 3],
    /// The left goes through these points (stitch frame) on its way to `left_run_down_to_m`, each
    /// leg taking `run_down_s`, while the right makes its run-down in the first leg: for a second
    /// throw whose ends cross, the tail carried over the long end once the right has drawn it clear.
    pub left_run_down_via_m: Vec<[f64; 3]>,
    /// The right goes through these points (stitch frame) on its way to `right_run_down_to_m`, each
    /// leg taking `run_down_s`: for example out of the way while the left carries the tail across
    /// (drawn away before the left crossed, the second throw's turn came off).
    pub right_run_down_via_m: Vec<[f64; 3]>,
    /// How long the run-down takes, s.
    pub run_down_s: f64,
    /// If set, each instrument stops its run-down where its gauge first reads this force, N (the
    /// grip on a thread slips at 5 N: a run-down that drags a jammed throw would lose it).
    pub run_down_force_n: Option<f64>,
    /// Then the left pulls the tail towards here, out over its flap at the tissue's level...
    pub left_pull_to_m: [f64; 3],
    /// ... while the right pulls the long end out over the other flap, until the set force. Pulled
    /// level with the tissue, the ends draw the knot down onto it and the wound closed (seeds
    /// 0-7: the wound 1.1-1.8 mm as both let go); pulled up and out (the left to (0, 0.05,
    /// 0.055)), the knot stayed 2-7 mm up and the wound 2.5-3.3 mm open.
    pub right_pull_to_m: [f64; 3],
    /// How long each pull takes to its target, s (it stops sooner at its set force; a fast pull
    /// carries the gauge's reading past the set force before the arm stops).
    pub pull_s: f64,
    /// Past its target each pull goes on this much further the same way (level with the tissue), at
    /// the same speed, within the arm's reach, m: to be stopped by its set force rather than by where
    /// it was sent (a slack loop never strains a pull that stops at its target: the wound
    /// 3.9 mm open at release; sent beyond, 0.14 mm).
    pub pull_on_m: f64,
    /// Whether both pulls stop as soon as either reaches its set force (the other pulling on tore
    /// the tail out of the left's stopped jaws at 16.5 N).
    pub pulls_stop_together: bool,
    /// Where the assist retreats to.
    pub assist_retreat_m: [f64; 3],
    /// Every move is slowed until no joint needs more than this fraction of its rated speed.
    pub speed_fraction: f64,
    /// Before the pulls, the left draws the tail back this far along its jaws, m.
    pub draw_back_m: f64,
    /// ... while the right moves this fraction of the same way (negative: the other way, holding the
    /// coils back as the jaws draw out of them).
    pub right_follows_draw: f64,
    /// If set, the right goes here meanwhile instead (stitch frame): drawing the turn off the left's
    /// jaws by the long end while the left, whose tail is already knotted, hardly moves.
    pub right_draws_to_m: Option<[f64; 3]>,
    /// Before the draw, the right carries the long end through these points (stitch frame) while the
    /// left holds the tail still. Meant for a second throw: round ahead of the jaws, so that the long
    /// end leaves the turn opposite to where the tail is drawn, as a surgeon's hands cross (taken
    /// over the top, the needle leg dragged the turn forward onto the grip, and the draw took it
    /// off the tips without the tail).
    pub right_before_draw_m: Vec<[f64; 3]>,
    /// How long the draw takes, s.
    pub draw_s: f64,
    /// While drawing back, the jaws turn this fraction of the way towards the shaft.
    pub draw_relax: f64,
    /// The pulls' set force, N (as the gauges read it, through their low-pass). With the gauges
    /// unfiltered the pulls stopped at one-step contact spikes (0.6 N read in a pull holding 0.1 N);
    /// filtered, a pull held at 0.6 N, and even at 0.3 N, snaps the knot tight enough for the thread
    /// to pass through itself in some runs (a coil lost: a trefoil at release).
    pub pull_force_n: f64,
    /// The left's set force on the tail, if not `pull_force_n`, N: the tail drawn on through the
    /// coils draws the long end's slack from the exit's leg round through the stitch.
    pub tail_pull_force_n: Option<f64>,
    /// ... held this long before the pull counts it as reached, s (0: at once).
    pub pull_force_sustain_s: f64,
    /// Whether a pull that reaches the set force stops and holds the thread there (both let go
    /// together at the end, the knot cinched between two tensions) rather than letting go at once.
    pub hold_at_force: bool,
    /// Whether that hold lasts until the jaws have opened at the end. Otherwise it ends as they start
    /// to open, and each arm goes on towards where its pull was headed while it lets go, jerking the
    /// thread (grips slipping at 5-14 N as they opened, the thread passing through itself).
    pub hold_through_release: bool,
    /// The second throw, if the expert ties one: the first throw's pulls then hold, and the second
    /// is planned from the world they leave ([`SecondThrow`]).
    pub second_throw: Option<SecondThrow>,
}

impl Default for TieGeometry {
    fn default() -> Self {
        Self {
            winding_point_m: [0.0, -0.02, 0.045],
            winding_radius_m: 0.011,
            winding_lead_rad: 1.6,
            winding_towards: [0.0, 0.0, 1.0],
            left_jaw_direction: None,
            left_fetches: Some(LeftFetch {
                along_tail: 0.6,
                jaw_direction: [0.0, 0.0, -1.0],
                approach_m: 0.012,
                stop_short_m: 0.0,
                as_one_body: false,
                looks: false,
                right_follows: 1.0,
                right_beside_m: None,
                hinge_along_tail: false,
            }),
            assist_presents: false,
            right_jaws_across_winding: 0.0,
            winding_behind_m: 0.003,
            winding_pitch_m: 0.0,
            winding_s: 8.0,
            winding_turns: 2.0,
            winding_jaw_rad: 0.0,
            winding_give_force_n: None,
            winding_give_rate_m_per_n_s: 0.05,
            winding_give_after_s: 1.0,
            tail_ahead_m: 0.012,
            tail_take_short_m: 0.0,
            tail_end_offered_m: None,
            tail_beyond_m: 0.008,
            tail_tension_m: 0.003,
            take_tail_jaw_rad: 0.8,
            loosen_m: 0.004,
            coils_back_m: 0.0,
            tail_swing_lean: [0.8, 0.0, 0.0],
            tail_via_m: Vec::new(),
            assist_jaw_direction: None,
            tail_give_fraction: 0.0,
            tail_brought_to_m: None,
            left_run_down_to_m: [0.0, 0.04, 0.05],
            right_run_down_to_m: [0.0, -0.012, 0.012],
            left_run_down_via_m: Vec::new(),
            right_run_down_via_m: Vec::new(),
            run_down_s: 2.5,
            run_down_force_n: None,
            left_pull_to_m: [0.0, 0.06, 0.01],
            right_pull_to_m: [0.0, -0.05, 0.005],
            pull_s: 2.5,
            pull_on_m: 0.0,
            pulls_stop_together: false,
            assist_retreat_m: [0.04, 0.04, 0.04],
            speed_fraction: 0.3,
            draw_back_m: 0.032,
            right_follows_draw: 0.0,
            right_draws_to_m: None,
            right_before_draw_m: Vec::new(),
            draw_s: 1.2,
            draw_relax: 0.4,
            pull_force_n: 0.3,
            tail_pull_force_n: None,
            pull_force_sustain_s: 0.0,
            hold_at_force: true,
            hold_through_release: false,
            second_throw: None,
        }
    }
}

impl TieGeometry {
    /// How the left fetches the tail, if it does (not where the assist presents it).
    pub fn fetch(&self) -> Option<&LeftFetch> {
        self.left_fetches.as_ref().filter(|_| !self.assist_presents)
    }
}

/// How the left goes to the tail with the coils on its jaws.
#[derive(Clone, Debug, PartialEq, serde::Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct LeftFetch {
    /// Where on the tail the left closes: this fraction of the way from the entry point to the
    /// assist's jaws, or less, as far as the long end reaches with the turns round the left's jaws
    /// ([`super::turn_thread`]).
    pub along_tail: f64,
    /// Where the left's jaws point to take it (stitch frame).
    pub jaw_direction: [f64; 3],
    /// The last stretch onto the tail, along the jaws, m.
    pub approach_m: f64,
    /// The jaws' centre stops this far short of the tail, m.
    pub stop_short_m: f64,
    /// The left's whole tip frame turns on the way (its hinge along the tail) and the right turns
    /// with the jaws' direction about their centre, as one body, so that coils wound tight round the
    /// jaws keep their shape; the left then keeps a whole frame as it draws the tail back (false: the
    /// left only points its jaws, the solver choosing their roll, and the right follows their shift).
    #[serde(default)]
    pub as_one_body: bool,
    /// The left looks where the tail lies before it closes on it, as a surgeon does: the first
    /// throw's plan stops with the left's jaws over the tail, and the rest is planned from the world
    /// then ([`super::plan_tail_take`]), the jaws closing on the tail's point nearest their line, not on
    /// the straight line from the entry point to the assist's jaws (a slack tail sags off it: 3-8 mm
    /// on the rope). The second throw's fetch looks too where the left takes the tail
    /// from the assist ([`super::plan_second_tail_take`]).
    #[serde(default)]
    pub looks: bool,
    /// Without `as_one_body`, the right follows this fraction of the left's shift (1: all of it, the
    /// coils carried as they are; 0: it stays, and the long end runs out through the coils as the
    /// left goes). Carried all the way to a tail the assist holds up, the right brought the needle's
    /// end of the long end beside the tail.
    #[serde(default = "all_the_way")]
    pub right_follows: f64,
    /// Without `as_one_body`, if set: the right goes to this offset from the left's jaw centre
    /// (stitch frame, m) as the left fetches, instead of following a share of its shift, and keeps it
    /// as the left comes onto the tail. The turn round the left's jaws needs the long end's thread
    /// from the knot round the jaws to the needle ([`super::turn_thread`]): left where it wound, the
    /// right stood too far from jaws taken 65-85 mm away to the tail and the turn came off their tips
    /// on the way; carried with their shift it went past them towards the tail.
    #[serde(default)]
    pub right_beside_m: Option<[f64; 3]>,
    /// The left takes the tail square to it: without `as_one_body` it still turns its whole tip
    /// frame, its hinge along the tail (so that the tail runs between the open jaws), the right
    /// following its shift; looking, it turns the hinge along the tail where it lies and, if that
    /// is off the jaws' line, goes over it before it comes onto it along the jaws (false: the left
    /// points its jaws, the solver choosing their roll: the jaws may come onto the tail flat).
    #[serde(default)]
    pub hinge_along_tail: bool,
}

fn all_the_way() -> f64 {
    1.0
}

impl LeftFetch {
    /// Whether the left holds a whole tip frame from the fetch on (as one body, or its hinge along
    /// the tail), rather than pointing its jaws with the roll left to the solver.
    pub fn holds_frame(&self) -> bool {
        self.as_one_body || self.hinge_along_tail
    }
}

//! The phases a throw of the instrument tie is made of, each planning one part of it on the three
//! instruments' tracks. [`super::plan`] strings them together, stage by stage:
//!
//! - [`second_start`]: how a second throw begins (who holds the tail, who takes it);
//! - [`hand_over`]: the tail handed to the assist before a second throw wound on its jaws;
//! - [`approach`] (L1): the left to the winding point, the right to where the winding starts;
//! - [`wind`] (R2): the long end wound round the left's jaws, loosened, the tail given;
//! - [`fetch`]: the left carries its coils to the tail and closes on it;
//! - [`present`]: the assist presents the tail ahead of the left's jaws, which take it;
//! - [`take_as_it_lies`]: the left, over the tail, closes on it where it lies now;
//! - [`assist_lets_go`] (A1), [`draw`] (L5, R3), [`run_down`] (L6, R4) and [`pull`] (R5): the
//!   rest of a throw once the left holds the tail.
//!
//! [`take_tail`] is how an instrument takes the tail at a point, which more than one phase does.

pub(crate) mod approach;
pub(crate) mod assist_lets_go;
pub(crate) mod draw;
pub(crate) mod fetch;
pub(crate) mod hand_over;
pub(crate) mod present;
pub(crate) mod pull;
pub(crate) mod run_down;
pub(crate) mod second_start;
pub(crate) mod take_as_it_lies;
pub(crate) mod take_tail;
pub(crate) mod wind;

use knotlab_hw::rig::ArmName;
use knotlab_hw::skill::Skill;
use knotlab_sim::world::{JAW_CENTRE_OFFSET_M, SimWorld, trocar_of};
use nalgebra::{Isometry3, Point3, Vector3};

use super::geometry::TieGeometry;
use super::motion::{Follow, TrackBuilder, Tremor};
use super::variation::Variation;

/// The assist's last stretch onto the tail it takes, along its jaws, m.
pub(crate) const TAKE_APPROACH_M: f64 = 0.012;

/// What every phase plans from: the world as it stands, the tie's geometry and the performance's
/// variation; places given in the stitch (tissue) frame are turned into the world's here.
pub(crate) struct Setting<'a> {
    pub world: &'a SimWorld,
    pub geometry: &'a TieGeometry,
    pub variation: &'a Variation,
    pub world_from_stitch: Isometry3<f64>,
}

impl<'a> Setting<'a> {
    pub fn new(world: &'a SimWorld, geometry: &'a TieGeometry, variation: &'a Variation) -> Self {
        Self { world, geometry, variation, world_from_stitch: world.tissue().world_from_tissue }
    }

    /// A point given in the stitch frame, in the world's (m).
    pub fn at(&self, p: [f64; 3]) -> Vector3<f64> {
        (self.world_from_stitch * Point3::from(Vector3::from(p))).coords
    }

    /// A direction given in the stitch frame, in the world's.
    pub fn dir(&self, d: [f64; 3]) -> Vector3<f64> {
        self.world_from_stitch.rotation * Vector3::from(d)
    }

    /// A nominal duration as this performance takes it, s.
    pub fn d(&self, s: f64) -> f64 {
        s * self.variation.slowness
    }

    /// The performance's pause number `i` between primitives, s.
    pub fn pause(&self, i: usize) -> f64 {
        self.variation.pauses_s[i]
    }

    /// Where the thread passes through `flap`'s surface, as the tissue lies now (world frame, m):
    /// the entry point in flap A (the tail's), the exit in flap B (the long end's).
    pub fn hole_m(&self, flap: knotlab_sim::tissue::Flap) -> Vector3<f64> {
        self.world.tissue().hole_m(self.world.physics(), flap)
    }

    /// The tissue's normal, out of it (world frame).
    pub fn up(&self) -> Vector3<f64> {
        self.world_from_stitch.rotation * Vector3::z()
    }

    /// The jaws' opening when they let go, rad.
    pub fn open(&self) -> f64 {
        SimWorld::JAW_OPEN_RAD
    }

    /// The trocar an arm's shaft passes through (world frame, m).
    pub fn trocar_m(&self, arm: ArmName) -> Vector3<f64> {
        trocar_of(self.world.config(), arm)
    }

    /// A track for `arm` from where its jaws are now, with them at `jaw_rad`, its moves checked
    /// against the arm's reach.
    fn track(&self, arm: ArmName, jaw_rad: f64, tremor: &Tremor) -> TrackBuilder {
        let trocar_m = self.trocar_m(arm);
        let jaw_centre_m =
            (self.world.world_from_tip(arm) * Point3::new(0.0, 0.0, -JAW_CENTRE_OFFSET_M)).coords;
        let mut b = TrackBuilder::new(arm, jaw_centre_m, jaw_rad, KEY_PERIOD_S, tremor.clone(), trocar_m);
        b.follow(Follow {
            model: self.world.rig().arm(arm).model,
            trocar_m,
            joints: self.world.arm(arm).command,
            speed_fraction: self.geometry.speed_fraction,
        });
        b
    }
}

/// The time between a track's keys, s.
const KEY_PERIOD_S: f64 = 0.01;

/// The three instruments' tracks, by their parts in the throw: `left` winds nothing and takes the
/// tail, `right` winds the long end, `assist` holds and presents the tail. Where the left and the
/// assist swap parts ([`second_start::SecondStart::LeftRetakes`]) the fields swap with them.
pub(crate) struct Hands {
    pub left: TrackBuilder,
    pub right: TrackBuilder,
    pub assist: TrackBuilder,
}

impl Hands {
    /// The tracks from where the instruments stand, their jaws at `jaws_rad` (left, right, assist);
    /// `as_they_stand`: each goes on holding its jaws as they point now (a plan that follows another).
    pub fn start(setting: &Setting, jaws_rad: [f64; 3], as_they_stand: bool) -> Self {
        let tremor = &setting.variation.tremor;
        let mut hands = Self {
            left: setting.track(ArmName::Left, jaws_rad[0], &tremor[0]),
            right: setting.track(ArmName::Right, jaws_rad[1], &tremor[1]),
            assist: setting.track(ArmName::Assist, jaws_rad[2], &tremor[2]),
        };
        if as_they_stand {
            for track in hands.all() {
                track.hold_as_it_stands();
            }
        }
        hands
    }

    /// The three tracks, left, right, assist.
    pub fn all(&mut self) -> [&mut TrackBuilder; 3] {
        [&mut self.left, &mut self.right, &mut self.assist]
    }

    /// When the last of the three tracks ends, s.
    pub fn latest_s(&self) -> f64 {
        self.left.time_s().max(self.right.time_s()).max(self.assist.time_s())
    }

    /// Every track waits until `time_s`.
    pub fn wait_until(&mut self, time_s: f64) {
        for track in self.all() {
            track.wait_until(time_s);
        }
    }

    /// The plan so far as a skill.
    pub fn skill(self, name: &str) -> Skill {
        Skill { name: name.into(), tracks: vec![self.left.build(), self.right.build(), self.assist.build()] }
    }
}

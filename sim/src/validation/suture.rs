//! The suture under test: the rope a scene's `[thread]` makes, at the scene's resolution.

use crate::rope::RopeParams;
use crate::rope::suture::{SPACING_RADII, rope_params};
use crate::thread::ThreadParams;

/// Gravity, m/s².
pub const G_MPS2: f64 = 9.81;

/// A scene's suture as the validation's experiments build it.
#[derive(Clone, Debug, PartialEq)]
pub struct SutureUnderTest {
    /// The rope's material and integration, as the scene's rope has them.
    pub params: RopeParams,
    /// The particles' spacing, m (the scene's `rope_spacing_radii` times its radius).
    pub spacing_m: f64,
    /// The suture's weight per metre, N/m (the scene's thread mass over its length, times g).
    pub weight_per_m_n: f64,
    /// The suture's friction on metal (the scene's `thread.friction`).
    pub friction_on_metal: f64,
    /// The jaws' grip on the suture, N (the scene's `sensor.grip_force_n`).
    pub grip_force_n: f64,
    /// The scene's step, s.
    pub dt_s: f64,
}

/// Why a scene's suture cannot be validated.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum NotValidated {
    /// The suite builds its experiments with the rope; the scene simulates the capsule chain.
    #[error(
        "thread.model: the suite builds its experiments with the rope (\"rope\"), not the capsule chain \
         this scene simulates (try scenarios/default.toml)"
    )]
    NotTheRope,
}

impl SutureUnderTest {
    /// The suture of `scene`, if it is the rope the suite validates.
    pub fn from_scene(scene: &crate::scene::SceneConfig) -> Result<Self, NotValidated> {
        match scene.thread.model {
            crate::thread::ThreadModel::Rope => {
                Ok(Self::from_thread(&scene.thread, scene.sensor.grip_force_n, scene.solver.dt_s))
            }
            crate::thread::ThreadModel::Chain => Err(NotValidated::NotTheRope),
        }
    }

    /// The suture of a scene's `thread`, gripped by jaws at `grip_force_n`, stepped at `dt_s`.
    pub fn from_thread(thread: &ThreadParams, grip_force_n: f64, dt_s: f64) -> Self {
        Self {
            params: rope_params(thread),
            spacing_m: thread.rope_spacing_radii.unwrap_or(SPACING_RADII) * thread.radius_m,
            weight_per_m_n: thread.mass_kg / thread.length_m * G_MPS2,
            friction_on_metal: thread.friction,
            grip_force_n,
            dt_s,
        }
    }

    /// The bending stiffness EI, N m².
    pub fn bending_stiffness_n_m2(&self) -> f64 {
        self.params.bending_stiffness_n_m2
    }

    /// The suture's diameter in its knots, m (its collision radius twice).
    pub fn diameter_m(&self) -> f64 {
        2.0 * self.params.radius_m
    }

    /// The suture's diameter where the instruments and the needle push it, m.
    pub fn diameter_at_metal_m(&self) -> f64 {
        2.0 * self.params.radius_at_metal_m()
    }

    /// The length over which the suture holds its own shape against gravity, (EI / w)^(1/3), m.
    pub fn gravity_bending_length_m(&self) -> f64 {
        (self.bending_stiffness_n_m2() / self.weight_per_m_n).cbrt()
    }

    /// A whole number of segments near the spacing for a strand `length_m` long (at least `least`).
    pub fn segments_for(&self, length_m: f64, least: usize) -> usize {
        ((length_m / self.spacing_m).round() as usize).max(least)
    }
}

/// The suture of the nominal scene (`scenarios/default.toml`), for the experiments' tests.
#[cfg(test)]
pub(crate) fn nominal() -> SutureUnderTest {
    let scene = crate::scene::parse_scene(include_str!("../../../scenarios/default.toml"), "default.toml")
        .expect("the shipped scene");
    SutureUnderTest::from_thread(&scene.thread, scene.sensor.grip_force_n, scene.solver.dt_s)
}

/// The nominal suture with its friction on itself set to `mu` (static; kinetic 0.8 of it, as the
/// scene has them), for the experiments' tests.
#[cfg(test)]
pub(crate) fn nominal_at_friction(mu: f64) -> SutureUnderTest {
    let mut suture = nominal();
    suture.params.static_friction = mu;
    suture.params.kinetic_friction = 0.8 * mu;
    suture
}

/// The suture of the 3-0 polypropylene scene (`scenarios/polypropylene-3-0.toml`), for the
/// experiments' tests.
#[cfg(test)]
pub(crate) fn polypropylene() -> SutureUnderTest {
    let scene = crate::scene::parse_scene(
        include_str!("../../../scenarios/polypropylene-3-0.toml"),
        "polypropylene-3-0.toml",
    )
    .expect("the shipped scene");
    SutureUnderTest::from_thread(&scene.thread, scene.sensor.grip_force_n, scene.solver.dt_s)
}

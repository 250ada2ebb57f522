//! How a human performance varies from run to run: speed, pauses, tremor, where the winding goes.

use nalgebra::Vector3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::motion::Tremor;

/// How a human performance varies from run to run.
#[derive(Clone, Debug, PartialEq)]
pub struct Variation {
    /// Every duration is multiplied by this.
    pub slowness: f64,
    /// The pauses between primitives, s.
    pub pauses_s: [f64; 6],
    /// Tremor of each instrument (left, right, assist).
    pub tremor: [Tremor; 3],
    /// Where the expert puts the winding point, off the nominal one, m.
    pub winding_offset_m: Vector3<f64>,
}

impl Variation {
    /// A machine-like performance: nominal speed, 0.25 s pauses, no tremor.
    pub fn none() -> Self {
        Self {
            slowness: 1.0,
            pauses_s: [0.25; 6],
            tremor: [Tremor::none(), Tremor::none(), Tremor::none()],
            winding_offset_m: Vector3::zeros(),
        }
    }

    /// A human one drawn from `seed`: speed within +-15 %, pauses of 0.15-0.4 s, a 0.1 mm tremor,
    /// the winding point within 1 mm.
    pub fn human(seed: u64) -> Self {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let slowness = rng.random_range(0.85..1.15);
        let pauses_s = std::array::from_fn(|_| rng.random_range(0.15..0.4));
        let mut tremor = || Tremor {
            amplitude_m: 1e-4,
            sines: std::array::from_fn(|_| {
                std::array::from_fn(|_| {
                    (rng.random_range(8.0..12.0), rng.random_range(0.0..std::f64::consts::TAU))
                })
            }),
        };
        let tremor = [tremor(), tremor(), tremor()];
        let winding_offset_m = Vector3::from_fn(|_, _| rng.random_range(-0.001..0.001));
        Self { slowness, pauses_s, tremor, winding_offset_m }
    }
}

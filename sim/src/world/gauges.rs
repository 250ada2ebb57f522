//! The instruments' strain gauges: the force on each instrument from its contacts and what its
//! jaws hold, through the gauges' filter, with their noise.

use nalgebra::Vector3;
use rand_distr::{Distribution, Normal};

use super::SimWorld;
use crate::convert::to_na;

impl SimWorld {
    /// Reads each instrument's gauge after a step.
    pub(super) fn read_forces(&mut self) {
        let dt = self.config.solver.dt_s;
        for a in 0..self.arms.len() {
            let mut total = Vector3::zeros();
            for h in &self.arms[a].instrument_bodies {
                for &c in self.physics.bodies[*h].colliders() {
                    for pair in self.physics.narrow_phase.contact_pairs_with(c) {
                        let impulse = pair.total_impulse();
                        // The impulse pushes collider 1 away from collider 2 along the normal.
                        let sign = if pair.collider1 == c { -1.0 } else { 1.0 };
                        total += to_na(impulse) * (sign / dt);
                    }
                }
            }
            let arm = &self.arms[a];
            self.suture.add_pull(&mut total, arm.hold(), &arm.instrument_bodies, &self.physics, dt);
            let arm = &mut self.arms[a];
            arm.filtered_force_n =
                crate::gauge::low_pass(&arm.filtered_force_n, &total, dt, self.config.sensor.force_filter_s);
            let mut total = arm.filtered_force_n;
            if let Ok(noise) = Normal::new(0.0, self.config.sensor.force_noise_n) {
                for k in 0..3 {
                    total[k] += noise.sample(&mut self.noise);
                }
            }
            self.arms[a].force_n = total;
        }
    }
}

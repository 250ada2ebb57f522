//! Inextensibility: a 50 mm length of the suture, one end held, the other pulled along it with 2 N
//! until it rests; its strain against the model's own (the pull over its axial stiffness EA; none
//! for an inextensible rope), within 0.1 % of the length.

use nalgebra::Vector3;

use super::{Check, SutureUnderTest, Tolerance};
use crate::rope::Ropes;

/// The pull, N.
pub const PULL_N: f64 = 2.0;
/// The length pulled, m.
const LENGTH_M: f64 = 0.05;

/// The strain under [`PULL_N`] after 1 s.
pub fn strain_under_pull(suture: &SutureUnderTest) -> f64 {
    let mut ropes = Ropes::new(suture.params);
    let segments = suture.segments_for(LENGTH_M, 4);
    let points: Vec<Vector3<f64>> =
        (0..=segments).map(|k| Vector3::x() * (LENGTH_M * k as f64 / segments as f64)).collect();
    let strand = ropes.add_strand(&points);
    ropes.w[strand.start] = 0.0;
    ropes.force_n[strand.end - 1] = Vector3::x() * PULL_N;
    for _ in 0..(1.0 / suture.dt_s).round() as usize {
        ropes.step(suture.dt_s);
    }
    let line = ropes.polyline(0);
    line.windows(2).map(|p| (p[1] - p[0]).norm()).sum::<f64>() / LENGTH_M - 1.0
}

/// The strain under 2 N against the pull over EA.
pub fn checks(suture: &SutureUnderTest) -> Vec<Check> {
    let ea = suture.params.axial_stiffness_n;
    let reference = if ea.is_finite() { PULL_N / ea } else { 0.0 };
    vec![Check::new(
        "stretch",
        format!("strain under {PULL_N} N"),
        "1",
        strain_under_pull(suture),
        reference,
        Tolerance::Absolute { by: 1e-3 },
        "inextensible rod, or F/EA for the model's EA",
    )]
}

//! The strain gauges' signal path: a first-order low-pass on the physical force, as the bandwidth of a
//! real gauge amplifier gives. The solver's contact impulses, computed every step, would otherwise
//! reach the controller as one-step spikes and fire its force events.

use nalgebra::Vector3;

/// One step of the low-pass: the filtered force after `dt_s` with `raw_n` held over the step (exact
/// for a piecewise-constant input); a time constant of zero passes `raw_n` through.
pub fn low_pass(
    filtered_n: &Vector3<f64>,
    raw_n: &Vector3<f64>,
    dt_s: f64,
    time_constant_s: f64,
) -> Vector3<f64> {
    let keep = if time_constant_s > 0.0 { (-dt_s / time_constant_s).exp() } else { 0.0 };
    filtered_n * keep + raw_n * (1.0 - keep)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The gauge filter reaches 1 - 1/e of a held force in one time constant, reads a one-step 10 N spike
    /// under 0.5 N, and passes the raw force with no time constant.
    #[test]
    fn a_held_force_rises_with_the_time_constant_and_a_one_step_spike_is_damped() {
        let (dt, tau) = (0.001, 0.02);
        let one = Vector3::new(0.0, 1.0, 0.0);
        let mut f = Vector3::zeros();
        for _ in 0..20 {
            f = low_pass(&f, &one, dt, tau);
        }
        assert!((f.y - (1.0 - (-1.0f64).exp())).abs() < 1e-12, "after one time constant: {}", f.y);
        // A 10 N spike lasting one step reads under 0.5 N.
        let spike = low_pass(&Vector3::zeros(), &(one * 10.0), dt, tau);
        assert!(spike.y < 0.5 && spike.y > 0.0, "{}", spike.y);
        // No filter: the raw force.
        assert_eq!(low_pass(&Vector3::zeros(), &one, dt, 0.0), one);
    }
}

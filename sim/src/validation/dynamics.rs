//! The suture's motion in time: a clamped length bent by a small tip load and let go rings at the
//! first bending mode of a cantilever, f₁ = 1.8751² / 2π · sqrt(EI / (m L⁴)), m the mass per metre
//! the solver moves. Checked twice: at the rope's own inertial mass (the solver's dynamics, within
//! 5 %), and that mass against the suture's real one (its weight's): an inertial mass k times the
//! real one slows every elastic motion of the thread by sqrt(k). A quasi-static task is blind to
//! that only while the slowed motions stay well inside the instruments' (about a second), so the
//! inertia must be within a factor of 2 in time of the real suture's (the slowed period of a
//! 100 mm free end of 3-0 polypropylene, 0.15 s real, under 0.3 s).

use nalgebra::Vector3;

use super::cantilever::{Load, clamp_point, clamped, rest_under};
use super::suture::G_MPS2;
use super::{Check, SutureUnderTest, Tolerance};
use crate::rope::RopeParams;

/// The first clamped-free mode's eigenvalue, β₁ L.
const BETA_1: f64 = 1.875_104_068_711_961;

/// The tip load that bends the length before it is let go (alpha = P L² / EI): small enough for
/// the linear beam, large enough to read the tip.
const ALPHA: f64 = 0.05;

/// The longest the let-go length is watched, s of simulated time (a nearly limp rope's mode is
/// minutes long).
pub const MAX_RING_S: f64 = 600.0;

const MODE_SOURCE: &str = "first cantilever mode, 1.8751^2/(2 pi) sqrt(EI/(m L^4)) (suture-mechanics.md 3.1)";
const INERTIA_SOURCE: &str =
    "quasi-static within a factor 2 in time of the suture's real mass (its weight / g)";

/// The first mode's frequency in closed form, Hz, for a length `length_m` of stiffness `ei_n_m2`
/// and `mass_per_m_kg`.
pub fn first_mode_hz(ei_n_m2: f64, mass_per_m_kg: f64, length_m: f64) -> f64 {
    BETA_1 * BETA_1 / (2.0 * std::f64::consts::PI) * (ei_n_m2 / (mass_per_m_kg * length_m.powi(4))).sqrt()
}

/// How a clamped length of the suture rang: its measured first-mode frequency and the closed
/// form's at the rope's inertial mass.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ringing {
    /// Measured from the tip's crossings of the clamp's level, Hz.
    pub measured_hz: f64,
    /// The closed form at the rope's inertial mass, Hz.
    pub closed_form_hz: f64,
    /// The free length, m.
    pub length_m: f64,
}

/// Bends a clamped length of `suture`'s rope to rest under a small tip load, lets it go with no
/// damping and gravity, and times the tip's swings through the clamp's level over two periods
/// (`None`: it has no stiffness, its closed-form mode is too slow to swing three times within
/// [`MAX_RING_S`], or it did not swing through twice within 20 closed-form periods or [`MAX_RING_S`]).
pub fn ring(suture: &SutureUnderTest) -> Option<Ringing> {
    let (mut ropes, clamp, tip, length_m) = clamped(suture, suture.params);
    let ei = suture.bending_stiffness_n_m2();
    let closed_form_hz = first_mode_hz(ei, suture.params.mass_per_m_kg, length_m);
    // A string (no stiffness) has no mode to ring at, and a mode whose three swings (the fewest
    // that time two periods) would outlast MAX_RING_S cannot be timed.
    if !(closed_form_hz > 0.0 && closed_form_hz.is_finite() && 3.0 / closed_form_hz <= MAX_RING_S) {
        return None;
    }
    rest_under(suture, &mut ropes, clamp, tip, length_m, Load::Tip(ALPHA));
    ropes.params = RopeParams { damping_per_s: 0.0, ..ropes.params };
    ropes.force_n.iter_mut().for_each(|f| *f = Vector3::zeros());
    let level = clamp_point(&ropes, clamp).z;
    // Steps of at most a hundredth of a period, for 20 periods or MAX_RING_S, whichever is shorter.
    let dt_s = suture.dt_s.min(0.01 / closed_form_hz);
    let steps = (20.0 / closed_form_hz).min(MAX_RING_S) / dt_s;
    let steps = steps.ceil() as usize;
    let mut upward = Vec::new();
    let mut below = ropes.x[tip].z - level;
    for k in 1..=steps {
        ropes.step(dt_s);
        let now = ropes.x[tip].z - level;
        if below < 0.0 && now >= 0.0 {
            // Where between the two steps the tip crossed, on a straight line.
            upward.push(dt_s * (k as f64 - now / (now - below)));
            if upward.len() == 3 {
                let measured_hz = 2.0 / (upward[2] - upward[0]);
                return Some(Ringing { measured_hz, closed_form_hz, length_m });
            }
        }
        below = now;
    }
    None
}

/// The first mode against the closed form at the rope's inertial mass, and that mass's time scale
/// against the suture's real mass.
pub fn checks(suture: &SutureUnderTest) -> Vec<Check> {
    let ringing = ring(suture);
    let (measured, closed_form, length_m) =
        ringing.map_or((f64::NAN, f64::NAN, f64::NAN), |r| (r.measured_hz, r.closed_form_hz, r.length_m));
    let real_per_m_kg = suture.weight_per_m_n / G_MPS2;
    // Periods scale as the square root of the mass.
    let slowed = (suture.params.mass_per_m_kg / real_per_m_kg).sqrt();
    vec![
        Check::new(
            "dynamics",
            format!("first mode of a {:.1} mm cantilever at the rope's inertial mass", length_m * 1e3),
            "Hz",
            measured,
            closed_form,
            Tolerance::Relative { fraction: 0.05 },
            MODE_SOURCE,
        ),
        Check::new(
            "dynamics",
            format!(
                "elastic motions slowed by the inertial mass ({} kg/m against the real {} kg/m)",
                super::figure_text(suture.params.mass_per_m_kg),
                super::figure_text(real_per_m_kg)
            ),
            "1",
            slowed,
            1.0,
            Tolerance::Range { low: 0.5, high: 2.0 },
            INERTIA_SOURCE,
        ),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::validation::suture::nominal;

    /// Guards the solver's dynamics: the nominal rope's clamped length rings at the closed-form
    /// first mode within 5 %, and at a quarter of the inertial mass twice as fast.
    #[test]
    fn a_clamped_length_rings_at_the_first_mode() {
        let suture = nominal();
        let heavy = ring(&suture).expect("it rings");
        let ratio = heavy.measured_hz / heavy.closed_form_hz;
        assert!(
            (ratio - 1.0).abs() < 0.05,
            "{:.4} Hz against {:.4} Hz",
            heavy.measured_hz,
            heavy.closed_form_hz
        );
        let mut light = suture.clone();
        light.params.mass_per_m_kg *= 0.25;
        let light = ring(&light).expect("it rings");
        let faster = light.measured_hz / heavy.measured_hz;
        assert!((faster - 2.0).abs() < 0.1, "a quarter of the mass rings {faster:.3} times as fast");
    }

    /// Guards against a rope with no mode to time: a string (EI 0) and a nearly limp rope (a mode
    /// hours long, past [`MAX_RING_S`]) give no ringing at once, and their checks fail instead of
    /// running on.
    #[test]
    fn a_limp_rope_gives_no_mode_and_fails() {
        let mut string = nominal();
        string.params.bending_stiffness_n_m2 = 0.0;
        assert_eq!(ring(&string), None);
        assert_eq!(checks(&string)[0].passed, Some(false));
        let mut limp = nominal();
        limp.params.bending_stiffness_n_m2 = 1e-16;
        assert_eq!(ring(&limp), None);
        assert_eq!(checks(&limp)[0].passed, Some(false));
    }

    /// Guards the inertia check: the nominal rope (0.15 kg/m against its weight's 0.05 kg/m) is
    /// slowed 1.7 times and passes; at the rope's default 0.67 kg/m it is slowed 3.7 times and fails;
    /// at its weight's mass it is not slowed.
    #[test]
    fn an_inertial_mass_far_above_the_weights_fails() {
        let mut suture = nominal();
        let slowed = |s: &SutureUnderTest| checks(s)[1].clone();
        let check = slowed(&suture);
        assert!((check.measured - 1.73).abs() < 0.01 && check.passed == Some(true), "{check:?}");
        suture.params.mass_per_m_kg = 0.67;
        let check = slowed(&suture);
        assert!((check.measured - 3.66).abs() < 0.01 && check.passed == Some(false), "{check:?}");
        suture.params.mass_per_m_kg = suture.weight_per_m_n / G_MPS2;
        let check = slowed(&suture);
        assert!((check.measured - 1.0).abs() < 1e-9 && check.passed == Some(true), "{check:?}");
    }
}

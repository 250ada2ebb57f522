//! Motion profiles for whoever generates skills: the minimum-jerk blend (Flash and Hogan's profile of a
//! reaching hand), used by the scripted expert, the simulator's stress sequence and the tests.

/// Minimum-jerk progress from 0 to 1 as `s` goes from 0 to 1 (clamped outside): at rest at both ends,
/// with zero acceleration there too.
pub fn min_jerk(s: f64) -> f64 {
    let s = s.clamp(0.0, 1.0);
    s * s * s * (10.0 - 15.0 * s + 6.0 * s * s)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The minimum-jerk profile runs from 0 to 1, clamps outside, is symmetric about its middle, and starts
    /// and ends with no speed.
    #[test]
    fn min_jerk_starts_and_ends_at_rest_and_is_symmetric() {
        assert_eq!(min_jerk(0.0), 0.0);
        assert_eq!(min_jerk(1.0), 1.0);
        assert_eq!(min_jerk(-1.0), 0.0);
        assert_eq!(min_jerk(2.0), 1.0);
        assert!((min_jerk(0.5) - 0.5).abs() < 1e-12);
        assert!((min_jerk(0.3) + min_jerk(0.7) - 1.0).abs() < 1e-12);
        let h = 1e-6;
        assert!(min_jerk(h) / h < 1e-6, "no speed at the start");
        assert!((1.0 - min_jerk(1.0 - h)) / h < 1e-6, "no speed at the end");
    }
}

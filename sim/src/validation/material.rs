//! The suture's size, stiffness and weight against a real 3-0 suture's: the European
//! Pharmacopoeia's diameter for USP 3-0 (metric 2), and the solid-rod bending stiffness, weight per
//! metre and gravity bending length of 3-0 polypropylene, nylon and polyester from their moduli and
//! densities (`../shared/reference/suture-mechanics.md`, §4).

use super::suture::G_MPS2;
use super::{Check, SutureUnderTest, Tolerance};

const DIAMETER_SOURCE: &str = "EP metric 2 (USP 3-0): 0.200-0.249 mm";
const SOLID_ROD_SOURCE: &str =
    "3-0 PP/nylon/PET solid rod, E 1.5-5 GPa, rho 905-1380 kg/m3 (suture-mechanics.md 4.3)";

/// The size, stiffness, weight and gravity bending length of a 3-0 suture, each within its range.
pub fn checks(suture: &SutureUnderTest) -> Vec<Check> {
    let weight_mg_per_m = suture.weight_per_m_n / G_MPS2 * 1e6;
    let figures = [
        ("diameter in its knots", "mm", suture.diameter_m() * 1e3, (0.200, 0.249), DIAMETER_SOURCE),
        (
            "diameter at the instruments",
            "mm",
            suture.diameter_at_metal_m() * 1e3,
            (0.200, 0.249),
            DIAMETER_SOURCE,
        ),
        ("bending stiffness EI", "N m2", suture.bending_stiffness_n_m2(), (1.2e-7, 9.4e-7), SOLID_ROD_SOURCE),
        ("weight per metre", "mg/m", weight_mg_per_m, (28.0, 67.0), SOLID_ROD_SOURCE),
        (
            "gravity bending length (EI/w)^(1/3)",
            "mm",
            suture.gravity_bending_length_m() * 1e3,
            (75.0, 120.0),
            SOLID_ROD_SOURCE,
        ),
    ];
    figures
        .into_iter()
        .map(|(figure, unit, measured, (low, high), source)| {
            Check::new(
                "material",
                figure,
                unit,
                measured,
                0.5 * (low + high),
                Tolerance::Range { low, high },
                source,
            )
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::validation::suture::nominal;

    /// Guards the ranges: a 0.22 mm polypropylene rod (EI 3.5e-7 N m², 34 mg/m) passes all five,
    /// and each figure out of its range fails on its own (the diameter in the knots and at the
    /// instruments apart).
    #[test]
    fn a_real_3_0_suture_passes_and_each_figure_out_of_range_fails() {
        let mut suture = nominal();
        suture.params.radius_m = 0.00011;
        suture.params.metal_radius_m = None;
        suture.params.bending_stiffness_n_m2 = 3.5e-7;
        suture.weight_per_m_n = 34e-6 * G_MPS2;
        let passed =
            |s: &SutureUnderTest| checks(s).iter().map(|c| c.passed == Some(true)).collect::<Vec<_>>();
        assert_eq!(passed(&suture), [true; 5]);
        let mut thick = suture.clone();
        thick.params.radius_m = 0.0004;
        thick.params.metal_radius_m = Some(0.00011);
        assert_eq!(passed(&thick), [false, true, true, true, true]);
        let mut thick_at_metal = suture.clone();
        thick_at_metal.params.metal_radius_m = Some(0.0004);
        assert_eq!(passed(&thick_at_metal), [true, false, true, true, true]);
        let mut heavy = suture.clone();
        heavy.weight_per_m_n *= 100.0;
        assert_eq!(passed(&heavy), [true, true, true, false, false]);
    }
}

//! The suture drawn through jaws that grip it by friction: one end held, the jaws closed on its
//! middle and drawn away at 20 mm/s, the suture sliding through them. While it slides the jaws pull
//! it with their grip force F and no more, and the suture between them and the held end carries F:
//! its strain is F / EA everywhere, the segment entering the jaws included (a grip's pull left on
//! its particle after the rope's solve shows there as stretch of order F h² / m per segment, the
//! substep `h` and the particle's inertial mass `m`; here it must not).

use nalgebra::Vector3;
use rapier3d::math::{Pose, Vector};
use rapier3d::prelude::*;

use super::{Check, SutureUnderTest, Tolerance};
use crate::rope::Ropes;
use crate::rope::grasp::RopeGrasp;
use crate::rope::rigid::RigidContacts;

/// The strand's length, m.
const LENGTH_M: f64 = 0.08;
/// How fast the jaws are drawn, m/s.
const SPEED_MPS: f64 = 0.02;
/// How long, s: the jaws slide along 16 mm of the 40 mm beyond them.
const DRAWN_S: f64 = 0.8;
/// From when the slide is measured, s (the rope drawn taut by then).
const SETTLED_S: f64 = 0.2;

/// What the slide showed: the jaws' mean pull over their grip force, and the mean of the largest
/// strain along the rope.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Slide {
    /// The jaws' pull on the rope, averaged over the slide, over their grip force.
    pub pull_over_grip: f64,
    /// The largest segment strain along the rope, averaged over the slide.
    pub largest_strain: f64,
}

/// One step of jaws moving along the suture: when, the jaws' pull on the rope, the mean strain of
/// the rope between the held end and the jaws (its tension over EA), and the largest strain along
/// the rope.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Drawn {
    t_s: f64,
    pull_n: f64,
    strain_to_jaws: f64,
    largest_strain: f64,
}

/// Moves jaws gripping the suture's middle with `grip_n` newtons along it, to `jaws_x_m(t)` for
/// `duration_s`, one end held; each step's record and whether the rope slid through the jaws by
/// more than two particles. `None` if the jaws found no rope.
fn draw(
    suture: &SutureUnderTest,
    grip_n: f64,
    duration_s: f64,
    jaws_x_m: impl Fn(f64) -> f64,
) -> Option<(Vec<Drawn>, bool)> {
    let mut bodies = RigidBodySet::new();
    let colliders = ColliderSet::new();
    let mut ropes = Ropes::new(suture.params);
    let segments = suture.segments_for(LENGTH_M, 8);
    let points: Vec<Vector3<f64>> =
        (0..=segments).map(|k| Vector3::x() * (LENGTH_M * (k as f64 / segments as f64 - 0.5))).collect();
    ropes.add_strand(&points);
    ropes.w[0] = 0.0;
    let jaws = bodies.insert(RigidBodyBuilder::kinematic_position_based());
    let mut contacts = RigidContacts::default();
    let across = suture.params.radius_m * 5.0;
    let line = (Vector3::new(0.0, -across, 0.0), Vector3::new(0.0, across, 0.0));
    let mut grasp =
        RopeGrasp::try_close(&ropes, &mut contacts, jaws, &Pose::IDENTITY, line, suture.spacing_m)?;
    grasp.grip(&mut contacts, grip_n);
    let rest_m = LENGTH_M / segments as f64;
    let steps = (duration_s / suture.dt_s).round() as usize;
    let mut drawn = Vec::with_capacity(steps);
    for step in 1..=steps {
        let t_s = step as f64 * suture.dt_s;
        let next = Pose::from_translation(Vector::new(jaws_x_m(t_s), 0.0, 0.0));
        bodies[jaws].set_next_kinematic_position(next);
        contacts.step(&mut ropes, suture.dt_s, &bodies, &colliders);
        bodies[jaws].set_position(next, true);
        let strains: Vec<f64> =
            ropes.polyline(0).windows(2).map(|p| (p[1] - p[0]).norm() / rest_m - 1.0).collect();
        let to_jaws = &strains[..grasp.particles.start.clamp(1, strains.len())];
        drawn.push(Drawn {
            t_s,
            pull_n: grasp.force_n(&contacts, suture.dt_s).norm(),
            strain_to_jaws: to_jaws.iter().sum::<f64>() / to_jaws.len() as f64,
            largest_strain: strains.iter().copied().fold(f64::MIN, f64::max),
        });
        while let Some(true) = grasp.follow_slide(&ropes, &mut contacts, &next, suture.spacing_m) {}
    }
    Some((drawn, grasp.particles.start > segments / 2 + 2))
}

/// Draws the suture through jaws gripping with `grip_n` newtons; `None` if the jaws found no rope
/// or it never slid.
pub fn slide(suture: &SutureUnderTest, grip_n: f64) -> Option<Slide> {
    let (drawn, slid) = draw(suture, grip_n, DRAWN_S, |t_s| SPEED_MPS * t_s)?;
    let measured: Vec<&Drawn> = drawn.iter().filter(|d| d.t_s > SETTLED_S).collect();
    let counted = measured.len() as f64;
    (!measured.is_empty() && slid).then(|| Slide {
        pull_over_grip: measured.iter().map(|d| d.pull_n).sum::<f64>() / counted / grip_n,
        largest_strain: measured.iter().map(|d| d.largest_strain).sum::<f64>() / counted,
    })
}

/// The jaws' pull against their grip force, and the largest strain against F / EA (none for an
/// inextensible rope), while the suture slides through them at the scene's grip force.
pub fn checks(suture: &SutureUnderTest) -> Vec<Check> {
    let grip_n = suture.grip_force_n;
    let shown = slide(suture, grip_n);
    let ea = suture.params.axial_stiffness_n;
    let strain = if ea.is_finite() { grip_n / ea } else { 0.0 };
    vec![
        Check::new(
            "grip_slide",
            format!("pull of jaws gripping at {grip_n} N over the grip, while the suture slides"),
            "1",
            shown.map_or(f64::NAN, |s| s.pull_over_grip),
            1.0,
            Tolerance::Relative { fraction: 0.05 },
            "Coulomb friction: a sliding grip pulls with its force",
        ),
        Check::new(
            "grip_slide",
            format!("largest strain along the suture sliding through jaws at {grip_n} N"),
            "1",
            shown.map_or(f64::NAN, |s| s.largest_strain),
            strain,
            Tolerance::Absolute { by: (0.1 * strain).max(1e-3) },
            "the pull over the model's EA (0 for an inextensible rod), the segment at the jaws included",
        ),
    ]
}

#[cfg(test)]
mod tests {
    use super::super::suture::nominal;
    use super::*;

    /// Drawn through jaws at the nominal grip, the suture is pulled with the grip force and stretched
    /// by it over EA, at the jaws as elsewhere, at the scene's step and at a quarter of it.
    #[test]
    fn a_suture_sliding_through_jaws_is_pulled_at_the_grip_and_stretched_by_it_over_ea() {
        let shown: Vec<(usize, Slide, f64)> = [1, 4]
            .into_iter()
            .map(|substeps| {
                let mut suture = nominal();
                suture.params.substeps *= substeps;
                let strain = 5.0 / suture.params.axial_stiffness_n;
                (substeps, slide(&suture, 5.0).expect("it slid"), strain)
            })
            .collect();
        println!("{shown:?}");
        for (_, slide, strain) in shown {
            assert!((slide.pull_over_grip - 1.0).abs() < 0.05, "{slide:?}");
            assert!((slide.largest_strain - strain).abs() < 0.1 * strain, "{slide:?} against {strain}");
        }
    }

    /// Jaws that slide along the suture and then ease back, so that the rope sticks in them, never
    /// pull harder than their grip (in the step the slide stops, the friction of the substep it
    /// slid in counted once, not again in those after it), and once still read the rope's tension:
    /// EA times the strain between them and the held end. At the scene's step and a quarter of it.
    #[test]
    fn jaws_that_stop_sliding_pull_no_harder_than_their_grip_and_then_read_the_tension() {
        for substeps in [1, 4] {
            let mut suture = nominal();
            suture.params.substeps *= substeps;
            let ea = suture.params.axial_stiffness_n;
            // Out at 20 mm/s for 0.5 s, back 0.6 mm over 0.05 s, then still for 0.25 s.
            let (drawn, slid) = draw(&suture, 5.0, 0.8, |t_s| {
                SPEED_MPS * t_s.min(0.5) - 0.012 * (t_s - 0.5).clamp(0.0, 0.05)
            })
            .expect("the jaws found the rope");
            assert!(slid, "the rope slid through the jaws while they were drawn out");
            let most_n = drawn.iter().map(|d| d.pull_n).fold(0.0, f64::max);
            let still: Vec<&Drawn> = drawn.iter().filter(|d| d.t_s > 0.65).collect();
            let tension_n = still.iter().map(|d| ea * d.strain_to_jaws).sum::<f64>() / still.len() as f64;
            let pull_n = still.iter().map(|d| d.pull_n).sum::<f64>() / still.len() as f64;
            println!("{substeps}x: most {most_n:.3} N; still: tension {tension_n:.3} N, pull {pull_n:.3} N");
            assert!(most_n < 5.0 * 1.02, "the jaws pulled {most_n} N gripping at 5 N");
            assert!(tension_n > 0.5 && tension_n < 4.5, "eased below the grip, still taut: {tension_n} N");
            assert!(
                (pull_n - tension_n).abs() < 0.05 * tension_n,
                "pull {pull_n} N against tension {tension_n} N"
            );
        }
    }
}

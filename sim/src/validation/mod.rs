//! The suture checked against mechanics: small experiments built with a scene's suture (its rope's
//! material, resolution and substeps), each measured figure set beside its reference from a closed
//! form, a table or a measured suture, with the tolerance and the source. `knotlab validate` runs
//! them; `docs/validation.md` holds the table it prints.
//!
//! - [`suture`]: the suture under test, read from a scene's `[thread]`.
//! - [`material`]: the suture's size, stiffness and weight against a real 3-0 suture's.
//! - [`stretch`]: inextensibility under a 2 N pull.
//! - [`cantilever`]: a clamped length bent by a tip load and by a uniform load, against the elastica.
//! - [`capstan`]: the suture pulled round a fixed cylinder and over suture, against the
//!   capstan law.
//! - [`slide`]: the suture drawn straight over suture under a known load, against Coulomb's law.
//! - [`grip`]: the suture drawn through jaws gripping it by friction: their pull against the grip
//!   force, its strain at the jaws against the pull over EA.
//! - [`knot`]: an open trefoil pulled tight, against the tightening law of a loose elastic knot.
//! - [`long_knot`]: the long overhand knots 5_1 and 7_1 pulled tight, against the friction law of
//!   long knots (reported; the `long_knot_sweep` example sweeps frictions and ramps).
//! - [`creep`]: the double throw held by equal pulls on its ends, staying where it is on the rope.
//! - [`dynamics`]: a clamped length ringing at the first cantilever mode, and the rope's inertial
//!   mass against the suture's real one.
//! - [`pinch`]: the suture drawn between two parts closer than its thickness (an experiment the
//!   pinch probe prints and the tests hold, not yet a row).

pub mod cantilever;
pub mod capstan;
pub mod creep;
pub mod dynamics;
pub mod grip;
pub mod knot;
pub mod long_knot;
pub mod material;
pub mod pinch;
pub mod slide;
pub mod stretch;
pub mod suture;

use serde::Serialize;

pub use suture::SutureUnderTest;

/// How a measured figure is judged against its reference.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Tolerance {
    /// |measured - reference| <= fraction * |reference|.
    Relative {
        /// The allowed fraction.
        fraction: f64,
    },
    /// |measured - reference| <= by.
    Absolute {
        /// The allowed difference, in the figure's unit.
        by: f64,
    },
    /// low <= measured <= high (the reference is the range's middle).
    Range {
        /// Lowest allowed.
        low: f64,
        /// Highest allowed.
        high: f64,
    },
    /// Reported beside its reference, not judged (where the model may differ by right: the
    /// reference's assumptions do not hold).
    Report,
}

/// One check: what was measured, against what, and whether it passed.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Check {
    /// The experiment (`cantilever_tip_load`, say).
    pub experiment: &'static str,
    /// What was measured, with its conditions (`v/L at alpha = 1`).
    pub figure: String,
    /// The unit of `measured` and `reference` (`1` for a pure number).
    pub unit: &'static str,
    /// Measured in the simulation.
    pub measured: f64,
    /// The reference value.
    pub reference: f64,
    /// How the two are compared.
    pub tolerance: Tolerance,
    /// Whether the measured figure is within the tolerance (`None`: reported only).
    pub passed: Option<bool>,
    /// Where the reference comes from.
    pub source: &'static str,
}

impl Check {
    /// A check, judged.
    pub fn new(
        experiment: &'static str,
        figure: impl Into<String>,
        unit: &'static str,
        measured: f64,
        reference: f64,
        tolerance: Tolerance,
        source: &'static str,
    ) -> Self {
        let within = |d: f64, by: f64| measured.is_finite() && d <= by;
        let passed = match tolerance {
            Tolerance::Relative { fraction } => {
                Some(within((measured - reference).abs(), fraction * reference.abs()))
            }
            Tolerance::Absolute { by } => Some(within((measured - reference).abs(), by)),
            Tolerance::Range { low, high } => Some(measured.is_finite() && (low..=high).contains(&measured)),
            Tolerance::Report => None,
        };
        Self { experiment, figure: figure.into(), unit, measured, reference, tolerance, passed, source }
    }

    /// The tolerance as a reader writes it (`±2 %`, `0.2-0.249`, `report`).
    pub fn tolerance_text(&self) -> String {
        match self.tolerance {
            Tolerance::Relative { fraction } => format!("±{} %", fraction * 100.0),
            Tolerance::Absolute { by } => format!("±{}", figure_text(by)),
            Tolerance::Range { low, high } => format!("{}-{}", figure_text(low), figure_text(high)),
            Tolerance::Report => "report".to_owned(),
        }
    }
}

/// A figure to four significant digits: fixed between 0.001 and 100,000, else in exponent form.
pub fn figure_text(x: f64) -> String {
    if x == 0.0 || !x.is_finite() || (1e-3..1e5).contains(&x.abs()) {
        let digits =
            if x == 0.0 || !x.is_finite() { 4 } else { (3 - x.abs().log10().floor() as i32).clamp(0, 6) };
        format!("{x:.*}", digits as usize)
    } else {
        format!("{x:.3e}")
    }
}

/// One experiment of the suite: its name (as `knotlab validate --only` takes it) and what it measures.
#[derive(Clone, Copy)]
pub struct Experiment {
    name: &'static str,
    checks: fn(&SutureUnderTest) -> Vec<Check>,
}

impl Experiment {
    /// The name `knotlab validate --only` takes.
    pub fn name(&self) -> &'static str {
        self.name
    }

    /// The experiment's checks on `suture`.
    pub fn checks(&self, suture: &SutureUnderTest) -> Vec<Check> {
        (self.checks)(suture)
    }
}

/// The suite's experiments, in the order the table lists them.
pub const EXPERIMENTS: [Experiment; 10] = [
    Experiment { name: "material", checks: material::checks },
    Experiment { name: "stretch", checks: stretch::checks },
    Experiment { name: "cantilever", checks: cantilever::checks },
    Experiment { name: "capstan", checks: capstan::checks },
    Experiment { name: "slide", checks: slide::checks },
    Experiment { name: "grip", checks: grip::checks },
    Experiment { name: "knot", checks: knot::checks },
    Experiment { name: "long_knot", checks: long_knot::checks },
    Experiment { name: "creep", checks: creep::checks },
    Experiment { name: "dynamics", checks: dynamics::checks },
];

/// The experiment `knotlab validate --only` names `name`, if the suite has one.
pub fn experiment(name: &str) -> Option<Experiment> {
    EXPERIMENTS.iter().copied().find(|e| e.name == name)
}

/// The checks of `experiments` on `suture`, in the order given. Each experiment runs on its own
/// thread (they share no state: each builds its own world from `suture`), so the suite finishes
/// sooner on more cores with the same figures, bit for bit, as one after another; a panic in one is
/// resumed on the caller's thread.
pub fn run(suture: &SutureUnderTest, experiments: &[Experiment]) -> Vec<Check> {
    std::thread::scope(|scope| {
        let running: Vec<_> = experiments.iter().map(|e| scope.spawn(|| e.checks(suture))).collect();
        running
            .into_iter()
            .flat_map(|run| run.join().unwrap_or_else(|panic| std::panic::resume_unwind(panic)))
            .collect()
    })
}

/// Every check of the suite on `suture`, in the table's order.
pub fn run_all(suture: &SutureUnderTest) -> Vec<Check> {
    run(suture, &EXPERIMENTS)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Relative, range and absolute checks pass inside their tolerance and fail outside it, a NaN figure
    /// fails, and a report-only check neither passes nor fails.
    #[test]
    fn a_check_passes_within_its_tolerance_and_fails_outside_it() {
        let rel = |m| Check::new("x", "f", "1", m, 1.0, Tolerance::Relative { fraction: 0.02 }, "s").passed;
        assert_eq!((rel(1.019), rel(0.979), rel(f64::NAN)), (Some(true), Some(false), Some(false)));
        let range =
            |m| Check::new("x", "f", "m", m, 0.0, Tolerance::Range { low: 1.0, high: 2.0 }, "s").passed;
        assert_eq!((range(1.5), range(2.5)), (Some(true), Some(false)));
        let abs = |m| Check::new("x", "f", "m", m, 0.0, Tolerance::Absolute { by: 0.1 }, "s").passed;
        assert_eq!((abs(-0.05), abs(0.2)), (Some(true), Some(false)));
        assert_eq!(Check::new("x", "f", "1", 9.0, 1.0, Tolerance::Report, "s").passed, None);
    }

    /// Experiments run side by side give the checks, in the order asked, with the same bits as the
    /// same experiments run one after another on the caller's thread.
    #[test]
    fn experiments_side_by_side_give_the_figures_they_give_one_after_another() {
        let suture = suture::nominal();
        let chosen: Vec<Experiment> =
            ["stretch", "material", "slide"].iter().map(|n| experiment(n).expect("in the suite")).collect();
        let serial: Vec<Check> = chosen.iter().flat_map(|e| e.checks(&suture)).collect();
        let threaded = run(&suture, &chosen);
        let bits = |checks: &[Check]| -> Vec<(&'static str, String, u64, u64)> {
            checks
                .iter()
                .map(|c| (c.experiment, c.figure.clone(), c.measured.to_bits(), c.reference.to_bits()))
                .collect()
        };
        assert_eq!(bits(&threaded), bits(&serial));
        let experiments: Vec<&str> = threaded.iter().map(|c| c.experiment).collect();
        assert_eq!(experiments.first(), Some(&"stretch"), "{experiments:?}");
        assert!(experiments.contains(&"material") && experiments.last() == Some(&"slide_on_suture"));
        assert!(experiment("trefoil").is_none());
    }

    /// Printed figures keep four significant digits, plain or in exponent form, from 6.25e-8 to 50000 and 0.
    #[test]
    fn figures_keep_four_significant_digits() {
        let texts: Vec<String> =
            [6.25e-8, 0.08361, 0.5, 4.6714, 50000.0, 0.0].into_iter().map(figure_text).collect();
        assert_eq!(texts, ["6.250e-8", "0.08361", "0.5000", "4.671", "50000", "0.0000"]);
    }
}

//! Success against a drawn parameter (play, calibration error, the stitch's displacement, turn and
//! tilt): equal-width bins
//! over the range observed across all methods, and per method and bin the trials, the successes and the
//! 95 % Wilson interval. Plain numbers, no drawing.

use serde::Serialize;

use crate::mc::{TrialLine, wilson_interval};

use super::methods::is_success;

/// Bins per parameter.
pub const BIN_COUNT: usize = 5;

/// A drawn parameter the report plots success against.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum Parameter {
    /// The joints' backlash, `draw.play_rad`.
    Play,
    /// The largest calibration offset over the arms' joints, `draw.calibration_max_rad`.
    Calibration,
    /// The norm of the stitch's shift, `|draw.stitch_offset_m|`.
    StitchDisplacement,
    /// The stitch's turn about the tissue's normal, `draw.stitch_rotate_rad` (signed: a turn one way
    /// and the other are not the same for the instruments).
    StitchTurn,
    /// The tissue's tilt about the wound, `draw.stitch_tilt_rad` (signed).
    StitchTilt,
}

impl Parameter {
    /// Every parameter, in the report's order.
    pub const ALL: [Parameter; 5] = [
        Parameter::Play,
        Parameter::Calibration,
        Parameter::StitchDisplacement,
        Parameter::StitchTurn,
        Parameter::StitchTilt,
    ];

    /// Its name in prose.
    pub fn name(self) -> &'static str {
        match self {
            Parameter::Play => "play",
            Parameter::Calibration => "calibration error",
            Parameter::StitchDisplacement => "stitch displacement",
            Parameter::StitchTurn => "stitch turn",
            Parameter::StitchTilt => "tissue tilt",
        }
    }

    /// Where it comes from in a line's `draw`.
    pub fn field(self) -> &'static str {
        match self {
            Parameter::Play => "play_rad",
            Parameter::Calibration => "calibration_max_rad",
            Parameter::StitchDisplacement => "stitch_offset_m",
            Parameter::StitchTurn => "stitch_rotate_rad",
            Parameter::StitchTilt => "stitch_tilt_rad",
        }
    }

    /// The unit it is shown in (its SI value times [`Parameter::shown_per_si`]).
    pub fn shown_unit(self) -> &'static str {
        match self {
            Parameter::Play | Parameter::Calibration => "mrad",
            Parameter::StitchDisplacement => "mm",
            Parameter::StitchTurn | Parameter::StitchTilt => "deg",
        }
    }

    /// Shown units per SI unit (rad to mrad, m to mm, rad to degrees).
    pub fn shown_per_si(self) -> f64 {
        match self {
            Parameter::StitchTurn | Parameter::StitchTilt => 180.0 / std::f64::consts::PI,
            _ => 1e3,
        }
    }

    /// The value of a line, in SI units (rad, m); none when its draw lacks it or it is not finite.
    pub fn value_si(self, line: &TrialLine) -> Option<f64> {
        let field = line.draw.get(self.field())?;
        let value = match self {
            Parameter::Play | Parameter::Calibration | Parameter::StitchTurn | Parameter::StitchTilt => {
                field.as_f64()?
            }
            Parameter::StitchDisplacement => {
                let xyz = field.as_array()?;
                if xyz.len() != 3 {
                    return None;
                }
                let mut sum = 0.0;
                for c in xyz {
                    let c = c.as_f64()?;
                    sum += c * c;
                }
                sum.sqrt()
            }
        };
        value.is_finite().then_some(value)
    }
}

/// Success in one bin.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Bin {
    /// Its place among the bins, from 0 (empty bins are left out, so this may skip).
    pub index: usize,
    /// Its lower bound, SI.
    pub from: f64,
    /// Its upper bound, SI (the last bin includes it).
    pub to: f64,
    /// Trials in it.
    pub trials: usize,
    /// Successes among them.
    pub successes: usize,
    /// successes / trials.
    pub success_rate: f64,
    /// The 95 % Wilson interval of the rate.
    pub wilson_95: [f64; 2],
}

impl Bin {
    /// The middle of the bin, SI.
    pub fn centre(&self) -> f64 {
        0.5 * (self.from + self.to)
    }
}

/// The smallest and largest of the finite `values`; none when there are none.
pub fn observed_range(values: impl IntoIterator<Item = f64>) -> Option<(f64, f64)> {
    values.into_iter().filter(|v| v.is_finite()).fold(None, |range, v| match range {
        None => Some((v, v)),
        Some((lo, hi)) => Some((v.min(lo), v.max(hi))),
    })
}

/// Whether `lo..hi` is one value (up to round-off), so there is nothing to bin.
pub fn is_degenerate(lo: f64, hi: f64) -> bool {
    hi - lo <= 1e-12 * lo.abs().max(hi.abs())
}

/// The bin of `value` among `count` equal-width bins over `lo..=hi` (a value at `hi` is in the last;
/// values outside are clamped to the first or last).
pub fn bin_index(value: f64, lo: f64, hi: f64, count: usize) -> usize {
    let last = count.saturating_sub(1);
    if is_degenerate(lo, hi) {
        return 0;
    }
    let k = ((value - lo) / (hi - lo) * count as f64).floor();
    if k <= 0.0 { 0 } else { (k as usize).min(last) }
}

/// `outcomes` (value, success) in `count` equal-width bins over `lo..=hi`; bins with no trials are
/// left out.
pub fn bin_outcomes(outcomes: &[(f64, bool)], lo: f64, hi: f64, count: usize) -> Vec<Bin> {
    let count = count.max(1);
    let mut tally = vec![(0usize, 0usize); count];
    for &(value, success) in outcomes {
        let t = &mut tally[bin_index(value, lo, hi, count)];
        t.0 += 1;
        t.1 += usize::from(success);
    }
    let width = (hi - lo) / count as f64;
    tally
        .into_iter()
        .enumerate()
        .filter(|(_, (trials, _))| *trials > 0)
        .map(|(index, (trials, successes))| {
            let (lo_95, hi_95) = wilson_interval(successes, trials);
            Bin {
                index,
                from: lo + width * index as f64,
                to: if index + 1 == count { hi } else { lo + width * (index + 1) as f64 },
                trials,
                successes,
                success_rate: successes as f64 / trials as f64,
                wilson_95: [lo_95, hi_95],
            }
        })
        .collect()
}

/// One method's bins.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MethodBins {
    /// The method.
    pub method: String,
    /// Its non-empty bins, in order.
    pub bins: Vec<Bin>,
}

/// What the lines say about one parameter.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub enum SweepShape {
    /// No line has the parameter.
    NoValues,
    /// Every line has the same value (SI): nothing to plot.
    Constant(f64),
    /// Bins over the observed range `lo..=hi` (SI), the same for every method.
    Binned {
        /// The smallest value seen.
        lo: f64,
        /// The largest value seen.
        hi: f64,
        /// Per method, in the order asked for.
        methods: Vec<MethodBins>,
    },
}

/// Success against one parameter.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Sweep {
    /// The parameter.
    pub parameter: Parameter,
    /// Lines whose draw lacks it (left out).
    pub lines_without_value: usize,
    /// The bins, or why there are none.
    pub shape: SweepShape,
}

/// Success against `parameter` for each of `methods`, in `count` bins over the range seen in `lines`.
pub fn sweep(lines: &[TrialLine], methods: &[String], parameter: Parameter, count: usize) -> Sweep {
    let valued: Vec<(&TrialLine, f64)> =
        lines.iter().filter_map(|l| parameter.value_si(l).map(|v| (l, v))).collect();
    let lines_without_value = lines.len() - valued.len();
    let shape = match observed_range(valued.iter().map(|(_, v)| *v)) {
        None => SweepShape::NoValues,
        Some((lo, hi)) if is_degenerate(lo, hi) => SweepShape::Constant(lo),
        Some((lo, hi)) => SweepShape::Binned {
            lo,
            hi,
            methods: methods
                .iter()
                .map(|m| {
                    let outcomes: Vec<(f64, bool)> = valued
                        .iter()
                        .filter(|(l, _)| &l.method == m)
                        .map(|(l, v)| (*v, is_success(l)))
                        .collect();
                    MethodBins { method: m.clone(), bins: bin_outcomes(&outcomes, lo, hi, count) }
                })
                .collect(),
        },
    };
    Sweep { parameter, lines_without_value, shape }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line(method: &str, play_rad: f64, offset_m: [f64; 3], verdict: &str) -> TrialLine {
        let draw = serde_json::json!({ "play_rad": play_rad, "calibration_max_rad": 0.0, "stitch_offset_m": offset_m });
        super::super::test_line(method, draw, verdict)
    }

    /// A value lands in its equal-width bin; the top value and anything above it fall in the last bin,
    /// anything below in the first.
    #[test]
    fn values_fall_in_equal_width_bins_and_the_top_value_in_the_last() {
        assert_eq!(bin_index(0.0, 0.0, 1.0, 5), 0);
        assert_eq!(bin_index(0.199, 0.0, 1.0, 5), 0);
        assert_eq!(bin_index(0.2, 0.0, 1.0, 5), 1);
        assert_eq!(bin_index(0.99, 0.0, 1.0, 5), 4);
        assert_eq!(bin_index(1.0, 0.0, 1.0, 5), 4);
        assert_eq!(bin_index(-3.0, 0.0, 1.0, 5), 0);
        assert_eq!(bin_index(7.0, 0.0, 1.0, 5), 4);
    }

    /// Each bin counts its trials and successes with its own Wilson interval, and bins with no trials are
    /// left out.
    #[test]
    fn bins_count_trials_and_successes_with_a_wilson_interval_each_and_skip_empty_ones() {
        let outcomes = [(0.0, true), (0.1, false), (0.5, true), (0.55, true), (1.0, false), (0.95, true)];
        let bins = bin_outcomes(&outcomes, 0.0, 1.0, 5);
        // Bins 1 (0.2..0.4) and 3 (0.6..0.8) hold nothing.
        assert_eq!(bins.iter().map(|b| b.index).collect::<Vec<_>>(), vec![0, 2, 4]);
        assert_eq!(
            bins.iter().map(|b| (b.trials, b.successes)).collect::<Vec<_>>(),
            vec![(2, 1), (2, 2), (2, 1)]
        );
        assert_eq!(bins.iter().map(|b| b.trials).sum::<usize>(), outcomes.len());
        for b in &bins {
            let (lo, hi) = wilson_interval(b.successes, b.trials);
            assert_eq!(b.wilson_95, [lo, hi]);
            assert!(b.wilson_95[0] <= b.success_rate && b.success_rate <= b.wilson_95[1], "{b:?}");
            assert!((b.to - b.from - 0.2).abs() < 1e-12, "{b:?}");
        }
        assert!((bins[1].from - 0.4).abs() < 1e-12 && (bins[1].centre() - 0.5).abs() < 1e-12);
        assert_eq!(bins[2].to, 1.0);
        // 2 of 2: the interval reaches 1 but not 0.
        assert_eq!(bins[1].success_rate, 1.0);
        assert!(bins[1].wilson_95[1] > 0.999 && bins[1].wilson_95[0] > 0.3);
    }

    /// A parameter drawn at one value only is reported as a constant, not binned, and a degenerate range puts
    /// everything in one bin instead of dividing by zero.
    #[test]
    fn a_parameter_with_one_value_is_constant_not_binned() {
        let lines: Vec<TrialLine> =
            (0..4).map(|k| line("fluid", 0.0, [0.001 * k as f64, 0.0, 0.0], "success")).collect();
        let methods = vec!["fluid".to_owned()];
        let play = sweep(&lines, &methods, Parameter::Play, BIN_COUNT);
        assert_eq!(play.shape, SweepShape::Constant(0.0));
        assert!(is_degenerate(0.02, 0.02) && is_degenerate(0.0, 0.0) && !is_degenerate(0.0, 1e-9));
        // A degenerate range puts everything in bin 0 (no division by zero).
        let bins = bin_outcomes(&[(0.3, true), (0.3, false)], 0.3, 0.3, 5);
        assert_eq!(bins.len(), 1);
        assert_eq!((bins[0].index, bins[0].trials, bins[0].successes), (0, 2, 1));
        let displacement = sweep(&lines, &methods, Parameter::StitchDisplacement, BIN_COUNT);
        assert!(matches!(displacement.shape, SweepShape::Binned { .. }), "{displacement:?}");
    }

    /// Bins span the range of every method's values together, and lines whose draw lacks the value are
    /// counted apart.
    #[test]
    fn bins_span_every_methods_values_and_lines_without_the_value_are_counted() {
        let mut lines = vec![
            line("fluid", 0.001, [0.0; 3], "success"),
            line("fluid", 0.0025, [0.0; 3], "no_knot"),
            line("dmp", 0.005, [0.0; 3], "success"),
            line("dmp", 0.0045, [0.0; 3], "loose"),
        ];
        let mut bare = line("dmp", 0.0, [0.0; 3], "unreachable");
        bare.draw = serde_json::Value::Null;
        lines.push(bare);
        let methods = vec!["fluid".to_owned(), "dmp".to_owned()];
        let s = sweep(&lines, &methods, Parameter::Play, 4);
        assert_eq!(s.lines_without_value, 1);
        let SweepShape::Binned { lo, hi, methods: per_method } = s.shape else { panic!("{s:?}") };
        assert_eq!((lo, hi), (0.001, 0.005));
        // Width 0.001: fluid in bins 0 and 1, dmp in bin 3 (0.0045 and the top value 0.005).
        assert_eq!(per_method[0].method, "fluid");
        assert_eq!(
            per_method[0].bins.iter().map(|b| (b.index, b.successes)).collect::<Vec<_>>(),
            vec![(0, 1), (1, 0)]
        );
        assert_eq!(
            per_method[1].bins.iter().map(|b| (b.index, b.trials, b.successes)).collect::<Vec<_>>(),
            vec![(3, 2, 1)]
        );
    }

    /// Stitch displacement is the drawn offset's norm; a malformed draw gives no value, not a wrong one.
    #[test]
    fn stitch_displacement_is_the_offsets_norm() {
        let l = line("fluid", 0.0, [0.003, 0.004, 0.0], "success");
        assert!((Parameter::StitchDisplacement.value_si(&l).unwrap() - 0.005).abs() < 1e-15);
        assert_eq!(Parameter::Play.value_si(&l), Some(0.0));
        let mut bad = l.clone();
        bad.draw = serde_json::json!({ "stitch_offset_m": [0.1, "x", 0.0] });
        assert_eq!(Parameter::StitchDisplacement.value_si(&bad), None);
        assert_eq!(Parameter::Calibration.value_si(&bad), None);
    }
}

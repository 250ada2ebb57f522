//! The workspace map: success over a grid of two drawn parameters (the stitch's shift along x by its
//! shift along y; its turn by the tissue's tilt), per method and cell with the 95 % Wilson interval,
//! the failure modes, and how many trials the arms could not reach there (the reachable boundary).
//! Plain numbers, no drawing.

use std::collections::BTreeMap;

use serde::Serialize;

use crate::mc::{TrialLine, wilson_interval};

use super::bins::{Parameter, bin_index, is_degenerate, observed_range};
use super::methods::is_success;

/// Cells along each axis of a map.
pub const MAP_CELLS: usize = 4;

/// The verdicts that mark where the arms cannot do the task: a target out of reach (or a skill that
/// could not be made there) and an arm's link against something.
pub const OUT_OF_REACH: [&str; 2] = ["unreachable", "collision"];

/// A drawn parameter a map is laid over.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum Axis {
    /// The stitch's shift along the world's x, `draw.stitch_offset_m[0]`.
    ShiftX,
    /// ... along y, `draw.stitch_offset_m[1]`.
    ShiftY,
    /// The stitch's turn about the tissue's normal, `draw.stitch_rotate_rad`.
    Turn,
    /// The tissue's tilt about the wound, `draw.stitch_tilt_rad`.
    Tilt,
}

impl Axis {
    /// The sweep parameter it is, for the turn and the tilt (their name, unit and value are the
    /// sweep's).
    fn parameter(self) -> Option<Parameter> {
        match self {
            Axis::ShiftX | Axis::ShiftY => None,
            Axis::Turn => Some(Parameter::StitchTurn),
            Axis::Tilt => Some(Parameter::StitchTilt),
        }
    }

    /// Its name in prose.
    pub fn name(self) -> &'static str {
        match (self, self.parameter()) {
            (_, Some(p)) => p.name(),
            (Axis::ShiftY, None) => "shift along y",
            (_, None) => "shift along x",
        }
    }

    /// The unit it is shown in.
    pub fn shown_unit(self) -> &'static str {
        self.parameter().map_or(Parameter::StitchDisplacement.shown_unit(), Parameter::shown_unit)
    }

    /// Shown units per SI unit.
    pub fn shown_per_si(self) -> f64 {
        self.parameter().map_or(Parameter::StitchDisplacement.shown_per_si(), Parameter::shown_per_si)
    }

    /// The value of a line, SI; none when its draw lacks it or it is not finite.
    pub fn value_si(self, line: &TrialLine) -> Option<f64> {
        if let Some(p) = self.parameter() {
            return p.value_si(line);
        }
        let xyz = line.draw.get(Parameter::StitchDisplacement.field())?.as_array()?;
        if xyz.len() != 3 {
            return None;
        }
        let value = xyz[usize::from(self == Axis::ShiftY)].as_f64()?;
        value.is_finite().then_some(value)
    }
}

/// One cell of a method's map.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Cell {
    /// Its column (along the map's x) and row (along its y), from 0.
    pub at: [usize; 2],
    /// Its bounds along x and along y, SI.
    pub x: [f64; 2],
    /// See [`Cell::x`].
    pub y: [f64; 2],
    /// Trials in it.
    pub trials: usize,
    /// Successes among them.
    pub successes: usize,
    /// successes / trials.
    pub success_rate: f64,
    /// The 95 % Wilson interval of the rate.
    pub wilson_95: [f64; 2],
    /// Trials per failure mode.
    pub failures: BTreeMap<String, usize>,
    /// Trials whose verdict is one of [`OUT_OF_REACH`].
    pub out_of_reach: usize,
}

impl Cell {
    /// Its failure modes, the most frequent first (ties by name).
    pub fn failures_by_count(&self) -> Vec<(&str, usize)> {
        let mut modes: Vec<(&str, usize)> = self.failures.iter().map(|(m, n)| (m.as_str(), *n)).collect();
        modes.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(b.0)));
        modes
    }
}

/// One method's cells (those with trials).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MethodMap {
    /// The method.
    pub method: String,
    /// Its cells with trials, row by row.
    pub cells: Vec<Cell>,
}

/// What the lines make of a map.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub enum MapShape {
    /// An axis has no values, or only one: no grid to lay.
    Flat,
    /// Cells over the observed ranges, the same for every method.
    Grid {
        /// The range along x, SI.
        x: [f64; 2],
        /// The range along y, SI.
        y: [f64; 2],
        /// Cells along each axis.
        cells: usize,
        /// Per method, in the order asked for.
        methods: Vec<MethodMap>,
    },
}

/// Success over a grid of two parameters.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Map {
    /// The parameter along x.
    pub x: Axis,
    /// The parameter along y.
    pub y: Axis,
    /// Lines whose draw lacks either (left out).
    pub lines_without_value: usize,
    /// The cells, or why there are none.
    pub shape: MapShape,
}

/// The map of `lines` for each of `methods` over `x` by `y`, `cells` by `cells` equal cells spanning
/// the values seen.
pub fn map(lines: &[TrialLine], methods: &[String], x: Axis, y: Axis, cells: usize) -> Map {
    let cells = cells.max(1);
    let valued: Vec<(&TrialLine, f64, f64)> =
        lines.iter().filter_map(|l| Some((l, x.value_si(l)?, y.value_si(l)?))).collect();
    let lines_without_value = lines.len() - valued.len();
    let ranges = (observed_range(valued.iter().map(|v| v.1)), observed_range(valued.iter().map(|v| v.2)));
    let shape = match ranges {
        (Some((x0, x1)), Some((y0, y1))) if !is_degenerate(x0, x1) && !is_degenerate(y0, y1) => {
            let bounds = |lo: f64, hi: f64, k: usize| {
                let width = (hi - lo) / cells as f64;
                [lo + width * k as f64, if k + 1 == cells { hi } else { lo + width * (k + 1) as f64 }]
            };
            let methods = methods
                .iter()
                .map(|m| {
                    let mut grid: BTreeMap<[usize; 2], Vec<&TrialLine>> = BTreeMap::new();
                    for (l, vx, vy) in valued.iter().filter(|v| &v.0.method == m) {
                        let at = [bin_index(*vx, x0, x1, cells), bin_index(*vy, y0, y1, cells)];
                        grid.entry(at).or_default().push(l);
                    }
                    // Row by row: y first.
                    let mut keyed: Vec<([usize; 2], Vec<&TrialLine>)> = grid.into_iter().collect();
                    keyed.sort_by_key(|(at, _)| (at[1], at[0]));
                    let cells = keyed
                        .into_iter()
                        .map(|(at, in_cell)| {
                            let trials = in_cell.len();
                            let successes = in_cell.iter().filter(|l| is_success(l)).count();
                            let mut failures = BTreeMap::new();
                            for l in in_cell.iter().filter(|l| !is_success(l)) {
                                *failures.entry(l.verdict.clone()).or_insert(0) += 1;
                            }
                            let out_of_reach =
                                in_cell.iter().filter(|l| OUT_OF_REACH.contains(&l.verdict.as_str())).count();
                            let (lo_95, hi_95) = wilson_interval(successes, trials);
                            Cell {
                                at,
                                x: bounds(x0, x1, at[0]),
                                y: bounds(y0, y1, at[1]),
                                trials,
                                successes,
                                success_rate: successes as f64 / trials as f64,
                                wilson_95: [lo_95, hi_95],
                                failures,
                                out_of_reach,
                            }
                        })
                        .collect();
                    MethodMap { method: m.clone(), cells }
                })
                .collect();
            MapShape::Grid { x: [x0, x1], y: [y0, y1], cells, methods }
        }
        _ => MapShape::Flat,
    };
    Map { x, y, lines_without_value, shape }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line(method: &str, offset_m: [f64; 3], rotate_rad: f64, verdict: &str) -> TrialLine {
        let draw = serde_json::json!({ "stitch_offset_m": offset_m, "stitch_rotate_rad": rotate_rad });
        super::super::test_line(method, draw, verdict)
    }

    /// Each trial lands in the cell of its shift; a cell counts its trials, successes, failure modes and
    /// the trials out of reach, with its own Wilson interval, per method over the same grid.
    #[test]
    fn trials_land_in_the_cell_of_their_shift_and_each_cell_counts_its_own() {
        let lines = vec![
            line("fluid", [-0.03, -0.03, 0.0], 0.0, "success"),
            line("fluid", [-0.029, -0.02, 0.0], 0.0, "no_knot"),
            line("fluid", [0.03, 0.03, 0.0], 0.0, "unreachable"),
            line("fluid", [0.025, 0.029, 0.0], 0.0, "success"),
            line("fluid", [0.026, 0.028, 0.0], 0.0, "collision"),
            line("replay", [0.0, 0.0, 0.0], 0.0, "wrong_knot_type"),
        ];
        let methods = vec!["fluid".to_owned(), "replay".to_owned()];
        let m = map(&lines, &methods, Axis::ShiftX, Axis::ShiftY, 4);
        let MapShape::Grid { x, y, cells, methods: per } = &m.shape else { panic!("{m:?}") };
        assert_eq!((*x, *y, *cells), ([-0.03, 0.03], [-0.03, 0.03], 4));
        let fluid = &per[0].cells;
        assert_eq!(fluid.iter().map(|c| c.at).collect::<Vec<_>>(), vec![[0, 0], [3, 3]]);
        assert_eq!((fluid[0].trials, fluid[0].successes, fluid[0].out_of_reach), (2, 1, 0));
        assert_eq!(fluid[0].failures.get("no_knot"), Some(&1));
        assert_eq!((fluid[1].trials, fluid[1].successes, fluid[1].out_of_reach), (3, 1, 2));
        assert_eq!(fluid[1].failures_by_count(), vec![("collision", 1), ("unreachable", 1)]);
        assert_eq!(fluid[1].wilson_95, {
            let (lo, hi) = wilson_interval(1, 3);
            [lo, hi]
        });
        assert!((fluid[1].x[0] - 0.015).abs() < 1e-12 && fluid[1].x[1] == 0.03);
        // The replay's one trial, at the centre, in cell (2, 2) of the same grid.
        assert_eq!(per[1].cells.len(), 1);
        assert_eq!((per[1].cells[0].at, per[1].cells[0].successes), ([2, 2], 0));
    }

    /// A parameter that does not vary lays no grid (the default scene draws no tilt), and lines without
    /// the values are counted apart.
    #[test]
    fn an_axis_that_does_not_vary_lays_no_grid() {
        let mut lines = vec![
            line("fluid", [0.01, 0.0, 0.0], 0.1, "success"),
            line("fluid", [0.0, 0.01, 0.0], -0.1, "success"),
        ];
        let methods = vec!["fluid".to_owned()];
        assert_eq!(map(&lines, &methods, Axis::Turn, Axis::Tilt, 4).shape, MapShape::Flat);
        assert!(matches!(map(&lines, &methods, Axis::ShiftX, Axis::ShiftY, 4).shape, MapShape::Grid { .. }));
        lines.push(super::super::test_line("fluid", serde_json::Value::Null, "success"));
        assert_eq!(map(&lines, &methods, Axis::ShiftX, Axis::ShiftY, 4).lines_without_value, 1);
        assert_eq!(Axis::ShiftY.value_si(&lines[1]), Some(0.01));
        assert_eq!(Axis::Turn.value_si(&lines[1]), Some(-0.1));
    }
}

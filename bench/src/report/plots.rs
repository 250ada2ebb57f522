//! The report's charts, drawn by plotters into SVG strings: success per method with Wilson error bars,
//! failure modes per method, success against a drawn parameter in bins, and the workspace maps. Only draws figures that
//! [`super::methods`] and [`super::bins`] computed.

use plotters::coord::combinators::WithKeyPoints;
use plotters::coord::types::RangedCoordi32;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::bins::{MethodBins, Parameter};
use super::map::{Axis, Cell, MethodMap};
use super::methods::MethodStats;

/// The first chart's title.
pub const METHODS_TITLE: &str = "Methods side by side";
/// The failure chart's title.
pub const FAILURES_TITLE: &str = "Failure modes";

const SIZE_PX: (u32, u32) = (720, 380);
const FONT: &str = "sans-serif";

/// A chart plotters could not draw.
#[derive(Debug, thiserror::Error)]
#[error("chart \"{chart}\": {reason}")]
pub struct PlotError {
    /// The chart's title.
    pub chart: String,
    /// Why.
    pub reason: String,
}

type Drawn = Result<(), DrawingAreaErrorKind<std::io::Error>>;

fn svg(chart: &str, draw: impl FnOnce(&mut String) -> Drawn) -> Result<String, PlotError> {
    let mut text = String::new();
    draw(&mut text).map_err(|e| PlotError { chart: chart.to_owned(), reason: e.to_string() })?;
    Ok(text)
}

/// The colour of the `index`-th method (the same in every chart and the tables' swatches).
pub fn method_colour(index: usize) -> RGBColor {
    const PALETTE: [RGBColor; 6] = [
        RGBColor(31, 119, 180),
        RGBColor(255, 127, 14),
        RGBColor(44, 160, 44),
        RGBColor(214, 39, 40),
        RGBColor(148, 103, 189),
        RGBColor(140, 86, 75),
    ];
    PALETTE[index % PALETTE.len()]
}

/// Category charts place category `i` at `i * CATEGORY` along x (integers, so that plotters formats the
/// ticks we give; its own f64 ticks would not fall on the categories).
const CATEGORY: i32 = 100;

/// The x range and ticks of `count` categories.
fn categories(count: usize) -> WithKeyPoints<RangedCoordi32> {
    let count = i32::try_from(count).unwrap_or(i32::MAX / CATEGORY);
    let ticks: Vec<i32> = (0..count).map(|i| i * CATEGORY).collect();
    (-CATEGORY / 2..count * CATEGORY - CATEGORY / 2).with_key_points(ticks)
}

/// The name at x position `x` when it is a category's tick, empty elsewhere.
fn category(names: &[String], x: i32) -> String {
    if x % CATEGORY != 0 || x < 0 {
        return String::new();
    }
    names.get((x / CATEGORY) as usize).cloned().unwrap_or_default()
}

fn legend_box(colour: RGBColor) -> impl Fn((i32, i32)) -> Rectangle<(i32, i32)> {
    move |(x, y)| Rectangle::new([(x, y - 5), (x + 12, y + 5)], colour.filled())
}

/// Success rate per method as bars, with the 95 % Wilson interval as error bars.
pub fn methods_chart(stats: &[MethodStats]) -> Result<String, PlotError> {
    svg(METHODS_TITLE, |text| {
        let root = SVGBackend::with_string(text, SIZE_PX).into_drawing_area();
        root.fill(&WHITE)?;
        let names: Vec<String> = stats.iter().map(|s| s.method.clone()).collect();
        let mut chart = ChartBuilder::on(&root)
            .caption(METHODS_TITLE, (FONT, 20))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(56)
            .build_cartesian_2d(categories(stats.len()), 0.0..100.0)?;
        chart
            .configure_mesh()
            .disable_x_mesh()
            .x_label_formatter(&|x| category(&names, *x))
            .x_desc("method")
            .y_desc("success rate (%)")
            .y_label_formatter(&|y| format!("{y:.0}"))
            .draw()?;
        let centres = (0..).step_by(CATEGORY as usize);
        chart.draw_series(stats.iter().zip(centres.clone()).enumerate().map(|(i, (s, x))| {
            let half = CATEGORY * 3 / 10;
            Rectangle::new(
                [(x - half, 0.0), (x + half, 100.0 * s.tally.success_rate)],
                method_colour(i).filled(),
            )
        }))?;
        chart.draw_series(stats.iter().zip(centres).map(|(s, x)| {
            let [lo, hi] = s.tally.wilson_95;
            ErrorBar::new_vertical(
                x,
                100.0 * lo,
                100.0 * s.tally.success_rate,
                100.0 * hi,
                BLACK.stroke_width(2),
                18,
            )
        }))?;
        root.present()
    })
}

/// Trials per failure mode (`modes`, along x), one bar per method in each group.
pub fn failures_chart(stats: &[MethodStats], modes: &[String]) -> Result<String, PlotError> {
    svg(FAILURES_TITLE, |text| {
        let root = SVGBackend::with_string(text, SIZE_PX).into_drawing_area();
        root.fill(&WHITE)?;
        let count = |s: &MethodStats, mode: &String| s.tally.verdicts.get(mode).copied().unwrap_or(0) as u32;
        let most = stats.iter().flat_map(|s| modes.iter().map(move |m| count(s, m))).max().unwrap_or(0);
        let mut chart = ChartBuilder::on(&root)
            .caption(FAILURES_TITLE, (FONT, 20))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(56)
            .build_cartesian_2d(categories(modes.len()), 0u32..most + 1 + most / 4)?;
        chart
            .configure_mesh()
            .disable_x_mesh()
            .x_label_formatter(&|x| category(modes, *x))
            .x_desc("verdict")
            .y_desc("trials")
            .draw()?;
        let width = CATEGORY * 8 / 10 / i32::try_from(stats.len().max(1)).unwrap_or(i32::MAX);
        for (j, s) in (0..).zip(stats) {
            let colour = method_colour(j as usize);
            chart
                .draw_series((0..).zip(modes).map(|(i, mode)| {
                    let left = i * CATEGORY - CATEGORY * 4 / 10 + j * width;
                    let mut bar =
                        Rectangle::new([(left, 0), (left + width, count(s, mode))], colour.filled());
                    bar.set_margin(0, 0, 1, 1);
                    bar
                }))?
                .label(s.method.as_str())
                .legend(legend_box(colour));
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .draw()?;
        root.present()
    })
}

/// Its title: "Success against play", ...
pub fn sweep_title(parameter: Parameter) -> String {
    format!("Success against {}", parameter.name())
}

/// Success against `parameter` (bins over `lo..=hi`, SI), one line per method with Wilson error bars
/// per bin (the methods shifted a little apart so their bars do not overlap). No legend inside: it would
/// hide points wherever it went; the page puts the methods' colours above the chart.
pub fn sweep_chart(
    parameter: Parameter,
    lo: f64,
    hi: f64,
    methods: &[MethodBins],
) -> Result<String, PlotError> {
    let title = sweep_title(parameter);
    svg(&title, |text| {
        let root = SVGBackend::with_string(text, SIZE_PX).into_drawing_area();
        root.fill(&WHITE)?;
        let per_si = parameter.shown_per_si();
        let (x0, x1) = (lo * per_si, hi * per_si);
        let pad = 0.05 * (x1 - x0);
        let mut chart = ChartBuilder::on(&root)
            .caption(&title, (FONT, 20))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(56)
            .build_cartesian_2d(x0 - pad..x1 + pad, -3.0..103.0)?;
        chart
            .configure_mesh()
            .x_desc(format!("{} ({})", parameter.name(), parameter.shown_unit()))
            .y_desc("success rate (%)")
            .y_label_formatter(&|y| format!("{y:.0}"))
            .draw()?;
        let shift = 0.03 * (x1 - x0);
        let middle = (methods.len() as f64 - 1.0) / 2.0;
        for (j, m) in methods.iter().enumerate() {
            let colour = method_colour(j);
            let dx = (j as f64 - middle) * shift;
            let points: Vec<(f64, f64)> =
                m.bins.iter().map(|b| (b.centre() * per_si + dx, 100.0 * b.success_rate)).collect();
            chart.draw_series(LineSeries::new(points.iter().copied(), colour.stroke_width(2)))?;
            chart.draw_series(points.iter().map(|&p| Circle::new(p, 4, colour.filled())))?;
            chart.draw_series(m.bins.iter().zip(&points).map(|(b, &(x, rate))| {
                ErrorBar::new_vertical(x, 100.0 * b.wilson_95[0], rate, 100.0 * b.wilson_95[1], colour, 10)
            }))?;
        }
        root.present()
    })
}

/// A map's title: "Success over shift along x and shift along y", ...
pub fn map_title(x: Axis, y: Axis) -> String {
    format!("Success over {} and {}", x.name(), y.name())
}

/// The colour of a success rate: red at 0, yellow at one half, green at 1.
fn rate_colour(rate: f64) -> RGBColor {
    let r = rate.clamp(0.0, 1.0);
    let mix = |a: f64, b: f64, t: f64| (a + (b - a) * t).round() as u8;
    if r < 0.5 {
        RGBColor(mix(215.0, 250.0, 2.0 * r), mix(48.0, 220.0, 2.0 * r), mix(39.0, 90.0, 2.0 * r))
    } else {
        RGBColor(
            mix(250.0, 40.0, 2.0 * r - 1.0),
            mix(220.0, 160.0, 2.0 * r - 1.0),
            mix(90.0, 70.0, 2.0 * r - 1.0),
        )
    }
}

/// One method's map: each cell with trials coloured by its success rate and labelled with its
/// successes over its trials and its Wilson interval; a cell with trials out of reach outlined in black
/// and marked with their count (the reachable boundary). Ranges and values SI.
pub fn map_chart(
    x: Axis,
    y: Axis,
    x_range: [f64; 2],
    y_range: [f64; 2],
    method: &MethodMap,
) -> Result<String, PlotError> {
    let title = format!("{} ({})", map_title(x, y), method.method);
    svg(&title, |text| {
        let root = SVGBackend::with_string(text, (560, 520)).into_drawing_area();
        root.fill(&WHITE)?;
        let (sx, sy) = (x.shown_per_si(), y.shown_per_si());
        let mut chart = ChartBuilder::on(&root)
            .caption(&title, (FONT, 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(56)
            .build_cartesian_2d(x_range[0] * sx..x_range[1] * sx, y_range[0] * sy..y_range[1] * sy)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(format!("{} ({})", x.name(), x.shown_unit()))
            .y_desc(format!("{} ({})", y.name(), y.shown_unit()))
            .draw()?;
        let corners = |c: &Cell| [(c.x[0] * sx, c.y[0] * sy), (c.x[1] * sx, c.y[1] * sy)];
        chart.draw_series(
            method.cells.iter().map(|c| Rectangle::new(corners(c), rate_colour(c.success_rate).filled())),
        )?;
        chart.draw_series(method.cells.iter().map(|c| {
            let outline = if c.out_of_reach > 0 { BLACK.stroke_width(3) } else { WHITE.stroke_width(1) };
            Rectangle::new(corners(c), outline)
        }))?;
        let centred = TextStyle::from((FONT, 14)).pos(Pos::new(HPos::Center, VPos::Center));
        let small = TextStyle::from((FONT, 11)).pos(Pos::new(HPos::Center, VPos::Center));
        for c in &method.cells {
            let (cx, cy) = (0.5 * (c.x[0] + c.x[1]) * sx, 0.5 * (c.y[0] + c.y[1]) * sy);
            let h = (c.y[1] - c.y[0]) * sy;
            chart.draw_series(std::iter::once(Text::new(
                format!("{}/{}", c.successes, c.trials),
                (cx, cy + 0.18 * h),
                centred.clone(),
            )))?;
            chart.draw_series(std::iter::once(Text::new(
                format!("{:.0}-{:.0} %", 100.0 * c.wilson_95[0], 100.0 * c.wilson_95[1]),
                (cx, cy),
                small.clone(),
            )))?;
            if c.out_of_reach > 0 {
                chart.draw_series(std::iter::once(Text::new(
                    format!("{} out of reach", c.out_of_reach),
                    (cx, cy - 0.18 * h),
                    small.clone(),
                )))?;
            }
        }
        root.present()
    })
}

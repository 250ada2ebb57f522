//! The report's page: one self-contained HTML file (inline style, inline SVG charts; no scripts, fonts
//! or links to fetch), with the run's header, a table per method and the tables beside the charts.

use super::bins::{Bin, MethodBins, Parameter};
use super::map::{Axis, MethodMap};
use super::methods::{MethodStats, RunOverview};
use super::plots::method_colour;

const STYLE: &str = "body{font-family:sans-serif;margin:2em auto;max-width:60em;padding:0 1em;color:#222}\
h1{font-size:1.6em}h2{font-size:1.25em;margin-top:2em;border-bottom:1px solid #ccc}\
table{border-collapse:collapse;margin:0.6em 1.5em 0.6em 0}\
th,td{border:1px solid #ccc;padding:0.25em 0.6em;text-align:left}td{text-align:right;white-space:nowrap}tr>th:first-child{white-space:nowrap}\
caption{font-weight:bold;text-align:left;padding-bottom:0.3em}\
.methods{display:flex;flex-wrap:wrap}.swatch{display:inline-block;width:0.8em;height:0.8em;margin-right:0.4em}\
svg{max-width:100%;height:auto}.note{color:#555}dl{display:grid;grid-template-columns:auto 1fr;gap:0.2em 1em}\
dt{font-weight:bold}dd{margin:0}.legend .item{margin-right:1.5em}";

/// A titled part of the page; its body is HTML already.
pub struct Section {
    /// The heading.
    pub title: String,
    /// The HTML under it.
    pub body: String,
}

/// `text` safe inside HTML text and attribute values.
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

fn percent(fraction: f64) -> String {
    format!("{:.1} %", 100.0 * fraction)
}

fn interval([lo, hi]: [f64; 2]) -> String {
    format!("{:.1}&ndash;{:.1} %", 100.0 * lo, 100.0 * hi)
}

fn list(items: impl IntoIterator<Item = String>) -> String {
    items.into_iter().collect::<Vec<_>>().join(", ")
}

/// The run: seeds, trials, methods, lines and (when known) the scene.
pub fn header(info: &RunOverview, scene: Option<&str>) -> String {
    let mut rows = vec![
        (if info.seeds.len() == 1 { "seed" } else { "seeds" }, list(info.seeds.iter().map(u64::to_string))),
        ("trials", format!("{} (indices {}&ndash;{})", info.trials, info.trial_range.0, info.trial_range.1)),
        ("methods", list(info.methods.iter().map(|m| escape(m)))),
        ("lines", format!("{} (one per trial and method)", info.lines)),
    ];
    if let Some(scene) = scene {
        rows.push(("scene", escape(scene)));
    }
    let rows: String = rows.iter().map(|(k, v)| format!("<dt>{k}</dt><dd>{v}</dd>")).collect();
    format!("<dl class=\"run\">{rows}</dl>\n")
}

fn swatch(index: usize) -> String {
    let c = method_colour(index);
    format!("<span class=\"swatch\" style=\"background:rgb({},{},{})\"></span>", c.0, c.1, c.2)
}

/// A table per method: trials, successes, rate, the 95 % Wilson interval, the trials per verdict and
/// the thread's self-crossings.
pub fn method_tables(stats: &[MethodStats]) -> String {
    let mut out = String::from("<div class=\"methods\">\n");
    for (i, s) in stats.iter().enumerate() {
        let name = escape(&s.method);
        out.push_str(&format!(
            "<table class=\"method\" id=\"method-{name}\">\n<caption>{}{name}</caption>\n",
            swatch(i)
        ));
        out.push_str(&format!("<tr><th>trials</th><td>{}</td></tr>\n", s.tally.trials));
        out.push_str(&format!("<tr><th>successes</th><td>{}</td></tr>\n", s.tally.successes));
        out.push_str(&format!("<tr><th>success rate</th><td>{}</td></tr>\n", percent(s.tally.success_rate)));
        out.push_str(&format!(
            "<tr><th>95 % Wilson interval</th><td>{}</td></tr>\n",
            interval(s.tally.wilson_95)
        ));
        for (verdict, n) in &s.tally.verdicts {
            out.push_str(&format!("<tr><th>verdict: {}</th><td>{n}</td></tr>\n", escape(verdict)));
        }
        let x = &s.thread_self_crossings;
        out.push_str(&format!(
            "<tr><th>thread self-crossings (solver failures)</th><td>{} in {} of {} trials counted</td></tr>\n",
            x.total, x.trials_with_any, x.counted_trials
        ));
        let t = &s.thread_stretch;
        let pct = |r: Option<f64>| r.map_or("&ndash;".to_owned(), |r| format!("{:.1} %", 100.0 * r));
        out.push_str(&format!(
            "<tr><th>thread stretch (solver error)</th><td>median {}, largest {}; over 5 % in {} of {} trials measured, for {} (median)</td></tr>\n",
            pct(t.median),
            pct(t.max),
            t.trials_over_5_percent,
            t.measured_trials,
            t.median_over_5_percent_s.map_or("&ndash;".to_owned(), |s| format!("{s:.3} s"))
        ));
        out.push_str("</table>\n");
    }
    out.push_str("</div>\n");
    out
}

fn cell(bin: Option<&Bin>) -> String {
    match bin {
        None => "<td>&ndash;</td>".to_owned(),
        Some(b) => format!(
            "<td>{} / {} ({}; {})</td>",
            b.successes,
            b.trials,
            percent(b.success_rate),
            interval(b.wilson_95)
        ),
    }
}

/// The bins beside a sweep's chart: per bin its range and, per method, successes / trials with the rate
/// and its 95 % Wilson interval (bins no method has a trial in are left out).
pub fn sweep_table(parameter: Parameter, methods: &[MethodBins]) -> String {
    let mut indices: Vec<usize> = methods.iter().flat_map(|m| m.bins.iter().map(|b| b.index)).collect();
    indices.sort_unstable();
    indices.dedup();
    let unit = parameter.shown_unit();
    let per_si = parameter.shown_per_si();
    let mut out = format!("<table class=\"bins\">\n<tr><th>{} ({unit})</th>", escape(parameter.name()));
    for (i, m) in methods.iter().enumerate() {
        out.push_str(&format!(
            "<th>{}{}: successes / trials (rate; 95 % Wilson)</th>",
            swatch(i),
            escape(&m.method)
        ));
    }
    out.push_str("</tr>\n");
    for index in indices {
        let bins: Vec<Option<&Bin>> =
            methods.iter().map(|m| m.bins.iter().find(|b| b.index == index)).collect();
        let Some(any) = bins.iter().flatten().next() else { continue };
        out.push_str(&format!("<tr><th>{:.3}&ndash;{:.3}</th>", any.from * per_si, any.to * per_si));
        for b in bins {
            out.push_str(&cell(b));
        }
        out.push_str("</tr>\n");
    }
    out.push_str("</table>\n");
    out
}

/// The methods' colours, as a line above a chart.
pub fn legend(methods: &[String]) -> String {
    let items: String = methods
        .iter()
        .enumerate()
        .map(|(i, m)| format!("<span class=\"item\">{}{}</span>", swatch(i), escape(m)))
        .collect();
    format!("<p class=\"legend\">{items}</p>\n")
}

/// A paragraph of prose.
pub fn note(text: &str) -> String {
    format!("<p class=\"note\">{}</p>\n", escape(text))
}

/// The page.
pub fn page(title: &str, header: &str, sections: &[Section]) -> String {
    let title = escape(title);
    let mut out = format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>{title}</title>\n\
         <style>{STYLE}</style>\n</head>\n<body>\n<h1>{title}</h1>\n{header}"
    );
    for s in sections {
        out.push_str(&format!("<section>\n<h2>{}</h2>\n{}</section>\n", escape(&s.title), s.body));
    }
    out.push_str("</body>\n</html>\n");
    out
}

/// One method's map as a table: per cell with trials its ranges, successes / trials with the rate and
/// its 95 % Wilson interval, its failure modes (most frequent first) and its trials out of reach.
pub fn map_table(x: Axis, y: Axis, method: &MethodMap) -> String {
    let mut out = format!(
        "<table class=\"bins\">\n<tr><th>{} ({})</th><th>{} ({})</th><th>successes / trials (rate; 95 % Wilson)</th><th>failure modes</th><th>out of reach</th></tr>\n",
        escape(x.name()),
        x.shown_unit(),
        escape(y.name()),
        y.shown_unit()
    );
    let (sx, sy) = (x.shown_per_si(), y.shown_per_si());
    for c in &method.cells {
        let modes: Vec<String> =
            c.failures_by_count().iter().map(|(mode, n)| format!("{} {n}", escape(mode))).collect();
        out.push_str(&format!(
            "<tr><td>{:.1}&ndash;{:.1}</td><td>{:.1}&ndash;{:.1}</td><td>{} / {} ({}; {})</td><td>{}</td><td>{}</td></tr>\n",
            c.x[0] * sx,
            c.x[1] * sx,
            c.y[0] * sy,
            c.y[1] * sy,
            c.successes,
            c.trials,
            percent(c.success_rate),
            interval(c.wilson_95),
            if modes.is_empty() { "&ndash;".to_owned() } else { modes.join(", ") },
            c.out_of_reach
        ));
    }
    out.push_str("</table>\n");
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Text taken from the results file is HTML-escaped, so it cannot inject markup into the page.
    #[test]
    fn text_from_the_results_file_is_escaped() {
        assert_eq!(escape("<b>\"a\" & 'b'</b>"), "&lt;b&gt;&quot;a&quot; &amp; &#39;b&#39;&lt;/b&gt;");
    }

    /// A method's table shows the thread's self-crossings as the total in the trials with any, of those
    /// that counted them.
    #[test]
    fn a_method_table_counts_the_threads_self_crossings() {
        let line = |trial, crossings| crate::mc::TrialLine {
            trial,
            thread_self_crossings: crossings,
            ..crate::report::test_line("replay", serde_json::Value::Null, "no_knot")
        };
        let lines = [line(0, Some(3)), line(1, Some(0)), line(2, None)];
        let stats = crate::report::methods::method_stats(&lines, &["replay".to_owned()]);
        let table = method_tables(&stats);
        assert!(
            table.contains(
                "<th>thread self-crossings (solver failures)</th><td>3 in 1 of 2 trials counted</td>"
            ),
            "{table}"
        );
    }
}

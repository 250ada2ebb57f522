//! `knotlab report DIR` on hand-made results: the HTML is self-contained, has a chart per varying
//! parameter (text for a fixed one), and its figures (and `--json`'s) follow from the lines; a directory
//! without results.jsonl, or with a malformed line, is an error naming the file.

use super::common;

use std::path::{Path, PathBuf};

use common::knotlab;
use serde_json::{Value, json};

const METHODS: [&str; 2] = ["dmp", "fluid"];

fn dir(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("cli-report-{name}-{}", std::process::id()));
    std::fs::remove_dir_all(&d).ok();
    std::fs::create_dir_all(&d).expect("a temporary directory");
    d
}

/// 2 methods x 6 trials; play, calibration, offset, turn and tilt vary with the trial, but play and
/// tilt not when `fixed`.
fn hand_made_lines(fixed: bool) -> Vec<Value> {
    let verdicts = [
        ("dmp", ["success", "wrong_knot_type", "no_knot", "no_knot", "success", "unreachable"]),
        ("fluid", ["success", "no_knot", "success", "loose", "success", "success"]),
    ];
    let mut lines = Vec::new();
    for trial in 0..6u64 {
        for (method, v) in &verdicts {
            let t = trial as f64;
            let play_rad = if fixed { 0.0 } else { 0.001 * t };
            let tilt_rad = if fixed { 0.0 } else { -0.05 + 0.02 * t };
            lines.push(json!({
                "trial": trial,
                "seed": 42,
                "method": method,
                "draw": {
                    "stitch_offset_m": [0.002 * t, 0.001 * (trial % 3) as f64, -0.0005 * t],
                    "stitch_rotate_rad": 0.01 * t,
                    "stitch_tilt_rad": tilt_rad,
                    "play_rad": play_rad,
                    "calibration_max_rad": 0.002 + 0.0005 * t,
                    "thread_friction": 0.3,
                    "thread_bend_stiffness": 1e-5,
                    "force_noise_n": 0.01,
                    "sim_seed": 1000 + trial,
                },
                "verdict": v[trial as usize],
                "knot": if v[trial as usize] == "success" { json!("square") } else { Value::Null },
                "wound_gap_m": 0.001,
                "sim_seconds": 30.0,
                "wall_seconds": 2.0,
                "error": if v[trial as usize] == "unreachable" { json!("no IK") } else { Value::Null },
            }));
        }
    }
    lines
}

fn write_results(dir: &Path, lines: &[Value]) {
    let text: String = lines.iter().map(|l| format!("{l}\n")).collect();
    std::fs::write(dir.join("results.jsonl"), text).expect("write results.jsonl");
}

fn successes(lines: &[Value], method: &str) -> (usize, usize) {
    let mine: Vec<&Value> = lines.iter().filter(|l| l["method"] == method).collect();
    (mine.len(), mine.iter().filter(|l| l["verdict"] == "success").count())
}

fn number(v: &Value) -> f64 {
    v.as_f64().expect("a number in the hand-made line")
}

/// Charts expected: methods side by side, failure modes (when any failed), one per varying parameter,
/// and a map per method for each pair of parameters (shift x and y; turn and tilt) that both vary.
fn expected_charts(lines: &[Value]) -> usize {
    let varies = |f: &dyn Fn(&Value) -> f64| {
        let first = f(&lines[0]);
        lines.iter().any(|l| f(l) != first)
    };
    let norm = |l: &Value| {
        let offset = l["draw"]["stitch_offset_m"].as_array().expect("an offset in the hand-made line");
        offset.iter().map(|c| number(c).powi(2)).sum::<f64>()
    };
    let shift = |axis: usize| move |l: &Value| number(&l["draw"]["stitch_offset_m"][axis]);
    let turn = |l: &Value| number(&l["draw"]["stitch_rotate_rad"]);
    let tilt = |l: &Value| number(&l["draw"]["stitch_tilt_rad"]);
    let maps =
        usize::from(varies(&shift(0)) && varies(&shift(1))) + usize::from(varies(&turn) && varies(&tilt));
    1 + usize::from(lines.iter().any(|l| l["verdict"] != "success"))
        + usize::from(varies(&|l| number(&l["draw"]["play_rad"])))
        + usize::from(varies(&|l| number(&l["draw"]["calibration_max_rad"])))
        + usize::from(varies(&norm))
        + usize::from(varies(&turn))
        + usize::from(varies(&tilt))
        + maps * METHODS.len()
}

fn method_table<'a>(html: &'a str, method: &str) -> &'a str {
    let start =
        html.find(&format!("id=\"method-{method}\"")).unwrap_or_else(|| panic!("no table for {method}"));
    let end = html[start..].find("</table>").expect("the table ends");
    &html[start..start + end]
}

fn assert_self_contained(html: &str) {
    let without_xmlns = html.replace("xmlns=\"http://www.w3.org/2000/svg\"", "");
    assert!(
        !without_xmlns.contains("http://") && !without_xmlns.contains("https://"),
        "an outside reference"
    );
    for fetch in ["<script", "<link", "src=", "@import", "url("] {
        assert!(!html.contains(fetch), "{fetch} in the report");
    }
}

/// `knotlab report` writes a self-contained HTML report with each method's counts by verdict, a failure-mode
/// chart and one chart per varying parameter, its figures following from the results lines.
#[test]
fn the_report_shows_every_method_and_a_chart_per_varying_parameter() {
    let d = dir("full");
    let lines = hand_made_lines(false);
    write_results(&d, &lines);
    let charts = d.join("charts");
    let (code, stdout, stderr) = knotlab(&[
        "report",
        d.to_str().expect("a UTF-8 path"),
        "--charts",
        charts.to_str().expect("a UTF-8 path"),
    ]);
    assert_eq!(code, 0, "{stdout}{stderr}");
    let path = d.join("report.html");
    assert!(stdout.contains(&path.display().to_string()), "{stdout}");
    let html = std::fs::read_to_string(&path).expect("report.html written");
    assert_eq!(expected_charts(&lines), 11);
    assert_eq!(html.matches("<svg").count(), expected_charts(&lines));
    // Each chart also on its own, as the page has it.
    let mut files: Vec<String> = std::fs::read_dir(&charts)
        .expect("the charts' folder")
        .map(|e| e.expect("an entry").file_name().to_string_lossy().into_owned())
        .collect();
    files.sort();
    assert_eq!(files.len(), expected_charts(&lines), "{files:?}");
    for name in [
        "methods.svg",
        "failures.svg",
        "stitch-turn.svg",
        "tissue-tilt.svg",
        "map-shift-dmp.svg",
        "map-turn-tilt-fluid.svg",
    ] {
        assert!(files.iter().any(|f| f == name), "{name} in {files:?}");
    }
    for f in &files {
        let svg = std::fs::read_to_string(charts.join(f)).expect("a chart");
        assert!(svg.starts_with("<svg") && html.contains(&svg), "{f} is not the page's chart");
    }
    for title in [
        "Methods side by side",
        "Failure modes",
        "Success against play",
        "Success against calibration error",
        "Success against stitch displacement",
        "Success against stitch turn",
        "Success against tissue tilt",
        "Success over shift along x and shift along y",
        "Success over stitch turn and tissue tilt",
    ] {
        assert!(html.contains(&format!("<h2>{title}</h2>")), "{title}");
    }
    // The one trial out of reach (dmp's last) is marked on both of dmp's maps, and on no other.
    assert_eq!(html.matches("1 out of reach").count(), 2, "the reachable boundary");
    for m in METHODS {
        let (trials, won) = successes(&lines, m);
        let table = method_table(&html, m);
        assert!(table.contains(&format!("<th>trials</th><td>{trials}</td>")), "{table}");
        assert!(table.contains(&format!("<th>successes</th><td>{won}</td>")), "{table}");
        assert!(stdout.contains(&format!("{m}: {won} of {trials} trials")), "{stdout}");
        for l in lines.iter().filter(|l| l["method"] == m) {
            let verdict = l["verdict"].as_str().unwrap();
            let n = lines.iter().filter(|k| k["method"] == m && k["verdict"] == verdict).count();
            assert!(table.contains(&format!("<th>verdict: {verdict}</th><td>{n}</td>")), "{verdict} {table}");
        }
    }
    // Every failure mode is on the failure chart's axis.
    for l in &lines {
        let verdict = l["verdict"].as_str().unwrap();
        if verdict != "success" {
            assert!(html.matches(verdict).count() >= 2, "{verdict}");
        }
    }
    assert!(html.contains("<dt>seed</dt><dd>42</dd>"), "the run's seed");
    assert_self_contained(&html);
    std::fs::remove_dir_all(&d).ok();
}

/// A parameter fixed across trials is stated in text instead of charted, the report goes to `--out`, and
/// `--json` gives each method's trials, successes and rate as the lines say.
#[test]
fn a_fixed_parameter_is_said_in_text_and_json_matches_the_lines() {
    let d = dir("fixed");
    let lines = hand_made_lines(true);
    write_results(&d, &lines);
    let out = d.join("elsewhere").join("r.html");
    let (code, stdout, stderr) =
        knotlab(&["report", d.to_str().unwrap(), "--out", out.to_str().unwrap(), "--json"]);
    assert_eq!(code, 0, "{stdout}{stderr}");
    let summary: Value = serde_json::from_str(&stdout).unwrap_or_else(|e| panic!("not JSON ({e}): {stdout}"));
    assert_eq!(summary["report"], out.display().to_string());
    let methods = summary["methods"].as_array().unwrap();
    assert_eq!(methods.len(), METHODS.len());
    for (m, reported) in METHODS.iter().zip(methods) {
        let (trials, won) = successes(&lines, m);
        assert_eq!(reported["method"], *m);
        assert_eq!(reported["trials"], trials);
        assert_eq!(reported["successes"], won);
        assert!((reported["success_rate"].as_f64().unwrap() - won as f64 / trials as f64).abs() < 1e-12);
    }
    let html = std::fs::read_to_string(&out).expect("the report at --out");
    assert_eq!(expected_charts(&lines), 7);
    assert_eq!(html.matches("<svg").count(), expected_charts(&lines));
    assert!(
        html.contains("The play was the same in every trial (0.000 mrad): no chart."),
        "no text for fixed play"
    );
    assert!(
        html.contains("The stitch turn and the tissue tilt did not both vary across the trials: no map."),
        "no text for the flat map"
    );
    assert!(!d.join("report.html").exists());
    assert_self_contained(&html);
    std::fs::remove_dir_all(&d).ok();
}

/// A directory with no results.jsonl, an empty one or a malformed line is an error naming the file and, for a
/// bad line, its number.
#[test]
fn a_directory_without_results_or_with_a_bad_line_is_named() {
    let d = dir("missing");
    let (code, stdout, stderr) = knotlab(&["report", d.to_str().unwrap()]);
    assert_ne!(code, 0, "{stdout}");
    assert!(stderr.contains(&d.join("results.jsonl").display().to_string()), "{stderr}");
    assert!(!d.join("report.html").exists());

    std::fs::write(d.join("results.jsonl"), "").unwrap();
    let (code, _, stderr) = knotlab(&["report", d.to_str().unwrap()]);
    assert_ne!(code, 0);
    assert!(stderr.contains("results.jsonl") && stderr.contains("no finished trial"), "{stderr}");

    let mut text = format!("{}\n", hand_made_lines(false)[0]);
    text.push_str("{\"trial\": \"one\"}\n");
    std::fs::write(d.join("results.jsonl"), text).unwrap();
    let (code, _, stderr) = knotlab(&["report", d.to_str().unwrap()]);
    assert_ne!(code, 0);
    assert!(stderr.contains("results.jsonl") && stderr.contains("line 2"), "{stderr}");
    std::fs::remove_dir_all(&d).ok();
}

/// Guards against the report hanging on a drawn value it cannot chart (a play of 1e308 rad, infinite in
/// mrad, left the chart's axis to tick for ever): such a line is refused, naming the file, the line,
/// the field and its value, and what is allowed, before any chart is drawn; a stitch offset that is not
/// three numbers is refused the same way.
#[test]
fn a_draw_the_report_cannot_show_is_refused_with_its_line() {
    let d = dir("huge-draw");
    let mut lines = hand_made_lines(false);
    lines[3]["draw"]["play_rad"] = json!(1e308);
    write_results(&d, &lines);
    let (code, _, stderr) = knotlab(&["report", d.to_str().unwrap()]);
    assert_eq!(code, 1, "{stderr}");
    for part in ["results.jsonl line 4", "draw.play_rad = 1e+308", "at most 1e300"] {
        assert!(stderr.contains(part), "'{part}' missing from: {stderr}");
    }
    assert!(!d.join("report.html").exists());

    let mut lines = hand_made_lines(false);
    lines[0]["draw"]["stitch_offset_m"] = json!([0.001, 0.002]);
    write_results(&d, &lines);
    let (code, _, stderr) = knotlab(&["report", d.to_str().unwrap()]);
    assert_eq!(code, 1, "{stderr}");
    assert!(stderr.contains("results.jsonl line 1") && stderr.contains("draw.stitch_offset_m"), "{stderr}");
    std::fs::remove_dir_all(&d).ok();
}

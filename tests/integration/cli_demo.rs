//! `knotlab demo`: the scripted expert's runs, each written as a demonstration that `knotlab learn`
//! reads, and the JSON report with the success rate and each run's verdict; bad seeds are refused.

use super::common;

use common::{json, knotlab};

/// `knotlab demo --json` reports each run's seed, verdict and knot at release, writes the snapshot,
/// centreline and contacts files, and a recording that `knotlab learn` reads as a demonstration.
#[test]
fn demo_json_reports_each_run_and_writes_loadable_demonstrations() {
    let dir = std::env::temp_dir().join(format!("knotlab-demo-{}", std::process::id()));
    let out = dir.to_str().unwrap();
    let (code, v) = json(&[
        "demo",
        "--scene",
        "scenarios/chain.toml",
        "--seeds",
        "5..6",
        "--out",
        out,
        "--snapshots",
        "9",
        "--json",
    ]);
    assert_eq!(code, 0, "{v}");
    assert_eq!(v["runs"], 1, "{v}");
    let rate = v["success_rate"].as_f64().unwrap();
    assert!((0.0..=1.0).contains(&rate));
    let run = &v["results"][0];
    assert_eq!(run["seed"], 5);
    assert!(run["verdict"].is_string(), "{run}");
    assert_eq!(run["fault"], serde_json::Value::Null, "{run}");
    // The knot where the pulls left it, taken as the left let go of the tail.
    assert!(run["knot_at_release"]["knot"].is_string(), "{run}");
    // How far its crossings spread: a knot has some, no knot none.
    let radius = &run["knot_at_release"]["radius_m"];
    if run["knot_at_release"]["knot"] == "unknot" {
        assert!(radius.is_null(), "{run}");
    } else {
        assert!(radius.as_f64().is_some_and(|r| r > 0.0 && r < 0.25), "{run}");
    }
    // Its legs, where the long end and the tail touch: a leg's thread spans at most its own length.
    for leg in ["exit_leg", "entry_leg"] {
        let l = &run["knot_at_release"][leg];
        if !l.is_null() {
            let (thread, span) = (l["thread_m"].as_f64().unwrap(), l["span_m"].as_f64().unwrap());
            assert!(span >= 0.0 && span <= thread + 1e-9, "{leg}: {l}");
        }
    }
    // How much each end bends inside the knot: none, or two angles that are not negative.
    let bending = &run["knot_at_release"]["bending"];
    if !bending.is_null() {
        for end in ["long_end_rad", "tail_rad"] {
            assert!(bending[end].as_f64().is_some_and(|a| a >= 0.0), "{end}: {bending}");
        }
    }
    // What the knot let through under the holding load: each end drawn in by at most the thread's
    // length (0.25 m), reported only when the holding test ran.
    if !run["slid"].is_null() {
        assert!(run["gap_after_m"].is_f64(), "{run}");
        for end in ["long_end_m", "tail_m"] {
            let slid = run["slid"][end].as_f64().expect("a number");
            assert!(slid.abs() <= 0.25, "{end}: {run}");
        }
    }
    // A snapshot 9 s in, as the right winds the long end: the picture, the centreline and where the
    // thread lies on the instruments (segment, link): on the left's jaws, which it is wound round.
    let seed_dir = dir.join("seed-5");
    assert!(seed_dir.join("snapshot-9.000s.png").is_file());
    assert!(seed_dir.join("centreline-9.000s.csv").is_file());
    let contacts = std::fs::read_to_string(seed_dir.join("contacts-9.000s.csv")).expect("contacts written");
    let mut rows = contacts.lines();
    assert_eq!(rows.next(), Some("segment,link"));
    let rows: Vec<(usize, &str)> = rows
        .map(|r| {
            let (segment, link) = r.split_once(',').expect("segment,link");
            (segment.parse().expect("a segment index"), link)
        })
        .collect();
    assert!(rows.iter().any(|(_, link)| link.starts_with("left_jaw")), "{contacts}");
    assert!(rows.iter().all(|(segment, _)| *segment < 80), "{contacts}");
    // The first self-crossings, listed as many as counted up to ten, each with its time and segments.
    let listed = run["first_self_crossings"].as_array().expect("a list");
    assert_eq!(listed.len() as u64, run["thread_self_crossings"].as_u64().unwrap().min(10), "{run}");
    for c in listed {
        assert!(c["time_s"].as_f64().is_some_and(|t| t >= 0.0) && c["segments"].is_array(), "{c}");
    }
    assert!(run["samples"].as_u64().unwrap() > 3000, "three instruments at 100 Hz for 10 s or more: {run}");
    // The learner reads what the expert wrote (and accepts or rejects it with its reason).
    let demo = dir.join("seed-5");
    let (code, out, err) =
        knotlab(&["learn", "--demo", demo.to_str().unwrap(), "--out", dir.join("kb.json").to_str().unwrap()]);
    assert!(code == 0 || code == 3, "read as a demonstration (0 accepted, 3 rejected): {out}{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// An empty, reversed, non-numeric or single-number `--seeds` range is refused with exit code 2, naming it.
#[test]
fn bad_seed_ranges_are_refused() {
    for range in ["5..5", "7..3", "a..4", "3"] {
        let (code, out, err) = knotlab(&["demo", "--seeds", range, "--out", "/tmp/never"]);
        assert_eq!(code, 2, "{range}: {out}");
        assert!(err.contains("--seeds"), "{range}: {err}");
    }
}

/// A narrower `--snapshot-half-width` draws a different snapshot and a bad one is refused; the centreline
/// beside it classifies and draws through along the left's or assist's jaws, a bad arm or grip refused.
#[test]
fn snapshots_zoom_to_the_half_width_asked_for() {
    let dir = std::env::temp_dir().join(format!("knotlab-demo-zoom-{}", std::process::id()));
    let mut pictures = Vec::new();
    for width in ["0.08", "0.02"] {
        let out = dir.join(width);
        // The chain's scene: its centreline is the 80 segments' ends (the rope's, its particles).
        let (code, stdout, err) = knotlab(&[
            "demo",
            "--scene",
            "scenarios/chain.toml",
            "--expert",
            "scenarios/experts/base.toml",
            "--seed",
            "0",
            "--until",
            "0.3",
            "--snapshots",
            "0.2",
            "--snapshot-half-width",
            width,
            "--out",
            out.to_str().unwrap(),
        ]);
        assert_eq!(code, 0, "{stdout}{err}");
        pictures.push(std::fs::read(out.join("snapshot-0.200s.png")).expect("the snapshot was drawn"));
        // The thread's centreline beside it, one point per segment end, as `knotlab knot` reads it.
        let csv = out.join("centreline-0.200s.csv");
        let text = std::fs::read_to_string(&csv).expect("the centreline was written");
        assert_eq!(text.lines().count(), 1 + 81, "header and the 80 segments' 81 ends");
        let (code, stdout, err) = knotlab(&["knot", "classify", csv.to_str().unwrap()]);
        assert_eq!(code, 0, "{stdout}{err}");
        assert!(stdout.contains("unknot"), "no knot yet at 0.2 s: {stdout}");
        // The same snapshot with the tail drawn back along the left's jaws (the draw-through what-if).
        let dir_arg = out.to_str().unwrap();
        let draw = |grip: &str, more: &[&str]| {
            let mut args = vec!["knot", "draw-through", dir_arg, "--at", "0.2", "--grip", grip];
            args.extend_from_slice(more);
            knotlab(&args)
        };
        let (code, stdout, err) = draw("70", &["--json"]);
        assert_eq!(code, 0, "{stdout}{err}");
        let report: serde_json::Value = serde_json::from_str(&stdout).expect("JSON");
        assert_eq!(report["as_it_lies"], "unknot", "{stdout}");
        assert!(report["drawn_through"].is_string(), "{stdout}");
        // In words: both knots, and the drawn one's invariants (an `unknown` says which knot it is not).
        let (code, text, err) = draw("70", &[]);
        assert_eq!(code, 0, "{text}{err}");
        let drawn = report["drawn_through"].as_str().unwrap_or_default();
        assert!(text.contains(&format!("unknot as it lies; {drawn} (")), "{text}");
        assert!(
            text.contains(&format!("writhe {:+})", report["drawn_writhe"].as_i64().unwrap_or(i64::MAX))),
            "{text}"
        );
        // Along the assist's jaws instead (a second throw wound on them): its own pose, named.
        let (code, stdout, err) = draw("70", &["--arm", "assist", "--json"]);
        assert_eq!(code, 0, "{stdout}{err}");
        let by_assist: serde_json::Value = serde_json::from_str(&stdout).expect("JSON");
        assert_eq!((&report["arm"], &by_assist["arm"]), (&"left".into(), &"assist".into()), "{stdout}");
        let (code, text, err) = draw("70", &["--arm", "assist"]);
        assert_eq!(code, 0, "{text}{err}");
        assert!(text.contains("back along the assist's jaws from point 70"), "{text}");
        let (code, stdout, err) = draw("70", &["--arm", "camera"]);
        assert_eq!(code, 2, "{stdout}{err}");
        assert!(err.contains("--arm"), "{err}");
        let (code, stdout, err) = draw("81", &[]);
        assert_eq!(code, 1, "{stdout}{err}");
        assert!(err.contains("grip point 81 is not on the thread"), "{err}");
    }
    assert_ne!(pictures[0], pictures[1], "a narrower view draws a different picture");
    for bad in ["0", "-0.1", "2", "wide"] {
        let (code, out, err) =
            knotlab(&["demo", "--seed", "0", &format!("--snapshot-half-width={bad}"), "--out", "/tmp/never"]);
        assert_eq!(code, 2, "{bad}: {out}");
        assert!(err.contains("--snapshot-half-width"), "{bad}: {err}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// `--knot-trace P` writes knot-trace.csv with its full header and a row every P seconds without drift;
/// without the flag no trace is written, and a zero, negative or non-numeric period is refused.
#[test]
fn the_knot_trace_takes_the_knot_and_the_gauges_at_the_period_asked() {
    let out = std::env::temp_dir().join(format!("knotlab-demo-trace-{}", std::process::id()));
    let (code, stdout, err) = knotlab(&[
        "demo",
        "--seed",
        "0",
        "--until",
        "1.0",
        "--knot-trace",
        "0.25",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{stdout}{err}");
    let text = std::fs::read_to_string(out.join("knot-trace.csv")).expect("the trace was written");
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().expect("a header").split(',').collect();
    assert_eq!(
        header,
        [
            "time_s",
            "knot",
            "height_m",
            "loop_outside_m",
            "radius_m",
            "exit_leg_thread_m",
            "exit_leg_span_m",
            "entry_leg_thread_m",
            "entry_leg_span_m",
            "exit_arc_m",
            "entry_arc_m",
            "wound_gap_m",
            "left_force_n",
            "right_force_n",
            "assist_force_n",
            "long_end_on_left",
            "tail_on_left",
            "long_end_on_right",
            "tail_on_right",
            "long_end_on_assist",
            "tail_on_assist",
            "long_end_bend_rad",
            "tail_bend_rad"
        ]
    );
    let column = |name: &str| header.iter().position(|h| *h == name).unwrap_or_else(|| panic!("no {name}"));
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    let times: Vec<f64> = rows.iter().map(|r| r[column("time_s")].parse().expect("a time")).collect();
    assert_eq!(times.len(), 5, "0, 0.25, 0.5, 0.75 and 1 s, where it stops: {times:?}");
    for (k, t) in times.iter().enumerate() {
        assert!((t - 0.25 * k as f64).abs() < 0.0011, "one point every 0.25 s, no drift: {times:?}");
    }
    for r in &rows {
        assert_eq!(r[column("knot")], "unknot", "no knot in the first second: {r:?}");
        assert_eq!(r.len(), header.len(), "{r:?}");
        // The thread passes the exit before the entry, counted from the needle end.
        let exit: f64 = r[column("exit_arc_m")].parse().expect("the exit's arc");
        let entry: f64 = r[column("entry_arc_m")].parse().expect("the entry's arc");
        assert!(0.0 < exit && exit < entry, "{r:?}");
        let gap: f64 = r[column("wound_gap_m")].parse().expect("the gap");
        assert!(gap > 0.0 && gap < 0.01, "{r:?}");
    }
    // The left waits clear of the thread in the first second: nothing of either end on it.
    for r in &rows {
        for name in ["long_end_on_left", "tail_on_left"] {
            let n: usize = r[column(name)].parse().expect("a count of segments");
            assert_eq!(n, 0, "{name}: {r:?}");
        }
        for name in ["long_end_on_right", "tail_on_right", "long_end_on_assist", "tail_on_assist"] {
            let n: usize = r[column(name)].parse().expect("a count of segments");
            assert!(n <= 80, "{name}: {r:?}");
        }
    }
    let assist: Vec<f64> =
        rows.iter().map(|r| r[column("assist_force_n")].parse().expect("a force")).collect();
    assert!(assist.iter().all(|f| f.is_finite() && *f >= 0.0), "{assist:?}");
    // Not asked for, not written.
    let untraced = out.join("untraced");
    let (code, stdout, err) =
        knotlab(&["demo", "--seed", "0", "--until", "0.1", "--out", untraced.to_str().unwrap()]);
    assert_eq!(code, 0, "{stdout}{err}");
    assert!(untraced.join("left.csv").exists() && !untraced.join("knot-trace.csv").exists());
    for bad in ["0", "-1", "often"] {
        let (code, stdout, err) =
            knotlab(&["demo", "--seed", "0", &format!("--knot-trace={bad}"), "--out", "/tmp/never"]);
        assert_eq!(code, 2, "{bad}: {stdout}");
        assert!(err.contains("--knot-trace"), "{bad}: {err}");
    }
    let _ = std::fs::remove_dir_all(&out);
}

/// `--expert FILE` changes the scripted expert's plan (base.toml matches an empty file), and a file with a
/// bad key is refused, naming the file, the line and the key.
#[test]
fn the_experts_geometry_comes_from_a_file_and_a_bad_one_is_refused_naming_its_key() {
    let dir = std::env::temp_dir().join(format!("knotlab-demo-expert-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // A winding point moved 1 cm towards the tail's flap: the left goes elsewhere in the first second.
    let moved = dir.join("moved.toml");
    std::fs::write(&moved, "winding_point_m = [0.0, -0.01, 0.045]\n").unwrap();
    let left_at_1s = |expert: Option<&std::path::Path>| {
        let out = dir.join(expert.and_then(|e| e.file_stem()).unwrap_or("shipped".as_ref()));
        let mut args =
            vec!["demo", "--seed", "0", "--until", "1.0", "--json", "--out", out.to_str().unwrap()];
        if let Some(e) = expert {
            args.extend(["--expert", e.to_str().unwrap()]);
        }
        let (code, v) = json(&args);
        assert_eq!(code, 0, "{v}");
        let named =
            expert.map_or("scenarios/experts/instrument-tie.toml".into(), |e| e.display().to_string());
        assert_eq!(v["expert"], named.as_str(), "no file: the shipped plan's; {v}");
        let left = std::fs::read_to_string(out.join("left.csv")).unwrap();
        left.lines().nth(101).expect("a sample at 1 s").to_owned()
    };
    assert_ne!(left_at_1s(None), left_at_1s(Some(&moved)), "the file moved the plan");
    // The base file lists the base plan: the same recording as a file that sets nothing.
    let empty = dir.join("empty.toml");
    std::fs::write(&empty, "# nothing set\n").unwrap();
    let base = std::path::Path::new("scenarios/experts/base.toml");
    assert_eq!(left_at_1s(Some(base)), left_at_1s(Some(&empty)), "base.toml is the base plan");
    let bad = dir.join("bad.toml");
    std::fs::write(&bad, "winding_turns = 2.0\npull_force = 1.0\n").unwrap();
    let (code, out, err) =
        knotlab(&["demo", "--seed", "0", "--expert", bad.to_str().unwrap(), "--out", "/tmp/never"]);
    assert_eq!(code, 1, "{out}");
    assert!(err.contains("bad.toml:2: pull_force"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// `knotlab learn` without `--demo` reads scenarios/demos/instrument-tie, accepts it and learns every
/// primitive of the shipped pattern (L1 to L6, R2 to R5 and A1).
#[test]
fn the_learner_accepts_the_canonical_demonstration_by_default() {
    let dir = std::env::temp_dir().join(format!("knotlab-canonical-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let kb = dir.join("kb.json");
    let (code, v) = json(&["learn", "--out", kb.to_str().unwrap(), "--json"]);
    assert_eq!(code, 0, "scenarios/demos/instrument-tie is a demonstration of the task: {v}");
    assert_eq!(v["accepted"], true, "{v}");
    assert_eq!(v["demo"], "scenarios/demos/instrument-tie", "{v}");
    let names: Vec<String> = v["instruments"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|i| {
            i["primitives"].as_array().unwrap().iter().map(|p| p["name"].as_str().unwrap().to_owned())
        })
        .collect();
    for name in ["L1", "L2", "L3", "L4", "L5", "L6", "R2", "R3", "R4", "R5", "A1"] {
        assert!(names.iter().any(|n| n == name), "no {name} in {names:?}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

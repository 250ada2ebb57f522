//! `knotlab sim`: the stress sequence's figures as JSON, snapshots as PNG, clear errors.

use super::common;

use common::{json, knotlab};

/// `knotlab sim --json` on the chain scene prints every stress figure, with 400 steps, no NaN events and a
/// finite stretch.
#[test]
fn sim_json_prints_the_figures() {
    let (code, v) = json(&["sim", "--scene", "scenarios/chain.toml", "--seconds", "0.4", "--json"]);
    assert_eq!(code, 0, "{v}");
    for key in [
        "max_stretch_ratio",
        "tunnelling_events",
        "nan_events",
        "realtime_factor",
        "steps",
        "bodies",
        "instrument_contact_steps",
    ] {
        assert!(v.get(key).is_some(), "no {key} in {v}");
    }
    assert_eq!(v["steps"], 400);
    assert_eq!(v["nan_events"], 0);
    assert!(v["bodies"].as_u64().unwrap() > 40, "{v}");
    let stretch = v["max_stretch_ratio"].as_f64().unwrap();
    // A 0.4 s run squeezes the whole sequence (its moves scale with the length): no stretch bound here,
    // sim/tests bound the thread's stretch under controlled loads.
    assert!(stretch > 0.0 && stretch.is_finite(), "stretch {stretch}");
    assert!(v["realtime_factor"].as_f64().unwrap() > 0.0);
}

/// `sim --snapshot --at` writes a 1440 x 480 PNG (three views side by side) for each time asked.
#[test]
fn sim_snapshots_are_png_files() {
    let dir = std::env::temp_dir().join(format!("knotlab-snap-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let base = dir.join("scene.png");
    let (code, out, err) =
        knotlab(&["sim", "--seconds", "0.2", "--snapshot", base.to_str().unwrap(), "--at", "0,0.1"]);
    assert_eq!(code, 0, "{out}{err}");
    for name in ["scene-0.000s.png", "scene-0.100s.png"] {
        let bytes = std::fs::read(dir.join(name)).unwrap_or_else(|e| panic!("{name}: {e}\n{out}"));
        assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "{name} is not a PNG");
        // Three 480-pixel views side by side.
        assert_eq!(u32::from_be_bytes(bytes[16..20].try_into().unwrap()), 1440);
        assert_eq!(u32::from_be_bytes(bytes[20..24].try_into().unwrap()), 480);
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// An unreadable scene, a zero `--seconds` and an `--at` past the end are refused, naming the file or the
/// flag, while the nominal scene's rope steps through the stress sequence.
#[test]
fn a_bad_scene_or_time_is_refused_clearly() {
    let (code, _, err) = knotlab(&["sim", "--scene", "/nonexistent/scene.toml"]);
    assert_eq!(code, 1);
    assert!(err.contains("/nonexistent/scene.toml: cannot read"), "{err}");
    // The stress sequence runs on either suture: the nominal scene's rope steps through it too.
    let (code, out, err) = knotlab(&["sim", "--scene", "scenarios/default.toml", "--seconds", "0.1"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("100 steps"), "{out}");
    let (code, _, err) = knotlab(&["sim", "--seconds", "0"]);
    assert_eq!(code, 1);
    assert!(err.contains("--seconds"), "{err}");
    let (code, _, err) = knotlab(&["sim", "--seconds", "1", "--snapshot", "/tmp/x.png", "--at", "2"]);
    assert_eq!(code, 1);
    assert!(err.contains("--at"), "{err}");
}

/// Guards `knotlab validate`: it runs the ten experiments, names them, and each reports measured,
/// reference, tolerance and source; the exit status says whether a judged check failed; the rope's
/// bending follows the elastica.
#[test]
fn validate_reports_every_check_and_exits_by_the_judged_ones() {
    let (code, v) = json(&["validate", "--json"]);
    assert_eq!(
        v["experiments"],
        serde_json::json!([
            "material",
            "stretch",
            "cantilever",
            "capstan",
            "slide",
            "grip",
            "knot",
            "long_knot",
            "creep",
            "dynamics"
        ]),
        "{v}"
    );
    let checks = v["checks"].as_array().expect("checks");
    let experiments: std::collections::BTreeSet<&str> =
        checks.iter().filter_map(|c| c["experiment"].as_str()).collect();
    for e in [
        "material",
        "stretch",
        "cantilever_tip_load",
        "cantilever_uniform_load",
        "capstan_cylinder",
        "capstan_suture",
        "slide_on_suture",
        "knot_trefoil",
        "knot_long",
        "knot_creep",
        "dynamics",
    ] {
        assert!(experiments.contains(e), "no {e} in {v}");
    }
    for c in checks {
        assert!(c["measured"].is_number() || c["measured"].is_null(), "{c}");
        assert!(
            c["reference"].as_f64().is_some() && c["source"].as_str().is_some_and(|s| !s.is_empty()),
            "{c}"
        );
    }
    let failed = checks.iter().filter(|c| c["passed"] == false).count();
    assert_eq!(v["failed"].as_u64(), Some(failed as u64), "{v}");
    assert_eq!(code, if failed > 0 { 1 } else { 0 }, "{v}");
    let cantilever: Vec<_> = checks
        .iter()
        .filter(|c| c["experiment"].as_str().is_some_and(|e| e.starts_with("cantilever")))
        .collect();
    assert!(cantilever.len() >= 6 && cantilever.iter().all(|c| c["passed"] == true), "{v}");
}

/// Guards `knotlab validate` against checking a rope a scene does not use: a chain scene is refused,
/// naming the file and the field; an experiment `--only` does not know is refused, naming those it does.
#[test]
fn validate_refuses_a_scene_whose_suture_is_the_chain() {
    let (code, _, stderr) = knotlab(&["validate", "--suture-from", "scenarios/chain.toml"]);
    assert_ne!(code, 0);
    assert!(stderr.contains("scenarios/chain.toml") && stderr.contains("thread.model"), "{stderr}");
    let (code, _, stderr) = knotlab(&["validate", "--only", "trefoil"]);
    assert_ne!(code, 0);
    assert!(stderr.contains("trefoil") && stderr.contains("long_knot"), "{stderr}");
}

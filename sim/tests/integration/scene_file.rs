//! (g) Scene files: the shipped one loads; malformed ones give errors naming the key (and line).

use knotlab_sim::scene::{SceneError, load_scene, parse_scene};

const DEFAULT: &str = include_str!("../../../scenarios/default.toml");
/// The chain's scene: it sets neither `thread.model` nor `friction_on_itself`, which the tests below add.
const CHAIN: &str = include_str!("../../../scenarios/chain.toml");

fn err(text: &str) -> String {
    match parse_scene(text, "bad.toml") {
        Ok(_) => panic!("a malformed scene loaded"),
        Err(e) => e.to_string(),
    }
}

/// The shipped default scene loads from its file with its 80 segments and its left trocar in place.
#[test]
fn the_shipped_scene_loads() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenarios/default.toml");
    let scene = load_scene(&path).unwrap();
    assert_eq!(scene.thread.segments, 80);
    assert_eq!(scene.trocars.left, [-0.08, 0.12, 1.02]);
}

/// The rope solves its contacts with itself from either end in turn unless the scene says `false`:
/// left out, the key means both ways (the one-way solve drags a knot towards the needle end).
#[test]
fn a_rope_scene_solves_its_contacts_both_ways_unless_it_says_otherwise() {
    let key = "rope_contacts_both_ways";
    let shipped = parse_scene(DEFAULT, "default.toml").unwrap();
    assert!(shipped.thread.rope_contacts_both_ways);
    let line = DEFAULT.lines().find(|l| l.starts_with(key)).expect("the shipped scene sets it");
    let left_out = parse_scene(&DEFAULT.replace(line, ""), "left-out.toml").unwrap();
    assert!(left_out.thread.rope_contacts_both_ways);
    let one_way = parse_scene(&DEFAULT.replace(line, &format!("{key} = false")), "one-way.toml").unwrap();
    assert!(!one_way.thread.rope_contacts_both_ways);
}

/// A misspelt key is refused, not ignored, with the file, the line and the key's dotted path.
#[test]
fn an_unknown_key_is_named_with_its_path_and_line() {
    let text = DEFAULT.replace("segments = 80", "segments = 80\nsegmnets = 81");
    let e = err(&text);
    let line = text.lines().position(|l| l.starts_with("segmnets")).unwrap() + 1;
    assert!(e.starts_with(&format!("bad.toml:{line}: thread.segmnets: unknown field `segmnets`")), "{e}");
}

/// An unknown thread model is refused with the file, the line and the key, listing the models there are.
#[test]
fn an_unknown_thread_model_is_named_with_its_path_line_and_the_models() {
    let text = CHAIN.replace("segments = 80", "segments = 80\nmodel = \"ropes\"");
    let e = err(&text);
    let line = text.lines().position(|l| l.starts_with("model = ")).unwrap() + 1;
    assert!(e.starts_with(&format!("bad.toml:{line}: thread.model:")), "{e}");
    assert!(e.contains("`chain` or `rope`"), "{e}");
}

/// A key of `[thread]` the chosen suture model does not read is refused, named with its line, not
/// ignored: a rope scene's `twist_free`, a chain scene's `rope_substeps`; a chain scene without its
/// joints' damping, at its model's line (its table's, the model left to its default).
#[test]
fn a_key_of_the_other_suture_model_is_refused_with_its_line() {
    let text = DEFAULT.replace("segments = 80", "segments = 80\ntwist_free = false");
    let e = err(&text);
    let line = text.lines().position(|l| l.starts_with("twist_free")).unwrap() + 1;
    assert!(
        e.starts_with(&format!("bad.toml:{line}: thread.twist_free: only the chain model reads it")),
        "{e}"
    );
    let text = CHAIN.replace("segments = 80", "segments = 80\nrope_substeps = 3");
    let e = err(&text);
    let line = text.lines().position(|l| l.starts_with("rope_substeps")).unwrap() + 1;
    assert!(
        e.starts_with(&format!("bad.toml:{line}: thread.rope_substeps: only the rope model reads it")),
        "{e}"
    );
    let text: String = CHAIN
        .lines()
        .filter(|l| !l.starts_with("bend_damping_n_m_s_per_rad"))
        .map(|l| format!("{l}\n"))
        .collect();
    assert!(text.len() < CHAIN.len(), "the chain's scene gives its joints' damping");
    let e = err(&text);
    // At the line of the model that needs it: the chain's scene leaves it to its default, so the
    // table's.
    assert!(!text.contains("model = "), "the chain's scene names its model");
    let line = text.lines().position(|l| l.starts_with("[thread]")).unwrap() + 1;
    assert!(e.starts_with(&format!("bad.toml:{line}: thread.bend_damping_n_m_s_per_rad: missing")), "{e}");
}

/// A value of the wrong type is refused naming the key's dotted path.
#[test]
fn a_wrong_type_is_named_with_its_path() {
    let e = err(&DEFAULT.replace("segments = 80", "segments = \"eighty\""));
    assert!(e.contains("thread.segments:"), "{e}");
}

/// A scene missing the thread's friction key is refused naming the missing field.
#[test]
fn a_missing_key_is_named() {
    // The thread's own friction line (the first key `friction` in the file), whatever its value.
    let text: String =
        DEFAULT.lines().filter(|l| !l.starts_with("friction = ")).map(|l| format!("{l}\n")).collect();
    assert!(text.len() < DEFAULT.len(), "the scene has a friction line");
    let e = err(&text);
    assert!(e.contains("thread") && e.contains("missing field `friction`"), "{e}");
}

/// Every out-of-range value in a scene is reported at once, each under its own key and at its line.
#[test]
fn out_of_range_values_are_all_named() {
    let text = CHAIN
        .replace("dt_s = 0.001", "dt_s = 0.5")
        .replace(
            "segments = 80",
            "segments = 2\nfriction_on_itself = -0.5\naxial_stiffness_n = 0.0\nrope_substeps = 0\nrope_spacing_radii = 0.1\nrope_inertial_mass_kg_per_m = 0.0\nrope_constraint_passes = 0\nrope_radius_at_metal_m = 0.001",
        )
        .replace("holding_load_n = 0.3", "holding_load_n = -0.3")
        .replace("force_filter_s = 0.02", "force_filter_s = -0.02");
    let text =
        text.replacen("left = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0]", "left = [0.0, 0.0, 0.3, 0.0, 0.0, 0.0]", 1);
    match parse_scene(&text, "bad.toml") {
        Err(SceneError::Invalid { problems, .. }) => {
            let keys: Vec<&str> = problems.iter().map(|(k, _)| k.as_str()).collect();
            assert!(keys.contains(&"solver.dt_s"), "{keys:?}");
            assert!(keys.contains(&"thread.segments"), "{keys:?}");
            assert!(keys.contains(&"thread.friction_on_itself"), "{keys:?}");
            assert!(keys.contains(&"thread.axial_stiffness_n"), "{keys:?}");
            assert!(keys.contains(&"thread.rope_substeps"), "{keys:?}");
            assert!(keys.contains(&"thread.rope_spacing_radii"), "{keys:?}");
            assert!(keys.contains(&"thread.rope_inertial_mass_kg_per_m"), "{keys:?}");
            assert!(keys.contains(&"thread.rope_constraint_passes"), "{keys:?}");
            let metal = problems.iter().find(|(k, _)| k == "thread.rope_radius_at_metal_m");
            assert!(
                metal.is_some_and(|(_, why)| why.contains("thread.radius_m") && why.contains("0.001")),
                "a radius at metal above the thread's: {problems:?}"
            );
            assert!(keys.contains(&"servo.calibration_offset_rad.left[2]"), "{keys:?}");
            assert!(keys.contains(&"evaluation.holding_load_n"), "{keys:?}");
            assert!(keys.contains(&"sensor.force_filter_s"), "{keys:?}");
        }
        other => panic!("expected range errors, got {other:?}"),
    }
    let line_of = |key: &str| text.lines().position(|l| l.starts_with(key)).expect(key) + 1;
    let e = err(&text);
    for (key, at) in [("thread.rope_spacing_radii", "rope_spacing_radii ="), ("solver.dt_s", "dt_s =")] {
        let named = format!("bad.toml:{}: {key}: must be within", line_of(at));
        assert!(e.contains(&named), "{named} in {e}");
    }
    let left = line_of("left = [0.0, 0.0, 0.3");
    assert!(e.contains(&format!("bad.toml:{left}: servo.calibration_offset_rad.left[2]")), "{e}");
}

/// Randomization bounds given high before low or out of range are named by key, and a misspelt randomization
/// key is refused.
#[test]
fn bad_randomization_bounds_are_named() {
    let text = DEFAULT
        .replace("thread_friction = [0.12, 0.18]", "thread_friction = [0.18, 0.12]")
        .replace("play_rad = [0.0, 0.0005]", "play_rad = [0.0, 0.5]");
    match parse_scene(&text, "bad.toml") {
        Err(SceneError::Invalid { problems, .. }) => {
            let keys: Vec<&str> = problems.iter().map(|(k, _)| k.as_str()).collect();
            assert!(keys.contains(&"randomization.thread_friction"), "{keys:?}");
            assert!(keys.contains(&"randomization.play_rad[1]"), "{keys:?}");
        }
        other => panic!("expected range errors, got {other:?}"),
    }
    let e = err(&DEFAULT.replace(
        "stitch_z_m = [0.0, 0.0]",
        "stitch_z_m = [0.0, 0.0]
stich_w_m = [0.0, 0.0]",
    ));
    assert!(e.contains("stich_w_m"), "{e}");
}

/// A preset's bounds are checked under its name, applying it changes only what it names, and an unknown
/// preset or preset key is refused by name.
#[test]
fn presets_are_checked_applied_and_named() {
    // A preset's bounds are checked as applied, under the preset's name.
    let text = DEFAULT.replace("play_rad = [0.0005, 0.002]", "play_rad = [0.002, 0.0005]");
    match parse_scene(&text, "bad.toml") {
        Err(SceneError::Invalid { problems, .. }) => {
            let keys: Vec<&str> = problems.iter().map(|(k, _)| k.as_str()).collect();
            assert_eq!(keys, vec!["presets.endopar.play_rad"], "{problems:?}");
        }
        other => panic!("expected range errors, got {other:?}"),
    }
    let scene = parse_scene(DEFAULT, "default.toml").expect("the default scene");
    let endopar = scene.with_preset("endopar").expect("endopar");
    assert_eq!(endopar.randomization.play_rad, [0.0005, 0.002]);
    assert_eq!(endopar.randomization.calibration_rad, [-0.002, 0.002]);
    // What the preset does not name stays as declared.
    assert_eq!(endopar.randomization.stitch_x_m, scene.randomization.stitch_x_m);
    assert!(endopar.presets.is_empty());
    let ideal = scene.with_preset("ideal").expect("ideal");
    assert_eq!((ideal.randomization.play_rad, ideal.randomization.calibration_rad), ([0.0; 2], [0.0; 2]));
    let e = scene.with_preset("endopr").expect_err("no such preset").to_string();
    assert!(e.contains("presets.endopr") && e.contains("endopar, ideal"), "{e}");
    // Unknown keys in a preset are named too.
    let e = err(&DEFAULT.replace("[presets.ideal]", "[presets.ideal]\nplay = [0.0, 0.0]"));
    assert!(e.contains("play"), "{e}");
}

/// A fixed-length array given one value too many is refused with its line, its key and the counts, not
/// read as its first values with the rest dropped.
#[test]
fn an_array_of_the_wrong_length_is_named_with_its_path_and_line() {
    let text = DEFAULT.replace("stitch_x_m = [-0.01, 0.01]", "stitch_x_m = [-0.01, 0.0, 0.01]");
    let line = text.lines().position(|l| l.starts_with("stitch_x_m = [-0.01, 0.0, 0.01]")).unwrap() + 1;
    let e = err(&text);
    assert!(
        e.starts_with(&format!(
            "bad.toml:{line}: randomization.stitch_x_m: 3 values where exactly 2 are allowed"
        )),
        "{e}"
    );
}

/// A TOML syntax error is reported with the file and the line it is on.
#[test]
fn broken_toml_gives_the_line() {
    let text = DEFAULT.replace("[stitch]", "[stitch");
    let line = text.lines().position(|l| l == "[stitch").unwrap() + 1;
    let e = err(&text);
    assert!(e.starts_with(&format!("bad.toml:{line}: (syntax)")), "{e}");
}

/// A scene file that cannot be read is refused naming its path.
#[test]
fn an_unreadable_file_is_named() {
    let e = load_scene(std::path::Path::new("/nonexistent/scene.toml")).unwrap_err().to_string();
    assert!(e.starts_with("/nonexistent/scene.toml: cannot read"), "{e}");
}

/// A trocar in or under the tissue is refused at load, naming the trocar and the height it must keep
/// (the trial used to fail deep inside the kinematics with "the target, jaw direction or trocar is not
/// finite").
#[test]
fn a_trocar_inside_the_tissue_is_refused_naming_it() {
    let text = DEFAULT.replace("left = [-0.08, 0.12, 1.02]", "left = [-0.08, 0.12, 0.95]");
    let e = err(&text);
    assert!(e.contains("trocars.left: z = 0.95 m is not above the tissue"), "{e}");
    assert!(e.contains("at least 0.02 m above its top surface"), "{e}");
}

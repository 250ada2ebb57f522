//! The TOML files' parsers on mutated shipped files and raw text: the scene, the rig configs, the
//! scripted expert's tie geometry and the task pattern.

use std::sync::Arc;

use knotlab_hw::rig_config::parse_rig_config;
use knotlab_learner::pattern::parse_pattern;
use knotlab_scenarios::expert::parse_tie_geometry;
use knotlab_sim::scene::parse_scene;

use super::mutate::{mutated_text, mutated_tree, raw_text};
use super::{Outcome, cases, fuzz, isolated, outcome, shipped};

/// Fuzzes `parse` on the shipped files `paths` (each of which must parse): text mutations, tree
/// mutations and raw text, [`super::cases`] each.
pub fn fuzz_toml(name: &str, paths: &[&str], parse: impl Fn(&str) -> Outcome) {
    let seeds: Vec<Arc<str>> = paths.iter().map(|p| Arc::from(shipped(p))).collect();
    for (path, text) in paths.iter().zip(&seeds) {
        assert_eq!(parse(text), Ok(()), "the shipped {path} parses");
    }
    let trees: Vec<(Arc<str>, toml::Value)> = seeds
        .iter()
        .map(|text| (text.clone(), toml::Value::Table(text.parse::<toml::Table>().expect("TOML"))))
        .collect();
    fuzz(&format!("{name}/text"), cases(), mutated_text(seeds.clone()), |(_, text)| parse(text));
    fuzz(&format!("{name}/tree"), cases(), mutated_tree(trees), |(_, _, text)| parse(text));
    fuzz(&format!("{name}/raw"), cases(), raw_text(seeds), |text| parse(text));
}

/// The scene parser never panics on a mutated `scenarios/default.toml` or on raw text, and names
/// what it refuses.
#[test]
fn scene_parser_survives_mutated_and_random_input() {
    isolated(|| {
        fuzz_toml("scene", &["scenarios/default.toml"], |text| outcome(parse_scene(text, "scene.toml")));
    });
}

/// The rig config parser never panics on a mutated shipped rig (simulated, gamepad, MELFA, the lab's
/// with CANopen drives and Net F/T sensors) or on raw text, and names what it refuses.
#[test]
fn rig_config_parser_survives_mutated_and_random_input() {
    isolated(|| {
        fuzz_toml(
            "rig-config",
            &[
                "scenarios/rigs/sim.toml",
                "scenarios/rigs/sim-gamepad.toml",
                "scenarios/rigs/melfa.toml",
                "scenarios/rigs/lab.toml",
            ],
            |text| outcome(parse_rig_config(text, "rig.toml")),
        );
    });
}

/// The tie geometry parser never panics on a mutated shipped expert plan (the shipped plan and the
/// base plan with every key) or on raw text, and names what it refuses.
#[test]
fn tie_geometry_parser_survives_mutated_and_random_input() {
    isolated(|| {
        fuzz_toml(
            "tie-geometry",
            &["scenarios/experts/instrument-tie.toml", "scenarios/experts/base.toml"],
            |text| outcome(parse_tie_geometry(text, "expert.toml")),
        );
    });
}

/// The task pattern parser never panics on a mutated `scenarios/patterns/knot_tying.toml` or on raw
/// text, and names what it refuses.
#[test]
fn pattern_parser_survives_mutated_and_random_input() {
    isolated(|| {
        fuzz_toml("pattern", &["scenarios/patterns/knot_tying.toml"], |text| {
            outcome(parse_pattern(text, "pattern.toml"))
        });
    });
}

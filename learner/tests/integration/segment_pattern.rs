//! The task-pattern format: the shipped knot-tying pattern parses into the canonical task, and a
//! malformed pattern file gives an error naming the line and the field.

use std::path::Path;

use knotlab_hw::rig::ArmName;
use knotlab_learner::features::FeatureKind;
use knotlab_learner::pattern::{PatternError, PrimitiveType, load_pattern, parse_pattern};

fn shipped_text() -> String {
    std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenarios/patterns/knot_tying.toml"),
    )
    .expect("read the shipped pattern")
}

/// The shipped pattern with `old` replaced by `new` (which must occur).
fn edited(old: &str, new: &str) -> String {
    let text = shipped_text();
    assert!(text.contains(old), "the shipped pattern has no '{old}'");
    text.replacen(old, new, 1)
}

/// The 1-based line of the first occurrence of `needle` in `text`.
fn line_of(text: &str, needle: &str) -> usize {
    text.lines().position(|l| l.contains(needle)).expect("needle present") + 1
}

fn error(text: &str) -> PatternError {
    parse_pattern(text, "p.toml").expect_err("a malformed pattern must be refused")
}

/// The shipped knot-tying pattern parses into the canonical task's primitives for each instrument, with
/// two loops, and its elements keep their source lines.
#[test]
fn the_shipped_pattern_is_the_canonical_task() {
    let p =
        load_pattern(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenarios/patterns/knot_tying.toml"))
            .unwrap();
    let names = |arm| -> Vec<(String, PrimitiveType)> {
        p.instrument(arm).unwrap().primitives.iter().map(|s| (s.name.clone(), s.kind)).collect()
    };
    assert_eq!(
        names(ArmName::Left),
        vec![
            ("L1".to_owned(), PrimitiveType::Linear),
            ("L2".to_owned(), PrimitiveType::Synchronized),
            ("L3".to_owned(), PrimitiveType::Linear),
            ("L4".to_owned(), PrimitiveType::Linear),
            ("L5".to_owned(), PrimitiveType::Linear),
            ("L6".to_owned(), PrimitiveType::Linear)
        ]
    );
    assert_eq!(
        names(ArmName::Right),
        vec![
            ("R2".to_owned(), PrimitiveType::TwoD),
            ("R3".to_owned(), PrimitiveType::Linear),
            ("R4".to_owned(), PrimitiveType::Linear),
            ("R5".to_owned(), PrimitiveType::Force)
        ]
    );
    assert_eq!(names(ArmName::Assist), vec![("A1".to_owned(), PrimitiveType::Linear)]);
    let loops =
        p.instrument(ArmName::Right).unwrap().elements.iter().filter(|e| e.kind == FeatureKind::Loop).count();
    assert_eq!(loops, 2, "a surgeon's knot winds twice");
    let text = shipped_text();
    let l3_open = p.instrument(ArmName::Left).unwrap().elements.iter().find(|e| e.id == "L3_open").unwrap();
    assert_eq!(l3_open.line, line_of(&text, "id = \"L3_open\"") - 1, "elements remember their line");
}

/// Each malformed pattern edit (unknown kind or type, bad version, negative magnitude, dangling
/// reference, duplicate id, unknown field, ...) is refused naming its line, field and reason.
#[test]
fn malformed_patterns_are_named_by_line_and_field() {
    // (edit: old, new; the line to expect: a needle on it; the field; a part of the reason)
    let cases: [(&str, &str, &str, &str, &str); 10] = [
        (
            "kind = \"loop\"",
            "kind = \"lop\"",
            "kind = \"lop\"",
            "right.feature[1].kind",
            "unknown feature kind 'lop'",
        ),
        ("format_version = 1", "format_version = 3", "format_version = 3", "format_version", "not supported"),
        (
            "min_magnitude = 0.12",
            "min_magnitude = -0.12",
            "min_magnitude = -0.12",
            "right.feature[9].min_magnitude",
            ">= 0",
        ),
        (
            "after = [\"R2_stop\"]",
            "after = [\"R9_stop\"]",
            "after = [\"R9_stop\"]",
            "left.feature[2].after",
            "no feature has the id 'R9_stop'",
        ),
        (
            "from = \"L1_start\"",
            "from = \"L1_begin\"",
            "from = \"L1_begin\"",
            "left.primitive[0].from",
            "'L1_begin' is no feature of left",
        ),
        (
            "type = \"2d\"",
            "type = \"3d\"",
            "type = \"3d\"",
            "right.primitive[0].type",
            "unknown primitive type '3d'",
        ),
        (
            "reference = \"R2\"",
            "reference = \"L1\"",
            "reference = \"L1\"",
            "left.primitive[1].reference",
            "another instrument's 2d primitive",
        ),
        (
            "grasp = \"holding\"",
            "grasp = \"held\"",
            "grasp = \"held\"",
            "left.feature[7].grasp",
            "not one of open, holding, closed_empty",
        ),
        (
            "id = \"R2_loop2\"",
            "id = \"R2_loop1\"",
            "id = \"R2_loop1\"\nkind = \"loop\"",
            "right.feature[2].id",
            "already an id",
        ),
        (
            "description = \"the left starts towards the winding point\"",
            "descripton = \"x\"",
            "descripton",
            "left.feature[0].descripton",
            "unknown field",
        ),
    ];
    for (old, new, needle, field, reason) in cases {
        let text = edited(old, new);
        let e = error(&text);
        let message = e.to_string();
        let expected_line = if needle.contains('\n') {
            // A needle spanning lines: the line of its first part, at its second occurrence.
            let first = needle.lines().next().unwrap();
            text.lines().enumerate().filter(|(_, l)| l.contains(first)).nth(1).unwrap().0 + 1
        } else {
            line_of(&text, needle)
        };
        assert_eq!(e.line(), expected_line, "line for '{new}': {message}");
        assert_eq!(e.field(), field, "field for '{new}': {message}");
        assert!(message.contains(reason), "reason for '{new}' should say '{reason}': {message}");
        assert!(message.starts_with(&format!("p.toml:{expected_line}: {field}: ")), "{message}");
    }
}

/// A backwards span, a cycle of `after`s, a syntax error, an unknown instrument, a bad threshold, a file
/// that is not a pattern and a missing file are each refused naming what is wrong.
#[test]
fn structural_mistakes_are_refused() {
    // A span that runs backwards.
    let e = error(&edited("from = \"L3_start\"\nto = \"L3_stop\"", "from = \"L3_stop\"\nto = \"L3_start\""));
    assert_eq!(e.field(), "left.primitive[2].to", "{e}");
    assert!(e.line() > 0);

    // `after` references that go round in a circle.
    let text = edited("description = \"the left starts towards the winding point\"", "after = [\"R2_stop\"]");
    let e = error(&text);
    assert!(e.to_string().contains("cycle"), "{e}");
    assert!(e.field().ends_with(".after"), "{e}");

    // A syntax error.
    let e = error(&edited("name = \"L1\"", "name = \"L1"));
    assert_eq!(e.field(), "(syntax)", "{e}");
    assert_eq!(e.line(), line_of(&shipped_text(), "name = \"L1\""), "{e}");

    // An unknown instrument.
    let e = error(&edited("[[assist.feature]]", "[[camera.feature]]"));
    assert!(e.to_string().contains("camera"), "{e}");
    assert!(e.line() > 0, "{e}");

    // A detector threshold out of range.
    let e = error(&edited("force_onset_n = 0.12", "force_onset_n = -1.0"));
    assert_eq!(e.field(), "detector.force_onset_n", "{e}");

    // Not a pattern at all.
    let e = error("format = \"knotlab-demonstration\"\nformat_version = 1\n");
    assert_eq!((e.line(), e.field()), (1, "format"), "{e}");

    // A file that is not there.
    let e = load_pattern(Path::new("/no/such/pattern.toml")).unwrap_err();
    assert!(e.to_string().contains("/no/such/pattern.toml: cannot read"), "{e}");
}

/// Detector thresholds set in a pattern are used, and any it leaves out keep their defaults.
#[test]
fn detector_thresholds_can_be_set_in_the_pattern() {
    // The shipped pattern sets the force thresholds; a key it leaves out keeps its default.
    let shipped =
        load_pattern(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenarios/patterns/knot_tying.toml"))
            .unwrap();
    assert_eq!(shipped.detector.force_onset_n, 0.12);
    let text = edited("force_onset_n = 0.12", "force_onset_n = 0.3\nloop_turns = 0.9");
    let p = parse_pattern(&text, "p.toml").unwrap();
    assert_eq!(p.detector.force_onset_n, 0.3);
    assert_eq!(p.detector.loop_turns, 0.9);
    assert_eq!(p.detector.smoothing_s, knotlab_learner::features::DetectorParams::default().smoothing_s);
}

//! Each kind of malformed demonstration is refused with an error naming the file, the line and the
//! field: a truncated file, a missing column, NaN, time that does not increase, a wrong version, and
//! more (wrong units, an unknown key, a bad grasp word, a non-unit quaternion, a gap, a missing file).

use std::path::{Path, PathBuf};

use knotlab_learner::demonstration::metadata::parse_metadata;
use knotlab_learner::demonstration::{DemoError, load_demonstration, write_demonstration};
use knotlab_learner::synthetic::{SyntheticSettings, canonical_demonstration};

struct TempDir(PathBuf);

impl TempDir {
    /// A directory holding a freshly written valid demonstration.
    fn with_demo(name: &str) -> Self {
        let dir = std::env::temp_dir().join(format!("knotlab-demo-malformed-{name}-{}", std::process::id()));
        std::fs::remove_dir_all(&dir).ok();
        let (demo, _) = canonical_demonstration(&SyntheticSettings::canonical(11, 100.0));
        write_demonstration(&dir, &demo).expect("write the valid demonstration");
        Self(dir)
    }

    fn edit(&self, file: &str, f: impl FnOnce(String) -> String) {
        let path = self.0.join(file);
        let text = std::fs::read_to_string(&path).expect("read");
        std::fs::write(&path, f(text)).expect("write");
    }

    fn load_error(&self) -> DemoError {
        load_demonstration(&self.0).expect_err("the malformed demonstration must be refused")
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        std::fs::remove_dir_all(&self.0).ok();
    }
}

/// Replaces line `n` (1-based) of a text.
fn replace_line(text: &str, n: usize, f: impl FnOnce(&str) -> String) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
    lines[n - 1] = f(&lines[n - 1]);
    lines.join("\n") + "\n"
}

/// Sets field `index` (0-based) of line `n` (1-based) of a text to `value`.
fn replace_field(text: &str, n: usize, index: usize, value: &str) -> String {
    replace_line(text, n, |l| {
        let mut fields: Vec<String> = l.split(',').map(str::to_owned).collect();
        fields[index] = value.to_owned();
        fields.join(",")
    })
}

fn assert_names(error: &DemoError, file_suffix: &str, line: usize, field: &str, reason_part: &str) {
    let text = error.to_string();
    assert!(error.file().ends_with(file_suffix), "file: {text}");
    assert_eq!(error.line(), line, "line: {text}");
    assert_eq!(error.field(), field, "field: {text}");
    assert!(text.contains(reason_part), "reason should say '{reason_part}': {text}");
    assert!(
        text.contains(&format!("{file_suffix}:{line}: {field}:")),
        "message names file:line: field: {text}"
    );
}

/// A freshly written valid demonstration loads, so each refusal here comes from its edit alone.
#[test]
fn the_valid_demonstration_loads() {
    let dir = TempDir::with_demo("valid");
    load_demonstration(&dir.0).unwrap();
}

/// A CSV file cut off inside a row is refused as truncated, naming that row's line and the column cut (`qx`).
#[test]
fn a_file_cut_inside_a_row_is_truncated_at_that_line_and_field() {
    let dir = TempDir::with_demo("cut-row");
    let mut last_line = 0;
    dir.edit("right.csv", |text| {
        // Cut the text in the middle of its 300th row, inside the `qx` column.
        let start: usize = text.lines().take(300).map(|l| l.len() + 1).sum();
        let row = text[start..].lines().next().unwrap();
        let cut = start + row.match_indices(',').nth(3).unwrap().0 + 3;
        last_line = 301;
        text[..cut].to_owned()
    });
    let error = dir.load_error();
    assert_names(&error, "right.csv", last_line, "qx", "truncated");
}

/// A CSV file missing its last 25 rows is refused as truncated at the line after the last one kept.
#[test]
fn a_file_missing_its_last_rows_is_truncated() {
    let dir = TempDir::with_demo("cut-rows");
    let mut kept = 0;
    dir.edit("left.csv", |text| {
        let lines: Vec<&str> = text.lines().collect();
        kept = lines.len() - 25;
        lines[..kept].join("\n") + "\n"
    });
    let error = dir.load_error();
    assert_names(&error, "left.csv", kept + 1, "(rows)", "truncated");
}

/// A CSV file without its `jaw_rad` column is refused as a missing column, named on the header line.
#[test]
fn a_missing_column_is_named_on_the_header_line() {
    let dir = TempDir::with_demo("column");
    dir.edit("assist.csv", |text| {
        text.lines()
            .map(|l| {
                let mut fields: Vec<&str> = l.split(',').collect();
                fields.remove(8); // jaw_rad
                fields.join(",")
            })
            .collect::<Vec<_>>()
            .join("\n")
            + "\n"
    });
    assert_names(&dir.load_error(), "assist.csv", 1, "jaw_rad", "missing column");
}

/// A demonstration row with a NaN force is refused naming its file, line and column (`fy_n`), not loaded.
#[test]
fn nan_is_named_with_its_line_and_column() {
    let dir = TempDir::with_demo("nan");
    dir.edit("left.csv", |text| replace_field(&text, 77, 11, "NaN")); // fy_n
    assert_names(&dir.load_error(), "left.csv", 77, "fy_n", "NaN");
}

/// A word where a number belongs is refused naming its line, its column (`z_m`) and the text.
#[test]
fn a_word_for_a_number_is_named_with_its_line_column_and_text() {
    let dir = TempDir::with_demo("word");
    dir.edit("right.csv", |text| replace_field(&text, 40, 3, "deep")); // z_m
    assert_names(&dir.load_error(), "right.csv", 40, "z_m", "not a number: 'deep'");
}

/// A blank line among the rows is refused with its line, not passed over as the CSV reader would:
/// the rows after it would then be counted one line short of where they are.
#[test]
fn a_blank_line_is_refused_with_its_line() {
    let dir = TempDir::with_demo("blank");
    dir.edit("assist.csv", |text| replace_line(&text, 12, |_| String::new()));
    assert_names(&dir.load_error(), "assist.csv", 12, "(row)", "empty line");
}

/// A row whose time does not increase on the row before is refused naming its line and `time_s`.
#[test]
fn time_going_back_is_named_with_its_line() {
    let dir = TempDir::with_demo("time");
    dir.edit("right.csv", |text| {
        let previous_time: String = text.lines().nth(48).unwrap().split(',').next().unwrap().to_owned();
        replace_line(&text, 50, |l| {
            let rest = l.split_once(',').unwrap().1;
            format!("{previous_time},{rest}")
        })
    });
    assert_names(&dir.load_error(), "right.csv", 50, "time_s", "time must increase");
}

/// A `format_version` of 2 is refused as unsupported, naming its line in `demo.toml`.
#[test]
fn a_wrong_version_is_refused_naming_its_line() {
    let dir = TempDir::with_demo("version");
    let mut line = 0;
    dir.edit("demo.toml", |text| {
        line = text.lines().position(|l| l.starts_with("format_version")).unwrap() + 1;
        text.replace("format_version = 1", "format_version = 2")
    });
    assert_names(&dir.load_error(), "demo.toml", line, "format_version", "version 2 is not supported");
}

/// Wrong units, an unknown key, an unknown grasp word, a non-unit quaternion, a gap, text for a number,
/// a missing instrument file and a missing directory are each refused naming where they are.
#[test]
fn other_malformations_are_named_too() {
    // Units other than the format's.
    let dir = TempDir::with_demo("units");
    dir.edit("demo.toml", |text| text.replace("position = \"m\"", "position = \"mm\""));
    let error = dir.load_error();
    assert_eq!(error.field(), "units.position", "{error}");
    assert!(error.line() > 0, "{error}");

    // An unknown key.
    let dir = TempDir::with_demo("key");
    dir.edit("demo.toml", |text| text.replace("sample_rate_hz", "sample_rate_hz = 100.0\nsample_rte_hz"));
    let error = dir.load_error();
    assert!(error.to_string().contains("sample_rte_hz"), "{error}");
    assert!(error.line() > 0, "{error}");

    // Seeds that are no seed: negative, a word, past 2^64 - 1, a float, an empty string.
    for bad in ["-3", "\"7a\"", "\"18446744073709551616\"", "7.0", "\"\""] {
        let dir = TempDir::with_demo("seed");
        dir.edit("demo.toml", |text| {
            let at = text.find("\nseed = ").expect("the demonstration has a seed") + 1;
            let end = at + text[at..].find('\n').unwrap();
            format!("{}seed = {bad}{}", &text[..at], &text[end..])
        });
        let error = dir.load_error();
        assert_eq!(error.field(), "seed", "{bad}: {error}");
        assert!(error.line() > 0 && error.to_string().contains("0 to 2^64 - 1"), "{bad}: {error}");
    }

    // A grasp state that is none of the three.
    let dir = TempDir::with_demo("grasp");
    dir.edit("left.csv", |text| replace_line(&text, 12, |l| l.replace("closed_empty", "shut")));
    assert_names(&dir.load_error(), "left.csv", 12, "grasp", "not one of open, holding, closed_empty");

    // A quaternion that is not a rotation.
    let dir = TempDir::with_demo("quaternion");
    dir.edit("left.csv", |text| replace_field(&text, 20, 7, "3.0")); // qw
    assert_names(&dir.load_error(), "left.csv", 20, "qx,qy,qz,qw", "not a unit quaternion");

    // A gap in the recording.
    let dir = TempDir::with_demo("gap");
    dir.edit("assist.csv", |text| {
        let lines: Vec<&str> = text.lines().collect();
        let mut kept: Vec<&str> = lines[..100].to_vec();
        kept.extend(&lines[130..]);
        kept.join("\n") + "\n"
    });
    dir.edit("demo.toml", |text| {
        let n = text.matches("samples = ").count();
        assert_eq!(n, 3);
        // The assist is the third instrument: its count drops by 30.
        let at = text.rfind("samples = ").unwrap();
        let count: usize = text[at + 10..].trim().parse().unwrap();
        format!("{}samples = {}\n", &text[..at], count - 30)
    });
    assert_names(&dir.load_error(), "assist.csv", 101, "time_s", "gap");

    // A text field where a number belongs.
    let dir = TempDir::with_demo("number");
    dir.edit("right.csv", |text| replace_line(&text, 3, |l| l.replacen(',', ",abc", 1)));
    let error = dir.load_error();
    assert_eq!((error.line(), error.field()), (3, "x_m"), "{error}");

    // A missing instrument file.
    let dir = TempDir::with_demo("file");
    std::fs::remove_file(dir.0.join("right.csv")).unwrap();
    let error = dir.load_error();
    assert!(error.file().ends_with("right.csv") && error.to_string().contains("cannot read"), "{error}");

    // Not a directory.
    let error = load_demonstration(Path::new("/definitely/not/here")).unwrap_err();
    assert!(error.file().ends_with("demo.toml"), "{error}");
}

/// A tip 1000 km away (one sample's `x_m` 1e6 m, which asked the features for 24 GB) is refused
/// naming its line and column, before anything is resampled along the path.
#[test]
fn a_tip_beyond_the_workspace_is_named_with_its_line_and_column() {
    let dir = TempDir::with_demo("far");
    dir.edit("left.csv", |text| replace_field(&text, 50, 1, "1e6")); // x_m
    assert_names(&dir.load_error(), "left.csv", 50, "x_m", "beyond the workspace");
}

/// A tip that jumps 1 m between two samples 10 ms apart (100 m/s) is refused naming the line it jumped
/// to.
#[test]
fn a_tip_jumping_faster_than_a_hand_moves_is_named_with_its_line() {
    let dir = TempDir::with_demo("jump");
    dir.edit("right.csv", |text| {
        let row = text.lines().nth(59).unwrap().to_owned();
        let y: f64 = row.split(',').nth(2).unwrap().parse().unwrap();
        replace_field(&text, 60, 2, &(y + 1.0).to_string()) // y_m
    });
    assert_names(&dir.load_error(), "right.csv", 60, "x_m,y_m,z_m", "m/s since the previous sample");
}

/// A stitch position given four numbers is refused with its line, field and the counts, not read as its
/// first three.
#[test]
fn a_stitch_position_of_four_numbers_is_refused_with_its_line() {
    let shipped = include_str!("../../../scenarios/demos/instrument-tie/demo.toml");
    parse_metadata(shipped, "demo.toml").expect("the shipped demo.toml");
    let text = shipped.replace("position_m = [0.0, 0.0, 0.95]", "position_m = [0.0, 0.0, 0.95, 1.0]");
    let line = text.lines().position(|l| l.starts_with("position_m = [0.0, 0.0, 0.95, 1.0]")).unwrap() + 1;
    let error = parse_metadata(&text, "demo.toml").expect_err("four numbers for a position");
    assert_names(&error, "demo.toml", line, "stitch.position_m", "4 values where exactly 3 are allowed");
}

/// A missing key is reported at the header of the table it belongs in (it was reported at line 0, as
/// `demo.toml:0:`), and a missing top-level key at the file's first line.
#[test]
fn a_missing_key_is_reported_at_its_tables_header_or_without_a_line() {
    let shipped = include_str!("../../../scenarios/demos/instrument-tie/demo.toml");
    let text = shipped.replace("quaternion_xyzw = [0.0, 0.0, 0.0, 1.0]\n", "");
    let line = text.lines().position(|l| l == "[stitch]").unwrap() + 1;
    let error = parse_metadata(&text, "demo.toml").expect_err("no stitch orientation");
    assert_names(&error, "demo.toml", line, "stitch", "missing field `quaternion_xyzw`");
    let text = shipped.replace("sample_rate_hz = 100.0\n", "");
    let message = parse_metadata(&text, "demo.toml").expect_err("no sample rate").to_string();
    assert!(message.starts_with("demo.toml:1: (top level): missing field `sample_rate_hz`"), "{message}");
}

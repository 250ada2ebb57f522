//! A demonstration written and loaded again is the same data, bit for bit, at 100 Hz and at 1 kHz;
//! data the loader would refuse is refused before anything is written.

use std::path::PathBuf;

use nalgebra::Vector3;

use knotlab_learner::demonstration::{
    Demonstration, GraspState, load_demonstration, metadata::METADATA_FILE, write_demonstration,
};
use knotlab_learner::synthetic::{SyntheticSettings, canonical_demonstration};

struct TempDir(PathBuf);

impl TempDir {
    fn new(name: &str) -> Self {
        let dir = std::env::temp_dir().join(format!("knotlab-demo-roundtrip-{name}-{}", std::process::id()));
        std::fs::remove_dir_all(&dir).ok();
        Self(dir)
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        std::fs::remove_dir_all(&self.0).ok();
    }
}

fn demo(seed: u64, rate_hz: f64) -> Demonstration {
    canonical_demonstration(&SyntheticSettings::canonical(seed, rate_hz)).0
}

/// A demonstration written and loaded back is identical bit for bit at 100 Hz and 1 kHz, and its
/// directory holds `demo.toml` and one CSV file per instrument.
#[test]
fn record_save_load_gives_identical_data_at_100_hz_and_1_khz() {
    for (seed, rate) in [(3, 100.0), (4, 1000.0)] {
        let original = demo(seed, rate);
        let dir = TempDir::new(&format!("{rate}"));
        write_demonstration(&dir.0, &original).unwrap();
        let loaded = load_demonstration(&dir.0).unwrap();
        assert_eq!(loaded, original, "round trip at {rate} Hz");
        // Bit for bit, not just equal within a tolerance (PartialEq on f64 is exact, but say it).
        let (a, b) = (&loaded.instruments[1].samples[123], &original.instruments[1].samples[123]);
        assert_eq!(a.position_m.x.to_bits(), b.position_m.x.to_bits());
        assert_eq!(a.force_n.z.to_bits(), b.force_n.z.to_bits());
        let files: Vec<String> = std::fs::read_dir(&dir.0)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        for name in ["demo.toml", "left.csv", "right.csv", "assist.csv"] {
            assert!(files.contains(&name.to_owned()), "{name} missing from {files:?}");
        }
    }
}

/// Every grasp state, negative zero, subnormal and huge numbers, and a description with quotes and a
/// newline survive a write and load unchanged.
#[test]
fn every_grasp_state_and_extreme_numbers_survive_the_round_trip() {
    let mut d = demo(5, 100.0);
    let samples = &mut d.instruments[0].samples;
    samples[10].grasp = GraspState::Open;
    samples[11].grasp = GraspState::Holding;
    samples[12].grasp = GraspState::ClosedEmpty;
    samples[13].force_n = Vector3::new(1e-300, -0.0, 123_456_789.123_456_78);
    // The left's tip held at one extreme point throughout (a tip jumping there in one sample moves
    // faster than a hand, and is refused).
    for s in samples.iter_mut() {
        s.position_m = Vector3::new(0.1 + 0.2, -1e-17, 5e-324);
    }
    d.metadata.description = "quotes \" and a\nnewline".to_owned();
    d.metadata.scene = "scenarios/default.toml".to_owned();
    d.metadata.seed = Some(i64::MAX as u64);
    let dir = TempDir::new("extremes");
    write_demonstration(&dir.0, &d).unwrap();
    let loaded = load_demonstration(&dir.0).unwrap();
    assert_eq!(loaded, d);
    assert_eq!(loaded.instruments[0].samples[13].force_n.y.to_bits(), (-0.0f64).to_bits());
}

/// A seed beyond TOML's integers (a Monte Carlo trial's draw, any `u64`) is written as a string of
/// digits and reads back to the same seed; one that fits stays an integer.
#[test]
fn a_seed_beyond_toml_integers_survives_the_round_trip() {
    for (seed, written) in [
        (u64::MAX, "seed = \"18446744073709551615\""),
        (i64::MAX as u64 + 1, "seed = \"9223372036854775808\""),
        (7, "seed = 7"),
    ] {
        let mut d = demo(5, 100.0);
        d.metadata.seed = Some(seed);
        let dir = TempDir::new("big-seed");
        write_demonstration(&dir.0, &d).unwrap();
        let text = std::fs::read_to_string(dir.0.join(METADATA_FILE)).unwrap();
        assert!(text.lines().any(|l| l == written), "{written} in:\n{text}");
        assert_eq!(load_demonstration(&dir.0).unwrap().metadata.seed, Some(seed));
    }
}

/// Writing a demonstration with a NaN, a time that does not increase or a wrong sample rate is refused
/// naming the file, line and field, before anything is written.
#[test]
fn writing_refuses_what_loading_would_refuse_and_writes_nothing() {
    let mut d = demo(6, 100.0);
    d.instruments[2].samples[40].force_n.y = f64::NAN;
    let dir = TempDir::new("refused");
    let error = write_demonstration(&dir.0, &d).unwrap_err();
    assert_eq!(error.file(), "assist.csv");
    assert_eq!(error.line(), 42, "sample 40 is on line 42: {error}");
    assert_eq!(error.field(), "fy_n");
    assert!(!dir.0.join(METADATA_FILE).exists(), "nothing written");

    let mut d = demo(6, 100.0);
    d.instruments[0].samples[7].time_s = d.instruments[0].samples[6].time_s;
    let error = write_demonstration(&dir.0, &d).unwrap_err();
    assert_eq!((error.file(), error.line(), error.field()), ("left.csv", 9, "time_s"), "{error}");

    let mut d = demo(6, 100.0);
    d.metadata.sample_rate_hz = 50.0;
    let error = write_demonstration(&dir.0, &d).unwrap_err();
    assert_eq!((error.file(), error.field()), ("demo.toml", "sample_rate_hz"), "{error}");
}

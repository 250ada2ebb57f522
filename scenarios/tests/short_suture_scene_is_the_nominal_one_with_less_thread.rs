//! `scenarios/short-suture.toml` is the nominal scene with a shorter suture, nothing else changed,
//! so that runs on it compare with the nominal scene's on the thread's length alone.

use knotlab_sim::scene::parse_scene;

#[test]
fn the_short_suture_scene_differs_from_the_nominal_one_only_in_the_thread_length() {
    let nominal = parse_scene(include_str!("../default.toml"), "default.toml").expect("the shipped scene");
    let mut short = parse_scene(include_str!("../short-suture.toml"), "short-suture.toml")
        .expect("the short-suture scene");
    // The same segment length: the thread is cut shorter, not made coarser.
    let segment_m = |length_m: f64, segments: usize| length_m / segments as f64;
    assert!(
        (segment_m(short.thread.length_m, short.thread.segments)
            - segment_m(nominal.thread.length_m, nominal.thread.segments))
        .abs()
            < 1e-4,
        "{} m in {} segments against {} m in {}",
        short.thread.length_m,
        short.thread.segments,
        nominal.thread.length_m,
        nominal.thread.segments
    );
    assert!(short.thread.length_m < nominal.thread.length_m - 0.04);
    short.thread.length_m = nominal.thread.length_m;
    short.thread.segments = nominal.thread.segments;
    assert_eq!(short, nominal, "every other setting as in default.toml");
}

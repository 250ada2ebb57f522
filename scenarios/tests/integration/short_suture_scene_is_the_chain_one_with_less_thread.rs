//! `scenarios/short-suture.toml` is the chain scene (`scenarios/chain.toml`, the nominal scene with the
//! capsule chain) with a shorter suture, nothing else changed, so that runs on it compare with the
//! chain scene's on the thread's length alone.
//! `scenarios/short-suture-friction-0.5.toml` is that scene with the thread's friction on itself
//! raised to where two throws hold (the expert's second throw is worked out on it).

use knotlab_sim::scene::parse_scene;

/// `short-suture.toml` differs from `chain.toml` only in a shorter thread cut at the same segment length.
#[test]
fn the_short_suture_scene_differs_from_the_chain_one_only_in_the_thread_length() {
    let chain = parse_scene(include_str!("../../chain.toml"), "chain.toml").expect("the chain scene");
    let mut short = parse_scene(include_str!("../../short-suture.toml"), "short-suture.toml")
        .expect("the short-suture scene");
    // The same segment length: the thread is cut shorter, not made coarser.
    let segment_m = |length_m: f64, segments: usize| length_m / segments as f64;
    assert!(
        (segment_m(short.thread.length_m, short.thread.segments)
            - segment_m(chain.thread.length_m, chain.thread.segments))
        .abs()
            < 1e-4,
        "{} m in {} segments against {} m in {}",
        short.thread.length_m,
        short.thread.segments,
        chain.thread.length_m,
        chain.thread.segments
    );
    assert!(short.thread.length_m < chain.thread.length_m - 0.04);
    short.thread.length_m = chain.thread.length_m;
    short.thread.segments = chain.thread.segments;
    assert_eq!(short, chain, "every other setting as in chain.toml");
}

/// `short-suture-friction-0.5.toml` differs from `short-suture.toml` only in the thread's friction on itself.
#[test]
fn the_two_throw_scene_is_the_short_suture_one_with_more_friction_on_itself() {
    let short = parse_scene(include_str!("../../short-suture.toml"), "short-suture.toml")
        .expect("the short-suture scene");
    let mut sticky =
        parse_scene(include_str!("../../short-suture-friction-0.5.toml"), "short-suture-friction-0.5.toml")
            .expect("the two-throw scene");
    assert_eq!(short.thread.friction_on_itself, None, "short-suture.toml: one friction for all");
    assert_eq!(sticky.thread.friction_on_itself, Some(0.5));
    sticky.thread.friction_on_itself = None;
    assert_eq!(sticky, short, "every other setting as in short-suture.toml");
}

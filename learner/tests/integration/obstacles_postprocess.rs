//! The fluid rules on obstacle masks: every blocked cell ends with two direct blocked neighbours and
//! no fluid on two opposite sides; the mask only grows, and a mask that obeys already is left alone.

use knotlab_learner::obstacles::ObstacleMask;
use knotlab_learner::obstacles::postprocess::{apply_fluid_rules, fluid_rule_violations};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn mask(rows: &[&str]) -> ObstacleMask {
    let n = rows.len();
    let mut m = ObstacleMask::free(n);
    // Rows as drawn: the first string is the top row (largest j).
    for (r, row) in rows.iter().enumerate() {
        for (i, c) in row.chars().enumerate() {
            m.set(i, n - 1 - r, c == '#');
        }
    }
    m
}

/// The fluid rules grow a lone cell and a corner cell to 2 x 2 blocks and double a one-cell wall, no more.
#[test]
fn lone_cells_and_thin_walls_grow() {
    let lone = mask(&["....", ".#..", "....", "...."]);
    assert_eq!(fluid_rule_violations(&lone), vec![(1, 2)]);
    let fixed = apply_fluid_rules(&lone);
    assert!(fluid_rule_violations(&fixed).is_empty());
    assert_eq!(fixed.count_blocked(), 4);
    assert!(fixed.get(1, 2));

    let wall = mask(&[".#...", ".#...", ".#...", ".#...", ".#..."]);
    assert!(!fluid_rule_violations(&wall).is_empty(), "a one-cell wall has fluid on both sides");
    let fixed = apply_fluid_rules(&wall);
    assert!(fluid_rule_violations(&fixed).is_empty());
    assert_eq!(fixed.count_blocked(), 10, "the wall is doubled, no more");

    let corner = mask(&["....", "....", "....", "#..."]);
    let fixed = apply_fluid_rules(&corner);
    assert_eq!(fixed, mask(&["....", "....", "##..", "##.."]));
}

/// On random masks the fluid rules leave no violation, never free a blocked cell, and leave an obeying
/// mask alone.
#[test]
fn random_masks_obey_after_growing_and_only_grow() {
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    for _ in 0..300 {
        let n = rng.random_range(2..24);
        let density = rng.random_range(0.0..0.5);
        let raw = ObstacleMask { n, blocked: (0..n * n).map(|_| rng.random_bool(density)).collect() };
        let fixed = apply_fluid_rules(&raw);
        assert!(fluid_rule_violations(&fixed).is_empty(), "n {n}");
        assert!(raw.blocked.iter().zip(&fixed.blocked).all(|(r, f)| !r || *f), "a blocked cell was freed");
        assert_eq!(apply_fluid_rules(&fixed), fixed, "obeying masks are left alone");
    }
}

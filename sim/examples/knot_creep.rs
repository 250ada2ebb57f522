//! The `knot_creep` check of `knotlab validate` alone, on any scene's suture: the surgeon's double
//! throw pulled 1 N on each end until it closes, then watched; prints how fast it moves along the
//! rope (positive: towards the strand's last end), with the rope's contacts with itself solved one
//! way and both ways:
//!
//! ```text
//! cargo run --release -p knotlab-sim --example knot_creep [SCENE]
//! ```
//!
//! SCENE defaults to `scenarios/default.toml`.

mod common;

use knotlab_sim::validation::creep::creep_m_per_s;

fn main() {
    let path = std::env::args().nth(1).unwrap_or_else(|| "scenarios/default.toml".to_owned());
    let suture = common::suture_of_scene(&path, "knot_creep");
    for both_ways in [false, true] {
        let mut suture = suture.clone();
        suture.params.contacts_both_ways = both_ways;
        let way = if both_ways { "both ways" } else { "one way" };
        match creep_m_per_s(&suture) {
            Ok(v) => println!("{path}: contacts {way}: {:+.3} mm/s along the rope", v * 1e3),
            Err(void) => println!("{path}: contacts {way}: {void}"),
        }
    }
}

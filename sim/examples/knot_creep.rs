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

use knotlab_sim::scene::parse_scene;
use knotlab_sim::validation::SutureUnderTest;
use knotlab_sim::validation::creep::creep_m_per_s;

fn main() {
    let path = std::env::args().nth(1).unwrap_or_else(|| "scenarios/default.toml".to_owned());
    let text = match std::fs::read_to_string(&path) {
        Ok(t) => t,
        Err(e) => {
            eprintln!("knot_creep: cannot read {path}: {e}");
            std::process::exit(2);
        }
    };
    let suture = match parse_scene(&text, &path)
        .map_err(|e| e.to_string())
        .and_then(|scene| SutureUnderTest::from_scene(&scene).map_err(|e| format!("{path}: {e}")))
    {
        Ok(s) => s,
        Err(e) => {
            eprintln!("knot_creep: {e}");
            std::process::exit(2);
        }
    };
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

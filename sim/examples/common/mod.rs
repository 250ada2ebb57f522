//! What the examples share: the suture of a scene file, or the example's exit naming what was wrong.

use knotlab_sim::scene::parse_scene;
use knotlab_sim::validation::SutureUnderTest;

/// The suture of the scene file at `path`; on an unreadable or invalid file, prints the error under
/// `example`'s name and exits with status 2.
pub fn suture_of_scene(path: &str, example: &str) -> SutureUnderTest {
    let loaded = std::fs::read_to_string(path)
        .map_err(|e| format!("cannot read {path}: {e}"))
        .and_then(|text| parse_scene(&text, path).map_err(|e| e.to_string()))
        .and_then(|scene| SutureUnderTest::from_scene(&scene).map_err(|e| format!("{path}: {e}")));
    match loaded {
        Ok(s) => s,
        Err(e) => {
            eprintln!("{example}: {e}");
            std::process::exit(2);
        }
    }
}

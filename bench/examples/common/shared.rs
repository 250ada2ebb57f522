//! What the trial examples share: their positional arguments (parsed, defaulted, or the example stopped
//! with a message), and the shipped skill and scene a Monte Carlo trial is drawn on.

use knotlab_learner::primitive::learn;
use knotlab_scenarios::shipped;
use knotlab_scenarios::trial::Learned;
use knotlab_sim::scene::SceneConfig;

/// Prints `message` as the example `name`'s and exits with status 2.
pub fn fail(name: &str, message: String) -> ! {
    eprintln!("{name}: {message}");
    std::process::exit(2)
}

/// Argument `k` (`what`, for the message) of the example `name`, or `default` when absent.
pub fn arg<T: std::str::FromStr>(name: &str, args: &[String], k: usize, what: &str, default: Option<T>) -> T {
    match (args.get(k), default) {
        (Some(text), _) => text
            .parse()
            .unwrap_or_else(|_| fail(name, format!("argument {k} ({what}): {text:?} is not valid"))),
        (None, Some(d)) => d,
        (None, None) => fail(name, format!("argument {k} ({what}) is missing; see the example's comment")),
    }
}

/// The shipped demonstration learned with the shipped pattern, and the shipped scene with `preset`
/// applied (`-`: none), as `knotlab mc` uses them by default; a failure stops the example `name`.
pub fn shipped_trial_inputs(name: &str, preset: &str) -> (Learned, SceneConfig) {
    let demonstration = shipped::demonstration(None).unwrap_or_else(|e| fail(name, e.to_string()));
    let task = shipped::pattern(None).unwrap_or_else(|e| fail(name, e.to_string()));
    let knowledge = learn(&demonstration, &task).unwrap_or_else(|e| fail(name, e.to_string()));
    let mut scene = shipped::scene(None, &shipped::SCENE).unwrap_or_else(|e| fail(name, e.to_string()));
    if preset != "-" {
        scene = scene.with_preset(preset).unwrap_or_else(|e| fail(name, format!("preset {preset}: {e}")));
    }
    (Learned { knowledge, demonstration }, scene)
}

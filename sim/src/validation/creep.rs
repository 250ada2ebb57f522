//! A knot held by equal pulls on its two ends stays where it is along the rope: nothing pulls it
//! either way, and friction holds it (Coulomb). The surgeon's double throw (the long-knot check's
//! cinquefoil, laid loose) is pulled by [`PULL_N`] on each end until it has closed (its shortening
//! at rest, as the trefoil's rests), then watched: the figure is how fast the middle of its
//! crossings moves along the rope, judged against zero. A rope whose contacts are solved always
//! from one end fails it ([`crate::rope::RopeParams::contacts_both_ways`]).

use super::knot::{Laid, MAX_REST_S, Void, at_rest};
use super::long_knot::open_long_knot;
use super::{Check, SutureUnderTest, Tolerance};
use crate::knot::classify::{KnotType, classify};
use crate::rope::Ropes;

/// The pull on each end, N.
pub const PULL_N: f64 = 1.0;
/// Watched this long, s.
const WATCH_S: usize = 5;
/// The fastest a knot may move along the rope and pass, m/s: 5 mm over the watch, four particles
/// of the nominal rope; the one-way solve moves it 15 mm/s.
pub const TOLERANCE_M_PER_S: f64 = 0.001;

const SOURCE: &str = "Coulomb friction: equal pulls on a knot's ends give it no net pull along the rope";

/// Where the rope's knot sits along it: the middle of its crossings' span, m from the first end;
/// void unless it is the double throw.
fn place_m(ropes: &Ropes) -> Result<f64, Void> {
    match classify(&ropes.polyline(0)) {
        Ok(c) if c.knot == KnotType::Surgeons => {
            c.span.map(|s| 0.5 * (s.start_m + s.end_m)).ok_or(Void::NoLongerTheKnotLaid)
        }
        _ => Err(Void::NoLongerTheKnotLaid),
    }
}

/// How fast the double throw, laid in `suture`'s rope at its own friction and pulled by
/// [`PULL_N`] on each end, moves along the rope once closed, m/s (positive: towards the strand's
/// last end). Void where it passed through itself, came undone or never closed.
pub fn creep_m_per_s(suture: &SutureUnderTest) -> Result<f64, Void> {
    let radius_m = suture.params.radius_m;
    let path = open_long_knot(2, radius_m);
    let Laid { mut ropes, first, last, along, length_m, .. } =
        Laid::along_path(suture, suture.params.static_friction, &path);
    ropes.force_n[first] = -along * PULL_N;
    ropes.force_n[last] = along * PULL_N;
    let steps_per_s = (1.0 / suture.dt_s).round() as usize;
    let mut elapsed_s = 0.0;
    let mut run = |ropes: &mut Ropes, seconds: usize| {
        for _ in 0..seconds * steps_per_s {
            ropes.step(suture.dt_s);
            elapsed_s += suture.dt_s;
            if !ropes.crossed_last_step().is_empty() {
                return Err(Void::PassedThroughItself(elapsed_s));
            }
        }
        Ok(())
    };
    // Closed: at rest, its shortening steady.
    let shortening = |ropes: &Ropes| length_m - (ropes.x[last] - ropes.x[first]).norm();
    let mut apart = Vec::new();
    loop {
        if apart.len() >= MAX_REST_S as usize {
            return Err(Void::NeverRested);
        }
        run(&mut ropes, 1)?;
        apart.push(shortening(&ropes));
        if at_rest(&apart, radius_m) {
            break;
        }
    }
    let closed_m = place_m(&ropes)?;
    run(&mut ropes, WATCH_S)?;
    let end_m = place_m(&ropes)?;
    Ok((end_m - closed_m) / WATCH_S as f64)
}

/// The double throw's speed along the rope under equal pulls, judged against zero.
pub fn checks(suture: &SutureUnderTest) -> Vec<Check> {
    let (speed, why) = match creep_m_per_s(suture) {
        Ok(v) => (v.abs() * 1e3, String::new()),
        Err(void) => (f64::NAN, format!(" ({void})")),
    };
    let figure =
        format!("speed along the rope of the double throw pulled {PULL_N} N on each end, once closed{why}");
    let tolerance = Tolerance::Absolute { by: TOLERANCE_M_PER_S * 1e3 };
    vec![Check::new("knot_creep", figure, "mm/s", speed, 0.0, tolerance, SOURCE)]
}
